/*
 * auto's online tuner on the GL side (core/tuner.h decides): which view path
 * this frame runs, and the cost of the measured frames: the larger of the
 * submitting thread's CPU time and the GPU time of the frame's timestamp
 * queries (taken with the default framebuffer bound: timer queries are
 * undefined while a multiview framebuffer is, caps bugs), read at the start
 * of the next render (a wait, in the measured frames only), or the test hook's.
 */
#include <string.h>

#include "renderer_internal.h"

const char *mvr_auto_state_name(mvr_auto_state state)
{
    switch (state) {
    case MVR_AUTO_NONE:
        return "none";
    case MVR_AUTO_RULE:
        return "rule";
    case MVR_AUTO_TUNING:
        return "tuning";
    case MVR_AUTO_SETTLED:
        return "settled";
    }
    return NULL;
}

static const mvr_view_path candidates[MVR_TUNER_CANDIDATES] = {MVR_VIEW_PATH_MULTIVIEW, MVR_VIEW_PATH_LOOP};

static uint32_t candidate_of(mvr_view_path path)
{
    return path == MVR_VIEW_PATH_LOOP ? 1u : 0u;
}

/* The GPU time of the last frame (ms), waiting for it; < 0 when there is none. */
static double last_gpu_ms(mvr_renderer *r)
{
    if (r->timer.pending)
        mvr_renderer_read_timer(r);
    return r->stats.gpu_ms; /* read now, or by mvr_renderer_get_stats already (or none) */
}

static void fill_stats(mvr_renderer *r, mvr_auto_state state, mvr_view_path prior)
{
    mvr_auto_choice *a = &r->stats.auto_choice;
    const mvr_tuner *t = &r->view_tuner;
    memset(a, 0, sizeof *a);
    a->state = state;
    a->prior = prior;
    a->chosen = state == MVR_AUTO_SETTLED ? candidates[t->chosen] : prior;
    for (uint32_t c = 0; c < MVR_TUNER_CANDIDATES; ++c) {
        a->candidates[c] = candidates[c];
        a->samples[c] = t->samples[c];
        a->cost_ms[c] = state == MVR_AUTO_SETTLED ? t->median[c] : t->samples[c] ? t->costs[c][t->samples[c] - 1] : -1.0;
    }
    a->margin = state == MVR_AUTO_SETTLED ? t->margin : 0.0;
    a->retunes = t->retunes;
}

mvr_view_path mvr_tuning_view_path(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t,
                                   mvr_view_path prior, bool multiview_ok)
{
    /* the previous frame's cost, if it was a measured one (before this frame resets the stats) */
    if (r->tuning_frame.pending) {
        r->tuning_frame.pending = false;
        mvr_view_path ran = candidates[r->tuning_frame.candidate];
        double cost;
        if (r->tuning_desc.frame_cost) {
            cost = r->tuning_desc.frame_cost(r->tuning_desc.user, ran, &r->stats);
        } else {
            double gpu = last_gpu_ms(r);
            cost = gpu > r->tuning_frame.cpu_ms ? gpu : r->tuning_frame.cpu_ms;
        }
        mvr_tuner_record(&r->view_tuner, r->tuning_frame.candidate, cost);
    }
    if (!r->tuning || !multiview_ok) {
        r->tuning_frame.candidate = candidate_of(prior);
        return prior;
    }
    mvr_tuner_key key = {views->count, t->desc.width, t->desc.height, r->frame.draw_count};
    bool measure = false;
    uint32_t c = mvr_tuner_next(&r->view_tuner, key, candidate_of(prior), &measure);
    r->tuning_frame.pending = measure;
    r->tuning_frame.candidate = c;
    return candidates[c];
}

void mvr_tuning_end_frame(mvr_renderer *r, mvr_view_path prior, bool ok)
{
    mvr_auto_state state = MVR_AUTO_NONE;
    if (r->requested_path == MVR_VIEW_PATH_AUTO)
        state = !r->tuning                                   ? MVR_AUTO_RULE
                : r->view_tuner.phase == MVR_TUNER_SETTLED   ? MVR_AUTO_SETTLED
                : r->view_tuner.phase == MVR_TUNER_TUNING    ? MVR_AUTO_TUNING
                                                             : MVR_AUTO_NONE;
    if (!ok)
        r->tuning_frame.pending = false; /* a failed frame measures nothing */
    else if (r->tuning_frame.pending)
        r->tuning_frame.cpu_ms = r->stats.cpu_ms;
    fill_stats(r, state, prior);
}
