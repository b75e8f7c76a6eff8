/* Asynchronous readback (mvr.h, "asynchronous readback"): glReadPixels of
 * each layer into one pixel buffer object, a fence after them, and the
 * copy out of the mapped buffer when the caller asks for the pixels. What a
 * read takes from a target (which attachment, which GL format and type,
 * how many bytes, what conversion) is decided by read_layout alone: the
 * colour in a format, or an extra output (depth, normals, IDs ...) from its
 * own array. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errors.h"
#include "outputs.h"
#include "readback_async.h"
#include "renderer.h"
#include "targets.h"

/* How the bytes GL reads become the bytes the caller gets. */
typedef enum read_convert {
    READ_AS_IS = 0,
    READ_FLOAT_TO_BYTES,         /* a float target read as RGBA8 (GLES reads float buffers as FLOAT only) */
    READ_BYTES_TO_FLOAT,         /* an 8-bit target read as RGBA32F: normalized */
    READ_CHANNELS                /* an extra output: its channels of the 4 x 32-bit texels read */
} read_convert;

typedef struct read_layout {
    GLenum attachment;           /* of the target's output framebuffer */
    GLenum gl_format, gl_type;   /* what glReadPixels is asked for */
    uint32_t read_bpp;           /* bytes per pixel in the buffer */
    uint32_t out_bpp;            /* bytes per pixel the caller gets */
    read_convert convert;
    uint32_t array;              /* an extra output's array (MVR_TARGET_OUTPUT_*); MVR_TARGET_OUTPUT_ARRAYS: the colour */
    uint32_t first_channel;      /* READ_CHANNELS: the output's first 32-bit channel in the texel */
} read_layout;

struct mvr_readback {
    mvr_renderer *renderer;      /* NULL once the renderer (or its context) is released */
    mvr_readback *next;          /* in renderer->readbacks */
    GLuint buffer;               /* GL_PIXEL_PACK_BUFFER: the layers one after another */
    size_t capacity;             /* bytes allocated for it */
    GLsync fence;                /* after the pending read's copies; 0 = none pending */
    uint32_t width, height, layers;
    read_layout layout;
};

/* The read a desc makes of a target: its colour in a format, or an extra
 * output from the array that holds it (as mvr_renderer_read_output reads
 * it, gl/outputs.c: the RGBA texels GLES always reads, then the output's
 * channels). false, with the reason in why: no such read. */
static bool read_layout_of(const mvr_target *t, const mvr_read_desc *d, read_layout *out, char *why, size_t why_size)
{
    read_layout l = {.attachment = GL_COLOR_ATTACHMENT0, .gl_format = GL_RGBA, .array = MVR_TARGET_OUTPUT_ARRAYS};
    if (d->output != MVR_OUTPUT_COLOR) {
        if (!mvr_output_name(d->output)) {
            snprintf(why, why_size, "unknown output %d", (int)d->output);
            return false;
        }
        if (!(t->desc.outputs & MVR_OUTPUT_BIT(d->output))) {
            snprintf(why, why_size, "the target was not created with the %s output (mvr_target_desc.outputs)",
                     mvr_output_name(d->output));
            return false;
        }
        mvr_output_place place = mvr_output_place_of(d->output);
        l.array = place.array;
        l.first_channel = place.first;
        l.gl_format = place.gl_format;
        l.gl_type = place.gl_type;
        l.read_bpp = 16;
        l.out_bpp = (uint32_t)mvr_output_pixel_size(d->output);
        l.convert = l.out_bpp == l.read_bpp ? READ_AS_IS : READ_CHANNELS;
        *out = l;
        return true;
    }
    bool float_target = t->internal_format == GL_RGBA16F || t->internal_format == GL_RGBA32F;
    switch (d->format) {
    case MVR_READBACK_RGBA8: l.out_bpp = 4; break;
    case MVR_READBACK_RGBA32F: l.out_bpp = 16; break;
    default: snprintf(why, why_size, "unknown format %d", (int)d->format); return false;
    }
    l.gl_type = float_target ? GL_FLOAT : GL_UNSIGNED_BYTE;
    l.read_bpp = float_target ? 16 : 4;
    l.convert = l.read_bpp == l.out_bpp ? READ_AS_IS : float_target ? READ_FLOAT_TO_BYTES : READ_BYTES_TO_FLOAT;
    *out = l;
    return true;
}

