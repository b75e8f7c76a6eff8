/*
 * Shader permutations: a variant (program, feature bits, view count, light
 * counts) becomes GLSL ES 3.00 source by prepending #version, the multiview
 * extension and #defines to the embedded files. Backend-free: the GL backend
 * compiles what this produces, and tests/shaders validates every variant the
 * library can generate with glslangValidator.
 */
#ifndef MVR_SHADER_GEN_H
#define MVR_SHADER_GEN_H

#include <stdbool.h>
#include <stdint.h>

#include "core_util.h"

typedef enum mvr_shader_stage {
    MVR_SHADER_STAGE_VERTEX = 0,
    MVR_SHADER_STAGE_FRAGMENT,
    MVR_SHADER_STAGE_COUNT
} mvr_shader_stage;

typedef enum mvr_program_kind {
    MVR_PROGRAM_MESH = 0,   /* scene geometry, metallic-roughness PBR */
    MVR_PROGRAM_COMPOSITE,  /* full-screen copy of one array layer per view */
    MVR_PROGRAM_ENVIRONMENT, /* environment prefiltering: a cube map level, six faces as six views */
    MVR_PROGRAM_BACKGROUND, /* the environment behind the scene, per view, at the far plane */
    MVR_PROGRAM_PRESKIN,    /* skinning and morphing once per frame, into a transform feedback buffer */
    MVR_PROGRAM_KIND_COUNT
} mvr_program_kind;

/* Feature bits of the mesh program; each compiles code in with a #define.
 * (Macros, not an enum: bit 31 is not an int, which C11 enumerators must be.) */
#define MVR_FEATURE_NORMALS (1u << 0)       /* vertex normals (else face normals) */
#define MVR_FEATURE_TANGENTS (1u << 1)      /* vertex tangents (else derived) */
#define MVR_FEATURE_UV0 (1u << 2)
#define MVR_FEATURE_UV1 (1u << 3)
#define MVR_FEATURE_COLOR0 (1u << 4)        /* vertex colors */
#define MVR_FEATURE_BASE_COLOR_TEX (1u << 5)
#define MVR_FEATURE_METAL_ROUGH_TEX (1u << 6)
#define MVR_FEATURE_NORMAL_TEX (1u << 7)
#define MVR_FEATURE_OCCLUSION_TEX (1u << 8)
#define MVR_FEATURE_EMISSIVE_TEX (1u << 9)
#define MVR_FEATURE_TEXTURE_TRANSFORM (1u << 10)
#define MVR_FEATURE_ALPHA_MASK (1u << 11)
#define MVR_FEATURE_ALPHA_BLEND (1u << 12)
#define MVR_FEATURE_DOUBLE_SIDED (1u << 13)
#define MVR_FEATURE_UNLIT (1u << 14)
#define MVR_FEATURE_MATERIAL_ARRAYS (1u << 15) /* texture arrays + layer index (batcher path) */
#define MVR_FEATURE_SRGB_OUTPUT (1u << 16)  /* shader encodes sRGB (UNORM targets) */
#define MVR_FEATURE_SHADOWS (1u << 17)      /* lights read shadow map layers (PCF) */
#define MVR_FEATURE_LIGHT_MASKS (1u << 18)  /* per-view light masks (render layers) */
#define MVR_FEATURE_SHADOW_CASTER (1u << 19) /* depth only: the shadow map pass (alpha test at most) */
#define MVR_FEATURE_IBL (1u << 20)          /* image-based lighting from a prefiltered environment */
#define MVR_FEATURE_IBL_REFERENCE (1u << 21) /* with IBL: the environment integrated per pixel (ground truth) */
#define MVR_FEATURE_SKIN (1u << 22)         /* skinning in the vertex stage, four influences (JOINTS_0) */
#define MVR_FEATURE_SKIN8 (1u << 23)        /* with SKIN: eight influences (JOINTS_1) */
#define MVR_FEATURE_MORPH (1u << 24)        /* morph targets in the vertex stage */
#define MVR_FEATURE_SPECULAR (1u << 25)     /* KHR_materials_ior / _specular: the dielectric's F0 and weight */
#define MVR_FEATURE_CLEARCOAT (1u << 26)    /* KHR_materials_clearcoat */
#define MVR_FEATURE_SHEEN (1u << 27)        /* KHR_materials_sheen */
#define MVR_FEATURE_TRANSMISSION (1u << 28) /* KHR_materials_transmission (+ _volume, _dispersion) */
#define MVR_FEATURE_IRIDESCENCE (1u << 29)  /* KHR_materials_iridescence */
#define MVR_FEATURE_ANISOTROPY (1u << 30)   /* KHR_materials_anisotropy */
#define MVR_FEATURE_SPEC_GLOSS (1u << 31)   /* KHR_materials_pbrSpecularGlossiness */
/* every bit of the 32 is taken: a further feature needs a wider key */
#define MVR_MESH_FEATURE_ALL_ 0xFFFFFFFFu

