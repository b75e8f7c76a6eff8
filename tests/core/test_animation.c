/* core: glTF 2.0 animation samplers (animation.h). Each interpolation mode
 * hits its keys exactly and matches the specification's formulas between
 * them; clamping outside the keys; slerp along the shorter arc; the cubic
 * Hermite spline of Appendix C reproduces a cubic; validation refuses what
 * cannot be sampled; clip time mapping with clamp and loop. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "animation.h"
#include "mvr_test.h"

#define PI 3.14159265358979323846

static mvr_anim_sampler make(const double *times, size_t count, const double *values, size_t value_count,
                             uint32_t components, mvr_interpolation interp, bool quat)
{
    mvr_anim_sampler s;
    memset(&s, 0, sizeof s);
    s.times = times;
    s.count = count;
    s.values = values;
    s.value_count = value_count;
    s.components = components;
    s.interpolation = interp;
    s.quaternion = quat;
    return s;
}

static double sample1(const mvr_anim_sampler *s, double t)
{
    double v = NAN;
    mvr_anim_sample(s, t, &v);
    return v;
}

static void step_values(mvr_test_state *t)
{
    const double times[] = {0.0, 1.0, 3.0};
    const double values[] = {10.0, 20.0, 40.0};
    mvr_anim_sampler s = make(times, 3, values, 3, 1, MVR_INTERPOLATION_STEP, false);
    char why[128] = "";
    CHECK_MSG(t, mvr_anim_sampler_valid(&s, why, sizeof why), "%s", why);
    CHECK(t, sample1(&s, 0.0) == 10.0);
    CHECK(t, sample1(&s, 0.999) == 10.0);
    CHECK(t, sample1(&s, 1.0) == 20.0);
    CHECK(t, sample1(&s, 2.5) == 20.0);
    CHECK(t, sample1(&s, 3.0) == 40.0);
    CHECK(t, sample1(&s, -5.0) == 10.0);
    CHECK(t, sample1(&s, 100.0) == 40.0);
}

static void linear_values_and_clamping(mvr_test_state *t)
{
    const double times[] = {0.0, 1.0, 3.0};
    /* two components */
    const double values[] = {10.0, -1.0, 20.0, -2.0, 40.0, 2.0};
    mvr_anim_sampler s = make(times, 3, values, 6, 2, MVR_INTERPOLATION_LINEAR, false);
    char why[128] = "";
    CHECK_MSG(t, mvr_anim_sampler_valid(&s, why, sizeof why), "%s", why);
    double v[2];
    mvr_anim_sample(&s, 1.0, v);
    CHECK(t, v[0] == 20.0 && v[1] == -2.0);
    mvr_anim_sample(&s, 0.25, v);
    CHECK_MSG(t, fabs(v[0] - 12.5) < 1e-12 && fabs(v[1] + 1.25) < 1e-12, "%g %g", v[0], v[1]);
    mvr_anim_sample(&s, 2.5, v);
    CHECK_MSG(t, fabs(v[0] - 35.0) < 1e-12 && fabs(v[1] - 1.0) < 1e-12, "%g %g", v[0], v[1]);
    mvr_anim_sample(&s, -1.0, v);
    CHECK(t, v[0] == 10.0 && v[1] == -1.0);
    mvr_anim_sample(&s, 3.0, v);
    CHECK(t, v[0] == 40.0 && v[1] == 2.0);
    mvr_anim_sample(&s, 1e9, v);
    CHECK(t, v[0] == 40.0 && v[1] == 2.0);
    mvr_anim_sample(&s, NAN, v);
    CHECK(t, v[0] == 10.0 && v[1] == -1.0);
}

static void single_key(mvr_test_state *t)
{
    const double times[] = {2.0};
    const double values[] = {7.0};
    const double cubic[] = {100.0, 7.0, -100.0};
    for (int m = 0; m < 3; ++m) {
        mvr_interpolation interp = (mvr_interpolation)m;
        bool is_cubic = interp == MVR_INTERPOLATION_CUBICSPLINE;
        mvr_anim_sampler s = make(times, 1, is_cubic ? cubic : values, is_cubic ? 3 : 1, 1, interp, false);
        char why[128] = "";
        CHECK_MSG(t, mvr_anim_sampler_valid(&s, why, sizeof why), "%s", why);
        CHECK(t, sample1(&s, 0.0) == 7.0);
        CHECK(t, sample1(&s, 2.0) == 7.0);
        CHECK(t, sample1(&s, 5.0) == 7.0);
    }
}