/* Deletes the GL objects (now, later or never: mvr_gl_delete) and
 * forgets the pending read. */
static void release(mvr_readback *rb)
{
    mvr_renderer *r = rb->renderer;
    if (r && r->ctx && rb->fence)
        mvr_context_delete_sync(r->ctx, rb->fence);
    rb->fence = 0;
    if (r)
        mvr_gl_delete(r, MVR_GL_BUFFER, &rb->buffer);
    rb->buffer = 0;
    rb->capacity = 0;
    rb->layers = 0;
}

void mvr_readbacks_release(mvr_renderer *r)
{
    while (r->readbacks) {
        mvr_readback *rb = r->readbacks;
        release(rb);
        r->readbacks = rb->next;
        rb->next = NULL;
        rb->renderer = NULL;
    }
}

mvr_result mvr_readback_create(mvr_renderer *r, mvr_readback **out)
{
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (!out)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_readback_create: out is NULL");
    *out = NULL;
    if (!r->ctx)
        return mvr_gl_fail(r, MVR_ERROR_CONTEXT, "mvr_readback_create: the renderer's context was destroyed");
    mvr_readback *rb = calloc(1, sizeof *rb);
    if (!rb)
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "mvr_readback_create: out of memory");
    /* GL objects are made by the first read, with the context current */
    rb->renderer = r;
    rb->next = r->readbacks;
    r->readbacks = rb;
    *out = rb;
    return MVR_OK;
}

void mvr_readback_destroy(mvr_readback *rb)
{
    if (!rb)
        return;
    mvr_renderer *r = rb->renderer;
    release(rb);
    if (r)
        for (mvr_readback **p = &r->readbacks; *p; p = &(*p)->next)
            if (*p == rb) {
                *p = rb->next;
                break;
            }
    free(rb);
}

/* The checks every call on a readback shares: its renderer, alive. */
static mvr_result check_readback(mvr_renderer *r, const mvr_readback *rb, const char *where)
{
    if (!rb)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: readback is NULL", where);
    if (!rb->renderer)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "%s: the readback was released with its renderer or context", where);
    if (rb->renderer != r)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: the readback belongs to another renderer",
                           where);
    return MVR_OK;
}

static mvr_result grow_buffer(mvr_renderer *r, mvr_readback *rb, size_t bytes)
{
    const mvr_gl_api_table *gl = r->gl;
    if (!rb->buffer)
        gl->GenBuffers(1, &rb->buffer);
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, rb->buffer);
    if (bytes <= rb->capacity)
        return MVR_OK;
    /* STREAM_READ: written by the GL once, read by the application once */
    gl->BufferData(GL_PIXEL_PACK_BUFFER, (GLsizeiptr)bytes, NULL, GL_STREAM_READ);
    mvr_result res = mvr_gl_check_alloc(r, "mvr_renderer_begin_read: a pixel buffer of %zu bytes", bytes);
    rb->capacity = res == MVR_OK ? bytes : 0;
    return res;
}

