/*
 * mvr_image: image files in and out, and image comparison, behind a C ABI.
 * 8-bit PNG goes through libpng; everything else (EXR, HDR, JPEG, WebP, float
 * pixels, comparisons) through OpenImageIO in libmvr_image_oiio.so, which is
 * loaded the first time a call needs it (found next to libmvr_image.so or the
 * program, or at $MVR_IMAGE_MODULE; a call that needs it and cannot load it
 * fails with MVR_ERROR_UNSUPPORTED naming the file and the reason). PNG
 * decodes to the pixels OpenImageIO gives.
 * Used by the glTF loader (texture decoding), the CLI (PNG / EXR output), the
 * tests (golden images) and the benchmark (error against a reference).
 */
#ifndef MVR_IMAGE_H
#define MVR_IMAGE_H

#include "mvr/mvr.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mvr_pixel_type {
    MVR_PIXEL_U8 = 0,            /* 8-bit unsigned normalized */
    MVR_PIXEL_F32                /* 32-bit float */
} mvr_pixel_type;

/* RGBA pixels in memory, 4 channels. */
typedef struct mvr_image_view {
    uint32_t width, height;
    mvr_pixel_type type;
    bool bottom_up;              /* first row is the image's bottom (GL readback order) */
    const void *pixels;
} mvr_image_view;

/* An image mvr_image_* allocated; free with mvr_image_free. Rows top first. */
typedef struct mvr_image_data {
    uint32_t width, height;
    mvr_pixel_type type;
    void *pixels;                /* width * height * 4 values */
} mvr_image_data;

void mvr_image_free(mvr_image_data *image);

/* What an encoded image's header says, read without decoding its pixels. */
typedef struct mvr_image_header {
    uint32_t width, height;
    uint32_t channels;           /* as stored (decoding expands to 4) */
    const char *format;          /* "png", "jpeg", "webp"; static storage */
} mvr_image_header;

/* Reads an encoded image's header from memory. The format is chosen from the
 * bytes' signature (PNG, JPEG, WebP), never from a name; mime_type (NULL or ""
 * = not declared) must agree with it, else MVR_ERROR_INVALID_ASSET; an
 * unknown signature is MVR_ERROR_UNSUPPORTED. */
mvr_result mvr_image_probe(const void *data, size_t size, const char *mime_type, mvr_image_header *out,
                           mvr_error *error);

/* Decodes an encoded image from memory into RGBA8 (gray, gray-alpha and RGB
 * expanded, 16-bit scaled), the format chosen as mvr_image_probe chooses it.
 * Images larger than max_dimension (0 = 16384) either way are refused, and so
 * are truncated ones (a PNG without IEND, a JPEG without its EOI marker), and
 * images over the default memory budget (see below). */
mvr_result mvr_image_decode(const void *data, size_t size, const char *mime_type,
                            uint32_t max_dimension, mvr_image_data *out, mvr_error *error);

/* Reads a file into RGBA8 or RGBA float, within the default memory budget. */
mvr_result mvr_image_read(const char *path, mvr_pixel_type type, mvr_image_data *out, mvr_error *error);

/* Memory: every decode and read checks, from the header and before it
 * allocates anything, what decoding holds at its peak (the RGBA result, the
 * pixels as the decoder delivers them, and the decoder's own working copies:
 * a 16-bit interlaced PNG's whole native image, OpenImageIO's copy in the
 * file's own type before converting, WebP's decoded image, a progressive
 * JPEG's coefficients) against a budget; over it, the call fails with
 * MVR_ERROR_OUT_OF_MEMORY naming the file, the declared size and the budget.
 * A budget of 0 means this default, the glTF loader's default too. */
#define MVR_IMAGE_DEFAULT_MEMORY_BUDGET (UINT64_C(2) << 30)

/* What decoding the bytes (mvr_image_decode) holds at its peak, in bytes,
 * from the header alone; the glTF loader charges it to the load's budget. */
