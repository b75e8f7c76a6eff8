/* mvr_context: picks a provider, loads the entry points, probes the caps. */
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>

#include "context_internal.h"
#include "program.h"
#include "renderer.h"

static const char *const provider_names[MVR_CONTEXT_PROVIDER_COUNT_] = {
    [MVR_CONTEXT_PROVIDER_DEFAULT] = "default",
    [MVR_CONTEXT_PROVIDER_SURFACELESS] = "surfaceless",
    [MVR_CONTEXT_PROVIDER_DEVICE] = "device",
    [MVR_CONTEXT_PROVIDER_PBUFFER] = "pbuffer",
    [MVR_CONTEXT_PROVIDER_OSMESA] = "osmesa",
    [MVR_CONTEXT_PROVIDER_EXTERNAL] = "external",
};

const char *mvr_context_provider_name(mvr_context_provider provider)
{
    if ((unsigned)provider >= MVR_CONTEXT_PROVIDER_COUNT_)
        return NULL;
    return provider_names[provider];
}

mvr_result mvr_context_provider_from_name(const char *name, mvr_context_provider *out)
{
    if (!name || !out)
        return MVR_ERROR_INVALID_ARGUMENT;
    for (int i = 0; i < MVR_CONTEXT_PROVIDER_COUNT_; ++i) {
        if (strcmp(name, provider_names[i]) == 0) {
            *out = (mvr_context_provider)i;
            return MVR_OK;
        }
    }
    return MVR_ERROR_INVALID_ARGUMENT;
}

const char *mvr_gl_api_name(mvr_gl_api api)
{
    switch (api) {
    case MVR_GL_API_DEFAULT: return "default";
    case MVR_GL_API_GLES: return "gles";
    case MVR_GL_API_DESKTOP: return "desktop";
    }
    return NULL;
}

static const mvr_provider_ops *provider_ops(mvr_context_provider kind)
{
    switch (kind) {
    case MVR_CONTEXT_PROVIDER_SURFACELESS:
    case MVR_CONTEXT_PROVIDER_DEVICE:
    case MVR_CONTEXT_PROVIDER_PBUFFER:
        return mvr_provider_egl_ops();
    case MVR_CONTEXT_PROVIDER_OSMESA:
        return mvr_provider_osmesa_ops();
    case MVR_CONTEXT_PROVIDER_DEFAULT:
    case MVR_CONTEXT_PROVIDER_EXTERNAL:
    case MVR_CONTEXT_PROVIDER_COUNT_:
        break;
    }
    return NULL;
}

bool mvr_context_provider_built(mvr_context_provider provider)
{
    switch (provider) {
    case MVR_CONTEXT_PROVIDER_DEFAULT:
    case MVR_CONTEXT_PROVIDER_EXTERNAL:
        return true;
    case MVR_CONTEXT_PROVIDER_SURFACELESS:
    case MVR_CONTEXT_PROVIDER_DEVICE:
    case MVR_CONTEXT_PROVIDER_PBUFFER:
    case MVR_CONTEXT_PROVIDER_OSMESA:
        return provider_ops(provider) != NULL;
    case MVR_CONTEXT_PROVIDER_COUNT_:
        break;
    }
    return false;
}

bool mvr_context_is_current(const mvr_context *ctx)
{
    if (ctx->provider && ctx->ops)
        return ctx->ops->is_current(ctx->provider);
    if (ctx->external_is_current)
        return ctx->external_is_current(ctx->external_is_current_user_data);
    if (ctx->external_egl_context)
        return mvr_egl_current_context(ctx->external_egl_api) == ctx->external_egl_context;
    /* GLX, WGL, ...: no identity to compare; trust the caller, but a thread
     * without any context gets NULL from glvnd's (or Mesa's) no-op dispatch */
    return ctx->gl.GetString && ctx->gl.GetString(GL_VERSION) != NULL;
}

/* Why the context is not current, for messages. */
static const char *not_current_why(const mvr_context *ctx)
{
    if (ctx->provider_kind != MVR_CONTEXT_PROVIDER_EXTERNAL)
        return "another context (or none) is current on this thread: call mvr_context_make_current "
               "(mvr never switches contexts by itself)";
    if (ctx->external_is_current)
        return "the application's is_current callback says its context is not current on this thread";
    if (ctx->external_egl_context)
        return "eglGetCurrentContext() is not the application's context adopted at create time";
    return "no GL context answers on this thread";
}

