/* gl: anti-aliased targets. Multisampled: each view drawn into a
 * multisampled renderbuffer and resolved into its layer; closer to a 4x4
 * supersampled reference than the plain render, pixels inside surfaces
 * unchanged, every requested view path the same bytes. Supersampled: views
 * drawn into a float array N times the size and resolved by a box-filter
 * pass, one multiview pass per chunk; multiview and loop the same bytes. */
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
                          samples, 0, samples > 1 ? MVR_ANTI_ALIASING_DEFAULT : MVR_ANTI_ALIASING_NONE, 0};
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
    /* where the GL draws multisampled multiview (NVIDIA: both ways), auto
     * takes it and the GL resolves; else (llvmpipe) one view at a time,
     * each resolved into its layer */
    const bool msaa_multiview = caps->ext.ovr_multiview2 &&
                                (caps->ext.ovr_multiview_multisampled_render_to_texture || caps->ext.multiview_msaa_array);
    const mvr_view_path msaa_path = msaa_multiview ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP;
    if (plain && msaa && ref) {
        CHECK_EQ_INT(t, st_msaa.samples, 4);
        if (!msaa_multiview)
            CHECK_EQ_INT(t, st_msaa.resolves, 2);  /* one per view */
        CHECK_EQ_INT(t, st_msaa.view_path, msaa_path);
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
        CHECK_EQ_INT(t, st_mv.view_path, msaa_path);
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
    mvr_target_desc td = {16, 16, 1, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, (uint32_t)caps->limits.max_samples * 2, 0, MVR_ANTI_ALIASING_DEFAULT, 0};
    CHECK(t, mvr_target_create(r, &td, &target) == MVR_ERROR_UNSUPPORTED && target == NULL);
    CHECK_MSG(t, strstr(mvr_renderer_last_error(r), "GL_MAX_SAMPLES") != NULL, "%s", mvr_renderer_last_error(r));
    mvr_renderer_destroy(r);
    mvr_context_destroy(ctx);
}


static uint8_t *render_demo_target(mvr_test_state *t, mvr_context *ctx, const char *demo, uint32_t views,
                                   mvr_view_path path, const mvr_target_desc *td, mvr_frame_stats *st)
{
    mvr_scene *s = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {views, td->width, td->height, {0}};
    if (mvr_demo_create(demo, &dd, &s, &vs, NULL) != MVR_OK) {
        CHECK(t, 0);
        return NULL;
    }
    mvr_renderer_desc rd = {.context = ctx, .view_path = path};
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, td, &target) == MVR_OK &&
              mvr_renderer_render(r, s, vs, target, NULL) == MVR_OK;
    CHECK_MSG(t, ok, "%s: %s", demo, r ? mvr_renderer_last_error(r) : "renderer");
    size_t layer = (size_t)td->width * td->height * 4;
    uint8_t *out = ok ? malloc(layer * views) : NULL;
    for (uint32_t k = 0; ok && k < views; ++k)
        ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, out + layer * k, layer) == MVR_OK;
    if (ok && st)
        mvr_renderer_get_stats(r, st);
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

