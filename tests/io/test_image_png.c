/*
 * mvr_image's PNG front (core/io/image_png.c) against OpenImageIO (the module
 * core/io/image_oiio.cpp, which mvr_image used for every image before):
 *  - every PNG of tests/data and tests/golden/data, and generated files of
 *    every colour type, bit depth, tRNS, gamma / sRGB and interlace, decode
 *    to the same header and the same pixels through both (exhaustively over
 *    colour x alpha for the association of alpha);
 *  - what the front writes decodes to the pixels of what OpenImageIO writes;
 *  - corrupt and oversized PNGs are refused by both;
 *  - PNG work never loads OpenImageIO into the process; other work does;
 *  - with --module-missing / --module-foreign (ctest sets MVR_IMAGE_MODULE to
 *    a missing file / a library that is not the module) the calls that need
 *    the module fail naming the file and the reason, and PNG still works.
 * This program links neither OpenImageIO nor the C++ runtime itself.
 */
#include <dirent.h>
#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "image_internal.h"
#include "mvr_test.h"

/* ---------------------------------------------------------------- helpers */

static const char *out_dir(void)
{
    return MVR_IMAGE_PNG_OUT;
}

/* Whether a shared library whose path contains `name` is mapped into this process. */
static int loaded(const char *name)
{
    FILE *f = fopen("/proc/self/maps", "r");
    if (!f)
        return -1;
    char line[4096];
    int found = 0;
    while (!found && fgets(line, sizeof line, f))
        found = strstr(line, name) != NULL;
    fclose(f);
    return found;
}

typedef struct bytes {
    unsigned char *data;
    size_t size, cap;
} bytes;

static void bytes_put(bytes *b, const void *p, size_t n)
{
    if (b->size + n > b->cap) {
        b->cap = (b->size + n) * 2;
        b->data = realloc(b->data, b->cap);
    }
    memcpy(b->data + b->size, p, n);
    b->size += n;
}

static bool read_file(const char *path, bytes *out)
{
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    unsigned char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        bytes_put(out, buf, n);
    fclose(f);
    return true;
}

/* A PNG as libpng writes it from raw rows: the generator of the cases. */
typedef struct png_spec {
    uint32_t width, height;
    int color, depth;
    bool interlace;
    double gamma;                /* gAMA; 0 = none */
    int srgb;                    /* sRGB intent; -1 = none */
    int palette_size;            /* palette colours (colour type 3) */
    int trns_count;              /* palette alpha entries, or 1 = a grey / RGB tRNS colour */
    bool icc;                    /* an iCCP chunk (a profile libpng does not recognise) */
    bool bad_crc;                /* flip a bit of the first IDAT's data */
    size_t cut;                  /* keep only this many bytes (0 = all) */
} png_spec;

static void put_bytes(png_structp png, png_bytep p, size_t n)
{
    bytes_put((bytes *)png_get_io_ptr(png), p, n);
}

static void no_flush(png_structp png)
{
    (void)png;
}

