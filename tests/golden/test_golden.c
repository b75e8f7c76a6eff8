/*
 * golden: each demo's views at a small size against stored PNGs, looked at by
 * a person before they were committed. Tolerance: at most 0.1% of the pixels
 * may differ, each channel by at most 1/255 (rounding differences between
 * LLVM versions / CPU vector widths in llvmpipe); anything more is a shading
 * regression. MVR_UPDATE_GOLDEN=1 rewrites the stored images instead.
 */
#include <stdlib.h>

#include "mvr_test.h"
#include "mvr/mvr.h"
#include "mvr/mvr_image.h"

#define W 160
#define H 120
#define MAX_CHANNEL_DIFF 1
#define MAX_DIFF_FRACTION 0.001

static bool compare(mvr_test_state *t, const char *name, const uint8_t *bottom_up, const char *path)
{
    mvr_image_view actual = {W, H, MVR_PIXEL_U8, true, bottom_up};
    mvr_error err;
    if (getenv("MVR_UPDATE_GOLDEN")) {
        CHECK_MSG(t, mvr_image_write(path, &actual, &err) == MVR_OK, "%s", err.message);
        printf("  updated %s\n", path);
        return true;
    }
    mvr_image_data gold;
    if (mvr_image_read(path, MVR_PIXEL_U8, &gold, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s (MVR_UPDATE_GOLDEN=1 makes it)", err.message);
        return false;
    }
    mvr_image_view expected = {gold.width, gold.height, MVR_PIXEL_U8, false, gold.pixels};
    mvr_image_compare_result r;
    char diff[512];
    snprintf(diff, sizeof diff, "%s.diff.png", name);
    /* a channel more than 1/255 off fails outright: the threshold sits
     * between one and two steps */
    bool ok = mvr_image_compare(&actual, &expected, 1.5 / 255.0, NULL, &r, &err) == MVR_OK;
    CHECK_MSG(t, ok, "%s: %s", name, err.message);
    if (ok) {
        uint64_t differing = 0;
        mvr_image_compare_result any;
        mvr_image_compare(&actual, &expected, 0.1 / 255.0, NULL, &any, &err);
        differing = any.pixels_over;
        double fraction = (double)differing / (W * H);
        printf("  %s: %llu pixels differ (%.3f%%), worst channel %.0f/255, PSNR %.1f dB\n", name,
               (unsigned long long)differing, fraction * 100.0, r.max_abs * 255.0, r.psnr);
        ok = r.pixels_over == 0 && fraction <= MAX_DIFF_FRACTION;
        CHECK_MSG(t, ok, "%s differs from %s beyond the tolerance (<= %d/255 on <= %.1f%% of pixels)", name, path,
                  MAX_CHANNEL_DIFF, MAX_DIFF_FRACTION * 100.0);
        if (!ok) {
            char out[512];
            snprintf(out, sizeof out, "%s.actual.png", name);
            mvr_image_write(out, &actual, &err);
            mvr_image_compare(&actual, &expected, 1.5 / 255.0, diff, &r, &err);
            printf("  wrote %s and %s for a look\n", out, diff);
        }
    }
    mvr_image_free(&gold);
    return ok;
}

static void golden(mvr_test_state *t, const char *demo, uint32_t views)
{
    mvr_context *ctx = NULL;
    mvr_error err;
    if (mvr_context_create(NULL, &ctx, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s", err.message);
        return;
    }
    mvr_scene *scene = NULL;
    mvr_view_set *vs = NULL;
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_demo_desc dd = {views, W, H, {0}};
    mvr_renderer_desc rd = {.context = ctx};
    mvr_target_desc td = {W, H, views, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    mvr_render_desc desc = {.clear_color = {0.02f, 0.025f, 0.035f, 1.0f}, .exposure = 1.0f, .tone_map = MVR_TONE_MAP_NONE};
    bool ok = mvr_demo_create(demo, &dd, &scene, &vs, &err) == MVR_OK &&
              mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
              mvr_renderer_render(r, scene, vs, target, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "%s: %s %s", demo, err.message, r ? mvr_renderer_last_error(r) : "");
    uint8_t *px = malloc((size_t)W * H * 4);
    for (uint32_t k = 0; ok && k < views; ++k) {
        ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, px, (size_t)W * H * 4) == MVR_OK;
        CHECK(t, ok);
        char name[64], path[1024];
        snprintf(name, sizeof name, "%s_view%u", demo, k);
        snprintf(path, sizeof path, "%s/%s.png", MVR_GOLDEN_DIR, name);
        if (ok)
            compare(t, name, px, path);
    }
    free(px);
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
}

static void golden_stereo(mvr_test_state *t) { golden(t, "stereo", 2); }
static void golden_cube(mvr_test_state *t) { golden(t, "cube", 6); }
static void golden_city(mvr_test_state *t) { golden(t, "city", 2); }
static void golden_ring(mvr_test_state *t) { golden(t, "ring", 4); }

MVR_TEST_MAIN(TEST(golden_stereo), TEST(golden_cube), TEST(golden_city), TEST(golden_ring))
