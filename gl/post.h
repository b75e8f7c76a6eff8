/* Full-screen passes and the HDR frame's post pass (gl/post.c). */
#ifndef MVR_POST_H
#define MVR_POST_H

#include "context_internal.h"
#include "frame_plan.h"
#include "view_set.h"

/* A pass's views: mvr_view_chunk of core/frame_plan.h (the frame plan
 * splits the view set into these; a loop-path chunk is one view). */

/* Full-screen composite passes reading `source` (bound to the
 * composite unit, with the state such passes need): per chunk one
 * multiview pass over its layers (multiview) or one pass per view, into the
 * target's output layers, or (luminance) level 0 of its log-luminance
 * array. post_mul: per view, exposure / pre-exposure (MVR_FEATURE_POST),
 * else NULL. Each pass adds 1 to *passes. */
mvr_result mvr_full_screen_passes(mvr_renderer *r, mvr_target *t, GLuint source, const mvr_view_chunk *chunks,
                                  uint32_t chunk_count, bool multiview, uint32_t features, const float *post_mul,
                                  bool luminance, uint32_t *passes);
/* The state of an attributeless full-screen triangle: no depth, blend,
 * culling or scissor, all colour channels, the empty vertex array. */
void mvr_full_screen_state(mvr_renderer *r);
/* The HDR frame's final passes (exposure, tone map, encode), with
 * auto-exposure's luminance reduction first. chunks: as the views' passes. */
bool mvr_post_needed(const mvr_render_desc *desc);
/* The pre-exposure the lighting pass multiplies by (keeps half floats in range). */
double mvr_post_pre_exposure(mvr_renderer *r, const mvr_target *t, const mvr_render_desc *desc);
mvr_result mvr_post_run(mvr_renderer *r, mvr_target *t, const mvr_view_set *views, const mvr_render_desc *desc,
                        const mvr_view_chunk *chunks, uint32_t chunk_count, bool multiview, double pre_exposure);

#endif
