/* The renderer's programs (gl/program_cache.c): one compiled program per
 * shader variant, looked up by the passes. */
#ifndef MVR_PROGRAM_CACHE_H
#define MVR_PROGRAM_CACHE_H

#include "program.h"

/* One compiled shader variant. */
typedef struct mvr_program_entry {
    mvr_shader_variant variant;
    GLuint program;
    GLint loc_view_base, loc_ambient, loc_exposure;
    GLint loc_output_alpha_cutoff;   /* outputs-only variants */
    float output_alpha_cutoff;       /* its value set (NaN: none yet) */
    GLint loc_layer_base, loc_factor, loc_post_exposure, loc_clear_depth, loc_clear_out;  /* composite programs */
    GLint loc_env_sh, loc_env_rotation, loc_env_intensity, loc_env_max_lod; /* mesh (IBL), background */
    GLint loc_face_base, loc_face_size, loc_equirect_lod, loc_roughness, loc_samples, loc_source_size,
        loc_source_max_lod;      /* environment programs */
    GLint loc_depth_range, loc_background_lod; /* background programs */
    GLint loc_env_samples;       /* mesh, the IBL reference */
    GLint loc_deform_info;       /* pre-skinning */
    GLint loc_transmission_base, loc_transmission_rect, loc_transmission_lod; /* mesh, transmission */
    uint64_t transmission_serial; /* the copy whose uniforms are set */
    int32_t view_base;           /* last value set (INT32_MIN = unknown) */
    uint64_t frame_serial;       /* frame whose per-frame uniforms are set */
    bool from_binary;            /* linked from the binary cache */
} mvr_program_entry;

/* A mesh variant as this renderer's blocks lay out: features, views (0 =
 * loop), its material table and per-draw block sizes; no lights. */
mvr_shader_variant mvr_mesh_variant(const mvr_renderer *r, uint32_t features, uint32_t num_views);

/* Program of a variant, compiled on first use. */
mvr_result mvr_program_cache_get(mvr_renderer *r, const mvr_shader_variant *v, mvr_program_entry **out);

/* Deletes every program (mvr_gl_delete); the entries stay until
 * mvr_program_cache_free. */
void mvr_program_cache_release(mvr_renderer *r);
void mvr_program_cache_free(mvr_renderer *r);

#endif
