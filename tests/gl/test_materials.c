#define _POSIX_C_SOURCE 200809L
/* gl: the material paths on the city demo (73 materials, two texture sizes):
 * arrays, per-material and per-draw give byte-identical layers on both view
 * paths; on the array path each pass binds each texture group once, on the
 * per-material path once per change to a textured material. */
#include <stdlib.h>

#include "gl_test_util.h"
#include "renderer.h"

#define W 64
#define H 48
#define VIEWS 3

typedef struct run {
    uint8_t *pixels;
    mvr_frame_stats stats;
    mvr_pass_stats pass[VIEWS];
    uint32_t expected_binds;     /* per pass, from the frame's draw order */
    uint32_t groups_in_frame;
} run;

/* Texture binds the per-material path should make in a pass: one per change
 * into a material with a base color texture (city's only textured role, one
 * distinct image per material). */
static uint32_t material_changes(const mvr_renderer *r, const mvr_scene *s)
{
    uint32_t n = 0, last = MVR_NO_INDEX;
    for (uint32_t i = 0; i < r->frame.draw_count; ++i) {
        uint32_t m = r->frame.draws[i].material;
        if (m != last && m != MVR_NO_INDEX && mvr_scene_material(s, m)->base_color.image.id)
            n++;
        last = m;
    }
    return n;
}

static uint32_t distinct_groups(const mvr_renderer *r)
{
    uint32_t n = 0;
    uint8_t seen[64] = {0};
    for (uint32_t i = 0; i < r->frame.draw_count; ++i) {
        const mvr_draw *d = &r->frame.draws[i];
        uint32_t slot = d->material == MVR_NO_INDEX ? r->gpu.material_count - 1 : d->material;
        uint16_t g = r->gpu.plan.materials[slot].group[0];
        if (g != MVR_NO_GROUP && g < 64 && !seen[g]) {
            seen[g] = 1;
            n++;
        }
    }
    return n;
}

