/*
 * mvr_image's parts, behind include/mvr/mvr_image.h:
 *  - image_io.c: the C front every program links. It picks a decoder from the
 *    bytes' signature and does 8-bit PNG (image_png.c) and JPEG (image_jpeg.c)
 *    itself; everything else goes to the OpenImageIO module.
 *  - image_png.c: 8-bit PNG in and out through libpng, giving the pixels
 *    OpenImageIO 2.4 gives (same libpng transforms, same alpha association,
 *    same 16-to-8-bit rounding); what it does not reproduce it defers.
 *  - image_jpeg.c: 8-bit greyscale / RGB JPEG through libjpeg-turbo, the
 *    same library calls OpenImageIO 2.4 makes; CMYK is deferred.
 *  - image_oiio.cpp: libmvr_image_oiio.so, OpenImageIO behind a table of C
 *    functions, loaded with dlopen() the first time a call needs it (EXR, HDR,
 *    WebP, CMYK JPEG, float pixels, comparisons): linking OpenImageIO costs every
 *    program ~0.3 s before main() (the static initialisers of its 260 shared
 *    libraries), which a program that only writes PNG never needs to pay.
 * Internal: tests/io/test_image_png.c and test_image_jpeg.c use these to compare
 * the front with OpenImageIO.
 */
#ifndef MVR_IMAGE_INTERNAL_H
#define MVR_IMAGE_INTERNAL_H

#include <stdio.h>

#include "mvr/mvr_image.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the OpenImageIO module (image_oiio.cpp) ---- */

/* Bumped whenever the table or a function's meaning changes: a module of
 * another build is refused rather than called with the wrong layout. */
#define MVR_IMAGE_MODULE_ABI 3u
#define MVR_IMAGE_MODULE_FILE "libmvr_image_oiio.so"
#define MVR_IMAGE_MODULE_ENTRY "mvr_image_oiio_backend"
/* A path: the module to load instead of searching for it (tests point it at
 * a missing file to check the message; users at a module moved elsewhere). */
#define MVR_IMAGE_MODULE_ENV "MVR_IMAGE_MODULE"

/* Each function is the public one of the same name as OpenImageIO does it;
 * the front has checked the arguments, the signature and the MIME type (and a
 * JPEG's framing). memory_budget is never 0 here: the front resolves it. */
typedef struct mvr_image_backend {
    uint32_t abi;                /* MVR_IMAGE_MODULE_ABI */
    uint32_t size;               /* sizeof(mvr_image_backend) */
    mvr_result (*probe)(const void *data, size_t size, const char *mime_type, mvr_image_header *out,
                        mvr_error *error);
    mvr_result (*decode_cost)(const void *data, size_t size, const char *mime_type, uint64_t *out_bytes,
                              mvr_error *error);
    /* held: bytes the front found the decoder will hold besides what the
     * module counts (a progressive JPEG's coefficients), added to its cost */
    mvr_result (*decode)(const void *data, size_t size, const char *mime_type, uint32_t max_dimension,
                         uint64_t memory_budget, uint64_t held, mvr_image_data *out, mvr_error *error);
    mvr_result (*read)(const char *path, mvr_pixel_type type, uint64_t memory_budget, uint64_t held,
                       mvr_image_data *out, mvr_error *error);
    mvr_result (*write)(const char *path, const mvr_image_view *image, mvr_error *error);
    mvr_result (*compare)(const mvr_image_view *a, const mvr_image_view *b, double threshold,
                          const char *diff_path, mvr_image_compare_result *out, mvr_error *error);
    /* EXR only: the front has checked the arguments and the names */
    mvr_result (*write_channels)(const char *path, const mvr_image_channels *image, mvr_error *error);
} mvr_image_backend;

/* The module's one exported function: its table, or NULL when abi differs. */
typedef const mvr_image_backend *(*mvr_image_backend_entry)(uint32_t abi);

/* The loaded module (loaded once per process, thread-safe, never unloaded),
 * or NULL with an error naming the file and dlerror()'s reason. `who` starts
 * the message. */
const mvr_image_backend *mvr_image_module(const char *who, mvr_error *error);

/* ---- the front's own decoders: PNG (image_png.c), JPEG (image_jpeg.c) ---- */

typedef enum mvr_front_status {
    MVR_FRONT_OK = 0,
    MVR_FRONT_DEFER,   /* not reproduced here, or libpng refused it: ask OpenImageIO (msg says why) */
    MVR_FRONT_FAILED   /* a final answer (size over the cap, out of memory, a file not writable) */
} mvr_front_status;

/* Where encoded bytes come from: memory, or an open file. */
typedef struct mvr_bytes_source {
    const unsigned char *data;
    size_t size;
    FILE *file;
} mvr_bytes_source;

/* The header as OpenImageIO's probe reports it (channels after expanding
 * palette, low bit depths and tRNS). */
