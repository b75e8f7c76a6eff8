/* core: environments for image-based lighting (core/environment.c) and the
 * split-sum DFG table (core/ibl_lut.c): validation, the white furnace, the
 * neutral studio's diffuse light, its spherical harmonics against a brute-
 * force irradiance integral, rotation and intensity, box filtering of wide
 * images, and the DFG table against a brute-force BRDF integral. */
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <time.h>

#include "environment.h"
#include "mvr_test.h"

#define PI 3.14159265358979323846

/* n points spread over the sphere (the Fibonacci lattice). */
static void fibonacci_dir(int k, int n, double d[3])
{
    double y = 1.0 - 2.0 * ((double)k + 0.5) / (double)n;
    double r = sqrt(1.0 - y * y), phi = (double)k * PI * (3.0 - sqrt(5.0));
    d[0] = r * cos(phi);
    d[1] = y;
    d[2] = r * sin(phi);
}

static mvr_environment *make(const mvr_environment_desc *desc)
{
    mvr_environment *env = NULL;
    mvr_error err;
    if (mvr_environment_create(desc, &env, &err) != MVR_OK) {
        printf("  mvr_environment_create: %s\n", err.message);
        return NULL;
    }
    return env;
}

/* e = R_y(-degrees) d, written out independently of the library. */
static void rot_y_inverse(double degrees, const double d[3], double e[3])
{
    double a = -degrees * PI / 180.0;
    e[0] = d[0] * cos(a) + d[2] * sin(a);
    e[1] = d[1];
    e[2] = -d[0] * sin(a) + d[2] * cos(a);
}

static void names(mvr_test_state *t)
{
    CHECK(t, strcmp(mvr_environment_source_name(MVR_ENVIRONMENT_NEUTRAL), "neutral") == 0);
    CHECK(t, strcmp(mvr_environment_source_name(MVR_ENVIRONMENT_PIXELS), "pixels") == 0);
    CHECK(t, strcmp(mvr_environment_source_name(MVR_ENVIRONMENT_UNIFORM), "uniform") == 0);
    CHECK(t, mvr_environment_source_name((mvr_environment_source)3) == NULL);
    CHECK(t, strcmp(mvr_background_name(MVR_BACKGROUND_COLOR), "color") == 0);
    CHECK(t, strcmp(mvr_background_name(MVR_BACKGROUND_ENVIRONMENT), "environment") == 0);
    CHECK(t, strcmp(mvr_background_name(MVR_BACKGROUND_BLUR), "blur") == 0);
    CHECK(t, mvr_background_name((mvr_background)3) == NULL);
}

static void defaults_are_resolved(mvr_test_state *t)
{
    mvr_environment *a = make(NULL), *b = make(NULL);
    CHECK(t, a && b);
    if (a && b) {
        CHECK(t, a->source == MVR_ENVIRONMENT_NEUTRAL);
        CHECK_EQ_INT(t, a->width, 512);
        CHECK_EQ_INT(t, a->height, 256);
        CHECK_EQ_INT(t, a->specular_size, 128);
        CHECK_EQ_INT(t, a->specular_samples, 256);
        CHECK(t, a->intensity == 1.0f && mvr_environment_intensity(a) == 1.0f);
        CHECK(t, a->rotation == 0.0f && mvr_environment_rotation(a) == 0.0f);
        CHECK(t, a->serial != 0 && b->serial != 0 && a->serial != b->serial);
    }
    mvr_environment_destroy(a);
    mvr_environment_destroy(b);
    mvr_environment_destroy(NULL);
}

/* A uniform radiance: the diffuse light of every normal is that radiance
 * (the white furnace: irradiance pi L, divided by pi), and every direction
 * reads it exactly. */
static void uniform_is_a_white_furnace(mvr_test_state *t)
{
    mvr_environment_desc d = {0};
    d.source = MVR_ENVIRONMENT_UNIFORM;
    mvr_environment *white = make(&d);
    d.color[0] = 0.25f;
    d.color[1] = 0.5f;
    d.color[2] = 2.0f;
    d.intensity = 3.0f;
    d.rotation = 37.0f;
    mvr_environment *tinted = make(&d);
    CHECK(t, white && tinted);
    if (!white || !tinted)
        return;
    double worst = 0;
    for (int k = 0; k < 100; ++k) {
        double n[3], rgb[3], l[3];
        fibonacci_dir(k, 100, n);
        mvr_environment_diffuse(white, n, rgb);
        mvr_environment_radiance(white, n, l);
        for (int c = 0; c < 3; ++c) {
            worst = fmax(worst, fabs(rgb[c] - 1.0));
            CHECK_MSG(t, fabs(rgb[c] - 1.0) <= 1e-5, "white diffuse %g at direction %d", rgb[c], k);
            CHECK_MSG(t, l[c] == 1.0, "white radiance %.17g at direction %d", l[c], k);
        }
        mvr_environment_diffuse(tinted, n, rgb);
        mvr_environment_radiance(tinted, n, l);
        for (int c = 0; c < 3; ++c) {
            double want = 3.0 * d.color[c];
            CHECK_MSG(t, fabs(rgb[c] - want) <= 1e-5 * want, "tinted diffuse %g, want %g", rgb[c], want);
            CHECK_MSG(t, l[c] == want, "tinted radiance %.17g, want %g", l[c], want);
        }
    }
    /* measured: 3e-8 (float storage of the coefficients) */
    printf("  white furnace: worst |diffuse - 1| = %.2e\n", worst);
    mvr_environment_destroy(white);
    mvr_environment_destroy(tinted);
}

