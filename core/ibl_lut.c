/* The DFG lookup table of the split-sum approximation (Karis 2013, "Real
 * Shading in Unreal Engine 4", SIGGRAPH course notes), as the Khronos glTF
 * Sample Renderer computes it (source/shaders/ibl_filtering.frag, LUT()),
 * here on the CPU in double.
 *
 * The specular BRDF is f(l, v) = D(h) Vis(l, v) F(v.h), with GGX
 * D(h) = a^2 / (pi ((n.h)^2 (a^2 - 1) + 1)^2), a = roughness^2, and the
 * height-correlated Smith visibility (Heitz 2014, "Understanding the
 * Masking-Shadowing Function in Microfacet-Based BRDFs"; the form of
 * Filament and the Sample Renderer)
 *   Vis = G2 / (4 n.l n.v)
 *       = 0.5 / (n.l sqrt((n.v)^2 (1 - a^2) + a^2) + n.v sqrt((n.l)^2 (1 - a^2) + a^2)).
 * With Schlick's F = F0 + (1 - F0) Fc, Fc = (1 - v.h)^5, so
 * F = F0 (1 - Fc) + Fc, the directional albedo splits into
 *   E_ss = integral f (n.l) dl = F0 * A + B,
 *   A = integral D Vis (1 - Fc) (n.l) dl,   B = integral D Vis Fc (n.l) dl.
 * Sampling h with pdf D(h) (n.h) (GGX importance sampling: cos theta_h =
 * sqrt((1 - xi) / (1 + (a^2 - 1) xi)), phi = 2 pi xi') and reflecting v
 * about h gives l with pdf D (n.h) / (4 v.h) (the reflection Jacobian,
 * Walter et al. 2007), so each sample contributes
 *   D Vis (n.l) / pdf = Vis (n.l) 4 (v.h) / (n.h) = G_vis,
 * and A = (1/N) sum (1 - Fc) G_vis, B = (1/N) sum Fc G_vis, over N
 * Hammersley points (xi' = k/N, xi = the base-2 radical inverse of k).
 * Samples with n.l <= 0 contribute nothing.
 *
 * The table is a pure function of (size, samples): a renderer computes it
 * once and uploads it as an RG texture sampled at (NdotV, roughness). */
#include <math.h>
#include <stdlib.h>

#include "environment.h"

#define PI 3.14159265358979323846

/* Van der Corput radical inverse in base 2 of k, in [0, 1). */
static double radical_inverse(uint32_t k)
{
    k = (k << 16) | (k >> 16);
    k = ((k & 0x55555555u) << 1) | ((k & 0xAAAAAAAAu) >> 1);
    k = ((k & 0x33333333u) << 2) | ((k & 0xCCCCCCCCu) >> 2);
    k = ((k & 0x0F0F0F0Fu) << 4) | ((k & 0xF0F0F0F0u) >> 4);
    k = ((k & 0x00FF00FFu) << 8) | ((k & 0xFF00FF00u) >> 8);
    return (double)k * (1.0 / 4294967296.0);
}

static double saturate(double x)
{
    return x < 0 ? 0 : x > 1 ? 1 : x;
}

bool mvr_ibl_dfg_lut(uint32_t size, uint32_t samples, float *out_rg)
{
    if (!out_rg || size < 1 || size > 4096 || samples < 1 || samples > 65536)
        return false;
    /* per sample: cos phi and xi (roughness-independent); then, per
     * roughness row, h.x, h.z and 4 / n.h. v has no y component, so h.y
     * never enters: v.h = v.x h.x + v.z h.z. */
    double *buf = malloc((size_t)samples * 5 * sizeof *buf);
    if (!buf)
        return false;
    double *pre = buf, *hv = buf + (size_t)samples * 2;
    for (uint32_t k = 0; k < samples; ++k) {
        pre[k * 2 + 0] = cos(2.0 * PI * ((double)k / (double)samples));
        pre[k * 2 + 1] = radical_inverse(k);
    }
    for (uint32_t j = 0; j < size; ++j) {
        double roughness = ((double)j + 0.5) / (double)size;
        double alpha = roughness * roughness, a2 = alpha * alpha;
        for (uint32_t k = 0; k < samples; ++k) {
            double xi = pre[k * 2 + 1];
            double ct = saturate(sqrt((1.0 - xi) / (1.0 + (a2 - 1.0) * xi))); /* > 0: xi < 1 */
            double st = sqrt(1.0 - ct * ct);
            hv[k * 3 + 0] = st * pre[k * 2 + 0];
            hv[k * 3 + 1] = ct;
            hv[k * 3 + 2] = 4.0 / ct;
        }
        for (uint32_t i = 0; i < size; ++i) {
            double nv = ((double)i + 0.5) / (double)size;
            double vx = sqrt(1.0 - nv * nv), vz = nv; /* v = (sin, 0, cos), n = +z */
            double ggxv_root = sqrt(nv * nv * (1.0 - a2) + a2);
            double a = 0, b = 0;
            for (uint32_t k = 0; k < samples; ++k) {
                const double *h = hv + (size_t)k * 3;
                double vh = vx * h[0] + vz * h[1];
                double nl = 2.0 * vh * h[1] - vz; /* l = reflect(-v, h) = 2 (v.h) h - v; n.l <= 1 */
                if (nl <= 0)
                    continue; /* also every v.h <= 0 (then n.l < 0) */
                /* Vis = G2 / (4 n.l n.v), height-correlated Smith for GGX */
                double vis = 0.5 / (nl * ggxv_root + nv * sqrt(nl * nl * (1.0 - a2) + a2));
                double g_vis = vis * nl * fmin(vh, 1.0) * h[2]; /* Vis 4 (n.l) (v.h) / (n.h) */
                double t = 1.0 - fmin(vh, 1.0), t2 = t * t, fc = t2 * t2 * t; /* (1 - v.h)^5 */
                a += (1.0 - fc) * g_vis;
                b += fc * g_vis;
            }
            a /= (double)samples;
            b /= (double)samples;
            /* The exact A + B never exceeds 1 (a single-scattering BRDF
             * conserves energy), but the estimate can, by ~1e-4 near
             * roughness 0 with 512 samples: scale such a texel back to 1 so
             * the table never creates energy (in float too). */
            if (a + b > 1.0) {
                double s = 1.0 / (a + b);
                a *= s;
                b *= s;
            }
            float fa = (float)a, fb = (float)b;
            while ((double)fa + (double)fb > 1.0) /* float rounding, at most a step or two */
                fa = nextafterf(fa, 0.0f);
            float *o = out_rg + ((size_t)j * size + i) * 2;
            o[0] = fa;
            o[1] = fb;
        }
    }
    free(buf);
    return true;
}