static void delete_now(const mvr_gl_api_table *gl, const mvr_gl_garbage *g)
{
    GLuint name = g->name;
    switch (g->kind) {
    case MVR_GL_TEXTURE: gl->DeleteTextures(1, &name); return;
    case MVR_GL_BUFFER: gl->DeleteBuffers(1, &name); return;
    case MVR_GL_FRAMEBUFFER: gl->DeleteFramebuffers(1, &name); return;
    case MVR_GL_RENDERBUFFER: gl->DeleteRenderbuffers(1, &name); return;
    case MVR_GL_VERTEX_ARRAY: gl->DeleteVertexArrays(1, &name); return;
    case MVR_GL_SAMPLER: gl->DeleteSamplers(1, &name); return;
    case MVR_GL_PROGRAM: mvr_gl_delete_program(gl, name); return;
    case MVR_GL_QUERY: gl->DeleteQueries(1, &name); return;
    case MVR_GL_SYNC: gl->DeleteSync(g->sync); return;
    }
}

static void defer_delete(mvr_context *ctx, mvr_gl_garbage g)
{
    if (mvr_context_is_current(ctx)) {
        delete_now(&ctx->gl, &g);
        return;
    }
    if (!mvr_array_grow((void **)&ctx->garbage, &ctx->garbage_cap, ctx->garbage_count, sizeof *ctx->garbage)) {
        mvr_log(&ctx->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                "mvr: out of memory queueing a GL object for deletion; it leaks until its context goes");
        return;
    }
    ctx->garbage[ctx->garbage_count++] = g;
}

void mvr_context_delete(mvr_context *ctx, mvr_gl_object kind, GLuint name)
{
    if (!ctx || !name)
        return;
    mvr_gl_garbage g = {kind, name, NULL};
    defer_delete(ctx, g);
}

void mvr_context_delete_sync(mvr_context *ctx, GLsync sync)
{
    if (!ctx || !sync)
        return;
    mvr_gl_garbage g = {MVR_GL_SYNC, 0, sync};
    defer_delete(ctx, g);
}

/* With the context current: deletes what waited for it. */
static void flush_garbage(mvr_context *ctx)
{
    for (uint32_t i = 0; i < ctx->garbage_count; ++i)
        delete_now(&ctx->gl, &ctx->garbage[i]);
    ctx->garbage_count = 0;
}

mvr_result mvr_context_begin(mvr_context *ctx, const char *where)
{
    if (!mvr_context_is_current(ctx))
        return mvr_context_fail(ctx, MVR_ERROR_CONTEXT, "%s: the %s context is not current: %s", where,
                                mvr_context_provider_name(ctx->provider_kind), not_current_why(ctx));
    /* errors from before this call are not mvr's: said as such, and dropped
     * so the check after mvr's work reports only its own */
    char names[256] = "";
    size_t used = 0;
    int count = 0;
    for (GLenum e; count < 16 && (e = ctx->gl.GetError()) != GL_NO_ERROR; ++count) {
        mvr_str_format(names + used, sizeof names - used, "%s%s", count ? ", " : "", mvr_gl_error_name(e));
        used = strlen(names);
    }
    if (count)
        mvr_log(&ctx->logger, MVR_LOG_WARNING, MVR_LOG_ID_GL_ERROR,
                "mvr: %s: %s was pending before mvr's work (an earlier GL call of the application's): dropped",
                where, names);
    flush_garbage(ctx);
    return MVR_OK;
}

mvr_result mvr_context_fail(mvr_context *ctx, mvr_result result, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    mvr_error_record(ctx->last_error, sizeof ctx->last_error, &ctx->logger, result, fmt, ap);
    va_end(ap);
    return result;
}

static void *external_get_proc(const char *name, void *user)
{
    mvr_context *ctx = user;
    if (ctx->external_get_proc)
        return ctx->external_get_proc(name, ctx->external_user_data);
    __eglMustCastToProperFunctionPointerType fp = eglGetProcAddress(name);
    void *addr;
    memcpy(&addr, &fp, sizeof addr);
    return addr;
}

static void *provider_get_proc(const char *name, void *user)
{
    mvr_context *ctx = user;
    return ctx->ops->get_proc(name, ctx->provider);
}

