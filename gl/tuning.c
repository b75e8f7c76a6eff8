/*
 * auto's online tuner on the GL side (core/tuner.h decides): which view path
 * and which skinning path this frame runs, and the cost of the measured
 * frames: the larger of the submitting thread's CPU time and the GPU time of
 * the frame's timestamp queries (taken with the default framebuffer bound:
 * timer queries are undefined while a multiview framebuffer is, caps bugs),
 * read at the start of the next render (a wait, in the measured frames
 * only), or the test hook's.
 *
 * The decisions are measured one after the other, never together: the view
 * path first; the skinning path once the view path settled (or is not
 * tuned), keyed on the view path that runs, so a new view path measures the
 * skinning path again.
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

static const mvr_view_path view_candidates[MVR_TUNER_CANDIDATES] = {MVR_VIEW_PATH_MULTIVIEW, MVR_VIEW_PATH_LOOP};
static const mvr_skinning_path skin_candidates[MVR_TUNER_CANDIDATES] = {MVR_SKINNING_PATH_VERTEX,
                                                                        MVR_SKINNING_PATH_PRESKIN};

static uint32_t view_candidate(mvr_view_path path)
{
    return path == MVR_VIEW_PATH_LOOP ? 1u : 0u;
}

static uint32_t skin_candidate(mvr_skinning_path path)
{
    return path == MVR_SKINNING_PATH_PRESKIN ? 1u : 0u;
}

/* The GPU time of the last frame (ms), waiting for it; < 0 when there is none. */
static double last_gpu_ms(mvr_renderer *r)
{
    if (r->timer.pending)
        mvr_renderer_read_timer(r);
    return r->stats.gpu_ms; /* read now, or by mvr_renderer_get_stats already (or none) */
}

/* The previous frame's cost, if it was a measured one (before this frame
 * resets the stats), into the tuner of the decision it measured. */
static void record_last_frame(mvr_renderer *r)
{
    if (!r->tuning_frame.pending)
        return;
    r->tuning_frame.pending = false;
    double cost;
    if (r->tuning_desc.frame_cost) {
        cost = r->tuning_desc.frame_cost(r->tuning_desc.user, r->stats.view_path, &r->stats);
    } else {
        double gpu = last_gpu_ms(r);
        cost = gpu > r->tuning_frame.cpu_ms ? gpu : r->tuning_frame.cpu_ms;
    }
    mvr_tuner *t = r->tuning_frame.skinning ? &r->skin_tuner : &r->view_tuner;
    mvr_tuner_record(t, r->tuning_frame.candidate, cost);
}

/* The skinning path of a frame that runs `view` (r->skinning.tuned; AUTO:
 * the rule), measured when the view path is not being measured. */
static void choose_skinning(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t, mvr_view_path view)
{
    mvr_skinning *k = &r->skinning;
    k->tuned = MVR_SKINNING_PATH_AUTO;
    r->skin_tuned_frame = false;
    if (!r->tuning || k->requested != MVR_SKINNING_PATH_AUTO || !r->frame.deform_count)
        return;
    r->skin_tuned_frame = true;
    mvr_skinning_path prior = mvr_skinning_rule(views->count);
    if (r->view_tuner.phase == MVR_TUNER_TUNING) {
        /* the view path is being measured: the skinning path stays put */
        const mvr_tuner *s = &r->skin_tuner;
        bool same_view = s->phase == MVR_TUNER_SETTLED && s->key.given == (uint32_t)view;
        k->tuned = same_view ? skin_candidates[s->chosen] : prior;
        return;
    }
    mvr_tuner_key key = {views->count, t->desc.width, t->desc.height, r->frame.draw_count, (uint32_t)view};
    bool measure = false;
    uint32_t c = mvr_tuner_next(&r->skin_tuner, key, skin_candidate(prior), &measure);
    if (measure) {
        r->tuning_frame.pending = true;
        r->tuning_frame.skinning = true;
        r->tuning_frame.candidate = c;
    }
    k->tuned = skin_candidates[c];
}

