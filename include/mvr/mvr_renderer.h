/*
 * mvr: renderers: the paths and switches a renderer is created
 * with (overrides, tuning), lifetimes, and what one render is asked for
 * (shadows, exposure, tone mapping, background).
 *
 * Part of the public C API; include <mvr/mvr.h>, whose conventions apply.
 */
#ifndef MVR_RENDERER_API_H
#define MVR_RENDERER_API_H

#include "mvr/mvr_context.h"
#include "mvr/mvr_environment.h"
#include "mvr/mvr_scene.h"
#include "mvr/mvr_views.h"

#ifdef __cplusplus
extern "C" {
#endif

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

/* The online tuner behind `auto` (the view path, then the material path,
 * then the skinning path): the first frames after a change of inputs (view
 * count, target size, the scene's draw count or the draws the views see
 * after culling by more than a factor of 2) run the candidates in turns of
 * two frames, the incumbent first (the choice remembered for these inputs,
 * else the rule's: the prior): the first frame of a turn follows a switch
 * (and warms a candidate up: program compiles, uploads) and is not
 * measured, the second is (the frame's cost: the larger of its
 * submitting-thread CPU time and its GPU time from timestamp queries, taken
 * outside multiview framebuffers; CPU time alone where the GL has no timer).
 * At least 3 measured frames each; where the estimates (the mean of the
 * cheaper half of each path's samples: one slow frame never decides) are
 * then within 10% of each other, up to 9 each until they part. The other
 * path replaces the incumbent only when cheaper by more than 3% (5% against
 * a remembered choice, over the runs it remembers). 12 frames per decision
 * and change where the paths differ clearly, at most 36 where they are
 * close, half of them on the other path; settled frames are not measured.
 * One decision is measured at a time, the later ones keyed on the earlier
 * ones' choices (the material path is measured on the view path settled),
 * running their own settled or remembered choice, or prior, meanwhile.
 * With a program_cache_dir, settled choices are remembered there (one small
 * authenticated file per decision, keyed by the scene's content, views,
 * target size, format and outputs, the settings that change the work and
 * the GL's renderer and version), so a later renderer or process starts on
 * them; an entry that does not verify is ignored with a warning. While the
 * material path is measured both representations of the
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
    /* MVR_ANISOTROPIC=on|off: on filters material textures whose sampler is
     * linear and mipmapped anisotropically (up to 16x) where the GL has
     * EXT_texture_filter_anisotropic, as the Khronos Sample Renderer does
     * (sharper at grazing angles: docs/peers.md). Off (trilinear) is the
     * default: Mesa's llvmpipe returns black where a triangle's UVs are
     * constant (zero derivatives) under anisotropic filtering */
    mvr_override_switch anisotropic;
} mvr_renderer_overrides;

/* The one place mvr reads the environment, and only when an application
 * calls it: fills *out (all of it; unset or empty variables = no override)
 * from MVR_VIEW_PATH, MVR_MATERIAL_PATH, MVR_DEPTH, MVR_CULLING,
 * MVR_INSTANCING, MVR_MSAA_MULTIVIEW, MVR_FORCE_FEATURES,
 * MVR_UBO_ALIGNMENT, MVR_SKINNING_PATH, MVR_DISABLE_FEATURES, MVR_TUNING and
 * MVR_ANISOTROPIC (values as mvr_renderer_overrides lists them). A value
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
     * offers no binary format the cache is silently unused. auto's tuner
     * keeps its settled choices here too (mvr_tuning). */
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

/* ---- rendering a frame */

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
    float clear_color[4];        /* linear RGBA, a display colour: written as given, never exposed or tone mapped */
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

/* Waits until the GPU has finished everything submitted so far (glFinish):
 * a frame's wall time ends here. */
mvr_result mvr_renderer_finish(mvr_renderer *renderer);

#ifdef __cplusplus
}
#endif
#endif /* MVR_RENDERER_API_H */
