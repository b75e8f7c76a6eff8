/*
 * mvr: GL contexts and their providers, and the capabilities a
 * context probes.
 *
 * Part of the public C API; include <mvr/mvr.h>, whose conventions apply.
 */
#ifndef MVR_CONTEXT_API_H
#define MVR_CONTEXT_API_H

#include "mvr/mvr_base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ context */

typedef struct mvr_context mvr_context;

typedef enum mvr_context_provider {
    MVR_CONTEXT_PROVIDER_DEFAULT = 0, /* surfaceless, then device, then pbuffer */
    MVR_CONTEXT_PROVIDER_SURFACELESS, /* EGL_MESA_platform_surfaceless: Mesa headless */
    MVR_CONTEXT_PROVIDER_DEVICE,      /* EGL_EXT_platform_device: NVIDIA (and Mesa) headless */
    MVR_CONTEXT_PROVIDER_PBUFFER,     /* default EGL display + a 1x1 pbuffer (needs a display) */
    MVR_CONTEXT_PROVIDER_OSMESA,      /* OSMesa: desktop GL core, no EGL (optional at build) */
    MVR_CONTEXT_PROVIDER_EXTERNAL,    /* the application's current context; mvr creates nothing */
    MVR_CONTEXT_PROVIDER_COUNT_
} mvr_context_provider;

/* "surfaceless", "device", ...; "default" for 0; NULL when out of range. */
const char *mvr_context_provider_name(mvr_context_provider provider);
/* Parses a name as printed by mvr_context_provider_name. */
mvr_result mvr_context_provider_from_name(const char *name, mvr_context_provider *out);
/* False where the provider was left out of this build (OSMesa). */
bool mvr_context_provider_built(mvr_context_provider provider);

typedef enum mvr_gl_api {
    MVR_GL_API_DEFAULT = 0, /* GLES 3 on EGL providers, desktop core on OSMesa */
    MVR_GL_API_GLES,        /* OpenGL ES 3.0 or newer */
    MVR_GL_API_DESKTOP      /* desktop OpenGL 4.3+ core (runs the ES 3.00 shaders) */
} mvr_gl_api;

const char *mvr_gl_api_name(mvr_gl_api api);

/* Returns the address of a GL entry point, or NULL (external provider). */
typedef void *(*mvr_get_proc_fn)(const char *name, void *user_data);
/* True when the application's context (external provider) is current on the
 * calling thread. */
typedef bool (*mvr_is_current_fn)(void *user_data);

typedef struct mvr_context_desc {
    mvr_context_provider provider;
    mvr_gl_api api;
    /* DEVICE provider: 0 = the first EGL device that gives a context;
     * k > 0 = the k-th device of eglQueryDevicesEXT (1-based). */
    int device_index;
    /* Debug context where possible, KHR_debug messages to the logger, and a
     * glGetError check after every public call that touches GL (always on in
     * debug builds). */
    bool debug;
    /* EXTERNAL provider: how to find GL entry points of the application's
     * context (e.g. glfwGetProcAddress). NULL = eglGetProcAddress. */
    mvr_get_proc_fn get_proc_address;
    void *get_proc_user_data;
    mvr_logger logger;
    /* EXTERNAL: how mvr tells, before it touches GL, that the application's
     * context is the current one. NULL: where an EGL context was current at
     * create time mvr compares eglGetCurrentContext() with it; elsewhere
     * (GLX, WGL, ...) the GL offers no identity to compare, so mvr trusts
     * the caller and only checks that some context answers glGetString. */
    mvr_is_current_fn is_current;
    void *is_current_user_data;
} mvr_context_desc;

/*
 * Creates a GL context from a provider and makes it current on the calling
 * thread (EXTERNAL: uses the context current now and creates nothing). Probes
 * the capabilities and loads every entry point. On failure *out_context is
 * NULL and *out_error (optional) says what failed and where.
 */
mvr_result mvr_context_create(const mvr_context_desc *desc, mvr_context **out_context,
                              mvr_error *out_error);
/* Releases what mvr created (EXTERNAL: nothing of the application's). NULL is
 * fine, and so are renderers and targets still alive: they are detached (see
 * "Lifetimes and the current context" in mvr_renderer.h). */
void mvr_context_destroy(mvr_context *context);
/* Makes the context current on this thread (EXTERNAL: checks that it is
 * current, as is_current says). With mvr_context_release_current, the only
 * calls besides mvr_context_create that change the thread's current context. */
