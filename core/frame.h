/*
 * Frame preparation, backend-free: world transforms in double, the draw list
 * (sorted per pass), per-draw blocks (model relative to the view set's origin,
 * narrowed to float), the lights, and the material table, all packed in the
 * std140 layouts of shaders/mesh.*.glsl. The GL backend uploads these bytes.
 */
#ifndef MVR_FRAME_H
#define MVR_FRAME_H

#include "batch_plan.h"
#include "scene_internal.h"
#include "shader_gen.h"

/* std140 sizes of the shader blocks. */
#define MVR_DRAW_BLOCK_SIZE 144u      /* mat4 model, mat4 normal, ivec4 info */
#define MVR_MATERIAL_BLOCK_SIZE 240u  /* see struct mvr_material in mesh.frag.glsl */
#define MVR_LIGHT_BLOCK_SIZE 64u
#define MVR_VIEW_MATRIX_SIZE 64u      /* one mat4 of mvr_view_proj */
#define MVR_VIEW_EYE_SIZE 16u         /* one vec4 of mvr_eye_position */

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
    uint32_t block;              /* its per-draw block in mvr_frame.draw_blocks */
    uint32_t material_page;      /* which block-sized page of the material table it reads */
    uint64_t group_key;          /* texture arrays it binds (array path; 0 otherwise) */
    mvr_pass_kind pass;
    bool mirrored;               /* negative determinant: front faces wind clockwise */
    float depth;                 /* distance from the origin to its bounds' center */
} mvr_draw;

typedef struct mvr_frame {
    mvr_draw *draws;
    uint32_t draw_count, draw_cap;
    uint32_t pass_first[MVR_PASS_KIND_COUNT], pass_count[MVR_PASS_KIND_COUNT];
    uint8_t *draw_blocks;        /* draw_count blocks, block_stride apart */
    size_t draw_blocks_cap;
    uint32_t block_stride;
    uint8_t light_blocks[3 * MVR_SHADER_MAX_LIGHTS_PER_TYPE * MVR_LIGHT_BLOCK_SIZE];
    uint32_t light_counts[3];    /* directional, point, spot (blocks in that order) */
    uint32_t lights_dropped;     /* beyond MVR_SHADER_MAX_LIGHTS_PER_TYPE of a type */
    mvr_dmat4 *world;
    uint32_t world_cap;
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

/* Mesh feature bits of a primitive drawn with a material. */
uint32_t mvr_draw_features(const scene_primitive *prim, const mvr_material_desc *material);

/* Packs a material into its 240-byte std140 block. */
void mvr_material_pack(const mvr_material_desc *material, uint8_t out[MVR_MATERIAL_BLOCK_SIZE]);

#endif
