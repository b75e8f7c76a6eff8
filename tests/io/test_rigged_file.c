/* io + gl: a real exporter's skinned, morphed, animated file.
 * tests/data/peers/rigged.gltf (Blender 3.4.1's glTF exporter,
 * scripts/peers/blender_rigged.py): a capped tube of 410 vertices on a chain
 * of 3 bones (most vertices weighted to 2 of them), a shape key "bulge", one
 * animation "bend" of 0 .. 2 s (sampled LINEAR keys on the bones'
 * translation / rotation / scale and the mesh's weights), one camera.
 *
 * Loaded with mvr_gltf_load_file and posed at 0, 0.5, 1.0 and 1.7 s of
 * "bend", it renders 3 views (96 x 96) from the file's camera with the same
 * bytes on the loop and multiview paths (where GL_OVR_multiview2 exists) and
 * on the vertex and pre-skinning paths, lit (a directional light the test
 * adds, so the skinned and morphed normals matter) and unlit; the poses
 * differ from each other; and each matches a CPU reference, the vertices
 * posed in double by mvr_scene_posed_positions drawn as a plain mesh: unlit
 * (the file's material made unlit) with the file's bind-pose normals, which
 * an unlit material ignores; and lit, with the normals posed by
 * mvr_scene_posed_normals (the same maths as deform.glsl). Bound: at most 0.5% of
 * the pixels differ by more than 2/255 (measured: none at all, lit or
 * unlit, on llvmpipe). One renderer playing the clip forward and back gives
 * a fresh renderer's bytes. The frame stats count 3 joints, the active
 * morph target (the bulge, where its weight is not 0), one pre-skin pass on
 * the pre-skinning path, and joint and weight bytes that are the same for 1
 * and 6 views.
 *
 * MVR_TEST_RIGGED_PPM=DIR writes each pose's unlit and lit view 0 there
 * (rigged_<ms>_{unlit,lit}.ppm) for a look. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_test_util.h"
#include "gl/skin_render.h"
#include "mvr/mvr.h"
#include "mvr/mvr_gltf.h"
#include "scene_internal.h"

#ifndef MVR_RIGGED_DIR
#error "MVR_RIGGED_DIR (tests/data/peers) must be defined"
#endif

#define W 96
#define H 96
#define VIEWS 3

static const double times[] = {0.0, 0.5, 1.0, 1.7};
#define TIMES (sizeof times / sizeof times[0])

static mvr_scene *load_rigged(mvr_test_state *t)
{
    mvr_scene *s = NULL;
    mvr_error err;
    mvr_gltf_info info;
    mvr_result r = mvr_gltf_load_file(MVR_RIGGED_DIR "/rigged.gltf", NULL, &s, &info, &err);
    CHECK_MSG(t, r == MVR_OK, "load %s: %s", MVR_RIGGED_DIR "/rigged.gltf", err.message);
    if (r != MVR_OK)
        return NULL;
    CHECK_EQ_INT(t, info.animation_channels_ignored, 0);
    return s;
}

/* The node that draws the tube (the file's only mesh). */
static uint32_t mesh_node(const mvr_scene *s)
{
    for (uint32_t n = 0; n < s->node_count; ++n)
        if (s->nodes[n].mesh != MVR_NO_INDEX)
            return n;
    return MVR_NO_INDEX;
}

static void make_unlit(mvr_scene *s)
{
    for (uint32_t m = 0; m < s->material_count; ++m)
        s->materials[m].desc.unlit = true;
    s->material_version++;
}

static void add_light(mvr_scene *s)
{
    mvr_light_desc ld = {.type = MVR_LIGHT_DIRECTIONAL, .color = {1, 1, 1}, .intensity = 3.0f};
    mvr_light_id light;
    mvr_scene_add_light(s, &ld, &light);
    /* from the upper right front: the bends and the bulge shade unevenly */
    mvr_node_desc nd = {.light = light, .rotation = {-0.3, 0.3, 0.0, 0.9}};
    mvr_node_id n;
    mvr_scene_add_node(s, &nd, &n);
}

