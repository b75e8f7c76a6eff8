/*
 * mvr: environments: image-based lighting.
 *
 * Part of the public C API; include <mvr/mvr.h>, whose conventions apply.
 */
#ifndef MVR_ENVIRONMENT_API_H
#define MVR_ENVIRONMENT_API_H

#include "mvr/mvr_base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ environments
 *
 * Image-based lighting: radiance arriving from every direction, as an
 * equirectangular image (latitude-longitude, linear RGB radiance), the
 * built-in neutral studio, or one uniform radiance. An environment is CPU
 * data (no GL): a renderer prefilters it on the GPU once, the first time it
 * renders with it (and again only when its pixels change), and every view of
 * every later frame reads the same maps (mvr_frame_stats.env_prefilter_passes
 * is 0 on those frames).
 *
 * Directions: glTF's world, +Y up. The image's top row is +Y, its bottom
 * row -Y; its centre column looks along -Z (what a glTF camera with no
 * rotation sees), its right quarter along +X: a direction d maps to
 * u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi (v = 0: top row).
 * rotation turns the environment about +Y, counter-clockwise seen from
 * above (so +90 brings what was at -Z to -X).
 *
 * Diffuse light is the irradiance of the environment in third-order
 * spherical harmonics (9 coefficients per channel, Ramamoorthi and
 * Hanrahan 2001), projected on the CPU in double precision when the
 * environment is created; specular light is the split-sum approximation
 * (Karis 2013): a GGX-prefiltered cube map chain (one roughness per level,
 * the Khronos glTF Sample Renderer's mapping lod = roughness * (levels - 1))
 * and a DFG lookup table computed once per renderer.
 */
typedef struct mvr_environment mvr_environment;

typedef enum mvr_environment_source {
    MVR_ENVIRONMENT_NEUTRAL = 0, /* the built-in studio: procedural, deterministic, no data shipped */
    MVR_ENVIRONMENT_PIXELS,      /* an equirectangular image in memory */
    MVR_ENVIRONMENT_UNIFORM      /* one radiance from every direction (the white furnace) */
} mvr_environment_source;
const char *mvr_environment_source_name(mvr_environment_source source);

typedef struct mvr_environment_desc {
    mvr_environment_source source;
    /* PIXELS: width * height RGBA floats, linear radiance, rows top first
     * (alpha ignored). Copied: the caller keeps its memory. Images larger
     * than 2048 either way are box-filtered (in linear light, exact area
     * weights) to fit 2048 x 2048, keeping their aspect (4096 x 2048 ->
     * 2048 x 1024). NaN, infinite and negative values become 0 (a warning). */
    const float *pixels;
    uint32_t width, height;
    float color[3];              /* UNIFORM: radiance; all 0 = (1, 1, 1) */
    float intensity;             /* multiplies the radiance; 0 = 1 */
    float rotation;              /* degrees about +Y */
    uint32_t specular_size;      /* prefiltered cube face size, a power of two 16..1024; 0 = 128 */
    /* GGX samples per texel of the prefilter, 1..4096; 0 = 256. Against the
     * Khronos glTF Sample Renderer under a sky with a small sun (radiance
     * 50 in a 4-degree disc: tests/io/test_peers.cpp), 64 samples differ by
     * RMSE 4.4/255, 256 by 2.6/255, for ~80 ms more prefilter on llvmpipe. */
    uint32_t specular_samples;
    mvr_logger logger;
} mvr_environment_desc;

mvr_result mvr_environment_create(const mvr_environment_desc *desc, mvr_environment **out, mvr_error *out_error);
/* NULL is fine. A renderer that used it keeps its maps until it renders
 * with another environment or is destroyed. */
void mvr_environment_destroy(mvr_environment *environment);
/* Intensity (0 = 1) and rotation (degrees) change without prefiltering again. */
void mvr_environment_set_intensity(mvr_environment *environment, float intensity);
void mvr_environment_set_rotation(mvr_environment *environment, float degrees);
float mvr_environment_intensity(const mvr_environment *environment);
float mvr_environment_rotation(const mvr_environment *environment);

/* The irradiance the spherical harmonics give a surface facing world
 * direction n, divided by pi (so a white Lambertian surface's radiance),
 * intensity and rotation applied. */
void mvr_environment_diffuse(const mvr_environment *environment, const double n[3], double out_rgb[3]);
/* The radiance arriving from world direction d (bilinear in the stored
 * image), intensity and rotation applied. */
void mvr_environment_radiance(const mvr_environment *environment, const double d[3], double out_rgb[3]);

#ifdef __cplusplus
}
#endif
#endif /* MVR_ENVIRONMENT_API_H */
