/*
 * EGL context providers: surfaceless (EGL_MESA_platform_surfaceless), device
 * (EGL_EXT_platform_device, how NVIDIA renders headless; Mesa offers it too)
 * and pbuffer (the default display and a 1x1 pbuffer, for EGL stacks without
 * surfaceless contexts; needs a display server).
 *
 * Displays are never eglTerminate'd: EGL displays are per-process singletons,
 * so terminating one would destroy the contexts of any other mvr_context (or
 * of the application) on the same display. Without EGL_KHR_display_reference
 * there is no safe reference count; Mesa finalizes displays at exit.
 */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

#include "core_util.h"
#include "provider.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif
#ifndef EGL_DRM_RENDER_NODE_FILE_EXT
#define EGL_DRM_RENDER_NODE_FILE_EXT 0x3377
#endif

struct mvr_provider {
    EGLDisplay display;
    EGLContext context;
    EGLSurface surface;        /* pbuffer, or EGL_NO_SURFACE when surfaceless */
    bool get_all_proc_addresses; /* eglGetProcAddress also returns core functions */
    void *gl_library;          /* dlopen'd fallback for core functions, lazily */
    mvr_gl_api api;
    char device[MVR_CAPS_STRING_SIZE];
};

static bool has_extension(const char *list, const char *name)
{
    if (!list)
        return false;
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    return false;
}

static const char *egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "unknown EGL error";
    }
}

/* ISO C: function pointers come back from eglGetProcAddress as __eglMustCastToProperFunctionPointerType. */
#define EGL_LOAD(type, var, name)                                         \
    type var = NULL;                                                      \
    do {                                                                  \
        __eglMustCastToProperFunctionPointerType fp_ = eglGetProcAddress(name); \
        memcpy(&var, &fp_, sizeof var);                                   \
    } while (0)

static void provider_free(mvr_provider *p)
{
    if (!p)
        return;
    if (p->display != EGL_NO_DISPLAY) {
        if (eglGetCurrentContext() == p->context && p->context != EGL_NO_CONTEXT)
            eglMakeCurrent(p->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (p->surface != EGL_NO_SURFACE)
            eglDestroySurface(p->display, p->surface);
        if (p->context != EGL_NO_CONTEXT)
            eglDestroyContext(p->display, p->context);
    }
    if (p->gl_library)
        dlclose(p->gl_library);
    free(p);
}

/* Opens the display of a provider kind; device_index as in mvr_context_desc
 * (the DEVICE provider's automatic choice is made by the caller, which tries
 * the devices in turn). */
static EGLDisplay open_display(mvr_context_provider kind, int device_index, char *device_name,
                               size_t device_name_size, mvr_result *result, char *why,
                               size_t why_size)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    EGL_LOAD(PFNEGLGETPLATFORMDISPLAYEXTPROC, get_platform_display, "eglGetPlatformDisplayEXT");
    *result = MVR_ERROR_NO_DISPLAY;
    switch (kind) {
    case MVR_CONTEXT_PROVIDER_SURFACELESS:
        if (!has_extension(client, "EGL_MESA_platform_surfaceless") || !get_platform_display) {
            mvr_str_copy(why, why_size,
                         "EGL has no EGL_MESA_platform_surfaceless (not a Mesa EGL?)");
            *result = MVR_ERROR_UNSUPPORTED;
            return EGL_NO_DISPLAY;
        }
        return get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    case MVR_CONTEXT_PROVIDER_DEVICE: {
        EGL_LOAD(PFNEGLQUERYDEVICESEXTPROC, query_devices, "eglQueryDevicesEXT");
        EGL_LOAD(PFNEGLQUERYDEVICESTRINGEXTPROC, query_device_string, "eglQueryDeviceStringEXT");
        if (!has_extension(client, "EGL_EXT_platform_device") || !query_devices ||
            !get_platform_display) {
            mvr_str_copy(why, why_size,
                         "EGL has no EGL_EXT_platform_device / EGL_EXT_device_enumeration");
            *result = MVR_ERROR_UNSUPPORTED;
            return EGL_NO_DISPLAY;
        }
        EGLDeviceEXT devices[32];
        EGLint count = 0;
        if (!query_devices((EGLint)MVR_ARRAY_COUNT(devices), devices, &count) || count <= 0) {
            mvr_str_copy(why, why_size, "eglQueryDevicesEXT found no EGL device");
            return EGL_NO_DISPLAY;
        }
        if (device_index < 1 || device_index > count) {
            mvr_str_format(why, why_size, "EGL device %d requested, %d present", device_index,
                           (int)count);
            *result = MVR_ERROR_INVALID_ARGUMENT;
            return EGL_NO_DISPLAY;
        }
        EGLDeviceEXT dev = devices[device_index - 1];
        const char *exts = query_device_string ? query_device_string(dev, EGL_EXTENSIONS) : NULL;
        const char *node = NULL;
        if (query_device_string && has_extension(exts, "EGL_EXT_device_drm_render_node"))
            node = query_device_string(dev, EGL_DRM_RENDER_NODE_FILE_EXT);
        if (!node && query_device_string && has_extension(exts, "EGL_EXT_device_drm"))
            node = query_device_string(dev, EGL_DRM_DEVICE_FILE_EXT);
        mvr_str_format(device_name, device_name_size, "%d of %d: %s%s", device_index, (int)count,
                       node ? node : "(no DRM node)",
                       has_extension(exts, "EGL_MESA_device_software") ? " (software)" : "");
        return get_platform_display(EGL_PLATFORM_DEVICE_EXT, dev, NULL);
    }
    case MVR_CONTEXT_PROVIDER_PBUFFER:
        return eglGetDisplay(EGL_DEFAULT_DISPLAY);
    case MVR_CONTEXT_PROVIDER_DEFAULT:
    case MVR_CONTEXT_PROVIDER_OSMESA:
    case MVR_CONTEXT_PROVIDER_EXTERNAL:
    case MVR_CONTEXT_PROVIDER_COUNT_:
        break;
    }
    mvr_str_copy(why, why_size, "not an EGL provider");
    *result = MVR_ERROR_INTERNAL;
    return EGL_NO_DISPLAY;
}

