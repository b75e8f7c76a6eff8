/*
 * OSMesa provider: a desktop OpenGL core context rendered by Mesa in process
 * memory, without EGL. It runs the same "#version 300 es" shaders through
 * ARB_ES3_compatibility (core in GL 4.3). OSMesa was removed from Mesa after
 * 25.0, so the provider is optional at build time (MVR_WITH_OSMESA).
 */
#include "provider.h"

#ifdef MVR_HAVE_OSMESA

#include <GL/osmesa.h>
#include <stdlib.h>
#include <string.h>

#include "core_util.h"

/* OSMesa needs a color buffer to be current; mvr renders into its own
 * framebuffer objects, so a tiny one is enough. */
#define OSMESA_BUFFER_SIZE 4

struct mvr_provider {
    OSMesaContext context;
    unsigned char buffer[OSMESA_BUFFER_SIZE * OSMESA_BUFFER_SIZE * 4];
};

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
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                           OSMESA_DEPTH_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 3,
                           0};
    p->context = OSMesaCreateContextAttribs(attribs, NULL);
    if (!p->context) {
        free(p);
        mvr_str_copy(why, why_size, "OSMesaCreateContextAttribs(core 4.3) failed");
        return MVR_ERROR_CONTEXT;
    }
    if (!OSMesaMakeCurrent(p->context, p->buffer, GL_UNSIGNED_BYTE, OSMESA_BUFFER_SIZE,
                           OSMESA_BUFFER_SIZE)) {
        OSMesaDestroyContext(p->context);
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
    if (OSMesaGetCurrentContext() == p->context)
        OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(p->context);
    free(p);
}

static mvr_result osmesa_make_current(mvr_provider *p, char *why, size_t why_size)
{
    if (!OSMesaMakeCurrent(p->context, p->buffer, GL_UNSIGNED_BYTE, OSMESA_BUFFER_SIZE,
                           OSMESA_BUFFER_SIZE)) {
        mvr_str_copy(why, why_size, "OSMesaMakeCurrent failed");
        return MVR_ERROR_CONTEXT;
    }
    return MVR_OK;
}

static void *osmesa_get_proc(const char *name, void *user)
{
    (void)user;
    OSMESAproc fp = OSMesaGetProcAddress(name);
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
    return OSMesaGetCurrentContext() == p->context;
}

static mvr_result osmesa_release_current(mvr_provider *p, char *why, size_t why_size)
{
    (void)p;
    /* OSMesa's way to unbind: a NULL context and buffer */
    if (!OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0)) {
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