/* Deterministic pseudo-random bytes (xorshift), so a failure reproduces. */
static uint32_t next_rand(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static int channels_of(int color)
{
    return color == PNG_COLOR_TYPE_GRAY ? 1 : color == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
         : color == PNG_COLOR_TYPE_RGB ? 3 : color == PNG_COLOR_TYPE_RGB_ALPHA ? 4 : 1;
}

/* Encodes spec with pixel bytes from fill (NULL: random, seeded). */
static bool make_png(const png_spec *s, const unsigned char *fill, uint32_t seed, bytes *out)
{
    memset(out, 0, sizeof *out);
    size_t row_bytes = ((size_t)s->width * (size_t)channels_of(s->color) * (size_t)s->depth + 7) / 8;
    unsigned char *pixels = malloc(row_bytes * s->height);
    png_bytep *rows = malloc(sizeof(png_bytep) * s->height);
    for (size_t i = 0; i < row_bytes * s->height; ++i) {
        unsigned char v = fill ? fill[i] : (unsigned char)next_rand(&seed);
        if (s->color == PNG_COLOR_TYPE_PALETTE && !fill) {
            /* indices within the palette: each sample of the byte mod size */
            int per = 8 / s->depth, mask = (1 << s->depth) - 1;
            unsigned char packed = 0;
            for (int k = 0; k < per; ++k)
                packed = (unsigned char)(packed << s->depth | ((int)(next_rand(&seed) % (uint32_t)s->palette_size) & mask));
            v = packed;
        }
        pixels[i] = v;
    }
    for (uint32_t y = 0; y < s->height; ++y)
        rows[y] = pixels + (size_t)y * row_bytes;
    png_color pal[256];
    png_byte alpha[256];
    for (int i = 0; i < s->palette_size; ++i) {
        pal[i].red = (png_byte)next_rand(&seed);
        pal[i].green = (png_byte)next_rand(&seed);
        pal[i].blue = (png_byte)next_rand(&seed);
    }
    for (int i = 0; i < s->trns_count; ++i)
        alpha[i] = (png_byte)(i == 0 ? 0 : i == 1 ? 255 : next_rand(&seed));
    png_byte profile_noise[376];
    for (size_t i = 0; i < sizeof profile_noise; ++i)
        profile_noise[i] = (png_byte)next_rand(&seed);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    bool ok = false;
    if (setjmp(png_jmpbuf(png)) == 0) {
        png_set_write_fn(png, out, put_bytes, no_flush);
        png_set_IHDR(png, info, s->width, s->height, s->depth, s->color,
                     s->interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                     PNG_FILTER_TYPE_DEFAULT);
        if (s->color == PNG_COLOR_TYPE_PALETTE) {
            png_set_PLTE(png, info, pal, s->palette_size);
            if (s->trns_count > 0)
                png_set_tRNS(png, info, alpha, s->trns_count, NULL);
        } else if (s->trns_count > 0) {
            /* a colour that occurs: the first pixel's */
            png_color_16 c = {0};
            int max = (1 << s->depth) - 1;
            if (s->depth == 16) {
                c.gray = c.red = (png_uint_16)(pixels[0] << 8 | pixels[1]);
                c.green = (png_uint_16)(pixels[2] << 8 | pixels[3]);
                c.blue = (png_uint_16)(pixels[4] << 8 | pixels[5]);
            } else if (s->depth == 8) {
                c.gray = c.red = pixels[0];
                c.green = pixels[1];
                c.blue = pixels[2];
            } else {
                c.gray = (png_uint_16)((pixels[0] >> (8 - s->depth)) & max);
            }
            png_set_tRNS(png, info, NULL, 0, &c);
        }
        if (s->gamma > 0)
            png_set_gAMA(png, info, s->gamma);
        if (s->srgb >= 0)
            png_set_sRGB(png, info, s->srgb);
        if (s->icc) {
            /* a small profile libpng accepts (ICC.1 7.2: size, version,
             * class, colour space, PCS, signature, D50; two tags, one of
             * noise so that the chunk compresses to more than the 92 bytes
             * libpng 1.6.39 reads before the zlib stream) and does not take
             * for sRGB */
            png_byte profile[376] = {0};
            profile[2] = 376 >> 8, profile[3] = 376 & 255;
            profile[8] = 2, profile[9] = 0x10;
            memcpy(profile + 12, "mntr", 4);
            memcpy(profile + 16, s->color & PNG_COLOR_MASK_COLOR ? "RGB " : "GRAY", 4);
            memcpy(profile + 20, "XYZ ", 4);
            memcpy(profile + 36, "acsp", 4);
            const png_byte d50[12] = {0, 0, 0xF6, 0xD6, 0, 1, 0, 0, 0, 0, 0xD3, 0x2D};
            memcpy(profile + 68, d50, sizeof d50);
            profile[131] = 2;
            const png_byte tags[24] = {'w', 't', 'p', 't', 0, 0, 0, 156, 0, 0, 0, 20,
                                       'z', 'z', 'z', 'z', 0, 0, 0, 176, 0, 0, 0, 200};
            memcpy(profile + 132, tags, sizeof tags);
            memcpy(profile + 156, "XYZ ", 4);
            memcpy(profile + 164, d50, sizeof d50);
            for (size_t k = 176; k < sizeof profile; ++k)
                profile[k] = profile_noise[k];
            png_set_iCCP(png, info, "test", 0, profile, sizeof profile);
        }
        png_write_info(png, info);
        png_write_image(png, rows);
        png_write_end(png, info);
        ok = true;
    }
    png_destroy_write_struct(&png, &info);
    free(rows);
    free(pixels);
    if (ok && s->bad_crc) {
        for (size_t at = 8; at + 12 <= out->size;) {
            uint32_t len = (uint32_t)out->data[at] << 24 | (uint32_t)out->data[at + 1] << 16 |
                           (uint32_t)out->data[at + 2] << 8 | out->data[at + 3];
            if (memcmp(out->data + at + 4, "IDAT", 4) == 0 && len > 4) {
                out->data[at + 8 + len / 2] ^= 0x10;
                break;
            }
            at += 12 + len;
        }
    }
    if (ok && s->cut && s->cut < out->size)
        out->size = s->cut;
    return ok;
}

/* Decodes with both; returns the front's status. `what` names the case. */
static mvr_front_status compare_decoders(mvr_test_state *t, const mvr_image_backend *m, const bytes *b,
                                       const char *what)
{
    mvr_error fe = {0}, oe = {0};
    mvr_image_header fh = {0}, oh = {0};
    mvr_bytes_source src = {.data = b->data, .size = b->size};
    mvr_front_status ps = mvr_png_probe(&src, &fh, &fe);
    mvr_result pr = m->probe(b->data, b->size, "image/png", &oh, &oe);
    if (ps == MVR_FRONT_OK) {
        CHECK_MSG(t, pr == MVR_OK, "%s: the front probes, OpenImageIO refuses: %s", what, oe.message);
        if (pr == MVR_OK) {
            CHECK_MSG(t, fh.width == oh.width && fh.height == oh.height && fh.channels == oh.channels,
                      "%s: header %ux%u/%u, OpenImageIO %ux%u/%u", what, fh.width, fh.height, fh.channels,
                      oh.width, oh.height, oh.channels);
            CHECK_MSG(t, strcmp(fh.format, oh.format) == 0, "%s: format %s vs %s", what, fh.format, oh.format);
        }
    }
    mvr_image_data fd = {0}, od = {0};
    mvr_front_status ds = mvr_png_decode(&src, 0, 0, what, &fd, &fe);
    mvr_result dr = m->decode(b->data, b->size, "image/png", 0, MVR_IMAGE_DEFAULT_MEMORY_BUDGET, 0, &od, &oe);
    if (ds == MVR_FRONT_OK) {
        CHECK_MSG(t, dr == MVR_OK, "%s: the front decodes, OpenImageIO refuses: %s", what, oe.message);
        if (dr == MVR_OK) {
            CHECK_MSG(t, fd.width == od.width && fd.height == od.height, "%s: size differs", what);
            if (fd.width == od.width && fd.height == od.height) {
                const unsigned char *a = fd.pixels, *o = od.pixels;
                size_t n = (size_t)fd.width * fd.height * 4, diff = 0, first = 0;
                for (size_t i = 0; i < n; ++i)
                    if (a[i] != o[i] && diff++ == 0)
                        first = i;
                CHECK_MSG(t, diff == 0, "%s: %zu of %zu values differ; first at pixel %zu channel %zu: %u vs OpenImageIO %u",
                          what, diff, n, first / 4, first % 4, a[first], o[first]);
            }
        }
    } else if (ds == MVR_FRONT_FAILED) {
        CHECK_MSG(t, dr != MVR_OK, "%s: the front refuses (%s), OpenImageIO decodes", what, fe.message);
    } else {
        /* deferred: the public call must give OpenImageIO's answer */
        mvr_image_data pd = {0};
        mvr_error pe = {0};
        mvr_result r = mvr_image_decode(b->data, b->size, "image/png", 0, &pd, &pe);
        CHECK_MSG(t, (r == MVR_OK) == (dr == MVR_OK), "%s: deferred, but mvr_image_decode says %s", what, pe.message);
        if (r == MVR_OK && dr == MVR_OK)
            CHECK_MSG(t, memcmp(pd.pixels, od.pixels, (size_t)od.width * od.height * 4) == 0,
                      "%s: deferred, but mvr_image_decode's pixels are not OpenImageIO's", what);
        mvr_image_free(&pd);
    }
    mvr_image_free(&fd);
    mvr_image_free(&od);
    return ds;
}

static const mvr_image_backend *module_or_fail(mvr_test_state *t)
{
    mvr_error err = {0};
    const mvr_image_backend *m = mvr_image_module("test_image_png", &err);
    CHECK_MSG(t, m != NULL, "%s", err.message);
    return m;
}

/* ------------------------------------------------------------------ cases */

/* First: nothing before it may have needed the module. */
static void png_work_leaves_openimageio_unloaded(mvr_test_state *t)
{
    CHECK_MSG(t, loaded("libOpenImageIO") == 0, "OpenImageIO is mapped before any image call");
    CHECK_MSG(t, loaded("libmvr_image_oiio") == 0, "the module is mapped before any image call");
    unsigned char px[4 * 6 * 5];
    for (size_t i = 0; i < sizeof px; ++i)
        px[i] = (unsigned char)(i * 37);
    char path[512];
    snprintf(path, sizeof path, "%s/unloaded.png", out_dir());
    mvr_image_view v = {.width = 6, .height = 5, .type = MVR_PIXEL_U8, .pixels = px};
    mvr_error err = {0};
    CHECK_MSG(t, mvr_image_write(path, &v, &err) == MVR_OK, "%s", err.message);
    mvr_image_data back = {0};
    CHECK_MSG(t, mvr_image_read(path, MVR_PIXEL_U8, &back, &err) == MVR_OK, "%s", err.message);
    CHECK(t, back.width == 6 && back.height == 5);
    bytes b;
    CHECK(t, read_file(path, &b));
    mvr_image_header h = {0};
    CHECK_MSG(t, mvr_image_probe(b.data, b.size, "image/png", &h, &err) == MVR_OK, "%s", err.message);
    CHECK(t, h.width == 6 && h.height == 5 && h.channels == 4 && strcmp(h.format, "png") == 0);
    mvr_image_data dec = {0};
    CHECK_MSG(t, mvr_image_decode(b.data, b.size, NULL, 0, &dec, &err) == MVR_OK, "%s", err.message);
    CHECK(t, dec.pixels && back.pixels && memcmp(dec.pixels, back.pixels, sizeof px) == 0);
    free(b.data);
    mvr_image_free(&back);
    mvr_image_free(&dec);
    CHECK_MSG(t, loaded("libOpenImageIO") == 0, "PNG write / read / probe / decode loaded OpenImageIO");
    CHECK_MSG(t, loaded("libmvr_image_oiio") == 0, "PNG write / read / probe / decode loaded the module");
    /* a float read needs OpenImageIO: now it is there */
    mvr_image_data sky = {0};
    CHECK_MSG(t, mvr_image_read(MVR_PEERS_DIR "/sky.hdr", MVR_PIXEL_F32, &sky, &err) == MVR_OK, "%s", err.message);
    CHECK(t, sky.width > 0 && sky.type == MVR_PIXEL_F32);
    mvr_image_free(&sky);
    CHECK_MSG(t, loaded("libmvr_image_oiio") == 1, "an HDR read did not load the module");
    CHECK_MSG(t, loaded("libOpenImageIO") == 1, "an HDR read did not load OpenImageIO");
}

static int walk_pngs(mvr_test_state *t, const mvr_image_backend *m, const char *dir)
{
    DIR *d = opendir(dir);
    CHECK_MSG(t, d != NULL, "cannot list %s", dir);
    if (!d)
        return 0;
    int count = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(path, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode)) {
            count += walk_pngs(t, m, path);
            continue;
        }
        size_t n = strlen(e->d_name);
        if (n < 4 || strcmp(e->d_name + n - 4, ".png") != 0)
            continue;
        bytes b;
        CHECK(t, read_file(path, &b));
        mvr_front_status s = compare_decoders(t, m, &b, path);
        CHECK_MSG(t, s == MVR_FRONT_OK, "%s: the front does not decode it itself", path);
        /* by path too (mvr_image_read: the front reads the file) */
        mvr_image_data a = {0}, o = {0};
        mvr_error ae = {0}, oe = {0};
        CHECK_MSG(t, mvr_image_read(path, MVR_PIXEL_U8, &a, &ae) == MVR_OK, "%s", ae.message);
        CHECK_MSG(t, m->read(path, MVR_PIXEL_U8, MVR_IMAGE_DEFAULT_MEMORY_BUDGET, 0, &o, &oe) == MVR_OK, "%s", oe.message);
        if (a.pixels && o.pixels)
            CHECK_MSG(t, a.width == o.width && a.height == o.height &&
                             memcmp(a.pixels, o.pixels, (size_t)a.width * a.height * 4) == 0,
                      "%s: mvr_image_read differs from OpenImageIO's", path);
        mvr_image_free(&a);
        mvr_image_free(&o);
        free(b.data);
        ++count;
    }
    closedir(d);
    return count;
}