/* The studio's design targets: a white Lambertian surface facing the camera
 * (+Z) reads 0.8-0.9, up 0.9-1.1, down 0.25-0.4, away 0.5-0.7; the
 * brightest softbox 5-10 (crisp highlights on metals); grey. Measured:
 * 0.865, 1.048, 0.368, 0.612 (+X 0.646, -X 0.739); texels 0.278 .. 9.167. */
static void neutral_studio_lights_every_side(mvr_test_state *t)
{
    mvr_environment *env = make(NULL);
    CHECK(t, env != NULL);
    if (!env)
        return;
    static const struct {
        const char *name;
        double n[3], lo, hi;
    } want[] = {
        {"+Z", {0, 0, 1}, 0.8, 0.9},   {"+Y", {0, 1, 0}, 0.9, 1.1},   {"-Y", {0, -1, 0}, 0.25, 0.4},
        {"-Z", {0, 0, -1}, 0.5, 0.7},  {"+X", {1, 0, 0}, 0.3, 1.2},   {"-X", {-1, 0, 0}, 0.3, 1.2},
    };
    for (size_t i = 0; i < sizeof want / sizeof want[0]; ++i) {
        double rgb[3];
        mvr_environment_diffuse(env, want[i].n, rgb);
        printf("  studio diffuse facing %s: %.4f\n", want[i].name, rgb[0]);
        CHECK_MSG(t, rgb[0] >= want[i].lo && rgb[0] <= want[i].hi, "facing %s: %g not in %g..%g", want[i].name,
                  rgb[0], want[i].lo, want[i].hi);
        CHECK(t, rgb[0] == rgb[1] && rgb[1] == rgb[2]);
    }
    float lo = INFINITY, hi = 0;
    bool grey = true;
    for (size_t p = 0; p < (size_t)env->width * env->height; ++p) {
        const float *px = env->pixels + p * 4;
        lo = fminf(lo, px[0]);
        hi = fmaxf(hi, px[0]);
        grey = grey && px[0] == px[1] && px[1] == px[2] && px[3] == 1.0f;
    }
    printf("  studio radiance: %.3f .. %.3f\n", (double)lo, (double)hi);
    CHECK(t, grey);
    CHECK_MSG(t, hi >= 5.0f && hi <= 10.0f, "brightest %g", (double)hi);
    CHECK_MSG(t, lo >= 0.15f, "darkest %g", (double)lo);
    /* the key light is front-upper-left, seen from the default camera */
    double key[3] = {-0.5, 0.6, 0.6}, l[3];
    mvr_environment_radiance(env, key, l);
    CHECK_MSG(t, l[0] >= 5.0, "key radiance %g", l[0]);
    mvr_environment_destroy(env);
}

/* Brute-force irradiance: every texel of the stored image as a small source
 * at its centre direction, weighted by the exact solid angle of its cell,
 * (2 pi / W) (cos theta0 - cos theta1); in double. */
typedef struct texel_source {
    double d[3];
    double power; /* red radiance times solid angle */
} texel_source;

static texel_source *texel_sources(const mvr_environment *env)
{
    const uint32_t w = env->width, h = env->height;
    texel_source *s = malloc((size_t)w * h * sizeof *s);
    if (!s)
        return NULL;
    for (uint32_t j = 0; j < h; ++j) {
        double t0 = PI * j / h, t1 = PI * (j + 1) / h, tc = PI * (j + 0.5) / h;
        double domega = 2.0 * PI / w * (cos(t0) - cos(t1));
        for (uint32_t i = 0; i < w; ++i) {
            double phi = 2.0 * PI * (i + 0.5) / w - PI;
            texel_source *p = s + (size_t)j * w + i;
            p->d[0] = sin(tc) * sin(phi);
            p->d[1] = cos(tc);
            p->d[2] = -sin(tc) * cos(phi);
            p->power = env->pixels[((size_t)j * w + i) * 4] * domega;
        }
    }
    return s;
}

