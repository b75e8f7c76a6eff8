/*
 * mvr_image's JPEG front (core/io/image_jpeg.c, libjpeg-turbo) against
 * OpenImageIO (the module core/io/image_oiio.cpp, which decoded every JPEG
 * before):
 *  - JPEGs this test writes with libjpeg (greyscale and RGB; baseline,
 *    progressive and non-interleaved multi-scan; 4:4:4, 4:2:2 and 4:2:0;
 *    restart markers; odd sizes) decode to the same header and exactly the
 *    same pixels through both, and mvr_image_decode_cost gives what it gave;
 *  - CMYK and YCCK are deferred, and mvr_image_decode gives OpenImageIO's pixels;
 *  - JPEG probe / decode / read never load OpenImageIO into the process;
 *  - truncated, corrupt and oversized JPEGs: a clear error naming the call,
 *    checked before allocation, never a crash (libjpeg's errors longjmp back
 *    into image_jpeg.c), and corrupt entropy data decodes as OpenImageIO does.
 * This program links neither OpenImageIO nor the C++ runtime itself.
 */
/* jpeglib.h uses size_t and FILE without including their headers */
#include <stddef.h>
#include <stdio.h>

#include <jpeglib.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "image_internal.h"
#include "mvr_test.h"

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

/* ------------------------------------------------------- the generator */

typedef enum layout { BASELINE, PROGRESSIVE, MULTISCAN } layout;

typedef struct jpeg_spec {
    uint32_t width, height;
    J_COLOR_SPACE in_space;      /* JCS_GRAYSCALE, JCS_RGB, JCS_CMYK */
    J_COLOR_SPACE file_space;    /* what the file stores (JCS_YCbCr, JCS_RGB, JCS_YCCK, ...) */
    int h_samp, v_samp;          /* the first component's sampling factors (1 or 2) */
    layout scans;
    int quality;
    unsigned restart_rows;       /* 0: no restart markers */
} jpeg_spec;

/* A sample with structure and noise, so every block has coefficients. */
static unsigned char sample(uint32_t x, uint32_t y, int c)
{
    uint32_t v = (x * 7u + y * 3u + (uint32_t)c * 50u) ^ ((x * y * 2654435761u) >> 27);
    return (unsigned char)(v + (uint32_t)c * 31u);
}

