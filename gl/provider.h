/* Context providers: each creates (or adopts) a GL context and resolves its
 * entry points. One interface; gl/context.c picks and drives them. */
#ifndef MVR_PROVIDER_H
#define MVR_PROVIDER_H

#include <stdbool.h>
#include <stddef.h>

#include "mvr/mvr.h"

typedef struct mvr_provider mvr_provider;  /* a provider's own state */

typedef struct mvr_provider_ops {
    /* Creates a context of the given API and makes it current. On failure
     * returns an error and writes why; *out stays NULL. */
    mvr_result (*create)(mvr_context_provider kind, const mvr_context_desc *desc, mvr_gl_api api,
                         mvr_provider **out, char *why, size_t why_size);
    void (*destroy)(mvr_provider *provider);
    mvr_result (*make_current)(mvr_provider *provider, char *why, size_t why_size);
    void *(*get_proc)(const char *name, void *provider);
    /* Fills the provider's part of the caps (EGL vendor, version, device). */
    void (*describe)(mvr_provider *provider, mvr_caps *caps);
    /* Whether the provider's context is current on the calling thread. */
    bool (*is_current)(const mvr_provider *provider);
    /* Makes no context current on the calling thread (the provider's API). */
    mvr_result (*release_current)(mvr_provider *provider, char *why, size_t why_size);
} mvr_provider_ops;

/* EGL's current context for a client API (EGL_OPENGL_ES_API, EGL_OPENGL_API)
 * on the calling thread, or NULL; the thread's bound API is left as it was. */
void *mvr_egl_current_context(unsigned api);
/* eglQueryAPI(): the client API bound on the calling thread. */
unsigned mvr_egl_bound_api(void);

/* NULL where the provider is not built. */
const mvr_provider_ops *mvr_provider_egl_ops(void);
const mvr_provider_ops *mvr_provider_osmesa_ops(void);

#endif
