/* gl: shadow maps. One depth array drawn once per frame (one multiview pass
 * whatever the view count), read by every view; the same pixels on both
 * view paths; per-view light masks (render layers): a light masked out of a
 * view contributes nothing there, and a light in no view takes no layer. */
#include <math.h>

#include "stress/stress_util.h"

#define SIZE 64
#define LAYER_BYTES ((size_t)SIZE * SIZE * 4)

/* A grey floor (y = 0, half size 4), a box over it (y 0.5 .. 1.5), a sun
 * along (0, -0.8, -0.6): the box's shadow falls on the floor towards -z,
 * around (0, 0, -1.2), where a camera looking straight down sees it. */
static mvr_scene *box_over_floor(mvr_test_state *t, uint32_t sun_layers, bool spot, uint32_t spot_layers)
{
    mvr_scene *s = stress_scene();
    mvr_material_desc grey = mvr_material_defaults();
    grey.metallic_factor = 0.0f;
    grey.base_color_factor[0] = grey.base_color_factor[1] = grey.base_color_factor[2] = 0.6f;
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, &grey, &mat) == MVR_OK);
    /* the quad faces +Z: -90 degrees about X turns it to face +Y */
    const double h = 0.70710678118654752;
    mvr_node_desc floor = {.mesh = stress_add_quad(t, s, mat), .rotation = {-h, 0, 0, h}, .scale = {4, 4, 4}};
    mvr_node_id id;
    CHECK(t, mvr_scene_add_node(s, &floor, &id) == MVR_OK);
    stress_node(t, s, stress_add_box(t, s, 0.5f, mat), 0, 1.0, 0, 1.0);
    /* -Z turned by a about X points along (0, sin a, -cos a): a = -53.13 degrees */
    double a = atan2(-0.8, 0.6);
    mvr_light_desc sun = {.type = MVR_LIGHT_DIRECTIONAL, .intensity = 3.0f, .cast_shadows = true, .layers = sun_layers};
    mvr_light_id lid;
    CHECK(t, mvr_scene_add_light(s, &sun, &lid) == MVR_OK);
    mvr_node_desc sun_node = {.light = lid, .rotation = {sin(a / 2), 0, 0, cos(a / 2)}};
    CHECK(t, mvr_scene_add_node(s, &sun_node, &id) == MVR_OK);
    if (spot) {
        /* a red spot straight down from (1.5, 3, 1.5) */
        mvr_light_desc sp = {.type = MVR_LIGHT_SPOT, .color = {1, 0.1f, 0.1f}, .intensity = 40.0f,
                             .outer_cone_angle = 0.7f, .cast_shadows = true, .layers = spot_layers};
        CHECK(t, mvr_scene_add_light(s, &sp, &lid) == MVR_OK);
        mvr_node_desc spot_node = {.light = lid, .translation = {1.5, 3, 1.5}, .rotation = {-h, 0, 0, h}};
        CHECK(t, mvr_scene_add_node(s, &spot_node, &id) == MVR_OK);
    }
    float ambient[3] = {0.15f, 0.15f, 0.15f};
    mvr_scene_set_ambient(s, ambient);
    return s;
}

/* Looking straight down from (x, 8, 0): screen right is +x, screen up -z;
 * orthographic, 3 units each side. */
static mvr_view_desc top_view(double x)
{
    const double h = 0.70710678118654752;
    mvr_view_desc v;
    memset(&v, 0, sizeof v);
    v.position[0] = x;
    v.position[1] = 8;
    v.orientation[0] = -h;
    v.orientation[3] = h;
    v.projection.type = MVR_PROJECTION_ORTHOGRAPHIC;
    v.projection.xmag = v.projection.ymag = 3;
    v.projection.znear = 0.1;
    v.projection.zfar = 20;
    return v;
}

/* Mean linear-ish luminance (byte units) of the 3x3 pixels around the
 * floor point (x, 0, z) in a top_view(view_x) layer. */
static double floor_luma(const uint8_t *layer, double view_x, double x, double z)
{
    int col = (int)(((x - view_x) / 3.0 * 0.5 + 0.5) * SIZE), row = (int)((-z / 3.0 * 0.5 + 0.5) * SIZE);
    double sum = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const uint8_t *p = layer + ((size_t)(row + dy) * SIZE + (size_t)(col + dx)) * 4;
            sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        }
    return sum / 9.0;
}

