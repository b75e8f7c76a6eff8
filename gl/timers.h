/* The renderer's GPU timer (gl/timers.c). */
#ifndef MVR_TIMERS_H
#define MVR_TIMERS_H

#include "context_internal.h"

typedef struct mvr_timer {
    GLuint queries[2];
    bool pending;
    bool timestamps;             /* GL_TIMESTAMP counters usable */
} mvr_timer;

/* Makes the two timestamp queries where GL_EXT_disjoint_timer_query has
 * usable counters (r->timer.timestamps). */
void mvr_timer_init(mvr_renderer *r);
/* Timestamps around a frame's passes, taken with no framebuffer bound;
 * stop leaves the queries pending when the frame succeeded. */
void mvr_timer_start(mvr_renderer *r);
void mvr_timer_stop(mvr_renderer *r, bool ok);
/* The last frame's timer queries into stats.gpu_ms (waits for them; -1 when
 * disjoint); the context current and a frame's queries pending. */
void mvr_timer_read(mvr_renderer *r);
void mvr_timer_release(mvr_renderer *r);

#endif
