/*
 * mvr: render glTF 2.0 scenes into many views at once on OpenGL ES 3.
 *
 * Public C API. Conventions (see docs/guide.md):
 * - opaque handles with create/destroy pairs; destroy accepts NULL;
 * - descriptor structs are read once at create time, and a zeroed descriptor
 *   means "all defaults" (every enum has 0 = default);
 * - every call that can fail returns mvr_result. A create call that fails has
 *   no object to hold its message, so it fills an optional mvr_error; a live
 *   object keeps the message of its last failure (mvr_*_last_error);
 * - the library logs through the descriptor's logger, never to stdout/stderr;
 * - no global state: two contexts never see each other.
 */
#ifndef MVR_H
#define MVR_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MVR_VERSION_MAJOR 0
#define MVR_VERSION_MINOR 1
#define MVR_VERSION_PATCH 0

/* ------------------------------------------------------------------ results */

typedef enum mvr_result {
    MVR_OK = 0,
    MVR_ERROR_INVALID_ARGUMENT, /* a NULL, out-of-range or inconsistent argument */
    MVR_ERROR_OUT_OF_MEMORY,
    MVR_ERROR_UNSUPPORTED,      /* the build, driver or GL lacks what was asked for */
    MVR_ERROR_NO_DISPLAY,       /* no EGL display / device / platform could be opened */
    MVR_ERROR_CONTEXT,          /* context creation or make-current failed; or a call's context is not
                                   current on this thread, or was destroyed */
    MVR_ERROR_GL,               /* the GL reported an error (glGetError) */
    MVR_ERROR_SHADER,           /* a shader failed to compile or a program to link */
    MVR_ERROR_FRAMEBUFFER,      /* a framebuffer is incomplete */
    MVR_ERROR_IO,               /* a file could not be read or written */
    MVR_ERROR_PARSE,            /* malformed input data */
    MVR_ERROR_INVALID_ASSET,    /* a file that is not valid (glTF, image): the message names the part */
    MVR_ERROR_INTERNAL,         /* a bug in mvr: please report it */
    MVR_RESULT_COUNT_
} mvr_result;

/* "MVR_ERROR_NO_DISPLAY" etc.; never NULL. */
const char *mvr_result_name(mvr_result result);

#define MVR_ERROR_MESSAGE_SIZE 512

/* Filled by create calls that fail before an object exists. */
typedef struct mvr_error {
    mvr_result result;
    char message[MVR_ERROR_MESSAGE_SIZE];
} mvr_error;

/* ------------------------------------------------------------------ logging */

typedef enum mvr_log_level {
    MVR_LOG_DEFAULT = 0, /* as a threshold: MVR_LOG_INFO */
    MVR_LOG_ERROR,
    MVR_LOG_WARNING,
    MVR_LOG_INFO,
    MVR_LOG_DEBUG
} mvr_log_level;

/* Stable message ids, so an application can filter or count kinds of message. */
typedef enum mvr_log_id {
    MVR_LOG_ID_GENERAL = 0,
    MVR_LOG_ID_ERROR_RESULT,       /* a call returned an error; message says what and where */
    MVR_LOG_ID_CONTEXT,            /* context created / provider chosen */
    MVR_LOG_ID_PROVIDER_FALLBACK,  /* the default provider tried one and moved on */
    MVR_LOG_ID_EXTENSION_DROPPED,  /* advertised extension whose entry points did not resolve */
    MVR_LOG_ID_DRIVER_BUG,         /* a known driver bug was detected and is worked around */
    MVR_LOG_ID_GL_DEBUG,           /* a KHR_debug message from the driver */
    MVR_LOG_ID_GL_ERROR,           /* glGetError reported an error */
    MVR_LOG_ID_SHADER              /* shader compile / link log */
} mvr_log_id;

typedef void (*mvr_log_fn)(mvr_log_level level, mvr_log_id id, const char *message,
                           void *user_data);

typedef struct mvr_logger {
    mvr_log_fn fn;          /* NULL: messages are dropped */
    void *user_data;
    mvr_log_level level;    /* most verbose level passed on; 0 = MVR_LOG_INFO */
} mvr_logger;

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
 * "Lifetimes and the current context" below). */
void mvr_context_destroy(mvr_context *context);
/* Makes the context current on this thread (EXTERNAL: checks that it is
 * current, as is_current says). The only call besides mvr_context_create
 * that changes the thread's current context. */
mvr_result mvr_context_make_current(mvr_context *context);
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


/* ------------------------------------------------------------------ scene
 *
 * A scene is built in code (or by the glTF loader) and owns copies of
 * everything given to it. Ids are small structs (0 = none / invalid), valid
 * for the scene that returned them. Nothing here touches GL: a renderer
 * uploads what it needs when it first draws a scene, and again only what
 * changed (geometry and materials on edits, transforms every frame).
 */

typedef struct mvr_scene mvr_scene;
typedef struct mvr_image_id { uint32_t id; } mvr_image_id;
typedef struct mvr_mesh_id { uint32_t id; } mvr_mesh_id;
typedef struct mvr_material_id { uint32_t id; } mvr_material_id;
typedef struct mvr_node_id { uint32_t id; } mvr_node_id;
typedef struct mvr_light_id { uint32_t id; } mvr_light_id;
typedef struct mvr_camera_id { uint32_t id; } mvr_camera_id;

typedef struct mvr_scene_desc {
    mvr_logger logger;
} mvr_scene_desc;

mvr_result mvr_scene_create(const mvr_scene_desc *desc, mvr_scene **out_scene, mvr_error *out_error);
void mvr_scene_destroy(mvr_scene *scene);
const char *mvr_scene_last_error(const mvr_scene *scene);

/* How an image's texels are stored. RGBA8 (the zero value) is 8-bit RGBA
 * pixels; the others are GPU block formats the GL samples without mvr
 * decoding them: the blocks are uploaded as given (glCompressedTex*), each
 * level ceil(w / bw) * ceil(h / bh) blocks, rows of blocks top first (as a
 * KTX2 file stores them). Whether a texture is sRGB-encoded comes from its
 * role (base color, emissive, ...: GL_COMPRESSED_SRGB8_ETC2 and the like),
 * as for RGBA8; EAC R11 / RG11 have no sRGB form and are sampled as stored.
 * ETC2 and EAC are core in OpenGL ES 3.0 (and desktop GL 4.3); ASTC needs
 * KHR_texture_compression_astc_ldr. An image the renderer's GL cannot
 * sample is drawn with its role's neutral value (white; a flat normal),
 * with a warning naming it (mvr_frame_stats.images_unsampleable). */
typedef enum mvr_image_format {
    MVR_IMAGE_FORMAT_RGBA8 = 0,
    MVR_IMAGE_FORMAT_ETC2_RGB8,        /* 4x4 blocks of 8 bytes */
    MVR_IMAGE_FORMAT_ETC2_RGB8_A1,     /* punch-through alpha; 4x4, 8 bytes */
    MVR_IMAGE_FORMAT_ETC2_RGBA8,       /* ETC2 colour + EAC alpha; 4x4, 16 bytes */
    MVR_IMAGE_FORMAT_EAC_R11,          /* unsigned; 4x4, 8 bytes; samples (r, 0, 0, 1) */
    MVR_IMAGE_FORMAT_EAC_RG11,         /* unsigned; 4x4, 16 bytes; samples (r, g, 0, 1) */
    MVR_IMAGE_FORMAT_ASTC_4x4,         /* ASTC LDR: 16 bytes per block of every size */
    MVR_IMAGE_FORMAT_ASTC_5x4,
    MVR_IMAGE_FORMAT_ASTC_5x5,
    MVR_IMAGE_FORMAT_ASTC_6x5,
    MVR_IMAGE_FORMAT_ASTC_6x6,
    MVR_IMAGE_FORMAT_ASTC_8x5,
    MVR_IMAGE_FORMAT_ASTC_8x6,
    MVR_IMAGE_FORMAT_ASTC_8x8,
    MVR_IMAGE_FORMAT_ASTC_10x5,
    MVR_IMAGE_FORMAT_ASTC_10x6,
    MVR_IMAGE_FORMAT_ASTC_10x8,
    MVR_IMAGE_FORMAT_ASTC_10x10,
    MVR_IMAGE_FORMAT_ASTC_12x10,
    MVR_IMAGE_FORMAT_ASTC_12x12,
    MVR_IMAGE_FORMAT_COUNT
} mvr_image_format;

/* Levels of a 16384-texel image's full mip chain. */
#define MVR_IMAGE_MAX_LEVELS 15

/* "rgba8", "etc2_rgb8", ..., "astc_12x12"; "unknown" outside the enum. */
const char *mvr_image_format_name(mvr_image_format format);
/* A format's block: width and height in texels and bytes (RGBA8: 1 x 1, 4
 * bytes). false outside the enum. */
bool mvr_image_format_block(mvr_image_format format, uint32_t *block_width, uint32_t *block_height,
                            uint32_t *block_bytes);
/* The bytes of mip level `level` of a width x height image in format:
 * max(1, width >> level) by max(1, height >> level) texels in whole blocks.
 * false (and *out 0) for a format outside the enum, a level outside the
 * image's chain (floor(log2(max(width, height))) + 1 levels) or a size that
 * overflows. */
bool mvr_image_level_size(mvr_image_format format, uint32_t width, uint32_t height, uint32_t level, uint64_t *out);

typedef struct mvr_image_level {
    const void *data;            /* the level's blocks, copied */
    size_t size;                 /* exactly mvr_image_level_size's bytes */
} mvr_image_level;

/* Images: 8-bit RGBA pixels, rows top to bottom (as image files store
 * them), or (format != RGBA8) GPU blocks with their mip levels. */
typedef struct mvr_image_desc {
    uint32_t width, height;
    const uint8_t *rgba8;        /* RGBA8: width * height * 4 bytes, copied; NULL otherwise */
    const char *name;            /* optional, for messages */
    mvr_image_format format;     /* 0 = RGBA8 */
    /* Block formats: level_count (1..MVR_IMAGE_MAX_LEVELS, at most the full
     * chain) levels, level 0 (width x height) first, each its exact size.
     * Fewer levels than the full chain are fine: a sampler that reads mips
     * reads only those. RGBA8 images leave these 0 (mips are generated). */
    uint32_t level_count;
    mvr_image_level levels[MVR_IMAGE_MAX_LEVELS];
} mvr_image_desc;
mvr_result mvr_scene_add_image(mvr_scene *scene, const mvr_image_desc *desc, mvr_image_id *out);

typedef enum mvr_filter {
    MVR_FILTER_DEFAULT = 0,      /* mag: linear; min: linear-mipmap-linear */
    MVR_FILTER_NEAREST,
    MVR_FILTER_LINEAR,
    MVR_FILTER_NEAREST_MIPMAP_NEAREST,
    MVR_FILTER_LINEAR_MIPMAP_NEAREST,
    MVR_FILTER_NEAREST_MIPMAP_LINEAR,
    MVR_FILTER_LINEAR_MIPMAP_LINEAR
} mvr_filter;

typedef enum mvr_wrap {
    MVR_WRAP_DEFAULT = 0,        /* repeat, as glTF */
    MVR_WRAP_REPEAT,
    MVR_WRAP_CLAMP_TO_EDGE,
    MVR_WRAP_MIRRORED_REPEAT
} mvr_wrap;

typedef struct mvr_sampler_desc {
    mvr_filter mag_filter, min_filter;
    mvr_wrap wrap_s, wrap_t;
} mvr_sampler_desc;

