/* core: stereo framing scaled to the scene (mvr_view_set_frame_scene,
 * mvr_stereo_default_ipd). A 2 cm model and a 100 m scene get eyes 1/30 of
 * the viewing distance apart, so each eye sees the whole bounding sphere;
 * with a fixed 0.064 a 2 cm model left one eye's frame. Eyes on a file's
 * camera (mvr_view_set_from_camera) and the default exposure of a scene
 * (mvr_render_desc_choose_exposure). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mvr_test.h"
#include "view_set.h"

/* A scene whose bounding sphere has radius r around (5r, 0, 0): an
 * axis-aligned box given by two triangles' corners. */
static mvr_scene *scene_of_radius(double r)
{
    mvr_scene *s = NULL;
    if (mvr_scene_create(NULL, &s, NULL) != MVR_OK)
        return NULL;
    float e = (float)(r / sqrt(3.0));
    const float pos[18] = {-e, -e, -e, e, -e, -e, e, e, -e, -e, -e, e, e, e, e, -e, e, e};
    mvr_primitive_desc p = {0};
    p.vertex_count = 6;
    p.positions = pos;
    mvr_mesh_desc m = {.primitives = &p, .primitive_count = 1, .name = "box"};
    mvr_mesh_id mesh;
    mvr_node_desc n = {0};
    n.translation[0] = 5.0 * r;
    mvr_node_id node;
    if (mvr_scene_add_mesh(s, &m, &mesh) != MVR_OK || (n.mesh = mesh, mvr_scene_add_node(s, &n, &node)) != MVR_OK) {
        mvr_scene_destroy(s);
        return NULL;
    }
    return s;
}

/* Whether a sphere (centre c, radius r) lies inside a view's frustum; views
 * from the stereo layout look down -Z with parallel axes. */
static bool sphere_inside(const mvr_view_desc *v, const double c[3], double r, double aspect)
{
    double dx = c[0] - v->position[0], dy = c[1] - v->position[1], dz = v->position[2] - c[2];
    double d = sqrt(dx * dx + dy * dy + dz * dz), margin = asin(r / d);
    double half_y = v->projection.yfov * 0.5, half_x = atan(tan(half_y) * aspect);
    return atan(fabs(dx) / dz) + margin <= half_x && atan(fabs(dy) / dz) + margin <= half_y;
}

static void eyes_scale_with_the_scene(mvr_test_state *t)
{
    const double radii[] = {0.01, 1.0, 100.0};
    const double aspects[] = {1.0, 16.0 / 9.0};
    for (int k = 0; k < 3; ++k) {
        for (int a = 0; a < 2; ++a) {
            double r = radii[k];
            mvr_scene *s = scene_of_radius(r);
            CHECK(t, s != NULL);
            if (!s)
                return;
            /* the sphere fit, level: the framing this test was written for */
            mvr_framing_desc fd = {.layout = MVR_LAYOUT_STEREO, .views = 2, .aspect = aspects[a], .level = true,
                                   .fit_sphere = true};
            mvr_view_set *vs = NULL;
            mvr_error err;
            CHECK_MSG(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_OK, "%s", err.message);
            if (vs) {
                const mvr_view_desc *v = vs->views;
                double c[3] = {5.0 * r, 0, 0};
                double sep = fabs(v[1].position[0] - v[0].position[0]);
                double dist = v[0].position[2] - c[2];
                CHECK_MSG(t, fabs(sep / dist - 1.0 / 30.0) < 1e-9, "r %g: eyes %g apart at %g", r, sep, dist);
                for (int e = 0; e < 2; ++e)
                    CHECK_MSG(t, sphere_inside(&v[e], c, r, aspects[a]), "r %g aspect %g: eye %d loses the scene", r,
                              aspects[a], e);
                mvr_view_set_destroy(vs);
            }
            /* a fixed human IPD is kept when asked for; on the 2 cm model it
             * moves the eyes out of frame (what the default now avoids) */
            fd.ipd = 0.064;
            CHECK(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_OK);
            if (vs) {
                double c[3] = {5.0 * r, 0, 0};
                CHECK(t, fabs(fabs(vs->views[1].position[0] - vs->views[0].position[0]) - 0.064) < 1e-12);
                if (r == 0.01)
                    CHECK(t, !sphere_inside(&vs->views[0], c, r, aspects[a]));
                mvr_view_set_destroy(vs);
            }
            mvr_scene_destroy(s);
        }
    }
    CHECK(t, fabs(mvr_stereo_default_ipd(1.92) - 0.064) < 1e-12);
    CHECK(t, mvr_stereo_default_ipd(0.0) == 0.064 && mvr_stereo_default_ipd(NAN) == 0.064);
}