static void every_png_of_the_repository(mvr_test_state *t)
{
    const mvr_image_backend *m = module_or_fail(t);
    if (!m)
        return;
    int n = walk_pngs(t, m, MVR_TEST_DATA_DIR) + walk_pngs(t, m, MVR_GOLDEN_DATA_DIR);
    printf("  %d PNG files compared\n", n);
    CHECK_MSG(t, n >= 20, "only %d PNG files found under %s and %s", n, MVR_TEST_DATA_DIR, MVR_GOLDEN_DATA_DIR);
}

static void generated_layouts(mvr_test_state *t)
{
    const mvr_image_backend *m = module_or_fail(t);
    if (!m)
        return;
    typedef struct layout {
        int color, depth, palette, trns;
    } layout;
    const layout layouts[] = {
        {PNG_COLOR_TYPE_GRAY, 1, 0, 0},       {PNG_COLOR_TYPE_GRAY, 2, 0, 0},
        {PNG_COLOR_TYPE_GRAY, 4, 0, 0},       {PNG_COLOR_TYPE_GRAY, 8, 0, 0},
        {PNG_COLOR_TYPE_GRAY, 16, 0, 0},      {PNG_COLOR_TYPE_GRAY, 1, 0, 1},
        {PNG_COLOR_TYPE_GRAY, 4, 0, 1},       {PNG_COLOR_TYPE_GRAY, 8, 0, 1},
        {PNG_COLOR_TYPE_GRAY, 16, 0, 1},      {PNG_COLOR_TYPE_GRAY_ALPHA, 8, 0, 0},
        {PNG_COLOR_TYPE_GRAY_ALPHA, 16, 0, 0}, {PNG_COLOR_TYPE_RGB, 8, 0, 0},
        {PNG_COLOR_TYPE_RGB, 16, 0, 0},       {PNG_COLOR_TYPE_RGB, 8, 0, 1},
        {PNG_COLOR_TYPE_RGB, 16, 0, 1},       {PNG_COLOR_TYPE_RGB_ALPHA, 8, 0, 0},
        {PNG_COLOR_TYPE_RGB_ALPHA, 16, 0, 0}, {PNG_COLOR_TYPE_PALETTE, 1, 2, 0},
        {PNG_COLOR_TYPE_PALETTE, 2, 4, 3},    {PNG_COLOR_TYPE_PALETTE, 4, 16, 0},
        {PNG_COLOR_TYPE_PALETTE, 4, 11, 5},   {PNG_COLOR_TYPE_PALETTE, 8, 256, 0},
        {PNG_COLOR_TYPE_PALETTE, 8, 200, 200}, {PNG_COLOR_TYPE_PALETTE, 8, 256, 17},
    };
    typedef struct colour {
        double gamma;
        int srgb;
        const char *name;
    } colour;
    const colour colours[] = {
        {0, -1, "no gamma"}, {0, 0, "sRGB"}, {1 / 2.2, -1, "gAMA 1/2.2"}, {1.0, -1, "gAMA 1"},
        {0.7, -1, "gAMA 0.7"}, {1 / 2.2, 1, "sRGB + gAMA"}, {1 / 1.0049, -1, "gAMA rounding to 1"},
    };
    int ok = 0, deferred = 0, cases = 0;
    uint32_t seed = 12345;
    for (size_t i = 0; i < sizeof layouts / sizeof layouts[0]; ++i) {
        for (size_t c = 0; c < sizeof colours / sizeof colours[0]; ++c) {
            for (int interlace = 0; interlace < 2; ++interlace) {
                png_spec s = {.width = 37u + (uint32_t)i % 3u, .height = 23u + (uint32_t)c, .color = layouts[i].color,
                              .depth = layouts[i].depth, .interlace = interlace != 0, .gamma = colours[c].gamma,
                              .srgb = colours[c].srgb, .palette_size = layouts[i].palette,
                              .trns_count = layouts[i].trns};
                bytes b;
                CHECK(t, make_png(&s, NULL, seed++, &b));
                char what[160];
                snprintf(what, sizeof what, "colour type %d, %d bit, tRNS %d, %s, %s", s.color, s.depth,
                         s.trns_count, colours[c].name, interlace ? "interlaced" : "not interlaced");
                mvr_front_status st = compare_decoders(t, m, &b, what);
                CHECK_MSG(t, st == MVR_FRONT_OK, "%s: deferred or refused", what);
                ok += st == MVR_FRONT_OK;
                ++cases;
                free(b.data);
            }
        }
    }
    /* alpha with an ICC profile: deferred, and then OpenImageIO's pixels */
    for (int depth = 8; depth <= 16; depth += 8) {
        png_spec s = {.width = 16, .height = 9, .color = PNG_COLOR_TYPE_RGB_ALPHA, .depth = depth, .gamma = 1 / 2.2,
                      .srgb = -1, .icc = true};
        bytes b;
        CHECK(t, make_png(&s, NULL, seed++, &b));
        mvr_front_status st = compare_decoders(t, m, &b, "RGBA with an iCCP chunk");
        deferred += st == MVR_FRONT_DEFER;
        ++cases;
        free(b.data);
    }
    printf("  %d generated files: %d decoded by the front, %d deferred to OpenImageIO\n", cases, ok, deferred);
    CHECK_EQ_INT(t, deferred, 2);
}

