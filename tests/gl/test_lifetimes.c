/* gl: lifetimes and the current context (mvr.h, "Lifetimes and the current
 * context"). Context, renderer, scene and target are destroyed in all 24
 * orders, each after a real render, and the survivors are used in between:
 * what lost its renderer or context fails with an error, what did not still
 * renders the right pixels. A renderer called with another context current
 * fails and changes nothing: made current again, it renders what a renderer
 * that never saw the other context renders. Run under ASan + UBSan: a
 * use-after-free or a leak fails the test. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>

#include "renderer.h"
#include "stress/stress_util.h"

#define W 16
#define H 16

/* A textured quad (a texture, an array, a material buffer, geometry: every
 * kind of GL object a scene upload makes) filling an orthographic view. */
static mvr_scene *quad_scene(mvr_test_state *t, uint8_t r, uint8_t g, uint8_t b)
{
    mvr_scene *s = stress_scene();
    if (!s)
        return NULL;
    uint8_t px[4 * 4 * 4];
    for (int i = 0; i < 16; ++i) {
        px[i * 4] = r;
        px[i * 4 + 1] = g;
        px[i * 4 + 2] = b;
        px[i * 4 + 3] = 255;
    }
    mvr_image_desc id = {.width = 4, .height = 4, .rgba8 = px, .name = "flat"};
    stress_unlit_image_quad(t, s, &id);
    return s;
}

static mvr_renderer *make_renderer(mvr_test_state *t, mvr_context *ctx)
{
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_renderer_create(&rd, &r, &err) == MVR_OK, "renderer: %s", err.message);
    return r;
}

static mvr_target *make_target(mvr_test_state *t, mvr_renderer *r)
{
    mvr_target_desc td = {.width = W, .height = H, .layers = 1};
    mvr_target *target = NULL;
    CHECK_MSG(t, r && mvr_target_create(r, &td, &target) == MVR_OK, "target: %s",
              r ? mvr_renderer_last_error(r) : "no renderer");
    return target;
}

/* Renders and checks the centre pixel is the scene's colour (sRGB target:
 * the stored bytes are the texture's, give or take a rounding). */
static bool render_check(mvr_test_state *t, mvr_renderer *r, mvr_scene *s, const mvr_view_set *vs, mvr_target *target,
                         const uint8_t want[3], const char *when)
{
    mvr_render_desc rd = {.clear_color = {0, 0, 0, 1}};
    mvr_result res = mvr_renderer_render(r, s, vs, target, &rd);
    CHECK_MSG(t, res == MVR_OK, "%s: render: %s", when, mvr_renderer_last_error(r));
    if (res != MVR_OK)
        return false;
    uint8_t px[W * H * 4];
    res = mvr_renderer_read_layer(r, target, 0, MVR_READBACK_RGBA8, px, sizeof px);
    CHECK_MSG(t, res == MVR_OK, "%s: read: %s", when, mvr_renderer_last_error(r));
    const uint8_t *c = px + ((H / 2) * W + W / 2) * 4;
    bool ok = res == MVR_OK;
    for (int k = 0; k < 3 && ok; ++k)
        ok = abs((int)c[k] - (int)want[k]) <= 1;
    CHECK_MSG(t, ok, "%s: centre pixel %u,%u,%u, want %u,%u,%u", when, c[0], c[1], c[2], want[0], want[1], want[2]);
    return ok;
}

enum { OBJ_CONTEXT, OBJ_RENDERER, OBJ_SCENE, OBJ_TARGET, OBJ_COUNT };
static const char *const obj_names[OBJ_COUNT] = {"context", "renderer", "scene", "target"};

typedef struct objects {
    mvr_context *ctx;
    mvr_renderer *r;
    mvr_scene *scene;
    mvr_target *target;
} objects;