mvr_result mvr_renderer_begin_read(mvr_renderer *r, mvr_target *t, const mvr_read_desc *desc, mvr_readback *rb)
{
    static const char where[] = "mvr_renderer_begin_read";
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    mvr_result res = check_readback(r, rb, where);
    if (res != MVR_OK)
        return res;
    if (!t || !desc || t->renderer != r)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: %s", where,
                           t && desc && !t->renderer ? "the target was released with its renderer or context"
                           : t && desc && t->renderer != r ? "the target belongs to another renderer"
                                                           : "target or desc is NULL");
    if (rb->fence)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "%s: the readback holds a read not finished (mvr_renderer_finish_read first)", where);
    uint32_t layers = t->desc.layers;
    if (desc->first_layer >= layers)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: first layer %u of a target of %u", where,
                           desc->first_layer, layers);
    uint32_t count = desc->layer_count ? desc->layer_count : layers - desc->first_layer;
    if (count > layers - desc->first_layer)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: layers %u .. %u of a target of %u", where,
                           desc->first_layer, desc->first_layer + count - 1, layers);
    read_layout lay;
    char why[160];
    if (!read_layout_of(t, desc, &lay, why, sizeof why))
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: %s", where, why);
    size_t layer_bytes = 0, bytes = 0;
    if (!mvr_size_mul((size_t)t->desc.width * t->desc.height, lay.read_bpp, &layer_bytes) ||
        !mvr_size_mul(layer_bytes, count, &bytes) || bytes > (size_t)PTRDIFF_MAX)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: %u layers of %ux%u are too large to read", where,
                           count, t->desc.width, t->desc.height);
    res = mvr_gl_call_begin(r, where);
    if (res != MVR_OK)
        return res;
    mvr_state_invalidate(&r->state);
    const mvr_gl_api_table *gl = r->gl;
    res = grow_buffer(r, rb, bytes);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    GLsizei w = (GLsizei)t->desc.width, h = (GLsizei)t->desc.height;
    for (uint32_t k = 0; k < count && res == MVR_OK; ++k) {
        /* one layer attached alone: reading from a multiview framebuffer is an error */
        GLuint fbo = 0;
        res = lay.array == MVR_TARGET_OUTPUT_ARRAYS
                  ? mvr_target_output_framebuffer(t, desc->first_layer + k, 0, &fbo)
                  : mvr_target_output_array_framebuffer(t, lay.array, desc->first_layer + k, &fbo);
        if (res != MVR_OK)
            break;
        mvr_state_read_framebuffer(&r->state, fbo);
        gl->ReadBuffer(lay.attachment);
        gl->ReadPixels(0, 0, w, h, lay.gl_format, lay.gl_type, (void *)(uintptr_t)(layer_bytes * k));
    }
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    /* never left bound: a later glReadPixels to client memory would write into it */
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (res == MVR_OK) {
        rb->fence = gl->FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        /* submitted now, so the fence signals without anyone waiting on it */
        gl->Flush();
        if (!rb->fence)
            res = mvr_gl_fail(r, MVR_ERROR_GL, "%s: glFenceSync failed", where);
    }
    res = mvr_gl_call_end(r, where, res);
    if (res != MVR_OK) {
        /* nothing pending after a failure: the next read starts clean */
        if (rb->fence)
            gl->DeleteSync(rb->fence);
        rb->fence = 0;
        return res;
    }
    rb->width = t->desc.width;
    rb->height = t->desc.height;
    rb->layers = count;
    rb->layout = lay;
    return MVR_OK;
}

mvr_result mvr_renderer_read_ready(mvr_renderer *r, mvr_readback *rb, bool *ready)
{
    static const char where[] = "mvr_renderer_read_ready";
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    mvr_result res = check_readback(r, rb, where);
    if (res != MVR_OK)
        return res;
    if (!ready)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: ready is NULL", where);
    *ready = false;
    if (!rb->fence)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: no read is pending", where);
    res = mvr_gl_call_begin(r, where);
    if (res != MVR_OK)
        return res;
    GLenum s = r->gl->ClientWaitSync(rb->fence, 0, 0);
    if (s == GL_WAIT_FAILED)
        res = mvr_gl_fail(r, MVR_ERROR_GL, "%s: glClientWaitSync failed", where);
    *ready = s == GL_ALREADY_SIGNALED || s == GL_CONDITION_SATISFIED;
    res = mvr_gl_call_end(r, where, res);
    if (res != MVR_OK)
        *ready = false;
    return res;
}

/* Waits for the fence: in slices of a second, for at most a minute (a GPU
 * that takes longer has hung; the read fails instead of blocking forever). */
static mvr_result wait_fence(mvr_renderer *r, GLsync fence, const char *where)
{
    const GLuint64 second = (GLuint64)1000 * 1000 * 1000;
    for (int k = 0; k < 60; ++k) {
        GLenum s = r->gl->ClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, second);
        if (s == GL_ALREADY_SIGNALED || s == GL_CONDITION_SATISFIED)
            return MVR_OK;
        if (s == GL_WAIT_FAILED)
            return mvr_gl_fail(r, MVR_ERROR_GL, "%s: glClientWaitSync failed", where);
    }
    return mvr_gl_fail(r, MVR_ERROR_GL, "%s: the read did not complete in 60 s", where);
}