/* A camera node at pos turned by yaw radians about +Y (looking along
 * (-sin yaw, 0, -cos yaw)); its x axis is (cos yaw, 0, -sin yaw). */
static mvr_node_id add_camera(mvr_scene *s, const double pos[3], double yaw)
{
    mvr_projection p = {0};
    p.yfov = 0.7;
    p.znear = 0.01;
    mvr_camera_id cam;
    mvr_node_desc n = {0};
    memcpy(n.translation, pos, sizeof n.translation);
    n.rotation[1] = sin(yaw * 0.5);
    n.rotation[3] = cos(yaw * 0.5);
    mvr_node_id node = {0};
    if (mvr_scene_add_camera(s, &p, &cam) == MVR_OK) {
        n.camera = cam;
        mvr_scene_add_node(s, &n, &node);
    }
    return node;
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static void eyes_on_a_camera(mvr_test_state *t)
{
    const double radii[] = {0.01, 1.0, 100.0};
    for (int k = 0; k < 3; ++k) {
        double r = radii[k];
        mvr_scene *s = scene_of_radius(r); /* centred on (5r, 0, 0) */
        CHECK(t, s != NULL);
        if (!s)
            return;
        /* 7r from the centre, turned 30 degrees: not along an axis */
        double yaw = 0.5235987755982988, pos[3] = {5.0 * r + 7.0 * r * sin(yaw), 0.0, 7.0 * r * cos(yaw)};
        const double centre[3] = {5.0 * r, 0, 0};
        mvr_node_id node = add_camera(s, pos, yaw);
        CHECK(t, node.id != 0);
        mvr_view_desc cam;
        CHECK(t, mvr_scene_camera_view(s, node, &cam) == MVR_OK);
        const double x_axis[3] = {cos(yaw), 0, -sin(yaw)};
        for (uint32_t n = 1; n <= 4; ++n) {
            for (int explicit_ipd = 0; explicit_ipd < 2; ++explicit_ipd) {
                double ipd = explicit_ipd ? 0.25 * r : 0.0;
                /* the default: 1/30 of the camera's distance to the scene's centre */
                double want = explicit_ipd ? ipd : dist3(pos, centre) / 30.0;
                mvr_view_set *vs = NULL;
                mvr_error err;
                CHECK_MSG(t, mvr_view_set_from_camera(s, node, n, ipd, &vs, &err) == MVR_OK, "%s", err.message);
                if (!vs)
                    continue;
                CHECK(t, vs->count == n);
                double mean[3] = {0, 0, 0};
                for (uint32_t i = 0; i < vs->count; ++i) {
                    const mvr_view_desc *v = &vs->views[i];
                    /* parallel: the camera's own orientation and projection */
                    CHECK(t, memcmp(v->orientation, cam.orientation, sizeof cam.orientation) == 0);
                    CHECK(t, v->projection.type == cam.projection.type && v->projection.yfov == 0.7 &&
                                 v->projection.znear == 0.01 && v->projection.aspect == cam.projection.aspect);
                    for (int c = 0; c < 3; ++c)
                        mean[c] += v->position[c] / n;
                    if (i == 0)
                        continue;
                    /* the step from the previous eye: ipd along the camera's x axis */
                    const double *a = vs->views[i - 1].position, *b = v->position;
                    for (int c = 0; c < 3; ++c)
                        CHECK_MSG(t, fabs(b[c] - a[c] - x_axis[c] * want) <= 1e-12 * (r + 1), "r %g n %u eye %u axis %d",
                                  r, n, i, c);
                }
                /* centred on the camera */
                CHECK_MSG(t, dist3(mean, pos) <= 1e-12 * (r + 1), "r %g n %u: eyes centred %g from the camera", r, n,
                          dist3(mean, pos));
                if (n == 1)
                    CHECK(t, memcmp(vs->views[0].position, cam.position, sizeof cam.position) == 0);
                mvr_view_set_destroy(vs);
            }
        }
        /* 0 views: a stereo pair */
        mvr_view_set *vs = NULL;
        CHECK(t, mvr_view_set_from_camera(s, node, 0, 0.0, &vs, NULL) == MVR_OK && vs && vs->count == 2);
        mvr_view_set_destroy(vs);
        /* refused, each with a message naming what is wrong */
        mvr_error err;
        vs = NULL;
        mvr_node_id mesh_node = {1};
        CHECK(t, mvr_view_set_from_camera(s, mesh_node, 2, 0.0, &vs, &err) == MVR_ERROR_INVALID_ARGUMENT && !vs);
        CHECK_MSG(t, strstr(err.message, "not a camera node") != NULL, "%s", err.message);
        const double bad[] = {-1.0, NAN, INFINITY};
        for (int b = 0; b < 3; ++b) {
            CHECK(t, mvr_view_set_from_camera(s, node, 2, bad[b], &vs, &err) == MVR_ERROR_INVALID_ARGUMENT && !vs);
            CHECK_MSG(t, strstr(err.message, "ipd") != NULL, "%s", err.message);
        }
        CHECK(t, mvr_view_set_from_camera(s, node, 1025, 0.0, &vs, &err) == MVR_ERROR_INVALID_ARGUMENT && !vs);
        CHECK(t, mvr_view_set_from_camera(NULL, node, 2, 0.0, &vs, &err) == MVR_ERROR_INVALID_ARGUMENT);
        mvr_scene_destroy(s);
    }
}

/* A directional light of the given lux in an otherwise empty scene. */
static mvr_scene *scene_with_sun(float lux)
{
    mvr_scene *s = NULL;
    if (mvr_scene_create(NULL, &s, NULL) != MVR_OK)
        return NULL;
    mvr_light_desc ld = {0};
    ld.type = MVR_LIGHT_DIRECTIONAL;
    ld.intensity = lux;
    mvr_light_id light;
    mvr_node_desc n = {0};
    mvr_node_id node;
    if (mvr_scene_add_light(s, &ld, &light) != MVR_OK || (n.light = light, mvr_scene_add_node(s, &n, &node)) != MVR_OK) {
        mvr_scene_destroy(s);
        return NULL;
    }
    return s;
}

static void exposure_follows_the_light_units(mvr_test_state *t)
{
    mvr_scene *sun = scene_with_sun(2049.0f), *lamp = scene_with_sun(3.0f);
    CHECK(t, sun && lamp);
    if (!sun || !lamp) {
        mvr_scene_destroy(sun);
        mvr_scene_destroy(lamp);
        return;
    }
    mvr_render_desc d;
    memset(&d, 0, sizeof d);
    d.exposure = 2.0f;
    mvr_render_desc_choose_exposure(sun, &d);
    CHECK(t, d.exposure_mode == MVR_EXPOSURE_AUTO && d.tone_map == MVR_TONE_MAP_KHR_PBR_NEUTRAL);
    mvr_render_desc_choose_exposure(lamp, &d);
    CHECK(t, d.exposure_mode == MVR_EXPOSURE_LINEAR && d.tone_map == MVR_TONE_MAP_NONE);
    CHECK(t, d.exposure == 2.0f); /* the multiplier is the caller's */
    /* under an environment: highlights rolled off, the exposure still linear */
    mvr_environment *env = NULL;
    CHECK(t, mvr_environment_create(NULL, &env, NULL) == MVR_OK);
    d.environment = env;
    mvr_render_desc_choose_exposure(lamp, &d);
    CHECK(t, d.exposure_mode == MVR_EXPOSURE_LINEAR && d.tone_map == MVR_TONE_MAP_KHR_PBR_NEUTRAL);
    mvr_render_desc_choose_exposure(sun, &d);
    CHECK(t, d.exposure_mode == MVR_EXPOSURE_AUTO && d.tone_map == MVR_TONE_MAP_KHR_PBR_NEUTRAL);
    mvr_environment_destroy(env);
    mvr_render_desc_choose_exposure(NULL, NULL); /* no crash */
    mvr_scene_destroy(sun);
    mvr_scene_destroy(lamp);
}

/* The view's forward axis: -Z turned by its orientation. */
static void forward_of(const mvr_view_desc *v, double f[3])
{
    double x = v->orientation[0], y = v->orientation[1], z = v->orientation[2], w = v->orientation[3];
    f[0] = -(2.0 * (x * z + w * y));
    f[1] = -(2.0 * (y * z - w * x));
    f[2] = -(1.0 - 2.0 * (x * x + y * y));
}

/* Every view of a set is dist from c and looks straight at it. */
static void views_look_at(mvr_test_state *t, const mvr_view_set *vs, const double c[3], double *dist)
{
    *dist = dist3(vs->views[0].position, c);
    for (uint32_t i = 0; i < vs->count; ++i) {
        const mvr_view_desc *v = &vs->views[i];
        double d = dist3(v->position, c), f[3];
        forward_of(v, f);
        double to_c = ((c[0] - v->position[0]) * f[0] + (c[1] - v->position[1]) * f[1] + (c[2] - v->position[2]) * f[2]) / d;
        CHECK_MSG(t, fabs(d - *dist) < 1e-9 * *dist && to_c > 1.0 - 1e-9, "view %u: %g from the centre, cos %g", i, d,
                  to_c);
    }
}

/* sphere: 200 views, each its own direction from the centre, spread evenly
 * (their mean direction near 0, neighbours no closer than half the mean
 * spacing sqrt(4 pi / n)), every one looking at the centre, the poles too.
 * orbit: 3 rings of 8 at -15, 22.5 and 60 degrees, evenly around, the
 * middle ring staggered half a step; 2 rings of 5 views share 3 and 2;
 * more rings than views, or elevations outside (-90, 90) degrees, refused. */
static void sphere_and_orbit_layouts(mvr_test_state *t)
{
    mvr_scene *s = scene_of_radius(1.0);
    CHECK(t, s != NULL);
    if (!s)
        return;
    const double c[3] = {5.0, 0, 0}, PI_ = 3.14159265358979323846;
    /* the sphere fit: every view as far from the centre */
    mvr_framing_desc fd = {.layout = MVR_LAYOUT_SPHERE, .views = 200, .fit_sphere = true};
    mvr_view_set *vs = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_OK, "%s", err.message);
    if (vs) {
        double dist;
        CHECK_EQ_INT(t, vs->count, 200);
        views_look_at(t, vs, c, &dist);
        double mean[3] = {0, 0, 0}, closest = 10.0;
        for (uint32_t i = 0; i < vs->count; ++i) {
            double a[3];
            for (int k = 0; k < 3; ++k) {
                a[k] = (vs->views[i].position[k] - c[k]) / dist;
                mean[k] += a[k] / vs->count;
            }
            for (uint32_t j = i + 1; j < vs->count; ++j) {
                double b[3];
                for (int k = 0; k < 3; ++k)
                    b[k] = (vs->views[j].position[k] - c[k]) / dist;
                closest = fmin(closest, acos(fmin(a[0] * b[0] + a[1] * b[1] + a[2] * b[2], 1.0)));
            }
        }
        double spacing = sqrt(4.0 * PI_ / 200.0);
        printf("  sphere of 200: closest pair %.3f rad (mean spacing %.3f), mean direction |%.4f|\n", closest, spacing,
               sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]));
        CHECK(t, closest > 0.5 * spacing);
        CHECK(t, sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]) < 0.01);
        mvr_view_set_destroy(vs);
    }
    fd = (mvr_framing_desc){.layout = MVR_LAYOUT_ORBIT, .fit_sphere = true};
    CHECK_MSG(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_OK, "%s", err.message);
    if (vs) {
        double dist;
        CHECK_EQ_INT(t, vs->count, 24);
        views_look_at(t, vs, c, &dist);
        const double el[3] = {-15.0, 22.5, 60.0};
        for (uint32_t i = 0; i < vs->count; ++i) {
            const double *p = vs->views[i].position;
            double e = asin((p[1] - c[1]) / dist) * 180.0 / PI_;
            double a = atan2(p[0] - c[0], p[2] - c[2]) * 180.0 / PI_;
            double expect_a = 45.0 * ((double)(i % 8) + 0.5 * (double)((i / 8) % 2));
            double da = fmod(a - expect_a + 720.0, 360.0);
            CHECK_MSG(t, fabs(e - el[i / 8]) < 1e-9 && (da < 1e-9 || da > 360.0 - 1e-9),
                      "view %u: elevation %g, azimuth %g (expected %g, %g)", i, e, a, el[i / 8], expect_a);
        }
        mvr_view_set_destroy(vs);
    }
    fd = (mvr_framing_desc){.layout = MVR_LAYOUT_ORBIT, .views = 5, .rows = 2, .fit_sphere = true};
    CHECK(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_OK);
    if (vs) {
        double y0 = vs->views[0].position[1];
        CHECK(t, vs->views[2].position[1] == y0 && vs->views[3].position[1] > y0 && vs->views[4].position[1] > y0);
        mvr_view_set_destroy(vs);
    }
    fd.rows = 6;
    CHECK(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_ERROR_INVALID_ARGUMENT && !vs);
    CHECK(t, strstr(err.message, "6 orbit rings for 5 views") != NULL);
    fd.rows = 2;
    fd.elevation_max = 2.0;
    CHECK(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_ERROR_INVALID_ARGUMENT && !vs);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(eyes_scale_with_the_scene), TEST(eyes_on_a_camera), TEST(exposure_follows_the_light_units),
              TEST(sphere_and_orbit_layouts))