static mvr_view_set *camera_views(mvr_test_state *t, const mvr_scene *s, uint32_t count)
{
    CHECK(t, mvr_scene_camera_node_count(s) >= 1);
    mvr_view_set *vs = NULL;
    mvr_error err;
    /* eyes 0.1 apart along the camera's x axis (the camera is ~7.6 from the tube) */
    mvr_result r = mvr_view_set_from_camera(s, mvr_scene_camera_node(s, 0), count, 0.1, &vs, &err);
    CHECK_MSG(t, r == MVR_OK, "views from the file's camera: %s", err.message);
    return r == MVR_OK ? vs : NULL;
}

static bool render_scene(mvr_test_state *t, mvr_context *ctx, mvr_scene *scene, mvr_view_set *vs,
                         mvr_view_path path, mvr_skinning_path skin, shot *out)
{
    return render_shot(t, ctx, scene, vs, path, skin, false, W, H, 1, out);
}

/* The CPU reference: the posed vertices (double, narrowed once) as a plain
 * mesh. Unlit: the file's (bind-pose) normals, which the unlit material
 * ignores, so this comparison needs posed positions only. Lit: the posed
 * normals too (mvr_scene_posed_normals), the file's material and the same
 * light. */
static mvr_scene *reference_scene(mvr_test_state *t, const mvr_scene *posed, bool lit)
{
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    if (!s)
        return NULL;
    mvr_material_desc md = posed->materials[0].desc;
    md.unlit = !lit;
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, &md, &mat) == MVR_OK);
    for (uint32_t n = 0; n < posed->node_count; ++n) {
        const scene_node *node = &posed->nodes[n];
        if (node->mesh == MVR_NO_INDEX)
            continue;
        const scene_mesh *m = &posed->meshes[node->mesh];
        for (uint32_t k = 0; k < m->primitive_count; ++k) {
            add_posed_copy(t, s, posed, n, m->first_primitive + k, mat, lit);
        }
    }
    if (lit)
        add_light(s);
    return s;
}

/* Pixels the (orange) tube covers: red well above the dark grey clear (~63). */
static uint32_t covered(const uint8_t *p, size_t pixels)
{
    uint32_t n = 0;
    for (size_t i = 0; i < pixels; ++i)
        n += p[i * 4] > 100 && p[i * 4] > p[i * 4 + 2] + 40;
    return n;
}

static void write_ppm(const char *dir, double time, const char *what, const uint8_t *rgba)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/rigged_%04d_%s.ppm", dir, (int)lround(time * 1000.0), what);
    FILE *f = fopen(path, "wb");
    if (!f)
        return;
    fprintf(f, "P6\n%d %d\n255\n", W, H);
    for (int y = H - 1; y >= 0; --y) /* rows bottom-up in GL: top row first */
        for (int x = 0; x < W; ++x)
            fwrite(rgba + ((size_t)y * W + (size_t)x) * 4, 1, 3, f);
    fclose(f);
}

