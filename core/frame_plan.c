/*
 * The frame plan: path, chunking, sub-passes, resolves and post of one
 * render, decided without GL (see frame_plan.h).
 */
#include "frame_plan.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bool grow(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap)
        return true;
    uint32_t n = *cap ? *cap : 16;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, (size_t)n * elem);
    if (!q)
        return false;
    *p = q;
    *cap = n;
    return true;
}

static bool same_viewport(mvr_viewport a, mvr_viewport b)
{
    return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
}

/* Splits the enabled views into passes. Multiview chunks hold consecutive
 * layers with one viewport (the GL has one viewport per pass), at most
 * max_views of them, never crossing a view block. */
static uint32_t make_chunks(const mvr_view_set *views, uint32_t width, uint32_t height, bool multiview,
                            uint32_t max_views, mvr_view_chunk *out)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < views->count; ++i) {
        const mvr_view_desc *v = &views->views[i];
        mvr_viewport vp = mvr_view_viewport(v, width, height);
        if (v->disabled || vp.width == 0 || vp.height == 0)
            continue;
        if (multiview && n > 0) {
            mvr_view_chunk *c = &out[n - 1];
            if (c->base + c->count == i && c->count < max_views && same_viewport(c->viewport, vp) &&
                c->base / MVR_VIEWS_PER_BLOCK == i / MVR_VIEWS_PER_BLOCK) {
                c->count++;
                continue;
            }
        }
        out[n].base = i;
        out[n].count = 1;
        out[n].viewport = vp;
        n++;
    }
    return n;
}

static mvr_plan_record *add(mvr_frame_plan *p, mvr_plan_kind kind, mvr_plan_when when, uint32_t chunk,
                            uint32_t first_view, uint32_t views, const char *why)
{
    mvr_plan_record *r = &p->records[p->count++];
    memset(r, 0, sizeof *r);
    r->kind = kind;
    r->when = when;
    r->chunk = chunk;
    r->first_view = first_view;
    r->views = views;
    r->why = why;
    return r;
}

bool mvr_frame_plan_multiview_drawable(uint32_t samples, bool post, mvr_msaa_multiview_mode mode, bool transmissive)
{
    if (samples <= 1)
        return true;
    /* transmission reads the opaque views mid-pass: not from storage the GL
     * resolves only at the pass's end (multisampled render to texture) */
    return !post && mode != MVR_MSAA_MV_NONE && !(transmissive && mode == MVR_MSAA_MV_RENDER_TO_TEXTURE);
}

/* The path that runs: multisampling needs multisampled multiview (and no
 * post pass) to stay on the multiview path, else views go one at a time. */
static void choose_path(mvr_frame_plan *p, const mvr_frame_plan_input *in)
{
    p->path = in->path;
    p->msaa_multiview =
        p->msaa && mvr_frame_plan_multiview_drawable(in->samples, p->post, in->msaa_multiview, in->transmissive != 0) &&
        p->path == MVR_VIEW_PATH_MULTIVIEW;
    if (p->path == MVR_VIEW_PATH_MULTIVIEW)
        p->path_why = p->msaa_multiview ? "multisampled multiview passes" : "one pass per chunk of views";
    else
        p->path_why = "one pass per view, as asked or chosen for this GL";
    if (p->msaa && !p->msaa_multiview && p->path == MVR_VIEW_PATH_MULTIVIEW) {
        p->path_why = p->post ? "MSAA in an HDR frame: one multisampled view at a time"
                              : "MSAA without multisampled multiview: one view at a time";
        p->path = MVR_VIEW_PATH_LOOP;
    }
    p->multiview = p->path == MVR_VIEW_PATH_MULTIVIEW;
    p->max_views = in->max_views > MVR_VIEWS_PER_BLOCK ? MVR_VIEWS_PER_BLOCK : in->max_views;
}

