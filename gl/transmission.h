/* Transmission (gl/transmission.c): the opaque views transmissive draws sample. */
#ifndef MVR_TRANSMISSION_H
#define MVR_TRANSMISSION_H

#include "frame_plan.h"
#include "program_cache.h"

typedef struct mvr_transmission {
    GLuint texture, fbo, sampler;
    GLenum format;
    uint32_t width, height, layers;
    float rect[4];               /* the chunk's viewport in the array (0..1) */
    float lod;                   /* log2 of its width in texels */
    int32_t base;                /* the chunk's first view in its view block */
    uint64_t serial;             /* one per copy */
} mvr_transmission;

/* The chunk of rec's opaque views into the transmission
 * array (its mips generated), the draw framebuffer resume_fbo bound again
 * after; loop_msaa_fbo: the multisampled renderbuffers a one-view MSAA
 * chunk draws into. block_base: the first view of the chunk's view block. */
mvr_result mvr_transmission_copy(mvr_renderer *r, mvr_target *t, const mvr_frame_plan *plan,
                                 const mvr_plan_record *rec, int32_t block_base, GLuint loop_msaa_fbo,
                                 GLuint resume_fbo);
/* A transmissive program's uniforms for the last copy. */
void mvr_transmission_set_uniforms(mvr_renderer *r, mvr_program_entry *e);
void mvr_transmission_release(mvr_renderer *r);

#endif
