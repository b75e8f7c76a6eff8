/* The context object shared by every module of the GL backend. */
#ifndef MVR_CONTEXT_INTERNAL_H
#define MVR_CONTEXT_INTERNAL_H

#include "core_util.h"
#include "gl_api.h"
#include "provider.h"

/* A GL object whose owner was destroyed while the context was not current:
 * deleted by the next mvr call that finds the context current. */
typedef enum mvr_gl_object {
    MVR_GL_TEXTURE,
    MVR_GL_BUFFER,
    MVR_GL_FRAMEBUFFER,
    MVR_GL_RENDERBUFFER,
    MVR_GL_VERTEX_ARRAY,
    MVR_GL_SAMPLER,
    MVR_GL_PROGRAM,
    MVR_GL_QUERY,
    MVR_GL_SYNC
} mvr_gl_object;

typedef struct mvr_gl_garbage {
    mvr_gl_object kind;
    GLuint name;
    GLsync sync;                   /* MVR_GL_SYNC */
} mvr_gl_garbage;

/* What the KHR_debug callback reads: its own allocation, so a callback left
 * installed in an application's context (destroyed while not current) never
 * reads a freed mvr_context. */
typedef struct mvr_debug_sink {
    mvr_logger logger;
} mvr_debug_sink;

struct mvr_renderer;

struct mvr_context {
    mvr_context_provider provider_kind;
    const mvr_provider_ops *ops;   /* NULL for EXTERNAL */
    mvr_provider *provider;        /* NULL for EXTERNAL */
    mvr_get_proc_fn external_get_proc;
    void *external_user_data;
    mvr_logger logger;
    bool check_errors;             /* glGetError after public GL paths */
    mvr_debug_sink *debug_sink;    /* our KHR_debug callback is set on this context (NULL: not) */
    /* EXTERNAL: how to tell the application's context is current (desc
     * callback; else the EGL context current at create; else trust) */
    mvr_is_current_fn external_is_current;
    void *external_is_current_user_data;
    void *external_egl_context;    /* EGLContext, or NULL (EGL_NO_CONTEXT) */
    unsigned external_egl_api;     /* EGLenum bound when it was captured */
    /* renderers drawing with this context (linked through their next_in_context):
     * destroying the context detaches them */
    struct mvr_renderer *renderers;
    mvr_gl_garbage *garbage;
    uint32_t garbage_count, garbage_cap;
    mvr_gl_api_table gl;
    mvr_caps caps;
    char last_error[MVR_ERROR_MESSAGE_SIZE];
};

/* Records a failure of a public call on ctx: the message is kept for
 * mvr_context_last_error and logged. Returns result. */
mvr_result mvr_context_fail(mvr_context *ctx, mvr_result result, const char *fmt, ...)
    MVR_PRINTF(3, 4);

/* Drains glGetError. When errors were pending, fails ctx naming `where`
 * (MVR_ERROR_OUT_OF_MEMORY when one was GL_OUT_OF_MEMORY, else
 * MVR_ERROR_GL); otherwise returns MVR_OK. Does nothing unless check_errors
 * (debug builds, or desc.debug) or force is set. */
mvr_result mvr_gl_check(mvr_context *ctx, const char *where, bool force);

/* Whether this context is the one current on the calling thread (gl/context.c
 * says how each provider tells). */
bool mvr_context_is_current(const mvr_context *ctx);

/* Before a public call's GL work: fails ctx with MVR_ERROR_CONTEXT naming
 * `where` unless the context is current; then drops (and logs as the
 * application's) GL errors pending from before the call, and deletes the
 * objects waiting for this context. */
mvr_result mvr_context_begin(mvr_context *ctx, const char *where);

/* Deletes a GL object of this context now when it is current, else queues it
 * for the next call that finds it current (a context destroyed first takes
 * its objects with it). name 0 / sync NULL: nothing. */
void mvr_context_delete(mvr_context *ctx, mvr_gl_object kind, GLuint name);
void mvr_context_delete_sync(mvr_context *ctx, GLsync sync);

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
