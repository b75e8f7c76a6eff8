/*
 * 8-bit JPEG in through libjpeg-turbo, with the pixels OpenImageIO 2.4 gives:
 * glTF's JPEG textures stop paying OpenImageIO's start-up (its module load
 * and probe were a third of DamagedHelmet's first image). OpenImageIO's JPEG
 * reader is libjpeg with the library's defaults (jpeg_read_header, then
 * jpeg_start_decompress: islow IDCT, fancy upsampling, YCbCr or RGB to RGB,
 * greyscale as one channel); this is the same calls on the same library, so
 * the samples are the same ones, expanded to RGBA8 as mvr expands OpenImageIO's
 * (grey to RGB, alpha 255). tests/io/test_image_jpeg.c compares both decoders
 * on baseline and progressive, greyscale and RGB files, pixel for pixel.
 *
 * Deferred to OpenImageIO (MVR_FRONT_DEFER): CMYK and YCCK (OpenImageIO
 * converts those itself in float), and any other colour space.
 *
 * libjpeg reports a fatal error by calling error_exit, which must not return:
 * it longjmps back to the setjmp in the C function that called libjpeg here,
 * so no C++ frame is ever crossed; warnings (corrupt entropy data, which
 * libjpeg decodes through as OpenImageIO lets it) print nothing.
 */
/* jpeglib.h uses size_t and FILE without including their headers */
#include <stddef.h>
#include <stdio.h>

#include <jpeglib.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "image_internal.h"

/* libjpeg's error manager with the jump back and the last message; reached
 * from cinfo->err, never a global. */
typedef struct jpeg_job {
    struct jpeg_error_mgr pub;   /* first: libjpeg sees a jpeg_error_mgr */
    jmp_buf back;
    char message[JMSG_LENGTH_MAX];
} jpeg_job;

static void on_error(j_common_ptr cinfo)
{
    jpeg_job *job = (jpeg_job *)(void *)cinfo->err;
    (*cinfo->err->format_message)(cinfo, job->message);
    longjmp(job->back, 1);
}

static void on_message(j_common_ptr cinfo)
{
    (void)cinfo;   /* the library never prints; warnings change nothing */
}

/* The header as decoding needs it. */
typedef struct jpeg_layout {
    uint32_t width, height;
    int channels;                /* 1 (grey) or 3 (RGB) */
    uint64_t coefficients;       /* a multi-scan file's whole-image coefficient buffer, else 0 */
} jpeg_layout;

/* Reads the header (libjpeg must have its source); false where deferred. */
static bool read_layout(struct jpeg_decompress_struct *cinfo, jpeg_layout *l, const char **why)
{
    jpeg_read_header(cinfo, TRUE);
    l->width = cinfo->image_width;
    l->height = cinfo->image_height;
    l->coefficients = 0;
    switch (cinfo->jpeg_color_space) {
    case JCS_GRAYSCALE: l->channels = 1; break;
    case JCS_YCbCr:
    case JCS_RGB: l->channels = 3; break;
    default:
        *why = cinfo->jpeg_color_space == JCS_CMYK || cinfo->jpeg_color_space == JCS_YCCK
                   ? "CMYK / YCCK (OpenImageIO converts it)"
                   : "a colour space other than greyscale, YCbCr or RGB";
        return false;
    }
    if (cinfo->num_components != l->channels) {
        *why = "a component count that does not match its colour space";
        return false;
    }
    /* a progressive or non-interleaved file keeps every DCT coefficient
     * until its last scan: 64 of 2 bytes a block, each component padded to
     * its sampling factors (libjpeg's jdcoefct.c whole-image buffer) */
    if (jpeg_has_multiple_scans(cinfo)) {
        for (int c = 0; c < cinfo->num_components; ++c) {
            const jpeg_component_info *k = &cinfo->comp_info[c];
            uint64_t bw = ((uint64_t)k->width_in_blocks + (uint64_t)k->h_samp_factor - 1) /
                          (uint64_t)k->h_samp_factor * (uint64_t)k->h_samp_factor;
            uint64_t bh = ((uint64_t)k->height_in_blocks + (uint64_t)k->v_samp_factor - 1) /
                          (uint64_t)k->v_samp_factor * (uint64_t)k->v_samp_factor;
            l->coefficients = mvr_image_add(l->coefficients, mvr_image_mul(bw * bh, 64u * sizeof(JCOEF)));
        }
    }
    return true;
}