/* Writes a JPEG as libjpeg's compressor makes it into *out (malloc'd). */
static bool make_jpeg(const jpeg_spec *s, unsigned char **out, unsigned long *size)
{
    struct jpeg_compress_struct c;
    struct jpeg_error_mgr err;
    c.err = jpeg_std_error(&err);
    jpeg_create_compress(&c);
    *out = NULL;
    *size = 0;
    jpeg_mem_dest(&c, out, size);
    int nc = s->in_space == JCS_GRAYSCALE ? 1 : s->in_space == JCS_CMYK ? 4 : 3;
    c.image_width = s->width;
    c.image_height = s->height;
    c.input_components = nc;
    c.in_color_space = s->in_space;
    jpeg_set_defaults(&c);
    jpeg_set_colorspace(&c, s->file_space);
    jpeg_set_quality(&c, s->quality, TRUE);
    c.comp_info[0].h_samp_factor = s->h_samp;
    c.comp_info[0].v_samp_factor = s->v_samp;
    for (int k = 1; k < c.num_components; ++k)
        c.comp_info[k].h_samp_factor = c.comp_info[k].v_samp_factor = 1;
    c.restart_in_rows = (int)s->restart_rows;
    if (s->scans == PROGRESSIVE)
        jpeg_simple_progression(&c);
    static jpeg_scan_info one_per_component[4];
    if (s->scans == MULTISCAN) {
        /* sequential, each component in a scan of its own (non-interleaved) */
        for (int k = 0; k < c.num_components; ++k) {
            jpeg_scan_info *si = &one_per_component[k];
            memset(si, 0, sizeof *si);
            si->comps_in_scan = 1;
            si->component_index[0] = k;
            si->Ss = 0;
            si->Se = 63;
        }
        c.scan_info = one_per_component;
        c.num_scans = c.num_components;
    }
    jpeg_start_compress(&c, TRUE);
    unsigned char *row = malloc((size_t)s->width * (size_t)nc);
    while (c.next_scanline < c.image_height) {
        for (uint32_t x = 0; x < s->width; ++x)
            for (int k = 0; k < nc; ++k)
                row[(size_t)x * (size_t)nc + (size_t)k] = sample(x, c.next_scanline, k);
        JSAMPROW r[1] = {row};
        jpeg_write_scanlines(&c, r, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    free(row);
    return *out && *size > 0;
}

static const mvr_image_backend *module_or_fail(mvr_test_state *t)
{
    mvr_error err = {0};
    const mvr_image_backend *m = mvr_image_module("test_image_jpeg", &err);
    CHECK_MSG(t, m != NULL, "%s", err.message);
    return m;
}

/* Both decoders on one file: same header, same pixels, same cost through
 * the public call; returns the front's status. */
static mvr_front_status compare_decoders(mvr_test_state *t, const mvr_image_backend *m, const unsigned char *b,
                                         size_t n, const char *what)
{
    mvr_error fe = {0}, oe = {0};
    mvr_image_header fh = {0}, oh = {0};
    mvr_bytes_source src = {.data = b, .size = n};
    mvr_front_status ps = mvr_jpeg_probe(&src, &fh, &fe);
    mvr_result pr = m->probe(b, n, "image/jpeg", &oh, &oe);
    if (ps == MVR_FRONT_OK) {
        CHECK_MSG(t, pr == MVR_OK, "%s: the front probes, OpenImageIO refuses: %s", what, oe.message);
        CHECK_MSG(t, fh.width == oh.width && fh.height == oh.height && fh.channels == oh.channels,
                  "%s: header %ux%u/%u, OpenImageIO %ux%u/%u", what, fh.width, fh.height, fh.channels, oh.width,
                  oh.height, oh.channels);
        CHECK_MSG(t, strcmp(fh.format, oh.format) == 0, "%s: format %s vs %s", what, fh.format, oh.format);
    }
    mvr_image_data fd = {0}, od = {0};
    mvr_front_status ds = mvr_jpeg_decode(&src, 0, 0, 0, what, &fd, &fe);
    mvr_result dr = m->decode(b, n, "image/jpeg", 0, MVR_IMAGE_DEFAULT_MEMORY_BUDGET, 0, &od, &oe);
    if (ds == MVR_FRONT_OK) {
        CHECK_MSG(t, dr == MVR_OK, "%s: the front decodes, OpenImageIO refuses: %s", what, oe.message);
        if (dr == MVR_OK && fd.width == od.width && fd.height == od.height) {
            const unsigned char *a = fd.pixels, *o = od.pixels;
            size_t count = (size_t)fd.width * fd.height * 4, diff = 0, first = 0;
            for (size_t i = 0; i < count; ++i)
                if (a[i] != o[i] && diff++ == 0)
                    first = i;
            CHECK_MSG(t, diff == 0, "%s: %zu of %zu values differ; first at pixel %zu channel %zu: %u vs OpenImageIO %u",
                      what, diff, count, first / 4, first % 4, a[first], o[first]);
        } else if (dr == MVR_OK) {
            CHECK_MSG(t, false, "%s: %ux%u, OpenImageIO %ux%u", what, fd.width, fd.height, od.width, od.height);
        }
        /* the public cost: OpenImageIO's figure plus the front's held bytes */
        uint64_t cost = 0, ocost = 0;
        mvr_error ce = {0};
        CHECK_MSG(t, mvr_image_decode_cost(b, n, "image/jpeg", &cost, &ce) == MVR_OK, "%s: %s", what, ce.message);
        CHECK_MSG(t, m->decode_cost(b, n, "image/jpeg", &ocost, &ce) == MVR_OK, "%s: %s", what, ce.message);
        CHECK_MSG(t, cost >= ocost, "%s: cost %llu under OpenImageIO's %llu", what, (unsigned long long)cost,
                  (unsigned long long)ocost);
    } else if (ds == MVR_FRONT_FAILED) {
        CHECK_MSG(t, dr != MVR_OK, "%s: the front refuses (%s), OpenImageIO decodes", what, fe.message);
    } else {
        mvr_image_data pd = {0};
        mvr_error pe = {0};
        mvr_result r = mvr_image_decode(b, n, "image/jpeg", 0, &pd, &pe);
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

/* ------------------------------------------------------------------ cases */

/* First: nothing before it may have needed the module. */
static void jpeg_work_leaves_openimageio_unloaded(mvr_test_state *t)
{
    CHECK_MSG(t, loaded("libmvr_image_oiio") == 0, "the module is mapped before any image call");
    jpeg_spec specs[] = {{40, 30, JCS_RGB, JCS_YCbCr, 2, 2, PROGRESSIVE, 90, 0},
                         {40, 30, JCS_GRAYSCALE, JCS_GRAYSCALE, 1, 1, BASELINE, 90, 0}};
    for (size_t k = 0; k < 2; ++k) {
        unsigned char *b = NULL;
        unsigned long n = 0;
        CHECK(t, make_jpeg(&specs[k], &b, &n));
        mvr_error err = {0};
        mvr_image_header h = {0};
        CHECK_MSG(t, mvr_image_probe(b, n, "image/jpeg", &h, &err) == MVR_OK, "%s", err.message);
        CHECK(t, h.width == 40 && h.height == 30 && h.channels == (k ? 1u : 3u) && strcmp(h.format, "jpeg") == 0);
        uint64_t cost = 0;
        CHECK_MSG(t, mvr_image_decode_cost(b, n, "image/jpg", &cost, &err) == MVR_OK, "%s", err.message);
        mvr_image_data d = {0}, r = {0};
        CHECK_MSG(t, mvr_image_decode(b, n, NULL, 0, &d, &err) == MVR_OK, "%s", err.message);
        char path[512];
        snprintf(path, sizeof path, "%s/front_%zu.jpg", MVR_IMAGE_JPEG_OUT, k);
        FILE *f = fopen(path, "wb");
        CHECK(t, f && fwrite(b, 1, n, f) == n);
        if (f)
            fclose(f);
        CHECK_MSG(t, mvr_image_read(path, MVR_PIXEL_U8, &r, &err) == MVR_OK, "%s", err.message);
        CHECK(t, d.pixels && r.pixels && d.width == 40 && memcmp(d.pixels, r.pixels, 40 * 30 * 4) == 0);
        mvr_image_free(&d);
        mvr_image_free(&r);
        free(b);
    }
    CHECK_MSG(t, loaded("libmvr_image_oiio") == 0, "JPEG probe / decode_cost / decode / read loaded the module");
    CHECK_MSG(t, loaded("libOpenImageIO") == 0, "JPEG probe / decode_cost / decode / read loaded OpenImageIO");
}

static void generated_layouts(mvr_test_state *t)
{
    const mvr_image_backend *m = module_or_fail(t);
    if (!m)
        return;
    static const uint32_t sizes[][2] = {{1, 1}, {17, 9}, {64, 48}, {333, 129}};
    static const int sampling[][2] = {{1, 1}, {2, 1}, {2, 2}};   /* 4:4:4, 4:2:2, 4:2:0 */
    int cases = 0, ok = 0;
    for (size_t si = 0; si < 4; ++si)
        for (int space = 0; space < 3; ++space)           /* grey, YCbCr, RGB stored as RGB (Adobe) */
            for (size_t sm = 0; sm < 3; ++sm)
                for (int scans = BASELINE; scans <= MULTISCAN; ++scans)
                    for (int q = 0; q < 2; ++q) {
                        if (space != 1 && sm > 0)
                            continue;   /* subsampling: YCbCr only */
                        jpeg_spec s = {sizes[si][0], sizes[si][1], space == 0 ? JCS_GRAYSCALE : JCS_RGB,
                                       space == 0 ? JCS_GRAYSCALE : space == 1 ? JCS_YCbCr : JCS_RGB,
                                       sampling[sm][0], sampling[sm][1], (layout)scans, q ? 97 : 40,
                                       (unsigned)(q && scans == BASELINE)};
                        unsigned char *b = NULL;
                        unsigned long n = 0;
                        char what[160];
                        snprintf(what, sizeof what, "%ux%u space %d sampling %dx%d scans %d quality %d", s.width,
                                 s.height, space, s.h_samp, s.v_samp, scans, s.quality);
                        CHECK_MSG(t, make_jpeg(&s, &b, &n), "%s: not written", what);
                        ++cases;
                        mvr_front_status st = compare_decoders(t, m, b, n, what);
                        CHECK_MSG(t, st == MVR_FRONT_OK, "%s: not decoded by the front", what);
                        ok += st == MVR_FRONT_OK;
                        free(b);
                    }
    printf("  %d generated JPEGs, %d decoded by the front, pixels equal to OpenImageIO's\n", cases, ok);
}

static void cmyk_deferred(mvr_test_state *t)
{
    const mvr_image_backend *m = module_or_fail(t);
    if (!m)
        return;
    for (int ycck = 0; ycck < 2; ++ycck) {
        jpeg_spec s = {24, 16, JCS_CMYK, ycck ? JCS_YCCK : JCS_CMYK, 1, 1, BASELINE, 90, 0};
        unsigned char *b = NULL;
        unsigned long n = 0;
        CHECK(t, make_jpeg(&s, &b, &n));
        mvr_front_status st = compare_decoders(t, m, b, n, ycck ? "YCCK" : "CMYK");
        CHECK_MSG(t, st == MVR_FRONT_DEFER, "%s: not deferred (%d)", ycck ? "YCCK" : "CMYK", (int)st);
        mvr_image_data d = {0};
        mvr_error e = {0};
        CHECK_MSG(t, mvr_image_decode(b, n, "image/jpeg", 0, &d, &e) == MVR_OK, "%s", e.message);
        CHECK(t, d.width == 24 && d.height == 16);
        mvr_image_free(&d);
        free(b);
    }
}

/* A big-endian 16-bit value at p. */
static void put16(unsigned char *p, unsigned v)
{
    p[0] = (unsigned char)(v >> 8);
    p[1] = (unsigned char)(v & 0xFF);
}

/* The offset of the first marker m (FF m) after SOI, or 0. */
static size_t find_marker(const unsigned char *b, size_t n, unsigned char m)
{
    for (size_t i = 2; i + 1 < n; ++i)
        if (b[i] == 0xFF && b[i + 1] == m)
            return i;
    return 0;
}

static void hostile(mvr_test_state *t)
{
    const mvr_image_backend *m = module_or_fail(t);
    jpeg_spec s = {96, 64, JCS_RGB, JCS_YCbCr, 2, 2, PROGRESSIVE, 90, 0};
    unsigned char *b = NULL;
    unsigned long n = 0;
    CHECK(t, make_jpeg(&s, &b, &n));
    mvr_error e = {0};
    mvr_image_data d = {0};
    /* truncated anywhere: refused by the front's framing check, naming why */
    for (size_t cut = 3; cut < n; cut += n / 23 + 1) {
        CHECK(t, mvr_image_decode(b, cut, "image/jpeg", 0, &d, &e) == MVR_ERROR_INVALID_ASSET);
        CHECK_MSG(t, strstr(e.message, "mvr_image_decode") && (strstr(e.message, "truncated") || strstr(e.message, "JPEG")),
                  "cut at %zu: %s", cut, e.message);
        /* and the decoder alone (no framing check) never crashes on it */
        mvr_bytes_source src = {.data = b, .size = cut};
        mvr_image_data alone = {0};
        (void)mvr_jpeg_decode(&src, 0, 0, 0, "alone", &alone, &e);
        mvr_image_free(&alone);
    }
    /* corrupt entropy-coded data: decoded through as OpenImageIO does */
    size_t sos = find_marker(b, n, 0xDA);
    CHECK(t, sos > 0);
    unsigned char *c = malloc(n);
    for (int k = 0; k < 8 && m; ++k) {
        memcpy(c, b, n);
        size_t at = sos + 20 + (size_t)k * ((n - sos - 30) / 8);
        c[at] ^= (unsigned char)(0x5A + k);
        if (c[at] == 0xFF)
            c[at] = 0x00;
        char what[64];
        snprintf(what, sizeof what, "corrupt byte %zu", at);
        (void)compare_decoders(t, m, c, n, what);
    }
    /* a corrupt header: refused with libjpeg's reason, naming the call */
    size_t dqt = find_marker(b, n, 0xDB);
    memcpy(c, b, n);
    put16(c + dqt + 2, 1);
    CHECK(t, mvr_image_decode(c, n, "image/jpeg", 0, &d, &e) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(e.message, "mvr_image_decode") != NULL, "%s", e.message);
    /* a SOF that says 0 rows, and one that says 65000 x 65000 */
    size_t sof = find_marker(b, n, 0xC2);
    CHECK(t, sof > 0);
    memcpy(c, b, n);
    put16(c + sof + 5, 0);
    CHECK(t, mvr_image_decode(c, n, "image/jpeg", 0, &d, &e) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(e.message, "mvr_image_decode") != NULL, "0 rows: %s", e.message);
    memcpy(c, b, n);
    put16(c + sof + 5, 65000);
    put16(c + sof + 7, 65000);
    CHECK(t, mvr_image_decode(c, n, "image/jpeg", 0, &d, &e) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(e.message, "65000x65000 is not within 1..16384") != NULL, "%s", e.message);
    /* within the caps but over the memory budget: refused before allocating */
    put16(c + sof + 5, 16000);
    put16(c + sof + 7, 16000);
    CHECK(t, mvr_image_decode_within(c, n, "image/jpeg", 0, 64u << 20, &d, &e) == MVR_ERROR_OUT_OF_MEMORY);
    CHECK_MSG(t, strstr(e.message, "16000x16000") && strstr(e.message, "memory budget"), "%s", e.message);
    /* the caller's cap */
    CHECK(t, mvr_image_decode(b, n, "image/jpeg", 95, &d, &e) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(e.message, "96x64 is not within 1..95") != NULL, "%s", e.message);
    CHECK(t, d.pixels == NULL);
    free(c);
    free(b);
}

int main(void)
{
    mkdir(MVR_IMAGE_JPEG_OUT, 0755);
    static const mvr_test_case cases[] = {
        TEST(jpeg_work_leaves_openimageio_unloaded),
        TEST(generated_layouts),
        TEST(cmyk_deferred),
        TEST(hostile),
    };
    return mvr_test_run(cases, sizeof cases / sizeof cases[0]);
}