/* Creates the provider's context (not for EXTERNAL / DEFAULT). */
static mvr_result create_provider(mvr_context *ctx, mvr_context_provider kind,
                                  const mvr_context_desc *desc, char *why, size_t why_size)
{
    const mvr_provider_ops *ops = provider_ops(kind);
    if (!ops) {
        mvr_str_format(why, why_size, "the %s provider is not built into this mvr",
                       mvr_context_provider_name(kind));
        return MVR_ERROR_UNSUPPORTED;
    }
    mvr_gl_api api = desc->api;
    if (api == MVR_GL_API_DEFAULT)
        api = kind == MVR_CONTEXT_PROVIDER_OSMESA ? MVR_GL_API_DESKTOP : MVR_GL_API_GLES;
    mvr_result r = ops->create(kind, desc, api, &ctx->provider, why, why_size);
    if (r != MVR_OK)
        return r;
    ctx->ops = ops;
    ctx->provider_kind = kind;
    ctx->caps.api = api;
    return MVR_OK;
}

static bool valid_desc(const mvr_context_desc *desc, mvr_error *error, mvr_result *r)
{
    if (!mvr_context_provider_name(desc->provider)) {
        *r = mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_context_create: provider %d is not an mvr_context_provider",
                           (int)desc->provider);
        return false;
    }
    if (!mvr_gl_api_name(desc->api)) {
        *r = mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_context_create: api %d is not an mvr_gl_api", (int)desc->api);
        return false;
    }
    if (desc->device_index < 0) {
        *r = mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_context_create: device_index %d is negative (0 = automatic)",
                           desc->device_index);
        return false;
    }
    if (desc->device_index > 0 && desc->provider != MVR_CONTEXT_PROVIDER_DEVICE) {
        *r = mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_context_create: device_index is for the device provider only");
        return false;
    }
    return true;
}

/* Loads entry points and probes caps on the current context. */
static mvr_result finish_create(mvr_context *ctx, bool debug_output, mvr_error *error)
{
    char missing[128] = "";
    bool desktop = ctx->caps.api == MVR_GL_API_DESKTOP;
    bool ok = ctx->provider_kind == MVR_CONTEXT_PROVIDER_EXTERNAL
                  ? mvr_gl_api_load(&ctx->gl, external_get_proc, ctx, desktop, missing, sizeof missing)
                  : mvr_gl_api_load(&ctx->gl, provider_get_proc, ctx, desktop, missing, sizeof missing);
    if (!ok)
        return mvr_error_set(error, MVR_ERROR_UNSUPPORTED,
                             "mvr_context_create(%s): the GL lacks %s (OpenGL ES 3.0 or desktop "
                             "GL 4.3 needed)",
                             mvr_context_provider_name(ctx->provider_kind), missing);
    /* glvnd answers any gl* name with a dispatch stub, so a missing current
     * context shows up here: glGetString returns NULL. */
    const GLubyte *version = ctx->gl.GetString(GL_VERSION);
    if (!version)
        return mvr_error_set(error, MVR_ERROR_CONTEXT,
                             "mvr_context_create(%s): no GL context is current "
                             "(glGetString(GL_VERSION) returned NULL)",
                             mvr_context_provider_name(ctx->provider_kind));
    if (ctx->provider_kind == MVR_CONTEXT_PROVIDER_EXTERNAL) {
        ctx->caps.api = strstr((const char *)version, "OpenGL ES") ? MVR_GL_API_GLES
                                                                   : MVR_GL_API_DESKTOP;
        if (ctx->external_is_current && !ctx->external_is_current(ctx->external_is_current_user_data))
            return mvr_error_set(error, MVR_ERROR_CONTEXT,
                                 "mvr_context_create(external): the is_current callback says the "
                                 "application's context is not current");
    }
    /* the application's earlier errors (external) are not the probe's */
    mvr_result begun = mvr_context_begin(ctx, "mvr_context_create");
    if (begun != MVR_OK)
        return mvr_error_set(error, begun, "%s", ctx->last_error);
    mvr_caps_probe(ctx);
    if (ctx->provider)
        ctx->ops->describe(ctx->provider, &ctx->caps);
    bool es3 = ctx->caps.api == MVR_GL_API_GLES && ctx->caps.gl_major >= 3;
    bool gl43 = ctx->caps.api == MVR_GL_API_DESKTOP &&
                (ctx->caps.gl_major > 4 || (ctx->caps.gl_major == 4 && ctx->caps.gl_minor >= 3));
    if (!es3 && !gl43)
        return mvr_error_set(error, MVR_ERROR_UNSUPPORTED,
                             "mvr_context_create(%s): %s is too old: mvr needs OpenGL ES 3.0 or "
                             "desktop GL 4.3 (ES 3.00 shaders)",
                             mvr_context_provider_name(ctx->provider_kind), ctx->caps.version);
    /* Only when asked: on an external context this changes the application's state. */
    if (debug_output)
        mvr_gl_debug_install(ctx);
    mvr_result checked = mvr_gl_check(ctx, "mvr_context_create (capability probe)", true);
    if (checked != MVR_OK)
        return mvr_error_set(error, checked, "%s", ctx->last_error);
    mvr_log(&ctx->logger, MVR_LOG_INFO, MVR_LOG_ID_CONTEXT, "mvr: %s context: %s, %s",
            mvr_context_provider_name(ctx->provider_kind), ctx->caps.version, ctx->caps.renderer);
    return MVR_OK;
}

