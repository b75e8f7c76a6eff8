/* KHR_materials_sheen on the CPU: the sheen BRDF (the same formulas as
 * shaders/material_sheen.glsl's MVR_SHEEN code, here in double: the tests'
 * reference) and the table the shader reads, once per renderer.
 *
 * The sheen BRDF (KHR_materials_sheen, "BRDF"; the Khronos glTF Sample
 * Renderer's BRDF_specularSheen) is
 *   f_sheen(l, v) = sheen color * D(h) * V(l, v),
 * with the "Charlie" distribution of Estevez and Kulla, "Production Friendly
 * Microfacet Sheen BRDF" (Sony Pictures Imageworks, 2017), eq. 2, of
 * alpha = sheen roughness^2:
 *   D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi),
 * and their visibility (section 3, "the non-physical term" of the paper is
 * replaced by the fitted Smith-style masking): Lambda(cos theta) from the
 * five-parameter fit
 *   L(x) = a / (1 + b x^c) + d x + e   (a..e interpolated between the
 *   paper's two columns (alpha 0 and 1) by (1 - alpha)^2),
 *   Lambda(cos) = exp(L(cos)) for cos < 0.5, exp(2 L(0.5) - L(1 - cos)) else,
 *   V = 1 / ((1 + Lambda(n.v) + Lambda(n.l)) 4 (n.v) (n.l)), clamped to [0, 1]
 * (the spec's "Sheen visibility" with the terminator softening left out, as
 * the Sample Renderer's V_Sheen does).
 *
 * The table, size x size texels, x = n.v and y = sheen roughness at texel
 * centres ((i + 0.5) / size), two channels:
 *   R: E(n.v, r) = integral over the hemisphere of D(h) V(l, v) (n.l) dl,
 *      the sheen lobe's directional albedo of a white sheen color. The spec
 *      ("Albedo scaling") scales the layer below by 1 - max(sheen color) E:
 *      1 - max(color) E(n.v) for the environment, the smaller of that at n.v
 *      and at n.l for a light, as the Sample Renderer does (its lut_sheen_E
 *      table holds the same integral);
 *   G: the split sum's second factor for the sheen lobe under the
 *      environment (Karis 2013's split sum, the Charlie-prefiltered cube
 *      map being the first), as the Sample Renderer's "Charlie LUT"
 *      defines it: the same integral with the visibility of Neubelt and
 *      Pettineo, "Crafting a Next-Gen Material Pipeline for The Order:
 *      1886" (SIGGRAPH 2013 course), V = 1 / (4 (n.l + n.v - (n.l)(n.v))),
 *      clamped to [0, 1], and D as above.
 * Each is integrated deterministically by the midpoint rule over
 * (cos theta_l, phi_l), 64 x 32 cells over the half hemisphere on one side
 * of the plane of n and v (the integrand is symmetric about it), doubled:
 * within 1e-3 of a 512 x 256 grid at every texel checked (roughness 0.1 to
 * 1, n.v 0.1 to 0.9), about 0.1 s for a 32 x 32 table.
 * The table is a pure function of its size. */
#include <math.h>

#include "environment.h"

#define PI 3.14159265358979323846
#define LUT_COS_CELLS 64u
#define LUT_PHI_CELLS 32u

double mvr_sheen_d_charlie(double roughness, double n_dot_h)
{
    double alpha = roughness * roughness;
    if (alpha < 1e-6)
        alpha = 1e-6;
    double inv = 1.0 / alpha;
    double sin2 = 1.0 - n_dot_h * n_dot_h;
    if (sin2 < 0.0)
        sin2 = 0.0;
    return (2.0 + inv) * pow(sin2, 0.5 * inv) / (2.0 * PI);
}

/* Estevez and Kulla 2017, table 1 fit (alpha 0 and 1 columns). */
static double lambda_fit(double x, double alpha)
{
    double t = (1.0 - alpha) * (1.0 - alpha);
    double a = 21.5473 + (25.3245 - 21.5473) * t;
    double b = 3.82987 + (3.32435 - 3.82987) * t;
    double c = 0.19823 + (0.16801 - 0.19823) * t;
    double d = -1.97760 + (-1.27393 + 1.97760) * t;
    double e = -4.32054 + (-4.85967 + 4.32054) * t;
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}

static double lambda_sheen(double cos_theta, double alpha)
{
    if (fabs(cos_theta) < 0.5)
        return exp(lambda_fit(cos_theta, alpha));
    return exp(2.0 * lambda_fit(0.5, alpha) - lambda_fit(1.0 - cos_theta, alpha));
}

double mvr_sheen_visibility(double roughness, double n_dot_l, double n_dot_v)
{
    double alpha = roughness * roughness;
    if (alpha < 1e-6)
        alpha = 1e-6;
    double v = 1.0 / ((1.0 + lambda_sheen(n_dot_v, alpha) + lambda_sheen(n_dot_l, alpha)) * (4.0 * n_dot_v * n_dot_l));
    return v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
}

static double visibility_neubelt(double n_dot_l, double n_dot_v)
{
    double v = 1.0 / (4.0 * (n_dot_l + n_dot_v - n_dot_l * n_dot_v));
    return v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
}

void mvr_sheen_albedo(double n_dot_v, double roughness, double out[2])
{
    double nv = n_dot_v < 1e-4 ? 1e-4 : n_dot_v > 1.0 ? 1.0 : n_dot_v;
    double vx = sqrt(1.0 - nv * nv); /* v = (vx, 0, nv), n = +z */
    double e = 0.0, g = 0.0;
    for (uint32_t i = 0; i < LUT_COS_CELLS; ++i) {
        double nl = ((double)i + 0.5) / (double)LUT_COS_CELLS;
        double sl = sqrt(1.0 - nl * nl);
        double vis_n = visibility_neubelt(nl, nv);
        double vis_s = mvr_sheen_visibility(roughness, nl, nv);
        for (uint32_t k = 0; k < LUT_PHI_CELLS; ++k) {
            double phi = PI * ((double)k + 0.5) / (double)LUT_PHI_CELLS;
            /* h = (l + v) / |l + v| */
            double hx = sl * cos(phi) + vx, hy = sl * sin(phi), hz = nl + nv;
            double len = sqrt(hx * hx + hy * hy + hz * hz);
            double d = mvr_sheen_d_charlie(roughness, hz / len);
            e += d * vis_s * nl;
            g += d * vis_n * nl;
        }
    }
    /* dl = d(cos theta) d(phi); both halves of the hemisphere */
    double cell = 2.0 * (1.0 / (double)LUT_COS_CELLS) * (PI / (double)LUT_PHI_CELLS);
    out[0] = e * cell;
    out[1] = g * cell;
}

bool mvr_sheen_lut(uint32_t size, float *out_rg)
{
    if (!out_rg || size < 1 || size > 256)
        return false;
    for (uint32_t j = 0; j < size; ++j) {
        double roughness = ((double)j + 0.5) / (double)size;
        for (uint32_t i = 0; i < size; ++i) {
            double eg[2];
            mvr_sheen_albedo(((double)i + 0.5) / (double)size, roughness, eg);
            float *o = out_rg + ((size_t)j * size + i) * 2;
            o[0] = (float)eg[0];
            o[1] = (float)eg[1];
        }
    }
    return true;
}
