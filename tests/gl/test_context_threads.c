/* gl: one context, several threads (mvr_context_release_current). An EGL
 * context is current on one thread at most (EGL 1.5, section 3.7.3: making a
 * context current that is current on another thread is EGL_BAD_ACCESS), so
 * a context created on one thread renders on another only after the first
 * releases it. The same renderer, target and scene render the same pixels on
 * the main thread, on a worker, and on the main thread again. */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdlib.h>

#include "renderer.h"
#include "stress/stress_util.h"

#define W 16
#define H 16

static const uint8_t orange[3] = {200, 100, 10};

typedef struct job {
    mvr_test_state *t;
    mvr_context *ctx;
    mvr_renderer *r;
    mvr_target *target;
    mvr_scene *scene;
    mvr_view_set *vs;
    bool release;           /* make current, render, release; else only try make current */
    mvr_result make_current;
    bool rendered;
    bool current_after;
} job;

static mvr_scene *orange_quad(mvr_test_state *t)
{
    mvr_scene *s = stress_scene();
    if (!s)
        return NULL;
    uint8_t px[4 * 4 * 4];
    for (int i = 0; i < 16; ++i) {
        px[i * 4] = orange[0];
        px[i * 4 + 1] = orange[1];
        px[i * 4 + 2] = orange[2];
        px[i * 4 + 3] = 255;
    }
    mvr_image_desc id = {.width = 4, .height = 4, .rgba8 = px, .name = "flat"};
    stress_unlit_image_quad(t, s, &id);
    return s;
}

/* Renders; true when the centre pixel is the quad's colour. */
static bool render_orange(job *j, const char *where)
{
    mvr_render_desc rd = {.clear_color = {0, 0, 0, 1}};
    mvr_result res = mvr_renderer_render(j->r, j->scene, j->vs, j->target, &rd);
    uint8_t px[W * H * 4];
    if (res == MVR_OK)
        res = mvr_renderer_read_layer(j->r, j->target, 0, MVR_READBACK_RGBA8, px, sizeof px);
    CHECK_MSG(j->t, res == MVR_OK, "%s: %s", where, mvr_renderer_last_error(j->r));
    if (res != MVR_OK)
        return false;
    const uint8_t *c = px + ((H / 2) * W + W / 2) * 4;
    bool ok = true;
    for (int k = 0; k < 3; ++k)
        ok = ok && abs((int)c[k] - (int)orange[k]) <= 1;
    CHECK_MSG(j->t, ok, "%s: centre pixel %u,%u,%u", where, c[0], c[1], c[2]);
    return ok;
}

static void *worker(void *arg)
{
    job *j = arg;
    j->make_current = mvr_context_make_current(j->ctx);
    if (j->make_current == MVR_OK && j->release) {
        j->rendered = render_orange(j, "worker thread");
        CHECK_MSG(j->t, mvr_context_release_current(j->ctx) == MVR_OK, "worker release: %s",
                  mvr_context_last_error(j->ctx));
    }
    j->current_after = mvr_context_is_current(j->ctx);
    return NULL;
}

static void run_worker(job *j, bool release)
{
    j->release = release;
    j->rendered = false;
    pthread_t th;
    CHECK(j->t, pthread_create(&th, NULL, worker, j) == 0);
    pthread_join(th, NULL);
}

static void round_trip(mvr_test_state *t, mvr_context_provider provider)
{
    mvr_context *ctx = create_or_report(t, provider, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    job j = {.t = t, .ctx = ctx, .scene = orange_quad(t), .vs = stress_front_view_set(t)};
    mvr_renderer_desc rd = {.context = ctx};
    mvr_error err;
    CHECK_MSG(t, mvr_renderer_create(&rd, &j.r, &err) == MVR_OK, "renderer: %s", err.message);
    mvr_target_desc td = {.width = W, .height = H, .layers = 1};
    CHECK(t, j.r && mvr_target_create(j.r, &td, &j.target) == MVR_OK);
    if (!j.target)
        goto done;
    render_orange(&j, "main thread, the creating one");

    if (provider != MVR_CONTEXT_PROVIDER_OSMESA) {
        /* still current here: EGL refuses it to another thread */
        run_worker(&j, false);
        CHECK_EQ_INT(t, j.make_current, MVR_ERROR_CONTEXT);
        CHECK(t, strstr(mvr_context_last_error(ctx), "EGL_BAD_ACCESS") != NULL);
        CHECK(t, mvr_context_is_current(ctx));
    }

    CHECK_MSG(t, mvr_context_release_current(ctx) == MVR_OK, "%s", mvr_context_last_error(ctx));
    CHECK(t, !mvr_context_is_current(ctx));
    /* released: the main thread's calls fail, changing nothing */
    CHECK_EQ_INT(t, mvr_renderer_render(j.r, j.scene, j.vs, j.target, NULL), MVR_ERROR_CONTEXT);
    /* released twice: nothing to do */
    CHECK_EQ_INT(t, mvr_context_release_current(ctx), MVR_OK);

    run_worker(&j, true);
    CHECK_MSG(t, j.make_current == MVR_OK, "worker make_current: %s", mvr_context_last_error(ctx));
    CHECK(t, j.rendered);
    CHECK(t, !j.current_after);

    CHECK_MSG(t, mvr_context_make_current(ctx) == MVR_OK, "back on main: %s", mvr_context_last_error(ctx));
    render_orange(&j, "main thread again");

    /* another context current here: releasing this one leaves it alone */
    mvr_context *other = create_or_report(t, provider, MVR_GL_API_DEFAULT, NULL);
    if (other) {
        CHECK_EQ_INT(t, mvr_context_release_current(ctx), MVR_OK);
        CHECK(t, mvr_context_is_current(other));
        mvr_context_destroy(other);
    }
done:
    mvr_target_destroy(j.target);
    mvr_renderer_destroy(j.r);
    mvr_view_set_destroy(j.vs);
    mvr_scene_destroy(j.scene);
    mvr_context_destroy(ctx);
}

static void egl_round_trip(mvr_test_state *t)
{
    round_trip(t, MVR_CONTEXT_PROVIDER_SURFACELESS);
    CHECK_EQ_INT(t, mvr_context_release_current(NULL), MVR_ERROR_INVALID_ARGUMENT);
}

static void osmesa_round_trip(mvr_test_state *t)
{
    if (!mvr_context_provider_built(MVR_CONTEXT_PROVIDER_OSMESA))
        SKIP(t, "built without OSMesa");
    round_trip(t, MVR_CONTEXT_PROVIDER_OSMESA);
}

MVR_TEST_MAIN(TEST(egl_round_trip), TEST(osmesa_round_trip))
