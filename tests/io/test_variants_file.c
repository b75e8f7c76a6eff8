/* io + gl: a real exporter's file with material variants.
 * tests/data/peers/variants.gltf (Blender 3.4.1's glTF exporter,
 * scripts/peers/blender_variants.py): a board facing the camera, its left
 * half (primitive 0, material "paint", white) mapped by the variants "red"
 * and "ruby" to "paint_red" and by "blue" to "paint_blue"; its right half
 * (primitive 1, "frame", grey) has no mappings. The file lists the
 * variants as red, ruby, blue and KHR_materials_variants in
 * extensionsRequired.
 *
 * Loaded with mvr_gltf_load_file, lit by a white ambient light, it renders
 * 2 views (64 x 64) from the file's camera. One renderer per view path
 * (loop, multiview where GL_OVR_multiview2 exists) and material path
 * (texture arrays, per material) selects default, red, blue, ruby, default
 * in turn on the same scene: the left half turns red, then blue (each
 * channel checked), ruby gives red's bytes, and the default at the end
 * gives the first frame's bytes exactly; the right half keeps its bytes
 * throughout; every path gives the same bytes as the loop path with
 * arrays; and each selection equals a fresh renderer's render of a freshly
 * loaded scene with that variant selected (nothing stale survives a
 * switch). Switching red -> ruby (the same material) moves no version and
 * sends no material; a switch uploads less than the first frame (no
 * geometry). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_test_util.h"
#include "gl/skin_render.h"
#include "mvr/mvr.h"
#include "mvr/mvr_gltf.h"
#include "scene_internal.h"

#ifndef MVR_PEERS_DIR
#error "MVR_PEERS_DIR (tests/data/peers) must be defined"
#endif

#define FILE_PATH MVR_PEERS_DIR "/variants.gltf"
#define W 64
#define H 64
#define VIEWS 2

static mvr_scene *load(mvr_test_state *t)
{
    mvr_scene *s = NULL;
    mvr_error err;
    mvr_gltf_info info;
    mvr_result r = mvr_gltf_load_file(FILE_PATH, NULL, &s, &info, &err);
    CHECK_MSG(t, r == MVR_OK, "load %s: %s", FILE_PATH, err.message);
    if (r != MVR_OK)
        return NULL;
    /* the extension is implemented: no "not implemented" warning */
    CHECK_EQ_INT(t, info.warnings, 0);
    const float white[3] = {1.0f, 1.0f, 1.0f};
    mvr_scene_set_ambient(s, white);
    return s;
}

static uint32_t find(mvr_test_state *t, const mvr_scene *s, const char *name)
{
    uint32_t i = MVR_VARIANT_DEFAULT;
    CHECK_MSG(t, mvr_scene_find_variant(s, name, &i) == MVR_OK, "%s", mvr_scene_last_error(s));
    return i;
}

static void file_has_the_variants(mvr_test_state *t)
{
    mvr_scene *s = load(t);
    if (!s)
        return;
    CHECK_EQ_INT(t, mvr_scene_variant_count(s), 3);
    const char *names[3] = {"red", "ruby", "blue"};
    for (uint32_t i = 0; i < 3; ++i) {
        const char *n = mvr_scene_variant_name(s, i);
        CHECK_MSG(t, n && strcmp(n, names[i]) == 0, "variant %u is '%s', expected '%s'", i, n ? n : "(null)",
                  names[i]);
    }
    CHECK(t, mvr_scene_selected_variant(s) == MVR_VARIANT_DEFAULT);
    /* the board: 2 primitives, the left one mapped (red and ruby to one
     * material, blue to another), the right one not */
    CHECK_EQ_INT(t, s->primitive_count, 2);
    if (s->primitive_count == 2) {
        const scene_primitive *left = &s->primitives[0], *right = &s->primitives[1];
        CHECK_EQ_INT(t, left->variant_map_count, 3);
        CHECK_EQ_INT(t, right->variant_map_count, 0);
        CHECK(t, strcmp(s->materials[left->material].name, "paint") == 0);
        CHECK(t, strcmp(s->materials[right->material].name, "frame") == 0);
        CHECK(t, mvr_scene_select_variant(s, find(t, s, "blue")) == MVR_OK);
        CHECK(t, strcmp(s->materials[left->material].name, "paint_blue") == 0);
        CHECK(t, strcmp(s->materials[right->material].name, "frame") == 0);
        CHECK(t, mvr_scene_select_variant(s, find(t, s, "ruby")) == MVR_OK);
        CHECK(t, strcmp(s->materials[left->material].name, "paint_red") == 0);
    }
    mvr_scene_destroy(s);
}

/* The mean colour of view 0's pixels in [x0, x1) x [y0, y1) (rows from
 * the bottom, as GL reads them). */
