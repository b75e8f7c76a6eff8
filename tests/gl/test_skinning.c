/* gl: skins and morph targets on both skinning paths. The two-bone strip
 * and the morph quad (tests/core/skin_scene.h) render with the same bytes on
 * the vertex path and the pre-skinning path, multiview and loop, with and
 * without shadows; both match the CPU reference (the posed vertices, in
 * double, drawn as a plain mesh) within a stated tolerance; joints and
 * weights are sent once per frame whatever the view count; posed bounds
 * keep a skinned mesh that moved far from its bind pose from being culled. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_test_util.h"
#include "mvr/mvr.h"
#include "scene_internal.h"
#include "skin_render.h"
#include "skin_scene.h"

#define W 96
#define H 96

static mvr_view_set *front_views(mvr_test_state *t, uint32_t count)
{
    mvr_view_desc views[16];
    memset(views, 0, sizeof views);
    for (uint32_t i = 0; i < count; ++i) {
        /* a row of eyes looking at the strip and the quad from +Z */
        double eye[3] = {-0.2 + 0.1 * (double)(i % 5), 0.8, 6.0}, target[3] = {-0.2, 0.8, 0.0}, up[3] = {0, 1, 0};
        mvr_view_look_at(&views[i], eye, target, up);
        views[i].projection.yfov = 0.75;
    }
    mvr_view_set_desc vd = {.view_count = count, .views = views};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_create(&vd, &vs, NULL) == MVR_OK);
    return vs;
}

/* Two frames (the second the steady state, read back), the first's stats. */
static bool render_scene(mvr_test_state *t, mvr_context *ctx, mvr_scene *scene, mvr_view_set *vs,
                         mvr_view_path path, mvr_skinning_path skin, bool shadows, shot *out)
{
    return render_shot(t, ctx, scene, vs, path, skin, shadows, W, H, 2, out);
}

static void add_light(mvr_scene *s)
{
    mvr_light_desc ld = {.type = MVR_LIGHT_DIRECTIONAL, .color = {1, 1, 1}, .intensity = 3.0f, .cast_shadows = true};
    mvr_light_id light;
    mvr_scene_add_light(s, &ld, &light);
    /* from the upper right front, pointing down -Z rotated */
    mvr_node_desc nd = {.light = light, .rotation = {-0.3, 0.3, 0.0, 0.9}};
    mvr_node_id n;
    mvr_scene_add_node(s, &nd, &n);
    /* a floor behind the strip catches its shadow */
    const float pos[12] = {-3, -1, -1, 3, -1, -1, 3, 3, -1, -3, 3, -1};
    const float nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    mvr_primitive_desc p = {.vertex_count = 4, .positions = pos, .normals = nrm, .index_count = 6, .indices16 = idx};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "wall"};
    mvr_mesh_id mesh;
    mvr_scene_add_mesh(s, &md, &mesh);
    mvr_node_desc wall = {.mesh = mesh, .name = "wall"};
    mvr_scene_add_node(s, &wall, &n);
}

static mvr_scene *posed_scene(mvr_test_state *t, skin_scene *k, bool light)
{
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    mvr_result r = build_skin_scene(s, k, true, true);
    CHECK_MSG(t, r == MVR_OK, "%s", mvr_scene_last_error(s));
    strip_rotate_tip(s, k, 90.0);
    /* the quad sits to the right, morphed by weights (0.5, 0.25) */
    const double tq[3] = {2.0, 0.0, -0.5}, rq[4] = {0, 0, 0, 1}, sq[3] = {0.5, 0.5, 0.5};
    mvr_scene_set_node_transform(s, k->quad, tq, rq, sq);
    const float w[2] = {0.5f, 0.25f};
    mvr_scene_set_node_weights(s, k->quad, w, 2);
    if (light)
        add_light(s);
    return s;
}

/* The CPU reference: the same scene with the skinned and morphed
 * primitives replaced by plain meshes at their posed vertices. */
static mvr_scene *reference_scene(mvr_test_state *t, mvr_scene *posed, bool light)
{
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    mvr_material_desc md = posed->materials[0].desc;
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, &md, &mat) == MVR_OK);
    for (uint32_t n = 0; n < posed->node_count; ++n) {
        const scene_node *node = &posed->nodes[n];
        if (node->mesh == MVR_NO_INDEX || strcmp(node->name, "wall") == 0)
            continue;
        /* normals stay +Z: the strip bends about Z, the quad is flat */
        add_posed_copy(t, s, posed, n, posed->meshes[node->mesh].first_primitive, mat, false);
    }
    if (light)
        add_light(s);
    return s;
}

static uint32_t covered(const uint8_t *p, size_t pixels)
{
    uint32_t n = 0;
    for (size_t i = 0; i < pixels; ++i)
        n += p[i * 4] > 40; /* the clear is 0.05 linear: ~63 sRGB in each channel; the strip is orange */
    return n;
}

