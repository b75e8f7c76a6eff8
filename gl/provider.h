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
} mvr_provider_ops;

/* NULL where the provider is not built. */
const mvr_provider_ops *mvr_provider_egl_ops(void);
const mvr_provider_ops *mvr_provider_osmesa_ops(void);

#endif
