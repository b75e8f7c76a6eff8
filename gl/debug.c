/* GL error checks and KHR_debug forwarding. */
#include <stdlib.h>
#include <string.h>

#include "context_internal.h"

const char *mvr_gl_error_name(GLenum error)
{
    switch (error) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW_KHR: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW_KHR: return "GL_STACK_UNDERFLOW";
    case GL_CONTEXT_LOST_KHR: return "GL_CONTEXT_LOST";
    default: return "unknown GL error";
    }
}

const char *mvr_gl_framebuffer_status_name(GLenum status)
{
    switch (status) {
    case GL_FRAMEBUFFER_COMPLETE: return "GL_FRAMEBUFFER_COMPLETE";
    case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    case GL_FRAMEBUFFER_INCOMPLETE_VIEW_TARGETS_OVR:
        return "GL_FRAMEBUFFER_INCOMPLETE_VIEW_TARGETS_OVR";
    default: return "unknown framebuffer status";
    }
}

mvr_result mvr_gl_check(mvr_context *ctx, const char *where, bool force)
{
    if (!ctx->check_errors && !force)
        return MVR_OK;
    char names[256] = "";
    size_t used = 0;
    int count = 0;
    bool oom = false;
    /* Bounded: a lost context may report errors forever. */
    for (GLenum e; count < 16 && (e = ctx->gl.GetError()) != GL_NO_ERROR; ++count) {
        mvr_str_format(names + used, sizeof names - used, "%s%s", count ? ", " : "",
                       mvr_gl_error_name(e));
        used = strlen(names);
        oom |= e == GL_OUT_OF_MEMORY;
    }
    if (count == 0)
        return MVR_OK;
    mvr_log(&ctx->logger, MVR_LOG_ERROR, MVR_LOG_ID_GL_ERROR, "mvr: GL error after %s: %s", where,
            names);
    /* out of memory is what the caller can act on (smaller targets, fewer
     * or smaller images); other errors are bugs or misuse */
    return mvr_context_fail(ctx, oom ? MVR_ERROR_OUT_OF_MEMORY : MVR_ERROR_GL, "%s: %s", where, names);
}

mvr_result mvr_gl_check_framebuffer(mvr_context *ctx, GLenum target, const char *where)
{
    GLenum status = ctx->gl.CheckFramebufferStatus(target);
    if (status == GL_FRAMEBUFFER_COMPLETE)
        return MVR_OK;
    return mvr_context_fail(ctx, MVR_ERROR_FRAMEBUFFER, "%s: framebuffer incomplete (%s)", where,
                            mvr_gl_framebuffer_status_name(status));
}

static mvr_log_level debug_level(GLenum severity, GLenum type)
{
    if (type == GL_DEBUG_TYPE_ERROR_KHR)
        return MVR_LOG_ERROR;
    switch (severity) {
    case GL_DEBUG_SEVERITY_HIGH_KHR: return MVR_LOG_ERROR;
    case GL_DEBUG_SEVERITY_MEDIUM_KHR: return MVR_LOG_WARNING;
    case GL_DEBUG_SEVERITY_LOW_KHR: return MVR_LOG_INFO;
    default: return MVR_LOG_DEBUG;
    }
}

static void GL_APIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity,
                                       GLsizei length, const GLchar *message,
                                       const void *user_param)
{
    (void)source;
    (void)length;
    const mvr_debug_sink *sink = user_param;
    mvr_log(&sink->logger, debug_level(severity, type), MVR_LOG_ID_GL_DEBUG, "GL debug %u: %s",
            (unsigned)id, message);
}

void mvr_gl_debug_install(mvr_context *ctx)
{
    if (!ctx->caps.ext.khr_debug || !ctx->gl.DebugMessageCallback || ctx->debug_sink)
        return;
    ctx->debug_sink = calloc(1, sizeof *ctx->debug_sink);
    if (!ctx->debug_sink)
        return;
    ctx->debug_sink->logger = ctx->logger;
    ctx->gl.DebugMessageCallback(debug_callback, ctx->debug_sink);
    ctx->gl.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR);
    ctx->gl.Enable(GL_DEBUG_OUTPUT_KHR);
}
