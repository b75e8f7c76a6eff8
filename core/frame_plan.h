/*
 * The frame plan, backend-free: what one render does, as an ordered list of
 * pass records built from the frame's state (view set, target, caps that
 * matter, options). View-independent passes come first (environment
 * prefilter, the frame's uploads, shadow maps), then per chunk of views one
 * view pass with its sub-passes (opaque, mask, background, blend, per-view
 * blend fallback) and its MSAA resolve, then the frame's final passes
 * (supersampling resolve or post). Each record names its views and why it
 * runs or is skipped; the GL backend (gl/passes.c) executes records, one
 * function per kind, and skips what the plan skips.
 *
 * Two decisions stay with the executor because they read the drawn data:
 * a sub-pass with nothing visible in its views sets no state, and where the
 * transparency policy is auto a multiview chunk blends in the shared order
 * unless its views' orders diverge (records MVR_PLAN_IF_ORDERS_AGREE and
 * MVR_PLAN_IF_ORDERS_DIVERGE).
 */
#ifndef MVR_FRAME_PLAN_H
#define MVR_FRAME_PLAN_H

#include "frame.h"
#include "view_set.h"

/* A pass's views: consecutive layers sharing one viewport (a loop-path
 * chunk is one view). */
typedef struct mvr_view_chunk {
    uint32_t base, count;
    mvr_viewport viewport;
} mvr_view_chunk;

/* How the GL draws multisampled multiview passes. */
typedef enum mvr_msaa_multiview_mode {
    MVR_MSAA_MV_NONE = 0,        /* not at all: MSAA targets take the loop path */
    MVR_MSAA_MV_ARRAY,           /* into a multisampled array, resolved layer by layer */
    MVR_MSAA_MV_RENDER_TO_TEXTURE /* the GL resolves (multisampled render to texture) */
} mvr_msaa_multiview_mode;

typedef enum mvr_plan_kind {
    MVR_PLAN_ENV_PREFILTER = 0,  /* once per new environment */
    MVR_PLAN_UPLOAD,             /* the frame's uniform data and state (joints and weights included) */
    MVR_PLAN_PRESKIN,            /* skinning and morphing once for every view (transform feedback) */
    MVR_PLAN_SHADOW_MAPS,        /* once, shared by every view */
    MVR_PLAN_VIEW_PASS,          /* one chunk: its framebuffer, viewport, clear and bindings */
    MVR_PLAN_OPAQUE,             /* sub-passes of the chunk's view pass */
    MVR_PLAN_MASK,
    MVR_PLAN_BACKGROUND,
    MVR_PLAN_BLEND,
    MVR_PLAN_BLEND_VIEW,         /* one view's own blend pass (per-view order) */
    MVR_PLAN_MSAA_RESOLVE,       /* the chunk's samples into its layers */
    MVR_PLAN_SUPERSAMPLE_RESOLVE,
    MVR_PLAN_POST,               /* exposure, tone map, encode of an HDR frame */
    MVR_PLAN_TRANSMISSION,       /* sub-pass: the chunk's opaque views into the mip-mapped array
                                    transmissive draws sample (before the blend sub-pass) */
    MVR_PLAN_OUTPUTS_BLEND,      /* one chunk's blended draws into the extra outputs alone (after
                                    every colour record: nothing the colour reads sees its depth) */
    MVR_PLAN_KIND_COUNT
} mvr_plan_kind;

typedef enum mvr_plan_when {
    MVR_PLAN_RUN = 0,
    MVR_PLAN_SKIP,
    MVR_PLAN_IF_ORDERS_AGREE,    /* the chunk's views agree on the blend order */
    MVR_PLAN_IF_ORDERS_DIVERGE
} mvr_plan_when;

/* A view pass's transparency: the shared order, per view where the views'
 * orders diverge, or per view always. */
typedef enum mvr_plan_blend_split {
    MVR_PLAN_BLEND_SHARED = 0,
    MVR_PLAN_BLEND_SPLIT_IF_DIVERGED,
    MVR_PLAN_BLEND_SPLIT
} mvr_plan_blend_split;

#define MVR_PLAN_NO_CHUNK UINT32_MAX

