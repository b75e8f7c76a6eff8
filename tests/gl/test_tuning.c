/* auto's online tuner (gl/tuning.c over core/tuner.h) on a real GL: with a
 * cost hook that says multiview is cheaper it settles on multiview after its
 * measured frames, reports the candidates and their costs, measures again
 * when the view count changes, never changes a pixel while it switches; off,
 * it is the caps rule; a pinned path is not tuned; with the real timers it
 * settles with positive costs; a skinned scene's skinning path is measured
 * after the view path and settles on the cheaper, pixels unchanged; MSAA
 * that multiview cannot draw is not tuned. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>

#include "gl_test_util.h"
#include "mvr/mvr.h"
#include "mvr_test.h"
#include "skin_scene.h"

#define W 64
#define H 48

typedef struct costs {
    double multiview, loop;
    uint32_t calls;
    bool cheap_set;              /* cheap_hook: the cheaper path is set */
    mvr_view_path cheap;
} costs;

static double hook(void *user, mvr_view_path path, const mvr_frame_stats *stats)
{
    costs *c = user;
    c->calls++;
    (void)stats;
    return path == MVR_VIEW_PATH_MULTIVIEW ? c->multiview : c->loop;
}

typedef struct rig {
    mvr_renderer *r;
    mvr_target *tg;
    mvr_scene *scene;
    mvr_view_set *views;
} rig;

static bool rig_make(mvr_test_state *t, const mvr_renderer_desc *rd, uint32_t views, rig *g)
{
    memset(g, 0, sizeof *g);
    mvr_demo_desc dd = {.views = views, .width = W, .height = H};
    mvr_target_desc td = {.width = W, .height = H, .layers = 16, .anti_aliasing = MVR_ANTI_ALIASING_NONE};
    bool ok = mvr_demo_create("ring", &dd, &g->scene, &g->views, NULL) == MVR_OK &&
              mvr_renderer_create(rd, &g->r, NULL) == MVR_OK && mvr_target_create(g->r, &td, &g->tg) == MVR_OK;
    CHECK(t, ok);
    return ok;
}

static void rig_free(rig *g)
{
    mvr_target_destroy(g->tg);
    mvr_renderer_destroy(g->r);
    mvr_view_set_destroy(g->views);
    mvr_scene_destroy(g->scene);
}

/* One frame: its stats and every layer's bytes. */
static bool frame(mvr_test_state *t, rig *g, uint8_t *px, mvr_frame_stats *st)
{
    mvr_render_desc desc = {.exposure = 1.0f};
    bool ok = mvr_renderer_render(g->r, g->scene, g->views, g->tg, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "render: %s", mvr_renderer_last_error(g->r));
    uint32_t n = mvr_view_set_count(g->views);
    for (uint32_t k = 0; ok && k < n; ++k)
        ok = mvr_renderer_read_layer(g->r, g->tg, k, MVR_READBACK_RGBA8, px + (size_t)k * W * H * 4, W * H * 4) ==
             MVR_OK;
    mvr_renderer_get_stats(g->r, st);
    return ok;
}