/* KHR_texture_transform: uv' = T(offset) * R(rotation) * S(scale) * uv. */
typedef struct mvr_texture_transform {
    bool enabled;
    float offset[2];
    float rotation;              /* radians, counter-clockwise */
    float scale[2];              /* 0 = 1 */
} mvr_texture_transform;

typedef struct mvr_texture_ref {
    mvr_image_id image;          /* 0 = no texture in this role */
    mvr_sampler_desc sampler;
    uint32_t texcoord;           /* 0 or 1 */
    mvr_texture_transform transform;
} mvr_texture_ref;

typedef enum mvr_alpha_mode {
    MVR_ALPHA_OPAQUE = 0,
    MVR_ALPHA_MASK,
    MVR_ALPHA_BLEND
} mvr_alpha_mode;

/* glTF 2.0 metallic-roughness material. Factors left at zero take glTF's
 * defaults only where the desc says so (use mvr_material_defaults). */
typedef struct mvr_material_desc {
    float base_color_factor[4];
    float metallic_factor;
    float roughness_factor;
    float emissive_factor[3];
    float emissive_strength;     /* KHR_materials_emissive_strength; 0 = 1 */
    float normal_scale;          /* 0 = 1 */
    float occlusion_strength;    /* 0 = 1 */
    float alpha_cutoff;          /* 0 = 0.5 */
    mvr_alpha_mode alpha_mode;
    bool double_sided;
    bool unlit;                  /* KHR_materials_unlit */
    mvr_texture_ref base_color, metallic_roughness, normal, occlusion, emissive;
    const char *name;
    /* KHR_materials_ior: the dielectric's index of refraction, F0 =
     * ((ior - 1) / (ior + 1))^2 (also the clearcoat's); 0 = 1.5 (F0 0.04) */
    float ior;
    /* KHR_materials_specular (enabled: the extension is present): factor
     * scales the dielectric's specular (its F0 and F90), color_factor tints
     * its F0 (min(F0(ior) * color, 1)); absent: 1 and (1, 1, 1). texture:
     * its A channel scales factor; color_texture (sRGB): its RGB the color */
    struct mvr_material_specular {
        bool enabled;
        float factor;
        float color_factor[3];
        mvr_texture_ref texture, color_texture;
    } specular;
    /* KHR_materials_clearcoat: a second GGX layer (F0 from ior) over the
     * material; factor 0 = none. texture: R scales factor; roughness_texture:
     * G scales roughness_factor; normal_texture: the coat's own normal map
     * (else the geometry's normal), its xy scaled by normal_scale (0 = 1) */
    struct mvr_material_clearcoat {
        float factor;
        float roughness_factor;
        mvr_texture_ref texture, roughness_texture, normal_texture;
        float normal_scale;
    } clearcoat;
    /* KHR_materials_sheen: a Charlie-distribution sheen layer (fabric);
     * color (0, 0, 0) = none. color_texture (sRGB): RGB scales color_factor;
     * roughness_texture: A scales roughness_factor */
    struct mvr_material_sheen {
        float color_factor[3];
        float roughness_factor;
        mvr_texture_ref color_texture, roughness_texture;
    } sheen;
    /* KHR_materials_transmission: the fraction of light passing through the
     * surface (0 = opaque); texture: R scales factor */
    struct mvr_material_transmission {
        float factor;
        mvr_texture_ref texture;
    } transmission;
    /* KHR_materials_volume: the medium under a transmissive surface.
     * thickness_factor 0 = thin-walled; thickness_texture: G scales it.
     * attenuation_distance 0 = no absorption (the extension's +infinity);
     * attenuation_color: the color white light takes after that distance */
    struct mvr_material_volume {
        float thickness_factor;
        mvr_texture_ref thickness_texture;
        float attenuation_distance;
        float attenuation_color[3];
    } volume;
    /* KHR_materials_dispersion: the Abbe-number spread of ior across
     * wavelengths, as 20 / V (0 = none); only with transmission and volume */
    float dispersion;
    /* KHR_materials_iridescence: a thin film over the base (factor 0 =
     * none); texture: R scales factor; the film's thickness in nanometres is
     * mix(thickness_minimum, thickness_maximum, thickness_texture's G) or
     * thickness_maximum without the texture. mvr_material_defaults: ior 1.3,
     * 100 and 400 nm (the extension's defaults) */
    struct mvr_material_iridescence {
        float factor;
        mvr_texture_ref texture;
        float ior;
        float thickness_minimum, thickness_maximum;
        mvr_texture_ref thickness_texture;
    } iridescence;
    /* KHR_materials_anisotropy: the specular lobe stretched along a
     * direction rotated by rotation (radians, counter-clockwise from the
     * tangent) by strength (0 = isotropic); texture: RG a direction in
     * tangent space ([0, 1] -> [-1, 1]), B scales strength */
    struct mvr_material_anisotropy {
        float strength;
        float rotation;
        mvr_texture_ref texture;
    } anisotropy;
    /* KHR_materials_pbrSpecularGlossiness (archived, still in many files):
     * when enabled, base_color_factor and base_color are the diffuse factor
     * and texture, and the specular color (F0) and glossiness (1 - roughness)
     * come from here; texture (sRGB): RGB scales specular_factor, A
     * glossiness_factor. metallic and roughness are ignored */
    struct mvr_material_spec_gloss {
        bool enabled;
        float specular_factor[3];
        float glossiness_factor;
        mvr_texture_ref texture;
    } spec_gloss;
} mvr_material_desc;

/* glTF's defaults: base color (1,1,1,1), metallic 1, roughness 1, opaque;
 * the extensions' own defaults (iridescence ior 1.3 and 100-400 nm, volume
 * attenuation color white, spec-gloss factors 1). */
mvr_material_desc mvr_material_defaults(void);
mvr_result mvr_scene_add_material(mvr_scene *scene, const mvr_material_desc *desc,
                                  mvr_material_id *out);

typedef enum mvr_primitive_mode {
    MVR_PRIMITIVE_TRIANGLES = 0,
    MVR_PRIMITIVE_LINES,
    MVR_PRIMITIVE_POINTS
} mvr_primitive_mode;

/* One draw's worth of geometry; arrays are copied. Optional arrays are NULL. */
typedef struct mvr_primitive_desc {
    uint32_t vertex_count;
    const float *positions;      /* 3 per vertex, required */
    const float *normals;        /* 3 per vertex */
    const float *tangents;       /* 4 per vertex (w = bitangent sign) */
    const float *texcoords0;     /* 2 per vertex */
    const float *texcoords1;     /* 2 per vertex */
    const float *colors;         /* 4 per vertex (linear RGBA) */
    uint32_t index_count;        /* 0 = non-indexed */
    const uint16_t *indices16;   /* one of these two when indexed */
    const uint32_t *indices32;
    mvr_primitive_mode mode;
    mvr_material_id material;    /* 0 = the default material */
    /* Skinning (glTF JOINTS_n / WEIGHTS_n): per vertex four joints and four
     * weights per set; set 1 (optional) adds four more influences. A joint
     * is an index into the joints of the skin of the node that draws the
     * mesh (mvr_scene_set_node_skin); an index past that skin's joints is
     * refused when the node is given the skin. Weights must be finite and
     * >= 0; each vertex's are normalised to sum 1 on the way in (a vertex
     * whose weights are all 0 follows joint 0 of its first set, logged as a
     * repair). A mesh with joints drawn by a node without a skin draws its
     * bind pose placed by the node, as glTF asks. */
    const uint16_t *joints0;     /* 4 per vertex */
    const float *weights0;       /* 4 per vertex; with joints0 */
    const uint16_t *joints1;     /* 4 per vertex; only with joints0 */
    const float *weights1;
    /* Morph targets: target_count targets, each with deltas of the same
     * attributes in every target of the primitive (glTF 3.7.2.2). */
    const struct mvr_morph_target_desc *targets;
    uint32_t target_count;
} mvr_primitive_desc;

/* The deltas of one morph target, per vertex of its primitive; NULL = none
 * of that attribute. A target may only move attributes the primitive has
 * (normals and tangents deltas need the primitive's normals and tangents). */
typedef struct mvr_morph_target_desc {
    const float *positions;      /* 3 per vertex */
    const float *normals;        /* 3 per vertex */
    const float *tangents;       /* 3 per vertex: xyz only (w, the handedness, stays) */
} mvr_morph_target_desc;

typedef struct mvr_mesh_desc {
    const mvr_primitive_desc *primitives;
    uint32_t primitive_count;
    const char *name;
    /* Default morph weights (glTF mesh.weights), one per target; every
     * primitive of a mesh with targets has the same target count. NULL = 0. */
    const float *weights;
    uint32_t weight_count;
} mvr_mesh_desc;
mvr_result mvr_scene_add_mesh(mvr_scene *scene, const mvr_mesh_desc *desc, mvr_mesh_id *out);

typedef enum mvr_light_type {
    MVR_LIGHT_DIRECTIONAL = 0,
    MVR_LIGHT_POINT,
    MVR_LIGHT_SPOT
} mvr_light_type;

/* KHR_lights_punctual: the light shines along its node's -Z; intensity in lux
 * (directional) or candela (point, spot). */
typedef struct mvr_light_desc {
    mvr_light_type type;
    float color[3];              /* all zero = white */
    float intensity;
    float range;                 /* 0 = infinite */
    float inner_cone_angle;      /* spot, radians */
    float outer_cone_angle;      /* spot, radians; 0 = pi/4 */
    /* Shadows (directional and spot lights; point lights cast none): drawn
     * when the render's shadow mode is MVR_SHADOWS_DEFAULT and this is true,
     * or the mode is MVR_SHADOWS_ALL. glTF has no such flag: false. */
    bool cast_shadows;
    /* Render layers: the light shines in the views whose light_layers share
     * a bit with these (mvr_view_desc.light_layers). 0 = every layer. A
     * light in no enabled view takes no shadow layer. */
    uint32_t layers;
} mvr_light_desc;
mvr_result mvr_scene_add_light(mvr_scene *scene, const mvr_light_desc *desc, mvr_light_id *out);

typedef enum mvr_projection_type {
    MVR_PROJECTION_PERSPECTIVE = 0, /* symmetric: yfov + aspect */
    MVR_PROJECTION_FRUSTUM,         /* asymmetric: four angles, as OpenXR's XrFovf */
    MVR_PROJECTION_ORTHOGRAPHIC,
    MVR_PROJECTION_MATRIX           /* explicit, GL conventions (clip z in [-w, w]) */
} mvr_projection_type;

typedef struct mvr_projection {
    mvr_projection_type type;
    double yfov;                 /* perspective, radians; 0 = 60 degrees */
    double aspect;               /* perspective; 0 = the viewport's */
    double angle_left, angle_right, angle_down, angle_up; /* frustum, radians (left/down < 0) */
    double xmag, ymag;           /* orthographic half extents */
    double znear;                /* 0 = 0.05 */
    double zfar;                 /* 0 = infinite (perspective, frustum); orthographic: 0 = 1000 */
    double matrix[16];           /* explicit, column-major */
} mvr_projection;

mvr_result mvr_scene_add_camera(mvr_scene *scene, const mvr_projection *projection,
                                mvr_camera_id *out);