/* What decoding is charged: the figure OpenImageIO's path is charged (the
 * samples at the file's channels, the RGBA8 result, and held: what the front
 * found a progressive file's coefficients take), so either decoder answers
 * mvr_image_decode_cost alike. This decoder holds one row of samples, not the
 * image, so the figure is an upper bound on it; a multi-scan file's
 * coefficient buffer counts where it is the larger of the two. */
static uint64_t layout_cost(const jpeg_layout *l, uint64_t held)
{
    uint64_t pixels = (uint64_t)l->width * l->height;
    uint64_t samples = mvr_image_mul(pixels, (uint64_t)l->channels);
    uint64_t extra = held > l->coefficients ? held : l->coefficients;
    return mvr_image_add(mvr_image_add(samples, mvr_image_mul(pixels, 4)), extra);
}

static void set_source(struct jpeg_decompress_struct *cinfo, const mvr_bytes_source *src)
{
    if (src->file)
        jpeg_stdio_src(cinfo, src->file);
    else
        jpeg_mem_src(cinfo, src->data, (unsigned long)src->size);
}

/* The decompressor with its error manager set up; libjpeg's create cannot
 * fail but by error_exit (out of memory), caught by the caller's setjmp. */
static void new_reader(struct jpeg_decompress_struct *cinfo, jpeg_job *job)
{
    memset(cinfo, 0, sizeof *cinfo);
    cinfo->err = jpeg_std_error(&job->pub);
    job->pub.error_exit = on_error;
    job->pub.output_message = on_message;
    job->message[0] = '\0';
}

/* libjpeg refused the file: final, since OpenImageIO reads JPEG through the
 * same libjpeg and would refuse it too. */
static mvr_front_status refused(mvr_error *error, const char *what, const char *why)
{
    mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "%s: JPEG: %s", what, why[0] ? why : "libjpeg error");
    return MVR_FRONT_FAILED;
}

static mvr_front_status deferred(mvr_error *error, const char *what, const char *why)
{
    mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "%s: JPEG: %s", what, why);
    return MVR_FRONT_DEFER;
}

/* The header only: what probe and decode_cost need. */
static mvr_front_status header_of(const mvr_bytes_source *src, const char *what, jpeg_layout *l, mvr_error *error)
{
    struct jpeg_decompress_struct cinfo;
    jpeg_job job;
    new_reader(&cinfo, &job);
    if (setjmp(job.back)) {
        jpeg_destroy_decompress(&cinfo);
        return refused(error, what, job.message);
    }
    jpeg_create_decompress(&cinfo);
    set_source(&cinfo, src);
    const char *why = NULL;
    bool ok = read_layout(&cinfo, l, &why);
    jpeg_destroy_decompress(&cinfo);
    if (!ok)
        return deferred(error, what, why);
    if (l->width == 0 || l->height == 0) {
        mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "%s: the header has no valid size", what);
        return MVR_FRONT_FAILED;
    }
    return MVR_FRONT_OK;
}

mvr_front_status mvr_jpeg_probe(const mvr_bytes_source *src, mvr_image_header *out, mvr_error *error)
{
    jpeg_layout l;
    mvr_front_status st = header_of(src, "mvr_image_probe", &l, error);
    if (st != MVR_FRONT_OK)
        return st;
    out->width = l.width;
    out->height = l.height;
    out->channels = (uint32_t)l.channels;
    out->format = "jpeg";
    return MVR_FRONT_OK;
}

mvr_front_status mvr_jpeg_decode_cost(const mvr_bytes_source *src, uint64_t held, uint64_t *out_bytes,
                                      mvr_error *error)
{
    jpeg_layout l;
    mvr_front_status st = header_of(src, "mvr_image_decode_cost", &l, error);
    if (st == MVR_FRONT_OK)
        *out_bytes = layout_cost(&l, held);
    return st;
}

/* One row of samples (1 or 3 channels) to RGBA8, as mvr expands
 * OpenImageIO's: grey to RGB, alpha 255. */
