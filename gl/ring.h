/* The uniform ring (gl/ring.c). */
#ifndef MVR_RING_H
#define MVR_RING_H

#include "context_internal.h"

/* Uniform data of one frame goes into one segment of a ring buffer; a fence
 * per segment keeps the CPU from overwriting what the GPU still reads. */
#define MVR_RING_SEGMENTS 3
typedef struct mvr_ring {
    GLuint buffer;
    GLsizeiptr static_size;      /* a region before the segments: per-draw blocks and lights,
                                    re-sent only when they change (same buffer as the views:
                                    binds of another buffer's ranges cost more in Mesa) */
    GLsizeiptr segment_size;
    uint32_t current;
    GLsync fences[MVR_RING_SEGMENTS];
} mvr_ring;

/* Room for `size` bytes of this frame's uniform data; the offset is
 * aligned to the GL's uniform buffer offset alignment. Sets *reallocated when
 * the buffer was replaced (the static region's contents are then gone). */
mvr_result mvr_ring_begin_frame(mvr_renderer *r, GLsizeiptr size, bool *reallocated);
/* Makes the static region at least `size` bytes (reallocating the ring;
 * *reallocated says so). */
mvr_result mvr_ring_reserve_static(mvr_renderer *r, GLsizeiptr size, bool *reallocated);
void mvr_ring_end_frame(mvr_renderer *r);
/* Deletes the buffer and its fences; the ring is empty after. */
void mvr_ring_release(mvr_renderer *r);

#endif