static uint8_t *render(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, const mvr_view_desc *views, uint32_t n,
                       mvr_view_path path, mvr_shadow_mode mode, mvr_frame_stats *st)
{
    mvr_view_set *vs = stress_view_set(t, views, n, NULL);
    stress_options o = {.width = SIZE, .height = SIZE, .path = path, .clear = {0, 0, 0, 1}};
    o.shadows.mode = mode;
    uint8_t *img = vs ? stress_render(t, ctx, s, vs, &o, st) : NULL;
    mvr_view_set_destroy(vs);
    return img;
}

static void shadow_falls_where_the_box_hides_the_sun(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = box_over_floor(t, 0, false, 0);
    mvr_view_desc v = top_view(0);
    mvr_frame_stats off_st, on_st;
    uint8_t *off = render(t, ctx, s, &v, 1, MVR_VIEW_PATH_AUTO, MVR_SHADOWS_OFF, &off_st);
    uint8_t *on = render(t, ctx, s, &v, 1, MVR_VIEW_PATH_AUTO, MVR_SHADOWS_DEFAULT, &on_st);
    if (off && on) {
        CHECK_EQ_INT(t, off_st.shadow_layers, 0);
        CHECK_EQ_INT(t, off_st.shadow_passes, 0);
        CHECK_EQ_INT(t, on_st.shadow_layers, 3); /* the default three cascades */
        double lit_off = floor_luma(off, 0, 0, -1.2), lit_on = floor_luma(on, 0, 0, -1.2);
        printf("  shadowed floor: %.1f without shadows, %.1f with\n", lit_off, lit_on);
        CHECK_MSG(t, lit_on < 0.5 * lit_off, "the box's shadow: luma %.1f with shadows, %.1f without", lit_on,
                  lit_off);
        /* where nothing stands between the floor and the sun: the same bytes
         * (the PCF taps all pass, so the light is multiplied by exactly 1) */
        const double lit_points[3][2] = {{0, 1.5}, {-2, -1.2}, {2, 2}};
        for (int k = 0; k < 3; ++k) {
            double a = floor_luma(off, 0, lit_points[k][0], lit_points[k][1]);
            double b = floor_luma(on, 0, lit_points[k][0], lit_points[k][1]);
            CHECK_MSG(t, a == b && a > 20.0, "lit floor at (%g, %g): %.2f without shadows, %.2f with",
                      lit_points[k][0], lit_points[k][1], a, b);
        }
        /* no acne: the lit floor is uniform (a directional light on a plane) */
        double lo = 1e9, hi = 0;
        for (double x = -2.5; x <= 2.5; x += 0.25) {
            double l = floor_luma(on, 0, x, 2.0);
            lo = fmin(lo, l);
            hi = fmax(hi, l);
        }
        CHECK_MSG(t, hi - lo <= 1.0, "lit floor row varies from %.2f to %.2f (shadow acne?)", lo, hi);
    }
    free(off);
    free(on);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

static void one_shadow_pass_whatever_the_views(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    if (mvr_context_caps(ctx)->limits.max_views_ovr < 4) {
        printf("  SKIP: no multiview with 4 views here\n");
        mvr_context_destroy(ctx);
        return;
    }
    /* a sun (3 cascades) and a spot: 4 layers, one multiview shadow pass */
    mvr_scene *s = box_over_floor(t, 0, true, 0);
    mvr_view_desc views[12];
    for (int i = 0; i < 12; ++i)
        views[i] = top_view(0.05 * i);
    const uint32_t counts[4] = {1, 2, 6, 12};
    uint8_t *mv_imgs[4] = {0};
    for (int c = 0; c < 4; ++c) {
        uint32_t n = counts[c];
        mvr_frame_stats mv, loop;
        uint8_t *a = render(t, ctx, s, views, n, MVR_VIEW_PATH_MULTIVIEW, MVR_SHADOWS_DEFAULT, &mv);
        uint8_t *b = render(t, ctx, s, views, n, MVR_VIEW_PATH_LOOP, MVR_SHADOWS_DEFAULT, &loop);
        if (a && b) {
            printf("  %2u views: multiview %u shadow pass(es), %u layers, %u caster draws; loop %u passes\n", n,
                   mv.shadow_passes, mv.shadow_layers, mv.shadow_draws, loop.shadow_passes);
            CHECK_EQ_INT(t, mv.shadow_passes, 1);
            CHECK_EQ_INT(t, mv.shadow_layers, 4);
            CHECK_EQ_INT(t, loop.shadow_layers, 4);
            CHECK_EQ_INT(t, loop.shadow_passes, 4); /* without multiview: a pass per layer */
            /* shadows render identically on both view paths */
            unsigned d = max_abs_diff8(a, b, LAYER_BYTES * n);
            CHECK_MSG(t, d == 0, "%u views: multiview and loop differ by %u", n, d);
        }
        free(b);
        mv_imgs[c] = a;
    }
    /* cascades fit the union of the views: more views may move them, but
     * every view still gets a shadow where the box hides the sun */
    for (int c = 0; c < 4; ++c)
        if (mv_imgs[c]) {
            double l = floor_luma(mv_imgs[c], 0, 0, -1.2), lit = floor_luma(mv_imgs[c], 0, -2, -1.2);
            CHECK_MSG(t, l < 0.6 * lit, "%u views: view 0's floor luma %.1f in the shadow, %.1f beside it", counts[c],
                      l, lit);
        }
    for (int c = 0; c < 4; ++c)
        free(mv_imgs[c]);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

static void masked_light_contributes_nothing_and_takes_no_layer(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    /* the sun on render layer 1, the red spot on layer 2 */
    mvr_scene *both = box_over_floor(t, 1, true, 2);
    mvr_scene *sun_only = box_over_floor(t, 0, false, 0);
    mvr_view_desc views[3] = {top_view(0), top_view(0), top_view(0)};
    views[0].light_layers = 1; /* the sun alone */
    views[1].light_layers = 2; /* the spot alone */
    views[2].light_layers = 3; /* both */
    for (int pi = 0; pi < 2; ++pi) {
        mvr_view_path path = pi ? MVR_VIEW_PATH_LOOP : MVR_VIEW_PATH_AUTO;
        mvr_frame_stats st, ref_st, one_st;
        uint8_t *img = render(t, ctx, both, views, 3, path, MVR_SHADOWS_DEFAULT, &st);
        uint8_t *ref = render(t, ctx, sun_only, views, 1, path, MVR_SHADOWS_DEFAULT, &ref_st);
        /* every view on layer 1: the spot shines in none, so it takes no layer */
        mvr_view_desc sun_views[2] = {views[0], views[0]};
        uint8_t *one = render(t, ctx, both, sun_views, 2, path, MVR_SHADOWS_DEFAULT, &one_st);
        if (img && ref && one) {
            CHECK_EQ_INT(t, st.shadow_layers, 4);     /* 3 cascades + the spot, shared by the views */
            CHECK_EQ_INT(t, ref_st.shadow_layers, 3);
            CHECK_EQ_INT(t, one_st.shadow_layers, 3); /* the spot, in no view, has none */
            /* view 0 sees the sun alone: as if the spot were not there */
            unsigned d = max_abs_diff8(img, ref, LAYER_BYTES);
            CHECK_MSG(t, d <= 1, "%s: the spot, masked out of view 0, changes it by %u", mvr_view_path_name(path), d);
            d = max_abs_diff8(one, ref, LAYER_BYTES);
            CHECK_MSG(t, d <= 1, "%s: the spot in no view changes view 0 by %u", mvr_view_path_name(path), d);
            /* view 1 sees the spot alone: red, and no sun (its shadow region
             * is as lit as anywhere: the sun does not reach it) */
            const uint8_t *v1 = img + LAYER_BYTES, *v2 = img + 2 * LAYER_BYTES;
            int col = SIZE / 2 + (int)(1.5 / 3.0 * 0.5 * SIZE), row = SIZE / 2 - (int)(1.5 / 3.0 * 0.5 * SIZE);
            const uint8_t *p1 = v1 + ((size_t)row * SIZE + (size_t)col) * 4;
            CHECK_MSG(t, p1[0] > p1[1] + 40, "view 1 under the spot: rgb %u %u %u, expected red", p1[0], p1[1], p1[2]);
            double sun_lit0 = floor_luma(img, 0, -2, 2), sun_lit1 = floor_luma(v1, 0, -2, 2);
            CHECK_MSG(t, sun_lit1 < 0.5 * sun_lit0, "view 1 (no sun): floor luma %.1f, view 0 %.1f", sun_lit1,
                      sun_lit0);
            /* view 2 sees both: brighter than either alone where both reach */
            const uint8_t *p2 = v2 + ((size_t)row * SIZE + (size_t)col) * 4;
            CHECK_MSG(t, p2[0] >= p1[0] && p2[1] > p1[1], "view 2 (both lights) %u %u vs view 1 %u %u", p2[0],
                      p2[1], p1[0], p1[1]);
        }
        free(img);
        free(ref);
        free(one);
    }
    mvr_scene_destroy(both);
    mvr_scene_destroy(sun_only);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(shadow_falls_where_the_box_hides_the_sun), TEST(one_shadow_pass_whatever_the_views),
              TEST(masked_light_contributes_nothing_and_takes_no_layer))
