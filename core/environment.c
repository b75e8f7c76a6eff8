/* Environments for image-based lighting, the CPU side: validation, the
 * stored equirectangular radiance (a caller's image, one uniform radiance,
 * or the built-in neutral studio), its irradiance in nine spherical
 * harmonics (Ramamoorthi and Hanrahan 2001, "An Efficient Representation for
 * Irradiance Environment Maps"), and CPU lookups that match what the shaders
 * evaluate. The GPU prefiltering lives in gl/; the DFG table in ibl_lut.c.
 *
 * Directions and the image (mvr.h): u = 0.5 + atan2(d.x, -d.z) / (2 pi),
 * v = acos(d.y) / pi, v = 0 the top row. So with theta = pi v (the polar
 * angle from +Y) and phi = 2 pi (u - 0.5):
 *   x = sin(theta) sin(phi),  y = cos(theta),  z = -sin(theta) cos(phi).
 * Texel (i, j) of a W x H image covers phi in [2pi i/W - pi, 2pi (i+1)/W - pi]
 * and theta in [pi j/H, pi (j+1)/H]; its centre is at i + 0.5, j + 0.5. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core_util.h"
#include "environment.h"

#if !defined(__STDC_NO_ATOMICS__)
#include <stdatomic.h>
#endif

#define PI 3.14159265358979323846

/* The SH constants at full precision (see environment.h). */
#define SH_K0 0.28209479177387814347 /* 1 / (2 sqrt(pi)) */
#define SH_K1 0.48860251190291992159 /* sqrt(3 / (4 pi)) */
#define SH_K2 1.09254843059207907054 /* sqrt(15 / (4 pi)) */
#define SH_K3 0.31539156525252000603 /* sqrt(5 / (16 pi)) */
#define SH_K4 0.54627421529603953527 /* sqrt(15 / (16 pi)) */

/* Uniform environments are stored as a small constant image. */
#define UNIFORM_WIDTH 8u
#define UNIFORM_HEIGHT 4u

/* ------------------------------------------------------------------ names */

const char *mvr_environment_source_name(mvr_environment_source source)
{
    switch (source) {
    case MVR_ENVIRONMENT_NEUTRAL: return "neutral";
    case MVR_ENVIRONMENT_PIXELS: return "pixels";
    case MVR_ENVIRONMENT_UNIFORM: return "uniform";
    }
    return NULL;
}

const char *mvr_background_name(mvr_background background)
{
    switch (background) {
    case MVR_BACKGROUND_COLOR: return "color";
    case MVR_BACKGROUND_ENVIRONMENT: return "environment";
    case MVR_BACKGROUND_BLUR: return "blur";
    }
    return NULL;
}

/* ------------------------------------------------------------------ serials */

/* Every environment gets a new serial, so a renderer can tell a new
 * environment from an old one at the same address. The counter is the one
 * piece of static state here: it carries no configuration, only uniqueness.
 * Without C11 atomics, the scene's scheme: address and time, hashed. */
