/* core: the shadow plan. Cascades cover what the views see, layers are
 * shared by views and only given to lights some view uses, and the layer
 * budget is kept. */
#include <math.h>

#include "mvr_test.h"
#include "shadow_plan.h"

static const float tri[9] = {-20, 0, -20, 20, 0, -20, 0, 0, 20};

/* A ground triangle, `suns` directional lights (cast_shadows, layers) and a spot. */
static mvr_scene *scene_with_lights(mvr_test_state *t, uint32_t suns, uint32_t spot_layers)
{
    mvr_scene *s = NULL;
    mvr_scene_create(NULL, &s, NULL);
    mvr_primitive_desc p = {.vertex_count = 3, .positions = tri};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "ground"};
    mvr_mesh_id mesh;
    CHECK(t, mvr_scene_add_mesh(s, &md, &mesh) == MVR_OK);
    mvr_node_desc nd = {.mesh = mesh};
    mvr_node_id id;
    CHECK(t, mvr_scene_add_node(s, &nd, &id) == MVR_OK);
    for (uint32_t i = 0; i < suns; ++i) {
        mvr_light_desc l = {.type = MVR_LIGHT_DIRECTIONAL, .intensity = 1, .cast_shadows = true};
        mvr_light_id lid;
        CHECK(t, mvr_scene_add_light(s, &l, &lid) == MVR_OK);
        /* pointing down and a little sideways: -Z turned about X */
        double a = -1.2 + 0.1 * i;
        mvr_node_desc ln = {.light = lid, .rotation = {sin(a / 2), 0, 0, cos(a / 2)}};
        CHECK(t, mvr_scene_add_node(s, &ln, &id) == MVR_OK);
    }
    mvr_light_desc sp = {.type = MVR_LIGHT_SPOT, .intensity = 1, .cast_shadows = true, .layers = spot_layers};
    mvr_light_id lid;
    CHECK(t, mvr_scene_add_light(s, &sp, &lid) == MVR_OK);
    mvr_node_desc ln = {.light = lid, .translation = {0, 5, 0}, .rotation = {-0.70710678, 0, 0, 0.70710678}};
    CHECK(t, mvr_scene_add_node(s, &ln, &id) == MVR_OK);
    return s;
}

static mvr_view_set *two_views(mvr_test_state *t, uint32_t layers0, uint32_t layers1)
{
    mvr_view_desc v[2];
    memset(v, 0, sizeof v);
    const double eyes[2][3] = {{-3, 2, 8}, {4, 3, 6}}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    for (int i = 0; i < 2; ++i) {
        mvr_view_look_at(&v[i], eyes[i], target, up);
        v[i].projection.yfov = 0.9;
    }
    v[0].light_layers = layers0;
    v[1].light_layers = layers1;
    mvr_view_set_desc d = {2, v, false, {0, 0, 0}};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_create(&d, &vs, NULL) == MVR_OK);
    return vs;
}

static mvr_dvec3 project(const mvr_dmat4 *m, mvr_dvec3 p)
{
    const double *a = m->m;
    double w = a[3] * p.x + a[7] * p.y + a[11] * p.z + a[15];
    return mvr_dvec3_make((a[0] * p.x + a[4] * p.y + a[8] * p.z + a[12]) / w,
                          (a[1] * p.x + a[5] * p.y + a[9] * p.z + a[13]) / w,
                          (a[2] * p.x + a[6] * p.y + a[10] * p.z + a[14]) / w);
}

static void cascades_hold_what_the_views_see(mvr_test_state *t)
{
    mvr_scene *s = scene_with_lights(t, 1, 0);
    mvr_view_set *vs = two_views(t, 0, 0);
    mvr_frame f = {0};
    char why[128];
    CHECK(t, mvr_frame_build(&f, s, vs->origin, 144, 64, NULL, why, sizeof why) == MVR_OK);
    mvr_shadow_desc d = mvr_shadow_desc_resolve(&(mvr_shadow_desc){0});
    mvr_shadow_plan plan;
    for (int reversed = 0; reversed < 2; ++reversed) {
        mvr_shadow_plan_build(&plan, &f, vs, 64, 64, reversed, &d);
        CHECK_EQ_INT(t, plan.layer_count, 4); /* 3 cascades + the spot */
        CHECK_EQ_INT(t, plan.light_first[0], 0);
        CHECK_EQ_INT(t, plan.light_layers[0], 3);
        CHECK_EQ_INT(t, plan.light_first[1], 3);
        CHECK_EQ_INT(t, plan.max_view_layers, 4);
        CHECK(t, !plan.masked);
        /* every point of the ground both views see lies inside some cascade
         * (xy in [-1, 1], depth inside the clip range) */
        mvr_frustum fr[2];
        for (int v = 0; v < 2; ++v) {
            mvr_dmat4 vp = mvr_view_relative_view_proj(&vs->views[v], vs->origin, (mvr_viewport){0, 0, 64, 64},
                                                       reversed);
            mvr_frustum_planes(&vp, reversed, &fr[v]);
        }
        unsigned seen = 0, outside = 0;
        for (double x = -15; x <= 15; x += 0.5)
            for (double z = -15; z <= 15; z += 0.5) {
                double p[3] = {x - vs->origin.x, -vs->origin.y, z - vs->origin.z};
                if (!mvr_sphere_in_frustum(&fr[0], p, 0) && !mvr_sphere_in_frustum(&fr[1], p, 0))
                    continue;
                seen++;
                bool inside = false;
                for (uint32_t k = 0; k < 3 && !inside; ++k) {
                    mvr_dvec3 c = project(&plan.layers[k].view_proj, mvr_dvec3_make(p[0], p[1], p[2]));
                    double zlo = reversed ? 0.0 : -1.0;
                    inside = fabs(c.x) <= 1 && fabs(c.y) <= 1 && c.z >= zlo && c.z <= 1;
                }
                outside += !inside;
            }
        CHECK_MSG(t, seen > 100 && outside == 0, "%s: %u of %u ground points the views see are in no cascade",
                  reversed ? "reversed" : "standard", outside, seen);
        /* cascades grow from near to far */
        CHECK(t, plan.layers[0].texel < plan.layers[1].texel && plan.layers[1].texel < plan.layers[2].texel);
    }
    mvr_frame_free(&f);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
}