static void paths_agree_and_match_the_cpu(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool have_mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    for (int light = 0; light < 2; ++light) {
        skin_scene k;
        mvr_scene *scene = posed_scene(t, &k, light);
        mvr_scene *ref = reference_scene(t, scene, light);
        mvr_view_set *vs = front_views(t, 3);
        size_t pixels = (size_t)3 * W * H;
        shot base, refshot;
        if (!render_scene(t, ctx, ref, vs, MVR_VIEW_PATH_LOOP, MVR_SKINNING_PATH_VERTEX, light, &refshot) ||
            !render_scene(t, ctx, scene, vs, MVR_VIEW_PATH_LOOP, MVR_SKINNING_PATH_VERTEX, light, &base)) {
            free(refshot.pixels);
            break;
        }
        CHECK(t, base.stats.skinning_path == MVR_SKINNING_PATH_VERTEX && base.stats.joints == 2 &&
                     base.stats.morph_targets_active == 2 && base.stats.preskin_passes == 0);
        /* the CPU reference: the GPU blends float joint matrices, the
         * reference poses in double; vertices differ by ~1e-7, which may
         * move a few edge pixels' coverage: at most 0.5% of the pixels by
         * more than 2/255 (measured: none, with and without shadows) */
        uint32_t d = count_diff(base.pixels, refshot.pixels, pixels, 2);
        printf("  shadows %d: %u of %zu pixels differ from the CPU reference (> 2/255)\n", light, d, pixels);
        CHECK_MSG(t, d <= pixels / 200, "%u pixels differ from the CPU-skinned reference", d);
        CHECK_MSG(t, covered(base.pixels, pixels) > 1000, "the strip and quad cover %u pixels",
                  covered(base.pixels, pixels));
        const mvr_view_path vpaths[2] = {MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_MULTIVIEW};
        const mvr_skinning_path spaths[2] = {MVR_SKINNING_PATH_VERTEX, MVR_SKINNING_PATH_PRESKIN};
        for (int vp = 0; vp < (have_mv ? 2 : 1); ++vp)
            for (int sp = 0; sp < 2; ++sp) {
                shot s;
                if (!render_scene(t, ctx, scene, vs, vpaths[vp], spaths[sp], light, &s))
                    continue;
                CHECK(t, s.stats.skinning_path == spaths[sp]);
                /* pre-skinning: one capture per deform (strip, quad) per frame */
                CHECK_EQ_INT(t, s.stats.preskin_passes, spaths[sp] == MVR_SKINNING_PATH_PRESKIN ? 2 : 0);
                uint32_t diff = count_diff(s.pixels, base.pixels, pixels, 0);
                CHECK_MSG(t, diff == 0, "shadows %d, %s, %s: %u pixels differ from the vertex path's loop", light,
                          mvr_view_path_name(vpaths[vp]), mvr_skinning_path_name(spaths[sp]), diff);
                free(s.pixels);
            }
        free(base.pixels);
        free(refshot.pixels);
        mvr_view_set_destroy(vs);
        mvr_scene_destroy(ref);
        mvr_scene_destroy(scene);
    }
    mvr_context_destroy(ctx);
}

/* Joints and weights go up once per frame for every view: the bytes
 * depend on the joints and active weights, not on the view count. */
static void upload_bytes_do_not_depend_on_views(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    skin_scene k;
    mvr_scene *scene = posed_scene(t, &k, false);
    /* 2 joints x 7 texels + the morph header and one texel of two pairs */
    const uint64_t expect = (2u * 7u + 1u + 1u) * 16u;
    const uint32_t counts[4] = {1, 2, 6, 16};
    for (int p = 0; p < 2; ++p)
        for (int i = 0; i < 4; ++i) {
            mvr_view_set *vs = front_views(t, counts[i]);
            shot s;
            mvr_skinning_path path = p ? MVR_SKINNING_PATH_PRESKIN : MVR_SKINNING_PATH_VERTEX;
            if (render_scene(t, ctx, scene, vs, MVR_VIEW_PATH_AUTO, path, false, &s))
                CHECK_MSG(t, s.stats.animation_upload_bytes == expect, "%u views, %s: %llu bytes, expected %llu",
                          counts[i], mvr_skinning_path_name(path), (unsigned long long)s.stats.animation_upload_bytes,
                          (unsigned long long)expect);
            free(s.pixels);
            mvr_view_set_destroy(vs);
        }
    /* a second frame of the same pose sends nothing; a new pose sends it again */
    mvr_view_set *vs = front_views(t, 4);
    mvr_renderer_desc rd = {.context = ctx, .tuning = {.mode = MVR_TUNING_OFF}}; /* steady-state uploads */
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_target_desc td = {.width = W, .height = H, .layers = 4};
    mvr_render_desc desc = {.exposure = 1.0f};
    mvr_frame_stats st[3];
    bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK;
    for (int f = 0; ok && f < 3; ++f) {
        if (f == 2)
            strip_rotate_tip(scene, &k, 45.0);
        ok = mvr_renderer_render(r, scene, vs, target, &desc) == MVR_OK;
        mvr_renderer_get_stats(r, &st[f]);
    }
    CHECK(t, ok);
    if (ok) {
        CHECK(t, st[0].animation_upload_bytes == expect && st[1].animation_upload_bytes == 0 &&
                     st[2].animation_upload_bytes == expect);
        CHECK(t, st[1].preskin_passes == 0 && st[0].preskin_passes == 2 && st[2].preskin_passes == 2);
    }
    /* morph weights all 0: the quad needs no capture (its own vertices are
     * what a capture would hold); the strip still does */
    const float zero[2] = {0.0f, 0.0f};
    mvr_scene_set_node_weights(scene, k.quad, zero, 2);
    ok = ok && mvr_renderer_render(r, scene, vs, target, &desc) == MVR_OK;
    mvr_frame_stats last;
    mvr_renderer_get_stats(r, &last);
    CHECK(t, ok && last.preskin_passes == 1 && last.morph_targets_active == 0);
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
}

