/* gl: every error path returns an error with a message; nothing crashes. */
#include <stdlib.h>

#include "gl_test_util.h"

/* Runs first, before this process has made any context current. */
static void external_without_current_context_fails(mvr_test_state *t)
{
    mvr_context_desc desc = {0};
    desc.provider = MVR_CONTEXT_PROVIDER_EXTERNAL;
    mvr_context *ctx = (mvr_context *)&desc; /* must be reset to NULL */
    mvr_error err;
    mvr_result r = mvr_context_create(&desc, &ctx, &err);
    CHECK_MSG(t, r == MVR_ERROR_CONTEXT || r == MVR_ERROR_UNSUPPORTED, "%s", mvr_result_name(r));
    CHECK(t, ctx == NULL);
    CHECK_EQ_INT(t, err.result, r);
    CHECK(t, strstr(err.message, "external") != NULL);
}

static void invalid_descriptors_are_refused(mvr_test_state *t)
{
    mvr_context *ctx = NULL;
    mvr_error err;
    mvr_context_desc desc = {0};

    desc.provider = (mvr_context_provider)99;
    CHECK(t, mvr_context_create(&desc, &ctx, &err) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(err.message, "provider 99") != NULL);
    CHECK(t, ctx == NULL);

    desc = (mvr_context_desc){0};
    desc.api = (mvr_gl_api)7;
    CHECK(t, mvr_context_create(&desc, &ctx, &err) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(err.message, "api 7") != NULL);

    desc = (mvr_context_desc){0};
    desc.device_index = -1;
    CHECK(t, mvr_context_create(&desc, &ctx, &err) == MVR_ERROR_INVALID_ARGUMENT);

    desc = (mvr_context_desc){0};
    desc.provider = MVR_CONTEXT_PROVIDER_SURFACELESS;
    desc.device_index = 1;
    CHECK(t, mvr_context_create(&desc, &ctx, &err) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(err.message, "device") != NULL);

    CHECK(t, mvr_context_create(&desc, NULL, &err) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_context_create(&desc, NULL, NULL) == MVR_ERROR_INVALID_ARGUMENT);
}

static void missing_device_is_an_error(mvr_test_state *t)
{
    log_sink sink = {0};
    mvr_context_desc desc = {0};
    desc.provider = MVR_CONTEXT_PROVIDER_DEVICE;
    desc.device_index = 999;
    desc.logger.fn = log_sink_fn;
    desc.logger.user_data = &sink;
    mvr_context *ctx = NULL;
    mvr_error err;
    mvr_result r = mvr_context_create(&desc, &ctx, &err);
    CHECK(t, r == MVR_ERROR_INVALID_ARGUMENT || r == MVR_ERROR_UNSUPPORTED);
    CHECK(t, ctx == NULL);
    CHECK_MSG(t, strstr(err.message, "999") != NULL, "%s", err.message);
    /* the failure also went to the logger */
    CHECK_EQ_INT(t, sink.errors, 1);
    CHECK(t, strstr(sink.last_error, "999") != NULL);
}

/* ctest runs this file with DISPLAY and WAYLAND_DISPLAY unset. Mesa's EGL
 * then has no default display; NVIDIA's has one without any window system
 * (seen on an H100, driver 580): there a pbuffer context must simply work. */
static void pbuffer_without_display_fails(mvr_test_state *t)
{
    if (getenv("DISPLAY") || getenv("WAYLAND_DISPLAY"))
        SKIP(t, "a display is set; this case needs none");
    mvr_context_desc desc = {0};
    desc.provider = MVR_CONTEXT_PROVIDER_PBUFFER;
    mvr_context *ctx = NULL;
    mvr_error err;
    mvr_result r = mvr_context_create(&desc, &ctx, &err);
    if (r == MVR_OK) {
        const mvr_caps *caps = mvr_context_caps(ctx);
        printf("  this EGL's default display needs no window system: %s\n", caps->renderer);
        CHECK(t, caps->renderer[0] != '\0');
        mvr_context_destroy(ctx);
        return;
    }
    CHECK_MSG(t, r == MVR_ERROR_NO_DISPLAY, "%s: %s", mvr_result_name(r), err.message);
    CHECK(t, ctx == NULL);
    CHECK(t, strstr(err.message, "pbuffer") != NULL);
    CHECK(t, strstr(err.message, "display") != NULL);
}

static void osmesa_refuses_gles(mvr_test_state *t)
{
    mvr_context_desc desc = {0};
    desc.provider = MVR_CONTEXT_PROVIDER_OSMESA;
    desc.api = MVR_GL_API_GLES;
    mvr_context *ctx = NULL;
    mvr_error err;
    mvr_result r = mvr_context_create(&desc, &ctx, &err);
    CHECK_EQ_INT(t, r, MVR_ERROR_UNSUPPORTED);
    CHECK(t, ctx == NULL);
    if (mvr_context_provider_built(MVR_CONTEXT_PROVIDER_OSMESA))
        CHECK(t, strstr(err.message, "desktop OpenGL only") != NULL);
    else
        CHECK(t, strstr(err.message, "not built") != NULL);
}

static void null_objects_are_harmless(mvr_test_state *t)
{
    mvr_context_destroy(NULL);
    CHECK(t, mvr_context_make_current(NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_context_last_error(NULL) != NULL);
    CHECK(t, mvr_context_caps(NULL) == NULL);
}

static void framebuffer_check_names_the_status(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    GLuint fbo = 0;
    ctx->gl.GenFramebuffers(1, &fbo);
    ctx->gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    CHECK(t, mvr_gl_check_framebuffer(ctx, GL_FRAMEBUFFER, "empty_fbo") == MVR_ERROR_FRAMEBUFFER);
    CHECK(t, strstr(mvr_context_last_error(ctx), "empty_fbo") != NULL);
    CHECK(t, strstr(mvr_context_last_error(ctx), "MISSING_ATTACHMENT") != NULL);
    ctx->gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    ctx->gl.DeleteFramebuffers(1, &fbo);
    mvr_context_destroy(ctx);
}

static void provider_names_round_trip(mvr_test_state *t)
{
    for (int i = 0; i < MVR_CONTEXT_PROVIDER_COUNT_; ++i) {
        mvr_context_provider p;
        const char *name = mvr_context_provider_name((mvr_context_provider)i);
        CHECK(t, name != NULL);
        CHECK(t, mvr_context_provider_from_name(name, &p) == MVR_OK && p == (mvr_context_provider)i);
    }
    mvr_context_provider p = MVR_CONTEXT_PROVIDER_DEVICE;
    CHECK(t, mvr_context_provider_from_name("wayland", &p) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK_EQ_INT(t, p, MVR_CONTEXT_PROVIDER_DEVICE);
    CHECK(t, mvr_context_provider_from_name(NULL, &p) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_context_provider_name(MVR_CONTEXT_PROVIDER_COUNT_) == NULL);
}

MVR_TEST_MAIN(TEST(external_without_current_context_fails), TEST(invalid_descriptors_are_refused),
              TEST(missing_device_is_an_error), TEST(pbuffer_without_display_fails),
              TEST(osmesa_refuses_gles), TEST(null_objects_are_harmless),
              TEST(framebuffer_check_names_the_status), TEST(provider_names_round_trip))