/* Every colour x alpha pair, 8 and 16 bit, with and without a gamma: the
 * association of alpha is the part of OpenImageIO's reader that is arithmetic. */
static void alpha_association_exhaustive(mvr_test_state *t)
{
    const mvr_image_backend *m = module_or_fail(t);
    if (!m)
        return;
    const double gammas[] = {0, 1 / 2.2, 1 / 1.8, 0.7};
    for (size_t g = 0; g < sizeof gammas / sizeof gammas[0]; ++g) {
        for (int depth = 8; depth <= 16; depth += 8) {
            size_t bpp = depth == 16 ? 8 : 4;
            unsigned char *fill = malloc(256u * 256u * bpp);
            uint32_t seed = 99;
            for (uint32_t y = 0; y < 256; ++y)
                for (uint32_t x = 0; x < 256; ++x) {
                    unsigned char *p = fill + ((size_t)y * 256 + x) * bpp;
                    if (depth == 8) {
                        p[0] = (unsigned char)x, p[1] = (unsigned char)(255 - x), p[2] = (unsigned char)(x ^ 0x5A);
                        p[3] = (unsigned char)y;
                    } else {
                        /* the high byte walks every value, the low byte is noise */
                        for (int c = 0; c < 4; ++c) {
                            p[2 * c] = (unsigned char)(c == 3 ? y : c == 1 ? 255 - x : x);
                            p[2 * c + 1] = (unsigned char)next_rand(&seed);
                        }
                    }
                }
            png_spec s = {.width = 256, .height = 256, .color = PNG_COLOR_TYPE_RGB_ALPHA, .depth = depth,
                          .gamma = gammas[g], .srgb = -1};
            bytes b;
            CHECK(t, make_png(&s, fill, 0, &b));
            char what[96];
            snprintf(what, sizeof what, "RGBA %d bit, colour x alpha, gAMA %.4f", depth, gammas[g]);
            CHECK_MSG(t, compare_decoders(t, m, &b, what) == MVR_FRONT_OK, "%s: not decoded by the front", what);
            free(b.data);
            free(fill);
        }
    }
}

