/* core: camera metadata of views (mvr_view_set_get_camera): random points
 * in front of a view land on the same pixel through its intrinsics and
 * extrinsics (the OpenCV / COLMAP pinhole, in double) as through the
 * view-projection the GPU is given (the OpenGL path), within 1e-6 pixel, for
 * a symmetric perspective, a stretched aspect, an off-axis frustum on
 * a sub-viewport and an explicit matrix; camera_to_world inverts
 * world_to_camera; an orthographic view has no pinhole; bad arguments are
 * refused. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mvr_test.h"
#include "view_set.h"

static double mul_point(const double m[16], const double p[3], int row)
{
    return m[0 * 4 + row] * p[0] + m[1 * 4 + row] * p[1] + m[2 * 4 + row] * p[2] + m[3 * 4 + row];
}

static uint32_t lcg = 12345u;
static double rnd(void)
{
    lcg = lcg * 1664525u + 1013904223u;
    return (double)(lcg >> 8) / (double)(1u << 24);
}

static void check_view(mvr_test_state *t, const mvr_view_set *vs, uint32_t index, uint32_t w, uint32_t h)
{
    mvr_view_camera cam;
    CHECK(t, mvr_view_set_get_camera(vs, index, w, h, &cam) == MVR_OK);
    CHECK(t, cam.perspective);
    const mvr_view_desc *v = &vs->views[index];
    mvr_viewport vp = mvr_view_viewport(v, w, h);
    mvr_dmat4 vpm = mvr_view_relative_view_proj(v, mvr_dvec3_make(0, 0, 0), vp, false);
    double worst = 0, inv_err = 0;
    for (int k = 0; k < 200; ++k) {
        /* a point in front of the camera: camera space, then world */
        double pc[3] = {(rnd() - 0.5) * 4.0, (rnd() - 0.5) * 4.0, -(0.5 + rnd() * 20.0)}, p[3];
        for (int r = 0; r < 3; ++r)
            p[r] = mul_point(cam.camera_to_world, pc, r);
        /* the OpenGL path */
        double clip[4];
        for (int r = 0; r < 4; ++r)
            clip[r] = vpm.m[0 * 4 + r] * p[0] + vpm.m[1 * 4 + r] * p[1] + vpm.m[2 * 4 + r] * p[2] + vpm.m[3 * 4 + r];
        double u_gl = (clip[0] / clip[3] + 1.0) * 0.5 * cam.width;
        double v_gl = (1.0 - clip[1] / clip[3]) * 0.5 * cam.height;
        /* the pinhole path: world -> OpenGL camera -> OpenCV camera */
        double x = mul_point(cam.world_to_camera, p, 0), y = mul_point(cam.world_to_camera, p, 1),
               z = mul_point(cam.world_to_camera, p, 2);
        double u = cam.fx * x / -z + cam.cx, vv = cam.fy * -y / -z + cam.cy;
        worst = fmax(worst, fmax(fabs(u - u_gl), fabs(vv - v_gl)));
        inv_err = fmax(inv_err, fmax(fabs(x - pc[0]), fmax(fabs(y - pc[1]), fabs(z - pc[2]))));
    }
    CHECK_MSG(t, worst < 1e-6, "view %u: the pinhole and the GL disagree by %g pixel", index, worst);
    CHECK_MSG(t, inv_err < 1e-9, "view %u: camera_to_world is not world_to_camera's inverse (%g)", index, inv_err);
}