static double brute_force_diffuse(const texel_source *s, size_t count, const double n[3])
{
    double e = 0;
    for (size_t k = 0; k < count; ++k) {
        double c = n[0] * s[k].d[0] + n[1] * s[k].d[1] + n[2] * s[k].d[2];
        if (c > 0)
            e += s[k].power * c;
    }
    return e / PI;
}

/* Nine spherical harmonics hold the irradiance to a few percent (Ramamoorthi
 * and Hanrahan 2001); small bright softboxes are the hard case (their
 * truncated bands ring into the dim side), which is why the studio puts most
 * of its directional light into smooth lobes that nine coefficients hold
 * exactly. Directions: the 26 of a 3x3x3 grid, the key, and 100 spread over
 * the sphere. Measured: worst 2.7% of these 127, down-right-behind at
 * (0.40, -0.73, -0.56), mean 0.6%; 1.85% the worst of the 26 grid
 * directions (at (1, -1, -1) / sqrt 3); 2.8% the worst of 400 directions. */
static void sh_matches_brute_force_irradiance(mvr_test_state *t)
{
    mvr_environment *env = make(NULL);
    CHECK(t, env != NULL);
    texel_source *src = env ? texel_sources(env) : NULL;
    CHECK(t, src != NULL);
    if (!env || !src) {
        mvr_environment_destroy(env);
        return;
    }
    enum { GRID = 26, COUNT = GRID + 1 + 100 };
    double dirs[COUNT][3];
    int n = 0;
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z)
                if (x || y || z) {
                    double l = sqrt((double)(x * x + y * y + z * z));
                    dirs[n][0] = x / l;
                    dirs[n][1] = y / l;
                    dirs[n][2] = z / l;
                    ++n;
                }
    double key_len = sqrt(0.25 + 0.36 + 0.36);
    dirs[n][0] = -0.5 / key_len, dirs[n][1] = 0.6 / key_len, dirs[n][2] = 0.6 / key_len;
    ++n;
    for (int k = 0; k < 100; ++k, ++n)
        fibonacci_dir(k, 100, dirs[n]);
    double worst = 0, mean = 0;
    int worst_at = 0;
    for (int k = 0; k < n; ++k) {
        double sh[3];
        mvr_environment_diffuse(env, dirs[k], sh);
        double bf = brute_force_diffuse(src, (size_t)env->width * env->height, dirs[k]);
        double e = fabs(sh[0] - bf) / bf;
        mean += e / n;
        if (e > worst)
            worst = e, worst_at = k;
        CHECK_MSG(t, e <= 0.03, "(%.3f %.3f %.3f): SH %.4f, brute force %.4f (%.1f%%)", dirs[k][0], dirs[k][1],
                  dirs[k][2], sh[0], bf, 100 * e);
    }
    printf("  studio SH vs brute force: worst %.2f%% at (%.2f %.2f %.2f), mean %.2f%%\n", 100 * worst,
           dirs[worst_at][0], dirs[worst_at][1], dirs[worst_at][2], 100 * mean);
    free(src);
    mvr_environment_destroy(env);
}

/* A radiance that is a polynomial of degree 2 in the direction lies in the
 * span of the nine harmonics, so its diffuse light is known in closed form:
 * each band scaled by A_l / pi = 1, 2/3, 1/4 (Ramamoorthi and Hanrahan
 * 2001). Written in plain x, y, z, this checks every basis function, its
 * sign and the image mapping at once. The stored coefficients are also
 * evaluated here with the basis as environment.h (and the shader) writes
 * it, so env->sh means what the GL backend takes it to mean. Measured
 * error: 1e-5 (the image holds the radiance at texel centres). */
static double poly_radiance(const double d[3], double w1, double w2)
{
    double x = d[0], y = d[1], z = d[2];
    return 3.0 + w1 * (0.5 * x - 0.3 * y + 0.2 * z) +
           w2 * (0.4 * x * y - 0.3 * y * z + 0.25 * (3 * z * z - 1) + 0.35 * x * z + 0.2 * (x * x - y * y));
}