/* The skeleton carries the strip 20 units to the right of its bind pose
 * (and of its node): views looking only there still draw it. */
static void posed_bounds_keep_it_visible(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    skin_scene k;
    mvr_scene *scene = NULL;
    CHECK(t, mvr_scene_create(NULL, &scene, NULL) == MVR_OK);
    CHECK(t, build_skin_scene(scene, &k, true, false) == MVR_OK);
    const double tr[3] = {20, 0, 0}, rr[4] = {0, 0, 0, 1}, sr[3] = {1, 1, 1};
    mvr_scene_set_node_transform(scene, k.root, tr, rr, sr);
    mvr_view_desc v = {.projection = {.yfov = 0.5}};
    double eye[3] = {20, 1, 6}, target[3] = {20, 1, 0}, up[3] = {0, 1, 0};
    mvr_view_look_at(&v, eye, target, up);
    mvr_view_set_desc vd = {.view_count = 1, .views = &v};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_create(&vd, &vs, NULL) == MVR_OK);
    for (int p = 0; p < 2; ++p) {
        shot s;
        mvr_skinning_path path = p ? MVR_SKINNING_PATH_PRESKIN : MVR_SKINNING_PATH_VERTEX;
        if (!render_scene(t, ctx, scene, vs, MVR_VIEW_PATH_AUTO, path, false, &s))
            continue;
        CHECK_EQ_INT(t, s.stats.culled, 0);
        CHECK_MSG(t, covered(s.pixels, (size_t)W * H) > 100, "%s: the strip covers %u pixels",
                  mvr_skinning_path_name(path), covered(s.pixels, (size_t)W * H));
        free(s.pixels);
    }
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
}

/* Eight influences (JOINTS_1 / WEIGHTS_1): the same skin with the row
 * y = 1's tip influence in the second set gives the same bytes on both
 * paths (adding zero-weighted joints is exact in float). */
static void eight_influences(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *four = NULL, *eight = NULL;
    skin_scene k4, k8;
    CHECK(t, mvr_scene_create(NULL, &four, NULL) == MVR_OK && mvr_scene_create(NULL, &eight, NULL) == MVR_OK);
    CHECK(t, build_skin_scene_sets(four, &k4, true, false, false) == MVR_OK);
    CHECK(t, build_skin_scene_sets(eight, &k8, true, false, true) == MVR_OK);
    CHECK(t, eight->primitives[0].influence_sets == 2);
    strip_rotate_tip(four, &k4, 60.0);
    strip_rotate_tip(eight, &k8, 60.0);
    mvr_view_set *vs = front_views(t, 2);
    shot a, b, c;
    if (render_scene(t, ctx, four, vs, MVR_VIEW_PATH_AUTO, MVR_SKINNING_PATH_VERTEX, false, &a) &&
        render_scene(t, ctx, eight, vs, MVR_VIEW_PATH_AUTO, MVR_SKINNING_PATH_VERTEX, false, &b) &&
        render_scene(t, ctx, eight, vs, MVR_VIEW_PATH_AUTO, MVR_SKINNING_PATH_PRESKIN, false, &c)) {
        size_t pixels = (size_t)2 * W * H;
        CHECK_EQ_INT(t, count_diff(a.pixels, b.pixels, pixels, 0), 0);
        CHECK_EQ_INT(t, count_diff(b.pixels, c.pixels, pixels, 0), 0);
        CHECK(t, covered(a.pixels, pixels) > 200);
        free(a.pixels);
        free(b.pixels);
        free(c.pixels);
    }
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(four);
    mvr_scene_destroy(eight);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(eight_influences), TEST(paths_agree_and_match_the_cpu), TEST(upload_bytes_do_not_depend_on_views),
              TEST(posed_bounds_keep_it_visible))
