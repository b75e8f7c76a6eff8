/*
 * 8-bit PNG in and out through libpng, with the pixels OpenImageIO 2.4 gives:
 * mvr's output and its glTF textures stop needing OpenImageIO (and its 0.3 s
 * of load time). tests/io/test_image_png.c compares both decoders on every
 * PNG of tests/data and on generated files of every colour type, bit depth,
 * tRNS, gamma and interlace, pixel for pixel.
 *
 * What OpenImageIO's PNG reader does, reproduced here:
 *  - png_set_expand: palette to RGB, 1/2/4-bit grey to 8-bit, tRNS to alpha;
 *    16-bit samples kept until the end;
 *  - alpha associated in the file's own type (8 or 16 bit): the colour times
 *    alpha over the maximum, in integers, when the image is sRGB (sRGB chunk),
 *    has no gamma or a gamma that rounds to 1; otherwise the colour times
 *    (alpha / max) ^ gamma in float, truncated, where gamma is 1 / gAMA
 *    rounded to hundredths;
 *  - 16 to 8 bit: (v * 255 + 32767) / 65535;
 *  - rows read one at a time (png_read_end not called), interlaced images
 *    whole (png_read_image, then png_read_end).
 * An image with alpha and an ICC profile is deferred: whether libpng takes an
 * embedded sRGB profile for an sRGB chunk depends on options OpenImageIO may
 * set, and that decides the association above.
 */
#include <errno.h>
#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "image_internal.h"

/* What the libpng callbacks share; reached through png_get_error_ptr /
 * png_get_io_ptr, never a global. */
typedef struct png_job {
    const mvr_bytes_source *src;
    size_t at;                   /* read position in src->data */
    FILE *out;                   /* writing */
    char message[200];           /* libpng's last error */
} png_job;

static void on_error(png_structp png, png_const_charp msg)
{
    png_job *job = (png_job *)png_get_error_ptr(png);
    snprintf(job->message, sizeof job->message, "%s", msg ? msg : "libpng error");
    png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg)
{
    (void)png, (void)msg;   /* the library never prints; warnings change nothing */
}

static void on_read(png_structp png, png_bytep to, size_t n)
{
    png_job *job = (png_job *)png_get_io_ptr(png);
    const mvr_bytes_source *src = job->src;
    if (src->file) {
        if (fread(to, 1, n, src->file) != n)
            png_error(png, "the file ends early (truncated?)");
        return;
    }
    if (n > src->size - job->at)
        png_error(png, "read past the end of the data (truncated?)");
    memcpy(to, src->data + job->at, n);
    job->at += n;
}

static void on_write(png_structp png, png_bytep from, size_t n)
{
    png_job *job = (png_job *)png_get_io_ptr(png);
    if (fwrite(from, 1, n, job->out) != n)
        png_error(png, strerror(errno));
}

static void on_flush(png_structp png)
{
    (void)png;
}

/* The header and transforms; returns false where the image is deferred. */
typedef struct png_layout {
    uint32_t width, height;
    int channels;                /* after png_set_expand: 1..4 */
    int depth;                   /* 8 or 16, after png_set_expand */
    int alpha;                   /* the alpha channel's index, -1 = none */
    bool interlaced;
    float gamma;                 /* OpenImageIO's oiio:Gamma; 1 = integer association */
} png_layout;

/* Everything up to the first row; longjmps on libpng errors. */
static bool read_layout(png_structp png, png_infop info, png_layout *l, const char **why)
{
    png_read_info(png, info);
    int srgb_intent = 0;
    double file_gamma = 0.0;
    l->gamma = 1.0f;
    if (!png_get_sRGB(png, info, &srgb_intent) && png_get_gAMA(png, info, &file_gamma) && file_gamma > 0.0) {
        /* as OpenImageIO rounds it: 2.2, not 2.19998 */
        float g = (float)(1.0 / file_gamma);
        l->gamma = roundf(100.0f * g) / 100.0f;
    }
    bool icc = png_get_valid(png, info, PNG_INFO_iCCP) != 0;
    png_set_expand(png);
    png_read_update_info(png, info);
    png_uint_32 w = 0, h = 0;
    int depth = 0, color = 0, interlace = 0;
    png_get_IHDR(png, info, &w, &h, &depth, &color, &interlace, NULL, NULL);
    l->width = w;
    l->height = h;
    l->depth = depth;
    l->channels = png_get_channels(png, info);
    l->alpha = l->channels == 2 ? 1 : l->channels == 4 ? 3 : -1;
    l->interlaced = interlace != PNG_INTERLACE_NONE;
    if ((depth != 8 && depth != 16) || l->channels < 1 || l->channels > 4) {
        *why = "an unexpected layout after expansion";
        return false;
    }
    if (icc && l->alpha >= 0) {
        *why = "alpha with an ICC profile";
        return false;
    }
    return true;
}