static void supersampling_on_every_path(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    uint32_t max_views = (uint32_t)mvr_context_caps(ctx)->limits.max_views_ovr;
    const char *demos[2] = {"stereo", "city"};
    const uint32_t counts[2] = {2, 8};
    for (int d = 0; d < 2; ++d)
        for (int c = 0; c < 2; ++c) {
            mvr_target_desc td = {MW, MH, counts[c], MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 2, MVR_ANTI_ALIASING_DEFAULT, 0};
            mvr_frame_stats sm, sl;
            uint8_t *loop = render_demo_target(t, ctx, demos[d], counts[c], MVR_VIEW_PATH_LOOP, &td, &sl);
            uint8_t *multi = mv ? render_demo_target(t, ctx, demos[d], counts[c], MVR_VIEW_PATH_MULTIVIEW, &td, &sm)
                                : NULL;
            size_t bytes = (size_t)MW * MH * 4 * counts[c];
            if (loop) {
                CHECK_EQ_INT(t, sl.supersample, 2);
                CHECK_EQ_INT(t, sl.resolves, counts[c]); /* one pass per layer */
            }
            if (loop && multi) {
                CHECK_MSG(t, memcmp(loop, multi, bytes) == 0, "%s x%u: supersampled multiview and loop differ",
                          demos[d], counts[c]);
                report_image_diff("supersampled multiview vs loop", loop, multi, MW, MH, counts[c]);
                CHECK_EQ_INT(t, sm.view_path, MVR_VIEW_PATH_MULTIVIEW);
                /* one resolve pass per multiview chunk, whatever the views */
                CHECK_EQ_INT(t, sm.resolves, (counts[c] + max_views - 1) / max_views);
            }
            free(loop);
            free(multi);
        }
    /* closer to the 4x4 reference than plain; an RGBA8 target (the resolve
     * encodes) within one step of the sRGB one (the GL encodes) */
    const size_t pixels = (size_t)MW * MH * 2;
    mvr_target_desc plain_td = {MW, MH, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    mvr_target_desc ss_td = {MW, MH, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 2, MVR_ANTI_ALIASING_DEFAULT, 0};
    mvr_target_desc ss8_td = {MW, MH, 2, MVR_COLOR_FORMAT_RGBA8, 0, 0, 0, 0, 2, MVR_ANTI_ALIASING_DEFAULT, 0};
    uint8_t *plain = render_demo_target(t, ctx, "stereo", 2, MVR_VIEW_PATH_AUTO, &plain_td, NULL);
    uint8_t *ss = render_demo_target(t, ctx, "stereo", 2, MVR_VIEW_PATH_AUTO, &ss_td, NULL);
    uint8_t *ss8 = render_demo_target(t, ctx, "stereo", 2, MVR_VIEW_PATH_AUTO, &ss8_td, NULL);
    uint8_t *ref = render_stereo(t, ctx, MVR_VIEW_PATH_LOOP, 0, 4, NULL);
    if (plain && ss && ss8 && ref) {
        double e_plain = rmse(plain, ref, pixels), e_ss = rmse(ss, ref, pixels);
        printf("  RMSE to the 4x4 reference: plain %.5f, 2x2 supersampled %.5f\n", e_plain, e_ss);
        CHECK_MSG(t, e_ss < 0.7 * e_plain, "2x2 %.5f is not closer to the reference than plain %.5f", e_ss, e_plain);
        int worst = 0;
        for (size_t i = 0; i < pixels * 4; ++i) {
            int dlt = abs((int)ss[i] - (int)ss8[i]);
            worst = dlt > worst ? dlt : worst;
        }
        CHECK_MSG(t, worst <= 1, "RGBA8 and sRGB supersampled targets differ by %d", worst);
    }
    free(plain);
    free(ss);
    free(ss8);
    free(ref);
    /* refused: more than 4, or with multisampling */
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    CHECK(t, mvr_renderer_create(&rd, &r, NULL) == MVR_OK);
    mvr_target_desc bad1 = {16, 16, 1, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 5, MVR_ANTI_ALIASING_DEFAULT, 0};
    mvr_target_desc bad2 = {16, 16, 1, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 4, 2, MVR_ANTI_ALIASING_DEFAULT, 0};
    CHECK(t, mvr_target_create(r, &bad1, &target) == MVR_ERROR_INVALID_ARGUMENT && !target);
    CHECK(t, mvr_target_create(r, &bad2, &target) == MVR_ERROR_INVALID_ARGUMENT && !target);
    mvr_renderer_destroy(r);
    mvr_context_destroy(ctx);
}

/* anti_aliasing picks samples or supersampling; auto is 4x MSAA where the
 * format takes it: multiview passes where the GL has multisampled
 * multiview, else view by view (llvmpipe) with the same bytes as asking
 * for 4 samples; the stats say which ran. */
static void anti_aliasing_choices(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_caps *caps = mvr_context_caps(ctx);
    const size_t bytes = (size_t)MW * MH * 4 * 2;
    mvr_target_desc four = {MW, MH, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 4, 0, MVR_ANTI_ALIASING_DEFAULT, 0};
    mvr_target_desc autod = {MW, MH, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_AUTO, 0};
    mvr_target_desc ss = {MW, MH, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_SUPERSAMPLE, 0};
    mvr_target_desc none = {MW, MH, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 4, 2, MVR_ANTI_ALIASING_NONE, 0};
    mvr_target_desc plain = {MW, MH, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    mvr_frame_stats st_four, st_auto, st_ss, st_none, st_plain;
    uint8_t *a = render_demo_target(t, ctx, "stereo", 2, MVR_VIEW_PATH_MULTIVIEW, &four, &st_four);
    uint8_t *b = render_demo_target(t, ctx, "stereo", 2, MVR_VIEW_PATH_MULTIVIEW, &autod, &st_auto);
    uint8_t *c = render_demo_target(t, ctx, "stereo", 2, MVR_VIEW_PATH_MULTIVIEW, &ss, &st_ss);
    uint8_t *d = render_demo_target(t, ctx, "stereo", 2, MVR_VIEW_PATH_MULTIVIEW, &none, &st_none);
    uint8_t *e = render_demo_target(t, ctx, "stereo", 2, MVR_VIEW_PATH_MULTIVIEW, &plain, &st_plain);
    if (a && b && c && d && e) {
        CHECK_EQ_INT(t, st_auto.anti_aliasing, MVR_ANTI_ALIASING_MSAA);
        CHECK_EQ_INT(t, st_auto.samples, 4);
        CHECK_EQ_INT(t, st_four.anti_aliasing, MVR_ANTI_ALIASING_MSAA);
        printf("  auto: %u samples, %s, %s path\n", st_auto.samples,
               st_auto.msaa_multiview ? "multiview passes" : "view by view", mvr_view_path_name(st_auto.view_path));
        /* multisampled multiview only where the GL attaches it */
        bool mv_msaa = caps->ext.multiview_msaa_array || caps->ext.ovr_multiview_multisampled_render_to_texture;
        CHECK_EQ_INT(t, st_auto.msaa_multiview, mv_msaa);
        if (!mv_msaa) {
            CHECK_EQ_INT(t, st_auto.view_path, MVR_VIEW_PATH_LOOP);
            CHECK_EQ_INT(t, st_auto.resolves, 2);
        } else {
            CHECK_EQ_INT(t, st_auto.view_path, MVR_VIEW_PATH_MULTIVIEW);
        }
        CHECK_MSG(t, memcmp(a, b, bytes) == 0, "auto and 4 samples differ by %u", max_abs_diff8(a, b, bytes));
        /* the default (nothing asked) is AUTO: anti-aliased */
        mvr_target_desc deflt = {MW, MH, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_DEFAULT, 0};
        mvr_frame_stats st_default;
        uint8_t *f = render_demo_target(t, ctx, "stereo", 2, MVR_VIEW_PATH_MULTIVIEW, &deflt, &st_default);
        CHECK_EQ_INT(t, st_default.anti_aliasing, MVR_ANTI_ALIASING_MSAA);
        CHECK_MSG(t, f && memcmp(f, b, bytes) == 0, "the default and auto differ");
        free(f);
        CHECK_EQ_INT(t, st_ss.anti_aliasing, MVR_ANTI_ALIASING_SUPERSAMPLE);
        CHECK_EQ_INT(t, st_ss.supersample, 2);
        CHECK_EQ_INT(t, st_ss.view_path, MVR_VIEW_PATH_MULTIVIEW);
        CHECK_EQ_INT(t, st_none.anti_aliasing, MVR_ANTI_ALIASING_NONE);
        CHECK_EQ_INT(t, st_none.samples, 1);
        CHECK_MSG(t, memcmp(d, e, bytes) == 0, "none (samples ignored) and plain differ by %u", max_abs_diff8(d, e, bytes));
        /* anti-aliasing changes edges */
        CHECK(t, memcmp(a, e, bytes) != 0 && memcmp(c, e, bytes) != 0);
    }
    free(a);
    free(b);
    free(c);
    free(d);
    free(e);
    /* an unknown choice is refused */
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    if (mvr_renderer_create(&rd, &r, NULL) == MVR_OK) {
        mvr_target_desc bad = {16, 16, 1, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, (mvr_anti_aliasing)99, 0};
        CHECK(t, mvr_target_create(r, &bad, &target) == MVR_ERROR_INVALID_ARGUMENT && !target);
        CHECK(t, strstr(mvr_renderer_last_error(r), "anti-aliasing") != NULL);
    }
    mvr_renderer_destroy(r);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(msaa_is_closer_to_the_reference), TEST(supersampling_on_every_path), TEST(anti_aliasing_choices))