static uint64_t next_serial(const void *address)
{
#if !defined(__STDC_NO_ATOMICS__)
    static atomic_uint_fast64_t counter; /* zero-initialised: a valid atomic state (C11 7.17.2.1) */
    (void)address;
    return (uint64_t)atomic_fetch_add(&counter, 1u) + 1u;
#else
    struct timespec ts = {0, 0};
    timespec_get(&ts, TIME_UTC);
    uint64_t h = (uint64_t)(uintptr_t)address * 0x9E3779B97F4A7C15ull;
    uint64_t t = (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
    for (int i = 0; i < 8; ++i) {
        h ^= (t >> (8 * i)) & 0xFFu;
        h *= 1099511628211ull; /* FNV-1a */
    }
    return h ? h : 1u;
#endif
}

/* ------------------------------------------------------------------ helpers */

static double smoothstep(double e0, double e1, double x)
{
    double t = (x - e0) / (e1 - e0);
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return t * t * (3.0 - 2.0 * t);
}

/* sin and cos of an angle in degrees, exact at multiples of 90 (so a
 * rotation of 90 maps -Z exactly onto -X). */
static void sincos_degrees(double degrees, double *s, double *c)
{
    double r = fmod(degrees, 360.0); /* exact; in (-360, 360) */
    static const double qs[9] = {0, -1, 0, 1, 0, 1, 0, -1, 0};
    static const double qc[9] = {1, 0, -1, 0, 1, 0, -1, 0, 1};
    double q = r / 90.0;
    if (q == floor(q)) {
        int k = (int)q + 4; /* -4..4 */
        *s = qs[k];
        *c = qc[k];
        return;
    }
    double a = r * (PI / 180.0);
    *s = sin(a);
    *c = cos(a);
}

/* e = R_y(-rotation) d: x' = x cos r - z sin r, z' = x sin r + z cos r. */
static void world_to_env(const mvr_environment *env, const double d[3], double e[3])
{
    double s, c;
    sincos_degrees((double)env->rotation, &s, &c);
    e[0] = d[0] * c - d[2] * s;
    e[1] = d[1];
    e[2] = d[0] * s + d[2] * c;
}

/* Normalises v into out; false for a zero-length or non-finite vector. */
static bool unit(const double v[3], double out[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(l > 0) || !isfinite(l))
        return false;
    for (int i = 0; i < 3; ++i)
        out[i] = v[i] / l;
    return true;
}

void mvr_environment_rotation_matrix(const mvr_environment *env, float out_m3[9])
{
    double s = 0, c = 1;
    if (env)
        sincos_degrees((double)env->rotation, &s, &c);
    /* column-major: columns are the images of world x, y, z */
    const float m[9] = {(float)c, 0.0f, (float)s, 0.0f, 1.0f, 0.0f, (float)-s, 0.0f, (float)c};
    memcpy(out_m3, m, sizeof m);
}

void mvr_environment_sh_basis(const double e[3], double y[9])
{
    double x = e[0], yy = e[1], z = e[2];
    y[0] = SH_K0;
    y[1] = SH_K1 * yy;
    y[2] = SH_K1 * z;
    y[3] = SH_K1 * x;
    y[4] = SH_K2 * x * yy;
    y[5] = SH_K2 * yy * z;
    y[6] = SH_K3 * (3.0 * z * z - 1.0);
    y[7] = SH_K2 * x * z;
    y[8] = SH_K4 * (x * x - yy * yy);
}

/* ------------------------------------------------------------------ spherical harmonics */

/* Projects the stored image onto the nine basis functions, treating each
 * texel as constant radiance over its cell, and integrating every basis
 * function over every cell exactly (the integrals separate into a theta
 * and a phi factor, listed below), so the cells tile the sphere without
 * quadrature error: a constant image projects onto Y0 alone, to rounding,
 * whatever its size (an 8 x 4 uniform image included). With s = sin(theta),
 * c = cos(theta) and dOmega = s dtheta dphi:
 *   Y0: k0 s                      Y1: k1 c s
 *   Y2: -k1 s^2 cos(phi)          Y3: k1 s^2 sin(phi)
 *   Y4: k2 s^2 c sin(phi)         Y5: -k2 s^2 c cos(phi)
 *   Y6: k3 (3 s^3 cos^2(phi) - s) Y7: -k2 s^3 sin(phi) cos(phi)
 *   Y8: k4 (s^3 sin^2(phi) - c^2 s)
 * Then the irradiance is the convolution with the clamped cosine, whose
 * zonal coefficients are A0 = pi, A1 = 2pi/3, A2 = pi/4 (Ramamoorthi and
 * Hanrahan 2001, eq. 8), and diffuse = irradiance / pi. */
static bool project_sh(mvr_environment *env)
{
    const uint32_t w = env->width, h = env->height;
    /* per column: the phi integrals of 1, cos, sin, cos^2, sin^2, sin cos */
    double *col = malloc((size_t)w * 6 * sizeof *col);
    if (!col)
        return false;
    for (uint32_t i = 0; i < w; ++i) {
        double p0 = 2.0 * PI * (double)i / (double)w - PI, p1 = 2.0 * PI * (double)(i + 1) / (double)w - PI;
        double dp = p1 - p0, mid = 0.5 * (p0 + p1), half = 0.5 * dp;
        double *f = col + (size_t)i * 6;
        f[0] = dp;
        f[1] = 2.0 * cos(mid) * sin(half);             /* sin p1 - sin p0 */
        f[2] = 2.0 * sin(mid) * sin(half);             /* cos p0 - cos p1 */
        double s2 = 0.5 * cos(p0 + p1) * sin(dp);      /* (sin 2p1 - sin 2p0) / 4 */
        f[3] = 0.5 * dp + s2;
        f[4] = 0.5 * dp - s2;
        f[5] = 0.5 * sin(p0 + p1) * sin(dp);           /* (sin^2 p1 - sin^2 p0) / 2 */
    }
    double acc[9][3];
    memset(acc, 0, sizeof acc);
    for (uint32_t j = 0; j < h; ++j) {
        double t0 = PI * (double)j / (double)h, t1 = PI * (double)(j + 1) / (double)h;
        double c0 = cos(t0), c1 = cos(t1), s0 = sin(t0), s1 = sin(t1);
        double dc = 2.0 * sin(0.5 * (t0 + t1)) * sin(0.5 * (t1 - t0)); /* c0 - c1 */
        double ts = dc;                                               /* int s */
        double tcs = 0.5 * dc * (c0 + c1);                            /* int c s */
        double ts2 = 0.5 * (t1 - t0) - 0.5 * cos(t0 + t1) * sin(t1 - t0); /* int s^2 */
        double ts2c = (s1 - s0) * (s1 * s1 + s1 * s0 + s0 * s0) / 3.0;  /* int s^2 c */
        double tc2s = dc * (c0 * c0 + c0 * c1 + c1 * c1) / 3.0;         /* int c^2 s */
        double ts3 = ts - tc2s;                                         /* int s^3 */
        /* row sums of L times each phi factor */
        double r[6][3];
        memset(r, 0, sizeof r);
        const float *row = env->pixels + (size_t)j * w * 4;
        for (uint32_t i = 0; i < w; ++i) {
            const double *f = col + (size_t)i * 6;
            for (int ch = 0; ch < 3; ++ch) {
                double l = (double)row[(size_t)i * 4 + (size_t)ch];
                for (int k = 0; k < 6; ++k)
                    r[k][ch] += l * f[k];
            }
        }
        for (int ch = 0; ch < 3; ++ch) {
            acc[0][ch] += SH_K0 * ts * r[0][ch];
            acc[1][ch] += SH_K1 * tcs * r[0][ch];
            acc[2][ch] += -SH_K1 * ts2 * r[1][ch];
            acc[3][ch] += SH_K1 * ts2 * r[2][ch];
            acc[4][ch] += SH_K2 * ts2c * r[2][ch];
            acc[5][ch] += -SH_K2 * ts2c * r[1][ch];
            acc[6][ch] += SH_K3 * (3.0 * ts3 * r[3][ch] - ts * r[0][ch]);
            acc[7][ch] += -SH_K2 * ts3 * r[5][ch];
            acc[8][ch] += SH_K4 * (ts3 * r[4][ch] - tc2s * r[0][ch]);
        }
    }
    free(col);
    static const double band[9] = {1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25}; /* A_l / pi */
    for (int k = 0; k < 9; ++k)
        for (int ch = 0; ch < 3; ++ch) /* absurd radiances (near FLT_MAX) stay finite */
            env->sh[k][ch] = (float)fmax(-FLT_MAX, fmin(FLT_MAX, band[k] * acc[k][ch]));
    return true;
}

/* ------------------------------------------------------------------ the neutral studio */

/* A rectangular softbox: centred on `dir`, `half_w` x `half_h` degrees
 * (half-extents, measured as angles in its own tangent frame, width along
 * the horizontal), edges blurred by smoothstep over +-soft degrees. */
typedef struct softbox {
    double dir[3];
    double half_w, half_h, soft;
    double radiance;
} softbox;

/* The built-in studio (MVR_ENVIRONMENT_NEUTRAL): a neutral grey room lit by
 * softboxes, the kind of light a product photographer or the glTF sample
 * viewers' "neutral" environments give: every side of a model lit, none
 * black, glossy metals showing crisp rectangular highlights. Pure math, no
 * data, no randomness: the same pixels every time. All radiances are grey
 * (R = G = B). The default camera sits on +Z looking along -Z, so "front"
 * is +Z and "left" is -X.
 *
 * Room, by elevation y = d.y: a floor of 0.24 below the horizon, walls of
 * 0.5 at the horizon rising smoothly (smoothstep in y) to 0.56 straight up;
 * the floor meets the walls through a smoothstep over y in [-0.08, 0.03].
 * On top, two smooth lobes b ((1 + d.k) / 2)^2: the light the key throws
 * onto the room (0.62, towards front-upper-left) and a fainter one behind
 * (0.2). They are quadratic polynomials in d, so nine spherical harmonics
 * hold them exactly: they carry most of the directional balance of the
 * diffuse light, and the softboxes stay small, which keeps the SH irradiance
 * within 3% of the true irradiance in every direction (small bright sources
 * ring through the truncated bands: with a 28 x 24 degree key the SH was off
 * by up to 10% on the dim side).
 *
 * Softboxes (upright rectangles; half-extents in degrees, edges a
 * smoothstep over +-2 to 2.5 degrees; radiance on top of the room):
 *   key   normalize(-0.5, 0.6, 0.6)  front-upper-left   6 x 5    8.0
 *   fill  normalize(0.8, 0.1, 0.6)   front-right-low    5 x 9    2.5
 *   rim   normalize(0.25, 0.6, -0.8) behind, high       12 x 3   5.0
 * The brightest texel is 9.17 (the key over the room), the darkest 0.28.
 *
 * Measured diffuse (irradiance / pi, white Lambertian; the test prints
 * them): facing +Z 0.865, +Y 1.048, -Y 0.368, -Z 0.612, +X 0.646, -X 0.739.
 * Against a brute-force integral over every texel the SH is within 2.8%
 * (worst of 400 directions; mean 0.6%). */
static const softbox studio_boxes[] = {
    {{-0.5, 0.6, 0.6}, 6.0, 5.0, 2.0, 8.0},
    {{0.8, 0.1, 0.6}, 5.0, 9.0, 2.5, 2.5},
    {{0.25, 0.6, -0.8}, 12.0, 3.0, 2.0, 5.0},
};

/* Smooth lobes of the room: b ((1 + d.k) / 2)^2, a quadratic polynomial in
 * d, so nine spherical harmonics hold them exactly. */
typedef struct lobe {
    double dir[3];
    double radiance;
} lobe;

static const lobe studio_lobes[] = {
    {{-0.3, 0.5, 0.8}, 0.62},
    {{0.2, 0.5, -0.8}, 0.2},
};

#define STUDIO_FLOOR 0.24
#define STUDIO_WALL 0.5
#define STUDIO_CEILING 0.56

/* A softbox's frame: forward f = its direction, right r = horizontal
 * (perpendicular to f and to +Y, so boxes stand upright; world x for a box
 * straight above or below), up u = r x f; made once per image, not per
 * texel (the same values: the same arithmetic on the same inputs). */
typedef struct softbox_frame {
    bool valid;
    double f[3], r[3], u[3];
    double tan_w, tan_h;         /* beyond these |d.r| / (d.f), |d.u| / (d.f): no light at all */
} softbox_frame;

static void softbox_frame_make(const softbox *b, softbox_frame *fr)
{
    memset(fr, 0, sizeof *fr);
    double *f = fr->f, *r = fr->r;
    if (!unit(b->dir, f))
        return;
    fr->valid = true;
    r[0] = f[2], r[1] = 0.0, r[2] = -f[0];
    if (!unit(r, r))
        r[0] = 1.0, r[1] = r[2] = 0.0;
    fr->u[0] = r[1] * f[2] - r[2] * f[1];
    fr->u[1] = r[2] * f[0] - r[0] * f[2];
    fr->u[2] = r[0] * f[1] - r[1] * f[0];
    /* where the smoothstep has surely reached 1 (a tenth of a degree past
     * its edge, far beyond atan2's rounding), the box adds exactly 0 */
    fr->tan_w = tan((b->half_w + b->soft + 0.1) * (PI / 180.0));
    fr->tan_h = tan((b->half_h + b->soft + 0.1) * (PI / 180.0));
}

/* The radiance of a softbox seen along unit direction d. */
static double softbox_radiance(const softbox *b, const softbox_frame *fr, const double d[3])
{
    if (!fr->valid)
        return 0.0;
    const double *f = fr->f, *r = fr->r, *u = fr->u;
    double fd = d[0] * f[0] + d[1] * f[1] + d[2] * f[2];
    if (fd <= 0)
        return 0.0;
    double dr = d[0] * r[0] + d[1] * r[1] + d[2] * r[2], du = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    /* outside the box and its soft edge: mw or mh is exactly 0, so is the result */
    if (fabs(dr) > fd * fr->tan_w || fabs(du) > fd * fr->tan_h)
        return 0.0;
    double a = fabs(atan2(dr, fd)) * (180.0 / PI);
    double e = fabs(atan2(du, fd)) * (180.0 / PI);
    double mw = 1.0 - smoothstep(b->half_w - b->soft, b->half_w + b->soft, a);
    double mh = 1.0 - smoothstep(b->half_h - b->soft, b->half_h + b->soft, e);
    return b->radiance * mw * mh;
}

/* The studio's lights, made once per image. */
typedef struct studio_frames {
    softbox_frame boxes[MVR_ARRAY_COUNT(studio_boxes)];
    bool lobe_valid[MVR_ARRAY_COUNT(studio_lobes)];
    double lobe_dir[MVR_ARRAY_COUNT(studio_lobes)][3];
} studio_frames;

static double studio_radiance(const studio_frames *sf, const double d[3])
{
    double y = d[1];
    double upper = STUDIO_WALL + (STUDIO_CEILING - STUDIO_WALL) * smoothstep(0.0, 1.0, y);
    double l = STUDIO_FLOOR + (upper - STUDIO_FLOOR) * smoothstep(-0.08, 0.03, y);
    for (size_t k = 0; k < MVR_ARRAY_COUNT(studio_lobes); ++k) {
        const double *f = sf->lobe_dir[k];
        if (sf->lobe_valid[k]) {
            double c = 0.5 * (1.0 + d[0] * f[0] + d[1] * f[1] + d[2] * f[2]);
            l += studio_lobes[k].radiance * c * c;
        }
    }
    for (size_t k = 0; k < MVR_ARRAY_COUNT(studio_boxes); ++k)
        l += softbox_radiance(&studio_boxes[k], &sf->boxes[k], d);
    return l;
}

/* The sines and cosines of each row's theta and each column's phi are
 * computed once (w + h of each, not w * h). */
static bool fill_studio(float *px, uint32_t w, uint32_t h)
{
    double *trig = malloc(((size_t)w + h) * 2 * sizeof *trig);
    if (!trig)
        return false;
    double *col = trig, *row = trig + (size_t)w * 2;
    for (uint32_t i = 0; i < w; ++i) {
        double phi = 2.0 * PI * ((double)i + 0.5) / (double)w - PI;
        col[i * 2] = sin(phi);
        col[i * 2 + 1] = cos(phi);
    }
    for (uint32_t j = 0; j < h; ++j) {
        double theta = PI * ((double)j + 0.5) / (double)h;
        row[j * 2] = sin(theta);
        row[j * 2 + 1] = cos(theta);
    }
    studio_frames sf;
    for (size_t k = 0; k < MVR_ARRAY_COUNT(studio_boxes); ++k)
        softbox_frame_make(&studio_boxes[k], &sf.boxes[k]);
    for (size_t k = 0; k < MVR_ARRAY_COUNT(studio_lobes); ++k)
        sf.lobe_valid[k] = unit(studio_lobes[k].dir, sf.lobe_dir[k]);
    for (uint32_t j = 0; j < h; ++j) {
        double st = row[j * 2], ct = row[j * 2 + 1];
        for (uint32_t i = 0; i < w; ++i) {
            double d[3] = {st * col[i * 2], ct, -st * col[i * 2 + 1]};
            float l = (float)studio_radiance(&sf, d);
            float *p = px + ((size_t)j * w + i) * 4;
            p[0] = p[1] = p[2] = l;
            p[3] = 1.0f;
        }
    }
    free(trig);
    return true;
}

/* ------------------------------------------------------------------ caller's pixels */

/* A radiance value as stored: NaN, infinities and negatives become 0. */
static float clean(float v)
{
    return isfinite(v) && v >= 0.0f ? v : 0.0f;
}

static uint64_t count_bad(const float *src, size_t texels)
{
    uint64_t bad = 0;
    for (size_t t = 0; t < texels; ++t)
        for (size_t ch = 0; ch < 3; ++ch)
            bad += !(isfinite(src[t * 4 + ch]) && src[t * 4 + ch] >= 0.0f);
    return bad;
}

/* Box filter (exact area average in image space, linear radiance) from
 * sw x sh to dw x dh, dw <= sw and dh <= sh. Output column x covers the
 * source interval [x sw/dw, (x+1) sw/dw); measured in units of 1/dw of a
 * source texel, the overlaps are integers, so the weights are exact and sum
 * to sw (rows likewise). Alpha becomes 1. */
static bool box_filter(const float *src, uint32_t sw, uint32_t sh, float *dst, uint32_t dw, uint32_t dh)
{
    double *acc = malloc((size_t)dw * 3 * sizeof *acc); /* one output row */
    if (!acc)
        return false;
    for (uint32_t y = 0; y < dh; ++y) {
        memset(acc, 0, (size_t)dw * 3 * sizeof *acc);
        uint64_t ya = (uint64_t)y * sh, yb = (uint64_t)(y + 1) * sh; /* in units of 1/dh source rows */
        for (uint64_t r = ya / dh; r < sh && r * dh < yb; ++r) {
            uint64_t lo = r * dh > ya ? r * dh : ya, hi = (r + 1) * dh < yb ? (r + 1) * dh : yb;
            double wy = (double)(hi - lo);
            const float *srow = src + (size_t)r * sw * 4;
            for (uint32_t x = 0; x < dw; ++x) {
                uint64_t xa = (uint64_t)x * sw, xb = (uint64_t)(x + 1) * sw;
                double s[3] = {0, 0, 0};
                for (uint64_t i = xa / dw; i < sw && i * dw < xb; ++i) {
                    uint64_t l0 = i * dw > xa ? i * dw : xa, l1 = (i + 1) * dw < xb ? (i + 1) * dw : xb;
                    double wx = (double)(l1 - l0);
                    for (int ch = 0; ch < 3; ++ch)
                        s[ch] += wx * (double)clean(srow[i * 4 + (uint64_t)ch]);
                }
                for (int ch = 0; ch < 3; ++ch)
                    acc[(size_t)x * 3 + (size_t)ch] += wy * s[ch];
            }
        }
        double norm = 1.0 / ((double)sw * (double)sh);
        for (uint32_t x = 0; x < dw; ++x) {
            float *p = dst + ((size_t)y * dw + x) * 4;
            for (int ch = 0; ch < 3; ++ch)
                p[ch] = (float)(acc[(size_t)x * 3 + (size_t)ch] * norm);
            p[3] = 1.0f;
        }
    }
    free(acc);
    return true;
}

/* ------------------------------------------------------------------ create / destroy */

static mvr_result fail(mvr_error *error, const mvr_logger *logger, mvr_result r, const char *fmt, ...)
    MVR_PRINTF(4, 5);
static mvr_result fail(mvr_error *error, const mvr_logger *logger, mvr_result r, const char *fmt, ...)
{
    char message[MVR_ERROR_MESSAGE_SIZE];
    va_list ap;
    va_start(ap, fmt);
    mvr_error_record(message, sizeof message, logger, r, fmt, ap);
    va_end(ap);
    return mvr_error_set(error, r, "%s", message);
}

mvr_result mvr_environment_create(const mvr_environment_desc *desc, mvr_environment **out, mvr_error *error)
{
    if (!out)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_environment_create: out is NULL");
    *out = NULL;
    mvr_environment_desc d;
    if (desc)
        d = *desc;
    else
        memset(&d, 0, sizeof d);
    const mvr_logger *log = &d.logger;
    const char *fn = "mvr_environment_create";

    if (!mvr_environment_source_name(d.source))
        return fail(error, log, MVR_ERROR_INVALID_ARGUMENT, "%s: unknown source %d", fn, (int)d.source);
    if (!isfinite(d.intensity) || d.intensity < 0)
        return fail(error, log, MVR_ERROR_INVALID_ARGUMENT, "%s: intensity %g is not finite and >= 0", fn,
                    (double)d.intensity);
    if (!isfinite(d.rotation))
        return fail(error, log, MVR_ERROR_INVALID_ARGUMENT, "%s: rotation %g is not finite", fn,
                    (double)d.rotation);
    uint32_t spec_size = d.specular_size ? d.specular_size : 128u;
    if (spec_size < 16u || spec_size > 1024u || (spec_size & (spec_size - 1u)) != 0)
        return fail(error, log, MVR_ERROR_INVALID_ARGUMENT,
                    "%s: specular_size %u is not a power of two in 16..1024 (0 = 128)", fn, d.specular_size);
    uint32_t spec_samples = d.specular_samples ? d.specular_samples : 256u;
    if (spec_samples > 4096u)
        return fail(error, log, MVR_ERROR_INVALID_ARGUMENT, "%s: specular_samples %u is not in 1..4096 (0 = 256)",
                    fn, d.specular_samples);

    float color[3] = {1.0f, 1.0f, 1.0f};
    size_t src_texels = 0;
    uint32_t w = 0, h = 0;
    switch (d.source) {
    case MVR_ENVIRONMENT_NEUTRAL:
        w = MVR_ENVIRONMENT_NEUTRAL_WIDTH;
        h = MVR_ENVIRONMENT_NEUTRAL_HEIGHT;
        break;
    case MVR_ENVIRONMENT_UNIFORM:
        for (int i = 0; i < 3; ++i)
            if (!isfinite(d.color[i]) || d.color[i] < 0)
                return fail(error, log, MVR_ERROR_INVALID_ARGUMENT, "%s: color[%d] %g is not finite and >= 0", fn,
                            i, (double)d.color[i]);
        if (d.color[0] != 0 || d.color[1] != 0 || d.color[2] != 0)
            memcpy(color, d.color, sizeof color);
        w = UNIFORM_WIDTH;
        h = UNIFORM_HEIGHT;
        break;
    case MVR_ENVIRONMENT_PIXELS: {
        if (!d.pixels)
            return fail(error, log, MVR_ERROR_INVALID_ARGUMENT, "%s: source PIXELS with pixels NULL", fn);
        if (d.width < 1 || d.height < 1)
            return fail(error, log, MVR_ERROR_INVALID_ARGUMENT, "%s: width %u x height %u (both must be >= 1)", fn,
                        d.width, d.height);
        size_t floats, bytes;
        if (!mvr_size_mul(d.width, d.height, &src_texels) || !mvr_size_mul(src_texels, 4, &floats) ||
            !mvr_size_mul(floats, sizeof(float), &bytes))
            return fail(error, log, MVR_ERROR_INVALID_ARGUMENT,
                        "%s: width %u x height %u RGBA floats overflow the address space", fn, d.width, d.height);
        /* Larger than 2048 in either dimension: box-filtered (exact area
         * averages of linear radiance, see box_filter) to fit in 2048 x 2048
         * with the aspect ratio kept, each side rounded to the nearest
         * integer and at least 1: a 2:1 image wider than 2048 becomes
         * exactly 2048 x 1024 (as mvr.h says); 3000 x 1500 -> 2048 x 1024;
         * 4096 x 8 -> 2048 x 4; a (non-equirectangular) 1000 x 3000 ->
         * 683 x 2048. */
        w = d.width;
        h = d.height;
        if (w > MVR_ENVIRONMENT_MAX_WIDTH || h > MVR_ENVIRONMENT_MAX_HEIGHT) {
            double s = fmin((double)MVR_ENVIRONMENT_MAX_WIDTH / w, (double)MVR_ENVIRONMENT_MAX_HEIGHT / h);
            w = (uint32_t)fmax(1.0, fmin((double)MVR_ENVIRONMENT_MAX_WIDTH, floor((double)d.width * s + 0.5)));
            h = (uint32_t)fmax(1.0, fmin((double)MVR_ENVIRONMENT_MAX_HEIGHT, floor((double)d.height * s + 0.5)));
        }
        break;
    }
    }

    mvr_environment *env = calloc(1, sizeof *env);
    float *px = env ? malloc((size_t)w * h * 4 * sizeof *px) : NULL;
    if (!px) {
        free(env);
        return fail(error, log, MVR_ERROR_OUT_OF_MEMORY, "%s: out of memory (%u x %u environment)", fn, w, h);
    }
    env->source = d.source;
    env->pixels = px;
    env->width = w;
    env->height = h;
    env->intensity = d.intensity > 0 ? d.intensity : 1.0f;
    env->rotation = d.rotation;
    env->specular_size = spec_size;
    env->specular_samples = spec_samples;
    env->logger = d.logger;
    env->serial = next_serial(env);

    switch (d.source) {
    case MVR_ENVIRONMENT_NEUTRAL:
        if (!fill_studio(px, w, h)) {
            mvr_environment_destroy(env);
            return fail(error, log, MVR_ERROR_OUT_OF_MEMORY, "%s: out of memory (neutral studio)", fn);
        }
        break;
    case MVR_ENVIRONMENT_UNIFORM:
        for (size_t t = 0; t < (size_t)w * h; ++t) {
            memcpy(px + t * 4, color, sizeof color);
            px[t * 4 + 3] = 1.0f;
        }
        break;
    case MVR_ENVIRONMENT_PIXELS: {
        uint64_t bad = count_bad(d.pixels, src_texels);
        if (w == d.width && h == d.height) {
            for (size_t t = 0; t < src_texels; ++t) {
                for (size_t ch = 0; ch < 3; ++ch)
                    px[t * 4 + ch] = clean(d.pixels[t * 4 + ch]);
                px[t * 4 + 3] = 1.0f;
            }
        } else {
            if (!box_filter(d.pixels, d.width, d.height, px, w, h)) {
                mvr_environment_destroy(env);
                return fail(error, log, MVR_ERROR_OUT_OF_MEMORY, "%s: out of memory (box filter)", fn);
            }
            mvr_log(log, MVR_LOG_INFO, MVR_LOG_ID_GENERAL, "%s: %u x %u image box-filtered to %u x %u", fn,
                    d.width, d.height, w, h);
        }
        if (bad)
            mvr_log(log, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                    "%s: %llu pixel values (of %llu RGB values) were NaN, infinite or negative: set to 0", fn,
                    (unsigned long long)bad, (unsigned long long)src_texels * 3ull);
        break;
    }
    }

    if (!project_sh(env)) {
        mvr_environment_destroy(env);
        return fail(error, log, MVR_ERROR_OUT_OF_MEMORY, "%s: out of memory (spherical harmonics)", fn);
    }
    *out = env;
    if (error) {
        error->result = MVR_OK;
        error->message[0] = '\0';
    }
    return MVR_OK;
}

void mvr_environment_destroy(mvr_environment *env)
{
    if (!env)
        return;
    free(env->pixels);
    free(env);
}

/* ------------------------------------------------------------------ settings */

/* A value the setters refuse leaves the setting as it was and logs an error
 * through the environment's logger (the setters have no result). */
void mvr_environment_set_intensity(mvr_environment *env, float intensity)
{
    if (!env)
        return;
    if (!isfinite(intensity) || intensity < 0) {
        mvr_log(&env->logger, MVR_LOG_ERROR, MVR_LOG_ID_ERROR_RESULT,
                "mvr_environment_set_intensity: %g is not finite and >= 0; intensity stays %g", (double)intensity,
                (double)env->intensity);
        return;
    }
    env->intensity = intensity > 0 ? intensity : 1.0f;
}

void mvr_environment_set_rotation(mvr_environment *env, float degrees)
{
    if (!env)
        return;
    if (!isfinite(degrees)) {
        mvr_log(&env->logger, MVR_LOG_ERROR, MVR_LOG_ID_ERROR_RESULT,
                "mvr_environment_set_rotation: %g is not finite; rotation stays %g", (double)degrees,
                (double)env->rotation);
        return;
    }
    env->rotation = degrees;
}

float mvr_environment_intensity(const mvr_environment *env)
{
    return env ? env->intensity : 0.0f;
}

float mvr_environment_rotation(const mvr_environment *env)
{
    return env ? env->rotation : 0.0f;
}

/* ------------------------------------------------------------------ lookups */

/* A NULL environment, or a zero-length or non-finite direction, gives 0. */
void mvr_environment_diffuse(const mvr_environment *env, const double n[3], double out_rgb[3])
{
    if (!out_rgb)
        return;
    out_rgb[0] = out_rgb[1] = out_rgb[2] = 0.0;
    double u[3], e[3], y[9];
    if (!env || !n || !unit(n, u))
        return;
    world_to_env(env, u, e);
    mvr_environment_sh_basis(e, y);
    for (int ch = 0; ch < 3; ++ch) {
        double s = 0;
        for (int k = 0; k < 9; ++k)
            s += (double)env->sh[k][ch] * y[k];
        out_rgb[ch] = s * (double)env->intensity;
    }
}

void mvr_environment_radiance(const mvr_environment *env, const double d[3], double out_rgb[3])
{
    if (!out_rgb)
        return;
    out_rgb[0] = out_rgb[1] = out_rgb[2] = 0.0;
    double u[3], e[3];
    if (!env || !d || !unit(d, u))
        return;
    world_to_env(env, u, e);
    double cu = 0.5 + atan2(e[0], -e[2]) / (2.0 * PI);
    double cv = acos(fmax(-1.0, fmin(1.0, e[1]))) / PI;
    const uint32_t w = env->width, h = env->height;
    /* texel centres at (i + 0.5) / w: wrap in u, clamp in v */
    double x = cu * w - 0.5, yv = cv * h - 0.5;
    double fx = floor(x), fy = floor(yv);
    double ax = x - fx, ay = yv - fy;
    long long ix = (long long)fx % (long long)w;
    if (ix < 0)
        ix += w;
    uint32_t i0 = (uint32_t)ix, i1 = (i0 + 1u) % w;
    uint32_t j0, j1;
    if (fy < 0) {
        j0 = j1 = 0;
        ay = 0;
    } else if (fy >= (double)(h - 1u)) {
        j0 = j1 = h - 1u;
        ay = 0;
    } else {
        j0 = (uint32_t)fy;
        j1 = j0 + 1u;
    }
    const float *p00 = env->pixels + ((size_t)j0 * w + i0) * 4, *p10 = env->pixels + ((size_t)j0 * w + i1) * 4;
    const float *p01 = env->pixels + ((size_t)j1 * w + i0) * 4, *p11 = env->pixels + ((size_t)j1 * w + i1) * 4;
    for (int ch = 0; ch < 3; ++ch) {
        /* a + t (b - a): exact where a == b, so a uniform image reads exactly */
        double top = (double)p00[ch] + ax * ((double)p10[ch] - (double)p00[ch]);
        double bot = (double)p01[ch] + ax * ((double)p11[ch] - (double)p01[ch]);
        out_rgb[ch] = (top + ay * (bot - top)) * (double)env->intensity;
    }
}