static png_structp new_reader(png_job *job, png_infop *info)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, job, on_error, on_warning);
    if (!png)
        return NULL;
    *info = png_create_info_struct(png);
    if (!*info) {
        png_destroy_read_struct(&png, NULL, NULL);
        return NULL;
    }
    png_set_read_fn(png, job, on_read);
    return png;
}

static mvr_front_status deferred(mvr_error *error, const char *what, const char *why)
{
    mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "%s: %s", what, why);
    return MVR_FRONT_DEFER;
}

/* libpng refused the file: final, since OpenImageIO reads PNG through the
 * same libpng and would refuse it too, printing libpng's message to stderr. */
static mvr_front_status refused(mvr_error *error, const char *what, const char *why)
{
    mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "%s: %s", what, why);
    return MVR_FRONT_FAILED;
}

/* What decoding holds at its peak (see mvr_png_decode_cost). */
static uint64_t layout_cost(const png_layout *l)
{
    uint64_t pixels = (uint64_t)l->width * l->height;
    uint64_t row_bytes = mvr_image_mul((uint64_t)l->width, (uint64_t)l->channels * (uint64_t)(l->depth / 8));
    uint64_t native = l->interlaced ? mvr_image_mul(row_bytes, l->height) : row_bytes;
    uint64_t rows = l->interlaced ? (uint64_t)l->height * sizeof(png_bytep) : 0;
    return mvr_image_add(mvr_image_add(mvr_image_mul(pixels, 4), native), rows);
}

mvr_front_status mvr_png_probe(const mvr_bytes_source *src, mvr_image_header *out, mvr_error *error)
{
    png_job job = {.src = src};
    png_infop info = NULL;
    png_structp png = new_reader(&job, &info);
    if (!png) {
        mvr_image_fail(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_image_probe: out of memory (libpng)");
        return MVR_FRONT_FAILED;
    }
    png_layout l;
    const char *why = NULL;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        return refused(error, "mvr_image_probe", job.message);
    }
    bool ok = read_layout(png, info, &l, &why);
    png_destroy_read_struct(&png, &info, NULL);
    if (!ok)
        return deferred(error, "mvr_image_probe", why);
    if (l.width == 0 || l.height == 0) {
        mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "mvr_image_probe: the header has no valid size");
        return MVR_FRONT_FAILED;
    }
    out->width = l.width;
    out->height = l.height;
    out->channels = (uint32_t)l.channels;
    out->format = "png";
    return MVR_FRONT_OK;
}

/* A native row (8 or 16 bit, big-endian, l->channels) to RGBA8: alpha
 * associated in the native type, 16 bits rounded to 8, grey expanded. */