mvr_result mvr_context_create(const mvr_context_desc *desc_in, mvr_context **out_context,
                              mvr_error *error)
{
    if (error) {
        error->result = MVR_OK;
        error->message[0] = '\0';
    }
    if (!out_context)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_context_create: out_context is NULL");
    *out_context = NULL;
    mvr_context_desc desc;
    if (desc_in)
        desc = *desc_in;
    else
        memset(&desc, 0, sizeof desc);
    mvr_result r;
    if (!valid_desc(&desc, error, &r))
        return r;

    mvr_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_context_create: out of memory");
    ctx->logger = desc.logger;
#ifdef NDEBUG
    ctx->check_errors = desc.debug;
#else
    ctx->check_errors = true;
#endif

    char why[MVR_ERROR_MESSAGE_SIZE] = "";
    if (desc.provider == MVR_CONTEXT_PROVIDER_EXTERNAL) {
        ctx->provider_kind = MVR_CONTEXT_PROVIDER_EXTERNAL;
        ctx->external_get_proc = desc.get_proc_address;
        ctx->external_user_data = desc.get_proc_user_data;
        ctx->external_is_current = desc.is_current;
        ctx->external_is_current_user_data = desc.is_current_user_data;
        if (!desc.is_current) {
            /* the EGL context current now is the application's: its identity */
            ctx->external_egl_api = mvr_egl_bound_api();
            ctx->external_egl_context = mvr_egl_current_context(ctx->external_egl_api);
        }
        r = MVR_OK;
    } else if (desc.provider == MVR_CONTEXT_PROVIDER_DEFAULT) {
        static const mvr_context_provider order[] = {MVR_CONTEXT_PROVIDER_SURFACELESS,
                                                     MVR_CONTEXT_PROVIDER_DEVICE,
                                                     MVR_CONTEXT_PROVIDER_PBUFFER};
        char all[MVR_ERROR_MESSAGE_SIZE] = "";
        r = MVR_ERROR_NO_DISPLAY;
        for (size_t i = 0; i < MVR_ARRAY_COUNT(order); ++i) {
            r = create_provider(ctx, order[i], &desc, why, sizeof why);
            if (r == MVR_OK)
                break;
            mvr_log(&ctx->logger, MVR_LOG_INFO, MVR_LOG_ID_PROVIDER_FALLBACK,
                    "mvr: %s provider unavailable (%s); trying the next",
                    mvr_context_provider_name(order[i]), why);
            size_t used = strlen(all);
            mvr_str_format(all + used, sizeof all - used, "%s%s: %s", used ? "; " : "",
                           mvr_context_provider_name(order[i]), why);
        }
        if (r != MVR_OK)
            mvr_str_copy(why, sizeof why, all);
    } else {
        r = create_provider(ctx, desc.provider, &desc, why, sizeof why);
    }
    if (r != MVR_OK) {
        mvr_error_set(error, r, "mvr_context_create(%s): %s",
                      mvr_context_provider_name(desc.provider), why);
        mvr_log(&desc.logger, MVR_LOG_ERROR, MVR_LOG_ID_ERROR_RESULT,
                "%s: mvr_context_create(%s): %s", mvr_result_name(r),
                mvr_context_provider_name(desc.provider), why);
        mvr_context_destroy(ctx);
        return r;
    }
    r = finish_create(ctx, desc.debug, error);
    if (r != MVR_OK) {
        if (error)
            mvr_log(&desc.logger, MVR_LOG_ERROR, MVR_LOG_ID_ERROR_RESULT, "%s: %s",
                    mvr_result_name(r), error->message);
        mvr_context_destroy(ctx);
        return r;
    }
    *out_context = ctx;
    return MVR_OK;
}

