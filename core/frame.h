/*
 * Frame preparation, backend-free: world transforms in double, the draw list
 * (sorted per pass), per-draw blocks (model relative to the view set's origin,
 * narrowed to float), the lights, and the material table, all packed in the
 * std140 layouts of shaders/mesh.*.glsl. The GL backend uploads these bytes.
 */
#ifndef MVR_FRAME_H
#define MVR_FRAME_H

#include "batch_plan.h"
#include "view_set.h"
#include "scene_internal.h"
#include "shader_gen.h"

/*
 * std140 layouts of the uniform blocks the C side writes: every member's
 * offset, named here and listed once in mvr_block_layouts() (below), which
 * tests/gl/test_block_layouts.c compares with what the GL reports for every
 * shader variant that declares the block. The packing code uses these names
 * only: no offset is spelled anywhere else.
 */

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

/* mvr_materials (shaders/mesh.frag.glsl): an array of struct mvr_material.
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

/* mvr_lights (shaders/mesh.frag.glsl): an array of struct mvr_light */
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

/* mvr_shadows (shaders/mesh.frag.glsl, MVR_SHADOWS): per layer, per light */
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
} mvr_block_layout;

/* The uniform blocks C writes: views, draw, materials, lights, shadows. */
const mvr_block_layout *mvr_block_layouts(uint32_t *count);

typedef enum mvr_pass_kind {
    MVR_PASS_OPAQUE = 0,
    MVR_PASS_MASK,
    MVR_PASS_BLEND,
    MVR_PASS_KIND_COUNT
} mvr_pass_kind;

typedef struct mvr_draw {
    uint32_t primitive;          /* scene primitive index */
    uint32_t material;           /* scene material index, MVR_NO_INDEX = default */
    uint32_t features;           /* mesh feature bits this draw needs */
    uint32_t block;              /* its per-draw block in mvr_frame.draw_blocks: after the sort
                                    its position in draws (blocks are packed in draw order);
                                    before it, creation order (the sort's last tiebreak) */
    uint32_t node;               /* scene node whose world matrix places it */
    uint32_t material_page;      /* which block-sized page of the material table it reads */
    uint64_t group_key;          /* texture arrays it binds (array path; 0 otherwise) */
    mvr_pass_kind pass;
    bool mirrored;               /* negative determinant: front faces wind clockwise */
    float depth;                 /* distance from the origin to its bounds' center */
    double center[3];            /* world bounding sphere, relative to the origin */
    double radius;
    uint32_t deform;             /* its entry in mvr_frame.deforms, or MVR_NO_INDEX */
} mvr_draw;

/* The per-frame deformation data (shaders/deform.glsl): RGBA32F texels in
 * rows of 2^MVR_DEFORM_WIDTH_LOG2, joint matrices of every skin drawn then
 * every morphed draw's active weights; uploaded once per frame for every
 * view. */
#define MVR_DEFORM_WIDTH_LOG2 10u
#define MVR_DEFORM_TEXELS_PER_JOINT 7u

/* One skinned or morphed (node, primitive): what the pre-skinning pass
 * runs once per frame, and what the vertex path reads per draw. */
typedef struct mvr_deform {
    uint32_t node, primitive;
    int32_t joint_base;          /* texel of the skin's joint 0, or -1 */
    int32_t morph_base;          /* texel of its morph header, or -1 */
    int32_t delta_base;          /* its primitive's first delta texel */
    uint32_t features;           /* SKIN, SKIN8, MORPH, NORMALS, TANGENTS (the pre-skinning variant) */
    uint32_t active_targets;
} mvr_deform;

/* What shadows and light masks need of a light, in the order of the light
 * blocks (directional, point, spot). */
typedef struct mvr_frame_light {
    mvr_light_type type;
    mvr_dvec3 position;          /* relative to the origin */
    mvr_dvec3 direction;         /* unit, the way the light points */
    double range;                /* 0 = infinite */
    double outer_cone_angle;     /* spot */
    bool cast_shadows;
    uint32_t layers;             /* render layers (never 0: 0 means all) */
    double peak;                 /* intensity times the color's largest channel (lux or candela) */
} mvr_frame_light;