typedef struct mvr_node_desc {
    mvr_node_id parent;          /* 0 = a root */
    double translation[3];
    double rotation[4];          /* quaternion x, y, z, w; all zero = identity */
    double scale[3];             /* all zero = (1, 1, 1) */
    bool use_matrix;             /* take matrix instead of TRS */
    double matrix[16];           /* column-major */
    mvr_mesh_id mesh;
    mvr_light_id light;
    mvr_camera_id camera;
    const char *name;
} mvr_node_desc;
mvr_result mvr_scene_add_node(mvr_scene *scene, const mvr_node_desc *desc, mvr_node_id *out);
/* Moves a node (only transforms are re-sent to the GPU). */
mvr_result mvr_scene_set_node_transform(mvr_scene *scene, mvr_node_id node,
                                        const double translation[3], const double rotation[4],
                                        const double scale[3]);

/* ---- skins, morph weights, animations */

typedef struct mvr_skin_id { uint32_t id; } mvr_skin_id;

/* A glTF skin: joint nodes and the inverse bind matrix of each. Vertex v of
 * a mesh drawn by a node with this skin lands at
 *   sum_i w_i * world(joints[j_i]) * inverse_bind_matrices[j_i] * v
 * (the drawing node's own transform does not apply, as glTF asks), computed
 * per frame in double and narrowed to float relative to the view set's
 * origin. */
typedef struct mvr_skin_desc {
    const mvr_node_id *joints;   /* joint_count nodes, each at most once */
    uint32_t joint_count;        /* 1 .. 65536 */
    const double *inverse_bind_matrices; /* 16 per joint, column-major; NULL = identities */
    mvr_node_id skeleton;        /* optional: the skeleton's root (glTF skin.skeleton); informative */
    const char *name;
} mvr_skin_desc;
mvr_result mvr_scene_add_skin(mvr_scene *scene, const mvr_skin_desc *desc, mvr_skin_id *out);
/* Gives a node (that draws a mesh) a skin; {0} removes it. Refused when a
 * primitive of the node's mesh names a joint past the skin's joints. */
mvr_result mvr_scene_set_node_skin(mvr_scene *scene, mvr_node_id node, mvr_skin_id skin);
/* A node's morph weights (glTF node.weights), one per target of its mesh;
 * count 0 returns to the mesh's default weights. */
mvr_result mvr_scene_set_node_weights(mvr_scene *scene, mvr_node_id node, const float *weights, uint32_t count);

typedef enum mvr_animation_path {
    MVR_ANIMATION_PATH_TRANSLATION = 0, /* 3 values per key */
    MVR_ANIMATION_PATH_ROTATION,        /* 4 (quaternion x, y, z, w) */
    MVR_ANIMATION_PATH_SCALE,           /* 3 */
    MVR_ANIMATION_PATH_WEIGHTS          /* one per morph target of the node's mesh */
} mvr_animation_path;
const char *mvr_animation_path_name(mvr_animation_path path);

typedef enum mvr_interpolation {
    MVR_INTERPOLATION_LINEAR = 0,  /* slerp along the shorter arc for rotations */
    MVR_INTERPOLATION_STEP,
    MVR_INTERPOLATION_CUBICSPLINE  /* glTF 2.0 Appendix C; per key in-tangent, value, out-tangent */
} mvr_interpolation;

typedef struct mvr_animation_sampler_desc {
    const float *times;          /* key_count seconds, finite, strictly increasing */
    uint32_t key_count;          /* >= 1 */
    const float *values;         /* value_count floats: key_count * components (x3 for CUBICSPLINE) */
    uint32_t value_count;
    mvr_interpolation interpolation;
} mvr_animation_sampler_desc;

typedef struct mvr_animation_channel_desc {
    uint32_t sampler;            /* index into the animation's samplers */
    mvr_node_id node;
    mvr_animation_path path;
} mvr_animation_channel_desc;

typedef struct mvr_animation_desc {
    const mvr_animation_sampler_desc *samplers;
    uint32_t sampler_count;
    const mvr_animation_channel_desc *channels;
    uint32_t channel_count;
    const char *name;
} mvr_animation_desc;

/* Adds an animation (copied): every sampler's times and values are checked
 * against the channels that read it (component counts, weights against the
 * target count of the node's mesh). *out_index (optional) is its index. */
mvr_result mvr_scene_add_animation(mvr_scene *scene, const mvr_animation_desc *desc, uint32_t *out_index);
uint32_t mvr_scene_animation_count(const mvr_scene *scene);

typedef struct mvr_animation_info {
    const char *name;            /* "" when unnamed; owned by the scene */
    double start, end;           /* seconds: the earliest and latest key of its samplers */
    uint32_t channels, samplers;
} mvr_animation_info;
mvr_result mvr_scene_get_animation_info(const mvr_scene *scene, uint32_t index, mvr_animation_info *out);
/* The index of the first animation with this name; MVR_ERROR_INVALID_ARGUMENT
 * (naming the animations there are) when none has it. */
mvr_result mvr_scene_find_animation(const mvr_scene *scene, const char *name, uint32_t *out_index);

#define MVR_ANIMATION_ALL UINT32_MAX

typedef enum mvr_animation_wrap {
    MVR_ANIMATION_CLAMP = 0,     /* before start: the first keys; after end: the last */
    MVR_ANIMATION_LOOP           /* time wrapped into [start, end) of the animation */
} mvr_animation_wrap;

/* Poses the scene at `time` seconds of animation `index` (MVR_ANIMATION_ALL:
 * every animation, in order, each at that time): the channels' nodes take
 * the sampled translation / rotation / scale / weights. Nodes no channel
 * targets keep their pose. Cheap: no GPU work until the next render, which
 * re-sends joint matrices and weights, never geometry; applying the pose
 * the scene already has (a paused player) changes nothing and sends nothing. */
mvr_result mvr_scene_apply_animation(mvr_scene *scene, uint32_t index, double time, mvr_animation_wrap wrap);
/* Back to the rest pose: the transforms and weights that mvr_scene_add_node,
 * mvr_scene_set_node_transform and mvr_scene_set_node_weights last gave
 * (else the mesh's default weights); animations never change it. */
void mvr_scene_reset_pose(mvr_scene *scene);

/* ---- material variants (KHR_materials_variants)
 *
 * A variant is a named configuration of materials (a product's colours, a
 * night and a day look). Each primitive may map some variants to materials;
 * while a variant is selected, every primitive that maps it draws with the
 * material it maps to, and every other primitive with its own material (the
 * one its mvr_primitive_desc gave). Selecting MVR_VARIANT_DEFAULT, the
 * initial state, draws every primitive with its own material. Selecting is
 * cheap: no geometry is sent again; the next render rebuilds its draws (the
 * material block and texture arrays are re-sent too: a variant can bring
 * materials, textures and shader features no draw had). */

#define MVR_VARIANT_DEFAULT UINT32_MAX

/* Adds a variant (name copied; glTF allows two variants to share a name,
 * mvr_scene_find_variant then gives the first). *out_index (optional) is
 * its index: 0, 1, ... in the order they are added. */
mvr_result mvr_scene_add_variant(mvr_scene *scene, const char *name, uint32_t *out_index);
uint32_t mvr_scene_variant_count(const mvr_scene *scene);
/* Its name, owned by the scene; NULL past the end. */
const char *mvr_scene_variant_name(const mvr_scene *scene, uint32_t index);
/* The index of the first variant with this name; MVR_ERROR_INVALID_ARGUMENT
 * (naming the variants there are) when none has it. */
mvr_result mvr_scene_find_variant(const mvr_scene *scene, const char *name, uint32_t *out_index);

typedef struct mvr_variant_mapping {
    uint32_t variant;            /* a variant's index */
    mvr_material_id material;    /* drawn with it while that variant is selected; 0 = the default material */
} mvr_variant_mapping;

/* Gives primitive `primitive` (its index in the mesh's desc) of `mesh` its
 * mappings (copied), replacing those it had; count 0 removes them. Each
 * variant at most once per primitive. Applies at once if a variant is
 * selected. */
mvr_result mvr_scene_set_primitive_variants(mvr_scene *scene, mvr_mesh_id mesh, uint32_t primitive,
                                            const mvr_variant_mapping *mappings, uint32_t count);
/* Selects variant `index`, or MVR_VARIANT_DEFAULT. Selecting the variant
 * already selected (or one that changes no primitive's material) changes
 * nothing and makes no work for the renderer. */
mvr_result mvr_scene_select_variant(mvr_scene *scene, uint32_t index);
/* The selected variant's index, or MVR_VARIANT_DEFAULT. */
uint32_t mvr_scene_selected_variant(const mvr_scene *scene);

/* Ambient light: uniform radiance from every direction (linear RGB). */
void mvr_scene_set_ambient(mvr_scene *scene, const float rgb[3]);

typedef struct mvr_scene_info {
    uint32_t images, materials, meshes, primitives, nodes, lights, cameras;
    uint32_t skins, joints, animations, morph_targets; /* joints and targets summed over skins / primitives */
    double bounds_min[3], bounds_max[3]; /* world space, of every drawn primitive */
    /* the brightest light of each type (directional lux; point and spot
     * candela; color's largest channel times intensity) */
    float max_light_intensity[3];
} mvr_scene_info;
/* True when the lights are in physical units at a scale exposure 1 would
 * blow out (a directional light over 20 lux, or a point or spot light over
 * 100 candela: a tool's export of a real scene, as KHR_lights_punctual
 * asks), so an auto-exposed, tone-mapped render is the one to show. */
bool mvr_scene_lights_physical(const mvr_scene *scene);
void mvr_scene_get_info(const mvr_scene *scene, mvr_scene_info *out);
/* What the extra outputs' IDs (MVR_OUTPUT_IDS) name: ids run 1..count of
 * mvr_scene_info. Names are "" when unnamed (owned by the scene); NULL for
 * an id the scene does not have. */
const char *mvr_scene_node_name(const mvr_scene *scene, mvr_node_id node);
const char *mvr_scene_mesh_name(const mvr_scene *scene, mvr_mesh_id mesh);
const char *mvr_scene_material_name(const mvr_scene *scene, mvr_material_id material);
/* The mesh a node draws (0: none or no such node). */
mvr_mesh_id mvr_scene_node_mesh(const mvr_scene *scene, mvr_node_id node);

/* Nodes that carry a camera, in node order. */
uint32_t mvr_scene_camera_node_count(const mvr_scene *scene);
/* Degenerate values repaired on the way in, each logged as a warning: NaN,
 * infinite or zero-length normals and tangents, NaN UVs and colors, NaN,
 * denormal or out-of-range material factors, zero quaternions. (NaN or
 * infinite positions and transforms are refused.) */
uint32_t mvr_scene_sanitized_count(const mvr_scene *scene);
mvr_node_id mvr_scene_camera_node(const mvr_scene *scene, uint32_t index); /* {0} past the end */

/* The world pose of a camera node, with its camera's projection, as a view. */
struct mvr_view_desc;
mvr_result mvr_scene_camera_view(const mvr_scene *scene, mvr_node_id camera_node,
                                 struct mvr_view_desc *out_view);

/* ------------------------------------------------------------------ view sets */

typedef struct mvr_viewport {
    int32_t x, y;                /* from the bottom-left, in layer pixels */
    uint32_t width, height;      /* 0 = the whole layer */
} mvr_viewport;

typedef struct mvr_view_desc {
    double position[3];          /* world */
    double orientation[4];       /* quaternion x, y, z, w, camera looks along -Z; all zero = identity */
    mvr_projection projection;
    mvr_viewport viewport;
    bool disabled;               /* not rendered (its layer is left as it was) */
    /* Lights this view sees: those whose layers share a bit with these
     * (mvr_light_desc.layers); a masked-out light contributes nothing here.
     * 0 = every layer. */
    uint32_t light_layers;
} mvr_view_desc;

