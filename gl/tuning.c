/*
 * auto's online tuner on the GL side (core/tuner.h decides): which view
 * path, material path and skinning path this frame runs, and the cost of the
 * measured frames: the larger of the submitting thread's CPU time and the
 * GPU time of the frame's timestamp queries (taken with the default
 * framebuffer bound: timer queries are undefined while a multiview
 * framebuffer is, caps bugs), read at the start of the next render (a wait,
 * in the measured frames only), or the test hook's.
 *
 * The decisions form a chain, measured one at a time: the view path, then
 * the material path keyed on the view path it settled on (issue 37: on
 * DamagedHelmet with a punctual light the material path measured under a
 * view path still switching picked arrays in 3 of 4 runs, per-material
 * being 1.18-1.61x faster), then the skinning path keyed on both. A
 * decision whose predecessor is still measuring runs its own choice settled
 * for the same inputs, its remembered one, or its prior. No cycle: a later
 * decision never restarts an earlier one.
 *
 * Memory (core/tuner_memory.h): with a program cache folder, each settled
 * decision is stored there, keyed by the scene's content, the views, the
 * target (size, format, samples, outputs), the renderer's settings that
 * change the work and the GL's renderer and version strings, and handed
 * back to the tuner the next time those inputs start tuning, in this
 * process or a later one. An entry that does not verify is ignored (logged).
 */
#include <stdio.h>
#include <string.h>

#include "renderer.h"
#include "scene_hash.h"
#include "skinning.h"
#include "targets.h"
#include "timers.h"
#include "tuning.h"

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

enum { DECIDE_MATERIAL, DECIDE_VIEW, DECIDE_SKINNING };
static const char *const decision_names[3] = {"material", "view", "skinning"};

static const mvr_material_path material_candidates[MVR_TUNER_CANDIDATES] = {MVR_MATERIAL_PATH_PER_MATERIAL,
                                                                            MVR_MATERIAL_PATH_ARRAYS};
static const mvr_view_path view_candidates[MVR_TUNER_CANDIDATES] = {MVR_VIEW_PATH_MULTIVIEW, MVR_VIEW_PATH_LOOP};
static const mvr_skinning_path skin_candidates[MVR_TUNER_CANDIDATES] = {MVR_SKINNING_PATH_VERTEX,
                                                                        MVR_SKINNING_PATH_PRESKIN};

static mvr_tuner *tuner_of(mvr_renderer *r, uint32_t decision)
{
    return decision == DECIDE_MATERIAL ? &r->material_tuner
           : decision == DECIDE_VIEW   ? &r->view_tuner
                                       : &r->skin_tuner;
}

/* The GPU time of the last frame (ms), waiting for it; < 0 when there is none. */
static double last_gpu_ms(mvr_renderer *r)
{
    if (r->timer.pending)
        mvr_timer_read(r);
    return r->stats.gpu_ms; /* read now, or by mvr_renderer_get_stats already (or none) */
}

/* The memory key of a decision's inputs into m->d[decision].key: false
 * when it does not fit (then nothing is remembered). */
static bool memory_key(mvr_renderer *r, uint32_t decision, const mvr_tuner_key *key, uint32_t prior,
                       const mvr_target *tg, char *out, size_t size)
{
    const mvr_target_desc *d = &tg->desc;
    const mvr_caps *caps = &r->ctx->caps;
    int n = snprintf(out, size,
                     "v1 scene %016llx views %u size %ux%u format %d samples %u ss %u aa %d outputs %u "
                     "features %u culling %d instancing %d msaa_mv %d decision %s given %u prior %u gl %s | %s",
                     (unsigned long long)r->tuning_memory.scene_hash, key->views, key->width, key->height,
                     (int)d->color_format, d->samples, d->supersample, (int)d->anti_aliasing, d->outputs,
                     r->frame.disabled_features, (int)r->culling, (int)(r->draw_capacity > 1),
                     (int)r->msaa_multiview_off, decision_names[decision], key->given, prior, caps->renderer,
                     caps->version);
    return n > 0 && (size_t)n < size && (size_t)n <= MVR_TUNER_MEMORY_MAX_KEY && !strpbrk(out, "\r\n");
}

