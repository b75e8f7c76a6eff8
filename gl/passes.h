/* The frame (gl/passes.c): its plan executed pass by pass. */
#ifndef MVR_PASSES_H
#define MVR_PASSES_H

#include "frame.h"
#include "view_set.h"

/* Prepares the frame's data, builds its plan and executes it. */
mvr_result mvr_renderer_draw_frame(mvr_renderer *r, const mvr_scene *scene, const mvr_view_set *views,
                                   mvr_target *target, const mvr_render_desc *desc, mvr_view_path path);

#endif