static void row_to_rgba(const png_layout *l, const unsigned char *in, unsigned char *out)
{
    int nc = l->channels;
    bool wide = l->depth == 16;
    uint32_t max = wide ? 65535u : 255u;
    /* OpenImageIO's float path: inv_max a float from a double division */
    float inv_max = (float)(1.0 / (double)max);
    for (uint32_t x = 0; x < l->width; ++x) {
        uint32_t v[4] = {0, 0, 0, 0};
        for (int c = 0; c < nc; ++c) {
            const unsigned char *p = in + ((size_t)x * (size_t)nc + (size_t)c) * (wide ? 2u : 1u);
            v[c] = wide ? (uint32_t)p[0] << 8 | p[1] : p[0];
        }
        if (l->alpha >= 0) {
            uint32_t a = v[l->alpha];
            if (l->gamma == 1.0f) {
                for (int c = 0; c < nc; ++c)
                    if (c != l->alpha)
                        v[c] = v[c] * a / max;
            } else {
                float k = powf((float)a * inv_max, l->gamma);
                for (int c = 0; c < nc; ++c)
                    if (c != l->alpha)
                        v[c] = (uint32_t)((float)v[c] * k);   /* truncated, as a cast to the type */
            }
        }
        if (wide)
            for (int c = 0; c < nc; ++c)
                v[c] = (v[c] * 255u + 32767u) / 65535u;
        unsigned char *o = out + (size_t)x * 4u;
        switch (nc) {
        case 1: o[0] = o[1] = o[2] = (unsigned char)v[0]; o[3] = 255; break;
        case 2: o[0] = o[1] = o[2] = (unsigned char)v[0]; o[3] = (unsigned char)v[1]; break;
        case 3: o[0] = (unsigned char)v[0]; o[1] = (unsigned char)v[1]; o[2] = (unsigned char)v[2]; o[3] = 255; break;
        default: for (int c = 0; c < 4; ++c) o[c] = (unsigned char)v[c]; break;
        }
    }
}

/* What decoding holds, freed on every path (a longjmp included). */
typedef struct png_buffers {
    unsigned char *rgba;
    unsigned char *native;       /* one row, or the whole image when interlaced */
    png_bytep *rows;
} png_buffers;

static void free_buffers(volatile png_buffers *b)
{
    free(b->rgba);
    free(b->native);
    free(b->rows);
    b->rgba = b->native = NULL;
    b->rows = NULL;
}

mvr_front_status mvr_png_decode_cost(const mvr_bytes_source *src, uint64_t *out_bytes, mvr_error *error)
{
    png_job job = {.src = src};
    png_infop info = NULL;
    png_structp png = new_reader(&job, &info);
    if (!png) {
        mvr_image_fail(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_image_decode_cost: out of memory (libpng)");
        return MVR_FRONT_FAILED;
    }
    png_layout l;
    const char *why = NULL;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        return refused(error, "mvr_image_decode_cost", job.message);
    }
    bool ok = read_layout(png, info, &l, &why);
    png_destroy_read_struct(&png, &info, NULL);
    if (!ok)
        return deferred(error, "mvr_image_decode_cost", why);
    *out_bytes = layout_cost(&l);
    return MVR_FRONT_OK;
}