/* What an earlier run settled on for these inputs (NULL: nothing, or no
 * memory); read when the inputs differ from the last look-up. */
static const mvr_tuner_memory *recall(mvr_renderer *r, uint32_t decision, const mvr_tuner_key *key, uint32_t prior,
                                      const mvr_target *tg)
{
    mvr_tuning_memory *m = &r->tuning_memory;
    if (!m->enabled)
        return NULL;
    char k[MVR_TUNER_MEMORY_MAX_KEY + 1];
    if (!memory_key(r, decision, key, prior, tg, k, sizeof k)) {
        m->d[decision].key[0] = 0; /* nothing remembered for inputs that make no key */
        m->d[decision].found = false;
        return NULL;
    }
    if (strcmp(k, m->d[decision].key) == 0)
        return m->d[decision].found ? &m->d[decision].memory : NULL;
    memcpy(m->d[decision].key, k, sizeof k);
    m->d[decision].found = false;
    char path[4096], why[256];
    if (!mvr_tuner_memory_path(r->program_cache_dir, k, path, sizeof path))
        return NULL;
    mvr_tuner_memory_status st = mvr_tuner_memory_read(path, &m->mac, k, &m->d[decision].memory, why, sizeof why);
    if (st == MVR_TUNER_MEMORY_CORRUPT || st == MVR_TUNER_MEMORY_STALE)
        mvr_log(&r->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL, "mvr: tuner memory %s: %s; ignored", path, why);
    m->d[decision].found = st == MVR_TUNER_MEMORY_HIT;
    return m->d[decision].found ? &m->d[decision].memory : NULL;
}

/* A decision that settled on measurements: its memory into the folder,
 * under the key its tuning started with. */
static void store(mvr_renderer *r, uint32_t decision)
{
    mvr_tuner *t = tuner_of(r, decision);
    mvr_tuning_memory *m = &r->tuning_memory;
    if (!t->store)
        return;
    t->store = false;
    const char *k = m->d[decision].tuned_key;
    char path[4096], why[256];
    if (!m->enabled || !k[0] || !mvr_tuner_memory_path(r->program_cache_dir, k, path, sizeof path))
        return;
    if (!mvr_tuner_memory_write(path, &m->mac, k, &t->memory, why, sizeof why)) {
        mvr_log(&r->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL, "mvr: tuner memory: %s", why);
        return;
    }
    /* the next look-up of these inputs finds what was written */
    memcpy(m->d[decision].key, k, sizeof m->d[decision].key);
    m->d[decision].memory = t->memory;
    m->d[decision].found = true;
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
    mvr_tuner_record(tuner_of(r, r->tuning_frame.decision), r->tuning_frame.candidate, cost);
    store(r, r->tuning_frame.decision);
}

/* One decision's candidate for this frame. *busy: an earlier decision is
 * measuring, so this one waits (its settled choice for these inputs, its
 * remembered one, or the prior); else it steps its tuner, and is busy
 * itself while tuning. */
static uint32_t decide(mvr_renderer *r, uint32_t decision, mvr_tuner_key key, uint32_t prior, const mvr_target *tg,
                       bool *busy)
{
    mvr_tuner *t = tuner_of(r, decision);
    const mvr_tuner_memory *mem = recall(r, decision, &key, prior, tg);
    bool restarts = mvr_tuner_restarts(t, key, prior);
    if (*busy)
        return t->phase == MVR_TUNER_SETTLED && !restarts ? t->chosen : mem ? mem->chosen : prior;
    if (restarts) {
        mvr_tuning_memory *m = &r->tuning_memory;
        memcpy(m->d[decision].tuned_key, m->d[decision].key, sizeof m->d[decision].key);
    }
    bool measure = false;
    /* what settles is kept for later runs: a memory folder, and a key to store it under */
    bool remembers = r->tuning_memory.enabled && r->tuning_memory.d[decision].key[0];
    uint32_t c = mvr_tuner_next_recalled(t, key, prior, mem, remembers, &measure);
    store(r, decision);
    if (measure) {
        r->tuning_frame.pending = true;
        r->tuning_frame.decision = decision;
        r->tuning_frame.candidate = c;
    }
    *busy = t->phase == MVR_TUNER_TUNING;
    return c;
}