static void plan_sub_passes(mvr_frame_plan *p, const mvr_frame_plan_input *in, uint32_t c, bool mv_pass,
                            bool mv_msaa, mvr_plan_blend_split split)
{
    const mvr_view_chunk *ch = &p->chunks[c];
    uint32_t base = ch->base, n = ch->count;
    static const char *const none[2] = {"no opaque draws", "no masked draws"};
    for (int k = MVR_PASS_OPAQUE; k <= MVR_PASS_MASK; ++k) {
        uint32_t draws = in->draws[k];
        mvr_plan_record *r = add(p, k == MVR_PASS_OPAQUE ? MVR_PLAN_OPAQUE : MVR_PLAN_MASK,
                                 draws ? MVR_PLAN_RUN : MVR_PLAN_SKIP, c, base, n,
                                 draws ? "its draws visible in the pass's views" : none[k]);
        r->multiview = mv_pass;
        r->draws = draws;
    }
    mvr_plan_record *r =
        add(p, MVR_PLAN_BACKGROUND, in->background ? MVR_PLAN_RUN : MVR_PLAN_SKIP, c, base, n,
            in->background ? "the environment behind the opaque and masked draws, before the blended"
                           : "the clear color is the background");
    r->multiview = mv_pass;
    r = add(p, MVR_PLAN_TRANSMISSION, in->transmissive ? MVR_PLAN_RUN : MVR_PLAN_SKIP, c, base, n,
            in->transmissive ? "the opaque views, mip-mapped, for the transmissive draws"
                             : "nothing transmissive");
    r->multiview = mv_pass;
    r->draws = in->transmissive;
    uint32_t blend = in->draws[MVR_PASS_BLEND];
    const char *why = "no blended draws";
    mvr_plan_when when = blend ? MVR_PLAN_RUN : MVR_PLAN_SKIP;
    if (blend && split == MVR_PLAN_BLEND_SPLIT_IF_DIVERGED) {
        when = MVR_PLAN_IF_ORDERS_AGREE;
        why = "the centroid order, unless the views' orders diverge";
    } else if (blend && split == MVR_PLAN_BLEND_SPLIT) {
        when = MVR_PLAN_SKIP;
        why = "per-view order asked: each view blends in its own pass";
    } else if (blend && mv_msaa && in->blend_policy != MVR_TRANSPARENCY_ORDER_CENTROID) {
        why = "the centroid order: a multisampled multiview pass cannot draw its views apart";
    } else if (blend && mv_pass) {
        why = "the centroid order (transparency policy)";
    } else if (blend) {
        why = in->blend_policy != MVR_TRANSPARENCY_ORDER_CENTROID && blend > 1 ? "the view's own back-to-front order"
                                                                              : "the shared back-to-front order";
    }
    r = add(p, MVR_PLAN_BLEND, when, c, base, n, why);
    r->multiview = mv_pass;
    r->draws = blend;
    for (uint32_t v = base; split != MVR_PLAN_BLEND_SHARED && v < base + n; ++v) {
        r = add(p, MVR_PLAN_BLEND_VIEW, split == MVR_PLAN_BLEND_SPLIT ? MVR_PLAN_RUN : MVR_PLAN_IF_ORDERS_DIVERGE,
                c, v, 1, "the view's own back-to-front order, into its layer");
        r->draws = blend;
    }
}

static void plan_chunk(mvr_frame_plan *p, const mvr_frame_plan_input *in, uint32_t c)
{
    const mvr_view_chunk *ch = &p->chunks[c];
    /* one view gains nothing from multiview (and costs more on llvmpipe):
     * a plain single-layer pass instead */
    bool mv_pass = p->multiview && ch->count > 1;
    bool mv_msaa = p->msaa && mv_pass;
    /* blended draws: the centroid order serves every view of a multiview
     * pass unless they disagree (auto) or per_view asks; not with
     * multisampled multiview (a view's samples cannot be drawn apart) */
    mvr_plan_blend_split split = MVR_PLAN_BLEND_SHARED;
    if (mv_pass && !mv_msaa && in->draws[MVR_PASS_BLEND] > 0 && in->blend_policy != MVR_TRANSPARENCY_ORDER_CENTROID)
        split = in->blend_policy == MVR_TRANSPARENCY_ORDER_PER_VIEW ? MVR_PLAN_BLEND_SPLIT
                                                                    : MVR_PLAN_BLEND_SPLIT_IF_DIVERGED;
    const char *why = mv_pass ? (mv_msaa ? "multisampled multiview pass over the chunk's layers"
                                         : "multiview pass over the chunk's layers")
                      : p->multiview ? "one view: a plain single-layer pass"
                                     : "the view's own pass";
    mvr_plan_record *r = add(p, MVR_PLAN_VIEW_PASS, MVR_PLAN_RUN, c, ch->base, ch->count, why);
    r->multiview = mv_pass;
    r->msaa = p->msaa;
    r->blend = split;
    plan_sub_passes(p, in, c, mv_pass, mv_msaa, split);
    if (p->msaa) {
        if (mv_msaa && in->msaa_multiview == MVR_MSAA_MV_RENDER_TO_TEXTURE) {
            r = add(p, MVR_PLAN_MSAA_RESOLVE, MVR_PLAN_SKIP, c, ch->base, ch->count,
                    "the GL resolves (multisampled render to texture)");
        } else {
            r = add(p, MVR_PLAN_MSAA_RESOLVE, MVR_PLAN_RUN, c, ch->base, mv_msaa ? ch->count : 1,
                    mv_msaa ? "layer by layer from the multisampled array" : "the view's samples into its layer");
            r->msaa = mv_msaa;
            r->depth = p->hdr_frame && !mv_msaa;
        }
    }
    p->records[p->count - 1].ends_chunk = true;
}