mvr_view_path mvr_tuning_choose(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t,
                                mvr_view_path prior, bool multiview_ok)
{
    record_last_frame(r);
    r->view_tuned_frame = r->tuning && multiview_ok;
    mvr_view_path path = prior;
    if (r->view_tuned_frame) {
        mvr_tuner_key key = {views->count, t->desc.width, t->desc.height, r->frame.draw_count, 0};
        bool measure = false;
        uint32_t c = mvr_tuner_next(&r->view_tuner, key, view_candidate(prior), &measure);
        if (measure) {
            r->tuning_frame.pending = true;
            r->tuning_frame.skinning = false;
            r->tuning_frame.candidate = c;
        }
        path = view_candidates[c];
    }
    choose_skinning(r, views, t, path);
    return path;
}

static mvr_auto_state state_of(const mvr_renderer *r, bool tuned, const mvr_tuner *t)
{
    if (!r->tuning)
        return MVR_AUTO_RULE;
    if (!tuned)
        return MVR_AUTO_NONE;
    return t->phase == MVR_TUNER_SETTLED ? MVR_AUTO_SETTLED
           : t->phase == MVR_TUNER_TUNING ? MVR_AUTO_TUNING
                                          : MVR_AUTO_NONE;
}

/* What a tuner measured: samples, costs (medians once settled, else the
 * latest; -1 for none), margin. */
static void fill_measured(const mvr_tuner *t, bool settled, uint32_t samples[2], double cost_ms[2], double *margin)
{
    for (uint32_t c = 0; c < MVR_TUNER_CANDIDATES; ++c) {
        samples[c] = t->samples[c];
        cost_ms[c] = settled ? t->median[c] : t->samples[c] ? t->costs[c][t->samples[c] - 1] : -1.0;
    }
    *margin = settled ? t->margin : 0.0;
}

void mvr_tuning_end_frame(mvr_renderer *r, mvr_view_path prior, bool ok)
{
    if (!ok)
        r->tuning_frame.pending = false; /* a failed frame measures nothing */
    else if (r->tuning_frame.pending)
        r->tuning_frame.cpu_ms = r->stats.cpu_ms;

    mvr_auto_choice *a = &r->stats.auto_choice;
    memset(a, 0, sizeof *a);
    if (r->requested_path == MVR_VIEW_PATH_AUTO) {
        const mvr_tuner *t = &r->view_tuner;
        a->state = state_of(r, r->view_tuned_frame, t);
        a->prior = prior;
        a->chosen = a->state == MVR_AUTO_SETTLED ? view_candidates[t->chosen] : prior;
        a->candidates[0] = view_candidates[0];
        a->candidates[1] = view_candidates[1];
        if (a->state == MVR_AUTO_SETTLED || a->state == MVR_AUTO_TUNING) {
            fill_measured(t, a->state == MVR_AUTO_SETTLED, a->samples, a->cost_ms, &a->margin);
            a->retunes = t->retunes;
        } else {
            a->cost_ms[0] = a->cost_ms[1] = -1.0;
        }
    }

    mvr_auto_skinning_choice *s = &r->stats.auto_skinning;
    memset(s, 0, sizeof *s);
    if (r->skinning.requested == MVR_SKINNING_PATH_AUTO && r->frame.deform_count) {
        const mvr_tuner *t = &r->skin_tuner;
        /* measured once the view path settled: until then "tuning" too */
        s->state = state_of(r, r->skin_tuned_frame, t);
        if (r->skin_tuned_frame && (t->phase == MVR_TUNER_IDLE || r->view_tuner.phase == MVR_TUNER_TUNING))
            s->state = MVR_AUTO_TUNING; /* waiting for the view path */
        bool keyed = t->phase != MVR_TUNER_IDLE;
        s->prior = keyed ? skin_candidates[t->prior] : r->skinning.path;
        s->chosen = s->state == MVR_AUTO_SETTLED ? skin_candidates[t->chosen] : r->skinning.path;
        s->candidates[0] = skin_candidates[0];
        s->candidates[1] = skin_candidates[1];
        if (keyed && (s->state == MVR_AUTO_SETTLED || s->state == MVR_AUTO_TUNING)) {
            fill_measured(t, s->state == MVR_AUTO_SETTLED, s->samples, s->cost_ms, &s->margin);
            s->retunes = t->retunes;
        } else {
            s->cost_ms[0] = s->cost_ms[1] = -1.0;
        }
    }
}
