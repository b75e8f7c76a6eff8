/* auto's online tuner (gl/tuning.c). */
#ifndef MVR_TUNING_H
#define MVR_TUNING_H

#include "context_internal.h"
#include "view_set.h"

/* The view path this frame runs (prior: the caps rule's choice
 * for auto, or the path asked for; tune_view: auto, and both paths can draw
 * this frame) and its skinning path (r->skinning.tuned); after the frame,
 * what to measure and the stats' auto_choice / auto_skinning. */
mvr_view_path mvr_tuning_choose(mvr_renderer *r, const mvr_scene *scene, const mvr_view_set *views,
                                const mvr_target *t, mvr_view_path prior, bool tune_view);
void mvr_tuning_end_frame(mvr_renderer *r, mvr_view_path ran, bool ok);

#endif