/* What the pre-skinning program does: the mesh bits it shares (same
 * #defines: NORMALS, TANGENTS, SKIN, SKIN8, MORPH). */
#define MVR_DEFORM_FEATURES (MVR_FEATURE_SKIN | MVR_FEATURE_SKIN8 | MVR_FEATURE_MORPH)
#define MVR_PRESKIN_FEATURES (MVR_FEATURE_NORMALS | MVR_FEATURE_TANGENTS | MVR_DEFORM_FEATURES)

#define MVR_TEXTURE_FEATURES                                                                        \
    (MVR_FEATURE_BASE_COLOR_TEX | MVR_FEATURE_METAL_ROUGH_TEX | MVR_FEATURE_NORMAL_TEX |                \
     MVR_FEATURE_OCCLUSION_TEX | MVR_FEATURE_EMISSIVE_TEX)

/* Feature bits of the composite program. */
typedef enum mvr_composite_feature {
    MVR_FEATURE_SRGB_ENCODE = 1u << 0,      /* exact piecewise sRGB encode on output */
    MVR_FEATURE_DOWNSAMPLE = 1u << 1,       /* box-filter factor x factor texels (supersampling resolve) */
    MVR_FEATURE_POST = 1u << 2,             /* exposure and tone mapping of an HDR source */
    MVR_FEATURE_POST_ACES = 1u << 3,        /* tone mapper: ACES (Hill's fit) */
    MVR_FEATURE_POST_PBR_NEUTRAL = 1u << 4, /* tone mapper: Khronos PBR Neutral */
    MVR_FEATURE_DITHER = 1u << 5,
    MVR_FEATURE_LOG_LUMINANCE = 1u << 6,    /* log2 luminance (auto-exposure reduction) */
    MVR_FEATURE_POST_MSAA = 1u << 7,        /* the post pass reads a multisampled array (GLSL ES 3.20) */
    MVR_COMPOSITE_FEATURE_ALL_ = (1u << 8) - 1u
} mvr_composite_feature;

/* Feature bits of the environment program (none: equirectangular image ->
 * cube map faces). */
typedef enum mvr_environment_feature {
    MVR_FEATURE_ENV_GGX = 1u << 0,          /* GGX prefilter of the source cube map (one roughness) */
    MVR_FEATURE_ENV_CHARLIE = 1u << 1,      /* the Charlie (sheen) prefilter instead (one sheen roughness) */
    MVR_ENVIRONMENT_FEATURE_ALL_ = (1u << 2) - 1u
} mvr_environment_feature;

/* Feature bits of the background program. */
typedef enum mvr_background_feature {
    MVR_FEATURE_BACKGROUND_SRGB_OUTPUT = 1u << 0, /* shader encodes sRGB (UNORM targets), as the mesh's */
    MVR_BACKGROUND_FEATURE_ALL_ = (1u << 1) - 1u
} mvr_background_feature;