static void destroy_one(objects *o, int which)
{
    switch (which) {
    case OBJ_CONTEXT: mvr_context_destroy(o->ctx); o->ctx = NULL; break;
    case OBJ_RENDERER: mvr_renderer_destroy(o->r); o->r = NULL; break;
    case OBJ_SCENE: mvr_scene_destroy(o->scene); o->scene = NULL; break;
    case OBJ_TARGET: mvr_target_destroy(o->target); o->target = NULL; break;
    }
}

/* What the survivors can still do, and what they must refuse. */
static void use_survivors(mvr_test_state *t, objects *o, bool context_gone, bool renderer_gone, mvr_scene *spare,
                          const mvr_view_set *vs, const char *when)
{
    static const uint8_t red[3] = {255, 0, 0}, blue[3] = {0, 0, 255};
    mvr_scene *scene = o->scene ? o->scene : spare;
    const uint8_t *colour = o->scene ? red : blue;
    char what[256];
    if (o->r && o->target && !context_gone) {
        /* whatever else went, renderer and target on a live context render */
        snprintf(what, sizeof what, "%s, renderer and target alive", when);
        render_check(t, o->r, scene, vs, o->target, colour, what);
    }
    if (o->r && context_gone) {
        /* every call that needs GL fails; none touches the freed context */
        mvr_target *x = NULL;
        mvr_target_desc td = {.width = W, .height = H};
        CHECK_EQ_INT(t, mvr_target_create(o->r, &td, &x), MVR_ERROR_CONTEXT);
        CHECK(t, x == NULL);
        CHECK(t, strstr(mvr_renderer_last_error(o->r), "context was destroyed") != NULL);
        CHECK_EQ_INT(t, mvr_renderer_finish(o->r), MVR_ERROR_CONTEXT);
        if (o->target) {
            /* the target was detached with the context: the renderer sees it as not its own */
            CHECK(t, mvr_renderer_render(o->r, scene, vs, o->target, NULL) != MVR_OK);
            uint8_t px[W * H * 4];
            CHECK(t, mvr_renderer_read_layer(o->r, o->target, 0, MVR_READBACK_RGBA8, px, sizeof px) != MVR_OK);
        }
        mvr_frame_stats st;
        mvr_renderer_get_stats(o->r, &st);
        CHECK(t, mvr_renderer_program_count(o->r) > 0); /* what it built is still described */
    }
    if (o->target && (renderer_gone || context_gone)) {
        /* mvr's color array went with its renderer or context */
        CHECK_EQ_INT(t, mvr_target_color_texture(o->target), 0);
    }
    if (o->ctx) {
        /* the context still renders for a new renderer, and refuses an orphaned target */
        mvr_renderer *r2 = make_renderer(t, o->ctx);
        mvr_target *t2 = make_target(t, r2);
        if (r2 && t2) {
            snprintf(what, sizeof what, "%s, a new renderer on the surviving context", when);
            render_check(t, r2, scene, vs, t2, colour, what);
            if (o->target && renderer_gone) {
                CHECK_EQ_INT(t, mvr_renderer_render(r2, scene, vs, o->target, NULL), MVR_ERROR_INVALID_ARGUMENT);
                CHECK(t, strstr(mvr_renderer_last_error(r2), "released with its renderer") != NULL);
            }
        }
        mvr_target_destroy(t2);
        mvr_renderer_destroy(r2);
    }
}