/* Raw RGBA8 rows of a PNG file (no transform: what the file stores). */
static unsigned char *stored_rgba(const char *path, uint32_t *w, uint32_t *h, bool *srgb)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    unsigned char *volatile px = NULL;
    if (setjmp(png_jmpbuf(png)) == 0) {
        png_init_io(png, f);
        png_read_info(png, info);
        int intent;
        *srgb = png_get_sRGB(png, info, &intent) != 0;
        *w = png_get_image_width(png, info);
        *h = png_get_image_height(png, info);
        if (png_get_color_type(png, info) == PNG_COLOR_TYPE_RGB_ALPHA && png_get_bit_depth(png, info) == 8) {
            px = malloc((size_t)*w * *h * 4);
            for (uint32_t y = 0; y < *h; ++y)
                png_read_row(png, px + (size_t)y * *w * 4, NULL);
        }
    } else {
        free(px);
        px = NULL;
    }
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    return px;
}

static void writers_agree(mvr_test_state *t)
{
    const mvr_image_backend *m = module_or_fail(t);
    if (!m)
        return;
    /* every colour x alpha, then a second pass bottom-up */
    unsigned char *px = malloc(256u * 256u * 4u);
    for (uint32_t y = 0; y < 256; ++y)
        for (uint32_t x = 0; x < 256; ++x) {
            unsigned char *p = px + ((size_t)y * 256 + x) * 4;
            p[0] = (unsigned char)x, p[1] = (unsigned char)(255 - x), p[2] = (unsigned char)(x * 7), p[3] = (unsigned char)y;
        }
    for (int flip = 0; flip < 2; ++flip) {
        mvr_image_view v = {.width = 256, .height = 256, .type = MVR_PIXEL_U8, .bottom_up = flip != 0, .pixels = px};
        char a[512], o[512];
        snprintf(a, sizeof a, "%s/front_%d.png", out_dir(), flip);
        snprintf(o, sizeof o, "%s/oiio_%d.png", out_dir(), flip);
        mvr_error err = {0};
        CHECK_MSG(t, mvr_png_write(a, &v, &err) == MVR_FRONT_OK, "%s", err.message);
        CHECK_MSG(t, m->write(o, &v, &err) == MVR_OK, "%s", err.message);
        uint32_t aw = 0, ah = 0, ow = 0, oh = 0;
        bool as = false, os = false;
        unsigned char *ap = stored_rgba(a, &aw, &ah, &as), *op = stored_rgba(o, &ow, &oh, &os);
        CHECK_MSG(t, ap && op, "not both RGBA8 files (%s, %s)", a, o);
        if (ap && op) {
            CHECK(t, aw == ow && ah == oh);
            size_t diff = 0;
            for (size_t i = 0; i < 256u * 256u * 4u; ++i)
                diff += ap[i] != op[i];
            CHECK_MSG(t, diff == 0, "bottom_up %d: %zu stored values differ from OpenImageIO's file", flip, diff);
            CHECK_MSG(t, as && os, "sRGB chunk: front %d, OpenImageIO %d", as, os);
        }
        free(ap);
        free(op);
        /* and both read back alike through either decoder */
        mvr_image_data ra = {0}, ro = {0};
        CHECK_MSG(t, mvr_image_read(a, MVR_PIXEL_U8, &ra, &err) == MVR_OK, "%s", err.message);
        CHECK_MSG(t, m->read(o, MVR_PIXEL_U8, MVR_IMAGE_DEFAULT_MEMORY_BUDGET, 0, &ro, &err) == MVR_OK, "%s", err.message);
        if (ra.pixels && ro.pixels)
            CHECK(t, memcmp(ra.pixels, ro.pixels, 256u * 256u * 4u) == 0);
        mvr_image_free(&ra);
        mvr_image_free(&ro);
    }
    free(px);
}