static void row_to_rgba(const unsigned char *in, int channels, uint32_t width, unsigned char *out)
{
    if (channels == 1) {
        for (uint32_t x = 0; x < width; ++x, out += 4) {
            out[0] = out[1] = out[2] = in[x];
            out[3] = 255;
        }
        return;
    }
    for (uint32_t x = 0; x < width; ++x, in += 3, out += 4) {
        out[0] = in[0];
        out[1] = in[1];
        out[2] = in[2];
        out[3] = 255;
    }
}

/* What decoding holds, freed on every path (a longjmp included). */
typedef struct jpeg_buffers {
    unsigned char *rgba;
    unsigned char *row;
} jpeg_buffers;

static void free_buffers(volatile jpeg_buffers *b)
{
    free(b->rgba);
    free(b->row);
    b->rgba = b->row = NULL;
}

mvr_front_status mvr_jpeg_decode(const mvr_bytes_source *src, uint32_t max_dimension, uint64_t memory_budget,
                                 uint64_t held, const char *what, mvr_image_data *out, mvr_error *error)
{
    struct jpeg_decompress_struct cinfo;
    jpeg_job job;
    new_reader(&cinfo, &job);
    /* changed after setjmp and freed after a longjmp: volatile (C11 7.13.2.1) */
    volatile jpeg_buffers b = {0};
    if (setjmp(job.back)) {
        free_buffers(&b);
        jpeg_destroy_decompress(&cinfo);
        return refused(error, what, job.message);
    }
    jpeg_create_decompress(&cinfo);
    set_source(&cinfo, src);
    jpeg_layout l;
    const char *why = NULL;
    if (!read_layout(&cinfo, &l, &why)) {
        jpeg_destroy_decompress(&cinfo);
        return deferred(error, what, why);
    }
    uint32_t cap = max_dimension ? max_dimension : 16384;
    if (l.width == 0 || l.height == 0 || l.width > cap || l.height > cap) {
        jpeg_destroy_decompress(&cinfo);
        mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "%s: %ux%u is not within 1..%u", what, l.width, l.height, cap);
        return MVR_FRONT_FAILED;
    }
    uint64_t budget = memory_budget ? memory_budget : MVR_IMAGE_DEFAULT_MEMORY_BUDGET;
    uint64_t needed = layout_cost(&l, held);
    if (needed > budget) {
        jpeg_destroy_decompress(&cinfo);
        mvr_image_over_budget(error, what, l.width, l.height, (uint32_t)l.channels, 1, needed, budget);
        return MVR_FRONT_FAILED;
    }
    /* checked before libjpeg allocates its image-sized buffers (start) */
    b.rgba = mvr_image_alloc_pixels((size_t)l.width * l.height * 4u);
    b.row = malloc((size_t)l.width * (size_t)l.channels);
    if (!b.rgba || !b.row) {
        free_buffers(&b);
        jpeg_destroy_decompress(&cinfo);
        mvr_image_fail(error, MVR_ERROR_OUT_OF_MEMORY, "%s: out of memory (%ux%u)", what, l.width, l.height);
        return MVR_FRONT_FAILED;
    }
    jpeg_start_decompress(&cinfo);
    if (cinfo.output_width != l.width || cinfo.output_height != l.height || cinfo.output_components != l.channels) {
        free_buffers(&b);
        jpeg_destroy_decompress(&cinfo);
        return deferred(error, what, "an unexpected output layout");
    }
    while (cinfo.output_scanline < cinfo.output_height) {
        uint32_t y = cinfo.output_scanline;
        JSAMPROW rows[1] = {b.row};
        if (jpeg_read_scanlines(&cinfo, rows, 1) != 1) {
            free_buffers(&b);
            jpeg_destroy_decompress(&cinfo);
            return refused(error, what, "the data ends early (truncated?)");
        }
        row_to_rgba(b.row, l.channels, l.width, b.rgba + (size_t)y * l.width * 4u);
    }
    /* jpeg_finish_decompress is not called: OpenImageIO does not either, and
     * what follows the last row (up to EOI) changes no pixel */
    jpeg_destroy_decompress(&cinfo);
    out->width = l.width;
    out->height = l.height;
    out->type = MVR_PIXEL_U8;
    out->pixels = b.rgba;
    b.rgba = NULL;
    free_buffers(&b);
    return MVR_FRONT_OK;
}