/* Every order of destroying context, renderer, scene and target. */
static void destroy_in_every_order(mvr_test_state *t)
{
    mvr_context *probe = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!probe)
        return;
    mvr_context_destroy(probe);
    static const uint8_t red[3] = {255, 0, 0};
    int orders = 0;
    int perm[OBJ_COUNT] = {0, 1, 2, 3};
    for (;;) {
        char order[64] = "";
        for (int i = 0; i < OBJ_COUNT; ++i)
            snprintf(order + strlen(order), sizeof order - strlen(order), "%s%s", i ? " > " : "", obj_names[perm[i]]);
        objects o = {0};
        o.ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
        o.scene = quad_scene(t, 255, 0, 0);
        mvr_scene *spare = quad_scene(t, 0, 0, 255);
        mvr_view_set *vs = stress_front_view_set(t);
        o.r = o.ctx ? make_renderer(t, o.ctx) : NULL;
        o.target = make_target(t, o.r);
        if (o.ctx && o.r && o.target && o.scene && spare && vs) {
            render_check(t, o.r, o.scene, vs, o.target, red, order);
            bool context_gone = false, renderer_gone = false;
            for (int i = 0; i < OBJ_COUNT; ++i) {
                destroy_one(&o, perm[i]);
                context_gone |= perm[i] == OBJ_CONTEXT;
                renderer_gone |= perm[i] == OBJ_RENDERER;
                char when[128];
                snprintf(when, sizeof when, "%s: after the %s", order, obj_names[perm[i]]);
                use_survivors(t, &o, context_gone, renderer_gone, spare, vs, when);
            }
        }
        for (int i = 0; i < OBJ_COUNT; ++i)
            destroy_one(&o, perm[i]);
        mvr_scene_destroy(spare);
        mvr_view_set_destroy(vs);
        orders++;
        /* next permutation (lexicographic) */
        int i = OBJ_COUNT - 2;
        while (i >= 0 && perm[i] > perm[i + 1])
            i--;
        if (i < 0)
            break;
        int j = OBJ_COUNT - 1;
        while (perm[j] < perm[i])
            j--;
        int tmp = perm[i];
        perm[i] = perm[j];
        perm[j] = tmp;
        for (int a = i + 1, b = OBJ_COUNT - 1; a < b; ++a, --b) {
            tmp = perm[a];
            perm[a] = perm[b];
            perm[b] = tmp;
        }
    }
    CHECK_EQ_INT(t, orders, 24);
}

/* A renderer called with another context current fails (MVR_ERROR_CONTEXT)
 * and changes nothing, in either context: made current again it renders the
 * bytes of a renderer that never saw the other context. */