static void file_has_the_rig(mvr_test_state *t)
{
    mvr_scene *s = load_rigged(t);
    if (!s)
        return;
    mvr_scene_info info;
    mvr_scene_get_info(s, &info);
    CHECK_MSG(t, info.skins >= 1 && info.joints >= 2 && info.morph_targets >= 1 && info.animations >= 1,
              "skins %u, joints %u, morph targets %u, animations %u", info.skins, info.joints, info.morph_targets,
              info.animations);
    CHECK_EQ_INT(t, info.skins, 1);
    CHECK_EQ_INT(t, info.joints, 3);
    CHECK_EQ_INT(t, info.morph_targets, 1);
    CHECK_EQ_INT(t, mvr_scene_camera_node_count(s), 1);
    uint32_t index = UINT32_MAX;
    CHECK_MSG(t, mvr_scene_find_animation(s, "bend", &index) == MVR_OK, "%s", mvr_scene_last_error(s));
    mvr_animation_info ai;
    if (index != UINT32_MAX && mvr_scene_get_animation_info(s, index, &ai) == MVR_OK) {
        CHECK_MSG(t, strcmp(ai.name, "bend") == 0, "name '%s'", ai.name);
        /* frames 0 .. 48 at 24 fps */
        CHECK_MSG(t, fabs(ai.start) < 1e-6 && fabs(ai.end - 2.0) < 1e-6, "bend: %g .. %g s", ai.start, ai.end);
        /* 3 bones x (translation, rotation, scale) + the mesh's weights */
        CHECK_EQ_INT(t, ai.channels, 10);
    }
    /* most vertices have two influences (smooth weights along the height) */
    uint32_t node = mesh_node(s);
    CHECK(t, node != MVR_NO_INDEX);
    if (node != MVR_NO_INDEX) {
        const scene_primitive *p = &s->primitives[s->meshes[s->nodes[node].mesh].first_primitive];
        CHECK(t, s->nodes[node].skin != MVR_NO_INDEX && p->influence_sets >= 1 && p->target_count == 1);
        uint32_t two = 0;
        for (uint32_t v = 0; p->influence_sets && v < p->vertex_count; ++v) {
            uint32_t k = 0;
            for (int c = 0; c < 4; ++c)
                k += p->weights[0][(size_t)v * 4 + (size_t)c] > 0.0f;
            two += k >= 2;
        }
        printf("  %u vertices, %u with 2 or more influences\n", p->vertex_count, two);
        CHECK_MSG(t, two * 2 > p->vertex_count, "%u of %u vertices have 2 influences", two, p->vertex_count);
    }
    mvr_scene_destroy(s);
}

