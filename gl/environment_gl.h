/* Image-based lighting on the GPU (gl/environment.c); core/environment.h
 * holds the environment itself. */
#ifndef MVR_ENVIRONMENT_GL_H
#define MVR_ENVIRONMENT_GL_H

#include "context_internal.h"
#include "program_cache.h"

/* An environment prefiltered for this renderer (gl/environment.c): made
 * when a render meets an environment whose serial differs, kept until then. */
typedef struct mvr_gpu_environment {
    uint64_t serial;             /* the environment's pixels these are of; 0 = none */
    GLuint source;               /* cube map RGBA16F with mips: the sharp background, the prefilter's input */
    uint32_t source_size, source_levels;
    GLuint specular;             /* cube map RGBA16F: level k = GGX of roughness k / (levels - 1) */
    uint32_t specular_size, specular_levels;
    GLuint cube_sampler;         /* trilinear, clamped */
    GLuint dfg;                  /* the DFG table, RG16F, once per renderer */
    GLuint dfg_sampler;
    /* KHR_materials_sheen, only for a frame with sheen: */
    GLuint charlie;              /* cube map RGBA16F, as specular: level k = Charlie of sheen roughness
                                    k / (levels - 1) */
    uint64_t charlie_serial;     /* the environment it is of; 0 = none */
    GLuint sheen_lut;            /* the sheen albedo table (core/sheen_lut.c), RG16F, once per renderer */
} mvr_gpu_environment;


/* Prefilters a new environment (nothing when it is the one
 * already prefiltered, or NULL); binds its maps for the mesh programs; sets
 * a program's environment uniforms; draws the background of one pass (its
 * views: num_views multiview, 0 = one view at view_base) after the opaque
 * geometry; releases the maps. */
/* sheen: also the Charlie chain (a frame with KHR_materials_sheen) */
mvr_result mvr_environment_sync(mvr_renderer *r, const mvr_environment *env, bool sheen);
void mvr_environment_bind(mvr_renderer *r, bool reference);
/* Whether a frame with this environment must prefilter first. */
bool mvr_environment_stale(const mvr_renderer *r, const mvr_environment *env, bool sheen);
/* KHR_materials_sheen: the albedo table (made once) and, with an
 * environment, the Charlie cube map, on their units. */
mvr_result mvr_sheen_lut_sync(mvr_renderer *r);
void mvr_sheen_bind(mvr_renderer *r, bool environment);
void mvr_environment_set_uniforms(mvr_renderer *r, const mvr_program_entry *e, const mvr_environment *env,
                                  uint32_t samples);
mvr_result mvr_environment_draw_background(mvr_renderer *r, const mvr_render_desc *desc, uint32_t num_views,
                                           int32_t view_base, bool srgb_output, float exposure);
void mvr_environment_release(mvr_renderer *r);
/* The luminance of a white Lambertian surface, averaged over directions. */
double mvr_environment_average_diffuse(const mvr_environment *env);

#endif
