/*
 * std140 layouts of the uniform blocks the C side writes: every member's
 * offset, named here and listed once in mvr_block_layouts() (core/block_layout.c),
 * which tests/gl/test_block_layouts.c compares with what the GL reports for
 * every shader variant that declares the block. The packing code uses these
 * names only: no offset is spelled anywhere else, and the shaders' block
 * declarations are generated from the same table (core/shader_gen.c: a
 * "#mvr_block NAME" line of a shaders/ file), so the two cannot drift.
 */
#ifndef MVR_BLOCK_LAYOUT_H
#define MVR_BLOCK_LAYOUT_H

#include <stdint.h>

#include "shader_gen.h"

/* mvr_draw (shaders/mesh.vert.glsl): an array of struct mvr_draw_data, one per
 * draw, spaced the GL's uniform offset alignment apart (padding vec4s) */
#define MVR_DRAW_MODEL_OFFSET 0u          /* mat4 model */
#define MVR_DRAW_NORMAL_MATRIX_OFFSET 64u /* vec4 normal_matrix[3]: the columns of a mat3 */
#define MVR_DRAW_IDS_OFFSET 112u          /* uvec4 ids: node, mesh, material, primitive (extra outputs;
                                             node / mesh / material id, 0 = the default material;
                                             primitive: its index in the mesh + 1) */
#define MVR_DRAW_INFO_OFFSET 128u         /* ivec4 info; x: material index; y, z, w: deform.glsl's
                                             joint base, morph header, morph delta base (-1: none) */
#define MVR_DRAW_BLOCK_SIZE 144u          /* the struct without padding */

/* mvr_materials (shaders/surface.glsl): an array of struct mvr_material.
 * Per texture role r (core/material.h): its array layer is 16 bits of
 * layers[r / 8][(r / 2) % 4] (the high half for odd r); its uv field is
 * 4 bits of uv[r / 8] at bit 4 * (r % 8) (bit 0: TEXCOORD_1, bits 1-3: the
 * transform slot, whose two rows are uv_transform[2 * slot], [2 * slot + 1]);
 * bit r of uv.w: the material has a texture in the role. */
#define MVR_MATERIAL_BASE_COLOR_OFFSET 0u     /* vec4 base_color_factor */
#define MVR_MATERIAL_EMISSIVE_OFFSET 16u      /* vec4 emissive: rgb factor * strength, a: alpha cutoff */
#define MVR_MATERIAL_PARAMS_OFFSET 32u        /* vec4 params: metallic, roughness (spec-gloss: glossiness),
                                                 normal scale, occlusion strength */
#define MVR_MATERIAL_LAYERS_OFFSET 48u        /* ivec4 layers[3] */
#define MVR_MATERIAL_LAYERS_COUNT 3u
#define MVR_MATERIAL_UV_OFFSET 96u            /* ivec4 uv */
#define MVR_MATERIAL_UV_TRANSFORM_OFFSET 112u /* vec4 uv_transform[16] */
#define MVR_MATERIAL_UV_TRANSFORM_COUNT 16u   /* two rows per transform slot */
#define MVR_MATERIAL_UV_TRANSFORM_STRIDE 16u
#define MVR_MATERIAL_SPECULAR_OFFSET 368u     /* vec4 specular: rgb dielectric F0, a: specular weight */
#define MVR_MATERIAL_CLEARCOAT_OFFSET 384u    /* vec4 clearcoat: factor, roughness, F0, normal scale */
#define MVR_MATERIAL_SHEEN_OFFSET 400u        /* vec4 sheen: rgb color, a roughness */
#define MVR_MATERIAL_TRANSMISSION_OFFSET 416u /* vec4 transmission: factor, thickness, attenuation
                                                 distance (0: none), dispersion */
#define MVR_MATERIAL_VOLUME_OFFSET 432u       /* vec4 volume: rgb attenuation color, a ior */
#define MVR_MATERIAL_IRIDESCENCE_OFFSET 448u  /* vec4 iridescence: factor, ior, thickness min, max (nm) */
#define MVR_MATERIAL_ANISOTROPY_OFFSET 464u   /* vec4 anisotropy: strength, cos, sin of the rotation */
#define MVR_MATERIAL_BLOCK_SIZE 480u

/* mvr_lights (shaders/lights.glsl): an array of struct mvr_light */
#define MVR_LIGHT_POSITION_RANGE_OFFSET 0u /* vec4 position_range */
#define MVR_LIGHT_DIRECTION_OFFSET 16u     /* vec4 direction */
#define MVR_LIGHT_COLOR_OFFSET 32u         /* vec4 color */
#define MVR_LIGHT_SPOT_OFFSET 48u          /* vec4 spot */
#define MVR_LIGHT_BLOCK_SIZE 64u

/* mvr_views (shaders/views.glsl): four arrays of MVR_VIEWS_PER_BLOCK (the
 * view matrices are sent only for extra outputs) */