static void settles_on_the_cheaper_path_without_changing_a_pixel(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    if (!mvr_context_caps(ctx)->ext.ovr_multiview2) {
        mvr_context_destroy(ctx);
        SKIP(t, "no GL_OVR_multiview2: one candidate, nothing to tune");
    }
    costs c = {.multiview = 5.0, .loop = 10.0};
    /* the material path pinned: this is the view path's decision alone */
    mvr_renderer_desc rd = {.context = ctx, .material_path = MVR_MATERIAL_PATH_ARRAYS,
                            .tuning = {.frame_cost = hook, .user = &c}};
    rig g;
    size_t bytes = (size_t)W * H * 4 * 6;
    uint8_t *first = malloc(bytes), *px = malloc(bytes);
    if (rig_make(t, &rd, 6, &g) && first && px) {
        mvr_frame_stats st;
        CHECK(t, frame(t, &g, first, &st));
        mvr_view_path prior = st.auto_choice.prior;
        /* the first frame runs the caps rule's choice */
        CHECK(t, st.view_path == prior && st.auto_choice.state == MVR_AUTO_TUNING);
        uint32_t frames = 1, switched = 0;
        mvr_view_path last = st.view_path;
        while (st.auto_choice.state != MVR_AUTO_SETTLED && frames < 20) {
            CHECK(t, frame(t, &g, px, &st));
            CHECK_MSG(t, memcmp(px, first, bytes) == 0, "frame %u (%s) differs", frames,
                      mvr_view_path_name(st.view_path));
            switched += st.view_path != last;
            last = st.view_path;
            frames++;
        }
        const mvr_auto_choice *a = &st.auto_choice;
        CHECK_MSG(t, a->state == MVR_AUTO_SETTLED && frames == 13, "settled after %u frames", frames);
        CHECK(t, switched >= 2 && c.calls == 6);
        CHECK(t, a->chosen == MVR_VIEW_PATH_MULTIVIEW && a->candidates[0] == MVR_VIEW_PATH_MULTIVIEW &&
                 a->candidates[1] == MVR_VIEW_PATH_LOOP);
        CHECK(t, a->samples[0] == 3 && a->samples[1] == 3 && a->cost_ms[0] == 5.0 && a->cost_ms[1] == 10.0);
        CHECK(t, prior == MVR_VIEW_PATH_MULTIVIEW ? a->margin == 0.0 : a->margin == 0.5);
        /* settled: multiview, measured no more, the same bytes */
        for (int i = 0; i < 3; ++i) {
            CHECK(t, frame(t, &g, px, &st) && memcmp(px, first, bytes) == 0);
            CHECK(t, st.view_path == MVR_VIEW_PATH_MULTIVIEW && st.auto_choice.state == MVR_AUTO_SETTLED);
        }
        CHECK(t, c.calls == 6);
        /* another view count: measured again, the prior first */
        mvr_view_set_destroy(g.views);
        mvr_scene_destroy(g.scene);
        g.views = NULL;
        g.scene = NULL;
        mvr_demo_desc dd = {.views = 4, .width = W, .height = H};
        CHECK(t, mvr_demo_create("ring", &dd, &g.scene, &g.views, NULL) == MVR_OK);
        c.multiview = 20.0; /* now the loop is cheaper */
        frames = 0;
        do {
            CHECK(t, frame(t, &g, px, &st));
            if (frames == 0)
                CHECK(t, st.view_path == prior && st.auto_choice.state == MVR_AUTO_TUNING &&
                             st.auto_choice.retunes == 1);
            frames++;
        } while (st.auto_choice.state != MVR_AUTO_SETTLED && frames < 20);
        CHECK(t, st.auto_choice.chosen == MVR_VIEW_PATH_LOOP && frames == 13);
    }
    free(first);
    free(px);
    rig_free(&g);
    mvr_context_destroy(ctx);
}