void mvr_context_destroy(mvr_context *ctx)
{
    if (!ctx)
        return;
    bool current = mvr_context_is_current(ctx);
    /* renderers (and their targets) still alive give their GL objects back
     * now and keep only their memory: later calls on them fail, destroys free */
    while (ctx->renderers)
        mvr_renderer_context_destroyed(ctx->renderers);
    if (current) {
        flush_garbage(ctx);
    } else if (ctx->garbage_count && ctx->provider_kind == MVR_CONTEXT_PROVIDER_EXTERNAL) {
        /* mvr's own contexts take their objects with them; the application's outlives us */
        mvr_log(&ctx->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                "mvr: mvr_context_destroy(external): the application's context is not current: %u GL "
                "objects of mvr's stay in it", ctx->garbage_count);
    }
    free(ctx->garbage);
    if (ctx->debug_sink) {
        if (current) {
            /* the callback points at the sink: take it back */
            ctx->gl.DebugMessageCallback(NULL, NULL);
            free(ctx->debug_sink);
        } else if (ctx->provider_kind == MVR_CONTEXT_PROVIDER_EXTERNAL) {
            /* still installed in a context mvr cannot reach: a silent sink
             * stays behind (a few bytes) rather than a dangling pointer */
            ctx->debug_sink->logger.fn = NULL;
        } else {
            free(ctx->debug_sink); /* its context is destroyed below */
        }
    }
    if (ctx->provider && ctx->ops)
        ctx->ops->destroy(ctx->provider);
    free(ctx);
}

mvr_result mvr_context_make_current(mvr_context *ctx)
{
    if (!ctx)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (ctx->provider_kind == MVR_CONTEXT_PROVIDER_EXTERNAL) {
        /* mvr never makes the application's context current; it checks it is. */
        if (!mvr_context_is_current(ctx))
            return mvr_context_fail(ctx, MVR_ERROR_CONTEXT,
                                    "mvr_context_make_current(external): the application's "
                                    "context is not current on this thread (%s)", not_current_why(ctx));
        return MVR_OK;
    }
    char why[MVR_ERROR_MESSAGE_SIZE] = "";
    mvr_result r = ctx->ops->make_current(ctx->provider, why, sizeof why);
    if (r != MVR_OK)
        return mvr_context_fail(ctx, r, "mvr_context_make_current(%s): %s",
                                mvr_context_provider_name(ctx->provider_kind), why);
    flush_garbage(ctx); /* objects of renderers destroyed while another context was current */
    return MVR_OK;
}

mvr_result mvr_context_release_current(mvr_context *ctx)
{
    if (!ctx)
        return MVR_ERROR_INVALID_ARGUMENT;
    /* the application's context is its own to bind; another thread's (or no)
     * current context is left alone */
    if (ctx->provider_kind == MVR_CONTEXT_PROVIDER_EXTERNAL || !mvr_context_is_current(ctx))
        return MVR_OK;
    flush_garbage(ctx);
    char why[MVR_ERROR_MESSAGE_SIZE] = "";
    mvr_result r = ctx->ops->release_current(ctx->provider, why, sizeof why);
    if (r != MVR_OK)
        return mvr_context_fail(ctx, r, "mvr_context_release_current(%s): %s",
                                mvr_context_provider_name(ctx->provider_kind), why);
    return MVR_OK;
}

const char *mvr_context_last_error(const mvr_context *ctx)
{
    return ctx ? ctx->last_error : "mvr_context_last_error: context is NULL";
}

mvr_context_provider mvr_context_get_provider(const mvr_context *ctx)
{
    return ctx ? ctx->provider_kind : MVR_CONTEXT_PROVIDER_DEFAULT;
}

const mvr_caps *mvr_context_caps(const mvr_context *ctx)
{
    return ctx ? &ctx->caps : NULL;
}
