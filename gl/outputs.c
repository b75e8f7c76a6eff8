/*
 * Extra outputs per view (depth, distance, normals, IDs, coverage): their
 * names, sizes and where each lives (read back by gl/readback.c and
 * gl/readback_async.c). The arrays are the target's (gl/targets.c), drawn
 * by the view passes (gl/passes.c) through core/shader_gen.h's MVR_SHADER_OUT_*.
 */
#include <stdlib.h>
#include <string.h>

#include "outputs.h"
#include "targets.h"

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