static void refused_by_both(mvr_test_state *t)
{
    const mvr_image_backend *m = module_or_fail(t);
    if (!m)
        return;
    png_spec good = {.width = 40, .height = 30, .color = PNG_COLOR_TYPE_RGB_ALPHA, .depth = 8, .srgb = -1};
    png_spec bad_crc = good, interlaced_crc = good;
    bad_crc.bad_crc = true;
    interlaced_crc.bad_crc = interlaced_crc.interlace = true;
    const png_spec *specs[] = {&bad_crc, &interlaced_crc};
    for (size_t i = 0; i < 2; ++i) {
        bytes b;
        CHECK(t, make_png(specs[i], NULL, 7, &b));
        mvr_bytes_source src = {.data = b.data, .size = b.size};
        mvr_image_data d = {0};
        mvr_error e = {0}, oe = {0};
        CHECK(t, mvr_png_decode(&src, 0, 0, "bad crc", &d, &e) == MVR_FRONT_FAILED);
        CHECK(t, m->decode(b.data, b.size, NULL, 0, MVR_IMAGE_DEFAULT_MEMORY_BUDGET, 0, &d, &oe) != MVR_OK);
        CHECK(t, mvr_image_decode(b.data, b.size, NULL, 0, &d, &e) == MVR_ERROR_INVALID_ASSET);
        CHECK(t, d.pixels == NULL);
        free(b.data);
    }
    /* truncated: the framing check refuses it before either decoder */
    bytes b;
    CHECK(t, make_png(&good, NULL, 8, &b));
    mvr_image_data d = {0};
    mvr_error e = {0};
    CHECK(t, mvr_image_decode(b.data, b.size / 2, "image/png", 0, &d, &e) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(e.message, "truncated") != NULL, "%s", e.message);
    /* over the caller's cap: refused by the front itself, naming the size */
    CHECK(t, mvr_image_decode(b.data, b.size, "image/png", 39, &d, &e) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(e.message, "40x30 is not within 1..39") != NULL, "%s", e.message);
    mvr_bytes_source src = {.data = b.data, .size = b.size};
    CHECK(t, mvr_png_decode(&src, 39, 0, "cap", &d, &e) == MVR_FRONT_FAILED);
    /* a MIME type that disagrees with the bytes */
    CHECK(t, mvr_image_decode(b.data, b.size, "image/jpeg", 0, &d, &e) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(e.message, "mimeType 'image/jpeg' but the bytes are png") != NULL, "%s", e.message);
    free(b.data);
    /* a file of another kind, read by path as 8 bits: OpenImageIO's answer */
    mvr_image_data sky = {0};
    CHECK(t, mvr_image_read(MVR_PEERS_DIR "/sky.hdr", MVR_PIXEL_U8, &sky, &e) == MVR_OK);
    mvr_image_free(&sky);
    CHECK(t, mvr_image_read(MVR_PEERS_DIR "/no_such_file.png", MVR_PIXEL_U8, &sky, &e) == MVR_ERROR_IO);
    CHECK_MSG(t, strstr(e.message, "no_such_file.png") != NULL, "%s", e.message);
    /* an EXR header cut short: OpenEXR reports it by throwing inside the
     * module (the sanitizer build checks that a C program survives that) */
    char bad[512];
    snprintf(bad, sizeof bad, "%s/cut.exr", out_dir());
    float one[4] = {1, 1, 1, 1};
    mvr_image_view f = {.width = 1, .height = 1, .type = MVR_PIXEL_F32, .pixels = one};
    CHECK_MSG(t, mvr_image_write(bad, &f, &e) == MVR_OK, "%s", e.message);
    bytes exr;
    CHECK(t, read_file(bad, &exr));
    FILE *cut = fopen(bad, "wb");
    CHECK(t, cut && fwrite(exr.data, 1, exr.size / 3, cut) == exr.size / 3);
    if (cut)
        fclose(cut);
    free(exr.data);
    CHECK(t, mvr_image_read(bad, MVR_PIXEL_F32, &sky, &e) != MVR_OK);
    CHECK(t, sky.pixels == NULL);
}

