/* mvr_context: picks a provider, loads the entry points, probes the caps. */
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>

#include "context_internal.h"

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
    if (ctx->provider_kind == MVR_CONTEXT_PROVIDER_EXTERNAL)
        ctx->caps.api = strstr((const char *)version, "OpenGL ES") ? MVR_GL_API_GLES
                                                                   : MVR_GL_API_DESKTOP;
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
    if (mvr_gl_check(ctx, "mvr_context_create (capability probe)", false) != MVR_OK)
        return mvr_error_set(error, MVR_ERROR_GL, "%s", ctx->last_error);
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
    /* The callback points at ctx: take it back from a context that outlives us. */
    if (ctx->debug_installed && ctx->provider_kind == MVR_CONTEXT_PROVIDER_EXTERNAL)
        ctx->gl.DebugMessageCallback(NULL, NULL);
    if (ctx->provider && ctx->ops)
        ctx->ops->destroy(ctx->provider);
    free(ctx);
}

mvr_result mvr_context_make_current(mvr_context *ctx)
{
    if (!ctx)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (ctx->provider_kind == MVR_CONTEXT_PROVIDER_EXTERNAL) {
        /* mvr never makes the application's context current; it checks one is. */
        if (!ctx->gl.GetString(GL_VERSION))
            return mvr_context_fail(ctx, MVR_ERROR_CONTEXT,
                                    "mvr_context_make_current(external): the application's "
                                    "context is not current on this thread");
        return MVR_OK;
    }
    char why[MVR_ERROR_MESSAGE_SIZE] = "";
    mvr_result r = ctx->ops->make_current(ctx->provider, why, sizeof why);
    if (r != MVR_OK)
        return mvr_context_fail(ctx, r, "mvr_context_make_current(%s): %s",
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