#define MVR_VIEWS_PER_BLOCK 64u       /* MVR_MAX_VIEWS of the shaders */
#define MVR_VIEW_MATRIX_SIZE 64u      /* array stride of mat4 mvr_view_proj[] */
#define MVR_VIEW_EYE_SIZE 16u         /* array stride of vec4 mvr_eye_position[] */
#define MVR_VIEW_INFO_SIZE 16u        /* array stride of ivec4 mvr_view_info[] */
#define MVR_VIEWS_VIEW_PROJ_OFFSET 0u
#define MVR_VIEWS_EYE_POSITION_OFFSET (MVR_VIEWS_VIEW_PROJ_OFFSET + MVR_VIEWS_PER_BLOCK * MVR_VIEW_MATRIX_SIZE)
#define MVR_VIEWS_VIEW_INFO_OFFSET (MVR_VIEWS_EYE_POSITION_OFFSET + MVR_VIEWS_PER_BLOCK * MVR_VIEW_EYE_SIZE)
#define MVR_VIEWS_VIEW_MATRIX_OFFSET (MVR_VIEWS_VIEW_INFO_OFFSET + MVR_VIEWS_PER_BLOCK * MVR_VIEW_INFO_SIZE)
#define MVR_VIEWS_BLOCK_SIZE (MVR_VIEWS_VIEW_MATRIX_OFFSET + MVR_VIEWS_PER_BLOCK * MVR_VIEW_MATRIX_SIZE)

/* mvr_shadows (shaders/shadows.glsl, MVR_SHADOWS): per layer, per light */
#define MVR_SHADOWS_LAYERS MVR_SHADER_MAX_SHADOW_LAYERS        /* MVR_MAX_SHADOW_LAYERS */
#define MVR_SHADOWS_LIGHTS (3u * MVR_SHADER_MAX_LIGHTS_PER_TYPE) /* MVR_MAX_LIGHTS */
#define MVR_SHADOWS_MATRIX_STRIDE 64u /* mat4 mvr_shadow_matrix[] */
#define MVR_SHADOWS_PARAMS_STRIDE 16u /* vec4 mvr_shadow_params[] */
#define MVR_SHADOWS_LIGHT_STRIDE 16u  /* ivec4 mvr_light_shadow[] */
#define MVR_SHADOWS_MATRIX_OFFSET 0u
#define MVR_SHADOWS_PARAMS_OFFSET (MVR_SHADOWS_MATRIX_OFFSET + MVR_SHADOWS_LAYERS * MVR_SHADOWS_MATRIX_STRIDE)
#define MVR_SHADOWS_LIGHT_OFFSET (MVR_SHADOWS_PARAMS_OFFSET + MVR_SHADOWS_LAYERS * MVR_SHADOWS_PARAMS_STRIDE)
#define MVR_SHADOWS_BLOCK_SIZE (MVR_SHADOWS_LIGHT_OFFSET + MVR_SHADOWS_LIGHTS * MVR_SHADOWS_LIGHT_STRIDE)

typedef enum mvr_std140_type {
    MVR_STD140_VEC4 = 0,
    MVR_STD140_IVEC4,
    MVR_STD140_UVEC4,
    MVR_STD140_MAT4   /* column-major, matrix stride 16 */
} mvr_std140_type;

/* One member of a block (or of the struct its one array holds). */
typedef struct mvr_block_member {
    const char *name;       /* GLSL name */
    mvr_std140_type type;
    uint32_t offset;        /* from the start of the block, or of the struct element */
    uint32_t size;          /* bytes of one element */
    uint32_t array_size;    /* 1: not an array */
    uint32_t array_stride;  /* bytes between array elements; 0: not an array */
    uint32_t matrix_stride; /* bytes between matrix columns; 0: not a matrix */
} mvr_block_member;

typedef struct mvr_block_layout {
    const char *block;      /* GLSL block name, e.g. "mvr_materials" */
    const char *element;    /* the block's one member, an array of this struct
                               (its length set per shader variant); NULL: the
                               members are the block's own */
    uint32_t size;          /* std140 size of the struct (element) or of the block */
    const mvr_block_member *members;
    uint32_t member_count;
    /* what the GLSL declaration needs beyond the offsets (the generator's) */
    const char *struct_name;   /* the element's struct type, e.g. "mvr_material"; NULL without element */
    const char *element_count; /* GLSL macro of the element array's length, e.g. "MVR_MAX_MATERIALS" */
    const char *padding;       /* GLSL macro: vec4s of padding that end the struct (NULL: none) */
} mvr_block_layout;

/* The uniform blocks C writes: views, draw, materials, lights, shadows. */
const mvr_block_layout *mvr_block_layouts(uint32_t *count);
/* One of them by its GLSL block name; NULL when the table has no such block. */
const mvr_block_layout *mvr_block_layout_find(const char *block);

#endif