mvr_front_status mvr_png_decode(const mvr_bytes_source *src, uint32_t max_dimension, uint64_t memory_budget,
                              const char *what, mvr_image_data *out, mvr_error *error)
{
    png_job job = {.src = src};
    png_infop info = NULL;
    png_structp png = new_reader(&job, &info);
    if (!png) {
        mvr_image_fail(error, MVR_ERROR_OUT_OF_MEMORY, "%s: out of memory (libpng)", what);
        return MVR_FRONT_FAILED;
    }
    /* changed after setjmp and freed after a longjmp: volatile (C11 7.13.2.1) */
    volatile png_buffers b = {0};
    png_layout l;
    const char *why = NULL;
    if (setjmp(png_jmpbuf(png))) {
        free_buffers(&b);
        png_destroy_read_struct(&png, &info, NULL);
        return refused(error, what, job.message);
    }
    if (!read_layout(png, info, &l, &why)) {
        png_destroy_read_struct(&png, &info, NULL);
        return deferred(error, what, why);
    }
    uint32_t cap = max_dimension ? max_dimension : 16384;
    if (l.width == 0 || l.height == 0 || l.width > cap || l.height > cap) {
        png_destroy_read_struct(&png, &info, NULL);
        mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "%s: %ux%u is not within 1..%u", what, l.width, l.height, cap);
        return MVR_FRONT_FAILED;
    }
    uint64_t budget = memory_budget ? memory_budget : MVR_IMAGE_DEFAULT_MEMORY_BUDGET;
    uint64_t needed = layout_cost(&l);
    if (needed > budget) {
        png_destroy_read_struct(&png, &info, NULL);
        mvr_image_over_budget(error, what, l.width, l.height, (uint32_t)l.channels, (uint32_t)l.depth / 8u, needed,
                              budget);
        return MVR_FRONT_FAILED;
    }
    size_t row_bytes = png_get_rowbytes(png, info);
    size_t native_rows = l.interlaced ? l.height : 1;
    b.rgba = mvr_image_alloc_pixels((size_t)l.width * l.height * 4u);
    b.native = malloc(row_bytes * native_rows);
    if (l.interlaced)
        b.rows = malloc(sizeof(png_bytep) * l.height);
    if (!b.rgba || !b.native || (l.interlaced && !b.rows)) {
        free_buffers(&b);
        png_destroy_read_struct(&png, &info, NULL);
        mvr_image_fail(error, MVR_ERROR_OUT_OF_MEMORY, "%s: out of memory (%ux%u)", what, l.width, l.height);
        return MVR_FRONT_FAILED;
    }
    if (l.interlaced) {
        for (uint32_t y = 0; y < l.height; ++y)
            b.rows[y] = b.native + (size_t)y * row_bytes;
        png_read_image(png, b.rows);
        png_read_end(png, NULL);
        for (uint32_t y = 0; y < l.height; ++y)
            row_to_rgba(&l, b.rows[y], b.rgba + (size_t)y * l.width * 4u);
    } else {
        for (uint32_t y = 0; y < l.height; ++y) {
            png_read_row(png, b.native, NULL);
            row_to_rgba(&l, b.native, b.rgba + (size_t)y * l.width * 4u);
        }
    }
    png_destroy_read_struct(&png, &info, NULL);
    out->width = l.width;
    out->height = l.height;
    out->type = MVR_PIXEL_U8;
    out->pixels = b.rgba;
    b.rgba = NULL;
    free_buffers(&b);
    return MVR_FRONT_OK;
}

/* The writer's state, freed on every path (a longjmp included). */
typedef struct png_out {
    png_structp png;
    png_infop info;
    unsigned char *row;
} png_out;

/* What one PNG writer writes: the header's fields, and each row made by
 * fill_row (row y counted from the top) into row_bytes bytes. */
typedef struct png_write_layout {
    const char *what;            /* the public call, for messages */
    uint32_t width, height;
    int bit_depth, color_type;
    bool srgb;                   /* the sRGB chunk (8-bit colour) */
    size_t row_bytes;
    void (*fill_row)(const void *source, uint32_t y, unsigned char *row);
    const void *source;
} png_write_layout;

/* The one writer behind mvr_png_write and mvr_png_write_gray: opens path,
 * writes every row, and removes the file on any failure (libpng's errors
 * come back through on_error's longjmp to the setjmp here). */
