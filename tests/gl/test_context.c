/* gl: context providers create working contexts; objects stay independent. */
#include "gl_test_util.h"

/* Draws nothing, but proves the context does real work: clear a 4x4
 * renderbuffer to a color and read it back. */
static void clear_and_read(mvr_test_state *t, mvr_context *ctx, float r, float g)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    GLuint rb = 0, fbo = 0;
    gl->GenRenderbuffers(1, &rb);
    gl->BindRenderbuffer(GL_RENDERBUFFER, rb);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, 0, GL_RGBA8, 4, 4);
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    CHECK(t, mvr_gl_check_framebuffer(ctx, GL_FRAMEBUFFER, "test") == MVR_OK);
    gl->ClearColor(r, g, 0.0f, 1.0f);
    gl->Clear(GL_COLOR_BUFFER_BIT);
    unsigned char px[4 * 4 * 4] = {0};
    gl->ReadPixels(0, 0, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, px);
    CHECK_EQ_INT(t, px[0], (int)(r * 255.0f + 0.5f));
    CHECK_EQ_INT(t, px[1], (int)(g * 255.0f + 0.5f));
    CHECK_EQ_INT(t, px[63], 255);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteRenderbuffers(1, &rb);
    CHECK(t, mvr_gl_check(ctx, "clear_and_read", true) == MVR_OK);
}

static void check_caps_sane(mvr_test_state *t, const mvr_caps *c, mvr_gl_api api)
{
    CHECK_EQ_INT(t, c->api, api);
    CHECK(t, c->renderer[0] && c->version[0] && c->glsl_version[0]);
    if (api == MVR_GL_API_GLES)
        CHECK_MSG(t, c->gl_major >= 3, "GLES %d.%d", c->gl_major, c->gl_minor);
    else
        CHECK_MSG(t, c->gl_major > 4 || (c->gl_major == 4 && c->gl_minor >= 3), "GL %d.%d",
                  c->gl_major, c->gl_minor);
    CHECK(t, c->limits.max_texture_size >= 2048);
    CHECK(t, c->limits.max_array_texture_layers >= 256);
    CHECK(t, c->limits.max_uniform_block_size >= 16384);
    CHECK(t, c->limits.uniform_buffer_offset_alignment >= 1);
}

static void surfaceless_gles(mvr_test_state *t)
{
    log_sink sink = {0};
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, &sink);
    if (!ctx)
        return;
    CHECK_EQ_INT(t, mvr_context_get_provider(ctx), MVR_CONTEXT_PROVIDER_SURFACELESS);
    check_caps_sane(t, mvr_context_caps(ctx), MVR_GL_API_GLES);
    CHECK(t, strstr(mvr_context_caps(ctx)->version, "OpenGL ES") != NULL);
    CHECK(t, mvr_context_caps(ctx)->egl_version[0] != '\0');
    CHECK(t, mvr_context_make_current(ctx) == MVR_OK);
    clear_and_read(t, ctx, 1.0f, 0.0f);
    CHECK_EQ_INT(t, sink.errors, 0);
    CHECK(t, strcmp(mvr_context_last_error(ctx), "") == 0);
    mvr_context_destroy(ctx);
}

static void surfaceless_desktop_gl(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DESKTOP, NULL);
    if (!ctx)
        return;
    check_caps_sane(t, mvr_context_caps(ctx), MVR_GL_API_DESKTOP);
    clear_and_read(t, ctx, 0.0f, 1.0f);
    mvr_context_destroy(ctx);
}

static void device_platform(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_DEVICE, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    CHECK(t, mvr_context_caps(ctx)->egl_device[0] != '\0');
    check_caps_sane(t, mvr_context_caps(ctx), MVR_GL_API_GLES);
    clear_and_read(t, ctx, 1.0f, 1.0f);
    mvr_context_destroy(ctx);
}

static void osmesa_desktop_core(mvr_test_state *t)
{
    if (!mvr_context_provider_built(MVR_CONTEXT_PROVIDER_OSMESA))
        SKIP(t, "this build has no OSMesa provider (MVR_WITH_OSMESA=OFF or libosmesa6-dev missing)");
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_OSMESA, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    check_caps_sane(t, mvr_context_caps(ctx), MVR_GL_API_DESKTOP);
    CHECK(t, strstr(mvr_context_caps(ctx)->version, "Core Profile") != NULL);
    CHECK(t, mvr_context_caps(ctx)->egl_version[0] == '\0');
    clear_and_read(t, ctx, 0.0f, 0.0f);
    mvr_context_destroy(ctx);
}

static void default_provider_picks_one(mvr_test_state *t)
{
    mvr_context *ctx = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_context_create(NULL, &ctx, &err) == MVR_OK, "%s", err.message);
    if (!ctx)
        return;
    mvr_context_provider p = mvr_context_get_provider(ctx);
    CHECK(t, p == MVR_CONTEXT_PROVIDER_SURFACELESS || p == MVR_CONTEXT_PROVIDER_DEVICE ||
                 p == MVR_CONTEXT_PROVIDER_PBUFFER);
    mvr_context_destroy(ctx);
}

