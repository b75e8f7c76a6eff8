/* gl: the order of blended draws. Centroid (one order for every view, by
 * distance from the view set's origin), per view (each view by its own eye:
 * after a multiview pass, a blend pass per view), and auto (per view only
 * where the views of a multiview pass disagree). */
#include "stress/stress_util.h"

/* Two half-transparent quads at z = -1 (red) and z = +1 (blue), seen from
 * z = +5 and z = -5: the two views need opposite orders, and from the
 * origin (their centroid) the quads are equally far. */
static mvr_scene *two_glass_panes(mvr_test_state *t)
{
    mvr_scene *s = stress_scene();
    const float colors[2][3] = {{1, 0, 0}, {0, 0, 1}};
    for (int i = 0; i < 2; ++i) {
        mvr_material_desc m = mvr_material_defaults();
        memcpy(m.base_color_factor, colors[i], sizeof colors[i]);
        m.base_color_factor[3] = 0.5f;
        m.alpha_mode = MVR_ALPHA_BLEND;
        m.unlit = true;
        m.double_sided = true;
        mvr_material_id mat;
        CHECK(t, mvr_scene_add_material(s, &m, &mat) == MVR_OK);
        stress_node(t, s, stress_add_quad(t, s, mat), 0, 0, i ? 1.0 : -1.0, 1.0);
    }
    return s;
}