/* The scene's content hash for the memory keys, once per scene and change;
 * the memory's user key, once. */
static void memory_begin(mvr_renderer *r, const mvr_scene *scene)
{
    mvr_tuning_memory *m = &r->tuning_memory;
    if (!m->enabled)
        return;
    if (!m->mac_loaded) {
        char why[512];
        m->mac_loaded = true;
        if (!mvr_program_cache_key_load(r->program_cache_dir, &m->mac, why, sizeof why)) {
            mvr_log(&r->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL, "mvr: tuner memory off: %s", why);
            m->enabled = false;
            return;
        }
    }
    uint64_t serial = mvr_scene_serial(scene), version = scene->geometry_version;
    if (!m->hashed || m->scene_serial != serial || m->geometry_version != version) {
        m->scene_hash = mvr_scene_content_hash(scene);
        m->scene_serial = serial;
        m->geometry_version = version;
        m->hashed = true;
    }
}

mvr_view_path mvr_tuning_choose(mvr_renderer *r, const mvr_scene *scene, const mvr_view_set *views,
                                const mvr_target *t, mvr_view_path prior, bool tune_view)
{
    memory_begin(r, scene);
    record_last_frame(r);
    /* what the last frame's views saw (culling is the same on every path) */
    uint64_t seen = (uint64_t)r->frame.draw_count * r->stats.views;
    seen = seen > r->stats.culled ? seen - r->stats.culled : 0;
    mvr_tuner_key key = {views->count, t->desc.width, t->desc.height, r->frame.draw_count, 0,
                         seen > UINT32_MAX ? UINT32_MAX : (uint32_t)seen};
    bool busy = false;

    /* the view path first */
    r->view_tuned_frame = r->tuning && tune_view;
    mvr_view_path path = prior;
    if (r->view_tuned_frame)
        path = view_candidates[decide(r, DECIDE_VIEW, key, prior == MVR_VIEW_PATH_LOOP, t, &busy)];

    /* the material path (arrays is the rule), keyed on the view path it
     * will run with: the settled one, or the incumbent while it is measured */
    mvr_view_path view_given = r->view_tuned_frame ? view_candidates[r->view_tuner.chosen] : path;
    key.given = (uint32_t)view_given + 1u;
    r->material_tuned_frame = r->tuning && r->material_requested == MVR_MATERIAL_PATH_AUTO;
    if (r->material_tuned_frame)
        r->material_path = material_candidates[decide(r, DECIDE_MATERIAL, key, 1, t, &busy)];

    /* the skinning path, keyed on both (a scene whose last frame drew skins
     * or morph targets: the first frame has not built its draw list yet) */
    mvr_skinning *k = &r->skinning;
    k->tuned = MVR_SKINNING_PATH_AUTO;
    r->skin_tuned_frame = r->tuning && k->requested == MVR_SKINNING_PATH_AUTO && r->frame.deform_count;
    if (r->skin_tuned_frame) {
        key.given = (uint32_t)r->material_path * 8u + (uint32_t)path;
        uint32_t skin_prior = mvr_skinning_rule(views->count) == MVR_SKINNING_PATH_PRESKIN;
        k->tuned = skin_candidates[decide(r, DECIDE_SKINNING, key, skin_prior, t, &busy)];
    }
    return path;
}

/* A decision's state for the stats: waiting for an earlier one counts as tuning. */
static mvr_auto_state state_of(const mvr_renderer *r, bool tuned, const mvr_tuner *t, bool earlier_busy)
{
    if (!r->tuning)
        return MVR_AUTO_RULE;
    if (!tuned)
        return MVR_AUTO_NONE;
    if (earlier_busy || t->phase != MVR_TUNER_SETTLED)
        return MVR_AUTO_TUNING;
    return MVR_AUTO_SETTLED;
}