mvr_result mvr_frame_plan_build(mvr_frame_plan *p, const mvr_frame_plan_input *in)
{
    uint32_t views = in->views->count;
    p->count = 0;
    p->chunk_count = 0;
    /* records: 3 before the views, at most 7 + its views per chunk, 2 after, one
     * per chunk for the extra outputs */
    if (!grow((void **)&p->chunks, &p->chunk_cap, views + 1, sizeof *p->chunks) ||
        !grow((void **)&p->records, &p->cap, 9 * views + 8, sizeof *p->records))
        return MVR_ERROR_OUT_OF_MEMORY;
    p->views = views;
    p->width = in->width;
    p->height = in->height;
    p->samples = in->samples;
    p->factor = in->factor ? in->factor : 1;
    p->msaa = in->samples > 1;
    p->post = in->post;
    p->hdr_frame = in->post && !in->supersampled;
    p->encode_in_mesh = in->unorm8 && p->factor == 1 && !in->post;
    choose_path(p, in);
    p->chunk_count = make_chunks(in->views, in->width, in->height, p->multiview, p->max_views, p->chunks);

    if (in->environment)
        add(p, MVR_PLAN_ENV_PREFILTER, in->environment_new ? MVR_PLAN_RUN : MVR_PLAN_SKIP, MVR_PLAN_NO_CHUNK, 0,
            views, in->environment_new ? "a new environment: its maps, once for every view"
                                       : "this environment is prefiltered already");
    add(p, MVR_PLAN_UPLOAD, MVR_PLAN_RUN, MVR_PLAN_NO_CHUNK, 0, views,
        "view blocks; per-draw blocks and lights only when changed");
    if (in->deforms) {
        mvr_plan_record *d = add(p, MVR_PLAN_PRESKIN, in->preskin && in->deforms_moved ? MVR_PLAN_RUN : MVR_PLAN_SKIP,
                                 MVR_PLAN_NO_CHUNK, 0, views,
                                 !in->preskin ? "vertex path: each view's vertex stage deforms"
                                 : in->deforms_moved ? "once, captured for every view and the shadow maps"
                                                     : "nothing moved: last capture reused");
        d->draws = in->deforms;
    }
    mvr_plan_record *r = add(p, MVR_PLAN_SHADOW_MAPS, in->shadow_layers ? MVR_PLAN_RUN : MVR_PLAN_SKIP,
                             MVR_PLAN_NO_CHUNK, 0, views,
                             in->shadow_layers ? "once, its layers shared by every view" : "no shadow layers planned");
    r->draws = in->shadow_layers;
    for (uint32_t c = 0; c < p->chunk_count; ++c)
        plan_chunk(p, in, c);
    if (p->factor > 1) {
        r = add(p, MVR_PLAN_SUPERSAMPLE_RESOLVE, p->post ? MVR_PLAN_SKIP : MVR_PLAN_RUN, MVR_PLAN_NO_CHUNK, 0, views,
                p->post ? "the post pass reads the supersampled views" : "the mean of each pixel's samples, encoded");
        r->multiview = p->multiview;
    }
    r = add(p, MVR_PLAN_POST, p->post ? MVR_PLAN_RUN : MVR_PLAN_SKIP, MVR_PLAN_NO_CHUNK, 0, views,
            p->post ? "exposure, tone map and encode of the HDR views"
                    : "linear exposure, no tone map or dither: the views are final");
    r->multiview = p->multiview;
    for (uint32_t c = 0; in->outputs && c < p->chunk_count; ++c) {
        const mvr_view_chunk *ch = &p->chunks[c];
        uint32_t blend = in->draws[MVR_PASS_BLEND];
        r = add(p, MVR_PLAN_OUTPUTS_BLEND, blend ? MVR_PLAN_RUN : MVR_PLAN_SKIP, c, ch->base, ch->count,
                blend ? "the front-most blended surface above the alpha cutoff, outputs alone"
                      : "no blended draws: the view pass wrote every output");
        r->multiview = p->multiview && ch->count > 1;
        r->draws = blend;
    }
    return MVR_OK;
}