static void many_keys_binary_search(mvr_test_state *t)
{
    enum { N = 1000 };
    static double times[N], values[N];
    for (int i = 0; i < N; ++i) {
        times[i] = 0.5 * i + 0.001 * i * i;  /* uneven spacing */
        values[i] = (double)i;
    }
    CHECK_EQ_INT(t, mvr_anim_find_key(times, N, -1.0), 0);
    CHECK_EQ_INT(t, mvr_anim_find_key(times, N, times[N - 1]), N - 1);
    CHECK_EQ_INT(t, mvr_anim_find_key(times, N, times[N - 1] + 1.0), N - 1);
    int bad = 0;
    for (int i = 0; i + 1 < N; ++i) {
        if (mvr_anim_find_key(times, N, times[i]) != (size_t)i)
            bad++;
        double mid = 0.5 * (times[i] + times[i + 1]);
        if (mvr_anim_find_key(times, N, mid) != (size_t)i)
            bad++;
    }
    CHECK_EQ_INT(t, bad, 0);
    mvr_anim_sampler s = make(times, N, values, N, 1, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, mvr_anim_sampler_valid(&s, NULL, 0));
    double mid = 0.25 * times[600] + 0.75 * times[601];
    CHECK_MSG(t, fabs(sample1(&s, mid) - 600.75) < 1e-9, "%.17g", sample1(&s, mid));
}

static bool quat_near(const double *q, const double *e, double tol)
{
    for (int i = 0; i < 4; ++i)
        if (!(fabs(q[i] - e[i]) <= tol))
            return false;
    return true;
}

static void slerp_90_degrees_about_y(mvr_test_state *t)
{
    const double times[] = {0.0, 1.0};
    const double h = 0.25 * PI; /* half of 90 degrees */
    const double values[] = {0, 0, 0, 1, 0, sin(h), 0, cos(h)};
    mvr_anim_sampler s = make(times, 2, values, 8, 4, MVR_INTERPOLATION_LINEAR, true);
    char why[128] = "";
    CHECK_MSG(t, mvr_anim_sampler_valid(&s, why, sizeof why), "%s", why);
    double q[4];
    /* 45 degrees about Y: half angle 22.5 degrees */
    const double e45[4] = {0, sin(0.125 * PI), 0, cos(0.125 * PI)};
    mvr_anim_sample(&s, 0.5, q);
    CHECK_MSG(t, quat_near(q, e45, 1e-12), "%.17g %.17g %.17g %.17g", q[0], q[1], q[2], q[3]);
    /* a quarter of the way: 22.5 degrees, not the lerp's angle */
    const double e225[4] = {0, sin(0.0625 * PI), 0, cos(0.0625 * PI)};
    mvr_anim_sample(&s, 0.25, q);
    CHECK_MSG(t, quat_near(q, e225, 1e-12), "%.17g %.17g %.17g %.17g", q[0], q[1], q[2], q[3]);
    mvr_anim_sample(&s, 1.0, q);
    CHECK(t, quat_near(q, values + 4, 1e-15));
    mvr_anim_sample(&s, 0.0, q);
    CHECK(t, quat_near(q, values, 0.0));

    /* q1 = -q: the same rotation; the shorter arc still gives 45 degrees */
    const double neg[] = {0, 0, 0, 1, -0.0, -sin(h), -0.0, -cos(h)};
    mvr_anim_sampler sn = make(times, 2, neg, 8, 4, MVR_INTERPOLATION_LINEAR, true);
    mvr_anim_sample(&sn, 0.5, q);
    CHECK_MSG(t, quat_near(q, e45, 1e-12), "%.17g %.17g %.17g %.17g", q[0], q[1], q[2], q[3]);
    double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    CHECK(t, fabs(n - 1.0) < 1e-14);

    /* nearly parallel keys fall back to normalised lerp and stay unit length */
    const double tiny = 1e-9;
    const double close[] = {0, 0, 0, 1, 0, sin(tiny), 0, cos(tiny)};
    mvr_anim_sampler sc = make(times, 2, close, 8, 4, MVR_INTERPOLATION_LINEAR, true);
    mvr_anim_sample(&sc, 0.5, q);
    const double ec[4] = {0, sin(0.5 * tiny), 0, cos(0.5 * tiny)};
    CHECK_MSG(t, quat_near(q, ec, 1e-15), "%.17g %.17g", q[1], q[3]);
    /* small angles above the fallback keep slerp's precision */
    const double small = 1e-4;
    const double near[] = {0, 0, 0, 1, 0, sin(small), 0, cos(small)};
    mvr_anim_sampler sm = make(times, 2, near, 8, 4, MVR_INTERPOLATION_LINEAR, true);
    mvr_anim_sample(&sm, 0.3, q);
    const double es[4] = {0, sin(0.3 * small), 0, cos(0.3 * small)};
    CHECK_MSG(t, quat_near(q, es, 1e-15), "%.17g %.17g", q[1], q[3]);
}