/* Pose helper: a view at eye looking at target with up. */
void mvr_view_look_at(mvr_view_desc *view, const double eye[3], const double target[3],
                      const double up[3]);

typedef struct mvr_view_set mvr_view_set;

typedef struct mvr_view_set_desc {
    uint32_t view_count;
    const mvr_view_desc *views;
    /* The origin the GPU sees as 0: model and view matrices are made relative
     * to it in double precision. false = the centroid of the view positions. */
    bool origin_set;
    double origin[3];
} mvr_view_set_desc;

mvr_result mvr_view_set_create(const mvr_view_set_desc *desc, mvr_view_set **out, mvr_error *out_error);
void mvr_view_set_destroy(mvr_view_set *set);
mvr_result mvr_view_set_update(mvr_view_set *set, uint32_t index, const mvr_view_desc *view);
uint32_t mvr_view_set_count(const mvr_view_set *set);
/* View `index` as given (or last updated), and the set's origin (as given, or
 * the centroid of its views): a set made of some of its views with this
 * origin (origin_set) renders them as the whole set does (what is fitted
 * to all the views of a render, such as shadow cascades and one shared
 * auto-exposure, is then fitted to that set's). Fail on NULL or an index
 * past the end. */
mvr_result mvr_view_set_get_view(const mvr_view_set *set, uint32_t index, mvr_view_desc *out);
mvr_result mvr_view_set_get_origin(const mvr_view_set *set, double out[3]);

/* Camera metadata of a view for data pipelines (issue 21): what each pixel
 * of its viewport sees, in double, whatever the GPU's relative matrices.
 * Conventions: the world is glTF's (right-handed, +Y up, metres if the file
 * says so); world_to_camera / camera_to_world (column-major) use the OpenGL
 * camera (x right, y up, looking along -Z, as glTF cameras and NeRF's
 * transforms.json); fx, fy, cx, cy are pinhole intrinsics in pixels for the
 * OpenCV / COLMAP camera (x right, y down, looking along +Z): a camera point
 * (X, Y, Z) lands at u = fx X / Z + cx, v = fy Y / Z + cy, measured from the
 * viewport's top-left corner with pixel k covering [k, k + 1) (COLMAP's; its
 * centre is k + 0.5: subtract 0.5 for OpenCV's integer centres).
 * projection: the OpenGL clip matrix (z in [-1, 1]; mvr's reversed-Z is
 * the GPU's business). Orthographic views have no pinhole: perspective is
 * false and fx .. cy are 0. width, height: the view's viewport on a layer of
 * that size. */
typedef struct mvr_view_camera {
    uint32_t width, height;
    bool perspective;
    double fx, fy, cx, cy;
    double projection[16];
    double world_to_camera[16];
    double camera_to_world[16];
} mvr_view_camera;
mvr_result mvr_view_set_get_camera(const mvr_view_set *set, uint32_t index, uint32_t layer_width,
                                   uint32_t layer_height, mvr_view_camera *out);
const char *mvr_view_set_last_error(const mvr_view_set *set);


/* ------------------------------------------------------------------ environments
 *
 * Image-based lighting: radiance arriving from every direction, as an
 * equirectangular image (latitude-longitude, linear RGB radiance), the
 * built-in neutral studio, or one uniform radiance. An environment is CPU
 * data (no GL): a renderer prefilters it on the GPU once, the first time it
 * renders with it (and again only when its pixels change), and every view of
 * every later frame reads the same maps (mvr_frame_stats.env_prefilter_passes
 * is 0 on those frames).
 *
 * Directions: glTF's world, +Y up. The image's top row is +Y, its bottom
 * row -Y; its centre column looks along -Z (what a glTF camera with no
 * rotation sees), its right quarter along +X: a direction d maps to
 * u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi (v = 0: top row).
 * rotation turns the environment about +Y, counter-clockwise seen from
 * above (so +90 brings what was at -Z to -X).
 *
 * Diffuse light is the irradiance of the environment in third-order
 * spherical harmonics (9 coefficients per channel, Ramamoorthi and
 * Hanrahan 2001), projected on the CPU in double precision when the
 * environment is created; specular light is the split-sum approximation
 * (Karis 2013): a GGX-prefiltered cube map chain (one roughness per level,
 * the Khronos glTF Sample Renderer's mapping lod = roughness * (levels - 1))
 * and a DFG lookup table computed once per renderer.
 */
typedef struct mvr_environment mvr_environment;

typedef enum mvr_environment_source {
    MVR_ENVIRONMENT_NEUTRAL = 0, /* the built-in studio: procedural, deterministic, no data shipped */
    MVR_ENVIRONMENT_PIXELS,      /* an equirectangular image in memory */
    MVR_ENVIRONMENT_UNIFORM      /* one radiance from every direction (the white furnace) */
} mvr_environment_source;
const char *mvr_environment_source_name(mvr_environment_source source);

typedef struct mvr_environment_desc {
    mvr_environment_source source;
    /* PIXELS: width * height RGBA floats, linear radiance, rows top first
     * (alpha ignored). Copied: the caller keeps its memory. Images larger
     * than 2048 either way are box-filtered (in linear light, exact area
     * weights) to fit 2048 x 2048, keeping their aspect (4096 x 2048 ->
     * 2048 x 1024). NaN, infinite and negative values become 0 (a warning). */
    const float *pixels;
    uint32_t width, height;
    float color[3];              /* UNIFORM: radiance; all 0 = (1, 1, 1) */
    float intensity;             /* multiplies the radiance; 0 = 1 */
    float rotation;              /* degrees about +Y */
    uint32_t specular_size;      /* prefiltered cube face size, a power of two 16..1024; 0 = 128 */
    /* GGX samples per texel of the prefilter, 1..4096; 0 = 256. Against the
     * Khronos glTF Sample Renderer under a sky with a small sun (radiance
     * 50 in a 4-degree disc: tests/io/test_peers.cpp), 64 samples differ by
     * RMSE 4.4/255, 256 by 2.6/255, for ~80 ms more prefilter on llvmpipe. */
    uint32_t specular_samples;
    mvr_logger logger;
} mvr_environment_desc;

mvr_result mvr_environment_create(const mvr_environment_desc *desc, mvr_environment **out, mvr_error *out_error);
/* NULL is fine. A renderer that used it keeps its maps until it renders
 * with another environment or is destroyed. */
void mvr_environment_destroy(mvr_environment *environment);
/* Intensity (0 = 1) and rotation (degrees) change without prefiltering again. */
void mvr_environment_set_intensity(mvr_environment *environment, float intensity);
void mvr_environment_set_rotation(mvr_environment *environment, float degrees);
float mvr_environment_intensity(const mvr_environment *environment);
float mvr_environment_rotation(const mvr_environment *environment);

/* The irradiance the spherical harmonics give a surface facing world
 * direction n, divided by pi (so a white Lambertian surface's radiance),
 * intensity and rotation applied. */
void mvr_environment_diffuse(const mvr_environment *environment, const double n[3], double out_rgb[3]);
/* The radiance arriving from world direction d (bilinear in the stored
 * image), intensity and rotation applied. */
void mvr_environment_radiance(const mvr_environment *environment, const double d[3], double out_rgb[3]);

/* ------------------------------------------------------------------ renderer */

typedef struct mvr_renderer mvr_renderer;
typedef struct mvr_target mvr_target;

typedef enum mvr_view_path {
    MVR_VIEW_PATH_AUTO = 0,      /* the faster for frame time, as measured: multiview where the GL has
                                    it, loop where multiview defers rasterization to the pass's end
                                    (llvmpipe) or cannot attach the target */
    MVR_VIEW_PATH_MULTIVIEW,     /* one pass per chunk of <= GL_MAX_VIEWS_OVR views */
    MVR_VIEW_PATH_LOOP           /* one pass per view */
} mvr_view_path;
const char *mvr_view_path_name(mvr_view_path path);

typedef enum mvr_material_path {
    /* measured (mvr_tuning_desc), from arrays; arrays without tuning. On
     * llvmpipe per-material drew most demo configurations faster, up to 29% (docs/benchmarks.md) */
    MVR_MATERIAL_PATH_AUTO = 0,
    MVR_MATERIAL_PATH_ARRAYS,        /* textures grouped into 2D arrays, bound once per group per pass */
    MVR_MATERIAL_PATH_PER_MATERIAL,  /* one 2D texture per image, bound when the material changes */
    MVR_MATERIAL_PATH_PER_DRAW       /* benchmark baseline: texture and material range re-bound every draw */
} mvr_material_path;
const char *mvr_material_path_name(mvr_material_path path);

/* Where skinning and morphing run (scenes without skins or morph targets
 * run neither). Both give the same pixels (tests/gl/test_skinning.c). */
typedef enum mvr_skinning_path {
    /* measured (mvr_tuning_desc), from the rule: pre-skinning for more than
     * one view, the vertex path for one (on llvmpipe 16 skinned meshes drew
     * 25-35% faster pre-skinned at 6 and 16 views and 20% slower at one,
     * docs/benchmarks.md) */
    MVR_SKINNING_PATH_AUTO = 0,
    /* in the mesh vertex shader of every pass: once per view where the GL
     * loops views inside a multiview draw (llvmpipe), and again in the
     * shadow pass */
    MVR_SKINNING_PATH_VERTEX,
    /* once per frame: a transform feedback pass writes the posed vertices
     * into a buffer that every view and the shadow pass then draw */
    MVR_SKINNING_PATH_PRESKIN
} mvr_skinning_path;
const char *mvr_skinning_path_name(mvr_skinning_path path);

/* Depth: reversed-Z (GL_EXT_clip_control zero-to-one, 32-bit float depth,
 * GL_GREATER, clear to 0, infinite far plane allowed) keeps about constant
 * relative precision with distance; standard depth (-1..1, GL_LESS, a finite
 * far plane) is what remains where clip control is missing. */
typedef enum mvr_depth_mode {
    MVR_DEPTH_MODE_AUTO = 0,     /* reversed-Z where clip control exists, else standard */
    MVR_DEPTH_MODE_REVERSED_Z,   /* refused (MVR_ERROR_UNSUPPORTED) without clip control */
    MVR_DEPTH_MODE_STANDARD
} mvr_depth_mode;
const char *mvr_depth_mode_name(mvr_depth_mode mode);

/* Order of blended (transparent) draws, back to front by object centre. A
 * multiview pass draws one order for all its views: the centroid order,
 * by distance from the view set's origin (the views' centroid unless set).
 * Where a view needs another order, its blended draws go in a pass of its
 * own after the multiview pass has drawn the opaque ones (same depth
 * buffer). A loop pass has one view, so its exact order costs nothing. */
typedef enum mvr_transparency_order {
    /* exact per view, falling back to per-view blend passes only in the
     * multiview chunks whose views disagree on the order (detected from the
     * sort keys: a pair of blended draws whose order flips between views) */
    MVR_TRANSPARENCY_ORDER_AUTO = 0,
    /* the centroid order everywhere, loop passes included: never an extra
     * pass; views far from the centroid may see nearby transparent objects
     * in the wrong order */
    MVR_TRANSPARENCY_ORDER_CENTROID,
    /* every view its own order: per-view blend passes in every multiview
     * chunk that draws blended objects */
    MVR_TRANSPARENCY_ORDER_PER_VIEW
} mvr_transparency_order;
const char *mvr_transparency_order_name(mvr_transparency_order order);