static void poses_agree_across_paths_and_with_the_cpu(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool have_mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    if (!have_mv)
        printf("  no GL_OVR_multiview2: the loop path only\n");
    const char *ppm_dir = getenv("MVR_TEST_RIGGED_PPM");
    /* lit: the file's material under a light; unlit: its material made unlit */
    mvr_scene *lit = load_rigged(t), *flat = load_rigged(t);
    mvr_view_set *vs = lit ? camera_views(t, lit, VIEWS) : NULL;
    if (!lit || !flat || !vs) {
        mvr_scene_destroy(lit);
        mvr_scene_destroy(flat);
        mvr_context_destroy(ctx);
        return;
    }
    add_light(lit);
    make_unlit(flat);
    uint32_t anim = 0, node = mesh_node(flat);
    CHECK(t, mvr_scene_find_animation(flat, "bend", &anim) == MVR_OK);
    const size_t pixels = (size_t)VIEWS * W * H;
    uint8_t *unlit_at[TIMES] = {0};
    const mvr_view_path vpaths[2] = {MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_MULTIVIEW};
    const mvr_skinning_path spaths[2] = {MVR_SKINNING_PATH_VERTEX, MVR_SKINNING_PATH_PRESKIN};
    for (size_t ti = 0; ti < TIMES; ++ti) {
        const double time = times[ti];
        CHECK(t, mvr_scene_apply_animation(lit, anim, time, MVR_ANIMATION_CLAMP) == MVR_OK);
        CHECK(t, mvr_scene_apply_animation(flat, anim, time, MVR_ANIMATION_CLAMP) == MVR_OK);
        const float *w = mvr_scene_node_weights(flat, &flat->nodes[node]);
        const float bulge = w ? w[0] : 0.0f;
        printf("  t = %.2f s: bulge weight %.4f\n", time, (double)bulge);
        for (int l = 0; l < 2; ++l) {
            mvr_scene *scene = l ? lit : flat;
            shot base = {0};
            for (int vp = 0; vp < (have_mv ? 2 : 1); ++vp)
                for (int sp = 0; sp < 2; ++sp) {
                    shot s;
                    if (!render_scene(t, ctx, scene, vs, vpaths[vp], spaths[sp], &s))
                        continue;
                    const char *what = l ? "lit" : "unlit";
                    CHECK(t, s.stats.view_path == vpaths[vp]);
                    CHECK(t, vpaths[vp] == MVR_VIEW_PATH_LOOP || s.stats.multiview_passes > 0);
                    CHECK(t, s.stats.skinning_path == spaths[sp]);
                    CHECK_EQ_INT(t, s.stats.joints, 3);
                    /* the bulge costs work only where its weight is not 0 */
                    CHECK_MSG(t, s.stats.morph_targets_active == (bulge != 0.0f ? 1u : 0u),
                              "t %.2f: %u morph targets active, bulge weight %g", time, s.stats.morph_targets_active,
                              (double)bulge);
                    /* pre-skinning: one transform feedback capture for the one deformed draw */
                    CHECK_EQ_INT(t, s.stats.preskin_passes, spaths[sp] == MVR_SKINNING_PATH_PRESKIN ? 1 : 0);
                    CHECK(t, s.stats.animation_upload_bytes > 0);
                    if (!base.pixels) {
                        base = s;
                        uint32_t c = covered(base.pixels, pixels);
                        CHECK_MSG(t, c > pixels / 40, "t %.2f, %s: the tube covers %u of %zu pixels", time, what, c,
                                  pixels);
                        if (ppm_dir)
                            write_ppm(ppm_dir, time, what, base.pixels);
                        continue;
                    }
                    uint32_t diff = count_diff(s.pixels, base.pixels, pixels, 0);
                    CHECK_MSG(t, diff == 0, "t %.2f, %s, %s, %s: %u pixels differ from the loop's vertex path", time,
                              what, mvr_view_path_name(vpaths[vp]), mvr_skinning_path_name(spaths[sp]), diff);
                    free(s.pixels);
                }
            if (l == 1 && base.pixels) {
                /* lit: the light shades the tube unevenly (the normals reached the pixels) */
                uint32_t lo = 255, hi = 0;
                for (size_t i = 0; i < pixels; ++i)
                    if (base.pixels[i * 4] > 100 && base.pixels[i * 4] > base.pixels[i * 4 + 2] + 40) {
                        lo = base.pixels[i * 4 + 1] < lo ? base.pixels[i * 4 + 1] : lo;
                        hi = base.pixels[i * 4 + 1] > hi ? base.pixels[i * 4 + 1] : hi;
                    }
                CHECK_MSG(t, hi > lo + 20, "t %.2f, lit: green spans only %u .. %u", time, lo, hi);
            }
            /* The CPU reference. Unlit (positions only, the comparison the
             * brief asks for): the GPU blends float joint matrices, the
             * reference poses in double; vertices differ by ~1e-7, which
             * may move a few edge pixels' coverage: at most 0.5% of the
             * pixels by more than 2/255. Lit (normals posed by
             * posed_normals too): the GPU interpolates the unnormalised
             * blended normals in float; the same bound. */
            mvr_scene *ref = base.pixels ? reference_scene(t, scene, l == 1) : NULL;
            shot r;
            if (ref && render_scene(t, ctx, ref, vs, MVR_VIEW_PATH_LOOP, MVR_SKINNING_PATH_VERTEX, &r)) {
                CHECK(t, r.stats.joints == 0 && r.stats.preskin_passes == 0);
                uint32_t d2 = count_diff(base.pixels, r.pixels, pixels, 2);
                uint32_t d0 = count_diff(base.pixels, r.pixels, pixels, 0);
                printf("  t = %.2f s, %s: %u of %zu pixels differ from the CPU reference by more than 2/255 "
                       "(%u at all)\n",
                       time, l ? "lit" : "unlit", d2, pixels, d0);
                CHECK_MSG(t, d2 <= pixels / 200, "t %.2f, %s: %u pixels differ from the CPU-skinned reference", time,
                          l ? "lit" : "unlit", d2);
                free(r.pixels);
            }
            mvr_scene_destroy(ref);
            if (l == 0)
                unlit_at[ti] = base.pixels;
            else
                free(base.pixels);
        }
    }
    /* the poses differ: every pair of times moves many pixels */
    for (size_t a = 0; a < TIMES; ++a)
        for (size_t b = a + 1; b < TIMES; ++b)
            if (unlit_at[a] && unlit_at[b]) {
                uint32_t d = count_diff(unlit_at[a], unlit_at[b], pixels, 2);
                CHECK_MSG(t, d > pixels / 100, "t %.2f and %.2f: only %u pixels differ", times[a], times[b], d);
            }
    for (size_t i = 0; i < TIMES; ++i)
        free(unlit_at[i]);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(lit);
    mvr_scene_destroy(flat);
    mvr_context_destroy(ctx);
}