/* f(x) = x^3 - 2x^2 + 0.5x + 1 and its derivative */
static double cubic_f(double x) { return ((x - 2.0) * x + 0.5) * x + 1.0; }
static double cubic_df(double x) { return (3.0 * x - 4.0) * x + 0.5; }

static void cubic_spline_reproduces_a_cubic(mvr_test_state *t)
{
    const double times[] = {0.0, 0.5, 2.0, 3.0};
    double values[12];
    for (int k = 0; k < 4; ++k) {
        values[3 * k + 0] = cubic_df(times[k]); /* in-tangent */
        values[3 * k + 1] = cubic_f(times[k]);
        values[3 * k + 2] = cubic_df(times[k]); /* out-tangent */
    }
    mvr_anim_sampler s = make(times, 4, values, 12, 1, MVR_INTERPOLATION_CUBICSPLINE, false);
    char why[128] = "";
    CHECK_MSG(t, mvr_anim_sampler_valid(&s, why, sizeof why), "%s", why);
    int bad = 0;
    for (int i = 0; i <= 60; ++i) {
        double x = 0.05 * i;
        double v = sample1(&s, x);
        if (!(fabs(v - cubic_f(x)) < 1e-12)) {
            printf("  x %g: %.17g != %.17g\n", x, v, cubic_f(x));
            bad++;
        }
    }
    CHECK_EQ_INT(t, bad, 0);
    for (int k = 0; k < 4; ++k)
        CHECK(t, sample1(&s, times[k]) == values[3 * k + 1]);
    /* clamped outside: the key's value, not its tangents */
    CHECK(t, sample1(&s, -1.0) == cubic_f(0.0));
    CHECK(t, sample1(&s, 4.0) == cubic_f(3.0));
}

static void cubic_spline_zero_tangents_is_smoothstep(mvr_test_state *t)
{
    const double times[] = {1.0, 3.0};
    /* two components: 0 -> 1 and 2 -> -2 */
    /* per key: in-tangent (2), value (2), out-tangent (2) */
    const double values[] = {0, 0, 0, 2, 0, 0, 0, 0, 1, -2, 0, 0};
    mvr_anim_sampler s = make(times, 2, values, 12, 2, MVR_INTERPOLATION_CUBICSPLINE, false);
    char why[128] = "";
    CHECK_MSG(t, mvr_anim_sampler_valid(&s, why, sizeof why), "%s", why);
    int bad = 0;
    for (int i = 0; i <= 20; ++i) {
        double u = i / 20.0, ease = u * u * (3.0 - 2.0 * u);
        double v[2];
        mvr_anim_sample(&s, 1.0 + 2.0 * u, v);
        if (!(fabs(v[0] - ease) < 1e-12 && fabs(v[1] - (2.0 - 4.0 * ease)) < 1e-12))
            bad++;
    }
    CHECK_EQ_INT(t, bad, 0);
    double v[2];
    mvr_anim_sample(&s, 2.0, v);
    CHECK(t, fabs(v[0] - 0.5) < 1e-15 && fabs(v[1]) < 1e-15);
}

