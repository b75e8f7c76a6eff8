/* gl: the order of blended draws. Shared (one order for every view, by
 * distance from the view set's origin) and per view (each view by its own
 * eye, one pass per view). */
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
        uint8_t *shared = stress_render(t, ctx, s, both, &o, &st);
        if (shared)
            CHECK_EQ_INT(t, st.transparency_order, MVR_TRANSPARENCY_ORDER_SHARED);
        /* per view, through the renderer desc */
        mvr_renderer_desc rd = {.context = ctx, .view_path = MVR_VIEW_PATH_MULTIVIEW,
                                .transparency_order = MVR_TRANSPARENCY_ORDER_PER_VIEW};
        if (!mvr_context_caps(ctx)->ext.ovr_multiview2 || pi)
            rd.view_path = path;
        mvr_renderer *r = NULL;
        mvr_target *target = NULL;
        mvr_target_desc td = {32, 32, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0};
        mvr_render_desc desc = {{0, 0, 0, 1}, 1.0f, MVR_TONE_MAP_NONE};
        bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
                  mvr_renderer_render(r, s, both, target, &desc) == MVR_OK;
        CHECK(t, ok);
        uint8_t *per_view = malloc(2 * layer);
        for (uint32_t k = 0; ok && k < 2; ++k)
            ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, per_view + k * layer, layer) == MVR_OK;
        mvr_renderer_get_stats(r, &st);
        CHECK_EQ_INT(t, st.transparency_order, MVR_TRANSPARENCY_ORDER_PER_VIEW);
        CHECK_EQ_INT(t, st.view_path, MVR_VIEW_PATH_LOOP); /* a pass per view, whatever was asked */
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

MVR_TEST_MAIN(TEST(per_view_order_is_each_views_own))