/* Extra outputs of the mesh program (mvr_shader_variant.outputs): each an
 * extra colour attachment of the view pass (location = attachment), written
 * at the end of the fragment stage (gl/targets.c allocates them). */
#define MVR_SHADER_OUT_GEOMETRY (1u << 0) /* location 1, RGBA32F: depth along -Z, ray distance, coverage */
#define MVR_SHADER_OUT_NORMAL (1u << 1)   /* location 2, RGBA32F: unit normal, world space */
#define MVR_SHADER_OUT_IDS (1u << 2)      /* location 3, RGBA32UI: node, mesh, material, primitive */
#define MVR_SHADER_OUT_NORMAL_CAMERA (1u << 3) /* with NORMAL: in the view's camera space */
/* the blended draws' outputs pass: no lighting, no colour; alpha below the
 * cutoff uniform discards (the front-most surface above it is recorded) */
#define MVR_SHADER_OUT_ONLY (1u << 4)
#define MVR_SHADER_OUT_ALL_ ((1u << 5) - 1u)

#define MVR_SHADER_MAX_LIGHTS_PER_TYPE 8
#define MVR_SHADER_MAX_SHADOW_LAYERS 16

typedef struct mvr_shader_variant {
    mvr_program_kind program;
    uint32_t features;      /* the program's feature bits (mvr_mesh_feature, mvr_composite_feature, ...) */
    uint32_t num_views;     /* 0: loop path (view index uniform); n >= 1: multiview, num_views = n */
    uint8_t directional_lights, point_lights, spot_lights;  /* mesh only */
    uint16_t material_capacity; /* materials per table block (mesh); 0 = 64 */
    uint16_t draw_capacity;     /* per-draw blocks in the draw block, indexed by gl_InstanceID
                                   (instancing; mesh); 0 = 1 */
    uint16_t draw_stride;       /* bytes between per-draw blocks: 144 (std140 size of the block),
                                   or more where the GL's uniform offset alignment asks (padding
                                   makes the array's stride match); 0 = 144 */
    uint8_t outputs;            /* MVR_SHADER_OUT_* (mesh only; 0 = colour alone) */
} mvr_shader_variant;

#define MVR_SHADER_DEFAULT_MATERIAL_CAPACITY 64
#define MVR_SHADER_MAX_MATERIAL_CAPACITY 1024
/* 144-byte per-draw blocks in GLES 3.0's smallest GL_MAX_UNIFORM_BLOCK_SIZE (16 KiB) */
#define MVR_SHADER_MAX_DRAW_CAPACITY 113

const char *mvr_program_kind_name(mvr_program_kind kind);
const char *mvr_shader_stage_name(mvr_shader_stage stage);
/* The #define name of one feature bit of a program; NULL when the bit is not one. */
const char *mvr_shader_feature_define(mvr_program_kind program, uint32_t bit);
uint32_t mvr_shader_feature_mask(mvr_program_kind program);

/* Checks a variant against the generator's limits; writes why not into why[why_size]. */
bool mvr_shader_variant_valid(const mvr_shader_variant *variant, char *why, size_t why_size);

/* Appends the full source of one stage of a variant. Returns false (and writes
 * why) for an invalid variant or a missing embedded file. */
bool mvr_shader_source(const mvr_shader_variant *variant, mvr_shader_stage stage,
                       mvr_str_builder *out, char *why, size_t why_size);

/* A short stable name of a variant, e.g. "mesh-mv6-f00a3-l1.0.0". */
void mvr_shader_variant_name(const mvr_shader_variant *variant, char *out, size_t size);

/*
 * The validation set: every program with no feature, each feature alone, and
 * all features together (the combination of all bits the program allows), on
 * the loop path and with multiview at 1, 2 and max_views views, with and
 * without lights. Call with index 0, 1, ... until it returns false.
 */
bool mvr_shader_variant_enumerate(unsigned index, uint32_t max_views, mvr_shader_variant *out);

#endif
