/* Where each extra output lives in a target (gl/outputs.c). */
#ifndef MVR_OUTPUTS_H
#define MVR_OUTPUTS_H

#include "context_internal.h"

/* Where an extra output lives: its array (MVR_TARGET_OUTPUT_*,
 * ARRAYS for colour), its first channel and channel count in the 4 x 32-bit
 * texels, and the format and type GLES always reads that array with. The
 * synchronous and the asynchronous readback both read through it. */
typedef struct mvr_output_place {
    uint32_t array, first, count;
    GLenum gl_format, gl_type;
} mvr_output_place;
mvr_output_place mvr_output_place_of(mvr_output output);

#endif