/* ------------------------------------------ with MVR_IMAGE_MODULE pointed away */

static void module_unavailable(mvr_test_state *t, const char *expect)
{
    const char *forced = getenv(MVR_IMAGE_MODULE_ENV);
    CHECK_MSG(t, forced && *forced, MVR_IMAGE_MODULE_ENV " is not set (ctest sets it)");
    if (!forced)
        return;
    mvr_image_data sky = {0};
    mvr_error err = {0};
    for (int attempt = 0; attempt < 2; ++attempt) {   /* the failure is remembered, the message the same */
        CHECK(t, mvr_image_read(MVR_PEERS_DIR "/sky.hdr", MVR_PIXEL_F32, &sky, &err) == MVR_ERROR_UNSUPPORTED);
        CHECK_MSG(t, strstr(err.message, "mvr_image_read(") == err.message, "%s", err.message);
        CHECK_MSG(t, strstr(err.message, MVR_IMAGE_MODULE_FILE) != NULL, "does not name the module: %s", err.message);
        CHECK_MSG(t, strstr(err.message, forced) != NULL, "does not name %s: %s", forced, err.message);
        CHECK_MSG(t, strstr(err.message, expect) != NULL, "does not say '%s': %s", expect, err.message);
    }
    printf("  %s\n", err.message);
    mvr_image_compare_result r;
    /* opaque: a colour with alpha < 255 comes back associated, not as written */
    mvr_image_view v = {.width = 1, .height = 1, .type = MVR_PIXEL_U8, .pixels = "abc\377"};
    CHECK(t, mvr_image_compare(&v, &v, 0, NULL, &r, &err) == MVR_ERROR_UNSUPPORTED);
    CHECK(t, strstr(err.message, MVR_IMAGE_MODULE_FILE) != NULL);
    /* PNG goes on without it */
    char path[512];
    snprintf(path, sizeof path, "%s/without_module.png", out_dir());
    CHECK_MSG(t, mvr_image_write(path, &v, &err) == MVR_OK, "%s", err.message);
    mvr_image_data back = {0};
    CHECK_MSG(t, mvr_image_read(path, MVR_PIXEL_U8, &back, &err) == MVR_OK, "%s", err.message);
    CHECK(t, back.pixels && memcmp(back.pixels, "abc\377", 4) == 0);
    mvr_image_free(&back);
    /* a deferred PNG (alpha with an ICC profile) reports the front's reason and the module's */
    png_spec s = {.width = 8, .height = 8, .color = PNG_COLOR_TYPE_RGB_ALPHA, .depth = 8, .srgb = -1, .icc = true};
    bytes b;
    CHECK(t, make_png(&s, NULL, 3, &b));
    CHECK(t, mvr_image_decode(b.data, b.size, NULL, 0, &back, &err) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(err.message, "mvr_image_decode: ") == err.message && strstr(err.message, MVR_IMAGE_MODULE_FILE),
              "%s", err.message);
    free(b.data);
    /* a corrupt one is the front's final answer: libpng's reason, no module needed */
    png_spec c = {.width = 8, .height = 8, .color = PNG_COLOR_TYPE_RGB, .depth = 8, .srgb = -1, .bad_crc = true};
    CHECK(t, make_png(&c, NULL, 3, &b));
    CHECK(t, mvr_image_decode(b.data, b.size, NULL, 0, &back, &err) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(err.message, "incorrect data check") && !strstr(err.message, MVR_IMAGE_MODULE_FILE), "%s",
              err.message);
    free(b.data);
}

static void module_missing(mvr_test_state *t)
{
    module_unavailable(t, "cannot open shared object file");
}

static void module_foreign(mvr_test_state *t)
{
    module_unavailable(t, "is not of this mvr");
}

int main(int argc, char **argv)
{
    mkdir(out_dir(), 0755);
    if (argc > 1 && strcmp(argv[1], "--module-missing") == 0) {
        static const mvr_test_case cases[] = {TEST(module_missing)};
        return mvr_test_run(cases, 1);
    }
    if (argc > 1 && strcmp(argv[1], "--module-foreign") == 0) {
        static const mvr_test_case cases[] = {TEST(module_foreign)};
        return mvr_test_run(cases, 1);
    }
    static const mvr_test_case cases[] = {
        TEST(png_work_leaves_openimageio_unloaded), TEST(every_png_of_the_repository), TEST(generated_layouts),
        TEST(alpha_association_exhaustive),         TEST(writers_agree),               TEST(refused_by_both),
    };
    return mvr_test_run(cases, sizeof cases / sizeof cases[0]);
}