static void convert_layer(const read_layout *l, const void *src, void *dst, size_t pixels)
{
    switch (l->convert) {
    case READ_AS_IS: memcpy(dst, src, pixels * l->out_bpp); return;
    case READ_FLOAT_TO_BYTES: {
        /* as mvr_renderer_read_layer converts */
        const float *in = src;
        uint8_t *out = dst;
        for (size_t i = 0; i < pixels * 4; ++i) {
            float v = in[i] < 0.0f ? 0.0f : in[i] > 1.0f ? 1.0f : in[i];
            out[i] = (uint8_t)(v * 255.0f + 0.5f);
        }
        return;
    }
    case READ_BYTES_TO_FLOAT: {
        const uint8_t *in = src;
        float *out = dst;
        for (size_t i = 0; i < pixels * 4; ++i)
            out[i] = (float)in[i] / 255.0f;
        return;
    }
    case READ_CHANNELS: {
        const uint8_t *in = (const uint8_t *)src + l->first_channel * 4;
        uint8_t *out = dst;
        for (size_t i = 0; i < pixels; ++i)
            memcpy(out + i * l->out_bpp, in + i * 16, l->out_bpp);
        return;
    }
    }
}

mvr_result mvr_renderer_finish_read(mvr_renderer *r, mvr_readback *rb, void *dst, size_t size)
{
    static const char where[] = "mvr_renderer_finish_read";
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    mvr_result res = check_readback(r, rb, where);
    if (res != MVR_OK)
        return res;
    if (!rb->fence)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: no read is pending", where);
    if (!dst)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: dst is NULL", where);
    size_t need = mvr_readback_size(rb);
    if (size < need)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: buffer of %zu bytes, %zu needed", where, size,
                           need);
    res = mvr_gl_call_begin(r, where);
    if (res != MVR_OK)
        return res; /* the read stays pending: a call with the context current finishes it */
    const mvr_gl_api_table *gl = r->gl;
    res = wait_fence(r, rb->fence, where);
    size_t pixels = (size_t)rb->width * rb->height;
    size_t read_bytes = pixels * rb->layout.read_bpp * rb->layers;
    if (res == MVR_OK) {
        gl->BindBuffer(GL_PIXEL_PACK_BUFFER, rb->buffer);
        const uint8_t *src = gl->MapBufferRange(GL_PIXEL_PACK_BUFFER, 0, (GLsizeiptr)read_bytes, GL_MAP_READ_BIT);
        if (!src) {
            res = mvr_gl_fail(r, MVR_ERROR_GL, "%s: glMapBufferRange of %zu bytes failed", where, read_bytes);
        } else {
            for (uint32_t k = 0; k < rb->layers; ++k)
                convert_layer(&rb->layout, src + pixels * rb->layout.read_bpp * k,
                              (uint8_t *)dst + pixels * rb->layout.out_bpp * k, pixels);
            if (!gl->UnmapBuffer(GL_PIXEL_PACK_BUFFER))
                res = mvr_gl_fail(r, MVR_ERROR_GL, "%s: the pixel buffer's contents were lost (glUnmapBuffer)",
                                  where);
        }
        gl->BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    }
    /* finished, failed or not: the readback is free for the next read */
    gl->DeleteSync(rb->fence);
    rb->fence = 0;
    rb->layers = 0;
    return mvr_gl_call_end(r, where, res);
}

size_t mvr_readback_layer_size(const mvr_readback *rb)
{
    return rb && rb->fence ? (size_t)rb->width * rb->height * rb->layout.out_bpp : 0;
}

size_t mvr_readback_size(const mvr_readback *rb)
{
    return mvr_readback_layer_size(rb) * (rb && rb->fence ? rb->layers : 0);
}

uint32_t mvr_readback_layer_count(const mvr_readback *rb)
{
    return rb && rb->fence ? rb->layers : 0;
}
