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
#include "png_read.h"
#include "png_write.h"

#define W 160
#define H 120
#define MAX_CHANNEL_DIFF 1
#define MAX_DIFF_FRACTION 0.001

static bool compare(mvr_test_state *t, const char *name, const uint8_t *bottom_up, const char *path)
{
    if (getenv("MVR_UPDATE_GOLDEN")) {
        CHECK_MSG(t, png_write_rgba8(path, bottom_up, W, H, true), "cannot write %s", path);
        printf("  updated %s\n", path);
        return true;
    }
    char why[256];
    uint32_t w = 0, h = 0;
    uint8_t *gold = png_read_rgba8(path, &w, &h, why, sizeof why);
    if (!gold) {
        CHECK_MSG(t, 0, "%s: %s (MVR_UPDATE_GOLDEN=1 makes it)", path, why);
        return false;
    }
    bool ok = w == W && h == H;
    CHECK_MSG(t, ok, "%s is %ux%u, expected %ux%u", path, w, h, W, H);
    uint32_t differing = 0, worst = 0;
    for (uint32_t y = 0; ok && y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            const uint8_t *a = bottom_up + ((size_t)(H - 1 - y) * W + x) * 4, *b = gold + ((size_t)y * W + x) * 4;
            uint32_t d = 0;
            for (int c = 0; c < 4; ++c) {
                uint32_t e = (uint32_t)abs((int)a[c] - (int)b[c]);
                d = e > d ? e : d;
            }
            differing += d > 0;
            worst = d > worst ? d : worst;
        }
    double fraction = (double)differing / (W * H);
    if (ok) {
        printf("  %s: %u pixels differ (%.3f%%), worst channel %u/255\n", name, differing, fraction * 100.0, worst);
        ok = worst <= MAX_CHANNEL_DIFF && fraction <= MAX_DIFF_FRACTION;
        CHECK_MSG(t, ok, "%s differs from %s beyond the tolerance (<= %d/255 on <= %.1f%% of pixels)", name, path,
                  MAX_CHANNEL_DIFF, MAX_DIFF_FRACTION * 100.0);
        if (!ok) {
            char out[512];
            snprintf(out, sizeof out, "%s.actual.png", name);
            png_write_rgba8(out, bottom_up, W, H, true);
            printf("  wrote %s for a look\n", out);
        }
    }
    free(gold);
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
    mvr_renderer_desc rd = {ctx, MVR_VIEW_PATH_AUTO, {0}};
    mvr_target_desc td = {W, H, views, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0};
    mvr_render_desc desc = {{0.02f, 0.025f, 0.035f, 1.0f}, 1.0f, MVR_TONE_MAP_NONE};
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
