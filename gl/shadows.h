/* Shadow maps on the GPU (gl/shadows.c); core/shadow_plan.h plans their layers. */
#ifndef MVR_SHADOWS_H
#define MVR_SHADOWS_H

#include "context_internal.h"
#include "shadow_plan.h"
#include "view_set.h"

/* Shadow maps: one depth array shared by every view, drawn once per frame
 * (gl/shadows.c), with the plan of the frame that drew it. */
#define MVR_SHADOW_FBOS 32
typedef struct mvr_shadow_maps {
    GLuint depth;                /* GL_TEXTURE_2D_ARRAY, DEPTH_COMPONENT32F */
    GLuint color;                /* R8 array: multiview passes keep a color attachment (masked) */
    uint32_t size, layers;       /* allocated */
    GLuint sampler;              /* linear, comparison (GEQUAL reversed-Z, LEQUAL standard) */
    GLenum compare;
    struct { uint32_t base, count; GLuint fbo; } fbos[MVR_SHADOW_FBOS];
    uint32_t fbo_count;
    mvr_shadow_desc settings;    /* resolved, this frame */
    mvr_shadow_plan plan;        /* this frame's */
} mvr_shadow_maps;

/* Plans this frame's shadow layers (r->shadows.plan) */
void mvr_shadows_plan(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t, const mvr_render_desc *desc);
/* Draws the planned layers: caster matrices in a view block at views_at,
 * per-draw blocks from draws_at (the ring's static region). */
mvr_result mvr_shadows_draw(mvr_renderer *r, GLintptr views_at, GLintptr draws_at);
/* Binds the maps and the receiver block (at block_at) for the view passes. */
void mvr_shadows_bind(mvr_renderer *r, GLintptr block_at);
void mvr_shadows_release(mvr_renderer *r);

#endif
