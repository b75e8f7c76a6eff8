/*
 * Extra outputs per view (depth, distance, normals, IDs, coverage): their
 * names, sizes and readback. The arrays are the target's (gl/targets.c), drawn
 * by the view passes (gl/passes.c) through core/shader_gen.h's MVR_SHADER_OUT_*.
 */
#include <stdlib.h>
#include <string.h>

#include "renderer_internal.h"

const char *mvr_output_name(mvr_output output)
{
    switch (output) {
    case MVR_OUTPUT_COLOR:
        return "color";
    case MVR_OUTPUT_DEPTH:
        return "depth";
    case MVR_OUTPUT_DISTANCE:
        return "distance";
    case MVR_OUTPUT_NORMAL:
        return "normal";
    case MVR_OUTPUT_IDS:
        return "ids";
    case MVR_OUTPUT_COVERAGE:
        return "coverage";
    case MVR_OUTPUT_COUNT:
        break;
    }
    return NULL;
}

size_t mvr_output_pixel_size(mvr_output output)
{
    switch (output) {
    case MVR_OUTPUT_COLOR:
        return 4;
    case MVR_OUTPUT_DEPTH:
    case MVR_OUTPUT_DISTANCE:
    case MVR_OUTPUT_COVERAGE:
        return sizeof(float);
    case MVR_OUTPUT_NORMAL:
        return 3 * sizeof(float);
    case MVR_OUTPUT_IDS:
        return 4 * sizeof(uint32_t);
    case MVR_OUTPUT_COUNT:
        break;
    }
    return 0;
}

const char *mvr_normal_space_name(mvr_normal_space space)
{
    switch (space) {
    case MVR_NORMAL_SPACE_WORLD:
        return "world";
    case MVR_NORMAL_SPACE_CAMERA:
        return "camera";
    }
    return NULL;
}

mvr_output_place mvr_output_place_of(mvr_output output)
{
    mvr_output_place p = {.array = MVR_TARGET_OUTPUT_ARRAYS, .gl_format = GL_RGBA, .gl_type = GL_FLOAT};
    switch (output) {
    case MVR_OUTPUT_DEPTH:
        p.array = MVR_TARGET_OUTPUT_GEOMETRY, p.first = 0, p.count = 1;
        break;
    case MVR_OUTPUT_DISTANCE:
        p.array = MVR_TARGET_OUTPUT_GEOMETRY, p.first = 1, p.count = 1;
        break;
    case MVR_OUTPUT_COVERAGE:
        p.array = MVR_TARGET_OUTPUT_GEOMETRY, p.first = 2, p.count = 1;
        break;
    case MVR_OUTPUT_NORMAL:
        p.array = MVR_TARGET_OUTPUT_NORMAL, p.first = 0, p.count = 3;
        break;
    case MVR_OUTPUT_IDS:
        /* the formats GLES always reads: RGBA / FLOAT for float, RGBA_INTEGER / UNSIGNED_INT for uint */
        p.array = MVR_TARGET_OUTPUT_IDS, p.first = 0, p.count = 4;
        p.gl_format = GL_RGBA_INTEGER, p.gl_type = GL_UNSIGNED_INT;
        break;
    case MVR_OUTPUT_COLOR:
    case MVR_OUTPUT_COUNT:
        break;
    }
    return p;
}

mvr_result mvr_renderer_read_output(mvr_renderer *r, mvr_target *t, uint32_t layer, mvr_output output, void *dst,
                                    size_t size)
{
    static const char where[] = "mvr_renderer_read_output";
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (!mvr_output_name(output))
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: unknown output %d", where, (int)output);
    if (output == MVR_OUTPUT_COLOR)
        return mvr_renderer_read_layer(r, t, layer, MVR_READBACK_RGBA8, dst, size);
    if (!t || !dst || t->renderer != r)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: %s", where,
                                 t && dst && !t->renderer ? "the target was released with its renderer or context"
                                                          : "bad target or buffer");
    if (!(t->desc.outputs & MVR_OUTPUT_BIT(output)))
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "%s: the target was not created with the %s output (mvr_target_desc.outputs)", where,
                                 mvr_output_name(output));
    if (layer >= t->desc.layers)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: layer %u of %u", where, layer, t->desc.layers);
    size_t pixels = (size_t)t->desc.width * t->desc.height;
    size_t need = pixels * mvr_output_pixel_size(output);
    if (size < need)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT, "%s: %s: buffer of %zu bytes, %zu needed", where,
                                 mvr_output_name(output), size, need);
    mvr_output_place place = mvr_output_place_of(output);
    /* the GL reads RGBA of 32-bit values; the output's channels are kept */
    uint32_t *texels = malloc(pixels * 4 * sizeof *texels);
    if (!texels)
        return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "%s: %s: out of memory", where, mvr_output_name(output));
    mvr_result res = mvr_renderer_begin(r, where);
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
            res = mvr_renderer_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    }
    if (res == MVR_OK) {
        uint8_t *out = dst;
        size_t bytes = place.count * sizeof *texels;
        for (size_t i = 0; i < pixels; ++i)
            memcpy(out + i * bytes, texels + i * 4 + place.first, bytes);
    }
    free(texels);
    return mvr_renderer_end(r, where, res);
}
