/* Targets (gl/targets.c): their GL objects and the framebuffers the passes draw into. */
#ifndef MVR_TARGETS_H
#define MVR_TARGETS_H

#include "context_internal.h"
#include "frame_plan.h"

typedef struct mvr_fbo_entry {
    uint32_t base, count;        /* layers; count 0 = a single-layer (non-multiview) FBO */
    bool output;                 /* the color array alone (supersampled targets: the resolve's) */
    bool msaa;                   /* multisampled multiview (count > 0), or one multisampled layer to read */
    uint8_t aux;                 /* 0, or MVR_FBO_HDR / MVR_FBO_LUMINANCE / MVR_FBO_LUMINANCE_TOP */
    GLuint fbo;
} mvr_fbo_entry;

/* The extra outputs' arrays of a target: colour attachment k + 1 and the
 * shader's location k + 1 (core/shader_gen.h MVR_SHADER_OUT_*). */
enum { MVR_TARGET_OUTPUT_GEOMETRY = 0, MVR_TARGET_OUTPUT_NORMAL, MVR_TARGET_OUTPUT_IDS, MVR_TARGET_OUTPUT_ARRAYS };

struct mvr_target {
    mvr_renderer *renderer;      /* NULL once the renderer (or its context) is destroyed */
    mvr_target *next;            /* in renderer->targets */
    mvr_target_desc desc;
    GLenum internal_format;
    GLuint color, depth;
    bool owns_color;
    mvr_fbo_entry *fbos;
    uint32_t fbo_count, fbo_cap;
    /* multisampling (desc.samples > 1): one view's color and depth, resolved
     * into its layer after its pass */
    GLuint msaa_fbo, msaa_color, msaa_depth;
    /* multisampled multiview, where the GL has it: the GL resolves
     * (render to texture), or these arrays are resolved layer by layer */
    mvr_msaa_multiview_mode msaa_multiview; /* (core/frame_plan.h) */
    GLuint msaa_array_color, msaa_array_depth;
    mvr_anti_aliasing anti_aliasing; /* resolved: NONE, MSAA or SUPERSAMPLE */
    /* HDR frames (a post pass): views draw into hdr_color (RGBA16F, or the
     * supersampled array, already float); auto-exposure reduces log2
     * luminance through lum's mip levels. Made on first use. */
    bool hdr_frame;
    GLuint hdr_color;
    GLuint msaa_hdr_color, msaa_hdr_fbo; /* multisampled HDR frames */
    /* where the GL samples multisampled arrays (GLES 3.2, GL 4.2): every
     * view's samples kept, one layer each (drawn view by view, resolved
     * for metering, read per sample by the post pass); else msaa_hdr_color */
    GLuint msaa_hdr_array;
    GLuint lum;
    uint32_t lum_levels;
    float post_clear[4];         /* the post pass's clear colour, as written (encoded for RGBA8) */
    double last_auto_exposure;   /* pre-exposure of the next auto-exposed frame (0 = none yet) */
    /* supersampling (desc.supersample > 1): views are drawn into these (N
     * times the size, linear float) and resolved into the color array */
    GLuint ss_color;
    GLenum ss_format;
    /* extra outputs (desc.outputs): the arrays behind colour attachments
     * 1..3 of every view framebuffer (0 = not asked for) */
    GLuint output_arrays[MVR_TARGET_OUTPUT_ARRAYS];
    uint32_t shader_outputs;     /* MVR_SHADER_OUT_GEOMETRY / _NORMAL / _IDS they give */
};

/* A framebuffer for layers [base, base + count) (multiview when
 * count > 0) or one layer (count = 0), created on first use: the one views
 * are drawn into (color and depth; a supersampled target's own arrays), or
 * with output the color array alone (what is read back, and what a
 * supersample resolve writes). */
mvr_result mvr_target_framebuffer(mvr_target *t, uint32_t base, uint32_t count, GLuint *out);
mvr_result mvr_target_output_framebuffer(mvr_target *t, uint32_t base, uint32_t count, GLuint *out);
enum { MVR_FBO_HDR = 1, MVR_FBO_LUMINANCE = 2, MVR_FBO_LUMINANCE_TOP = 3, MVR_FBO_MSAA_HDR = 4,
       MVR_FBO_OUTPUT_ARRAY = 5 /* + k */ };
/* Multisampled HDR frames: the framebuffer view `layer` is drawn into
 * (layer of msaa_hdr_array, or the one renderbuffer). */
mvr_result mvr_target_msaa_hdr_framebuffer(mvr_target *t, uint32_t layer, GLuint *out);
/* Extra outputs: one layer of output array k alone (what read_output reads). */
mvr_result mvr_target_output_array_framebuffer(mvr_target *t, uint32_t k, uint32_t layer, GLuint *out);
/* Which colour attachments of the bound view framebuffer are drawn: the
 * colour (MVR_DRAW_COLOR), the extra outputs (MVR_DRAW_OUTPUTS) or both
 * (the framebuffer's own setting, which every sub-pass leaves behind). */
enum { MVR_DRAW_COLOR = 1, MVR_DRAW_OUTPUTS = 2, MVR_DRAW_ALL = 3 };
void mvr_target_draw_buffers(mvr_target *t, int which);
/* HDR frames: makes hdr_color (and the multisampled HDR renderbuffer). */
mvr_result mvr_target_ensure_hdr(mvr_target *t);
/* Auto-exposure: the log-luminance array; framebuffers of its level 0
 * (layers [base, base + count), multiview when count > 0) or of one layer's
 * last level (MVR_FBO_LUMINANCE_TOP, count 0). */
mvr_result mvr_target_luminance_framebuffer(mvr_target *t, int kind, uint32_t base, uint32_t count, GLuint *out);

/* Multisampled multiview (t->msaa_multiview): the framebuffer views
 * [base, base + count) are drawn into (count > 1), or (count 0) one
 * multisampled layer to resolve from (the array mode). */
mvr_result mvr_target_msaa_framebuffer(mvr_target *t, uint32_t base, uint32_t count, GLuint *out);
/* Releases the target's GL objects (mvr_gl_delete) and keeps its memory. */
void mvr_target_release_gl(mvr_target *t);
/* The size views are drawn at: the layer size times the supersample factor. */
uint32_t mvr_target_factor(const mvr_target *t);

#endif