/* Two contexts: destroying one leaves the other working (no shared state,
 * and the EGL display is not terminated under the survivor). */
static void two_contexts_are_independent(mvr_test_state *t)
{
    mvr_context *a = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    mvr_context *b = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (a && b) {
        CHECK(t, mvr_context_make_current(a) == MVR_OK);
        clear_and_read(t, a, 1.0f, 0.0f);
        CHECK(t, mvr_context_make_current(b) == MVR_OK);
        clear_and_read(t, b, 0.0f, 1.0f);
        mvr_context_destroy(a);
        a = NULL;
        CHECK(t, mvr_context_make_current(b) == MVR_OK);
        clear_and_read(t, b, 1.0f, 1.0f);
    }
    mvr_context_destroy(a);
    mvr_context_destroy(b);
}

/* EXTERNAL adopts the context current on the thread, creates nothing, and
 * leaves it alive (and current) when destroyed. */
static void external_adopts_current_context(mvr_test_state *t)
{
    mvr_context *owner = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!owner)
        return;
    mvr_context_desc desc = {0};
    desc.provider = MVR_CONTEXT_PROVIDER_EXTERNAL;
    desc.debug = true;
    mvr_context *ext = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_context_create(&desc, &ext, &err) == MVR_OK, "%s", err.message);
    if (ext) {
        CHECK_EQ_INT(t, mvr_context_get_provider(ext), MVR_CONTEXT_PROVIDER_EXTERNAL);
        CHECK(t, strcmp(mvr_context_caps(ext)->renderer, mvr_context_caps(owner)->renderer) == 0);
        CHECK_EQ_INT(t, mvr_context_caps(ext)->api, MVR_GL_API_GLES);
        CHECK(t, mvr_context_make_current(ext) == MVR_OK);
        clear_and_read(t, ext, 0.0f, 1.0f);
        mvr_context_destroy(ext);
    }
    /* the application's context is still current and working */
    CHECK(t, owner->gl.GetString(GL_VERSION) != NULL);
    clear_and_read(t, owner, 1.0f, 0.0f);
    mvr_context_destroy(owner);
}

static void *counting_get_proc(const char *name, void *user)
{
    mvr_context *owner = ((void **)user)[0];
    int *calls = ((void **)user)[1];
    (*calls)++;
    return owner->ops->get_proc(name, owner->provider);
}

static void external_uses_application_loader(mvr_test_state *t)
{
    mvr_context *owner = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!owner)
        return;
    int calls = 0;
    void *user[2] = {owner, &calls};
    mvr_context_desc desc = {0};
    desc.provider = MVR_CONTEXT_PROVIDER_EXTERNAL;
    desc.get_proc_address = counting_get_proc;
    desc.get_proc_user_data = user;
    mvr_context *ext = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_context_create(&desc, &ext, &err) == MVR_OK, "%s", err.message);
    CHECK_MSG(t, calls > 100, "the application's loader was called %d times", calls);
    mvr_context_destroy(ext);
    mvr_context_destroy(owner);
}

static void debug_context_forwards_driver_messages(mvr_test_state *t)
{
    log_sink sink = {0};
    mvr_context_desc desc = {0};
    desc.provider = MVR_CONTEXT_PROVIDER_SURFACELESS;
    desc.debug = true;
    desc.logger.fn = log_sink_fn;
    desc.logger.user_data = &sink;
    mvr_context *ctx = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_context_create(&desc, &ctx, &err) == MVR_OK, "%s", err.message);
    if (!ctx)
        return;
    if (!mvr_context_caps(ctx)->ext.khr_debug) {
        mvr_context_destroy(ctx);
        SKIP(t, "no KHR_debug on %s", mvr_context_caps(ctx)->renderer);
    }
    /* an invalid enum: the driver reports it through KHR_debug, and the check
     * after it fails with a message naming where */
    ctx->gl.Enable(0x1234);
    CHECK(t, sink.errors >= 1);
    CHECK(t, mvr_gl_check(ctx, "test_enable", false) == MVR_ERROR_GL);
    CHECK(t, strstr(mvr_context_last_error(ctx), "test_enable") != NULL);
    CHECK(t, strstr(mvr_context_last_error(ctx), "GL_INVALID_ENUM") != NULL);
    CHECK(t, mvr_gl_check(ctx, "after", false) == MVR_OK); /* drained */
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(surfaceless_gles), TEST(surfaceless_desktop_gl), TEST(device_platform),
              TEST(osmesa_desktop_core), TEST(default_provider_picks_one),
              TEST(two_contexts_are_independent), TEST(external_adopts_current_context),
              TEST(external_uses_application_loader), TEST(debug_context_forwards_driver_messages))