static void quadratic_radiance_is_exact(mvr_test_state *t)
{
    const uint32_t w = 512, h = 256;
    float *px = malloc((size_t)w * h * 4 * sizeof *px);
    CHECK(t, px != NULL);
    if (!px)
        return;
    for (uint32_t j = 0; j < h; ++j) {
        double th = PI * (j + 0.5) / h;
        for (uint32_t i = 0; i < w; ++i) {
            double ph = 2.0 * PI * (i + 0.5) / w - PI;
            double d[3] = {sin(th) * sin(ph), cos(th), -sin(th) * cos(ph)};
            float *p = px + ((size_t)j * w + i) * 4;
            p[0] = p[1] = p[2] = (float)poly_radiance(d, 1.0, 1.0);
            p[3] = 1.0f;
        }
    }
    mvr_environment_desc d = {0};
    d.source = MVR_ENVIRONMENT_PIXELS;
    d.pixels = px;
    d.width = w;
    d.height = h;
    mvr_environment *env = make(&d);
    free(px);
    CHECK(t, env != NULL);
    if (!env)
        return;
    double worst = 0;
    for (int k = 0; k < 100; ++k) {
        double n[3], rgb[3];
        fibonacci_dir(k, 100, n);
        mvr_environment_diffuse(env, n, rgb);
        double want = poly_radiance(n, 2.0 / 3.0, 0.25);
        worst = fmax(worst, fabs(rgb[0] - want));
        CHECK_MSG(t, fabs(rgb[0] - want) <= 1e-4, "(%.3f %.3f %.3f): %.6f, want %.6f", n[0], n[1], n[2], rgb[0],
                  want);
        double x = n[0], y = n[1], z = n[2];
        const double basis[9] = {0.282095,         0.488603 * y,     0.488603 * z,
                                 0.488603 * x,     1.092548 * x * y, 1.092548 * y * z,
                                 0.315392 * (3 * z * z - 1), 1.092548 * x * z, 0.546274 * (x * x - y * y)};
        double shader = 0;
        for (int i = 0; i < 9; ++i)
            shader += env->sh[i][0] * basis[i];
        CHECK_MSG(t, fabs(shader - want) <= 1e-4, "shader's basis: %.6f, want %.6f", shader, want);
    }
    printf("  quadratic radiance: worst diffuse error %.1e\n", worst);
    mvr_environment_destroy(env);
}

static void neutral_studio_is_deterministic(mvr_test_state *t)
{
    mvr_environment *a = make(NULL), *b = make(NULL);
    CHECK(t, a && b);
    if (a && b) {
        CHECK(t, a->width == b->width && a->height == b->height);
        CHECK(t, memcmp(a->pixels, b->pixels, (size_t)a->width * a->height * 4 * sizeof(float)) == 0);
        CHECK(t, memcmp(a->sh, b->sh, sizeof a->sh) == 0);
    }
    mvr_environment_destroy(a);
    mvr_environment_destroy(b);
}

/* An image whose texel (i, j) holds (i, j, 1): what a lookup returns says
 * where in the image it read. */
static float *coordinate_image(uint32_t w, uint32_t h)
{
    float *px = malloc((size_t)w * h * 4 * sizeof *px);
    if (!px)
        return NULL;
    for (uint32_t j = 0; j < h; ++j)
        for (uint32_t i = 0; i < w; ++i) {
            float *p = px + ((size_t)j * w + i) * 4;
            p[0] = (float)i;
            p[1] = (float)j;
            p[2] = 1.0f;
            p[3] = 1.0f;
        }
    return px;
}

