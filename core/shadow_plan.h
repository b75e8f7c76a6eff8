/*
 * Shadow plan, backend-free: which lights get shadow map layers this frame,
 * and each layer's light-space projection. Directional lights take one layer
 * per cascade, fitted to the union of the frustums of the views the light
 * shines in; spot lights take one perspective layer. Layers are shared by
 * every view: a light shining in several views has its layers once, a light
 * shining in none has none. The GL backend draws the casters into these
 * layers and uploads the receiver block this packs.
 */
#ifndef MVR_SHADOW_PLAN_H
#define MVR_SHADOW_PLAN_H

#include "frame.h"

#define MVR_SHADOW_MAX_LAYERS MVR_SHADER_MAX_SHADOW_LAYERS
#define MVR_SHADOW_MAX_CASCADES 4
#define MVR_FRAME_MAX_LIGHTS (3 * MVR_SHADER_MAX_LIGHTS_PER_TYPE)
/* std140 size of the mvr_shadows block (shaders/shadows.glsl declares it from
 * the layout table): receiver matrices, per-layer parameters, per-light (first
 * layer, count); its members' offsets are MVR_SHADOWS_* of block_layout.h */
#define MVR_SHADOW_BLOCK_SIZE MVR_SHADOWS_BLOCK_SIZE

typedef struct mvr_shadow_layer {
    uint32_t light;              /* index in the frame's light list */
    uint32_t cascade;            /* 0 for spot lights */
    mvr_dmat4 view_proj;         /* casters: world relative to the origin -> clip */
    mvr_frustum frustum;         /* of view_proj, for caster culling */
    double texel;                /* world size of a texel (orthographic), or per unit of
                                    distance from the light (perspective) */
    bool perspective;
} mvr_shadow_layer;

typedef struct mvr_shadow_plan {
    uint32_t layer_count;
    mvr_shadow_layer layers[MVR_SHADOW_MAX_LAYERS];
    int32_t light_first[MVR_FRAME_MAX_LIGHTS];    /* first layer, -1 = no shadow */
    uint32_t light_layers[MVR_FRAME_MAX_LIGHTS];  /* layers of the light */
    uint32_t lights_unshadowed;  /* wanted a shadow, but the layers ran out */
    uint32_t max_view_layers;    /* the most layers one enabled view reads */
    bool masked;                 /* some light is masked out of some enabled view */
} mvr_shadow_plan;

/* Shadow settings with every default filled in (zero fields of mvr_shadow_desc). */
mvr_shadow_desc mvr_shadow_desc_resolve(const mvr_shadow_desc *desc);

/* Bit i set: light i of the frame shines in the view (render layers). */
uint32_t mvr_view_light_mask(const mvr_frame *frame, const mvr_view_desc *view);

/* Plans the layers for the frame's lights seen by the set's enabled views
 * (layers width x height, for aspect ratios). settings: resolved. reversed:
 * the depth convention of the caster matrices (as the views'). */
void mvr_shadow_plan_build(mvr_shadow_plan *plan, const mvr_frame *frame, const mvr_view_set *views,
                           uint32_t width, uint32_t height, bool reversed, const mvr_shadow_desc *settings);

/* The receiver block: for each layer, world (relative to the origin) ->
 * (u, v, depth) in [0, 1]; its parameters; each light's layers. */
void mvr_shadow_block_pack(const mvr_shadow_plan *plan, const mvr_shadow_desc *settings, bool reversed,
                           uint8_t out[MVR_SHADOW_BLOCK_SIZE]);

#endif