static void mean(const uint8_t *px, int x0, int x1, int y0, int y1, double rgb[3])
{
    double sum[3] = {0, 0, 0};
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c)
                sum[c] += px[((size_t)y * W + (size_t)x) * 4 + (size_t)c];
    for (int c = 0; c < 3; ++c)
        rgb[c] = sum[c] / ((x1 - x0) * (y1 - y0));
}

/* The board spans about x 7..57, y 19..45 of a 64 x 64 view: a patch well
 * inside each half. */
static void left_patch(const uint8_t *px, double rgb[3])
{
    mean(px, 12, 26, 26, 38, rgb);
}

/* Whether the right half's patch (no mappings) is the same bytes in a and b. */
static bool right_same(const uint8_t *a, const uint8_t *b)
{
    for (int v = 0; v < VIEWS; ++v)
        for (int y = 26; y < 38; ++y)
            if (memcmp(a + (((size_t)v * H + (size_t)y) * W + 38) * 4, b + (((size_t)v * H + (size_t)y) * W + 38) * 4,
                       14 * 4) != 0)
                return false;
    return true;
}

enum { SEL_DEFAULT, SEL_RED, SEL_BLUE, SEL_RUBY, SEL_DEFAULT_AGAIN, SELECTIONS };
static const char *const selection_names[SELECTIONS] = {"default", "red", "blue", "ruby", "default again"};

static uint32_t selection_index(mvr_test_state *t, const mvr_scene *s, int sel)
{
    switch (sel) {
    case SEL_RED: return find(t, s, "red");
    case SEL_BLUE: return find(t, s, "blue");
    case SEL_RUBY: return find(t, s, "ruby");
    default: return MVR_VARIANT_DEFAULT;
    }
}