static bool render_city(mvr_test_state *t, mvr_context *ctx, mvr_view_path vp, mvr_material_path mp, run *out)
{
    memset(out, 0, sizeof *out);
    mvr_scene *scene = NULL;
    mvr_view_set *views = NULL;
    mvr_demo_desc dd = {VIEWS, W, H, {0}};
    mvr_renderer_desc rd = {.context = ctx, .view_path = vp, .material_path = mp};
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_target_desc td = {W, H, VIEWS, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    mvr_error err;
    bool ok = mvr_demo_create("city", &dd, &scene, &views, &err) == MVR_OK &&
              mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
              mvr_renderer_render(r, scene, views, target, NULL) == MVR_OK;
    CHECK_MSG(t, ok, "%s/%s: %s", mvr_view_path_name(vp), mvr_material_path_name(mp),
              r ? mvr_renderer_last_error(r) : err.message);
    if (ok) {
        mvr_renderer_get_stats(r, &out->stats);
        for (uint32_t k = 0; k < VIEWS; ++k)
            mvr_renderer_get_pass_stats(r, k, &out->pass[k]);
        out->expected_binds = mp == MVR_MATERIAL_PATH_ARRAYS ? distinct_groups(r) : material_changes(r, scene);
        out->groups_in_frame = mp == MVR_MATERIAL_PATH_ARRAYS ? r->gpu.plan.group_count : 0;
        out->pixels = malloc((size_t)VIEWS * W * H * 4);
        for (uint32_t k = 0; k < VIEWS; ++k)
            CHECK(t, mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, out->pixels + (size_t)k * W * H * 4,
                                             (size_t)W * H * 4) == MVR_OK);
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(views);
    mvr_scene_destroy(scene);
    return ok;
}

static void material_paths_agree(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    const mvr_view_path vps[2] = {MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_MULTIVIEW};
    const mvr_material_path mps[3] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL,
                                      MVR_MATERIAL_PATH_PER_DRAW};
    run runs[2][3];
    memset(runs, 0, sizeof runs);
    for (int v = 0; v < (mv ? 2 : 1); ++v)
        for (int m = 0; m < 3; ++m)
            render_city(t, ctx, vps[v], mps[m], &runs[v][m]);
    const run *ref = &runs[0][0];
    for (int v = 0; v < (mv ? 2 : 1); ++v)
        for (int m = 0; m < 3; ++m) {
            const run *x = &runs[v][m];
            if (!ref->pixels || !x->pixels)
                continue;
            CHECK_MSG(t, memcmp(ref->pixels, x->pixels, (size_t)VIEWS * W * H * 4) == 0,
                      "%s/%s differs from loop/arrays", mvr_view_path_name(vps[v]), mvr_material_path_name(mps[m]));
            CHECK_EQ_INT(t, x->stats.material_path, mps[m]);
            uint32_t passes = x->stats.passes;
            for (uint32_t p = 0; p < passes && p < VIEWS; ++p) {
                printf("  %-9s %-12s pass %u: %u texture binds, %u groups, %u programs, %u range binds\n",
                       mvr_view_path_name(vps[v]), mvr_material_path_name(mps[m]), p, x->pass[p].texture_binds,
                       x->pass[p].texture_groups, x->pass[p].program_binds, x->pass[p].ubo_range_binds);
                if (mps[m] == MVR_MATERIAL_PATH_PER_DRAW)
                    CHECK(t, x->pass[p].texture_binds > 10 * runs[v][1].pass[p].texture_binds);
                else
                    CHECK_MSG(t, x->pass[p].texture_binds == x->expected_binds, "%s pass %u: %u texture binds, expected %u",
                              mvr_material_path_name(mps[m]), p, x->pass[p].texture_binds, x->expected_binds);
                if (mps[m] == MVR_MATERIAL_PATH_ARRAYS)
                    CHECK_EQ_INT(t, x->pass[p].texture_groups, x->expected_binds);
            }
        }
    /* city's textures come in two sizes: two arrays; the white layer lets the
     * plain materials share the textured ones' program */
    CHECK_EQ_INT(t, ref->groups_in_frame, 2);
    CHECK_EQ_INT(t, ref->stats.texture_groups, 2);
    CHECK_MSG(t, runs[0][0].pass[0].program_binds < runs[0][1].pass[0].program_binds, "arrays %u programs, per-material %u",
              runs[0][0].pass[0].program_binds, runs[0][1].pass[0].program_binds);
    for (int v = 0; v < 2; ++v)
        for (int m = 0; m < 3; ++m)
            free(runs[v][m].pixels);
    mvr_context_destroy(ctx);
}

/* A material change re-sends the material blocks: the array path rebuilds
 * its arrays (the plan depends on the materials), the per-material path
 * keeps its textures (found again by image). */