mvr_front_status mvr_png_probe(const mvr_bytes_source *src, mvr_image_header *out, mvr_error *error);

/* What mvr_png_decode holds at its peak for this image, from its header: the
 * RGBA8 result, one native row or (interlaced) the whole native image at the
 * file's bit depth after expansion, and the row pointers. */
mvr_front_status mvr_png_decode_cost(const mvr_bytes_source *src, uint64_t *out_bytes, mvr_error *error);

/* RGBA8, rows top first, as OpenImageIO's read_image(UINT8) and mvr's
 * channel expansion give it. max_dimension 0 = 16384; memory_budget 0 = the
 * default; both checked before anything is allocated; `what` starts messages.
 * A PNG libpng refuses is a final answer (MVR_FRONT_FAILED, libpng's message):
 * OpenImageIO's libpng would refuse it too, and print to stderr doing so. */
mvr_front_status mvr_png_decode(const mvr_bytes_source *src, uint32_t max_dimension, uint64_t memory_budget,
                              const char *what, mvr_image_data *out, mvr_error *error);

/* An RGBA8 view to an 8-bit RGBA PNG with an sRGB chunk, alpha unassociated
 * as OpenImageIO's PNG writer does it (the colour of a pixel with alpha a,
 * 0 < a < 255, becomes min(255, c * 255 / a)). */
mvr_front_status mvr_png_write(const char *path, const mvr_image_view *image, mvr_error *error);

/* One U8 or U16 channel to an 8- or 16-bit grayscale PNG, the values as
 * given (no sRGB chunk: they are data, not colour). */
mvr_front_status mvr_png_write_gray(const char *path, const mvr_image_channel *channel, uint32_t width,
                                  uint32_t height, bool bottom_up, mvr_error *error);

/* ---- JPEG through libjpeg-turbo (image_jpeg.c) ---- */

/* The header as OpenImageIO's probe reports it: greyscale (1 channel) and
 * YCbCr / RGB (3); other colour spaces (CMYK, YCCK) are deferred. The front
 * has checked the framing (SOI ... EOI). */
mvr_front_status mvr_jpeg_probe(const mvr_bytes_source *src, mvr_image_header *out, mvr_error *error);

/* What decoding is charged, as OpenImageIO's path is: the samples, the RGBA8
 * result and `held` (the front's figure for a progressive file's
 * coefficients), or a multi-scan file's own coefficient buffer if larger. */
mvr_front_status mvr_jpeg_decode_cost(const mvr_bytes_source *src, uint64_t held, uint64_t *out_bytes,
                                      mvr_error *error);

/* RGBA8, rows top first, the pixels OpenImageIO's read_image(UINT8) and mvr's
 * channel expansion give; max_dimension 0 = 16384, memory_budget 0 = the
 * default, both checked before the pixels are allocated; `what` starts
 * messages. A JPEG libjpeg refuses is a final answer (MVR_FRONT_FAILED). */
mvr_front_status mvr_jpeg_decode(const mvr_bytes_source *src, uint32_t max_dimension, uint64_t memory_budget,
                                 uint64_t held, const char *what, mvr_image_data *out, mvr_error *error);

/* The refusal of an image over its memory budget: MVR_ERROR_OUT_OF_MEMORY,
 * naming what, the declared size and both byte counts (inline: the front and
 * the module, a separate shared object, both say it). */
static inline mvr_result mvr_image_over_budget(mvr_error *error, const char *what, uint32_t width, uint32_t height,
                                               uint32_t channels, uint32_t bytes_per_channel, uint64_t needed,
                                               uint64_t budget)
{
    if (error) {
        snprintf(error->message, sizeof error->message,
                 "%.300s: declared %ux%u, %u channel(s) of %u byte(s): decoding would hold %.1f MiB, over the memory "
                 "budget of %.1f MiB",
                 what, width, height, channels, bytes_per_channel, (double)needed / 1048576.0,
                 (double)budget / 1048576.0);
        error->result = MVR_ERROR_OUT_OF_MEMORY;
    }
    return MVR_ERROR_OUT_OF_MEMORY;
}

/* a * b, or UINT64_MAX where it overflows (a cost that large is over any budget) */
static inline uint64_t mvr_image_mul(uint64_t a, uint64_t b)
{
    uint64_t r;
    return __builtin_mul_overflow(a, b, &r) ? UINT64_MAX : r;
}

static inline uint64_t mvr_image_add(uint64_t a, uint64_t b)
{
    return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

/* malloc() for a decoded image's pixels, advised into huge pages where it is
 * large (freed with free()). */
void *mvr_image_alloc_pixels(size_t bytes);

/* printf into error (NULL: nothing), returns r. */
mvr_result mvr_image_fail(mvr_error *error, mvr_result r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#ifdef __cplusplus
}
#endif
#endif
