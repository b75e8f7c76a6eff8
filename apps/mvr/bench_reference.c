/* mvr bench's reference at any view count and size (issue 37: 16 views at
 * 1024x1024 asked llvmpipe for one 4.0 GiB RGBA32F target, which it
 * refused before anything was measured): the views are rendered in chunks
 * whose supersampled float target fits --reference-memory, one chunk after
 * another into the same target, and read back chunk by chunk; where a
 * single view at 4x4 does not fit, the reference supersamples less (3x3,
 * 2x2, then none), said in the report. A chunk is a view set of some of the
 * views with the whole set's origin (mvr_view_set_get_origin), so its
 * pixels are the whole set's but for what is fitted to the views of one
 * render (shadow cascades; the bench's exposure is fixed). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* Bytes of one view's reference colour target at ss x ss samples per pixel (RGBA32F). */
static uint64_t view_bytes(uint32_t w, uint32_t h, uint32_t ss)
{
    return (uint64_t)w * ss * h * ss * 16u;
}

bool bench_reference_plan(const bench_options *o, mvr_view_set *vs, bench_chunks *out, char *note, size_t note_size)
{
    memset(out, 0, sizeof *out);
    uint32_t n = mvr_view_set_count(vs), w = o->scene.width, h = o->scene.height;
    uint64_t budget = o->reference_memory ? o->reference_memory : (uint64_t)256 << 20;
    uint32_t ss = 4;
    while (ss > 1 && view_bytes(w, h, ss) > budget)
        --ss;
    out->supersample = ss;
    uint64_t fit = budget / view_bytes(w, h, ss);
    out->per_chunk = fit >= n ? n : fit ? (uint32_t)fit : 1u;
    if (ss < 4)
        snprintf(note, note_size, "the reference supersampled %ux%u (4x4 takes %llu MiB a view, over "
                 "--reference-memory %llu MiB); ", ss, ss, (unsigned long long)(view_bytes(w, h, 4) >> 20),
                 (unsigned long long)(budget >> 20));
    if (out->per_chunk >= n)
        return true;
    out->count = (n + out->per_chunk - 1) / out->per_chunk;
    out->sets = calloc(out->count, sizeof *out->sets);
    mvr_view_desc *views = calloc(out->per_chunk, sizeof *views);
    mvr_view_set_desc vd = {.origin_set = true};
    bool ok = out->sets && views && mvr_view_set_get_origin(vs, vd.origin) == MVR_OK;
    for (uint32_t c = 0; ok && c < out->count; ++c) {
        uint32_t first = c * out->per_chunk, count = n - first < out->per_chunk ? n - first : out->per_chunk;
        for (uint32_t k = 0; ok && k < count; ++k)
            ok = mvr_view_set_get_view(vs, first + k, &views[k]) == MVR_OK;
        vd.view_count = count;
        vd.views = views;
        ok = ok && mvr_view_set_create(&vd, &out->sets[c], NULL) == MVR_OK;
    }
    free(views);
    if (!ok) {
        fprintf(stderr, "mvr bench: out of memory for the reference's chunks of views\n");
        bench_chunks_free(out);
        return false;
    }
    size_t l = strlen(note);
    snprintf(note + l, note_size - l, "the reference rendered in %u chunks of %u views (--reference-memory); ",
             out->count, out->per_chunk);
    return true;
}

void bench_chunks_free(bench_chunks *c)
{
    for (uint32_t i = 0; c->sets && i < c->count; ++i)
        mvr_view_set_destroy(c->sets[i]);
    free(c->sets);
    memset(c, 0, sizeof *c);
}

mvr_result bench_render_views(mvr_renderer *r, mvr_scene *s, mvr_view_set *vs, const bench_chunks *chunks,
                              mvr_target *t, const mvr_render_desc *desc)
{
    if (!chunks || !chunks->count)
        return mvr_renderer_render(r, s, vs, t, desc);
    mvr_result res = MVR_OK;
    for (uint32_t c = 0; res == MVR_OK && c < chunks->count; ++c)
        res = mvr_renderer_render(r, s, chunks->sets[c], t, desc);
    return res;
}

bool bench_read_views(mvr_renderer *r, mvr_scene *s, mvr_view_set *vs, const bench_chunks *chunks, mvr_target *t,
                      const mvr_render_desc *desc, uint32_t w, uint32_t h, uint32_t ss, uint8_t *display)
{
    size_t layer = (size_t)w * h * 4;
    if (!chunks || !chunks->count) {
        bool ok = true;
        for (uint32_t k = 0; ok && k < mvr_view_set_count(vs); ++k)
            ok = cli_read_display_layer(r, t, k, w, h, ss, display + layer * k, NULL);
        return ok;
    }
    /* each chunk drawn again (the scene as the last measured frame posed it) and read */
    bool ok = true;
    for (uint32_t c = 0; ok && c < chunks->count; ++c) {
        ok = mvr_renderer_render(r, s, chunks->sets[c], t, desc) == MVR_OK;
        uint32_t count = mvr_view_set_count(chunks->sets[c]);
        for (uint32_t k = 0; ok && k < count; ++k)
            ok = cli_read_display_layer(r, t, k, w, h, ss, display + layer * ((size_t)c * chunks->per_chunk + k),
                                        NULL);
    }
    return ok;
}