static void selections_render_their_materials(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool have_mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    if (!have_mv)
        printf("  no GL_OVR_multiview2: the loop path only\n");
    mvr_scene *s = load(t);
    mvr_view_set *vs = NULL;
    mvr_error err;
    if (s)
        CHECK_MSG(t, mvr_view_set_from_camera(s, mvr_scene_camera_node(s, 0), VIEWS, 0.05, &vs, &err) == MVR_OK,
                  "views: %s", err.message);
    if (!s || !vs) {
        mvr_scene_destroy(s);
        mvr_context_destroy(ctx);
        return;
    }
    const size_t layer = (size_t)W * H * 4, bytes = layer * VIEWS;
    /* each selection as a fresh renderer draws a freshly loaded scene */
    uint8_t *fresh[SELECTIONS] = {0};
    for (int sel = 0; sel < SEL_DEFAULT_AGAIN; ++sel) {
        mvr_scene *f = load(t);
        shot sh = {0};
        if (f && mvr_scene_select_variant(f, selection_index(t, f, sel)) == MVR_OK &&
            render_shot(t, ctx, f, vs, MVR_VIEW_PATH_LOOP, MVR_SKINNING_PATH_AUTO, false, W, H, 1, &sh))
            fresh[sel] = sh.pixels;
        mvr_scene_destroy(f);
    }
    fresh[SEL_DEFAULT_AGAIN] = fresh[SEL_DEFAULT] ? malloc(bytes) : NULL;
    if (fresh[SEL_DEFAULT_AGAIN])
        memcpy(fresh[SEL_DEFAULT_AGAIN], fresh[SEL_DEFAULT], bytes);
    /* the colours: white-ish paint by default, red, blue; the frame darker and grey */
    if (fresh[SEL_DEFAULT] && fresh[SEL_RED] && fresh[SEL_BLUE]) {
        double d[3], r[3], b[3], frame[3];
        left_patch(fresh[SEL_DEFAULT], d);
        left_patch(fresh[SEL_RED], r);
        left_patch(fresh[SEL_BLUE], b);
        mean(fresh[SEL_DEFAULT], 38, 52, 26, 38, frame);
        printf("  left half: default (%.0f, %.0f, %.0f), red (%.0f, %.0f, %.0f), blue (%.0f, %.0f, %.0f); "
               "right half (%.0f, %.0f, %.0f)\n",
               d[0], d[1], d[2], r[0], r[1], r[2], b[0], b[1], b[2], frame[0], frame[1], frame[2]);
        CHECK_MSG(t, d[0] > 120 && abs((int)(d[0] - d[1])) < 6 && abs((int)(d[0] - d[2])) < 6,
                  "default: (%.0f, %.0f, %.0f) is not a light grey", d[0], d[1], d[2]);
        CHECK_MSG(t, frame[0] + 30 < d[0], "the frame (%.0f) is not darker than the paint (%.0f)", frame[0], d[0]);
        CHECK_MSG(t, r[0] > r[1] + 60 && r[0] > r[2] + 60, "red: (%.0f, %.0f, %.0f)", r[0], r[1], r[2]);
        CHECK_MSG(t, b[2] > b[0] + 60 && b[2] > b[1] + 60, "blue: (%.0f, %.0f, %.0f)", b[0], b[1], b[2]);
        CHECK(t, right_same(fresh[SEL_DEFAULT], fresh[SEL_RED]) && right_same(fresh[SEL_DEFAULT], fresh[SEL_BLUE]));
    }
    if (fresh[SEL_RED] && fresh[SEL_RUBY])
        CHECK_MSG(t, memcmp(fresh[SEL_RED], fresh[SEL_RUBY], bytes) == 0, "ruby is not red's bytes");

    /* one renderer per path switching on one scene: the fresh bytes each time */
    const mvr_view_path vpaths[2] = {MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_MULTIVIEW};
    const mvr_material_path mpaths[2] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL};
    uint8_t *got = malloc(bytes);
    for (int vp = 0; got && vp < (have_mv ? 2 : 1); ++vp)
        for (int mp = 0; mp < 2; ++mp) {
            const char *path = mvr_view_path_name(vpaths[vp]), *mpath = mvr_material_path_name(mpaths[mp]);
            mvr_renderer_desc rd = {.context = ctx, .view_path = vpaths[vp], .material_path = mpaths[mp]};
            mvr_renderer *r = NULL;
            mvr_target *target = NULL;
            mvr_target_desc td = {.width = W, .height = H, .layers = VIEWS, .anti_aliasing = MVR_ANTI_ALIASING_NONE};
            bool ok = mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK;
            CHECK_MSG(t, ok, "renderer / target: %s", r ? mvr_renderer_last_error(r) : err.message);
            mvr_render_desc desc = {.clear_color = {0.05f, 0.05f, 0.05f, 1.0f}, .exposure = 1.0f};
            uint8_t *first = malloc(bytes);
            uint64_t first_upload = 0;
            for (int sel = 0; ok && first && sel < SELECTIONS; ++sel) {
                uint64_t version = s->material_version;
                CHECK(t, mvr_scene_select_variant(s, selection_index(t, s, sel)) == MVR_OK);
                /* ruby after blue moves the version; the same material does not (below) */
                CHECK(t, sel == SEL_DEFAULT || s->material_version != version);
                ok = mvr_renderer_render(r, s, vs, target, &desc) == MVR_OK;
                CHECK_MSG(t, ok, "%s, %s, %s: %s", path, mpath, selection_names[sel], mvr_renderer_last_error(r));
                mvr_frame_stats st;
                mvr_renderer_get_stats(r, &st);
                CHECK(t, st.view_path == vpaths[vp] && st.material_path == mpaths[mp]);
                if (sel == SEL_DEFAULT)
                    first_upload = st.upload_bytes;
                else /* a switch sends materials and draws again, never the geometry */
                    CHECK_MSG(t, st.upload_bytes < first_upload, "%s, %s, %s: %llu bytes uploaded, first frame %llu",
                              path, mpath, selection_names[sel], (unsigned long long)st.upload_bytes,
                              (unsigned long long)first_upload);
                for (uint32_t v = 0; ok && v < VIEWS; ++v)
                    ok = mvr_renderer_read_layer(r, target, v, MVR_READBACK_RGBA8, got + v * layer, layer) == MVR_OK;
                if (!ok)
                    break;
                if (sel == SEL_DEFAULT)
                    memcpy(first, got, bytes);
                if (sel == SEL_DEFAULT_AGAIN)
                    CHECK_MSG(t, memcmp(got, first, bytes) == 0, "%s, %s: the default again is not the first bytes",
                              path, mpath);
                if (fresh[sel]) {
                    uint32_t diff = count_diff(got, fresh[sel], (size_t)W * H * VIEWS, 0);
                    CHECK_MSG(t, diff == 0, "%s, %s, %s: %u pixels differ from a fresh renderer's loop render", path,
                              mpath, selection_names[sel], diff);
                }
                if (sel == SEL_RED) {
                    /* red -> ruby -> red: the same material, nothing moves, nothing is sent */
                    uint64_t v0 = s->material_version;
                    CHECK(t, mvr_scene_select_variant(s, find(t, s, "ruby")) == MVR_OK);
                    CHECK(t, mvr_scene_select_variant(s, find(t, s, "red")) == MVR_OK);
                    CHECK(t, mvr_scene_select_variant(s, find(t, s, "red")) == MVR_OK);
                    CHECK(t, s->material_version == v0);
                    ok = mvr_renderer_render(r, s, vs, target, &desc) == MVR_OK;
                    mvr_renderer_get_stats(r, &st);
                    CHECK_MSG(t, st.upload_bytes == 0, "%s, %s: %llu bytes uploaded after red -> ruby -> red", path,
                              mpath, (unsigned long long)st.upload_bytes);
                }
            }
            free(first);
            mvr_target_destroy(target);
            mvr_renderer_destroy(r);
            CHECK(t, mvr_scene_select_variant(s, MVR_VARIANT_DEFAULT) == MVR_OK);
        }
    free(got);
    for (int i = 0; i < SELECTIONS; ++i)
        free(fresh[i]);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(file_has_the_variants), TEST(selections_render_their_materials))