void mvr_frame_plan_free(mvr_frame_plan *p)
{
    free(p->records);
    free(p->chunks);
    memset(p, 0, sizeof *p);
}

const char *mvr_plan_kind_name(mvr_plan_kind kind)
{
    static const char *const names[MVR_PLAN_KIND_COUNT] = {
        "env-prefilter", "upload", "preskin", "shadow-maps", "view-pass",           "opaque",       "mask",
        "background",    "blend",  "blend-view",  "msaa-resolve", "supersample-resolve", "post", "transmission",
        "outputs-blend"};
    return (unsigned)kind < MVR_PLAN_KIND_COUNT ? names[kind] : "?";
}

typedef struct text {
    char *buf;
    size_t size, len;
} text;

static void put(text *t, const char *fmt, ...) MVR_PRINTF(2, 3);
static void put(text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    size_t room = t->len < t->size ? t->size - t->len : 0;
    int n = vsnprintf(room ? t->buf + t->len : NULL, room, fmt, ap);
    va_end(ap);
    if (n > 0)
        t->len += (size_t)n;
}

size_t mvr_frame_plan_format(const mvr_frame_plan *p, char *buf, size_t size)
{
    text t = {buf, size, 0};
    if (size)
        buf[0] = '\0';
    put(&t, "frame plan: %u views in %u passes, %s path (%s); layers %ux%u", p->views, p->chunk_count,
        p->path == MVR_VIEW_PATH_MULTIVIEW ? "multiview" : "loop", p->path_why ? p->path_why : "", p->width, p->height);
    if (p->multiview)
        put(&t, ", at most %u views a pass", p->max_views);
    if (p->msaa)
        put(&t, ", MSAA %ux%s", p->samples, p->msaa_multiview ? " multiview" : "");
    if (p->factor > 1)
        put(&t, ", supersampled %ux", p->factor);
    put(&t, "%s%s\n", p->hdr_frame ? ", HDR frame" : "", p->encode_in_mesh ? ", sRGB encoded by the mesh" : "");
    static const char *const when[] = {"run", "skip", "if-agree", "if-diverge"};
    for (uint32_t i = 0; i < p->count; ++i) {
        const mvr_plan_record *r = &p->records[i];
        bool sub = r->chunk != MVR_PLAN_NO_CHUNK && r->kind != MVR_PLAN_VIEW_PASS;
        char views[48];
        if (r->views == 1)
            snprintf(views, sizeof views, "view %u", r->first_view);
        else
            snprintf(views, sizeof views, "views %u-%u", r->first_view, r->first_view + r->views - 1);
        put(&t, "%3u %s%-*s %-10s %-12s", i + 1, sub ? "  " : "", sub ? 19 : 21, mvr_plan_kind_name(r->kind),
            when[r->when], r->views ? views : "-");
        const char *sep = " ";
        if (r->multiview) {
            put(&t, "%smultiview", sep);
            sep = ", ";
        }
        if (r->kind == MVR_PLAN_SHADOW_MAPS && r->draws)
            put(&t, "%s%u layers", sep, r->draws), sep = ", ";
        else if ((r->kind >= MVR_PLAN_OPAQUE && r->kind <= MVR_PLAN_BLEND_VIEW && r->kind != MVR_PLAN_BACKGROUND) ||
                 r->kind == MVR_PLAN_TRANSMISSION || r->kind == MVR_PLAN_OUTPUTS_BLEND)
            put(&t, "%s%u draws", sep, r->draws), sep = ", ";
        if (r->depth)
            put(&t, "%swith depth", sep);
        put(&t, ": %s\n", r->why ? r->why : "");
    }
    return t.len;
}