/* One renderer plays the clip (as mvr render --frames and the viewer do):
 * every pose comes out with the same bytes as a fresh renderer's, going
 * forward and back in time; a second frame of the same pose (the animation
 * not applied again) sends no joints and runs no pre-skin pass, a new pose
 * sends them again. */
static void one_renderer_plays_the_clip(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool have_mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    mvr_scene *s = load_rigged(t);
    mvr_view_set *vs = s ? camera_views(t, s, VIEWS) : NULL;
    uint32_t anim = 0;
    if (!s || !vs || mvr_scene_find_animation(s, "bend", &anim) != MVR_OK) {
        CHECK(t, false);
        mvr_view_set_destroy(vs);
        mvr_scene_destroy(s);
        mvr_context_destroy(ctx);
        return;
    }
    add_light(s);
    const size_t pixels = (size_t)VIEWS * W * H, bytes = pixels * 4;
    /* fresh renderers: the expected bytes of each pose */
    uint8_t *fresh[TIMES] = {0};
    for (size_t ti = 0; ti < TIMES; ++ti) {
        shot sh;
        CHECK(t, mvr_scene_apply_animation(s, anim, times[ti], MVR_ANIMATION_CLAMP) == MVR_OK);
        if (render_scene(t, ctx, s, vs, MVR_VIEW_PATH_LOOP, MVR_SKINNING_PATH_VERTEX, &sh))
            fresh[ti] = sh.pixels;
    }
    /* forward, back, the same pose twice */
    const size_t order[] = {0, 1, 2, 3, 1, 1, 0, 2};
    const size_t steps = sizeof order / sizeof order[0];
    uint8_t *got = malloc(bytes);
    for (int vp = 0; got && vp < (have_mv ? 2 : 1); ++vp)
        for (int sp = 0; sp < 2; ++sp) {
            mvr_view_path vpath = vp ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP;
            mvr_skinning_path spath = sp ? MVR_SKINNING_PATH_PRESKIN : MVR_SKINNING_PATH_VERTEX;
            /* tuning off: per-frame uploads of a steady material path */
            mvr_renderer_desc rd = {.context = ctx, .view_path = vpath, .skinning_path = spath,
                                    .tuning = {.mode = MVR_TUNING_OFF}};
            mvr_renderer *r = NULL;
            mvr_target *target = NULL;
            mvr_target_desc td = {.width = W, .height = H, .layers = VIEWS, .anti_aliasing = MVR_ANTI_ALIASING_NONE};
            mvr_render_desc desc = {.clear_color = {0.05f, 0.05f, 0.05f, 1.0f}, .exposure = 1.0f};
            bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK;
            CHECK(t, ok);
            for (size_t k = 0; ok && k < steps; ++k) {
                const size_t ti = order[k];
                /* the same pose again: rendered without applying the
                 * animation again (applying it always re-sends the joints,
                 * as mvr_scene_apply_animation says) */
                const bool same_pose = k > 0 && order[k - 1] == ti;
                if (!same_pose)
                    CHECK(t, mvr_scene_apply_animation(s, anim, times[ti], MVR_ANIMATION_CLAMP) == MVR_OK);
                ok = mvr_renderer_render(r, s, vs, target, &desc) == MVR_OK;
                CHECK_MSG(t, ok, "%s", mvr_renderer_last_error(r));
                mvr_frame_stats st;
                mvr_renderer_get_stats(r, &st);
                CHECK_MSG(t, (st.animation_upload_bytes == 0) == same_pose &&
                                 (st.preskin_passes == 0) == (same_pose || !sp),
                          "%s, %s, step %zu (t %.2f): %llu bytes of joints and weights, %u pre-skin passes",
                          mvr_view_path_name(vpath), mvr_skinning_path_name(spath), k, times[ti],
                          (unsigned long long)st.animation_upload_bytes, st.preskin_passes);
                for (uint32_t v = 0; ok && v < VIEWS; ++v)
                    ok = mvr_renderer_read_layer(r, target, v, MVR_READBACK_RGBA8, got + (size_t)v * W * H * 4,
                                                 (size_t)W * H * 4) == MVR_OK;
                if (ok && fresh[ti]) {
                    uint32_t d = count_diff(got, fresh[ti], pixels, 0);
                    CHECK_MSG(t, d == 0, "%s, %s, step %zu (t %.2f): %u pixels differ from a fresh renderer's",
                              mvr_view_path_name(vpath), mvr_skinning_path_name(spath), k, times[ti], d);
                }
            }
            mvr_target_destroy(target);
            mvr_renderer_destroy(r);
        }
    free(got);
    for (size_t i = 0; i < TIMES; ++i)
        free(fresh[i]);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* Joints and weights go up once per frame for all views. */
static void upload_bytes_do_not_depend_on_views(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = load_rigged(t);
    uint32_t anim = 0;
    if (!s || mvr_scene_find_animation(s, "bend", &anim) != MVR_OK) {
        CHECK(t, false);
        mvr_scene_destroy(s);
        mvr_context_destroy(ctx);
        return;
    }
    /* t = 0: the bulge's weight is 0; t = 1: it is 1 */
    for (int k = 0; k < 2; ++k) {
        CHECK(t, mvr_scene_apply_animation(s, anim, k ? 1.0 : 0.0, MVR_ANIMATION_CLAMP) == MVR_OK);
        for (int p = 0; p < 2; ++p) {
            mvr_skinning_path path = p ? MVR_SKINNING_PATH_PRESKIN : MVR_SKINNING_PATH_VERTEX;
            uint64_t bytes[2] = {0, 0};
            const uint32_t counts[2] = {1, 6};
            for (int i = 0; i < 2; ++i) {
                mvr_view_set *vs = camera_views(t, s, counts[i]);
                shot sh;
                if (vs && render_scene(t, ctx, s, vs, MVR_VIEW_PATH_AUTO, path, &sh)) {
                    bytes[i] = sh.stats.animation_upload_bytes;
                    CHECK_EQ_INT(t, sh.stats.joints, 3);
                    CHECK_EQ_INT(t, sh.stats.morph_targets_active, k);
                    free(sh.pixels);
                }
                mvr_view_set_destroy(vs);
            }
            printf("  t = %d s, %s: %llu bytes of joints and weights for 1 view, %llu for 6\n", k,
                   mvr_skinning_path_name(path), (unsigned long long)bytes[0], (unsigned long long)bytes[1]);
            /* at least the 3 joint matrices (each 4 x 4 floats) */
            CHECK(t, bytes[0] >= 3 * 64);
            CHECK(t, bytes[0] == bytes[1]);
        }
    }
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(file_has_the_rig), TEST(poses_agree_across_paths_and_with_the_cpu),
              TEST(one_renderer_plays_the_clip), TEST(upload_bytes_do_not_depend_on_views))