typedef enum mvr_tone_map {
    MVR_TONE_MAP_NONE = 0,       /* clamp */
    MVR_TONE_MAP_ACES,           /* the fitted ACES curve of the Khronos glTF Sample Renderer */
    MVR_TONE_MAP_KHR_PBR_NEUTRAL /* Khronos PBR Neutral */
} mvr_tone_map;

/* Images the GL cannot hold: larger than GL_MAX_TEXTURE_SIZE, or whose
 * texture (with its mip chain; on the array path, its texture array with the
 * other layers of its group) the GL refuses with GL_OUT_OF_MEMORY. Both
 * material paths decide the same way; the array path may halve further when
 * its array's other layers are what does not fit. */
typedef enum mvr_oversized_image {
    MVR_OVERSIZED_IMAGE_DEFAULT = 0, /* downscale */
    /* halved (both sides, a box filter in linear light for sRGB roles) until
     * the GL holds it; logged as a warning naming the image, counted in
     * mvr_frame_stats.images_downscaled */
    MVR_OVERSIZED_IMAGE_DOWNSCALE,
    /* the render fails (MVR_ERROR_UNSUPPORTED over GL_MAX_TEXTURE_SIZE,
     * MVR_ERROR_OUT_OF_MEMORY on GL_OUT_OF_MEMORY) naming the image */
    MVR_OVERSIZED_IMAGE_REFUSE
} mvr_oversized_image;
const char *mvr_oversized_image_name(mvr_oversized_image policy);

/* Overrides: debugging, test and benchmark switches that win over what the
 * other fields of the renderer desc (and the descs of the renderer's
 * targets) ask. Zero = none: a field left 0 leaves the descriptors in
 * charge. mvr reads no environment variable by itself; an application that
 * lets its users steer these from the environment calls
 * mvr_renderer_overrides_from_env (the mvr CLI and mvr-viewer do: each
 * field names its variable). */
typedef enum mvr_override_switch {
    MVR_OVERRIDE_NONE = 0,       /* what the descriptors ask */
    MVR_OVERRIDE_OFF,
    MVR_OVERRIDE_ON
} mvr_override_switch;

typedef enum mvr_view_path_override {
    MVR_VIEW_PATH_OVERRIDE_NONE = 0, /* view_path */
    MVR_VIEW_PATH_OVERRIDE_AUTO,
    MVR_VIEW_PATH_OVERRIDE_MULTIVIEW,
    MVR_VIEW_PATH_OVERRIDE_LOOP
} mvr_view_path_override;

typedef enum mvr_material_path_override {
    MVR_MATERIAL_PATH_OVERRIDE_NONE = 0, /* material_path */
    MVR_MATERIAL_PATH_OVERRIDE_AUTO,
    MVR_MATERIAL_PATH_OVERRIDE_ARRAYS,
    MVR_MATERIAL_PATH_OVERRIDE_PER_MATERIAL,
    MVR_MATERIAL_PATH_OVERRIDE_PER_DRAW
} mvr_material_path_override;

typedef enum mvr_depth_mode_override {
    MVR_DEPTH_MODE_OVERRIDE_NONE = 0, /* depth_mode */
    MVR_DEPTH_MODE_OVERRIDE_AUTO,
    MVR_DEPTH_MODE_OVERRIDE_REVERSED_Z, /* refused without clip control, as depth_mode's is */
    MVR_DEPTH_MODE_OVERRIDE_STANDARD
} mvr_depth_mode_override;

typedef enum mvr_skinning_path_override {
    MVR_SKINNING_PATH_OVERRIDE_NONE = 0, /* skinning_path */
    MVR_SKINNING_PATH_OVERRIDE_AUTO,
    MVR_SKINNING_PATH_OVERRIDE_VERTEX,
    MVR_SKINNING_PATH_OVERRIDE_PRESKIN
} mvr_skinning_path_override;

/* The online tuner behind `auto` (the material path, then the view path,
 * then the skinning path): the first frames after a change of inputs (view
 * count, target size, the scene's draw count or the draws the views see
 * after culling by more than a factor of 2) run the candidates in turns of
 * two frames, the rule's choice (the prior) first: the first frame of a turn
 * follows a switch (and warms a candidate up: program compiles, uploads) and
 * is not measured, the second is (the frame's cost: the larger of its
 * submitting-thread CPU time and its GPU time from timestamp queries, taken
 * outside multiview framebuffers; CPU time alone where the GL has no timer).
 * At least 3 measured frames each; where the medians are then within 10% of
 * each other (inside the noise), up to 7 each until they part. The path with
 * the lower median is kept (the prior on a tie). 12
 * frames per decision and change where the paths differ clearly, at most 28
 * where they are close, half of them on the other path; settled frames are
 * not measured. One decision is measured at a time,
 * the later ones keyed on the earlier ones' choices (a new material path
 * measures the view path again), running their own settled choice or prior
 * meanwhile. While the material path is measured both representations of the
 * materials (texture arrays, per-material textures) are resident; the one not
 * chosen is released when it settles. Where only one path can run (no
 * multiview, MSAA that multiview cannot draw, no skins or morph targets)
 * that decision is not measured. Every candidate gives the same pixels
 * (tested). stats.auto_choice, auto_material and auto_skinning say what was
 * measured and why each path runs. */
typedef enum mvr_tuning {
    MVR_TUNING_DEFAULT = 0,      /* on */
    MVR_TUNING_ON,
    MVR_TUNING_OFF               /* auto is the caps rule alone (the prior) */
} mvr_tuning;

typedef struct mvr_frame_stats mvr_frame_stats;
typedef struct mvr_tuning_desc {
    mvr_tuning mode;
    /* Tests and experiments: the cost (ms) of each measured frame instead of
     * the timers (path: the candidate it ran). NULL = the timers. */
    double (*frame_cost)(void *user, mvr_view_path path, const mvr_frame_stats *stats);
    void *user;
} mvr_tuning_desc;

typedef struct mvr_renderer_overrides {
    /* MVR_VIEW_PATH=auto|multiview|loop: the view path, whatever view_path asks */
    mvr_view_path_override view_path;
    /* MVR_MATERIAL_PATH=auto|arrays|per_material|per_draw */
    mvr_material_path_override material_path;
    /* MVR_DEPTH=auto|reversed_z|standard */
    mvr_depth_mode_override depth_mode;
    /* MVR_CULLING=on|off: per-view frustum culling, whatever disable_culling asks */
    mvr_override_switch culling;
    /* MVR_INSTANCING=on|off: instancing, whatever disable_instancing asks
     * (on: where the material path and the block alignment allow it, as by
     * default) */
    mvr_override_switch instancing;
    /* MVR_MSAA_MULTIVIEW=on|off: off draws the renderer's multisampled
     * targets view by view (the loop path) even where the GL has
     * multisampled multiview; on is the default */
    mvr_override_switch msaa_multiview;
    /* MVR_FORCE_FEATURES=inert: every draw's program variant gains the
     * features that cannot change its pixels (tests: skipping features
     * changes cost, not pixels) */
    bool force_inert_features;
    /* MVR_UBO_ALIGNMENT=N: uniform data laid out for a uniform buffer offset
     * alignment of N bytes (a power of two, at most 4096), as a GL that needs
     * N would (tests of the padded layouts desktop GPUs use, on a GL that
     * needs less); never below the GL's own. 0 = the GL's. */
    uint32_t ubo_alignment;
    /* MVR_SKINNING_PATH=auto|vertex|preskin */
    mvr_skinning_path_override skinning_path;
    /* MVR_DISABLE_FEATURES=SPECULAR,CLEARCOAT,TRANSMISSION,SHEEN,
     * IRIDESCENCE,ANISOTROPY: material extensions drawn as if absent (mesh
     * feature bits, as mvr_program_feature_name names them; only these may
     * be disabled): what an extension costs, and what it changes, in
     * `mvr bench`. 0 = none */
    uint32_t disable_features;
    /* Image formats treated as ones the GL cannot sample (bits
     * 1u << mvr_image_format; RGBA8's bit is ignored): tests of the
     * neutral-value fallback on a GL that has the formats. 0 = none */
    uint32_t disable_image_formats;
    /* MVR_TUNING=on|off: the online tuner behind auto (mvr_tuning_desc) */
    mvr_override_switch tuning;
} mvr_renderer_overrides;

/* The one place mvr reads the environment, and only when an application
 * calls it: fills *out (all of it; unset or empty variables = no override)
 * from MVR_VIEW_PATH, MVR_MATERIAL_PATH, MVR_DEPTH, MVR_CULLING,
 * MVR_INSTANCING, MVR_MSAA_MULTIVIEW, MVR_FORCE_FEATURES and
 * MVR_UBO_ALIGNMENT (values as mvr_renderer_overrides lists them). A value
 * outside those fails with MVR_ERROR_INVALID_ARGUMENT and a message naming
 * the variable, *out left all zero. Put the result in
 * mvr_renderer_desc.overrides. */
mvr_result mvr_renderer_overrides_from_env(mvr_renderer_overrides *out, mvr_error *out_error);

typedef struct mvr_renderer_desc {
    mvr_context *context;        /* required; the renderer draws with it */
    mvr_view_path view_path;
    mvr_logger logger;           /* 0 = the context's */
    mvr_material_path material_path;
    /* Per-view frustum culling is on by default (conservative bounding
     * spheres: it never changes pixels); true turns it off. */
    bool disable_culling;
    /* A directory for program binaries (glGetProgramBinary), so a later
     * renderer links variants without compiling them. NULL = no cache. The
     * directory must exist; entries are checked (checksum, driver, shader
     * source) before use and rewritten when they fail. Where the driver
     * offers no binary format the cache is silently unused. */
    const char *program_cache_dir;
    /* Instancing is on by default: consecutive draws of one primitive with
     * the same program, textures and material page become one instanced
     * draw (same pixels). true turns it off. */
    bool disable_instancing;
    mvr_depth_mode depth_mode;
    mvr_transparency_order transparency_order;
    mvr_oversized_image oversized_images;
    mvr_renderer_overrides overrides; /* 0 = none; win over the fields above */
    mvr_skinning_path skinning_path;
    mvr_tuning_desc tuning;      /* what `auto` measures (the paths set to AUTO) */
} mvr_renderer_desc;

/*
 * Lifetimes and the current context.
 * - A renderer draws with its context, and only while that context is
 *   current on the calling thread: every call that touches GL (create,
 *   render, read, finish, target create) checks first and otherwise fails
 *   with MVR_ERROR_CONTEXT, changing nothing, so the next call with the
 *   right context current works as if the failed one never happened. mvr
 *   never makes a context current by itself; only mvr_context_create (its
 *   own new context) and mvr_context_make_current do. How the current
 *   context is recognised: eglGetCurrentContext() (EGL providers),
 *   OSMesaGetCurrentContext() (OSMesa), the desc's is_current callback or
 *   the adopted EGL context (EXTERNAL; else the caller is trusted).
 * - Contexts, renderers, targets and scenes may be destroyed in any order.
 *   Destroying a context detaches its renderers, and destroying a renderer
 *   its targets: what is detached keeps only its memory, its calls fail
 *   (MVR_ERROR_CONTEXT, MVR_ERROR_INVALID_ARGUMENT) and its destroy frees it.
 *   GL objects are deleted while their context is current; an object
 *   destroyed while another context is current is deleted by the next call
 *   that finds its context current (or goes with the context). Scenes hold
 *   no GL: a renderer keeps nothing of a scene between renders but an
 *   identity, so a scene may be destroyed at any time.
 * - No call returns MVR_OK while a GL error from its own work is pending:
 *   a failed allocation (texture, buffer, renderbuffer, framebuffer) fails
 *   the call that made it (MVR_ERROR_OUT_OF_MEMORY for GL_OUT_OF_MEMORY)
 *   with a message naming the object. GL errors already pending when a call
 *   starts are the application's: logged as such (a warning) and dropped.
 */