static mvr_front_status write_png(const char *path, const png_write_layout *l, mvr_error *error)
{
    png_job job = {.out = fopen(path, "wb")};
    if (!job.out) {
        mvr_image_fail(error, MVR_ERROR_IO, "%s(%s): %s", l->what, path, strerror(errno));
        return MVR_FRONT_FAILED;
    }
    png_out w = {0};   /* set before setjmp, unchanged after it */
    w.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &job, on_error, on_warning);
    w.info = w.png ? png_create_info_struct(w.png) : NULL;
    w.row = malloc(l->row_bytes);
    if (!w.png || !w.info || !w.row) {
        png_destroy_write_struct(&w.png, &w.info);
        free(w.row);
        fclose(job.out);
        remove(path);
        mvr_image_fail(error, MVR_ERROR_OUT_OF_MEMORY, "%s(%s): out of memory", l->what, path);
        return MVR_FRONT_FAILED;
    }
    if (setjmp(png_jmpbuf(w.png))) {
        png_destroy_write_struct(&w.png, &w.info);
        free(w.row);
        fclose(job.out);
        remove(path);
        mvr_image_fail(error, MVR_ERROR_IO, "%s(%s): %s", l->what, path, job.message);
        return MVR_FRONT_FAILED;
    }
    png_set_write_fn(w.png, &job, on_write, on_flush);
    png_set_IHDR(w.png, w.info, l->width, l->height, l->bit_depth, l->color_type, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    /* mvr's 8-bit pixels are sRGB-encoded: the sRGB chunk (with its gAMA
     * and cHRM fallbacks), as OpenImageIO wrote for oiio:ColorSpace sRGB */
    if (l->srgb)
        png_set_sRGB_gAMA_and_cHRM(w.png, w.info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_set_compression_level(w.png, 6);
    png_write_info(w.png, w.info);
    for (uint32_t y = 0; y < l->height; ++y) {
        l->fill_row(l->source, y, w.row);
        png_write_row(w.png, w.row);
    }
    png_write_end(w.png, w.info);
    png_destroy_write_struct(&w.png, &w.info);
    free(w.row);
    if (fclose(job.out) != 0) {
        remove(path);
        mvr_image_fail(error, MVR_ERROR_IO, "%s(%s): %s", l->what, path, strerror(errno));
        return MVR_FRONT_FAILED;
    }
    return MVR_FRONT_OK;
}

/* Row y (from the top) of an RGBA8 image as PNG stores it. */
static void rgba_row(const void *source, uint32_t y, unsigned char *row)
{
    const mvr_image_view *image = source;
    const unsigned char *pixels = (const unsigned char *)image->pixels;
    size_t stride = (size_t)image->width * 4u;
    const unsigned char *in = pixels + stride * (image->bottom_up ? image->height - 1u - y : y);
    for (uint32_t x = 0; x < image->width; ++x) {
        const unsigned char *p = in + (size_t)x * 4u;
        unsigned char *o = row + (size_t)x * 4u;
        uint32_t a = p[3];
        /* PNG's alpha is unassociated: OpenImageIO's writer divides by
         * alpha (integers, clamped; alpha 0 keeps the colour) */
        for (int c = 0; c < 3; ++c) {
            uint32_t v = a ? (uint32_t)p[c] * 255u / a : p[c];
            o[c] = (unsigned char)(v > 255u ? 255u : v);
        }
        o[3] = (unsigned char)a;
    }
}

mvr_front_status mvr_png_write(const char *path, const mvr_image_view *image, mvr_error *error)
{
    png_write_layout l = {.what = "mvr_image_write", .width = image->width, .height = image->height, .bit_depth = 8,
                    .color_type = PNG_COLOR_TYPE_RGB_ALPHA, .srgb = true, .row_bytes = (size_t)image->width * 4u,
                    .fill_row = rgba_row, .source = image};
    return write_png(path, &l, error);
}

/* A gray channel to write, and how its rows run. */
typedef struct gray_source {
    const mvr_image_channel *channel;
    uint32_t width, height;
    bool bottom_up;
} gray_source;

/* Row y (from the top) of a gray channel as PNG stores it: 16-bit samples
 * most significant byte first (ISO/IEC 15948, 7.1). */
static void gray_row(const void *source, uint32_t y, unsigned char *out)
{
    const gray_source *g = source;
    const mvr_image_channel *c = g->channel;
    const unsigned char *in = (const unsigned char *)c->first +
                              (size_t)(g->bottom_up ? g->height - 1u - y : y) * c->row_stride;
    for (uint32_t x = 0; x < g->width; ++x, in += c->pixel_stride) {
        if (c->type == MVR_CHANNEL_U8) {
            out[x] = *in;
        } else {
            uint16_t v;
            memcpy(&v, in, sizeof v);
            out[2u * x] = (unsigned char)(v >> 8);
            out[2u * x + 1u] = (unsigned char)(v & 0xFFu);
        }
    }
}

mvr_front_status mvr_png_write_gray(const char *path, const mvr_image_channel *channel, uint32_t width,
                                  uint32_t height, bool bottom_up, mvr_error *error)
{
    int depth = channel->type == MVR_CHANNEL_U16 ? 16 : 8;
    gray_source g = {channel, width, height, bottom_up};
    png_write_layout l = {.what = "mvr_image_write_channels", .width = width, .height = height, .bit_depth = depth,
                    .color_type = PNG_COLOR_TYPE_GRAY, .row_bytes = (size_t)width * (size_t)(depth / 8),
                    .fill_row = gray_row, .source = &g};
    return write_png(path, &l, error);
}
