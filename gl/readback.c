/* Synchronous readback: a layer's colour, or one of its extra outputs,
 * read into the caller's memory (gl/readback_async.c reads without waiting). */
#include <stdlib.h>
#include <string.h>

#include "errors.h"
#include "outputs.h"
#include "renderer.h"
#include "targets.h"

mvr_result mvr_renderer_read_layer(mvr_renderer *r, mvr_target *t, uint32_t layer,
                                   mvr_readback_format format, void *dst, size_t size)
{
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (!t || !dst || t->renderer != r)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           t && dst && !t->renderer
                               ? "mvr_renderer_read_layer: the target was released with its renderer or context"
                               : "mvr_renderer_read_layer: bad target or buffer");
    if (layer >= t->desc.layers)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_renderer_read_layer: layer %u of %u", layer, t->desc.layers);
    if ((unsigned)format > MVR_READBACK_RGBA32F)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_read_layer: unknown format");
    size_t pixels = (size_t)t->desc.width * t->desc.height;
    size_t need = pixels * 4 * (format == MVR_READBACK_RGBA32F ? sizeof(float) : 1);
    if (size < need)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_renderer_read_layer: buffer of %zu bytes, %zu needed", size, need);
    mvr_result res = mvr_gl_call_begin(r, "mvr_renderer_read_layer");
    if (res != MVR_OK)
        return res;
    mvr_state_invalidate(&r->state);
    /* One layer attached alone: reading from a multiview framebuffer is an error. */
    GLuint fbo = 0;
    res = mvr_target_output_framebuffer(t, layer, 0, &fbo);
    if (res != MVR_OK)
        return mvr_gl_call_end(r, "mvr_renderer_read_layer", res);
    const mvr_gl_api_table *gl = r->gl;
    mvr_state_read_framebuffer(&r->state, fbo);
    gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    bool float_target = t->internal_format == GL_RGBA16F || t->internal_format == GL_RGBA32F;
    GLsizei w = (GLsizei)t->desc.width, h = (GLsizei)t->desc.height;
    if (float_target == (format == MVR_READBACK_RGBA32F)) {
        gl->ReadPixels(0, 0, w, h, GL_RGBA, float_target ? GL_FLOAT : GL_UNSIGNED_BYTE, dst);
    } else if (float_target) {
        /* float storage read as bytes: GLES reads float buffers as FLOAT only */
        float *tmp = malloc(pixels * 4 * sizeof *tmp);
        if (!tmp)
            return mvr_gl_call_end(r, "mvr_renderer_read_layer",
                                   mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY,
                                               "mvr_renderer_read_layer: out of memory"));
        gl->ReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, tmp);
        uint8_t *out = dst;
        for (size_t i = 0; i < pixels * 4; ++i) {
            float v = tmp[i] < 0.0f ? 0.0f : tmp[i] > 1.0f ? 1.0f : tmp[i];
            out[i] = (uint8_t)(v * 255.0f + 0.5f);
        }
        free(tmp);
    } else {
        /* 8-bit storage read as floats: normalized */
        uint8_t *tmp = malloc(pixels * 4);
        if (!tmp)
            return mvr_gl_call_end(r, "mvr_renderer_read_layer",
                                   mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY,
                                               "mvr_renderer_read_layer: out of memory"));
        gl->ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, tmp);
        float *out = dst;
        for (size_t i = 0; i < pixels * 4; ++i)
            out[i] = (float)tmp[i] / 255.0f;
        free(tmp);
    }
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    return mvr_gl_call_end(r, "mvr_renderer_read_layer", MVR_OK);
}

mvr_result mvr_renderer_read_output(mvr_renderer *r, mvr_target *t, uint32_t layer, mvr_output output, void *dst,
                                    size_t size)
{
    static const char where[] = "mvr_renderer_read_output";
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (!mvr_output_name(output))
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: unknown output %d", where, (int)output);
    if (output == MVR_OUTPUT_COLOR)
        return mvr_renderer_read_layer(r, t, layer, MVR_READBACK_RGBA8, dst, size);
    if (!t || !dst || t->renderer != r)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: %s", where,
                           t && dst && !t->renderer ? "the target was released with its renderer or context"
                                                    : "bad target or buffer");
    if (!(t->desc.outputs & MVR_OUTPUT_BIT(output)))
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "%s: the target was not created with the %s output (mvr_target_desc.outputs)", where,
                           mvr_output_name(output));
    if (layer >= t->desc.layers)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: layer %u of %u", where, layer, t->desc.layers);
    size_t pixels = (size_t)t->desc.width * t->desc.height;
    size_t need = pixels * mvr_output_pixel_size(output);
    if (size < need)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: %s: buffer of %zu bytes, %zu needed", where,
                           mvr_output_name(output), size, need);
    mvr_output_place place = mvr_output_place_of(output);
    /* the GL reads RGBA of 32-bit values; the output's channels are kept */
    uint32_t *texels = malloc(pixels * 4 * sizeof *texels);
    if (!texels)
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "%s: %s: out of memory", where, mvr_output_name(output));
    mvr_result res = mvr_gl_call_begin(r, where);
    if (res != MVR_OK) {
        free(texels);
        return res;
    }
    mvr_state_invalidate(&r->state);
    GLuint fbo = 0;
    res = mvr_target_output_array_framebuffer(t, place.array, layer, &fbo);
    if (res == MVR_OK) {
        const mvr_gl_api_table *gl = r->gl;
        mvr_state_read_framebuffer(&r->state, fbo);
        gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
        gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl->ReadPixels(0, 0, (GLsizei)t->desc.width, (GLsizei)t->desc.height, place.gl_format, place.gl_type, texels);
        res = mvr_gl_check(r->ctx, where, true);
        if (res != MVR_OK)
            res = mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    }
    if (res == MVR_OK) {
        uint8_t *out = dst;
        size_t bytes = place.count * sizeof *texels;
        for (size_t i = 0; i < pixels; ++i)
            memcpy(out + i * bytes, texels + i * 4 + place.first, bytes);
    }
    free(texels);
    return mvr_gl_call_end(r, where, res);
}
