/* Programs: compile and link one shader variant from core/shader_gen. */
#ifndef MVR_PROGRAM_H
#define MVR_PROGRAM_H

#include "context_internal.h"
#include "material.h"
#include "shader_gen.h"

/* Uniform block binding points, fixed for every program. */
enum {
    MVR_BLOCK_VIEWS = 0,
    MVR_BLOCK_DRAW = 1,
    MVR_BLOCK_MATERIALS = 2,
    MVR_BLOCK_LIGHTS = 3,
    MVR_BLOCK_SHADOWS = 4
};

/* Texture units of the material roles and of the composite source. */
enum {
    MVR_UNIT_BASE_COLOR = 0,
    MVR_UNIT_METAL_ROUGH = 1,
    MVR_UNIT_NORMAL = 2,
    MVR_UNIT_OCCLUSION = 3,
    MVR_UNIT_EMISSIVE = 4,
    MVR_UNIT_SHADOW_MAP = 5,
    MVR_UNIT_ENV_SPECULAR = 6,   /* mesh: the prefiltered cube map */
    MVR_UNIT_ENV_DFG = 7,        /* mesh: the DFG table */
    MVR_UNIT_ENV_BACKGROUND = 8, /* background: the cube map it shows (its own unit: the
                                    mesh draws after it in the pass keep theirs) */
    MVR_UNIT_ANIM_DATA = 9,      /* mesh and pre-skinning vertex stages: joints and morph weights */
    MVR_UNIT_MORPH_DELTAS = 10,  /* mesh and pre-skinning vertex stages: morph target deltas */
    MVR_UNIT_EXTENSION_ROLES = 11, /* mesh: the extensions' texture roles, 11 + role - 5 (to 23) */
    MVR_UNIT_TRANSMISSION = 24,  /* mesh: the opaque colour behind transmissive surfaces */
    MVR_UNIT_ENV_CHARLIE = 25,   /* mesh (KHR_materials_sheen): the Charlie-prefiltered cube map */
    MVR_UNIT_SHEEN_LUT = 26,     /* mesh (KHR_materials_sheen): the sheen albedo table */
    MVR_UNIT_COMPOSITE_SOURCE = 0,
    MVR_UNIT_COMPOSITE_DEPTH = 1,
    MVR_UNIT_ENV_INPUT = 0       /* environment program: the equirect image or the source cube */
};

/* The texture unit of a material texture role (core/material.h). */
static inline GLint mvr_role_unit(uint32_t role)
{
    return role < MVR_CORE_ROLE_COUNT ? (GLint)role : (GLint)(MVR_UNIT_EXTENSION_ROLES + role - MVR_CORE_ROLE_COUNT);
}

/* glDeleteProgram, after glUseProgram(0) where the program is current (a
 * deleted current program lives on under a name the driver may reuse). */
void mvr_gl_delete_program(const mvr_gl_api_table *gl, GLuint program);

/* Builds the variant into a linked program with its blocks and samplers bound.
 * On failure ctx's last error holds the compile / link log. On success the
 * new program is left current (callers with a state cache record that). */
mvr_result mvr_gl_program_build(mvr_context *ctx, const mvr_shader_variant *variant,
                                GLuint *out_program);

typedef struct mvr_program_build_info {
    GLuint program;
    bool from_binary;       /* linked from the binary cache, nothing compiled */
    bool binary_rejected;   /* a cache entry was there but corrupt, stale or refused */
    bool binary_stored;     /* compiled, and the binary written to the cache */
    bool binary_store_failed; /* storing failed, or the key file is unsafe (cache off) */
    char why[512];          /* what was wrong with a rejected entry, or why storing failed */
} mvr_program_build_info;

/* The GL's identity in cache keys: API, vendor, renderer and version strings
 * (a driver update changes it, so old entries go stale). */
void mvr_gl_driver_identity(const mvr_context *ctx, char *out, size_t size);

/* mvr_gl_program_build with a program binary cache in cache_dir (NULL or ""
 * = none; also none where the driver offers no binary format). An entry is
 * used only after its checks pass and the driver accepts it; otherwise the
 * variant is compiled and the entry rewritten. */
mvr_result mvr_gl_program_build_cached(mvr_context *ctx, const mvr_shader_variant *variant, const char *cache_dir,
                                       mvr_program_build_info *info);

/* Builds a variant on ctx and deletes it again: a check that the driver
 * accepts it (tests). */
mvr_result mvr_context_check_shader_variant(mvr_context *ctx, const mvr_shader_variant *variant);

#endif