mvr_result mvr_context_make_current(mvr_context *context);
/* Makes no context current on this thread, if this context is the current
 * one (after deleting GL objects that waited for it), so that another thread
 * may make it current: an EGL context is current on one thread at most.
 * MVR_OK and nothing changed where the context is not current here, and for
 * EXTERNAL (mvr never changes the application's binding). */
mvr_result mvr_context_release_current(mvr_context *context);
/* The message of the last failed call on this object; "" when none failed. */
const char *mvr_context_last_error(const mvr_context *context);
mvr_context_provider mvr_context_get_provider(const mvr_context *context);

/* ------------------------------------------------------------------ capabilities */

#define MVR_CAPS_STRING_SIZE 256

typedef struct mvr_caps_ext {
    bool ovr_multiview;
    bool ovr_multiview2;
    bool ovr_multiview_multisampled_render_to_texture;
    bool ext_clip_control;       /* or ARB_clip_control / GL 4.5 on desktop */
    bool ext_disjoint_timer_query; /* or ARB_timer_query / GL 3.3 on desktop */
    bool khr_debug;              /* or GL 4.3 / ES 3.2 core */
    bool ext_texture_filter_anisotropic;
    bool ext_color_buffer_float; /* float color targets renderable */
    bool ext_color_buffer_half_float;
    bool oes_texture_float_linear; /* 32-bit float textures filtered linearly (core on desktop) */
    bool program_binary;         /* at least one program binary format */
    /* A multisampled 2D array texture attaches with glFramebufferTextureMultiviewOVR
     * and gives a complete framebuffer (probed at create time, not assumed). */
    bool multiview_msaa_array;
    /* compressed texture formats */
    bool etc2;                   /* core in ES 3.0; ARB_ES3_compatibility on desktop */
    bool astc_ldr;               /* KHR_texture_compression_astc_ldr */
    bool s3tc;                   /* EXT_texture_compression_s3tc */
    bool rgtc;                   /* EXT_texture_compression_rgtc */
    bool bptc;                   /* EXT_texture_compression_bptc */
} mvr_caps_ext;

typedef struct mvr_caps_limits {
    int max_views_ovr;           /* 0 without OVR_multiview */
    int max_array_texture_layers;
    int max_texture_size;
    int uniform_buffer_offset_alignment;
    int max_uniform_block_size;
    int max_uniform_buffer_bindings;
    int max_samples;
    int max_combined_texture_image_units;
    int max_draw_buffers;
    int program_binary_formats;
    float max_anisotropy;        /* 1 without EXT_texture_filter_anisotropic */
} mvr_caps_limits;

/* Known driver bugs and quirks, detected from the renderer; each is worked
 * around where it matters (gl/caps.c says how each is detected and why). */
typedef struct mvr_caps_bugs {
    bool timer_query_in_multiview_undefined;
    bool multiview_level_zero_only;  /* multiview attaches mip level 0 only (Mesa 25) */
    bool mediump_is_fp16;
    bool multiview_pass_defers_raster;
    bool half_float_sampling_slow;   /* a half float texel costs more to sample than a float one */
} mvr_caps_bugs;

typedef struct mvr_caps {
    mvr_gl_api api;
    int gl_major, gl_minor;      /* 3.2 for "OpenGL ES 3.2 Mesa 25.0.7" */
    char vendor[MVR_CAPS_STRING_SIZE];
    char renderer[MVR_CAPS_STRING_SIZE];
    char version[MVR_CAPS_STRING_SIZE];
    char glsl_version[MVR_CAPS_STRING_SIZE];
    char egl_vendor[MVR_CAPS_STRING_SIZE];  /* "" outside EGL */
    char egl_version[MVR_CAPS_STRING_SIZE];
    char egl_device[MVR_CAPS_STRING_SIZE];  /* DEVICE provider: which device, e.g. a DRM node */
    mvr_caps_ext ext;
    mvr_caps_limits limits;
    mvr_caps_bugs bugs;
    bool is_software;            /* llvmpipe, softpipe, swiftshader */
} mvr_caps;

const mvr_caps *mvr_context_caps(const mvr_context *context);

#ifdef __cplusplus
}
#endif
#endif /* MVR_CONTEXT_API_H */