mvr_result mvr_renderer_create(const mvr_renderer_desc *desc, mvr_renderer **out, mvr_error *out_error);
/* NULL is fine. Its targets stay valid to destroy (they are detached). */
void mvr_renderer_destroy(mvr_renderer *renderer);
const char *mvr_renderer_last_error(const mvr_renderer *renderer);

typedef enum mvr_color_format {
    MVR_COLOR_FORMAT_DEFAULT = 0, /* SRGB8_ALPHA8: linear lighting, sRGB-encoded storage */
    MVR_COLOR_FORMAT_RGBA8,       /* UNORM; the shader writes the exact sRGB encoding */
    MVR_COLOR_FORMAT_RGBA16F,     /* linear */
    MVR_COLOR_FORMAT_RGBA32F      /* linear */
} mvr_color_format;
const char *mvr_color_format_name(mvr_color_format format);

/* Anti-aliasing of a target. */
typedef enum mvr_anti_aliasing {
    MVR_ANTI_ALIASING_DEFAULT = 0, /* what samples and supersample ask (none when both are 0) */
    MVR_ANTI_ALIASING_NONE,
    MVR_ANTI_ALIASING_MSAA,        /* samples per pixel (0 = 4) */
    MVR_ANTI_ALIASING_SUPERSAMPLE, /* supersample per side (0 = 2) */
    /* 4x MSAA: in the multiview passes where the GL attaches multisampled
     * arrays with multiview (or has OVR_multiview_multisampled_render_to_
     * texture), else view by view on the loop path; 2x2 supersampling where
     * the format cannot be multisampled 4 times. Measured by `mvr bench`
     * (docs/benchmarks.md): per-view 4x MSAA costs 1.9-2.3x the frame time
     * without AA, 2x2 supersampling 3.0-3.6x, on every demo. */
    MVR_ANTI_ALIASING_AUTO
} mvr_anti_aliasing;
const char *mvr_anti_aliasing_name(mvr_anti_aliasing aa);

typedef struct mvr_target_desc {
    uint32_t width, height;
    uint32_t layers;             /* one per view; 0 = 1 */
    mvr_color_format color_format;
    /* An application-owned GL_TEXTURE_2D_ARRAY to render into (e.g. an XR
     * swapchain image): mvr attaches it, never deletes it. color_format must
     * name its format. Views go to layers base_layer .. base_layer+layers-1 of
     * mip level `level`. 0 = mvr makes its own. */
    uint32_t external_color_texture;
    uint32_t external_level;
    uint32_t external_base_layer;
    /* Multisampling: samples per pixel (0 or 1 = none). Where the GL has
     * multisampled multiview (OVR_multiview_multisampled_render_to_texture:
     * resolved by the GL; or multisampled 2D arrays that attach with
     * multiview: resolved layer by layer with glBlitFramebuffer), views
     * keep their multiview passes. Elsewhere (llvmpipe) each view is drawn
     * into a multisampled renderbuffer and resolved into its layer, one
     * view at a time (the loop path). The renderer's
     * overrides.msaa_multiview = MVR_OVERRIDE_OFF forces the latter. Refused above GL_MAX_SAMPLES or where the color format cannot
     * be multisampled. */
    uint32_t samples;
    /* Supersampling: N x N samples per pixel (0 or 1 = none, at most 4).
     * Views are drawn into a linear float array N times the size (every
     * view path, multiview included) and resolved into the layers by a
     * box filter pass (one multiview pass per chunk of views). Not with
     * samples > 1. */
    uint32_t supersample;
    mvr_anti_aliasing anti_aliasing;
    /* Extra outputs per view (mvr_output, below): MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH) | ...; 0 =
     * colour alone. Each is an extra colour attachment of the same layered
     * framebuffers, drawn in the same passes as the colour (multiview or
     * loop, the same bytes); one not asked for is not allocated or written.
     * Depth, distance and coverage share one RGBA32F array, normals take
     * one RGBA32F array, IDs one RGBA32UI array. Not with anti-aliasing
     * (samples, supersample or MSAA / SUPERSAMPLE / AUTO): an ID or a depth
     * is not averaged. Needs float colour buffers (OpenGL ES 3.2, or
     * EXT_color_buffer_float) for depth, distance, normal and coverage. */
    uint32_t outputs;
} mvr_target_desc;

/* Allocates the target's arrays and framebuffers; any the GL refuses fails
 * the call (MVR_ERROR_OUT_OF_MEMORY for GL_OUT_OF_MEMORY, MVR_ERROR_FRAMEBUFFER
 * for an incomplete framebuffer) with a message on the renderer naming it. */
mvr_result mvr_target_create(mvr_renderer *renderer, const mvr_target_desc *desc, mvr_target **out);
/* NULL is fine; so is a target whose renderer is gone (frees its memory). */
void mvr_target_destroy(mvr_target *target);
/* The GL name of the color array (the application's, or mvr's; 0 once mvr's
 * was released with its renderer). */
uint32_t mvr_target_color_texture(const mvr_target *target);

typedef enum mvr_shadow_mode {
    MVR_SHADOWS_DEFAULT = 0,     /* lights whose cast_shadows is set */
    MVR_SHADOWS_ALL,             /* every directional and spot light */
    MVR_SHADOWS_OFF
} mvr_shadow_mode;
const char *mvr_shadow_mode_name(mvr_shadow_mode mode);

/* Shadow maps: one depth texture array shared by every view, drawn once
 * per frame before the views (one multiview pass over its layers where the
 * GL has multiview and the view path is not forced to loop; one pass per
 * layer otherwise). Directional lights take one layer per cascade, fitted
 * to the union of the frustums of the views they shine in; spot lights one
 * layer. Filtering: 3x3 bilinear PCF taps. Bias: slope-scaled polygon
 * offset on the casters plus a normal offset on the receivers. Opaque and
 * alpha-masked draws cast; blended ones do not. */
typedef struct mvr_shadow_desc {
    mvr_shadow_mode mode;
    uint32_t map_size;           /* texels per side; 0 = 1024 */
    uint32_t cascades;           /* per directional light, 1..4; 0 = 3 */
    double distance;             /* view depth the cascades cover; 0 = to the scene's far side */
    float slope_bias;            /* glPolygonOffset factor; 0 = 2 */
    float constant_bias;         /* glPolygonOffset units; 0 = 2 */
    float normal_bias;           /* receiver offset along its normal, in shadow texels; 0 = 1.5 */
} mvr_shadow_desc;

const char *mvr_tone_map_name(mvr_tone_map tone_map);

/* Exposure. LINEAR multiplies the lit color by `exposure` in the lighting
 * pass (the default: results of existing code do not move). The others are
 * physical (glTF's lights are in lux and candela) and, like any tone
 * mapping or dithering, make the frame an HDR one: lighting goes into a
 * half-float array, and one final full-screen pass per chunk of views (one
 * multiview pass; per view on the loop path, the same bytes) applies
 * exposure, tone mapping, dithering and the sRGB encode into the target.
 * The photometric exposure follows Lagarde and de Rousiers, "Moving
 * Frostbite to Physically Based Rendering" (2014): exposure =
 * 1 / (1.2 * 2^EV100) (saturation-based speed, ISO 12232, S = 100), and
 * EV100 = log2(N^2 / t * 100 / S) for a camera of f-number N, shutter t
 * seconds and sensitivity S. */
typedef enum mvr_exposure_mode {
    MVR_EXPOSURE_LINEAR = 0,     /* `exposure` as a multiplier (0 = 1) */
    MVR_EXPOSURE_EV100,          /* ev100 */
    MVR_EXPOSURE_CAMERA,         /* aperture, shutter, iso */
    /* from the rendered HDR layers: their average log2 luminance (a
     * reduction through the mip levels of a log-luminance array) is put on
     * `exposure_key`; one EV100 for all views unless exposure_per_view */
    MVR_EXPOSURE_AUTO
} mvr_exposure_mode;
const char *mvr_exposure_mode_name(mvr_exposure_mode mode);

/* What pixels no geometry covers show: the clear colour, or the
 * environment (sharp, from the source cube map, or blurred, from a
 * prefiltered level), drawn per view in the same pass as the scene after
 * the opaque geometry, with the depth test, so only uncovered pixels pay. */
typedef enum mvr_background {
    MVR_BACKGROUND_COLOR = 0,    /* clear_color */
    MVR_BACKGROUND_ENVIRONMENT,  /* the environment as seen (needs one) */
    MVR_BACKGROUND_BLUR          /* the environment's prefiltered level of background_blur */
} mvr_background;
const char *mvr_background_name(mvr_background background);

/* The space of MVR_OUTPUT_NORMAL. */
typedef enum mvr_normal_space {
    MVR_NORMAL_SPACE_WORLD = 0,  /* glTF's world: right-handed, +Y up */
    MVR_NORMAL_SPACE_CAMERA      /* the view's OpenGL camera: x right, y up, +Z towards the viewer */
} mvr_normal_space;
const char *mvr_normal_space_name(mvr_normal_space space);

typedef struct mvr_render_desc {
    float clear_color[4];        /* linear RGBA */
    float exposure;              /* LINEAR: multiplies the lit color; 0 = 1 */
    mvr_tone_map tone_map;
    mvr_shadow_desc shadows;
    mvr_exposure_mode exposure_mode;
    double ev100;                /* EV100 mode */
    double aperture;             /* CAMERA: f-number; 0 = 16 */
    double shutter;              /* CAMERA: seconds; 0 = 1/125 */
    double iso;                  /* CAMERA: 0 = 100 */
    float exposure_compensation; /* EV added to what the mode gives (not LINEAR) */
    float exposure_key;          /* AUTO: where the average log luminance lands; 0 = 0.18 */
    float ev100_min, ev100_max;  /* AUTO: clamps; both 0 = -8 .. 24 */
    bool exposure_per_view;      /* AUTO: each view its own EV100 (default: one shared, so two
                                    eyes never disagree) */
    bool dither;                 /* +-1 step of triangular noise before 8-bit storage (HDR frames) */
    /* Image-based lighting (NULL = none: no IBL code is compiled, the
     * scene's ambient term is all there is). Added to punctual lights;
     * occlusion textures darken it, never the punctual lights. */
    const mvr_environment *environment;
    mvr_background background;   /* what uncovered pixels show */
    float background_blur;       /* BLUR: the roughness whose prefiltered level is shown; 0 = 0.5 */
    /* 0: the prefiltered maps (split sum, spherical harmonics). N (1..65536):
     * the reference instead: each pixel integrates the environment with N
     * importance samples per lobe (diffuse and GGX) from the unfiltered cube
     * map: slow ground truth to measure the maps' error against. */
    uint32_t environment_samples;
    /* Extra outputs (the target's): the normals' space, and the alpha from
     * which a blended (transparent) surface is recorded in depth, distance,
     * normal, IDs and coverage (0 = 0.5; see mvr_output). */
    mvr_normal_space normal_space;
    float output_alpha_cutoff;
} mvr_render_desc;

