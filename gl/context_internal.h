/* The context object shared by every module of the GL backend. */
#ifndef MVR_CONTEXT_INTERNAL_H
#define MVR_CONTEXT_INTERNAL_H

#include "core_util.h"
#include "gl_api.h"
#include "provider.h"

struct mvr_context {
    mvr_context_provider provider_kind;
    const mvr_provider_ops *ops;   /* NULL for EXTERNAL */
    mvr_provider *provider;        /* NULL for EXTERNAL */
    mvr_get_proc_fn external_get_proc;
    void *external_user_data;
    mvr_logger logger;
    bool check_errors;             /* glGetError after public GL paths */
    bool debug_installed;          /* our KHR_debug callback is set on this context */
    mvr_gl_api_table gl;
    mvr_caps caps;
    char last_error[MVR_ERROR_MESSAGE_SIZE];
};

/* Records a failure of a public call on ctx: the message is kept for
 * mvr_context_last_error and logged. Returns result. */
mvr_result mvr_context_fail(mvr_context *ctx, mvr_result result, const char *fmt, ...)
    MVR_PRINTF(3, 4);

/* Drains glGetError. When errors were pending, fails ctx with MVR_ERROR_GL
 * naming `where`; otherwise returns MVR_OK. Does nothing unless check_errors
 * (debug builds, or desc.debug) or force is set. */
mvr_result mvr_gl_check(mvr_context *ctx, const char *where, bool force);

/* Checks the bound framebuffer on target; fails ctx naming `where` if incomplete. */
mvr_result mvr_gl_check_framebuffer(mvr_context *ctx, GLenum target, const char *where);

/* Human-readable names for GL enums in messages. */
const char *mvr_gl_error_name(GLenum error);
const char *mvr_gl_framebuffer_status_name(GLenum status);

/* Installs the KHR_debug callback that forwards driver messages to the logger. */
void mvr_gl_debug_install(mvr_context *ctx);

/* Probes version, extensions, limits and bugs into ctx->caps (gl/caps.c). */
void mvr_caps_probe(mvr_context *ctx);

#endif