static void pinhole_matches_the_gpu(mvr_test_state *t)
{
    mvr_view_desc v[4];
    memset(v, 0, sizeof v);
    double eye[3] = {3, 1.5, 7}, at[3] = {0, 0.2, 0}, up[3] = {0, 1, 0};
    for (int i = 0; i < 4; ++i)
        mvr_view_look_at(&v[i], eye, at, up);
    v[0].projection.yfov = 0.8; /* symmetric, the viewport's aspect */
    v[1].projection.type = MVR_PROJECTION_FRUSTUM;
    v[1].projection.angle_left = -0.3;
    v[1].projection.angle_right = 0.6;
    v[1].projection.angle_down = -0.5;
    v[1].projection.angle_up = 0.2;
    v[1].viewport = (mvr_viewport){10, 20, 200, 100};
    v[2].projection.type = MVR_PROJECTION_PERSPECTIVE;
    v[2].projection.yfov = 1.2;
    v[2].projection.aspect = 2.0; /* a stretched aspect */
    v[2].projection.zfar = 50;
    v[3].projection.type = MVR_PROJECTION_MATRIX;
    {
        /* an explicit off-axis GL frustum: l -0.2, r 0.1, b -0.1, t 0.15, n 0.1, f 100 */
        double l = -0.2, r = 0.1, b = -0.1, tp = 0.15, n = 0.1, f = 100;
        double m[16] = {2 * n / (r - l), 0, 0, 0, 0, 2 * n / (tp - b), 0, 0, (r + l) / (r - l), (tp + b) / (tp - b),
                        -(f + n) / (f - n), -1, 0, 0, -2 * f * n / (f - n), 0};
        memcpy(v[3].projection.matrix, m, sizeof m);
    }
    mvr_view_set_desc d = {.view_count = 4, .views = v};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_create(&d, &vs, NULL) == MVR_OK);
    for (uint32_t i = 0; vs && i < 4; ++i)
        check_view(t, vs, i, 320, 240);
    if (vs) {
        mvr_view_camera cam;
        CHECK(t, mvr_view_set_get_camera(vs, 1, 320, 240, &cam) == MVR_OK && cam.width == 200 && cam.height == 100);
        /* a symmetric frustum puts the principal point at the viewport's centre */
        CHECK(t, mvr_view_set_get_camera(vs, 0, 320, 240, &cam) == MVR_OK && fabs(cam.cx - 160.0) < 1e-9 &&
                     fabs(cam.cy - 120.0) < 1e-9 && fabs(cam.fx - cam.fy) < 1e-9);
        CHECK(t, mvr_view_set_get_camera(vs, 4, 320, 240, &cam) == MVR_ERROR_INVALID_ARGUMENT);
        CHECK(t, mvr_view_set_get_camera(vs, 0, 0, 240, &cam) == MVR_ERROR_INVALID_ARGUMENT);
        mvr_view_set_destroy(vs);
    }
    /* orthographic: no pinhole */
    v[0].projection = (mvr_projection){.type = MVR_PROJECTION_ORTHOGRAPHIC, .xmag = 2, .ymag = 2, .zfar = 10};
    d.view_count = 1;
    CHECK(t, mvr_view_set_create(&d, &vs, NULL) == MVR_OK);
    if (vs) {
        mvr_view_camera cam;
        CHECK(t, mvr_view_set_get_camera(vs, 0, 64, 64, &cam) == MVR_OK && !cam.perspective && cam.fx == 0.0);
        mvr_view_set_destroy(vs);
    }
}

/* The getters give back the views as given and the origin the GPU sees:
 * the centroid of the positions, or the one given (what a set of some of
 * its views needs to render them as the whole set does). */
static void views_and_origin_come_back(mvr_test_state *t)
{
    mvr_view_desc v[3] = {0};
    double eyes[3][3] = {{1, 2, 3}, {4, 5, 6}, {7, 8, 12}}, at[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    for (int i = 0; i < 3; ++i) {
        mvr_view_look_at(&v[i], eyes[i], at, up);
        v[i].projection = (mvr_projection){.type = MVR_PROJECTION_PERSPECTIVE, .yfov = 0.5 + 0.1 * i, .znear = 0.1};
        v[i].light_layers = 1u << i;
    }
    v[2].disabled = true;
    for (int given = 0; given < 2; ++given) {
        mvr_view_set_desc d = {.view_count = 3, .views = v, .origin_set = given, .origin = {100, -200, 1e7}};
        mvr_view_set *vs = NULL;
        CHECK(t, mvr_view_set_create(&d, &vs, NULL) == MVR_OK);
        if (!vs)
            continue;
        for (uint32_t i = 0; i < 3; ++i) {
            mvr_view_desc got;
            CHECK(t, mvr_view_set_get_view(vs, i, &got) == MVR_OK && memcmp(&got, &v[i], sizeof got) == 0);
        }
        mvr_view_desc got;
        CHECK(t, mvr_view_set_get_view(vs, 3, &got) == MVR_ERROR_INVALID_ARGUMENT);
        CHECK(t, mvr_view_set_get_view(vs, 0, NULL) == MVR_ERROR_INVALID_ARGUMENT);
        double o[3];
        CHECK(t, mvr_view_set_get_origin(vs, o) == MVR_OK);
        if (given)
            CHECK(t, o[0] == 100 && o[1] == -200 && o[2] == 1e7);
        else
            CHECK_MSG(t, fabs(o[0] - 4) < 1e-12 && fabs(o[1] - 5) < 1e-12 && fabs(o[2] - 7) < 1e-12,
                      "centroid %g %g %g", o[0], o[1], o[2]);
        CHECK(t, mvr_view_set_get_origin(NULL, o) == MVR_ERROR_INVALID_ARGUMENT);
        mvr_view_set_destroy(vs);
    }
}

MVR_TEST_MAIN(TEST(pinhole_matches_the_gpu), TEST(views_and_origin_come_back))
