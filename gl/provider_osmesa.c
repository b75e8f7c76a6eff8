/*
 * OSMesa provider: a desktop OpenGL core context rendered by Mesa in process
 * memory, without EGL. It runs the same "#version 300 es" shaders through
 * ARB_ES3_compatibility (core in GL 4.3). OSMesa was removed from Mesa after
 * 25.0, so the provider is optional at build time (MVR_WITH_OSMESA).
 *
 * libOSMesa is dlopen()ed when an OSMesa context is asked for, not linked:
 * libmvr.so (and a Python wheel carrying it) then loads on a system with
 * EGL only, and the osmesa provider fails there with a message naming the
 * library. The handle is kept open (Mesa is not made to be unloaded; dlopen
 * counts references, so each context's dlopen is cheap).
 */
#include "provider.h"

#ifdef MVR_HAVE_OSMESA

#include <GL/osmesa.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core_util.h"

/* Mesa's soname for OSMesa (Debian's libosmesa6) */
#define OSMESA_LIBRARY "libOSMesa.so.8"

typedef struct osmesa_api {
    OSMesaContext (*CreateContextAttribs)(const int *attribList, OSMesaContext sharelist);
    void (*DestroyContext)(OSMesaContext ctx);
    GLboolean (*MakeCurrent)(OSMesaContext ctx, void *buffer, GLenum type, GLsizei width, GLsizei height);
    OSMesaContext (*GetCurrentContext)(void);
    OSMESAproc (*GetProcAddress)(const char *funcName);
} osmesa_api;

/* OSMesa needs a color buffer to be current; mvr renders into its own
 * framebuffer objects, so a tiny one is enough. */
#define OSMESA_BUFFER_SIZE 4

struct mvr_provider {
    osmesa_api api;
    OSMesaContext context;
    unsigned char buffer[OSMESA_BUFFER_SIZE * OSMESA_BUFFER_SIZE * 4];
};

/* Each entry point by name (POSIX: a data pointer from dlsym converts to
 * a function pointer; memcpy keeps -Wpedantic quiet about it). */
static bool osmesa_load(osmesa_api *api, char *why, size_t why_size)
{
    void *lib = dlopen(OSMESA_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        const char *e = dlerror();
        snprintf(why, why_size, "cannot load %s (Mesa's OSMesa, Debian package libosmesa6): %s", OSMESA_LIBRARY,
                 e ? e : "dlopen failed");
        return false;
    }
    static const char *const names[] = {"OSMesaCreateContextAttribs", "OSMesaDestroyContext", "OSMesaMakeCurrent",
                                        "OSMesaGetCurrentContext", "OSMesaGetProcAddress"};
    void *fns[5];
    for (size_t i = 0; i < 5; ++i) {
        fns[i] = dlsym(lib, names[i]);
        if (!fns[i]) {
            snprintf(why, why_size, "%s has no %s", OSMESA_LIBRARY, names[i]);
            return false; /* the library stays loaded: unloading Mesa is not safe */
        }
    }
    memcpy(&api->CreateContextAttribs, &fns[0], sizeof fns[0]);
    memcpy(&api->DestroyContext, &fns[1], sizeof fns[1]);
    memcpy(&api->MakeCurrent, &fns[2], sizeof fns[2]);
    memcpy(&api->GetCurrentContext, &fns[3], sizeof fns[3]);
    memcpy(&api->GetProcAddress, &fns[4], sizeof fns[4]);
    return true;
}

static mvr_result osmesa_create(mvr_context_provider kind, const mvr_context_desc *desc,
                                mvr_gl_api api, mvr_provider **out, char *why, size_t why_size)
{
    (void)kind;
    (void)desc;
    if (api != MVR_GL_API_DESKTOP) {
        mvr_str_copy(why, why_size, "OSMesa offers desktop OpenGL only, not OpenGL ES");
        return MVR_ERROR_UNSUPPORTED;
    }
    mvr_provider *p = calloc(1, sizeof *p);
    if (!p) {
        mvr_str_copy(why, why_size, "out of memory");
        return MVR_ERROR_OUT_OF_MEMORY;
    }
    if (!osmesa_load(&p->api, why, why_size)) {
        free(p);
        return MVR_ERROR_UNSUPPORTED;
    }
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                           OSMESA_DEPTH_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 3,
                           0};
    p->context = p->api.CreateContextAttribs(attribs, NULL);
    if (!p->context) {
        free(p);
        mvr_str_copy(why, why_size, "OSMesaCreateContextAttribs(core 4.3) failed");
        return MVR_ERROR_CONTEXT;
    }
    if (!p->api.MakeCurrent(p->context, p->buffer, GL_UNSIGNED_BYTE, OSMESA_BUFFER_SIZE,
                           OSMESA_BUFFER_SIZE)) {
        p->api.DestroyContext(p->context);
        free(p);
        mvr_str_copy(why, why_size, "OSMesaMakeCurrent failed");
        return MVR_ERROR_CONTEXT;
    }
    *out = p;
    return MVR_OK;
}

static void osmesa_destroy(mvr_provider *p)
{
    if (!p)
        return;
    if (p->api.GetCurrentContext() == p->context)
        p->api.MakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    p->api.DestroyContext(p->context);
    free(p);
}

static mvr_result osmesa_make_current(mvr_provider *p, char *why, size_t why_size)
{
    if (!p->api.MakeCurrent(p->context, p->buffer, GL_UNSIGNED_BYTE, OSMESA_BUFFER_SIZE,
                           OSMESA_BUFFER_SIZE)) {
        mvr_str_copy(why, why_size, "OSMesaMakeCurrent failed");
        return MVR_ERROR_CONTEXT;
    }
    return MVR_OK;
}

static void *osmesa_get_proc(const char *name, void *user)
{
    const mvr_provider *p = user;
    OSMESAproc fp = p->api.GetProcAddress(name);
    void *addr;
    memcpy(&addr, &fp, sizeof addr);
    return addr;
}

static void osmesa_describe(mvr_provider *p, mvr_caps *caps)
{
    (void)p;
    caps->egl_vendor[0] = caps->egl_version[0] = caps->egl_device[0] = '\0';
}

static bool osmesa_is_current(const mvr_provider *p)
{
    return p->api.GetCurrentContext() == p->context;
}

static mvr_result osmesa_release_current(mvr_provider *p, char *why, size_t why_size)
{
    (void)p;
    /* OSMesa's way to unbind: a NULL context and buffer */
    if (!p->api.MakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0)) {
        mvr_str_copy(why, why_size, "OSMesaMakeCurrent(NULL) failed");
        return MVR_ERROR_CONTEXT;
    }
    return MVR_OK;
}

static const mvr_provider_ops osmesa_ops = {
    .create = osmesa_create,
    .destroy = osmesa_destroy,
    .make_current = osmesa_make_current,
    .get_proc = osmesa_get_proc,
    .describe = osmesa_describe,
    .is_current = osmesa_is_current,
    .release_current = osmesa_release_current,
};

const mvr_provider_ops *mvr_provider_osmesa_ops(void)
{
    return &osmesa_ops;
}

#else

const mvr_provider_ops *mvr_provider_osmesa_ops(void)
{
    return NULL;
}

#endif