static mvr_result create_on_display(mvr_provider *p, mvr_context_provider kind,
                                    const mvr_context_desc *desc, char *why, size_t why_size)
{
    EGLint major = 0, minor = 0;
    if (!eglInitialize(p->display, &major, &minor)) {
        mvr_str_format(why, why_size, "eglInitialize failed (%s)%s", egl_error_name(eglGetError()),
                       kind == MVR_CONTEXT_PROVIDER_PBUFFER
                           ? ": no default display (is DISPLAY / WAYLAND_DISPLAY set?)"
                           : "");
        return MVR_ERROR_NO_DISPLAY;
    }
    const char *exts = eglQueryString(p->display, EGL_EXTENSIONS);
    bool desktop = p->api == MVR_GL_API_DESKTOP;
    if (!eglBindAPI(desktop ? EGL_OPENGL_API : EGL_OPENGL_ES_API)) {
        mvr_str_format(why, why_size, "eglBindAPI(%s) failed: this EGL has no %s",
                       desktop ? "EGL_OPENGL_API" : "EGL_OPENGL_ES_API",
                       desktop ? "desktop OpenGL" : "OpenGL ES");
        return MVR_ERROR_UNSUPPORTED;
    }

    bool want_surface = kind == MVR_CONTEXT_PROVIDER_PBUFFER ||
                        !has_extension(exts, "EGL_KHR_surfaceless_context");
    EGLConfig config = (EGLConfig)0;
    if (want_surface || !has_extension(exts, "EGL_KHR_no_config_context")) {
        const EGLint config_attribs[] = {
            EGL_RENDERABLE_TYPE, desktop ? EGL_OPENGL_BIT : EGL_OPENGL_ES3_BIT,
            EGL_SURFACE_TYPE, want_surface ? EGL_PBUFFER_BIT : 0,
            EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
            EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(p->display, config_attribs, &config, 1, &n) || n < 1) {
            mvr_str_format(why, why_size, "no EGL config with %s%s",
                           desktop ? "desktop OpenGL" : "OpenGL ES 3",
                           want_surface ? " and pbuffer support" : "");
            return MVR_ERROR_UNSUPPORTED;
        }
    }

    /* Try with the debug flag first when asked; some drivers refuse it. */
    for (int attempt = desc->debug ? 0 : 1; attempt < 2; ++attempt) {
        EGLint attribs[16];
        int i = 0;
        attribs[i++] = EGL_CONTEXT_MAJOR_VERSION;
        attribs[i++] = desktop ? 4 : 3;
        attribs[i++] = EGL_CONTEXT_MINOR_VERSION;
        attribs[i++] = desktop ? 3 : 0;
        if (desktop) {
            attribs[i++] = EGL_CONTEXT_OPENGL_PROFILE_MASK;
            attribs[i++] = EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT;
        }
        if (attempt == 0) {
            attribs[i++] = EGL_CONTEXT_OPENGL_DEBUG;
            attribs[i++] = EGL_TRUE;
        }
        attribs[i] = EGL_NONE;
        p->context = eglCreateContext(p->display, config, EGL_NO_CONTEXT, attribs);
        if (p->context != EGL_NO_CONTEXT)
            break;
    }
    if (p->context == EGL_NO_CONTEXT) {
        mvr_str_format(why, why_size, "eglCreateContext(%s) failed (%s)",
                       desktop ? "desktop GL 4.3 core" : "OpenGL ES 3.0",
                       egl_error_name(eglGetError()));
        return MVR_ERROR_CONTEXT;
    }
    if (want_surface) {
        const EGLint pbuffer_attribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        p->surface = eglCreatePbufferSurface(p->display, config, pbuffer_attribs);
        if (p->surface == EGL_NO_SURFACE) {
            mvr_str_format(why, why_size, "eglCreatePbufferSurface failed (%s)",
                           egl_error_name(eglGetError()));
            return MVR_ERROR_CONTEXT;
        }
    }
    if (!eglMakeCurrent(p->display, p->surface, p->surface, p->context)) {
        mvr_str_format(why, why_size, "eglMakeCurrent failed (%s)", egl_error_name(eglGetError()));
        return MVR_ERROR_CONTEXT;
    }
    p->get_all_proc_addresses =
        has_extension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS),
                      "EGL_KHR_client_get_all_proc_addresses") ||
        has_extension(exts, "EGL_KHR_get_all_proc_addresses");
    return MVR_OK;
}