/* The photometric exposure of an EV100 (see mvr_exposure_mode): the
 * multiplier from scene luminance to the tone mapper's input. */
double mvr_exposure_from_ev100(double ev100);
/* EV100 of a camera: f-number, shutter in seconds, ISO sensitivity. */
double mvr_ev100_from_camera(double aperture, double shutter, double iso);

/* Renders every enabled view of the set into its layer of the target
 * (view i -> layer i). Uploads what changed in the scene first. */
mvr_result mvr_renderer_render(mvr_renderer *renderer, mvr_scene *scene, const mvr_view_set *views,
                               mvr_target *target, const mvr_render_desc *desc);

typedef enum mvr_readback_format {
    MVR_READBACK_RGBA8 = 0,      /* the stored bytes (sRGB-encoded for sRGB targets) */
    MVR_READBACK_RGBA32F         /* floats as stored (normalized for 8-bit targets) */
} mvr_readback_format;

/* Reads one layer into memory, rows bottom to top (GL order). size must be at
 * least width * height * 4 * (1 or 4 bytes). Never reads from a multiview
 * framebuffer: the layer is attached alone to a read framebuffer. */
mvr_result mvr_renderer_read_layer(mvr_renderer *renderer, mvr_target *target, uint32_t layer,
                                   mvr_readback_format format, void *dst, size_t size);

/* Extra outputs per view (mvr_target_desc.outputs) and what
 * mvr_renderer_read_output gives of each, per pixel. Every output describes
 * the same surface at a pixel: the front-most opaque or alpha-masked
 * surface (its pixel centre's fragment, as the colour), or a blended
 * (transparent) surface in front of it whose alpha (base colour factor x
 * texture x vertex colour) reaches mvr_render_desc.output_alpha_cutoff (the
 * front-most of those; surfaces below the cutoff are seen through). A
 * transmissive surface counts as opaque. Pixels without a surface read 0.
 * Depth and distance are in world units (relative to the view set's origin
 * in float, so as precise as the colour's geometry). */
typedef enum mvr_output {
    MVR_OUTPUT_COLOR = 0,        /* 4 x uint8: the stored colour (as MVR_READBACK_RGBA8) */
    MVR_OUTPUT_DEPTH,            /* float32: the point's depth along the camera's -Z axis (view-space -z) */
    MVR_OUTPUT_DISTANCE,         /* float32: its distance to the camera's centre (the ray's length) */
    MVR_OUTPUT_NORMAL,           /* 3 x float32: the unit normal of the geometry (interpolated vertex
                                    normals, else the face's; not normal maps), facing the viewer on
                                    the back of a double-sided surface; mvr_render_desc.normal_space */
    MVR_OUTPUT_IDS,              /* 4 x uint32: node id, mesh id, material id (0 = the default
                                    material), primitive (its index in the mesh + 1): mvr's ids
                                    (mvr_node_id.id ...), exact and the same on every path */
    MVR_OUTPUT_COVERAGE,         /* float32: 1 where a surface is recorded, else 0 */
    MVR_OUTPUT_COUNT
} mvr_output;
#define MVR_OUTPUT_BIT(output) (1u << (output))
const char *mvr_output_name(mvr_output output);
/* Bytes per pixel mvr_renderer_read_output writes (0 for an unknown output). */
size_t mvr_output_pixel_size(mvr_output output);

/* Reads one layer's output into dst in the output's own type, rows bottom
 * to top (GL order, as mvr_renderer_read_layer). size must be at least
 * width * height * mvr_output_pixel_size(output). An output the target was
 * not created with fails, naming it. */
mvr_result mvr_renderer_read_output(mvr_renderer *renderer, mvr_target *target, uint32_t layer, mvr_output output,
                                    void *dst, size_t size);

/* What `auto` measured and why the path runs (mvr_tuning_desc). */
typedef enum mvr_auto_state {
    MVR_AUTO_NONE = 0,           /* the path was asked for (not auto), or only one works here */
    MVR_AUTO_RULE,               /* tuning off: the caps rule */
    MVR_AUTO_TUNING,             /* this frame is one of the measured ones */
    MVR_AUTO_SETTLED             /* the measured choice */
} mvr_auto_state;
const char *mvr_auto_state_name(mvr_auto_state state);

typedef struct mvr_auto_choice {
    mvr_auto_state state;
    mvr_view_path prior;         /* the caps rule's choice */
    mvr_view_path chosen;        /* what runs once settled (the prior until then) */
    mvr_view_path candidates[2]; /* multiview, loop */
    uint32_t samples[2];         /* measured frames of each */
    double cost_ms[2];           /* their medians (settled), or the latest (tuning); < 0: none */
    double margin;               /* settled: the chosen path's saving over the prior's median (0..1) */
    uint32_t retunes;            /* input changes that started the measurement again */
} mvr_auto_choice;

/* The same for the material path (material path AUTO; MVR_AUTO_NONE
 * otherwise). */
typedef struct mvr_auto_material_choice {
    mvr_auto_state state;
    mvr_material_path prior;     /* arrays */
    mvr_material_path chosen;
    mvr_material_path candidates[2]; /* per_material, arrays */
    uint32_t samples[2];
    double cost_ms[2];
    double margin;
    uint32_t retunes;
} mvr_auto_material_choice;

/* The same for the skinning path (skinning path AUTO, a scene with skins or
 * morph targets; MVR_AUTO_NONE otherwise). */
typedef struct mvr_auto_skinning_choice {
    mvr_auto_state state;
    mvr_skinning_path prior;     /* the rule's choice */
    mvr_skinning_path chosen;
    mvr_skinning_path candidates[2]; /* vertex, preskin */
    uint32_t samples[2];
    double cost_ms[2];
    double margin;
    uint32_t retunes;
} mvr_auto_skinning_choice;

struct mvr_frame_stats {
    mvr_view_path view_path;     /* the path that ran */
    uint32_t views;              /* enabled views rendered */
    uint32_t passes;             /* framebuffer passes (multiview chunks or loop views) */
    uint32_t multiview_passes;   /* passes through a multiview framebuffer (a chunk of one
                                    view takes a plain pass: same pixels, less work) */
    uint32_t draws;              /* objects drawn (an instanced draw counts each instance) */
    uint32_t draw_calls;         /* GL draw commands */
    uint32_t instanced_draw_calls; /* of those, instanced ones (more than one object) */
    uint32_t program_binds;
    uint32_t texture_binds;
    uint32_t ubo_range_binds;
    uint64_t upload_bytes;       /* view-independent: geometry, textures, materials, per-draw data */
    uint64_t view_upload_bytes;  /* per-view matrices */
    uint64_t compacted_bytes;    /* per-pass copies of the visible draws' blocks, where culling
                                    would otherwise split instanced runs */
    uint32_t programs_compiled;  /* variants compiled from source in this render */
    uint32_t program_cache_hits; /* variant lookups served by a program already built */
    uint32_t program_binary_loads;   /* variants linked from the binary cache */
    uint32_t program_binary_rejects; /* cache entries found corrupt, stale or refused (rebuilt) */
    mvr_depth_mode depth_mode;   /* the depth mode that ran (never AUTO) */
    mvr_transparency_order transparency_order; /* the policy that ran */
    uint32_t blend_diverged_chunks; /* multiview chunks whose views disagree on the blend order */
    uint32_t blend_fallback_passes; /* per-view blend passes after a multiview pass */
    mvr_material_path material_path; /* the material path that ran */
    uint32_t texture_groups;     /* texture arrays of the scene's batch plan (array path) */
    uint32_t culled;             /* summed over views: draws outside a view's frustum */
    uint32_t sanitized;          /* the scene's repaired degenerate values (mvr_scene_sanitized_count) */
    uint32_t samples;            /* the target's samples per pixel (1 = no multisampling) */
    mvr_anti_aliasing anti_aliasing; /* what ran: NONE, MSAA or SUPERSAMPLE */
    bool msaa_multiview;         /* multisampled multiview passes (else MSAA went view by view) */
    uint32_t resolves;           /* multisample resolves (one per view) and supersample resolve
                                    passes (one per chunk of views) */
    uint32_t supersample;        /* the target's samples per pixel side (1 = none) */
    /* Sub-passes drawn, summed over passes: [0] opaque, [1] alpha-masked,
     * [2] blended (transparent). A pass skips a list with nothing to draw in
     * it, state changes included: a scene without transparency runs no
     * blend sub-pass. */
    uint32_t sub_passes[3];
    uint32_t shadow_passes;      /* shadow map passes: 1 per frame (multiview, <= GL_MAX_VIEWS_OVR
                                    layers) whatever the view count; one per layer without multiview */
    uint32_t shadow_layers;      /* layers of the shadow map array in use (cascades + spot maps) */
    uint32_t shadow_draws;       /* caster objects drawn into the shadow maps */
    mvr_exposure_mode exposure_mode;
    double exposure_ev100;       /* the EV100 that ran (view 0's with per-view auto exposure;
                                    LINEAR: the EV100 whose exposure is that multiplier) */
    mvr_tone_map tone_mapper;
    uint32_t post_passes;        /* final full-screen passes (1 per multiview chunk, 1 per view on
                                    the loop path; 0 without an HDR frame) */
    uint32_t luminance_passes;   /* auto-exposure log-luminance passes */
    /* Environment prefiltering (view-independent: only in the render that
     * first meets an environment or its new pixels; 0 on every later frame
     * whatever the view count): passes drawn (one per cube level: the six
     * faces are six views of one multiview pass, else six passes), and
     * their time on the submitting thread with the GL finished (ms; 0 when
     * none ran). */
    uint32_t env_prefilter_passes;
    double env_prefilter_ms;
    uint32_t background_draws;   /* environment background draws (one per pass that drew one) */
    double cpu_ms;               /* submitting thread, render call */
    double gpu_ms;               /* timer queries; < 0 when not available */
    uint32_t images_downscaled;  /* scene images stored smaller than given: too large for the GL
                                    (mvr_oversized_image) */
    /* Skins and morph targets: joints posed this frame (summed over the
     * skins drawn), the path skinning ran on (AUTO when nothing is skinned
     * or morphed), morph targets with a non-zero weight summed over the
     * morphed draws (the only ones that cost work), the bytes of joint
     * matrices and weights sent this frame (once for all views), and the
     * transform feedback passes of the pre-skinning path. */
    uint32_t joints;
    mvr_skinning_path skinning_path;
    uint32_t morph_targets_active;
    uint64_t animation_upload_bytes;
    uint32_t preskin_passes;
    /* KHR_materials_transmission: views whose opaque colour was copied for
     * the transmissive draws (0 when nothing is transmissive), and the
     * bytes of the mip-mapped copy array */
    uint32_t transmission_copies;
    uint64_t transmission_bytes;
    /* Scene images the GL holds block-compressed as given (no RGBA8
     * decode), and scene images whose format the GL cannot sample, drawn
     * with their roles' neutral values (each warned about once per upload). */
    uint32_t images_compressed;
    uint32_t images_unsampleable;
    /* Extra outputs: the target's (mvr_target_desc.outputs) that were
     * drawn, and the outputs-only passes of blended draws (one per chunk
     * of views with blended draws; 0 without outputs). */
    uint32_t outputs;
    uint32_t output_blend_passes;
    /* Auto-exposure: the views whose luminance was measured (some lit
     * pixel; the others do not count) and the mean over them of each one's
     * average log2 luminance (before exposure), which the shared EV100
     * follows from (EV100 = it - log2(1.2 * exposure_key) - compensation,
     * clamped): what a caller that renders a view set in parts needs to
     * meter them all as one render would. 0 without auto-exposure. */
    uint32_t exposure_measured_views;
    double exposure_log2_luminance;
    mvr_auto_choice auto_choice; /* the view path's `auto` */
    mvr_auto_skinning_choice auto_skinning; /* the skinning path's `auto` */
    mvr_auto_material_choice auto_material; /* the material path's `auto` */
};

