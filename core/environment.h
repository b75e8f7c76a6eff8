/* Environments (image-based lighting), the CPU side: the stored
 * equirectangular radiance, its irradiance in spherical harmonics, the
 * rotation, and the split-sum DFG table. Backend-free: the GL backend reads
 * these fields to prefilter and to fill its uniforms. */
#ifndef MVR_CORE_ENVIRONMENT_H
#define MVR_CORE_ENVIRONMENT_H

#include <stdbool.h>
#include <stdint.h>

#include "mvr/mvr.h"

/* The size of the built-in neutral studio (MVR_ENVIRONMENT_NEUTRAL). */
#define MVR_ENVIRONMENT_NEUTRAL_WIDTH 512u
#define MVR_ENVIRONMENT_NEUTRAL_HEIGHT 256u
/* PIXELS images are box-filtered to fit in this many columns and rows. */
#define MVR_ENVIRONMENT_MAX_WIDTH 2048u
#define MVR_ENVIRONMENT_MAX_HEIGHT 2048u

struct mvr_environment {
    mvr_environment_source source;
    float *pixels;              /* RGBA float equirectangular, rows top first (+Y first), linear radiance,
                                   intensity NOT applied; alpha is 1 */
    uint32_t width, height;
    float sh[9][3];             /* coefficients c_i (per channel) with diffuse(e) = sum_i c_i * Y_i(e):
                                   irradiance / pi, intensity NOT applied, e in environment space (unrotated) */
    float intensity;            /* resolved: never 0 */
    float rotation;             /* degrees */
    uint32_t specular_size, specular_samples; /* resolved defaults (128, 256) */
    uint64_t serial;            /* a new value for every environment created (process-unique) */
    mvr_logger logger;
};

/* Rotation: world direction d sees environment direction e = R_y(-rotation) d,
 * R_y standard right-handed (x' = x cos a + z sin a, z' = -x sin a + z cos a).
 * Multiples of 90 degrees are exact (sin and cos are 0 or +-1). */
void mvr_environment_rotation_matrix(const mvr_environment *env, float out_m3[9]); /* column-major mat3 mapping
                                                                                      world d -> e, for a GLSL
                                                                                      mat3 uniform */

/* The real SH basis in this order and with these constants (the shader
 * evaluates the same):
 *   Y0 = 0.282095; Y1 = 0.488603*y; Y2 = 0.488603*z; Y3 = 0.488603*x;
 *   Y4 = 1.092548*x*y; Y5 = 1.092548*y*z; Y6 = 0.315392*(3z^2-1);
 *   Y7 = 1.092548*x*z; Y8 = 0.546274*(x^2-y^2).
 * (Full precision: 1/(2 sqrt(pi)), sqrt(3/(4pi)), sqrt(15/(4pi)),
 * sqrt(5/(16pi)), sqrt(15/(16pi)).) Writes the nine values for a unit
 * direction e. */
void mvr_environment_sh_basis(const double e[3], double out_y[9]);

/* DFG lookup table of the split-sum approximation (Karis 2013, "Real Shading
 * in Unreal Engine 4"), as the Khronos glTF Sample Renderer defines it:
 * texel (i, j) of a size x size table is at NdotV = (i + 0.5)/size,
 * roughness = (j + 0.5)/size (perceptual roughness; alpha = roughness^2), and
 * holds (A, B) with E_ss = F0 * A + B for GGX with height-correlated Smith
 * visibility, integrated in double with `samples` Hammersley GGX importance
 * samples. out_rg: size*size*2 floats, row j = roughness. False (nothing
 * written) for a NULL out_rg, size outside 1..4096 or samples outside
 * 1..65536. */
bool mvr_ibl_dfg_lut(uint32_t size, uint32_t samples, float *out_rg);

/* KHR_materials_sheen (core/sheen_lut.c, where the formulas are cited): the
 * Charlie distribution D(h) of a sheen roughness, the sheen visibility
 * V(l, v), and the sheen lobe's directional albedo at n.v: out[0] with V
 * (the albedo scaling's E), out[1] with Neubelt and Pettineo's visibility
 * (the environment's split-sum factor). */
double mvr_sheen_d_charlie(double roughness, double n_dot_h);
double mvr_sheen_visibility(double roughness, double n_dot_l, double n_dot_v);
void mvr_sheen_albedo(double n_dot_v, double roughness, double out[2]);
/* The table of mvr_sheen_albedo at texel centres: x = n.v, y = sheen
 * roughness; out_rg: size*size*2 floats, row j = roughness. False (nothing
 * written) for a NULL out_rg or size outside 1..256. */
bool mvr_sheen_lut(uint32_t size, float *out_rg);

#endif
