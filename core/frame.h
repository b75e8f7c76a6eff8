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
#include "block_layout.h"
#include "shader_gen.h"

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
    uint64_t group_key;          /* the textures it binds: its texture arrays' groups (array
                                    path), else its material + 1 where that samples a texture,
                                    0 where it samples none; draws with equal keys bind the same */
    mvr_pass_kind pass;
    bool mirrored;               /* negative determinant: front faces wind clockwise */
    float depth;                 /* distance from the origin to its bounds' center */
    double center[3];            /* world bounding sphere, relative to the origin */
    double radius;
    uint32_t deform;             /* its entry in mvr_frame.deforms, or MVR_NO_INDEX */
} mvr_draw;

/* Whether two draws of a pass bind the same (primitive, program, winding,
 * material table page, textures), so that consecutive ones can be one
 * instanced call: core/frame.c counts calls with it, gl/draw_list.c
 * instances with it (adding what only the GL side knows: pre-skinned
 * vertices are never instanced). */
static inline bool mvr_draws_bind_alike(const mvr_draw *a, const mvr_draw *b)
{
    return a->primitive == b->primitive && a->features == b->features && a->mirrored == b->mirrored &&
           a->material_page == b->material_page && a->group_key == b->group_key;
}

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