typedef struct mvr_plan_record {
    mvr_plan_kind kind;
    mvr_plan_when when;
    uint32_t chunk;              /* index in the plan's chunks, or MVR_PLAN_NO_CHUNK */
    uint32_t first_view, views;  /* the views (target layers) it draws, reads or serves */
    bool multiview;              /* one multiview pass over the views (else one layer at a time) */
    bool msaa;                   /* view pass: multisampled; resolve: from a multisampled array */
    bool depth;                  /* MSAA resolve: depth too (an HDR frame's metering reads it) */
    bool ends_chunk;             /* the chunk's last record: its stats close after it */
    mvr_plan_blend_split blend;  /* view pass */
    uint32_t draws;              /* sub-passes: draws listed; shadow maps: layers */
    const char *why;             /* why it runs or is skipped (static text) */
} mvr_plan_record;

/* What the plan is built from. */
typedef struct mvr_frame_plan_input {
    const mvr_view_set *views;
    uint32_t width, height;      /* the target's layer size */
    uint32_t samples;            /* > 1: multisampled */
    uint32_t factor;             /* supersampling: views drawn factor times the layer size (1 = none) */
    bool supersampled;           /* views drawn into the target's own float array (already HDR) */
    bool unorm8;                 /* an 8-bit sRGB-encoded target (RGBA8): something must encode */
    bool post;                   /* tone mapping, physical exposure or dithering: an HDR frame */
    uint32_t max_views;          /* GL_MAX_VIEWS_OVR (0 without multiview) */
    mvr_msaa_multiview_mode msaa_multiview;
    mvr_view_path path;          /* MULTIVIEW or LOOP (auto already resolved) */
    mvr_transparency_order blend_policy;
    bool background;             /* an environment background (not the clear color) */
    bool environment;            /* image-based lighting this frame */
    bool environment_new;        /* ... from an environment not yet prefiltered */
    uint32_t shadow_layers;      /* layers of this frame's shadow plan */
    uint32_t deforms;            /* skinned or morphed draws (0: no pre-skinning record) */
    bool preskin;                /* ... deformed on the pre-skinning path */
    bool deforms_moved;          /* ... whose joints or weights changed since the last capture */
    uint32_t draws[MVR_PASS_KIND_COUNT]; /* the frame's opaque, mask and blend lists */
    uint32_t transmissive;       /* of the blend list: draws that sample the opaque views */
    bool outputs;                /* the target has extra outputs (depth, normals, IDs) */
} mvr_frame_plan_input;

typedef struct mvr_frame_plan {
    mvr_plan_record *records;
    uint32_t count, cap;
    mvr_view_chunk *chunks;
    uint32_t chunk_count, chunk_cap;
    uint32_t views;              /* in the view set */
    uint32_t width, height, samples, factor;
    mvr_view_path path;          /* the path that runs */
    const char *path_why;
    bool multiview;              /* path == MULTIVIEW */
    bool msaa, msaa_multiview;   /* multisampled; in multiview passes */
    bool post, hdr_frame;        /* a post pass; views drawn into a half-float array */
    bool encode_in_mesh;         /* the mesh programs encode sRGB (8-bit target, nothing after) */
    uint32_t max_views;          /* views one multiview pass may hold */
} mvr_frame_plan;

/* Whether multiview passes can draw a frame of `samples` samples per pixel
 * (the plan's rule; auto's tuner asks before the frame): multisampling needs
 * multisampled multiview and no post pass, and transmission (which reads the
 * opaque views mid-pass) storage that is not resolved only at the pass's end. */
bool mvr_frame_plan_multiview_drawable(uint32_t samples, bool post, mvr_msaa_multiview_mode mode, bool transmissive);

/* Builds the plan (reusing its memory). Fails only when out of memory. */
mvr_result mvr_frame_plan_build(mvr_frame_plan *plan, const mvr_frame_plan_input *in);
void mvr_frame_plan_free(mvr_frame_plan *plan);

const char *mvr_plan_kind_name(mvr_plan_kind kind);

/* The plan as text, one line a record after a summary line; writes at most
 * size bytes (NUL-terminated when size > 0) and returns the length the whole
 * text needs, as snprintf does. */
size_t mvr_frame_plan_format(const mvr_frame_plan *plan, char *buf, size_t size);

#endif
