/* core: the projections, transforms and precision rules of the frame model. */
#include <math.h>

#include "mvr_math.h"
#include "mvr_test.h"
#include "view_set.h"

static void project(const mvr_dmat4 *p, double z_eye, double *ndc_z)
{
    double z = p->m[10] * z_eye + p->m[14];
    double w = p->m[11] * z_eye + p->m[15];
    *ndc_z = z / w;
}

static void reversed_z_maps_near_to_one_far_to_zero(mvr_test_state *t)
{
    mvr_dmat4 p = mvr_dmat4_perspective(1.0, 1.5, 0.1, 100.0, true);
    double z;
    project(&p, -0.1, &z);
    CHECK_MSG(t, fabs(z - 1.0) < 1e-12, "near -> %g", z);
    project(&p, -100.0, &z);
    CHECK_MSG(t, fabs(z) < 1e-12, "far -> %g", z);
    /* infinite far: built directly, finite everywhere, -> 0 at infinity */
    mvr_dmat4 inf = mvr_dmat4_perspective(1.0, 1.5, 0.1, 0.0, true);
    for (int i = 0; i < 16; ++i)
        CHECK(t, isfinite(inf.m[i]));
    project(&inf, -0.1, &z);
    CHECK(t, fabs(z - 1.0) < 1e-12);
    project(&inf, -1e30, &z);
    CHECK(t, z >= 0.0 && z < 1e-30);
    /* standard GL: near -> -1, far -> +1 */
    mvr_dmat4 s = mvr_dmat4_perspective(1.0, 1.5, 0.1, 100.0, false);
    project(&s, -0.1, &z);
    CHECK(t, fabs(z + 1.0) < 1e-9);
    project(&s, -100.0, &z);
    CHECK(t, fabs(z - 1.0) < 1e-9);
    /* an explicit GL matrix converted to reversed-Z agrees with the direct one */
    mvr_dmat4 conv = mvr_dmat4_gl_to_reversed(&s);
    mvr_dmat4 direct = mvr_dmat4_perspective(1.0, 1.5, 0.1, 100.0, true);
    for (double ze = -0.1; ze > -100.0; ze *= 2.0) {
        double a, b;
        project(&conv, ze, &a);
        project(&direct, ze, &b);
        CHECK_MSG(t, fabs(a - b) < 1e-9, "z_eye %g: %g vs %g", ze, a, b);
    }
    /* orthographic reversed */
    mvr_dmat4 o = mvr_dmat4_orthographic(2, 1, 1, 11, true);
    project(&o, -1.0, &z);
    CHECK(t, fabs(z - 1.0) < 1e-12);
    project(&o, -11.0, &z);
    CHECK(t, fabs(z) < 1e-12);
}

static void asymmetric_frustum_edges(mvr_test_state *t)
{
    /* OpenXR-style angles: a point on the left edge maps to x_ndc = -1 */
    double l = -0.9, r = 0.5, d = -0.6, u = 0.7;
    mvr_dmat4 p = mvr_dmat4_frustum(l, r, d, u, 0.1, 0.0, true);
    double ze = -3.0;
    double xs[2] = {tan(l) * -ze, tan(r) * -ze}, ys[2] = {tan(d) * -ze, tan(u) * -ze};
    for (int i = 0; i < 2; ++i) {
        double x = (p.m[0] * xs[i] + p.m[8] * ze) / -ze;
        double y = (p.m[5] * ys[i] + p.m[9] * ze) / -ze;
        CHECK_MSG(t, fabs(x - (i ? 1.0 : -1.0)) < 1e-12, "x edge %d -> %g", i, x);
        CHECK_MSG(t, fabs(y - (i ? 1.0 : -1.0)) < 1e-12, "y edge %d -> %g", i, y);
    }
}

