/* The uniform ring: one buffer, a static region and a segment per frame
 * in flight (gl/ring.h). */
#include "errors.h"
#include "renderer.h"
#include "ring.h"

/* Replaces the ring buffer with one of the given region sizes. The old
 * buffer may still be read by queued draws; GL keeps it alive until they
 * finish, so deleting it here is safe. On failure the ring is empty. */
static mvr_result ring_allocate(mvr_renderer *r, GLsizeiptr static_size, GLsizeiptr segment_size)
{
    const mvr_gl_api_table *gl = r->gl;
    mvr_ring *ring = &r->ring;
    for (int i = 0; i < MVR_RING_SEGMENTS; ++i) {
        if (ring->fences[i])
            gl->DeleteSync(ring->fences[i]);
        ring->fences[i] = 0;
    }
    mvr_gl_delete(r, MVR_GL_BUFFER, &ring->buffer);
    r->frame_key.valid = false; /* the static region is empty now */
    GLsizeiptr total = static_size + segment_size * MVR_RING_SEGMENTS;
    gl->GenBuffers(1, &ring->buffer);
    gl->BindBuffer(GL_UNIFORM_BUFFER, ring->buffer);
    gl->BufferData(GL_UNIFORM_BUFFER, total, NULL, GL_DYNAMIC_DRAW);
    mvr_result res = mvr_gl_check_alloc(r, "uniform ring buffer (%lld bytes)", (long long)total);
    if (res != MVR_OK) {
        mvr_gl_delete(r, MVR_GL_BUFFER, &ring->buffer);
        ring->static_size = ring->segment_size = 0;
        return res;
    }
    ring->static_size = static_size;
    ring->segment_size = segment_size;
    ring->current = 0;
    return MVR_OK;
}

static GLsizeiptr grown(GLsizeiptr have, GLsizeiptr need)
{
    GLsizeiptr v = have ? have : 64 * 1024;
    while (v < need)
        v *= 2;
    return v;
}

mvr_result mvr_ring_reserve_static(mvr_renderer *r, GLsizeiptr size, bool *reallocated)
{
    *reallocated = false;
    if (r->ring.buffer && size <= r->ring.static_size)
        return MVR_OK;
    *reallocated = true;
    return ring_allocate(r, grown(r->ring.static_size, size), r->ring.segment_size ? r->ring.segment_size : 64 * 1024);
}

mvr_result mvr_ring_begin_frame(mvr_renderer *r, GLsizeiptr size, bool *reallocated)
{
    const mvr_gl_api_table *gl = r->gl;
    mvr_ring *ring = &r->ring;
    *reallocated = false;
    if (!ring->buffer || size > ring->segment_size) {
        mvr_result res = ring_allocate(r, ring->static_size, grown(ring->segment_size, size));
        if (res != MVR_OK)
            return res;
        *reallocated = true;
    } else {
        ring->current = (ring->current + 1) % MVR_RING_SEGMENTS;
    }
    GLsync fence = ring->fences[ring->current];
    if (fence) {
        /* the GPU may still read this segment from three frames ago */
        gl->ClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, (GLuint64)10 * 1000 * 1000 * 1000);
        gl->DeleteSync(fence);
        ring->fences[ring->current] = 0;
    }
    gl->BindBuffer(GL_UNIFORM_BUFFER, ring->buffer);
    return MVR_OK;
}

void mvr_ring_end_frame(mvr_renderer *r)
{
    r->ring.fences[r->ring.current] = r->gl->FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

void mvr_ring_release(mvr_renderer *r)
{
    for (int i = 0; i < MVR_RING_SEGMENTS; ++i) {
        if (r->ctx)
            mvr_context_delete_sync(r->ctx, r->ring.fences[i]);
        r->ring.fences[i] = 0;
    }
    mvr_gl_delete(r, MVR_GL_BUFFER, &r->ring.buffer);
    r->ring.static_size = r->ring.segment_size = 0;
}
