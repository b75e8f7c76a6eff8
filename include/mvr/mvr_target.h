/*
 * mvr: targets (the layered images a render draws into), their
 * extra outputs, and reading them back (at once or asynchronously).
 *
 * Part of the public C API; include <mvr/mvr.h>, whose conventions apply.
 */
#ifndef MVR_TARGET_API_H
#define MVR_TARGET_API_H

#include "mvr/mvr_renderer.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ targets */

typedef enum mvr_color_format {
    MVR_COLOR_FORMAT_DEFAULT = 0, /* SRGB8_ALPHA8: linear lighting, sRGB-encoded storage */
    MVR_COLOR_FORMAT_RGBA8,       /* UNORM; the shader writes the exact sRGB encoding */
    MVR_COLOR_FORMAT_RGBA16F,     /* linear */
    MVR_COLOR_FORMAT_RGBA32F      /* linear */
} mvr_color_format;
const char *mvr_color_format_name(mvr_color_format format);

/* Anti-aliasing of a target. */
typedef enum mvr_anti_aliasing {
    /* what samples and supersample ask (1 = none); both 0: AUTO, or none
     * where extra outputs are asked (they stay exact, never averaged) */
    MVR_ANTI_ALIASING_DEFAULT = 0,
    MVR_ANTI_ALIASING_NONE,
    MVR_ANTI_ALIASING_MSAA,        /* samples per pixel (0 = 4) */
    MVR_ANTI_ALIASING_SUPERSAMPLE, /* supersample per side (0 = 2) */
    /* 4x MSAA: in the multiview passes where the GL attaches multisampled
     * arrays with multiview (or has OVR_multiview_multisampled_render_to_
     * texture), else view by view on the loop path; 2x2 supersampling where
     * the format cannot be multisampled 4 times. Measured by `mvr bench`
     * (docs/benchmarks.md): per-view 4x MSAA costs 1.9-2.3x the frame time
     * without AA, 2x2 supersampling 3.0-3.6x, on every demo; on stereo and
     * city 4x MSAA is cheaper than 2x2 supersampling and on city closer to
     * the reference (RMSE 0.017 against 0.025; none 0.051): the default.
     * An HDR frame tone maps each sample before the average (GLES 3.2). */
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
    /* Multisampling: samples per pixel (1 = none; 0 = the default, see
     * MVR_ANTI_ALIASING_DEFAULT). Where the GL has
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
     * is not averaged; the default then draws without anti-aliasing. Needs float colour buffers (OpenGL ES 3.2, or
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

/* The supersampling resolve: box-filters linear RGBA float pixels (width x
 * height, rows bottom-up or top-down alike) by an integer factor into dst
 * (width / factor x height / factor), each output the mean of its
 * factor x factor samples. Width and height must be multiples of factor.
 * Average linear values only: sRGB-encoded ones would darken edges. */
mvr_result mvr_downsample_rgba32f(const float *src, uint32_t width, uint32_t height, uint32_t factor, float *dst);

/* ------------------------------------------------------------------ reading back */

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

#ifdef __cplusplus
}
#endif
#endif /* MVR_TARGET_API_H */