static void off_pinned_and_real_timers(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    uint8_t *px = malloc((size_t)W * H * 4 * 6);
    costs c = {.multiview = 1.0, .loop = 100.0};
    /* off: the rule, every frame */
    mvr_renderer_desc off = {.context = ctx, .tuning = {.mode = MVR_TUNING_OFF, .frame_cost = hook, .user = &c}};
    rig g;
    mvr_frame_stats st;
    if (rig_make(t, &off, 6, &g) && px)
        for (int i = 0; i < 10; ++i) {
            CHECK(t, frame(t, &g, px, &st));
            CHECK(t, st.auto_choice.state == MVR_AUTO_RULE && st.view_path == st.auto_choice.prior);
        }
    CHECK(t, c.calls == 0);
    rig_free(&g);
    /* pinned: no tuning, no auto */
    mvr_renderer_desc pinned = {.context = ctx, .view_path = MVR_VIEW_PATH_LOOP,
                                .material_path = MVR_MATERIAL_PATH_ARRAYS,
                                .tuning = {.frame_cost = hook, .user = &c}};
    if (rig_make(t, &pinned, 6, &g) && px)
        for (int i = 0; i < 10; ++i) {
            CHECK(t, frame(t, &g, px, &st));
            CHECK(t, st.auto_choice.state == MVR_AUTO_NONE && st.view_path == MVR_VIEW_PATH_LOOP);
        }
    CHECK(t, c.calls == 0);
    rig_free(&g);
    /* the real timers: settled after the measured frames, with positive costs */
    mvr_renderer_desc real = {.context = ctx};
    if (mvr_context_caps(ctx)->ext.ovr_multiview2 && rig_make(t, &real, 6, &g) && px) {
        /* the view path, then the material path: 12 frames each where the
         * paths differ by 10% or more, up to 36 where closer */
        int frames = 0;
        do
            CHECK(t, frame(t, &g, px, &st));
        while ((st.auto_choice.state == MVR_AUTO_TUNING || st.auto_material.state == MVR_AUTO_TUNING) &&
               ++frames < 2 * 4 * 9 + 1);
        CHECK_MSG(t, st.auto_material.state == MVR_AUTO_SETTLED && st.auto_material.cost_ms[0] > 0.0 &&
                     st.auto_material.cost_ms[1] > 0.0,
                  "material: %s, %.3f / %.3f ms", mvr_auto_state_name(st.auto_material.state),
                  st.auto_material.cost_ms[0], st.auto_material.cost_ms[1]);
        printf("  measured: per_material %.2f ms, arrays %.2f ms: %s\n", st.auto_material.cost_ms[0],
               st.auto_material.cost_ms[1], mvr_material_path_name(st.auto_material.chosen));
        const mvr_auto_choice *a = &st.auto_choice;
        CHECK_MSG(t, a->state == MVR_AUTO_SETTLED && a->cost_ms[0] > 0.0 && a->cost_ms[1] > 0.0,
                  "state %s, costs %.3f / %.3f ms", mvr_auto_state_name(a->state), a->cost_ms[0], a->cost_ms[1]);
        printf("  measured: multiview %.2f ms, loop %.2f ms: %s (margin %.1f%%)\n", a->cost_ms[0], a->cost_ms[1],
               mvr_view_path_name(a->chosen), 100.0 * a->margin);
        rig_free(&g);
    }
    /* MVR_TUNING from the environment */
    mvr_renderer_overrides ov;
    setenv("MVR_TUNING", "off", 1);
    CHECK(t, mvr_renderer_overrides_from_env(&ov, NULL) == MVR_OK && ov.tuning == MVR_OVERRIDE_OFF);
    setenv("MVR_TUNING", "maybe", 1);
    CHECK(t, mvr_renderer_overrides_from_env(&ov, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    unsetenv("MVR_TUNING");
    mvr_renderer_desc bad = {.context = ctx, .tuning = {.mode = (mvr_tuning)9}};
    mvr_renderer *r = NULL;
    CHECK(t, mvr_renderer_create(&bad, &r, NULL) == MVR_ERROR_INVALID_ARGUMENT && !r);
    free(px);
    mvr_context_destroy(ctx);
}

/* The skinning hook: multiview 5 ms, loop 10; pre-skinning 3 ms more than the vertex path. */
static double skin_hook(void *user, mvr_view_path path, const mvr_frame_stats *stats)
{
    costs *c = user;
    c->calls++;
    return (path == MVR_VIEW_PATH_MULTIVIEW ? 5.0 : 10.0) + (stats->skinning_path == MVR_SKINNING_PATH_PRESKIN ? 3.0 : 0.0);
}

static mvr_view_set *strip_views(uint32_t count)
{
    mvr_view_desc views[4];
    memset(views, 0, sizeof views);
    for (uint32_t i = 0; i < count; ++i) {
        double eye[3] = {-0.2 + 0.1 * (double)i, 0.8, 6.0}, target[3] = {-0.2, 0.8, 0.0}, up[3] = {0, 1, 0};
        mvr_view_look_at(&views[i], eye, target, up);
        views[i].projection.yfov = 0.75;
    }
    mvr_view_set_desc vd = {.view_count = count, .views = views};
    mvr_view_set *vs = NULL;
    return mvr_view_set_create(&vd, &vs, NULL) == MVR_OK ? vs : NULL;
}

/* The strip and the quad seen by 4 views, 4 layers. */
static bool skin_rig_make(mvr_test_state *t, const mvr_renderer_desc *rd, skin_scene *k, rig *g)
{
    memset(g, 0, sizeof *g);
    mvr_target_desc td = {.width = W, .height = H, .layers = 4, .anti_aliasing = MVR_ANTI_ALIASING_NONE};
    bool ok = mvr_scene_create(NULL, &g->scene, NULL) == MVR_OK && build_skin_scene(g->scene, k, true, true) == MVR_OK &&
              (g->views = strip_views(4)) != NULL && mvr_renderer_create(rd, &g->r, NULL) == MVR_OK &&
              mvr_target_create(g->r, &td, &g->tg) == MVR_OK;
    CHECK(t, ok);
    return ok;
}

/* Renders until the skinning path settled (at most `limit` frames), every
 * frame's bytes against the first's; returns the frames. */
static uint32_t until_skinning_settles(mvr_test_state *t, rig *g, uint8_t *first, uint8_t *px, uint32_t limit,
                                       mvr_frame_stats *st)
{
    size_t bytes = (size_t)W * H * 4 * mvr_view_set_count(g->views);
    uint32_t frames = 0;
    do {
        CHECK(t, frame(t, g, frames ? px : first, st));
        if (frames)
            CHECK_MSG(t, memcmp(px, first, bytes) == 0, "frame %u (%s, %s) differs", frames,
                      mvr_view_path_name(st->view_path), mvr_skinning_path_name(st->skinning_path));
        frames++;
    } while (st->auto_skinning.state != MVR_AUTO_SETTLED && frames < limit);
    return frames;
}

static void skinning_path_after_the_view_path(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    uint8_t *first = malloc((size_t)W * H * 4 * 4), *px = malloc((size_t)W * H * 4 * 4);
    costs c = {0};
    skin_scene k;
    rig g;
    memset(&g, 0, sizeof g);
    mvr_renderer_desc rd = {.context = ctx, .material_path = MVR_MATERIAL_PATH_ARRAYS,
                            .tuning = {.frame_cost = skin_hook, .user = &c}};
    bool ok = first && px && skin_rig_make(t, &rd, &k, &g);
    if (ok) {
        strip_rotate_tip(g.scene, &k, 60.0);
        mvr_frame_stats st;
        uint32_t frames = until_skinning_settles(t, &g, first, px, 40, &st);
        const mvr_auto_skinning_choice *s = &st.auto_skinning;
        /* the view path first (12 frames, 6 measured), then the skinning path
         * (12 more); the rule's pre-skinning for 4 views is the prior */
        CHECK_MSG(t, s->state == MVR_AUTO_SETTLED && frames == (mv ? 25u : 13u), "%u frames, state %s", frames,
                  mvr_auto_state_name(s->state));
        CHECK(t, s->prior == MVR_SKINNING_PATH_PRESKIN && s->chosen == MVR_SKINNING_PATH_VERTEX &&
                 st.skinning_path == MVR_SKINNING_PATH_VERTEX);
        CHECK(t, s->candidates[0] == MVR_SKINNING_PATH_VERTEX && s->candidates[1] == MVR_SKINNING_PATH_PRESKIN);
        double view_cost = mv ? 5.0 : 10.0;
        CHECK_MSG(t, s->samples[0] == 3 && s->samples[1] == 3 && s->cost_ms[0] == view_cost &&
                     s->cost_ms[1] == view_cost + 3.0,
                  "samples %u/%u, costs %.1f/%.1f", s->samples[0], s->samples[1], s->cost_ms[0], s->cost_ms[1]);
        CHECK(t, s->margin > 0.0);
        if (mv)
            CHECK(t, st.auto_choice.state == MVR_AUTO_SETTLED && st.view_path == MVR_VIEW_PATH_MULTIVIEW);
        CHECK(t, c.calls == (mv ? 12u : 6u));
        /* settled: nothing measured any more */
        for (int i = 0; i < 3; ++i)
            CHECK(t, frame(t, &g, px, &st) && st.auto_skinning.state == MVR_AUTO_SETTLED &&
                         st.skinning_path == MVR_SKINNING_PATH_VERTEX);
        CHECK(t, c.calls == (mv ? 12u : 6u));
    }
    rig_free(&g);
    /* the view path pinned: the skinning path is measured at once */
    c.calls = 0;
    mvr_renderer_desc pinned = {.context = ctx, .view_path = MVR_VIEW_PATH_LOOP,
                                .material_path = MVR_MATERIAL_PATH_ARRAYS,
                                .tuning = {.frame_cost = skin_hook, .user = &c}};
    ok = first && px && skin_rig_make(t, &pinned, &k, &g);
    if (ok) {
        mvr_frame_stats st;
        /* the first frame has no drawn deforms yet; then 12 frames */
        uint32_t frames = until_skinning_settles(t, &g, first, px, 40, &st);
        CHECK_MSG(t, frames == 14 && st.auto_skinning.chosen == MVR_SKINNING_PATH_VERTEX && c.calls == 6,
                  "%u frames, %u calls", frames, c.calls);
        CHECK(t, st.auto_choice.state == MVR_AUTO_NONE && st.view_path == MVR_VIEW_PATH_LOOP);
    }
    rig_free(&g);
    free(first);
    free(px);
    mvr_context_destroy(ctx);
}

/* Multisampling without multisampled multiview draws view by view whatever
 * auto picks: one path, nothing to measure. */
static void msaa_without_multiview_is_not_tuned(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    costs c = {.multiview = 1.0, .loop = 100.0};
    mvr_renderer_desc rd = {.context = ctx,
                            .material_path = MVR_MATERIAL_PATH_ARRAYS,
                            .overrides = {.msaa_multiview = MVR_OVERRIDE_OFF},
                            .tuning = {.frame_cost = hook, .user = &c}};
    mvr_demo_desc dd = {.views = 4, .width = W, .height = H};
    mvr_target_desc td = {.width = W, .height = H, .layers = 4, .samples = 4};
    rig g;
    memset(&g, 0, sizeof g);
    bool ok = mvr_demo_create("ring", &dd, &g.scene, &g.views, NULL) == MVR_OK &&
              mvr_renderer_create(&rd, &g.r, NULL) == MVR_OK && mvr_target_create(g.r, &td, &g.tg) == MVR_OK;
    CHECK(t, ok);
    mvr_render_desc desc = {.exposure = 1.0f};
    for (int i = 0; ok && i < 12; ++i) {
        mvr_frame_stats st;
        CHECK(t, mvr_renderer_render(g.r, g.scene, g.views, g.tg, &desc) == MVR_OK);
        mvr_renderer_get_stats(g.r, &st);
        CHECK_MSG(t, st.auto_choice.state == MVR_AUTO_NONE && st.view_path == MVR_VIEW_PATH_LOOP,
                  "frame %d: %s on %s", i, mvr_auto_state_name(st.auto_choice.state), mvr_view_path_name(st.view_path));
    }
    CHECK(t, c.calls == 0);
    rig_free(&g);
    mvr_context_destroy(ctx);
}

/* The material hook: per-material 4 ms, arrays 8; the loop 1 ms more than multiview. */
static double material_hook(void *user, mvr_view_path path, const mvr_frame_stats *stats)
{
    costs *c = user;
    c->calls++;
    return (stats->material_path == MVR_MATERIAL_PATH_PER_MATERIAL ? 4.0 : 8.0) +
           (path == MVR_VIEW_PATH_LOOP ? 1.0 : 0.0);
}

static void view_path_first_then_the_material_path(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    costs c = {0};
    mvr_renderer_desc rd = {.context = ctx, .tuning = {.frame_cost = material_hook, .user = &c}};
    rig g;
    size_t bytes = (size_t)W * H * 4 * 6;
    uint8_t *first = malloc(bytes), *px = malloc(bytes);
    if (rig_make(t, &rd, 6, &g) && first && px) {
        mvr_frame_stats st;
        CHECK(t, frame(t, &g, first, &st));
        /* the first frame: arrays (the rule) while the view path is measured */
        CHECK(t, st.material_path == MVR_MATERIAL_PATH_ARRAYS && st.auto_material.state == MVR_AUTO_TUNING &&
                 st.auto_material.prior == MVR_MATERIAL_PATH_ARRAYS);
        CHECK(t, !mv || st.auto_choice.state == MVR_AUTO_TUNING);
        uint32_t frames = 1, view_settled_at = mv ? 0 : 1, switches = 0;
        mvr_material_path last = st.material_path;
        while ((st.auto_material.state != MVR_AUTO_SETTLED || (mv && st.auto_choice.state != MVR_AUTO_SETTLED)) &&
               frames < 40) {
            CHECK(t, frame(t, &g, px, &st));
            CHECK_MSG(t, memcmp(px, first, bytes) == 0, "frame %u (%s, %s) differs", frames,
                      mvr_material_path_name(st.material_path), mvr_view_path_name(st.view_path));
            if (view_settled_at)
                switches += st.material_path != last;
            else
                CHECK(t, st.material_path == MVR_MATERIAL_PATH_ARRAYS);
            last = st.material_path;
            frames++;
            if (!view_settled_at && st.auto_choice.state == MVR_AUTO_SETTLED)
                view_settled_at = frames;
        }
        const mvr_auto_material_choice *m = &st.auto_material;
        CHECK_MSG(t, view_settled_at == (mv ? 13u : 1u) && frames == (mv ? 25u : 13u), "view settled at %u, all at %u",
                  view_settled_at, frames);
        CHECK(t, switches >= 2 && m->chosen == MVR_MATERIAL_PATH_PER_MATERIAL);
        CHECK(t, m->candidates[0] == MVR_MATERIAL_PATH_PER_MATERIAL && m->candidates[1] == MVR_MATERIAL_PATH_ARRAYS);
        CHECK(t, m->samples[0] == 3 && m->samples[1] == 3);
        /* the view path measured on arrays; the material path on the view path it settled on */
        double loop_extra = mv ? 0.0 : 1.0;
        CHECK_MSG(t, m->cost_ms[0] == 4.0 + loop_extra && m->cost_ms[1] == 8.0 + loop_extra, "costs %.1f / %.1f",
                  m->cost_ms[0], m->cost_ms[1]);
        CHECK(t, m->margin == 1.0 - (4.0 + loop_extra) / (8.0 + loop_extra));
        if (mv)
            CHECK(t, st.auto_choice.chosen == MVR_VIEW_PATH_MULTIVIEW && st.auto_choice.cost_ms[0] == 8.0 &&
                         st.auto_choice.cost_ms[1] == 9.0);
        CHECK(t, c.calls == (mv ? 12u : 6u));
        /* settled: per-material, the arrays released, nothing sent or measured */
        for (int i = 0; i < 3; ++i) {
            CHECK(t, frame(t, &g, px, &st) && memcmp(px, first, bytes) == 0);
            CHECK(t, st.material_path == MVR_MATERIAL_PATH_PER_MATERIAL && st.texture_groups == 0 &&
                     st.upload_bytes == 0);
        }
        CHECK(t, c.calls == (mv ? 12u : 6u));
        /* another view count: the view path first again, the material path
         * meanwhile on its prior */
        mvr_view_set_destroy(g.views);
        mvr_scene_destroy(g.scene);
        g.views = NULL;
        g.scene = NULL;
        mvr_demo_desc dd = {.views = 4, .width = W, .height = H};
        CHECK(t, mvr_demo_create("ring", &dd, &g.scene, &g.views, NULL) == MVR_OK);
        CHECK(t, frame(t, &g, px, &st));
        CHECK(t, st.material_path == MVR_MATERIAL_PATH_ARRAYS && st.auto_material.state == MVR_AUTO_TUNING);
        CHECK(t, mv ? st.auto_choice.retunes == 1 : st.auto_material.retunes == 1);
    }
    free(first);
    free(px);
    rig_free(&g);
    mvr_context_destroy(ctx);
}

/* c->cheap half as costly as the other path. */
static double cheap_hook(void *user, mvr_view_path path, const mvr_frame_stats *stats)
{
    costs *c = user;
    c->calls++;
    (void)stats;
    return path == c->cheap ? 5.0 : 10.0;
}

static void count_ignored(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    (void)id;
    if (level == MVR_LOG_WARNING && strstr(message, "tuner memory") && strstr(message, "ignored"))
        ++*(uint32_t *)user;
}

/* Runs a renderer on the program cache folder dir until its view path
 * settled; *first: the path of its first frame. Returns the settled choice. */
static mvr_view_path remembered_run(mvr_test_state *t, mvr_context *ctx, const char *dir, costs *c, uint32_t *ignored,
                                    mvr_view_path *first)
{
    mvr_renderer_desc rd = {.context = ctx, .material_path = MVR_MATERIAL_PATH_ARRAYS, .program_cache_dir = dir,
                            .logger = {.fn = count_ignored, .user_data = ignored},
                            .tuning = {.frame_cost = cheap_hook, .user = c}};
    rig g;
    mvr_frame_stats st;
    memset(&st, 0, sizeof st);
    uint8_t *px = malloc((size_t)W * H * 4 * 6);
    if (rig_make(t, &rd, 6, &g) && px) {
        int frames = 0;
        do {
            CHECK(t, frame(t, &g, px, &st));
            if (!frames)
                *first = st.view_path;
            if (!c->cheap_set) /* the path the rule does not start on */
                c->cheap = st.view_path == MVR_VIEW_PATH_LOOP ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP;
            c->cheap_set = true;
        } while (st.auto_choice.state != MVR_AUTO_SETTLED && ++frames < 80);
    }
    free(px);
    rig_free(&g);
    return st.auto_choice.chosen;
}

/* With a program cache folder, a settled choice is remembered: the next
 * renderer (as a later process would) starts on it; a corrupted entry is
 * ignored with a warning, and the prior runs first again. */
static void settled_choices_are_remembered(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    if (!mvr_context_caps(ctx)->ext.ovr_multiview2) {
        mvr_context_destroy(ctx);
        SKIP(t, "no GL_OVR_multiview2: one candidate, nothing to remember");
    }
    char dir[] = "/tmp/mvr-tuning-XXXXXX";
    CHECK(t, mkdtemp(dir) != NULL);
    costs c = {0};
    uint32_t ignored = 0;
    mvr_view_path first = MVR_VIEW_PATH_AUTO, prior = MVR_VIEW_PATH_AUTO;
    CHECK(t, remembered_run(t, ctx, dir, &c, &ignored, &prior) == c.cheap && c.cheap != prior);
    /* read back: the remembered path runs first, and stays */
    CHECK(t, remembered_run(t, ctx, dir, &c, &ignored, &first) == c.cheap);
    CHECK_MSG(t, first == c.cheap && ignored == 0, "first frame %s, %u ignored", mvr_view_path_name(first), ignored);
    /* every entry corrupted: ignored (said), the prior first again */
    char cmd[300];
    snprintf(cmd, sizeof cmd, "for f in %s/tuner-*.txt; do sed -i 's/^runs /runs 1/' \"$f\"; done", dir);
    CHECK(t, system(cmd) == 0);
    CHECK(t, remembered_run(t, ctx, dir, &c, &ignored, &first) == c.cheap);
    CHECK_MSG(t, first == prior && ignored >= 1, "first frame %s, %u ignored", mvr_view_path_name(first), ignored);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    CHECK(t, system(cmd) == 0);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(settled_choices_are_remembered), TEST(settles_on_the_cheaper_path_without_changing_a_pixel), TEST(off_pinned_and_real_timers),
              TEST(view_path_first_then_the_material_path),
              TEST(skinning_path_after_the_view_path), TEST(msaa_without_multiview_is_not_tuned))
