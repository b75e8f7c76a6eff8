/* Skinning and morphing (gl/skinning.c): the vertex or pre-skinning path. */
#ifndef MVR_SKINNING_H
#define MVR_SKINNING_H

#include "context_internal.h"
#include "frame.h"

/* Skins and morph targets on the GPU (gl/skinning.c): the morph deltas
 * (once per scene geometry), the frame's deformation texels (joints and
 * weights, once per frame for every view), and on the pre-skinning path
 * one captured vertex buffer per deform. */
typedef struct mvr_preskin_buffer {
    GLuint buffer, vao;
    uint32_t primitive;          /* the primitive whose vertices it holds (MVR_NO_INDEX: none) */
    uint32_t vertices;
} mvr_preskin_buffer;

typedef struct mvr_skinning {
    mvr_skinning_path requested;  /* the renderer's setting (AUTO allowed) */
    mvr_skinning_path path;       /* this frame's: VERTEX or PRESKIN */
    mvr_skinning_path tuned;      /* auto's tuner's choice for this frame (AUTO: the rule's) */
    GLuint deltas;                /* RGBA32F, rows of 2^MVR_DEFORM_WIDTH_LOG2 texels */
    uint64_t deltas_geometry;     /* the geometry version they are of (0: none) */
    GLuint data;                  /* RGBA32F, this frame's joints and weights */
    uint32_t data_rows;           /* allocated */
    mvr_preskin_buffer *buffers;  /* per frame deform (pre-skinning path) */
    uint32_t buffer_count, buffer_cap;
    uint64_t captured_key;        /* the frame key the buffers hold (0: stale) */
    /* a complete 1x1 framebuffer bound during the capture: a draw with the
     * rasterizer off still fails without one (GL_INVALID_FRAMEBUFFER_OPERATION
     * on surfaceless contexts, which have no default framebuffer) */
    GLuint capture_fbo, capture_color;
} mvr_skinning;

/* The morph deltas of a scene's geometry (after its upload);
 * this frame's path, deformation texels and, on the pre-skinning path, the
 * capture pass (frame_changed: the frame was rebuilt, so joints or weights
 * may have moved; nothing is sent or captured otherwise); the vertex array
 * a draw of a deform uses (0: the primitive's own). */
mvr_result mvr_skinning_sync_scene(mvr_renderer *r, const mvr_scene *scene);
mvr_skinning_path mvr_skinning_choose(const mvr_renderer *r, const mvr_scene *scene, uint32_t views);
/* auto's rule (the tuner's prior): pre-skinning above one view */
mvr_skinning_path mvr_skinning_rule(uint32_t views);
mvr_result mvr_skinning_frame(mvr_renderer *r, bool frame_changed);
mvr_result mvr_skinning_capture(mvr_renderer *r);
GLuint mvr_skinning_vao(const mvr_renderer *r, const mvr_draw *d);
void mvr_skinning_release(mvr_renderer *r);

#endif