static void wrong_context_changes_nothing(mvr_test_state *t)
{
    log_sink sink = {0};
    mvr_context *a = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, &sink);
    if (!a)
        return;
    mvr_scene *s = quad_scene(t, 30, 200, 90);
    mvr_view_set *vs = stress_front_view_set(t);
    static const uint8_t green[3] = {30, 200, 90};
    /* on A: one renderer that rendered before the other context existed, one that never rendered */
    mvr_renderer *used = make_renderer(t, a), *fresh = make_renderer(t, a);
    mvr_target *used_target = make_target(t, used), *fresh_target = make_target(t, fresh);
    if (used_target)
        render_check(t, used, s, vs, used_target, green, "before the second context");
    mvr_context *b = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (b && used_target && fresh_target) {
        /* B is current now (mvr_context_create made it so) */
        mvr_render_desc rd = {.clear_color = {0, 0, 0, 1}};
        CHECK_EQ_INT(t, mvr_renderer_render(used, s, vs, used_target, &rd), MVR_ERROR_CONTEXT);
        CHECK_MSG(t, strstr(mvr_renderer_last_error(used), "not current") != NULL, "message: %s",
                  mvr_renderer_last_error(used));
        CHECK_EQ_INT(t, mvr_renderer_render(fresh, s, vs, fresh_target, &rd), MVR_ERROR_CONTEXT);
        uint8_t px[W * H * 4];
        CHECK_EQ_INT(t, mvr_renderer_read_layer(used, used_target, 0, MVR_READBACK_RGBA8, px, sizeof px),
                     MVR_ERROR_CONTEXT);
        CHECK_EQ_INT(t, mvr_renderer_finish(used), MVR_ERROR_CONTEXT);
        mvr_target *x = NULL;
        mvr_target_desc td = {.width = W, .height = H};
        CHECK_EQ_INT(t, mvr_target_create(used, &td, &x), MVR_ERROR_CONTEXT);
        CHECK(t, x == NULL);
        mvr_renderer_desc rdesc = {.context = a};
        mvr_renderer *y = NULL;
        mvr_error err;
        CHECK_EQ_INT(t, mvr_renderer_create(&rdesc, &y, &err), MVR_ERROR_CONTEXT);
        CHECK(t, y == NULL && strstr(err.message, "not current") != NULL);
        /* nothing was sent to B: no error there, its context still its own */
        CHECK_EQ_INT(t, b->gl.GetError(), GL_NO_ERROR);
        CHECK(t, mvr_context_is_current(b) && !mvr_context_is_current(a));
        /* a renderer destroyed while B is current: its objects wait for A */
        mvr_renderer *doomed = NULL;
        CHECK(t, mvr_context_make_current(a) == MVR_OK);
        doomed = make_renderer(t, a);
        mvr_target *doomed_target = make_target(t, doomed);
        if (doomed_target)
            render_check(t, doomed, s, vs, doomed_target, green, "a renderer to destroy");
        CHECK(t, mvr_context_make_current(b) == MVR_OK);
        mvr_target_destroy(doomed_target);
        mvr_renderer_destroy(doomed);
        CHECK_MSG(t, a->garbage_count > 0, "%u GL objects queued for A", a->garbage_count);
        CHECK_EQ_INT(t, b->gl.GetError(), GL_NO_ERROR);

        /* the right context again: both render as if the failures never happened */
        CHECK(t, mvr_context_make_current(a) == MVR_OK);
        CHECK_EQ_INT(t, a->garbage_count, 0);
        uint8_t got_used[W * H * 4], got_fresh[W * H * 4], want[W * H * 4];
        bool ok = render_check(t, used, s, vs, used_target, green, "used, back on A") &&
                  render_check(t, fresh, s, vs, fresh_target, green, "fresh, back on A") &&
                  mvr_renderer_read_layer(used, used_target, 0, MVR_READBACK_RGBA8, got_used, sizeof got_used) ==
                      MVR_OK &&
                  mvr_renderer_read_layer(fresh, fresh_target, 0, MVR_READBACK_RGBA8, got_fresh, sizeof got_fresh) ==
                      MVR_OK;
        /* the reference: a renderer made now, on A, that never saw B */
        mvr_renderer *ref = make_renderer(t, a);
        mvr_target *ref_target = make_target(t, ref);
        ok = ok && ref_target && render_check(t, ref, s, vs, ref_target, green, "reference") &&
             mvr_renderer_read_layer(ref, ref_target, 0, MVR_READBACK_RGBA8, want, sizeof want) == MVR_OK;
        CHECK(t, ok);
        if (ok) {
            CHECK_MSG(t, memcmp(got_used, want, sizeof want) == 0, "used renderer differs from the reference");
            CHECK_MSG(t, memcmp(got_fresh, want, sizeof want) == 0, "fresh renderer differs from the reference");
        }
        mvr_target_destroy(ref_target);
        mvr_renderer_destroy(ref);
    }
    mvr_target_destroy(used_target);
    mvr_target_destroy(fresh_target);
    mvr_renderer_destroy(used);
    mvr_renderer_destroy(fresh);
    mvr_context_destroy(b);
    mvr_context_destroy(a);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
}

static bool says_current(void *user)
{
    return *(const bool *)user;
}

/* EXTERNAL: the application's is_current callback, or the EGL context that
 * was current when the context was adopted, decides. */
