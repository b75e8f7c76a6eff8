/* The frame's uniform data (gl/frame_upload.c): where each part lives in
 * the ring, and its upload. */
#ifndef MVR_FRAME_UPLOAD_H
#define MVR_FRAME_UPLOAD_H

#include "context_internal.h"
#include "frame_plan.h"
#include "view_set.h"

static inline GLsizeiptr mvr_align_up(GLsizeiptr v, GLsizeiptr a)
{
    return (v + a - 1) / a * a;
}

typedef struct mvr_frame_layout {
    GLintptr draws, lights;          /* in the ring's static region (re-sent only on change) */
    GLintptr views;                  /* in this frame's ring segment */
    GLsizeiptr lights_size;
    uint32_t view_blocks;
    GLintptr draw_materials;         /* per-draw baseline: a material block per draw */
    GLsizeiptr draw_material_stride;
    GLintptr *compact;               /* per chunk: its compacted blocks in this segment, or -1 */
    GLintptr shadow_views;           /* the shadow pass's view block: caster matrices */
    GLintptr shadow_block;           /* the receivers' mvr_shadows block */
} mvr_frame_layout;

/* Sends this frame's uniform data into the ring (the per-draw blocks and
 * lights only when static_current is false or the ring was replaced), and
 * lays it out in *lay: views, shadow blocks, per-draw materials and each
 * chunk's compacted blocks (lay->compact, one per chunk). */
mvr_result mvr_frame_upload(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t,
                            const mvr_view_chunk *chunks, uint32_t chunk_count, mvr_frame_layout *lay,
                            bool static_current);

#endif
