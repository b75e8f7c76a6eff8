/* The draw lists of a pass (gl/draw_list.c): programs, per-draw blocks,
 * textures and instanced runs, blended draws in back-to-front order. */
#ifndef MVR_DRAW_LIST_H
#define MVR_DRAW_LIST_H

#include "frame.h"
#include "frame_upload.h"
#include "program_cache.h"

/* What the draws of one pass share: its views and their block, the frame's
 * layout and features, and the program lookup cache. */
typedef struct mvr_pass_context {
    mvr_renderer *r;
    const mvr_scene *scene;
    const mvr_frame_layout *lay;
    const mvr_render_desc *desc;
    uint32_t output_features;
    uint32_t shader_outputs;     /* the target's extra outputs (MVR_SHADER_OUT_*, 0 = none) */
    bool outputs_only;           /* the blended draws' outputs pass */
    float output_alpha_cutoff;
    uint32_t num_views;          /* 0 on the loop path */
    int32_t view_base;           /* within the bound view block */
    uint32_t last_features;      /* program lookup cache */
    mvr_program_entry *last_program;
    uint8_t *groups_used;        /* array path: groups sampled in this pass */
    uint32_t groups_used_count;
    uint32_t first_view, views;  /* the pass's views: a draw visible in any is drawn */
    float mesh_exposure;         /* the linear exposure, or an HDR frame's pre-exposure */
    GLintptr compact;            /* the pass's compacted blocks, or -1 */
    uint32_t compact_next;       /* next compacted block to draw */
    const mvr_view_set *view_set;
    mvr_target *target;
} mvr_pass_context;

/* Whether a draw (by position in the frame's list) is visible in any of the
 * views [first, first + count). */
bool mvr_draw_visible(const mvr_renderer *r, uint32_t first, uint32_t count, uint32_t draw);
/* Whether any view of the pass needs another order of its blended draws
 * than the centroid order. */
bool mvr_blend_orders_diverge(const mvr_renderer *r, const mvr_pass_context *pc);
/* Draws one pass list (opaque, masked or blended) of the frame. */
mvr_result mvr_draw_list(mvr_pass_context *pc, mvr_pass_kind kind);
/* Binds the textures of the roles in `features` a draw samples (array
 * path: its groups' arrays, marking them in groups_used when given; else
 * its material's 2D textures). */
void mvr_bind_draw_textures(mvr_renderer *r, const mvr_draw *d, uint32_t features, uint8_t *groups_used,
                            uint32_t *groups_used_count);
/* Face culling for the draw's winding and sidedness, its vertex array, and
 * the draw command for `instances` consecutive per-draw blocks. */
void mvr_submit_draw(mvr_renderer *r, const mvr_draw *d, uint32_t instances);

#endif