static void a_material_change_keeps_per_material_textures(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_material_path mps[2] = {MVR_MATERIAL_PATH_PER_MATERIAL, MVR_MATERIAL_PATH_ARRAYS};
    uint64_t first[2] = {0}, changed[2] = {0};
    for (int m = 0; m < 2; ++m) {
        mvr_scene *scene = NULL;
        mvr_view_set *views = NULL;
        mvr_demo_desc dd = {VIEWS, W, H, {0}};
        mvr_renderer_desc rd = {.context = ctx, .material_path = mps[m]};
        mvr_renderer *r = NULL;
        mvr_target *target = NULL;
        mvr_target_desc td = {.width = W, .height = H, .layers = VIEWS};
        bool ok = mvr_demo_create("city", &dd, &scene, &views, NULL) == MVR_OK &&
                  mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK;
        CHECK(t, ok);
        mvr_frame_stats st;
        for (int f = 0; ok && f < 3; ++f) {
            if (f == 2) { /* a new material: material_version moves */
                mvr_material_desc md;
                memset(&md, 0, sizeof md);
                mvr_material_id id;
                CHECK(t, mvr_scene_add_material(scene, &md, &id) == MVR_OK);
            }
            CHECK(t, mvr_renderer_render(r, scene, views, target, NULL) == MVR_OK);
            mvr_renderer_get_stats(r, &st);
            if (f == 0)
                first[m] = st.upload_bytes;
            if (f == 1)
                CHECK_EQ_INT(t, st.upload_bytes, 0);
            if (f == 2)
                changed[m] = st.upload_bytes;
        }
        printf("  %s: first frame %llu bytes, after a material change %llu\n", mvr_material_path_name(mps[m]),
               (unsigned long long)first[m], (unsigned long long)changed[m]);
        mvr_target_destroy(target);
        mvr_renderer_destroy(r);
        mvr_view_set_destroy(views);
        mvr_scene_destroy(scene);
    }
    /* per-material: blocks only, so it re-sends less than arrays (textures
     * too) by city's textures: at least a quarter of the first frame. Not a
     * share of per-material's own first frame: that holds the per-draw blocks,
     * 16 times the bytes at a GPU's 256-byte uniform offset alignment (NVIDIA)
     * as at llvmpipe's 16 */
    CHECK_MSG(t, changed[0] > 0 && changed[0] < changed[1] && (changed[1] - changed[0]) * 4 > first[1],
              "per-material: %llu of %llu, arrays %llu of %llu", (unsigned long long)changed[0],
              (unsigned long long)first[0], (unsigned long long)changed[1], (unsigned long long)first[1]);
    /* arrays: rebuilt, textures with them */
    CHECK_MSG(t, changed[1] * 2 > first[1], "arrays: %llu of %llu", (unsigned long long)changed[1],
              (unsigned long long)first[1]);
    mvr_context_destroy(ctx);
}

/* overrides.material_path wins over the descriptor's material_path; the
 * environment (MVR_MATERIAL_PATH) is read only by
 * mvr_renderer_overrides_from_env, which refuses a bad value naming the
 * variable (tests/gl/test_overrides.c). */
static void material_path_override(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    log_sink sink = {0};
    mvr_renderer_desc rd = {.context = ctx, .logger = {log_sink_fn, &sink, MVR_LOG_DEFAULT}};
    mvr_renderer *r = NULL;
    rd.overrides.material_path = MVR_MATERIAL_PATH_OVERRIDE_PER_MATERIAL;
    CHECK(t, mvr_renderer_create(&rd, &r, NULL) == MVR_OK && r->material_path == MVR_MATERIAL_PATH_PER_MATERIAL);
    mvr_renderer_destroy(r);
    rd.material_path = MVR_MATERIAL_PATH_PER_DRAW;
    CHECK(t, mvr_renderer_create(&rd, &r, NULL) == MVR_OK && r->material_path == MVR_MATERIAL_PATH_PER_MATERIAL);
    mvr_renderer_destroy(r);
    rd.overrides.material_path = MVR_MATERIAL_PATH_OVERRIDE_AUTO; /* auto wins too: arrays */
    CHECK(t, mvr_renderer_create(&rd, &r, NULL) == MVR_OK && r->material_path == MVR_MATERIAL_PATH_ARRAYS);
    mvr_renderer_destroy(r);
    rd.overrides.material_path = MVR_MATERIAL_PATH_OVERRIDE_NONE;
    rd.material_path = MVR_MATERIAL_PATH_AUTO;
    CHECK(t, mvr_renderer_create(&rd, &r, NULL) == MVR_OK && r->material_path == MVR_MATERIAL_PATH_ARRAYS);
    CHECK_EQ_INT(t, sink.warnings, 0);
    mvr_renderer_destroy(r);
    mvr_error err;
    rd.overrides.material_path = (mvr_material_path_override)9;
    CHECK(t, mvr_renderer_create(&rd, &r, &err) == MVR_ERROR_INVALID_ARGUMENT && r == NULL);
    CHECK(t, strstr(err.message, "overrides.material_path") != NULL);
    rd.overrides.material_path = MVR_MATERIAL_PATH_OVERRIDE_NONE;
    rd.material_path = (mvr_material_path)9;
    CHECK(t, mvr_renderer_create(&rd, &r, &err) == MVR_ERROR_INVALID_ARGUMENT && r == NULL);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(material_paths_agree), TEST(material_path_override),
              TEST(a_material_change_keeps_per_material_textures))