static void normal_matrix_is_inverse_transpose(mvr_test_state *t)
{
    mvr_dquat q = mvr_dquat_from_axis_angle(mvr_dvec3_make(1, 2, 3), 0.7);
    mvr_dmat4 m = mvr_dmat4_trs(mvr_dvec3_make(5, -2, 1), q, mvr_dvec3_make(2, 0.5, -3));
    mvr_dmat4 inv;
    CHECK(t, mvr_dmat4_invert(&m, &inv));
    mvr_dmat4 n = mvr_dmat4_normal_matrix(&m);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            CHECK_MSG(t, fabs(n.m[c * 4 + r] - inv.m[r * 4 + c]) < 1e-12, "normal matrix [%d][%d]", c, r);
    CHECK(t, mvr_dmat4_det3(&m) < 0); /* one negative scale mirrors */
    /* zero scale: finite (cofactors), no NaN */
    mvr_dmat4 z = mvr_dmat4_trs(mvr_dvec3_make(0, 0, 0), q, mvr_dvec3_make(1, 0, 1));
    mvr_dmat4 nz = mvr_dmat4_normal_matrix(&z);
    for (int i = 0; i < 16; ++i)
        CHECK(t, isfinite(nz.m[i]));
    /* a non-normalized quaternion is normalized */
    mvr_dquat big = {0, 0, 2, 2};
    mvr_dmat4 r = mvr_dmat4_trs(mvr_dvec3_make(0, 0, 0), big, mvr_dvec3_make(1, 1, 1));
    CHECK(t, fabs(mvr_dmat4_det3(&r) - 1.0) < 1e-12);
}

static void relative_transforms_keep_precision_far_away(mvr_test_state *t)
{
    /* a model 1e7 units out, seen from a view 5 m from it: relative to the
     * view's origin the GPU gets small, exact floats */
    mvr_dvec3 far = mvr_dvec3_make(1e7 + 0.123456, 2e7 - 0.5, -3e7 + 0.25);
    mvr_dmat4 m = mvr_dmat4_trs(far, mvr_dquat_normalize((mvr_dquat){0, 0, 0, 1}), mvr_dvec3_make(1, 1, 1));
    mvr_dvec3 origin = mvr_dvec3_add(far, mvr_dvec3_make(0, 0, 5));
    mvr_mat4f f = mvr_dmat4_relative_to(&m, origin);
    CHECK(t, f.m[12] == 0.0f && f.m[13] == 0.0f && f.m[14] == -5.0f);
    /* the naive way (narrow first, subtract on the GPU) loses the offset:
     * floats are 2 apart at 3e7 */
    float naive_z = (float)far.z - (float)origin.z;
    CHECK_MSG(t, naive_z != -5.0f, "naive float subtraction would have been exact (%g)", (double)naive_z);
}

static void look_rotation_looks_along_minus_z(mvr_test_state *t)
{
    mvr_dvec3 fwd = mvr_dvec3_make(1, -1, -2);
    mvr_dquat q = mvr_dquat_look_rotation(fwd, mvr_dvec3_make(0, 1, 0));
    mvr_dvec3 z = mvr_dquat_rotate(q, mvr_dvec3_make(0, 0, -1));
    mvr_dvec3 f = mvr_dvec3_normalize(fwd, fwd);
    CHECK(t, fabs(z.x - f.x) < 1e-12 && fabs(z.y - f.y) < 1e-12 && fabs(z.z - f.z) < 1e-12);
    mvr_dvec3 up = mvr_dquat_rotate(q, mvr_dvec3_make(0, 1, 0));
    CHECK(t, up.y > 0);
    /* the view matrix takes the eye to the origin and forward to -Z */
    mvr_dmat4 v = mvr_dmat4_view(mvr_dvec3_make(3, 4, 5), q);
    mvr_dvec3 e = mvr_dmat4_transform_point(&v, mvr_dvec3_make(3, 4, 5));
    CHECK(t, mvr_dvec3_length(e) < 1e-12);
    mvr_dvec3 ahead = mvr_dmat4_transform_point(&v, mvr_dvec3_add(mvr_dvec3_make(3, 4, 5), f));
    CHECK(t, fabs(ahead.z + 1.0) < 1e-12 && fabs(ahead.x) < 1e-12);
    /* straight up with up = +Y does not produce NaN */
    mvr_dquat qu = mvr_dquat_look_rotation(mvr_dvec3_make(0, 1, 0), mvr_dvec3_make(0, 1, 0));
    CHECK(t, isfinite(qu.x) && isfinite(qu.w));
}

MVR_TEST_MAIN(TEST(reversed_z_maps_near_to_one_far_to_zero), TEST(asymmetric_frustum_edges),
              TEST(normal_matrix_is_inverse_transpose), TEST(relative_transforms_keep_precision_far_away),
              TEST(look_rotation_looks_along_minus_z))