static void external_context_checks(mvr_test_state *t)
{
    mvr_context *app = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!app)
        return;
    mvr_scene *s = quad_scene(t, 200, 100, 10);
    mvr_view_set *vs = stress_front_view_set(t);
    static const uint8_t orange[3] = {200, 100, 10};

    /* the callback */
    bool current = true;
    mvr_context_desc cd = {.provider = MVR_CONTEXT_PROVIDER_EXTERNAL, .is_current = says_current,
                           .is_current_user_data = &current};
    mvr_context *ext = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_context_create(&cd, &ext, &err) == MVR_OK, "%s", err.message);
    mvr_renderer *r = ext ? make_renderer(t, ext) : NULL;
    mvr_target *target = make_target(t, r);
    if (target) {
        render_check(t, r, s, vs, target, orange, "callback says current");
        current = false;
        CHECK_EQ_INT(t, mvr_renderer_render(r, s, vs, target, NULL), MVR_ERROR_CONTEXT);
        CHECK(t, strstr(mvr_renderer_last_error(r), "is_current") != NULL);
        CHECK_EQ_INT(t, mvr_context_make_current(ext), MVR_ERROR_CONTEXT);
        current = true;
        render_check(t, r, s, vs, target, orange, "callback says current again");
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_context_destroy(ext);

    /* the adopted EGL context */
    ext = NULL;
    mvr_context_desc plain = {.provider = MVR_CONTEXT_PROVIDER_EXTERNAL};
    CHECK_MSG(t, mvr_context_create(&plain, &ext, &err) == MVR_OK, "%s", err.message);
    r = ext ? make_renderer(t, ext) : NULL;
    target = make_target(t, r);
    mvr_context *other = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (target && other) {
        CHECK_EQ_INT(t, mvr_renderer_render(r, s, vs, target, NULL), MVR_ERROR_CONTEXT);
        CHECK(t, strstr(mvr_renderer_last_error(r), "eglGetCurrentContext") != NULL);
        CHECK(t, mvr_context_make_current(app) == MVR_OK); /* the application switches back */
        render_check(t, r, s, vs, target, orange, "the adopted EGL context current again");
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_context_destroy(ext);
    mvr_context_destroy(other);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(app);
}

/* What a destroyed renderer leaves current is no deleted program. A deleted
 * program that is current stays in use (ES 3.2, 7.3), and NVIDIA's driver
 * (H100, 580.159) gave its name to the next renderer's programs: that
 * renderer's glUseProgram of the name was taken for the old program, and its
 * draws ran the old code, so renders differed at random from renderer to
 * renderer in one context. Mesa never reuses a name, so this checks the cause. */
static void no_deleted_program_stays_current(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_gl_api_table *gl = &ctx->gl;
    mvr_scene *s = quad_scene(t, 200, 100, 50);
    mvr_view_set *vs = stress_front_view_set(t);
    static const uint8_t want[3] = {200, 100, 50};
    for (int round = 0; round < 2; ++round) {
        mvr_renderer *r = make_renderer(t, ctx);
        mvr_target *target = make_target(t, r);
        if (target)
            render_check(t, r, s, vs, target, want, round ? "a second renderer" : "the first renderer");
        GLint current = 0;
        gl->GetIntegerv(GL_CURRENT_PROGRAM, &current);
        CHECK_MSG(t, current != 0, "round %d: the render left no program current (nothing to check)", round);
        mvr_target_destroy(target);
        mvr_renderer_destroy(r);
        gl->GetIntegerv(GL_CURRENT_PROGRAM, &current);
        GLint deleted = GL_FALSE;
        if (current)
            gl->GetProgramiv((GLuint)current, GL_DELETE_STATUS, &deleted);
        CHECK_MSG(t, deleted == GL_FALSE, "round %d: program %d is current after mvr_renderer_destroy, deleted",
                  round, current);
    }
    /* the context's check of a variant builds a program (left current) and deletes it */
    mvr_shader_variant v;
    memset(&v, 0, sizeof v);
    v.program = MVR_PROGRAM_MESH;
    CHECK(t, mvr_context_check_shader_variant(ctx, &v) == MVR_OK);
    GLint current = 0, deleted = GL_FALSE;
    gl->GetIntegerv(GL_CURRENT_PROGRAM, &current);
    if (current)
        gl->GetProgramiv((GLuint)current, GL_DELETE_STATUS, &deleted);
    CHECK_MSG(t, deleted == GL_FALSE, "program %d is current after mvr_context_check_shader_variant, deleted", current);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(destroy_in_every_order), TEST(wrong_context_changes_nothing), TEST(external_context_checks),
              TEST(no_deleted_program_stays_current))