static void cubic_spline_quaternion_is_normalised(mvr_test_state *t)
{
    const double times[] = {0.0, 1.0};
    const double h = 0.25 * PI;
    const double values[] = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0,
                             0, 0, 0, 0, 0, sin(h), 0, cos(h), 0, 0, 0, 0};
    mvr_anim_sampler s = make(times, 2, values, 24, 4, MVR_INTERPOLATION_CUBICSPLINE, true);
    char why[128] = "";
    CHECK_MSG(t, mvr_anim_sampler_valid(&s, why, sizeof why), "%s", why);
    double q[4];
    mvr_anim_sample(&s, 0.5, q);
    double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    CHECK(t, fabs(n - 1.0) < 1e-14);
    /* symmetric ease: the midpoint of the componentwise spline is the
     * normalised average, i.e. 45 degrees about Y */
    const double e45[4] = {0, sin(0.125 * PI), 0, cos(0.125 * PI)};
    CHECK_MSG(t, quat_near(q, e45, 1e-12), "%.17g %.17g %.17g %.17g", q[0], q[1], q[2], q[3]);
}

static void validation(mvr_test_state *t)
{
    char why[160];
    const double values[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    const double ok[] = {0.0, 1.0, 2.0};
    mvr_anim_sampler s = make(ok, 3, values, 3, 1, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, mvr_anim_sampler_valid(&s, why, sizeof why));

    const double equal[] = {0.0, 1.0, 1.0};
    s = make(equal, 3, values, 3, 1, MVR_INTERPOLATION_LINEAR, false);
    why[0] = '\0';
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    CHECK_MSG(t, strstr(why, "increasing") != NULL, "%s", why);

    const double decreasing[] = {0.0, 2.0, 1.0};
    s = make(decreasing, 3, values, 3, 1, MVR_INTERPOLATION_STEP, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));

    const double with_nan[] = {0.0, NAN, 2.0};
    s = make(with_nan, 3, values, 3, 1, MVR_INTERPOLATION_LINEAR, false);
    why[0] = '\0';
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    CHECK_MSG(t, strstr(why, "finite") != NULL, "%s", why);
    const double with_inf[] = {0.0, 1.0, INFINITY};
    s = make(with_inf, 3, values, 3, 1, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, NULL, 0));

    /* short value arrays: LINEAR needs count * components, CUBICSPLINE three times that */
    s = make(ok, 3, values, 5, 2, MVR_INTERPOLATION_LINEAR, false);
    why[0] = '\0';
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    CHECK_MSG(t, strstr(why, "need 6") != NULL, "%s", why);
    s = make(ok, 3, values, 6, 2, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, mvr_anim_sampler_valid(&s, why, sizeof why));
    s = make(ok, 3, values, 6, 2, MVR_INTERPOLATION_CUBICSPLINE, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    s = make(ok, 3, values, 8, 1, MVR_INTERPOLATION_CUBICSPLINE, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    s = make(ok, 3, values, 9, 1, MVR_INTERPOLATION_CUBICSPLINE, false);
    CHECK(t, mvr_anim_sampler_valid(&s, why, sizeof why));

    /* overflowing sizes, no keys, no components, NULL arrays, non-finite
     * values, a quaternion of 3 components, an unknown interpolation */
    s = make(ok, SIZE_MAX / 2, values, SIZE_MAX, 4, MVR_INTERPOLATION_CUBICSPLINE, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    size_t n = 0;
    CHECK(t, !mvr_anim_sampler_value_count(SIZE_MAX / 2, 4, MVR_INTERPOLATION_LINEAR, &n));
    CHECK(t, mvr_anim_sampler_value_count(5, 4, MVR_INTERPOLATION_CUBICSPLINE, &n) && n == 60);
    s = make(ok, 0, values, 9, 1, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    s = make(ok, 3, values, 9, 0, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    s = make(NULL, 3, values, 9, 1, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    s = make(ok, 3, NULL, 9, 1, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    const double nan_value[] = {0.0, NAN, 1.0};
    s = make(ok, 3, nan_value, 3, 1, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    s = make(ok, 3, values, 9, 3, MVR_INTERPOLATION_LINEAR, true);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    s = make(ok, 3, values, 9, 1, (mvr_interpolation)7, false);
    CHECK(t, !mvr_anim_sampler_valid(&s, why, sizeof why));
    CHECK(t, !mvr_anim_sampler_valid(NULL, why, sizeof why));
}

static void clip_time(mvr_test_state *t)
{
    /* clamp */
    CHECK(t, mvr_anim_time(-1.0, 0.0, 2.0, false) == 0.0);
    CHECK(t, mvr_anim_time(1.5, 0.0, 2.0, false) == 1.5);
    CHECK(t, mvr_anim_time(2.0, 0.0, 2.0, false) == 2.0);
    CHECK(t, mvr_anim_time(7.0, 0.0, 2.0, false) == 2.0);
    CHECK(t, mvr_anim_time(INFINITY, 1.0, 2.0, false) == 2.0);
    /* loop */
    CHECK(t, mvr_anim_time(2.0, 0.0, 2.0, true) == 0.0);   /* t = end: the next period's start */
    CHECK(t, mvr_anim_time(4.5, 0.0, 2.0, true) == 0.5);
    CHECK(t, mvr_anim_time(-0.5, 0.0, 2.0, true) == 1.5);  /* negative times wrap backwards */
    CHECK(t, mvr_anim_time(-2.0, 0.0, 2.0, true) == 0.0);
    CHECK(t, mvr_anim_time(-4.25, 0.0, 2.0, true) == 1.75);
    CHECK(t, mvr_anim_time(0.5, 1.0, 3.0, true) == 2.5);   /* before an offset start */
    CHECK(t, mvr_anim_time(3.0, 1.0, 3.0, true) == 1.0);
    CHECK(t, mvr_anim_time(4.0, 1.0, 3.0, true) == 2.0);
    /* a tiny negative remainder must not round up to end */
    double tiny = mvr_anim_time(-1e-300, 0.0, 2.0, true);
    CHECK_MSG(t, tiny >= 0.0 && tiny < 2.0, "%.17g", tiny);
    double r = mvr_anim_time(-1e-17, 0.0, 1.0, true);
    CHECK_MSG(t, r >= 0.0 && r < 1.0, "%.17g", r);
    /* zero-length or reversed clip, non-finite times */
    CHECK(t, mvr_anim_time(5.0, 1.0, 1.0, true) == 1.0);
    CHECK(t, mvr_anim_time(5.0, 1.0, 1.0, false) == 1.0);
    CHECK(t, mvr_anim_time(-5.0, 1.0, 1.0, true) == 1.0);
    CHECK(t, mvr_anim_time(5.0, 2.0, 1.0, true) == 2.0);
    CHECK(t, mvr_anim_time(NAN, 1.0, 2.0, true) == 1.0);
    CHECK(t, mvr_anim_time(NAN, 1.0, 2.0, false) == 1.0);
    CHECK(t, mvr_anim_time(INFINITY, 1.0, 2.0, true) == 1.0);
    CHECK(t, mvr_anim_time(1.0, NAN, 2.0, true) == 0.0);
    /* a looped sample through a sampler: the clip's values repeat */
    const double times[] = {0.0, 1.0};
    const double values[] = {0.0, 10.0};
    mvr_anim_sampler s = make(times, 2, values, 2, 1, MVR_INTERPOLATION_LINEAR, false);
    CHECK(t, fabs(sample1(&s, mvr_anim_time(-0.75, 0.0, 1.0, true)) - 2.5) < 1e-12);
}

MVR_TEST_MAIN(TEST(step_values), TEST(linear_values_and_clamping), TEST(single_key),
              TEST(many_keys_binary_search), TEST(slerp_90_degrees_about_y),
              TEST(cubic_spline_reproduces_a_cubic), TEST(cubic_spline_zero_tangents_is_smoothstep),
              TEST(cubic_spline_quaternion_is_normalised), TEST(validation), TEST(clip_time))