static void rotation_turns_about_y(mvr_test_state *t)
{
    float *px = coordinate_image(64, 32);
    mvr_environment_desc d = {0};
    d.source = MVR_ENVIRONMENT_PIXELS;
    d.pixels = px;
    d.width = 64;
    d.height = 32;
    mvr_environment *e0 = make(&d);
    d.rotation = 90.0f;
    mvr_environment *e90 = make(&d);
    free(px);
    CHECK(t, e0 && e90);
    if (!e0 || !e90)
        return;
    /* the mapping of mvr.h: -Z is the centre column, +X the right quarter, +Y the top */
    double mz[3] = {0, 0, -1}, px_[3] = {1, 0, 0}, mx[3] = {-1, 0, 0}, up[3] = {0, 1, 0}, l[3], l2[3];
    mvr_environment_radiance(e0, mz, l);
    CHECK_MSG(t, l[0] == 31.5 && l[1] == 15.5, "-Z reads (%g, %g)", l[0], l[1]);
    mvr_environment_radiance(e0, px_, l);
    CHECK_MSG(t, l[0] == 47.5 && l[1] == 15.5, "+X reads (%g, %g)", l[0], l[1]);
    mvr_environment_radiance(e0, up, l);
    CHECK_MSG(t, l[1] == 0.0, "+Y reads row %g", l[1]);
    /* "+90 brings what was at -Z to -X" */
    mvr_environment_radiance(e90, mx, l);
    mvr_environment_radiance(e0, mz, l2);
    CHECK_MSG(t, l[0] == l2[0] && l[1] == l2[1], "rotation 90 at -X reads (%g, %g), -Z at 0 (%g, %g)", l[0], l[1],
              l2[0], l2[1]);
    mvr_environment_radiance(e0, mx, l);
    CHECK(t, l[0] != l2[0]);
    /* radiance(d) at 90 = radiance(R_y(-90) d) at 0, and the same for diffuse */
    for (int k = 0; k < 50; ++k) {
        double dd[3], e[3], a[3], b[3];
        fibonacci_dir(k, 50, dd);
        rot_y_inverse(90.0, dd, e);
        mvr_environment_radiance(e90, dd, a);
        mvr_environment_radiance(e0, e, b);
        for (int c = 0; c < 3; ++c)
            CHECK_MSG(t, fabs(a[c] - b[c]) <= 1e-9 * (1 + fabs(b[c])), "radiance %d: %g vs %g", k, a[c], b[c]);
        mvr_environment_diffuse(e90, dd, a);
        mvr_environment_diffuse(e0, e, b);
        for (int c = 0; c < 3; ++c)
            CHECK_MSG(t, fabs(a[c] - b[c]) <= 1e-9 * (1 + fabs(b[c])), "diffuse %d: %g vs %g", k, a[c], b[c]);
    }
    /* an arbitrary angle, through the setter */
    mvr_environment_set_rotation(e90, -123.5f);
    CHECK(t, mvr_environment_rotation(e90) == -123.5f);
    mvr_environment_set_rotation(e90, NAN);
    CHECK(t, mvr_environment_rotation(e90) == -123.5f);
    for (int k = 0; k < 50; ++k) {
        double dd[3], e[3], a[3], b[3];
        fibonacci_dir(k, 50, dd);
        rot_y_inverse(-123.5, dd, e);
        mvr_environment_diffuse(e90, dd, a);
        mvr_environment_diffuse(e0, e, b);
        CHECK_MSG(t, fabs(a[0] - b[0]) <= 1e-6 * (1 + fabs(b[0])), "diffuse %d: %g vs %g", k, a[0], b[0]);
    }
    /* the shader's matrix agrees: world -X -> environment -Z at 90 */
    mvr_environment_set_rotation(e90, 90.0f);
    float m[9];
    mvr_environment_rotation_matrix(e90, m);
    double w[3] = {-1, 0, 0}, e[3];
    for (int r = 0; r < 3; ++r)
        e[r] = m[0 * 3 + r] * w[0] + m[1 * 3 + r] * w[1] + m[2 * 3 + r] * w[2];
    CHECK_MSG(t, e[0] == 0 && e[1] == 0 && e[2] == -1, "M (-X) = (%g %g %g)", e[0], e[1], e[2]);
    mvr_environment_set_rotation(e90, 30.0f);
    mvr_environment_rotation_matrix(e90, m);
    double dd[3] = {0.3, -0.2, 0.9};
    rot_y_inverse(30.0, dd, w);
    for (int r = 0; r < 3; ++r) {
        e[r] = m[0 * 3 + r] * dd[0] + m[1 * 3 + r] * dd[1] + m[2 * 3 + r] * dd[2];
        CHECK_MSG(t, fabs(e[r] - w[r]) < 1e-6, "matrix row %d: %g vs %g", r, e[r], w[r]);
    }
    mvr_environment_destroy(e0);
    mvr_environment_destroy(e90);
}

static void intensity_scales(mvr_test_state *t)
{
    mvr_environment_desc d = {0};
    mvr_environment *one = make(&d);
    d.intensity = 2.5f;
    mvr_environment *more = make(&d);
    CHECK(t, one && more);
    if (!one || !more)
        return;
    CHECK(t, mvr_environment_intensity(more) == 2.5f);
    for (int k = 0; k < 20; ++k) {
        double n[3], a[3], b[3];
        fibonacci_dir(k, 20, n);
        mvr_environment_diffuse(one, n, a);
        mvr_environment_diffuse(more, n, b);
        CHECK(t, fabs(b[0] - 2.5 * a[0]) <= 1e-12 * b[0]);
        mvr_environment_radiance(one, n, a);
        mvr_environment_radiance(more, n, b);
        CHECK(t, fabs(b[0] - 2.5 * a[0]) <= 1e-12 * b[0]);
    }
    mvr_environment_set_intensity(one, 0.5f);
    CHECK(t, mvr_environment_intensity(one) == 0.5f);
    double n[3] = {0, 0, 1}, a[3], b[3];
    mvr_environment_diffuse(one, n, a);
    mvr_environment_diffuse(more, n, b);
    CHECK(t, fabs(b[0] - 5.0 * a[0]) <= 1e-12 * b[0]);
    mvr_environment_set_intensity(one, -1.0f); /* refused: unchanged */
    CHECK(t, mvr_environment_intensity(one) == 0.5f);
    mvr_environment_set_intensity(one, NAN);
    CHECK(t, mvr_environment_intensity(one) == 0.5f);
    mvr_environment_set_intensity(one, 0.0f); /* 0 = 1 */
    CHECK(t, mvr_environment_intensity(one) == 1.0f);
    /* degenerate directions give 0, not NaN */
    double zero[3] = {0, 0, 0};
    mvr_environment_diffuse(one, zero, a);
    mvr_environment_radiance(one, zero, b);
    CHECK(t, a[0] == 0 && b[0] == 0);
    mvr_environment_destroy(one);
    mvr_environment_destroy(more);
}