static mvr_result egl_create_one(mvr_context_provider kind, const mvr_context_desc *desc,
                                 mvr_gl_api api, int device_index, mvr_provider **out, char *why,
                                 size_t why_size)
{
    mvr_provider *p = calloc(1, sizeof *p);
    if (!p) {
        mvr_str_copy(why, why_size, "out of memory");
        return MVR_ERROR_OUT_OF_MEMORY;
    }
    p->display = EGL_NO_DISPLAY;
    p->context = EGL_NO_CONTEXT;
    p->surface = EGL_NO_SURFACE;
    p->api = api;
    mvr_result r = MVR_OK;
    p->display = open_display(kind, device_index, p->device, sizeof p->device, &r, why, why_size);
    if (p->display == EGL_NO_DISPLAY) {
        if (!why[0])
            mvr_str_format(why, why_size, "no EGL display (%s)", egl_error_name(eglGetError()));
        provider_free(p);
        return r;
    }
    r = create_on_display(p, kind, desc, why, why_size);
    if (r != MVR_OK) {
        provider_free(p);
        return r;
    }
    *out = p;
    return MVR_OK;
}

/* Device indices (1-based) in the order the automatic choice tries them:
 * hardware devices first, Mesa's software device (EGL_MESA_device_software,
 * enumerated beside NVIDIA's under glvnd) last. Returns the count. */
static int device_try_order(int *order, int capacity)
{
    EGL_LOAD(PFNEGLQUERYDEVICESEXTPROC, query_devices, "eglQueryDevicesEXT");
    EGL_LOAD(PFNEGLQUERYDEVICESTRINGEXTPROC, query_device_string, "eglQueryDeviceStringEXT");
    EGLDeviceEXT devices[32];
    EGLint count = 0;
    if (!query_devices || !query_devices((EGLint)MVR_ARRAY_COUNT(devices), devices, &count))
        return 0;
    int n = 0;
    for (int pass = 0; pass < 2; ++pass) {
        for (EGLint i = 0; i < count && n < capacity; ++i) {
            const char *exts = query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : NULL;
            bool software = has_extension(exts, "EGL_MESA_device_software");
            if (software == (pass == 1))
                order[n++] = (int)i + 1;
        }
    }
    return n;
}