/* The supersampling resolve: box-filters linear RGBA float pixels (width x
 * height, rows bottom-up or top-down alike) by an integer factor into dst
 * (width / factor x height / factor), each output the mean of its
 * factor x factor samples. Width and height must be multiples of factor.
 * Average linear values only: sRGB-encoded ones would darken edges. */
mvr_result mvr_downsample_rgba32f(const float *src, uint32_t width, uint32_t height, uint32_t factor, float *dst);

/* Waits until the GPU has finished everything submitted so far (glFinish):
 * a frame's wall time ends here. */
mvr_result mvr_renderer_finish(mvr_renderer *renderer);

/* Stats of the last render (waits for its GPU timer result where there is one). */
void mvr_renderer_get_stats(mvr_renderer *renderer, mvr_frame_stats *out);

typedef struct mvr_pass_stats {
    uint32_t first_view, views;  /* the views (layers) the pass rendered */
    bool multiview;
    uint32_t draws, program_binds, texture_binds, ubo_range_binds;
    uint32_t texture_groups;     /* distinct texture arrays the pass sampled (array path) */
} mvr_pass_stats;

/* The shader variants a renderer has built, in build order: each is one
 * feature key (the scene's features, the path and the output) compiled with
 * #defines, so a scene without textures has no texturing code. */
typedef struct mvr_program_info {
    char name[64];               /* e.g. "mesh-mv2-f10021-l1.0.0" */
    bool mesh;                   /* mesh program (else the composite copy) */
    uint32_t features;           /* feature bits; mvr_program_feature_name names them */
    uint32_t num_views;          /* multiview views; 0 = loop path */
    uint32_t lights[3];          /* directional, point, spot (mesh) */
    bool from_binary_cache;
} mvr_program_info;

uint32_t mvr_renderer_program_count(const mvr_renderer *renderer);
bool mvr_renderer_get_program_info(const mvr_renderer *renderer, uint32_t index, mvr_program_info *out);
/* The name of one mesh feature bit ("BASE_COLOR_TEX", "NORMAL_TEX", ...);
 * NULL when the bit is not one. */
const char *mvr_program_feature_name(uint32_t bit);

/* Draws culled in view `view` of the last render (outside its frustum). */
uint32_t mvr_renderer_view_culled(const mvr_renderer *renderer, uint32_t view);

/* Stats of pass `index` of the last render (the first 256 passes); false past the end. */
bool mvr_renderer_get_pass_stats(const mvr_renderer *renderer, uint32_t index, mvr_pass_stats *out);

/* The frame plan of the last render as text (what `mvr render --plan`
 * prints): a summary line, then one line per pass record in order (view-
 * independent passes, each view pass with its sub-passes and resolve, the
 * supersampling resolve and post), each with its views, whether it runs, is
 * skipped or depends on the drawn data, and why. Writes at most size bytes,
 * NUL-terminated when size > 0 (buf may be NULL when size is 0); returns the
 * length of the whole text, as snprintf does. */
size_t mvr_renderer_format_plan(const mvr_renderer *renderer, char *buf, size_t size);

/* ------------------------------------------------------------------ asynchronous readback
 *
 * mvr_renderer_read_layer waits for the GPU and copies at once. A readback
 * instead queues the copy of some layers into a GL pixel buffer object and
 * a fence, and returns: the application renders the next views (into
 * another target) while the copy completes, asks whether it is ready
 * without blocking, and collects the pixels when it needs them. The bytes
 * are mvr_renderer_read_layer's (or mvr_renderer_read_output's for an extra
 * output), layer for layer. A readback keeps its
 * buffer from read to read (it grows, never shrinks), so a stream of reads
 * allocates nothing per frame. It belongs to the renderer it was created
 * with; destroying that renderer (or its context) releases its GL objects,
 * as it does a target's (its calls then fail; destroy frees it). */
typedef struct mvr_readback mvr_readback;

typedef struct mvr_read_desc {
    uint32_t first_layer;
    uint32_t layer_count;        /* 0 = every layer from first_layer on */
    mvr_readback_format format;  /* as mvr_renderer_read_layer's (the colour only) */
    /* MVR_OUTPUT_COLOR (0): the colour in `format`; another output (the
     * target must have it, mvr_target_desc.outputs): that output in its own
     * type, mvr_renderer_read_output's bytes layer for layer (`format` is
     * not used) */
    mvr_output output;
} mvr_read_desc;

mvr_result mvr_readback_create(mvr_renderer *renderer, mvr_readback **out);
/* Also drops a read not finished. NULL is ignored. */
void mvr_readback_destroy(mvr_readback *readback);
/* Queues the read of layers [first_layer, first_layer + layer_count) of the
 * target as it is now (after the renders issued so far; the target may be
 * rendered into again or destroyed before the read finishes). Refused while
 * the readback holds a read not yet finished. */
mvr_result mvr_renderer_begin_read(mvr_renderer *renderer, mvr_target *target, const mvr_read_desc *desc,
                                   mvr_readback *readback);
/* Whether the pending read has completed on the GPU, without waiting
 * (*ready false while it has not; a readback with no read pending fails). */
mvr_result mvr_renderer_read_ready(mvr_renderer *renderer, mvr_readback *readback, bool *ready);
/* Waits for the pending read if needed and copies it into dst: layer k of
 * the read at dst + k * mvr_readback_layer_size, rows bottom to top (GL
 * order), as mvr_renderer_read_layer writes one layer; size must be at least
 * mvr_readback_size. The readback is then free for the next read. */
mvr_result mvr_renderer_finish_read(mvr_renderer *renderer, mvr_readback *readback, void *dst, size_t size);
/* Bytes of one layer and of the whole pending read (0 when none is pending),
 * and its layers. */
size_t mvr_readback_layer_size(const mvr_readback *readback);
size_t mvr_readback_size(const mvr_readback *readback);
uint32_t mvr_readback_layer_count(const mvr_readback *readback);


/* ------------------------------------------------------------------ framing
 *
 * How a scene is shown by default: views laid out around its bounding
 * sphere, for files without cameras (or when the caller wants a layout
 * instead of the file's camera); views from a camera of the file; the
 * exposure its lights call for.
 */
typedef enum mvr_view_layout {
    MVR_LAYOUT_STEREO = 0,       /* a row of eyes ipd apart in front of the scene, parallel axes */
    MVR_LAYOUT_CUBE,             /* six 90-degree views from the center */
    MVR_LAYOUT_RING,             /* N cameras in a horizontal circle, looking at the center */
    MVR_LAYOUT_GRID,             /* a light-field grid of cameras on a plane, looking at the center */
    MVR_LAYOUT_SPHERE,           /* N cameras spread evenly over a sphere (a Fibonacci lattice), looking at
                                    the center: the capture of a multi-view reconstruction dataset */
    MVR_LAYOUT_ORBIT             /* a turntable: rings of cameras at rising elevations, looking at the center */
} mvr_view_layout;

typedef struct mvr_framing_desc {
    mvr_view_layout layout;
    uint32_t views;              /* 0 = the layout's own (stereo 2, cube 6, ring 8, grid 9, sphere 50,
                                    orbit 24) */
    double ipd;                  /* stereo: scene units between eyes; 0 = mvr_stereo_default_ipd of the framing distance */
    double aspect;               /* width / height of the layers; 0 = 1 */
    uint32_t rows;               /* orbit: rings (0 = 3), the views shared out among them (the first
                                    rings take the remainder), each ring's azimuths staggered by half a step */
    double elevation_min, elevation_max; /* orbit, radians in (-pi/2, pi/2): the lowest and the highest
                                    ring, evenly between (both 0 = -15 and 60 degrees; one ring: their mean) */
} mvr_framing_desc;

/* The eye separation for a subject viewing_distance away: 1/30 of it (the
 * stereographers' 1/30 rule), so a 2 cm model and a 100 m scene get the same
 * depth impression; a subject framed 1.9 m away gets 0.064, a human IPD. */
double mvr_stereo_default_ipd(double viewing_distance);

const char *mvr_view_layout_name(mvr_view_layout layout);
mvr_result mvr_view_set_frame_scene(const mvr_scene *scene, const mvr_framing_desc *desc, mvr_view_set **out,
                                    mvr_error *out_error);

/* Views from a camera node of the scene (a file's camera): its world pose
 * and projection (mvr_scene_camera_view) as the centre of a row of `views`
 * eyes (0 = 2, a stereo pair; 1 = the camera itself) along the camera's x
 * axis, ipd apart, with parallel axes and the camera's projection each.
 * ipd 0 = mvr_stereo_default_ipd of the camera's distance to the centre of
 * the scene's bounding sphere (the project's stereo rule, the 1/30 rule,
 * as mvr_view_set_frame_scene applies it to its framing distance); NaN,
 * infinite or negative is refused. The view set's origin is the camera. */
mvr_result mvr_view_set_from_camera(const mvr_scene *scene, mvr_node_id camera_node, uint32_t views, double ipd,
                                    mvr_view_set **out, mvr_error *out_error);

/* The exposure a scene is shown with by default (mvr render and mvr-viewer
 * both use it): lights in physical units (mvr_scene_lights_physical: a sun
 * of thousands of lux, as exporters write KHR_lights_punctual) give
 * MVR_EXPOSURE_AUTO with MVR_TONE_MAP_KHR_PBR_NEUTRAL, as a camera would
 * expose them; any other scene MVR_EXPOSURE_LINEAR (the light values as
 * authored, `exposure` as the multiplier), with no tone map, or, when
 * desc->environment is set (set it first), Khronos PBR Neutral (the
 * identity below 0.76, highlights rolled off instead of clipped: the
 * Khronos glTF Sample Viewer's default). Writes only exposure_mode and
 * tone_map: an application whose user chose an exposure or a tone map
 * applies that choice after this call. */
void mvr_render_desc_choose_exposure(const mvr_scene *scene, mvr_render_desc *desc);

/* ------------------------------------------------------------------ demo scenes
 *
 * Scenes generated in code (no files), with views to match: the default for
 * `mvr render` and the benchmark's workload.
 *   stereo  a small room with varied materials and lights, eyes 64 mm apart
 *   cube    the room from its center: six 90-degree views (cube-map faces)
 *   city    a grid of thousands of buildings over 64+ textured materials
 *   ring    N cameras in a circle around an object
 */
typedef struct mvr_demo_desc {
    uint32_t views;              /* 0 = the demo's own count (stereo 2, cube 6, city 2, ring 8) */
    uint32_t width, height;      /* layer size, for aspect ratios; 0 = square */
    mvr_logger logger;
} mvr_demo_desc;

/* The i-th demo's name; NULL past the last. */
const char *mvr_demo_name(uint32_t index);
mvr_result mvr_demo_create(const char *name, const mvr_demo_desc *desc, mvr_scene **out_scene,
                           mvr_view_set **out_views, mvr_error *out_error);

#ifdef __cplusplus
}
#endif
#endif /* MVR_H */