static bool refused(mvr_test_state *t, const mvr_environment_desc *d, const char *field)
{
    mvr_environment *env = (mvr_environment *)(uintptr_t)1;
    mvr_error err = {MVR_OK, ""};
    mvr_result r = mvr_environment_create(d, &env, &err);
    CHECK_MSG(t, r == MVR_ERROR_INVALID_ARGUMENT, "%s: %s", field, mvr_result_name(r));
    CHECK_MSG(t, err.result == r, "%s", field);
    CHECK_MSG(t, strstr(err.message, field) != NULL, "message \"%s\" does not name %s", err.message, field);
    CHECK(t, env == NULL);
    if (r == MVR_OK)
        mvr_environment_destroy(env);
    return r == MVR_ERROR_INVALID_ARGUMENT;
}

static void invalid_descriptors_are_refused(mvr_test_state *t)
{
    mvr_environment_desc d = {0};
    d.intensity = NAN;
    refused(t, &d, "intensity");
    d.intensity = -1.0f;
    refused(t, &d, "intensity");
    d.intensity = INFINITY;
    refused(t, &d, "intensity");
    d.intensity = 0;
    d.rotation = INFINITY;
    refused(t, &d, "rotation");
    d.rotation = 0;
    d.specular_size = 100;
    refused(t, &d, "specular_size");
    d.specular_size = 8;
    refused(t, &d, "specular_size");
    d.specular_size = 2048;
    refused(t, &d, "specular_size");
    d.specular_size = 16;
    d.specular_samples = 4097;
    refused(t, &d, "specular_samples");
    d.specular_samples = 4096;
    mvr_environment *ok = make(&d); /* the extremes are fine */
    CHECK(t, ok && ok->specular_size == 16 && ok->specular_samples == 4096);
    mvr_environment_destroy(ok);
    d.specular_samples = 0;
    d.source = (mvr_environment_source)7;
    refused(t, &d, "source");
    d.source = MVR_ENVIRONMENT_UNIFORM;
    d.color[1] = NAN;
    refused(t, &d, "color");
    d.color[1] = -0.5f;
    refused(t, &d, "color");
    d.color[1] = 0;
    d.source = MVR_ENVIRONMENT_PIXELS;
    d.width = 4;
    d.height = 2;
    refused(t, &d, "pixels");
    float px[8 * 4] = {0};
    d.pixels = px;
    d.width = 0;
    refused(t, &d, "width");
    d.width = 4;
    d.height = 0;
    refused(t, &d, "height");
    d.width = UINT32_MAX; /* UINT32_MAX^2 RGBA floats: more bytes than a 64-bit size_t holds */
    d.height = UINT32_MAX;
    refused(t, &d, "width");
    d.width = 4;
    d.height = 2;
    ok = make(&d);
    CHECK(t, ok != NULL);
    mvr_environment_destroy(ok);
    mvr_environment *env = NULL;
    CHECK(t, mvr_environment_create(NULL, NULL, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_environment_create(NULL, &env, NULL) == MVR_OK && env);
    mvr_environment_destroy(env);
}

typedef struct log_count {
    int warnings, errors;
    char last[256];
} log_count;

static void count_log(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    (void)id;
    log_count *c = user;
    if (level == MVR_LOG_WARNING)
        c->warnings++;
    if (level == MVR_LOG_ERROR)
        c->errors++;
    snprintf(c->last, sizeof c->last, "%s", message);
}

/* NaN, infinities and negatives are stored as 0, counted, logged once. */
static void bad_pixels_become_zero(mvr_test_state *t)
{
    float px[4 * 2 * 4];
    for (int i = 0; i < 32; ++i)
        px[i] = 1.0f;
    px[0] = NAN;
    px[5] = -2.0f;
    px[10] = INFINITY;
    px[13] = -INFINITY;
    px[3] = NAN; /* alpha: ignored */
    log_count lc = {0, 0, ""};
    mvr_environment_desc d = {0};
    d.source = MVR_ENVIRONMENT_PIXELS;
    d.pixels = px;
    d.width = 4;
    d.height = 2;
    d.logger.fn = count_log;
    d.logger.user_data = &lc;
    mvr_environment *env = make(&d);
    CHECK(t, env != NULL);
    if (!env)
        return;
    CHECK(t, env->pixels[0] == 0 && env->pixels[5] == 0 && env->pixels[10] == 0 && env->pixels[13] == 0);
    CHECK(t, env->pixels[1] == 1.0f && env->pixels[3] == 1.0f);
    CHECK_EQ_INT(t, lc.warnings, 1);
    CHECK_MSG(t, strstr(lc.last, "4 pixel values") != NULL, "%s", lc.last);
    for (int i = 0; i < 9; ++i)
        for (int c = 0; c < 3; ++c)
            CHECK(t, isfinite(env->sh[i][c]));
    mvr_environment_destroy(env);
    /* refusals reach the logger too */
    d.intensity = NAN;
    mvr_environment *none = NULL;
    CHECK(t, mvr_environment_create(&d, &none, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK_EQ_INT(t, lc.errors, 1);
}

/* Wider than 2048: a box filter in linear light to 2048 wide, the height
 * scaled alike. 4096 x 8 -> 2048 x 4, each texel the mean of a 2 x 2 block;
 * 3000 x 6 -> 2048 x 4 by exact area weights (a constant stays constant). */
static void wide_images_are_box_filtered(mvr_test_state *t)
{
    float *px = malloc((size_t)4096 * 8 * 4 * sizeof *px);
    CHECK(t, px != NULL);
    if (!px)
        return;
    for (uint32_t j = 0; j < 8; ++j)
        for (uint32_t i = 0; i < 4096; ++i) {
            float *p = px + ((size_t)j * 4096 + i) * 4;
            p[0] = (float)i + 100.0f * (float)j;
            p[1] = (i + j) % 2 ? 3.0f : 1.0f; /* a checkerboard averages to 2 */
            p[2] = 0.75f;
            p[3] = 0.0f;
        }
    mvr_environment_desc d = {0};
    d.source = MVR_ENVIRONMENT_PIXELS;
    d.pixels = px;
    d.width = 4096;
    d.height = 8;
    mvr_environment *env = make(&d);
    CHECK(t, env != NULL);
    if (env) {
        CHECK_EQ_INT(t, env->width, 2048);
        CHECK_EQ_INT(t, env->height, 4);
        int bad = 0;
        for (uint32_t y = 0; y < 4; ++y)
            for (uint32_t x = 0; x < 2048; ++x) {
                const float *p = env->pixels + ((size_t)y * 2048 + x) * 4;
                float want = (float)(2 * x) + 0.5f + 100.0f * ((float)(2 * y) + 0.5f);
                bad += p[0] != want || p[1] != 2.0f || p[2] != 0.75f || p[3] != 1.0f;
            }
        CHECK_EQ_INT(t, bad, 0);
    }
    mvr_environment_destroy(env);
    for (size_t i = 0; i < (size_t)3000 * 6 * 4; ++i)
        px[i] = 1.5f;
    d.width = 3000;
    d.height = 6;
    env = make(&d);
    CHECK(t, env != NULL);
    if (env) {
        CHECK_EQ_INT(t, env->width, 2048);
        CHECK_EQ_INT(t, env->height, 4);
        double worst = 0;
        for (size_t i = 0; i < (size_t)2048 * 4; ++i)
            worst = fmax(worst, fabs(env->pixels[i * 4] - 1.5));
        CHECK_MSG(t, worst <= 1e-6, "constant image filtered off by %g", worst);
        double n[3] = {0.2, 0.7, -0.3}, rgb[3];
        mvr_environment_diffuse(env, n, rgb);
        CHECK_MSG(t, fabs(rgb[0] - 1.5) <= 1e-5, "diffuse %g", rgb[0]);
    }
    mvr_environment_destroy(env);
    /* taller than 2048 (not an equirectangular shape, but accepted): the
     * height is capped alike, 10 x 3000 -> 7 x 2048 */
    d.width = 10;
    d.height = 3000;
    env = make(&d);
    CHECK(t, env && env->width == 7 && env->height == 2048);
    if (env)
        CHECK(t, fabs(env->pixels[4 * 1000] - 1.5) <= 1e-6);
    mvr_environment_destroy(env);
    free(px);
}

/* ------------------------------------------------------------------ DFG */

/* A and B at (NdotV, roughness) by brute force: the full BRDF
 * D Vis F (n.l) over a fine midpoint grid of the hemisphere of l,
 * (cos theta_l, phi), with no importance sampling. */
static void brute_force_dfg(double nv, double roughness, double *out_a, double *out_b)
{
    const int nmu = 2000, nphi = 2000;
    double alpha = roughness * roughness, a2 = alpha * alpha;
    double v[3] = {sqrt(1 - nv * nv), 0, nv};
    double a = 0, b = 0;
    for (int im = 0; im < nmu; ++im) {
        double mu = (im + 0.5) / nmu, st = sqrt(1 - mu * mu);
        for (int ip = 0; ip < nphi; ++ip) {
            double phi = PI * (ip + 0.5) / nphi; /* symmetric in phi: [0, pi], doubled */
            double l[3] = {st * cos(phi), st * sin(phi), mu};
            double h[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]};
            double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            double nh = h[2] / hl, vh = (v[0] * h[0] + v[2] * h[2]) / hl;
            double q = nh * nh * (a2 - 1) + 1;
            double dd = a2 / (PI * q * q);
            double vis = 0.5 / (mu * sqrt(nv * nv * (1 - a2) + a2) + nv * sqrt(mu * mu * (1 - a2) + a2));
            double fc = pow(1 - vh, 5);
            double f = dd * vis * mu * (1.0 / nmu) * (PI / nphi) * 2;
            a += f * (1 - fc);
            b += f * fc;
        }
    }
    *out_a = a;
    *out_b = b;
}

static void dfg_lut(mvr_test_state *t)
{
    enum { N = 64 };
    static float lut[N * N * 2];
    /* (its time, ~14 ms here, is a benchmark's business, not a test's) */
    CHECK(t, mvr_ibl_dfg_lut(N, 512, lut));
    int over = 0, negative = 0;
    double max_sum = 0;
    for (int k = 0; k < N * N; ++k) {
        double s = (double)lut[2 * k] + lut[2 * k + 1];
        max_sum = fmax(max_sum, s);
        over += s > 1.0;
        negative += lut[2 * k] < 0 || lut[2 * k + 1] < 0 || !isfinite(s);
    }
    printf("  DFG LUT max A+B %.5f\n", max_sum);
    CHECK_EQ_INT(t, over, 0);
    CHECK_EQ_INT(t, negative, 0);
    /* smooth, nearly mirror-like: nearly everything reflected, nearly all of it F0 */
    const float *smooth = lut + ((size_t)0 * N + (N - 1)) * 2;
    printf("  DFG LUT at roughness %.4f, NdotV %.4f: A %.5f B %.5f\n", 0.5 / N, (N - 0.5) / N, smooth[0],
           smooth[1]);
    CHECK(t, smooth[0] + smooth[1] >= 0.98f);
    CHECK(t, smooth[1] < 0.01f);
    /* rough: much less (single scattering loses the energy of the light
     * that bounces between microfacets); brute force: 0.457 */
    const float *rough = lut + ((size_t)(N - 1) * N + N / 2) * 2;
    CHECK_MSG(t, rough[0] + rough[1] > 0.42f && rough[0] + rough[1] < 0.49f, "%g", (double)(rough[0] + rough[1]));
    /* against the brute-force integral: measured worst 1.1% of A + B (at
     * NdotV 0.195, roughness 0.805: 512 samples' own error there) */
    static const int at[][2] = {{32, 32}, {57, 19}, {12, 51}, {5, 10}, {40, 60}};
    double worst = 0;
    for (size_t p = 0; p < sizeof at / sizeof at[0]; ++p) {
        int i = at[p][0], j = at[p][1];
        double nv = (i + 0.5) / N, r = (j + 0.5) / N, a, b;
        brute_force_dfg(nv, r, &a, &b);
        const float *o = lut + ((size_t)j * N + (size_t)i) * 2;
        double ea = fabs(o[0] - a) / (a + b), eb = fabs(o[1] - b) / (a + b);
        worst = fmax(worst, fmax(ea, eb));
        printf("  NdotV %.3f roughness %.3f: LUT (%.4f, %.4f), brute force (%.4f, %.4f)\n", nv, r, o[0], o[1], a,
               b);
        CHECK_MSG(t, ea <= 0.015 && eb <= 0.015, "at (%d, %d): %.2f%%, %.2f%% of A+B", i, j, 100 * ea, 100 * eb);
    }
    printf("  DFG LUT vs brute force: worst %.2f%% of A+B\n", 100 * worst);
    CHECK(t, !mvr_ibl_dfg_lut(0, 16, lut));
    CHECK(t, !mvr_ibl_dfg_lut(16, 0, lut));
    CHECK(t, !mvr_ibl_dfg_lut(16, 16, NULL));
}

MVR_TEST_MAIN(TEST(names), TEST(defaults_are_resolved), TEST(uniform_is_a_white_furnace),
              TEST(neutral_studio_lights_every_side), TEST(sh_matches_brute_force_irradiance),
              TEST(quadratic_radiance_is_exact),
              TEST(neutral_studio_is_deterministic), TEST(rotation_turns_about_y), TEST(intensity_scales),
              TEST(invalid_descriptors_are_refused), TEST(bad_pixels_become_zero), TEST(wide_images_are_box_filtered),
              TEST(dfg_lut))