/* What a tuner measured: samples, costs (estimates once settled, else the
 * latest; -1 for none), margin, retunes. */
static void fill_measured(const mvr_tuner *t, mvr_auto_state state, uint32_t samples[2], double cost_ms[2],
                          double *margin, uint32_t *retunes)
{
    bool settled = state == MVR_AUTO_SETTLED;
    bool keyed = t->phase != MVR_TUNER_IDLE && (state == MVR_AUTO_SETTLED || state == MVR_AUTO_TUNING);
    for (uint32_t c = 0; c < MVR_TUNER_CANDIDATES; ++c) {
        samples[c] = keyed ? t->samples[c] : 0;
        cost_ms[c] = !keyed ? -1.0 : settled ? t->estimate[c] : t->samples[c] ? t->costs[c][t->samples[c] - 1] : -1.0;
    }
    *margin = settled ? t->margin : 0.0;
    *retunes = keyed ? t->retunes : 0;
}

void mvr_tuning_end_frame(mvr_renderer *r, mvr_view_path prior, bool ok)
{
    if (!ok)
        r->tuning_frame.pending = false; /* a failed frame measures nothing */
    else if (r->tuning_frame.pending)
        r->tuning_frame.cpu_ms = r->stats.cpu_ms;
    bool view_busy = r->view_tuned_frame && r->view_tuner.phase == MVR_TUNER_TUNING;
    bool material_busy = view_busy || (r->material_tuned_frame && r->material_tuner.phase == MVR_TUNER_TUNING);

    mvr_auto_material_choice *m = &r->stats.auto_material;
    memset(m, 0, sizeof *m);
    if (r->material_requested == MVR_MATERIAL_PATH_AUTO) {
        const mvr_tuner *t = &r->material_tuner;
        m->state = state_of(r, r->material_tuned_frame, t, view_busy);
        m->prior = MVR_MATERIAL_PATH_ARRAYS;
        m->chosen = m->state == MVR_AUTO_SETTLED ? material_candidates[t->chosen] : m->prior;
        m->candidates[0] = material_candidates[0];
        m->candidates[1] = material_candidates[1];
        fill_measured(t, m->state, m->samples, m->cost_ms, &m->margin, &m->retunes);
    }

    mvr_auto_choice *a = &r->stats.auto_choice;
    memset(a, 0, sizeof *a);
    if (r->requested_path == MVR_VIEW_PATH_AUTO) {
        const mvr_tuner *t = &r->view_tuner;
        a->state = state_of(r, r->view_tuned_frame, t, false);
        a->prior = prior;
        a->chosen = a->state == MVR_AUTO_SETTLED ? view_candidates[t->chosen] : prior;
        a->candidates[0] = view_candidates[0];
        a->candidates[1] = view_candidates[1];
        fill_measured(t, a->state, a->samples, a->cost_ms, &a->margin, &a->retunes);
    }

    mvr_auto_skinning_choice *s = &r->stats.auto_skinning;
    memset(s, 0, sizeof *s);
    if (r->skinning.requested == MVR_SKINNING_PATH_AUTO && r->frame.deform_count) {
        const mvr_tuner *t = &r->skin_tuner;
        /* the first frame with deforms is not keyed yet: waiting too */
        s->state = state_of(r, r->skin_tuned_frame, t, material_busy || (r->skin_tuned_frame && t->phase == MVR_TUNER_IDLE));
        if (r->tuning && !r->skin_tuned_frame)
            s->state = MVR_AUTO_TUNING; /* deforms seen for the first time: measured from the next frame */
        s->prior = mvr_skinning_rule(r->stats.views);
        s->chosen = s->state == MVR_AUTO_SETTLED ? skin_candidates[t->chosen] : r->skinning.path;
        s->candidates[0] = skin_candidates[0];
        s->candidates[1] = skin_candidates[1];
        fill_measured(t, s->state, s->samples, s->cost_ms, &s->margin, &s->retunes);
    }
}