mvr_result mvr_image_decode_cost(const void *data, size_t size, const char *mime_type, uint64_t *out_bytes,
                                 mvr_error *error);

/* mvr_image_decode and mvr_image_read with a memory budget (0 = the default). */
mvr_result mvr_image_decode_within(const void *data, size_t size, const char *mime_type, uint32_t max_dimension,
                                   uint64_t memory_budget, mvr_image_data *out, mvr_error *error);
mvr_result mvr_image_read_within(const char *path, mvr_pixel_type type, uint64_t memory_budget,
                                 mvr_image_data *out, mvr_error *error);

/* Writes a file; the format follows the extension: .png (8-bit, the bytes as
 * given: sRGB-encoded for mvr's sRGB targets), .exr (half float, linear:
 * floats are written as given, 8-bit input is sRGB-decoded first). */
mvr_result mvr_image_write(const char *path, const mvr_image_view *image, mvr_error *error);

/* Named channels of one type each, for images that are not RGBA colour:
 * 16-bit depth and ID PNGs, 8-bit masks, and EXRs of many named layers. */
typedef enum mvr_channel_type {
    MVR_CHANNEL_U8 = 0,
    MVR_CHANNEL_U16,
    MVR_CHANNEL_U32,
    MVR_CHANNEL_F16,             /* stored as half; given as float32 */
    MVR_CHANNEL_F32
} mvr_channel_type;

typedef struct mvr_image_channel {
    const char *name;            /* EXR channel name ("R", "Z", "N.X", "id.node"); PNG: not used */
    mvr_channel_type type;       /* as stored; the values given are uint8 / uint16 / uint32 / float32 */
    const void *first;           /* the value of the first pixel of the first row in memory */
    size_t pixel_stride;         /* bytes from one pixel's value to the next's */
    size_t row_stride;           /* bytes from one row's first value to the next row's */
} mvr_image_channel;

typedef struct mvr_image_channels {
    uint32_t width, height;
    bool bottom_up;              /* the first row in memory is the image's bottom (GL order) */
    uint32_t count;              /* 1..MVR_IMAGE_MAX_CHANNELS */
    const mvr_image_channel *channels;
} mvr_image_channels;

#define MVR_IMAGE_MAX_CHANNELS 64u

/* Writes named channels; the format follows the extension:
 *  - .png: one channel, U8 or U16: an 8- or 16-bit grayscale PNG, the values
 *    as given (no colour space; libpng, never OpenImageIO);
 *  - .exr: 1..MVR_IMAGE_MAX_CHANNELS channels, each stored in its own type
 *    (OpenEXR's UINT for U32, HALF for U8 and F16, FLOAT for U16 and F32:
 *    every value exact but F16's) under its name, through the OpenImageIO module; names must be distinct.
 * Anything else (another channel count or type for PNG, an empty or
 * repeated name for EXR) is MVR_ERROR_INVALID_ARGUMENT naming the file. */
mvr_result mvr_image_write_channels(const char *path, const mvr_image_channels *image, mvr_error *error);

typedef struct mvr_image_compare_result {
    double rmse;                 /* over all channels, in [0, 1] units */
    double psnr;                 /* dB; infinite for identical images */
    double max_abs;              /* largest channel difference, [0, 1] units */
    double mean_abs;
    uint64_t pixels_over;        /* pixels with a channel difference > threshold */
    double fraction_over;        /* pixels_over / pixel count */
} mvr_image_compare_result;

/* Compares two images of the same size channel by channel (OpenImageIO's
 * ImageBufAlgo::compare) in [0, 1] units; threshold likewise (e.g. 2/255).
 * diff_path (optional) receives |a - b| as an image. */
mvr_result mvr_image_compare(const mvr_image_view *a, const mvr_image_view *b, double threshold,
                             const char *diff_path, mvr_image_compare_result *out, mvr_error *error);

#ifdef __cplusplus
}
#endif
#endif