static mvr_result egl_create(mvr_context_provider kind, const mvr_context_desc *desc,
                             mvr_gl_api api, mvr_provider **out, char *why, size_t why_size)
{
    why[0] = '\0';
    if (kind != MVR_CONTEXT_PROVIDER_DEVICE || desc->device_index > 0)
        return egl_create_one(kind, desc, api, desc->device_index, out, why, why_size);

    /* DEVICE, automatic: the first device that gives a context. */
    int order[32];
    int count = device_try_order(order, (int)MVR_ARRAY_COUNT(order));
    if (count <= 0)
        return egl_create_one(kind, desc, api, 1, out, why, why_size);
    mvr_result r = MVR_ERROR_NO_DISPLAY;
    char all[MVR_ERROR_MESSAGE_SIZE] = "";
    for (int i = 0; i < count; ++i) {
        char one[MVR_ERROR_MESSAGE_SIZE] = "";
        r = egl_create_one(kind, desc, api, order[i], out, one, sizeof one);
        if (r == MVR_OK)
            return MVR_OK;
        size_t used = strlen(all);
        mvr_str_format(all + used, sizeof all - used, "%sdevice %d: %s", used ? "; " : "",
                       order[i], one);
    }
    mvr_str_copy(why, why_size, all);
    return r;
}

static void egl_destroy(mvr_provider *p)
{
    provider_free(p);
}

static mvr_result egl_make_current(mvr_provider *p, char *why, size_t why_size)
{
    if (!eglBindAPI(p->api == MVR_GL_API_DESKTOP ? EGL_OPENGL_API : EGL_OPENGL_ES_API) ||
        !eglMakeCurrent(p->display, p->surface, p->surface, p->context)) {
        mvr_str_format(why, why_size, "eglMakeCurrent failed (%s)", egl_error_name(eglGetError()));
        return MVR_ERROR_CONTEXT;
    }
    return MVR_OK;
}

static void *egl_get_proc(const char *name, void *user)
{
    mvr_provider *p = user;
    __eglMustCastToProperFunctionPointerType fp = eglGetProcAddress(name);
    void *addr;
    memcpy(&addr, &fp, sizeof addr);
    if (addr || p->get_all_proc_addresses)
        return addr;
    /* EGL 1.4 without get_all_proc_addresses returns only extension functions;
     * core ones come from the client library itself. */
    if (!p->gl_library)
        p->gl_library = dlopen(p->api == MVR_GL_API_DESKTOP ? "libOpenGL.so.0" : "libGLESv2.so.2",
                               RTLD_NOW | RTLD_LOCAL);
    return p->gl_library ? dlsym(p->gl_library, name) : NULL;
}

void *mvr_egl_current_context(unsigned api)
{
    /* EGL keeps one current context per client API and thread: ask for the
     * given one, then give back the application's binding untouched */
    EGLenum bound = eglQueryAPI();
    if (bound == (EGLenum)api)
        return eglGetCurrentContext();
    if (!eglBindAPI((EGLenum)api))
        return NULL;
    EGLContext current = eglGetCurrentContext();
    if (bound != EGL_NONE)
        eglBindAPI(bound);
    return current;
}

unsigned mvr_egl_bound_api(void)
{
    return (unsigned)eglQueryAPI();
}

static bool egl_is_current(const mvr_provider *p)
{
    return p->context != EGL_NO_CONTEXT &&
           mvr_egl_current_context(p->api == MVR_GL_API_DESKTOP ? EGL_OPENGL_API : EGL_OPENGL_ES_API) == p->context;
}

static mvr_result egl_release_current(mvr_provider *p, char *why, size_t why_size)
{
    /* EGL keeps a current context per client API: release the one this
     * provider's contexts bind; eglMakeCurrent flushes it first (EGL 1.5,
     * section 3.7.3) */
    if (!eglBindAPI(p->api == MVR_GL_API_DESKTOP ? EGL_OPENGL_API : EGL_OPENGL_ES_API) ||
        !eglMakeCurrent(p->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT)) {
        mvr_str_format(why, why_size, "eglMakeCurrent(EGL_NO_CONTEXT) failed (%s)", egl_error_name(eglGetError()));
        return MVR_ERROR_CONTEXT;
    }
    return MVR_OK;
}

static void egl_describe(mvr_provider *p, mvr_caps *caps)
{
    mvr_str_copy(caps->egl_vendor, sizeof caps->egl_vendor, eglQueryString(p->display, EGL_VENDOR));
    mvr_str_copy(caps->egl_version, sizeof caps->egl_version,
                 eglQueryString(p->display, EGL_VERSION));
    mvr_str_copy(caps->egl_device, sizeof caps->egl_device, p->device);
}

static const mvr_provider_ops egl_ops = {
    .create = egl_create,
    .destroy = egl_destroy,
    .make_current = egl_make_current,
    .get_proc = egl_get_proc,
    .describe = egl_describe,
    .is_current = egl_is_current,
    .release_current = egl_release_current,
};

const mvr_provider_ops *mvr_provider_egl_ops(void)
{
    return &egl_ops;
}
