/* The std140 layout table of the uniform blocks (block_layout.h): what the
 * packing code's offsets are checked against and what the shaders' block
 * declarations are generated from. The comments say what each member holds
 * (the generated GLSL carries the names only). */
#include <string.h>

#include "block_layout.h"
#include "core_util.h"

#define MEMBER(name, type, offset) {name, MVR_STD140_##type, offset, MEMBER_SIZE_##type, 1u, 0u, MEMBER_MSTRIDE_##type}
#define ARRAY(name, type, offset, count, stride) \
    {name, MVR_STD140_##type, offset, MEMBER_SIZE_##type, count, stride, MEMBER_MSTRIDE_##type}
#define MEMBER_SIZE_VEC4 16u
#define MEMBER_SIZE_IVEC4 16u
#define MEMBER_SIZE_UVEC4 16u
#define MEMBER_SIZE_MAT4 64u
#define MEMBER_MSTRIDE_VEC4 0u
#define MEMBER_MSTRIDE_IVEC4 0u
#define MEMBER_MSTRIDE_UVEC4 0u
#define MEMBER_MSTRIDE_MAT4 16u

/* The view set of a pass (shaders/views.glsl). Matrices are relative to the
 * view set's origin (camera-relative precision: the CPU subtracts the origin
 * in double before narrowing to float). */
static const mvr_block_member views_members[] = {
    ARRAY("mvr_view_proj", MAT4, MVR_VIEWS_VIEW_PROJ_OFFSET, MVR_VIEWS_PER_BLOCK, MVR_VIEW_MATRIX_SIZE),
    /* xyz relative to the origin */
    ARRAY("mvr_eye_position", VEC4, MVR_VIEWS_EYE_POSITION_OFFSET, MVR_VIEWS_PER_BLOCK, MVR_VIEW_EYE_SIZE),
    /* x: bit i set = light i shines in the view */
    ARRAY("mvr_view_info", IVEC4, MVR_VIEWS_VIEW_INFO_OFFSET, MVR_VIEWS_PER_BLOCK, MVR_VIEW_INFO_SIZE),
    /* world (relative) to camera; sent only for extra outputs */
    ARRAY("mvr_view_matrix", MAT4, MVR_VIEWS_VIEW_MATRIX_OFFSET, MVR_VIEWS_PER_BLOCK, MVR_VIEW_MATRIX_SIZE),
};
/* One per draw (shaders/mesh.vert.glsl); an instanced draw reads
 * consecutive ones by gl_InstanceID. */
static const mvr_block_member draw_members[] = {
    MEMBER("model", MAT4, MVR_DRAW_MODEL_OFFSET), /* relative to the view origin */
    /* inverse-transpose of the model's upper 3x3 (columns) */
    ARRAY("normal_matrix", VEC4, MVR_DRAW_NORMAL_MATRIX_OFFSET, 3u, 16u),
    MEMBER("ids", UVEC4, MVR_DRAW_IDS_OFFSET), /* node, mesh, material, primitive (the extra outputs' IDs) */
    /* x: material index; y: joint texel base (< 0: not skinned); z: morph
     * header texel (< 0: no targets); w: morph delta base */
    MEMBER("info", IVEC4, MVR_DRAW_INFO_OFFSET),
};
/* One per material of a table page (shaders/surface.glsl); 480 bytes in
 * std140, whatever the features. */
static const mvr_block_member material_members[] = {
    MEMBER("base_color_factor", VEC4, MVR_MATERIAL_BASE_COLOR_OFFSET),
    MEMBER("emissive", VEC4, MVR_MATERIAL_EMISSIVE_OFFSET), /* rgb: emissive factor * strength, a: alpha cutoff */
    /* x: metallic, y: roughness (spec-gloss: glossiness), z: normal scale,
     * w: occlusion strength */
    MEMBER("params", VEC4, MVR_MATERIAL_PARAMS_OFFSET),
    /* per texture role: its array layer, 16 bits each (mvr_layer) */
    ARRAY("layers", IVEC4, MVR_MATERIAL_LAYERS_OFFSET, MVR_MATERIAL_LAYERS_COUNT, 16u),
    /* xyz: per role 4 bits (TEXCOORD_1, transform slot); w: bit per role
     * with a texture (mvr_uv, mvr_has_texture) */
    MEMBER("uv", IVEC4, MVR_MATERIAL_UV_OFFSET),
    /* per transform slot: two rows of a 2x3 affine (KHR_texture_transform) */
    ARRAY("uv_transform", VEC4, MVR_MATERIAL_UV_TRANSFORM_OFFSET, MVR_MATERIAL_UV_TRANSFORM_COUNT,
          MVR_MATERIAL_UV_TRANSFORM_STRIDE),
    /* rgb: dielectric F0 (KHR_materials_ior x _specular color, unclamped),
     * a: specular weight */
    MEMBER("specular", VEC4, MVR_MATERIAL_SPECULAR_OFFSET),
    /* factor, roughness, F0, normal scale (KHR_materials_clearcoat) */
    MEMBER("clearcoat", VEC4, MVR_MATERIAL_CLEARCOAT_OFFSET),
    MEMBER("sheen", VEC4, MVR_MATERIAL_SHEEN_OFFSET), /* rgb: color, a: roughness (KHR_materials_sheen) */
    /* factor, thickness, attenuation distance (0: none), dispersion */
    MEMBER("transmission", VEC4, MVR_MATERIAL_TRANSMISSION_OFFSET),
    MEMBER("volume", VEC4, MVR_MATERIAL_VOLUME_OFFSET),           /* rgb: attenuation color, a: ior */
    MEMBER("iridescence", VEC4, MVR_MATERIAL_IRIDESCENCE_OFFSET), /* factor, ior, thickness minimum, maximum (nm) */
    MEMBER("anisotropy", VEC4, MVR_MATERIAL_ANISOTROPY_OFFSET),   /* strength, cos and sin of the rotation */
};
/* One per light (shaders/lights.glsl): directional, then point, then spot. */
static const mvr_block_member light_members[] = {
    /* xyz relative to the view origin; w: range (0 = infinite) */
    MEMBER("position_range", VEC4, MVR_LIGHT_POSITION_RANGE_OFFSET),
    MEMBER("direction", VEC4, MVR_LIGHT_DIRECTION_OFFSET), /* xyz: direction the light points to (unit) */
    MEMBER("color", VEC4, MVR_LIGHT_COLOR_OFFSET),         /* rgb: color * intensity */
    MEMBER("spot", VEC4, MVR_LIGHT_SPOT_OFFSET),           /* x: angle scale, y: angle offset (KHR_lights_punctual) */
};
/* The shadow maps' (shaders/shadows.glsl). */
static const mvr_block_member shadows_members[] = {
    /* world (relative to the origin) -> (u, v, depth) */
    ARRAY("mvr_shadow_matrix", MAT4, MVR_SHADOWS_MATRIX_OFFSET, MVR_SHADOWS_LAYERS, MVR_SHADOWS_MATRIX_STRIDE),
    /* x: texel size (world; perspective: per unit of distance), y: 1 =
     * perspective, z: normal bias in texels, w: 1 / map size */
    ARRAY("mvr_shadow_params", VEC4, MVR_SHADOWS_PARAMS_OFFSET, MVR_SHADOWS_LAYERS, MVR_SHADOWS_PARAMS_STRIDE),
    /* x: first layer, y: layers (0 = no shadow) */
    ARRAY("mvr_light_shadow", IVEC4, MVR_SHADOWS_LIGHT_OFFSET, MVR_SHADOWS_LIGHTS, MVR_SHADOWS_LIGHT_STRIDE),
};

/* The draw struct ends in MVR_DRAW_PAD vec4s where the GL's uniform offset
 * alignment spaces blocks further apart than its 144 bytes (256 on many
 * desktop GPUs): its std140 array stride then equals the ring's. */
static const mvr_block_layout block_layouts[] = {
    {"mvr_views", NULL, MVR_VIEWS_BLOCK_SIZE, views_members, MVR_ARRAY_COUNT(views_members), NULL, NULL, NULL},
    {"mvr_draw", "mvr_draws", MVR_DRAW_BLOCK_SIZE, draw_members, MVR_ARRAY_COUNT(draw_members), "mvr_draw_data",
     "MVR_DRAW_CAPACITY", "MVR_DRAW_PAD"},
    {"mvr_materials", "mvr_material_table", MVR_MATERIAL_BLOCK_SIZE, material_members,
     MVR_ARRAY_COUNT(material_members), "mvr_material", "MVR_MAX_MATERIALS", NULL},
    {"mvr_lights", "mvr_light_list", MVR_LIGHT_BLOCK_SIZE, light_members, MVR_ARRAY_COUNT(light_members),
     "mvr_light", "MVR_LIGHT_COUNT", NULL},
    {"mvr_shadows", NULL, MVR_SHADOWS_BLOCK_SIZE, shadows_members, MVR_ARRAY_COUNT(shadows_members), NULL, NULL,
     NULL},
};

const mvr_block_layout *mvr_block_layouts(uint32_t *count)
{
    *count = (uint32_t)MVR_ARRAY_COUNT(block_layouts);
    return block_layouts;
}

const mvr_block_layout *mvr_block_layout_find(const char *block)
{
    for (size_t i = 0; i < MVR_ARRAY_COUNT(block_layouts); ++i)
        if (strcmp(block_layouts[i].block, block) == 0)
            return &block_layouts[i];
    return NULL;
}