static void per_view_order_is_each_views_own(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = two_glass_panes(t);
    const double eyes[2][3] = {{0, 0, 5}, {0, 0, -5}}, center[3] = {0, 0, 0};
    mvr_projection proj = {.yfov = 0.6, .znear = 0.1};
    mvr_view_desc views[2] = {stress_view(eyes[0], center, proj), stress_view(eyes[1], center, proj)};
    mvr_view_set *both = stress_view_set(t, views, 2, NULL);
    const size_t layer = (size_t)32 * 32 * 4;
    for (int pi = 0; pi < 2 && both; ++pi) {
        mvr_view_path path = pi ? MVR_VIEW_PATH_LOOP : MVR_VIEW_PATH_AUTO;
        stress_options o = {.width = 32, .height = 32, .path = path, .clear = {0, 0, 0, 1}};
        mvr_frame_stats st;
        /* the exact image of each view: a set of that view alone, whose
         * origin (its centroid) is its eye, so the shared order is its own */
        uint8_t *exact[2];
        for (int v = 0; v < 2; ++v) {
            mvr_view_set *one = stress_view_set(t, &views[v], 1, NULL);
            exact[v] = one ? stress_render(t, ctx, s, one, &o, NULL) : NULL;
            mvr_view_set_destroy(one);
        }
        /* centroid, through the renderer desc: one order for both views */
        mvr_renderer_desc cd = {.context = ctx, .view_path = path, .transparency_order = MVR_TRANSPARENCY_ORDER_CENTROID};
        uint8_t *shared = NULL;
        {
            mvr_renderer *cr = NULL;
            mvr_target *ct = NULL;
            mvr_target_desc ctd = {32, 32, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
            mvr_render_desc cdesc = {.clear_color = {0, 0, 0, 1}, .exposure = 1.0f, .tone_map = MVR_TONE_MAP_NONE};
            bool cok = mvr_renderer_create(&cd, &cr, NULL) == MVR_OK && mvr_target_create(cr, &ctd, &ct) == MVR_OK &&
                       mvr_renderer_render(cr, s, both, ct, &cdesc) == MVR_OK;
            CHECK(t, cok);
            shared = cok ? malloc(2 * layer) : NULL;
            for (uint32_t k = 0; cok && k < 2; ++k)
                cok = mvr_renderer_read_layer(cr, ct, k, MVR_READBACK_RGBA8, shared + k * layer, layer) == MVR_OK;
            mvr_renderer_get_stats(cr, &st);
            CHECK_EQ_INT(t, st.transparency_order, MVR_TRANSPARENCY_ORDER_CENTROID);
            CHECK_EQ_INT(t, st.blend_fallback_passes, 0);
            mvr_target_destroy(ct);
            mvr_renderer_destroy(cr);
        }
        /* auto (the default): these two views disagree, so on the multiview
         * path each gets its own blend pass after the shared opaque pass */
        mvr_renderer_desc rd = {.context = ctx, .view_path = MVR_VIEW_PATH_MULTIVIEW};
        if (!mvr_context_caps(ctx)->ext.ovr_multiview2 || pi)
            rd.view_path = path;
        mvr_renderer *r = NULL;
        mvr_target *target = NULL;
        mvr_target_desc td = {32, 32, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
        mvr_render_desc desc = {.clear_color = {0, 0, 0, 1}, .exposure = 1.0f, .tone_map = MVR_TONE_MAP_NONE};
        bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
                  mvr_renderer_render(r, s, both, target, &desc) == MVR_OK;
        CHECK(t, ok);
        uint8_t *per_view = malloc(2 * layer);
        for (uint32_t k = 0; ok && k < 2; ++k)
            ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, per_view + k * layer, layer) == MVR_OK;
        mvr_renderer_get_stats(r, &st);
        CHECK_EQ_INT(t, st.transparency_order, MVR_TRANSPARENCY_ORDER_AUTO);
        if (st.view_path == MVR_VIEW_PATH_MULTIVIEW) {
            CHECK_EQ_INT(t, st.blend_diverged_chunks, 1);
            CHECK_EQ_INT(t, st.blend_fallback_passes, 2);
            CHECK_EQ_INT(t, st.passes, 1);
        } else {
            CHECK_EQ_INT(t, st.blend_fallback_passes, 0); /* loop passes order each view anyway */
        }
        if (ok && exact[0] && exact[1] && shared) {
            for (int v = 0; v < 2; ++v)
                CHECK_MSG(t, memcmp(per_view + (size_t)v * layer, exact[v], layer) == 0,
                          "view %d: the per-view order differs from the view's own", v);
            /* and the shared order gets one of the two wrong, so the check above can fail */
            bool wrong = memcmp(shared, exact[0], layer) != 0 || memcmp(shared + layer, exact[1], layer) != 0;
            CHECK_MSG(t, wrong, "the shared order matched both views: the scene does not test the order");
            /* the panes overlap at the centre: red over blue from +z would be wrong there */
            const uint8_t *c0 = exact[0] + (16 * 32 + 16) * 4, *c1 = exact[1] + (16 * 32 + 16) * 4;
            CHECK_MSG(t, c0[2] > c0[0] && c1[0] > c1[2], "front pane should dominate: %u,%u,%u / %u,%u,%u", c0[0],
                      c0[1], c0[2], c1[0], c1[1], c1[2]);
        }
        free(per_view);
        free(shared);
        free(exact[0]);
        free(exact[1]);
        mvr_target_destroy(target);
        mvr_renderer_destroy(r);
    }
    mvr_view_set_destroy(both);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}


/* Every demo, 2 and 10 views: with auto and per_view the multiview path
 * (per-view blend passes where needed) equals the loop byte for byte; on
 * the stereo demo (glass, two eyes 6.4 cm apart) the centroid order is
 * within 1/255 RMSE of the exact one, and auto needs no fallback there. */
static void multiview_with_fallback_equals_loop(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    if (!mvr_context_caps(ctx)->ext.ovr_multiview2) {
        mvr_context_destroy(ctx);
        SKIP(t, "no GL_OVR_multiview2");
    }
    const mvr_transparency_order orders[2] = {MVR_TRANSPARENCY_ORDER_AUTO, MVR_TRANSPARENCY_ORDER_PER_VIEW};
    const uint32_t counts[2] = {2, 10};
    for (uint32_t d = 0; mvr_demo_name(d); ++d)
        for (int c = 0; c < 2; ++c) {
            mvr_scene *s = NULL;
            mvr_view_set *vs = NULL;
            mvr_demo_desc dd = {counts[c], 48, 48, {0}};
            CHECK(t, mvr_demo_create(mvr_demo_name(d), &dd, &s, &vs, NULL) == MVR_OK);
            size_t bytes = (size_t)counts[c] * 48 * 48 * 4;
            uint8_t *img[3] = {NULL, NULL, NULL};
            mvr_frame_stats st[3];
            for (int k = 0; k < 3; ++k) {
                /* k 0: loop (auto); 1: multiview, auto; 2: multiview, per_view */
                mvr_renderer_desc rd = {.context = ctx, .view_path = k ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP,
                                        .transparency_order = k == 2 ? orders[1] : orders[0]};
                mvr_renderer *r = NULL;
                mvr_target *tg = NULL;
                mvr_target_desc td = {48, 48, counts[c], MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
                bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK &&
                          mvr_renderer_render(r, s, vs, tg, NULL) == MVR_OK;
                CHECK(t, ok);
                img[k] = ok ? malloc(bytes) : NULL;
                for (uint32_t l = 0; ok && l < counts[c]; ++l)
                    ok = mvr_renderer_read_layer(r, tg, l, MVR_READBACK_RGBA8, img[k] + (size_t)l * 48 * 48 * 4,
                                                 48 * 48 * 4) == MVR_OK;
                mvr_renderer_get_stats(r, &st[k]);
                mvr_target_destroy(tg);
                mvr_renderer_destroy(r);
            }
            if (img[0] && img[1] && img[2]) {
                CHECK_MSG(t, memcmp(img[0], img[1], bytes) == 0, "%s x%u: auto multiview differs from the loop",
                          mvr_demo_name(d), counts[c]);
                CHECK_MSG(t, memcmp(img[0], img[2], bytes) == 0, "%s x%u: per_view multiview differs from the loop",
                          mvr_demo_name(d), counts[c]);
                report_image_diff("auto multiview vs loop", img[0], img[1], 48, 48, counts[c]);
                report_image_diff("per_view multiview vs loop", img[0], img[2], 48, 48, counts[c]);
                printf("  %-6s x%-2u blended sub-passes %u; auto: %u chunks diverged, %u fallback passes; "
                       "per_view: %u\n", mvr_demo_name(d), counts[c], st[1].sub_passes[2], st[1].blend_diverged_chunks,
                       st[1].blend_fallback_passes, st[2].blend_fallback_passes);
            }
            for (int k = 0; k < 3; ++k)
                free(img[k]);
            mvr_view_set_destroy(vs);
            mvr_scene_destroy(s);
        }

    /* stereo: the centroid order against the exact one */
    mvr_scene *s = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {2, 160, 120, {0}};
    CHECK(t, mvr_demo_create("stereo", &dd, &s, &vs, NULL) == MVR_OK);
    uint8_t *img[2] = {NULL, NULL};
    for (int k = 0; k < 2; ++k) {
        mvr_renderer_desc rd = {.context = ctx, .view_path = MVR_VIEW_PATH_MULTIVIEW,
                                .transparency_order = k ? MVR_TRANSPARENCY_ORDER_CENTROID : MVR_TRANSPARENCY_ORDER_PER_VIEW};
        mvr_renderer *r = NULL;
        mvr_target *tg = NULL;
        mvr_target_desc td = {160, 120, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
        bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK &&
                  mvr_renderer_render(r, s, vs, tg, NULL) == MVR_OK;
        img[k] = ok ? malloc((size_t)160 * 120 * 8) : NULL;
        for (uint32_t l = 0; ok && l < 2; ++l)
            ok = mvr_renderer_read_layer(r, tg, l, MVR_READBACK_RGBA8, img[k] + (size_t)l * 160 * 120 * 4,
                                         160 * 120 * 4) == MVR_OK;
        CHECK(t, ok);
        mvr_target_destroy(tg);
        mvr_renderer_destroy(r);
    }
    if (img[0] && img[1]) {
        double sum = 0;
        size_t n = (size_t)160 * 120 * 2;
        for (size_t i = 0; i < n; ++i)
            for (size_t ch = 0; ch < 3; ++ch) {
                double diff = (double)img[0][i * 4 + ch] - (double)img[1][i * 4 + ch];
                sum += diff * diff;
            }
        double rmse = sqrt(sum / (3.0 * (double)n)) / 255.0;
        printf("  stereo: centroid order against exact per-view order: RMSE %.6f\n", rmse);
        CHECK_MSG(t, rmse <= 1.0 / 255.0, "stereo: centroid order RMSE %.5f > 1/255", rmse);
    }
    free(img[0]);
    free(img[1]);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(per_view_order_is_each_views_own), TEST(multiview_with_fallback_equals_loop))