typedef struct mvr_frame {
    mvr_draw *draws;
    uint32_t draw_count, draw_cap;
    uint32_t pass_first[MVR_PASS_KIND_COUNT], pass_count[MVR_PASS_KIND_COUNT];
    uint32_t transmissive_draws; /* in the blend list: they sample the opaque views (KHR_materials_transmission) */
    uint8_t *draw_blocks;        /* draw_count blocks, block_stride apart */
    size_t draw_blocks_cap;
    uint32_t block_stride;
    uint8_t light_blocks[3 * MVR_SHADER_MAX_LIGHTS_PER_TYPE * MVR_LIGHT_BLOCK_SIZE];
    uint32_t light_counts[3];    /* directional, point, spot (blocks in that order) */
    uint32_t lights_dropped;     /* beyond MVR_SHADER_MAX_LIGHTS_PER_TYPE of a type */
    mvr_frame_light lights[3 * MVR_SHADER_MAX_LIGHTS_PER_TYPE];
    mvr_dmat4 *world;
    uint32_t world_cap;
    /* skins and morph targets */
    mvr_deform *deforms;
    uint32_t deform_count, deform_cap;
    float *deform_data;          /* deform_texels * 4 floats */
    uint32_t deform_texels;
    size_t deform_data_cap;      /* floats */
    mvr_dmat4 *joint_world;      /* every drawn skin's joint matrices (double, not relative) */
    uint32_t joint_world_cap;
    uint32_t *skin_first;        /* per scene skin: its first joint in joint_world, or MVR_NO_INDEX */
    uint32_t skin_first_cap;
    uint32_t joints;             /* joint matrices in deform_data */
    uint32_t morph_active;       /* non-zero weights summed over morphed draws */
    /* set before mvr_frame_build: the pre-skinning path takes deformation
     * out of the draws' programs (no SKIN, SKIN8, MORPH bits): they draw
     * the vertices its pass captured */
    bool preskin;
    /* set before mvr_frame_build: feature bits taken out of every draw
     * (overrides.disable_features: material extensions drawn as absent) */
    uint32_t disabled_features;
} mvr_frame;

/* Builds the frame's draws, blocks and lights for a scene seen from origin.
 * block_stride >= MVR_DRAW_BLOCK_SIZE (the GL's uniform offset alignment);
 * material_capacity: materials per table block (the table is paged; a draw's
 * block holds its index within its page). The default material's slot is
 * the scene's material_count. plan: the array path's batch plan (draws then
 * sample texture arrays, white layers fill roles a material lacks, and draws
 * sort by the arrays they bind); NULL on the per-material path. */
mvr_result mvr_frame_build(mvr_frame *frame, const mvr_scene *scene, mvr_dvec3 origin,
                           uint32_t block_stride, uint32_t material_capacity,
                           const mvr_batch_plan *plan, char *why, size_t why_size);

void mvr_frame_free(mvr_frame *frame);

/* Per-view frustum culling: visible[view * words + draw / 64] bit draw % 64
 * says whether the draw's bounding sphere touches the view's frustum (a
 * conservative test: a visible draw is never culled). */
typedef struct mvr_visibility {
    uint64_t *bits;
    size_t cap_words;
    uint32_t views, words;       /* words per view */
    uint32_t *culled;            /* per view: draws outside its frustum */
    uint32_t culled_cap;
} mvr_visibility;

/* The six frustum planes (a, b, c, d; a*x + b*y + c*z + d >= 0 inside) of a
 * view-projection matrix, from its rows (Gribb and Hartmann, "Fast
 * Extraction of Viewing Frustum Planes from the World-View-Projection
 * Matrix", 2001), for clip z in [-w, w] (standard) or [0, w] (reversed).
 * Degenerate planes (an infinite far plane) come back all zero. */
typedef struct mvr_frustum {
    double planes[6][4];
} mvr_frustum;

void mvr_frustum_planes(const mvr_dmat4 *view_proj, bool reversed, mvr_frustum *out);

/* True when a sphere touches the frustum. */
bool mvr_sphere_in_frustum(const mvr_frustum *frustum, const double center[3], double radius);

/* Fills visibility for every draw of the frame and every view of the set
 * (layers width x height, for aspect ratios). */
mvr_result mvr_visibility_compute(mvr_visibility *vis, const mvr_frame *frame, const mvr_view_set *views,
                                  uint32_t width, uint32_t height, bool reversed);
void mvr_visibility_free(mvr_visibility *vis);

static inline bool mvr_visible(const mvr_visibility *vis, uint32_t view, uint32_t draw)
{
    return (vis->bits[(size_t)view * vis->words + draw / 64] >> (draw % 64)) & 1u;
}

/* Mesh feature bits of a primitive drawn with a material. */
uint32_t mvr_draw_features(const scene_primitive *prim, const mvr_material_desc *material);


#endif
