/* gl: multisampled targets. Each view is drawn into a multisampled
 * renderbuffer and resolved into its layer; the result is closer to a 4x4
 * supersampled reference than the plain render, pixels inside surfaces do
 * not change, and every requested view path gives the same bytes. */
#include "stress/stress_util.h"

#define MW 96u
#define MH 72u

static uint8_t *render_stereo(mvr_test_state *t, mvr_context *ctx, mvr_view_path path, uint32_t samples,
                              uint32_t supersample, mvr_frame_stats *st)
{
    mvr_scene *s = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {2, MW, MH, {0}};
    if (mvr_demo_create("stereo", &dd, &s, &vs, NULL) != MVR_OK) {
        CHECK(t, 0);
        return NULL;
    }
    mvr_renderer_desc rd = {.context = ctx, .view_path = path};
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    uint32_t w = MW * supersample, h = MH * supersample;
    mvr_target_desc td = {w, h, 2, supersample > 1 ? MVR_COLOR_FORMAT_RGBA32F : MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0,
                          samples};
    bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
              mvr_renderer_render(r, s, vs, target, NULL) == MVR_OK;
    CHECK_MSG(t, ok, "%s", r ? mvr_renderer_last_error(r) : "renderer");
    uint8_t *out = ok ? malloc((size_t)MW * MH * 4 * 2) : NULL;
    float *samples_f = ok && supersample > 1 ? malloc((size_t)w * h * 16) : NULL;
    float *resolved = ok && supersample > 1 ? malloc((size_t)MW * MH * 16) : NULL;
    for (uint32_t k = 0; ok && k < 2; ++k) {
        uint8_t *dst = out + (size_t)k * MW * MH * 4;
        if (supersample > 1) {
            ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA32F, samples_f, (size_t)w * h * 16) ==
                     MVR_OK &&
                 mvr_downsample_rgba32f(samples_f, w, h, supersample, resolved) == MVR_OK;
            for (size_t i = 0; ok && i < (size_t)MW * MH * 4; ++i) {
                float c = resolved[i] < 0 ? 0 : resolved[i] > 1 ? 1 : resolved[i];
                if (i % 4 != 3) /* exact sRGB encode */
                    c = c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
                dst[i] = (uint8_t)(c * 255.0f + 0.5f);
            }
        } else {
            ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, dst, (size_t)MW * MH * 4) == MVR_OK;
        }
    }
    if (ok && st)
        mvr_renderer_get_stats(r, st);
    free(samples_f);
    free(resolved);
    if (!ok) {
        free(out);
        out = NULL;
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    return out;
}

static double rmse(const uint8_t *a, const uint8_t *b, size_t pixels)
{
    double sum = 0;
    for (size_t i = 0; i < pixels; ++i)
        for (size_t c = 0; c < 3; ++c) {
            double d = (double)a[i * 4 + c] - (double)b[i * 4 + c];
            sum += d * d;
        }
    return sqrt(sum / (3.0 * (double)pixels)) / 255.0;
}

static void msaa_is_closer_to_the_reference(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_caps *caps = mvr_context_caps(ctx);
    if (caps->limits.max_samples < 4) {
        mvr_context_destroy(ctx);
        SKIP(t, "GL_MAX_SAMPLES %d < 4", caps->limits.max_samples);
    }
    const size_t pixels = (size_t)MW * MH * 2;
    mvr_frame_stats st_msaa, st_mv;
    uint8_t *plain = render_stereo(t, ctx, MVR_VIEW_PATH_AUTO, 0, 1, NULL);
    uint8_t *msaa = render_stereo(t, ctx, MVR_VIEW_PATH_AUTO, 4, 1, &st_msaa);
    uint8_t *ref = render_stereo(t, ctx, MVR_VIEW_PATH_LOOP, 0, 4, NULL);
    uint8_t *msaa_mv = caps->ext.ovr_multiview2 ? render_stereo(t, ctx, MVR_VIEW_PATH_MULTIVIEW, 4, 1, &st_mv) : NULL;
    if (plain && msaa && ref) {
        CHECK_EQ_INT(t, st_msaa.samples, 4);
        CHECK_EQ_INT(t, st_msaa.resolves, 2);  /* one per view */
        CHECK_EQ_INT(t, st_msaa.view_path, MVR_VIEW_PATH_LOOP);
        double e_plain = rmse(plain, ref, pixels), e_msaa = rmse(msaa, ref, pixels);
        printf("  RMSE to the 4x4 reference: plain %.5f, 4x MSAA %.5f\n", e_plain, e_msaa);
        /* edges are where aliasing lives: MSAA must take a clear share of it away */
        CHECK_MSG(t, e_msaa < 0.9 * e_plain, "MSAA %.5f is not closer to the reference than plain %.5f", e_msaa,
                  e_plain);
        size_t same = 0;
        for (size_t i = 0; i < pixels; ++i)
            same += memcmp(plain + i * 4, msaa + i * 4, 4) == 0;
        /* one shading sample per pixel: inside surfaces nothing changes */
        CHECK_MSG(t, same > pixels / 2 && same < pixels, "%zu of %zu pixels unchanged by MSAA", same, pixels);
    }
    if (msaa && msaa_mv) {
        CHECK_MSG(t, memcmp(msaa, msaa_mv, pixels * 4) == 0, "MSAA: requested multiview and auto differ");
        CHECK_EQ_INT(t, st_mv.view_path, MVR_VIEW_PATH_LOOP);
    }
    free(plain);
    free(msaa);
    free(ref);
    free(msaa_mv);

    /* more samples than the GL has are refused with a message */
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    CHECK(t, mvr_renderer_create(&rd, &r, NULL) == MVR_OK);
    mvr_target_desc td = {16, 16, 1, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, (uint32_t)caps->limits.max_samples * 2};
    CHECK(t, mvr_target_create(r, &td, &target) == MVR_ERROR_UNSUPPORTED && target == NULL);
    CHECK_MSG(t, strstr(mvr_renderer_last_error(r), "GL_MAX_SAMPLES") != NULL, "%s", mvr_renderer_last_error(r));
    mvr_renderer_destroy(r);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(msaa_is_closer_to_the_reference))