static void layers_go_to_lights_some_view_uses(mvr_test_state *t)
{
    mvr_scene *s = scene_with_lights(t, 1, 2);
    mvr_shadow_desc d = mvr_shadow_desc_resolve(&(mvr_shadow_desc){0});
    char why[128];
    /* the spot is on layer 2: view 1 only */
    mvr_view_set *vs = two_views(t, 1, 3);
    mvr_frame f = {0};
    CHECK(t, mvr_frame_build(&f, s, vs->origin, 144, 64, NULL, why, sizeof why) == MVR_OK);
    mvr_shadow_plan plan;
    mvr_shadow_plan_build(&plan, &f, vs, 64, 64, true, &d);
    CHECK_EQ_INT(t, plan.layer_count, 4);
    CHECK_EQ_INT(t, plan.max_view_layers, 4);
    CHECK(t, plan.masked);
    CHECK_EQ_INT(t, mvr_view_light_mask(&f, &vs->views[0]), 1u);
    CHECK_EQ_INT(t, mvr_view_light_mask(&f, &vs->views[1]), 3u);
    mvr_view_set_destroy(vs);
    /* no view on layer 2: the spot takes no layer */
    vs = two_views(t, 1, 1);
    mvr_shadow_plan_build(&plan, &f, vs, 64, 64, true, &d);
    CHECK_EQ_INT(t, plan.layer_count, 3);
    CHECK_EQ_INT(t, plan.light_first[1], -1);
    CHECK_EQ_INT(t, plan.light_layers[1], 0);
    /* a disabled view does not count */
    mvr_view_desc v1 = vs->views[1];
    v1.light_layers = 2;
    v1.disabled = true;
    CHECK(t, mvr_view_set_update(vs, 1, &v1) == MVR_OK);
    mvr_shadow_plan_build(&plan, &f, vs, 64, 64, true, &d);
    CHECK_EQ_INT(t, plan.layer_count, 3);
    /* shadows off: nothing */
    d.mode = MVR_SHADOWS_OFF;
    mvr_shadow_plan_build(&plan, &f, vs, 64, 64, true, &d);
    CHECK_EQ_INT(t, plan.layer_count, 0);
    mvr_frame_free(&f);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
}

static void the_layer_budget_is_kept(mvr_test_state *t)
{
    /* six suns of 3 cascades want 18 layers: five fit in 16, with the spot */
    mvr_scene *s = scene_with_lights(t, 6, 0);
    mvr_view_set *vs = two_views(t, 0, 0);
    mvr_frame f = {0};
    char why[128];
    CHECK(t, mvr_frame_build(&f, s, vs->origin, 144, 64, NULL, why, sizeof why) == MVR_OK);
    mvr_shadow_desc d = mvr_shadow_desc_resolve(&(mvr_shadow_desc){0});
    mvr_shadow_plan plan;
    mvr_shadow_plan_build(&plan, &f, vs, 64, 64, true, &d);
    CHECK_EQ_INT(t, plan.layer_count, 16);
    CHECK_EQ_INT(t, plan.lights_unshadowed, 1);
    CHECK_EQ_INT(t, plan.light_first[5], -1);
    CHECK_EQ_INT(t, plan.light_first[6], 15); /* the spot still fits */
    /* one cascade each: all seven lights */
    d.cascades = 1;
    mvr_shadow_plan_build(&plan, &f, vs, 64, 64, true, &d);
    CHECK_EQ_INT(t, plan.layer_count, 7);
    CHECK_EQ_INT(t, plan.lights_unshadowed, 0);
    mvr_frame_free(&f);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(cascades_hold_what_the_views_see), TEST(layers_go_to_lights_some_view_uses),
              TEST(the_layer_budget_is_kept))
