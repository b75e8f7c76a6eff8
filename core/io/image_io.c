/*
 * mvr_image's C front (include/mvr/mvr_image.h): the decoder is picked from
 * the bytes' signature, never from a name; PNG is done here through libpng
 * (image_png.c), JPEG through libjpeg-turbo (image_jpeg.c), and everything
 * else (and what those two defer) by OpenImageIO in libmvr_image_oiio.so,
 * loaded the first time a call needs it (image_internal.h says why).
 *
 * The module is searched, in this order:
 *  1. $MVR_IMAGE_MODULE (a file: then nowhere else);
 *  2. next to the object holding this code (libmvr_image.so's folder, or the
 *     executable's when mvr_image is linked statically), then that folder's
 *     parent (the build tree's tests/ programs) and ../<libdir> (an installed
 *     bin/ program);
 *  3. by name, as dlopen() searches (the caller's RUNPATH, LD_LIBRARY_PATH,
 *     the system's library folders);
 *  4. the library folder of the install prefix mvr was configured with.
 * It is loaded once per process (pthread_once), kept until exit (never
 * dlclose'd, so leak reports keep its symbols), and a failure to load it is
 * remembered: every call that needs it gets the same message, naming the
 * files tried and dlerror()'s reason.
 */
#define _GNU_SOURCE   /* dladdr1, RTLD_DL_LINKMAP, secure_getenv */
#include <dlfcn.h>
#include <errno.h>
#include <link.h>
#include <limits.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "image_internal.h"

#ifndef MVR_IMAGE_INSTALL_LIBDIR
#define MVR_IMAGE_INSTALL_LIBDIR ""
#endif
#ifndef MVR_IMAGE_LIBDIR_NAME
#define MVR_IMAGE_LIBDIR_NAME "lib"
#endif

mvr_result mvr_image_fail(mvr_error *error, mvr_result r, const char *fmt, ...)
{
    if (error) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(error->message, sizeof error->message, fmt, ap);
        va_end(ap);
        error->result = r;
    }
    return r;
}

void *mvr_image_alloc_pixels(size_t bytes)
{
    void *p = malloc(bytes);
#ifdef MADV_HUGEPAGE
    /* written once, row after row, right after this: in 2 MiB pages where
     * the kernel's transparent huge pages are on for madvise()d memory, one
     * page fault per 2 MiB instead of 512 (the faults of a 2048x2048
     * texture's 16 MiB were a third of a textured file's first image) */
    const uintptr_t huge = (uintptr_t)2 << 20;
    if (p && bytes >= 2 * huge) {
        uintptr_t from = ((uintptr_t)p + huge - 1) & ~(huge - 1), to = ((uintptr_t)p + bytes) & ~(huge - 1);
        if (to > from)
            (void)madvise((void *)from, to - from, MADV_HUGEPAGE);   /* advice: refused, nothing changes */
    }
#endif
    return p;
}

/* ---------------------------------------------------------------- the module */

/* The one process-wide state of mvr_image: which module was loaded, or why
 * none could be. Written once under pthread_once, read-only after. */
static pthread_once_t module_once = PTHREAD_ONCE_INIT;
static const mvr_image_backend *module_table;
static char module_failure[MVR_ERROR_MESSAGE_SIZE];

/* The folder of the object this code is linked into: libmvr_image.so, or the
 * executable (whose link map has an empty name). */
static bool own_folder(char *dir, size_t size)
{
    Dl_info info;
    struct link_map *map = NULL;
    char path[PATH_MAX];
    path[0] = '\0';
    if (dladdr1((const void *)&module_once, &info, (void **)&map, RTLD_DL_LINKMAP) && map && map->l_name &&
        map->l_name[0]) {
        snprintf(path, sizeof path, "%s", map->l_name);
    } else {
        ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
        if (n <= 0)
            return false;
        path[n] = '\0';
    }
    char *slash = strrchr(path, '/');
    if (!slash)
        return false;
    *slash = '\0';
    snprintf(dir, size, "%s", path[0] ? path : "/");
    return true;
}

/* dlopen()s one candidate: on success its name goes to `opened`, on failure
 * "dlerror()" is appended to `tried`. */
static void *try_open(const char *file, char *opened, size_t opened_size, char *tried, size_t size)
{
    void *h = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    if (h) {
        snprintf(opened, opened_size, "%s", file);
    } else {
        const char *why = dlerror();
        size_t used = strlen(tried);
        snprintf(tried + used, size - used, "%s%s", used ? "; " : "", why ? why : file);
    }
    return h;
}

static void load_module(void)
{
    char tried[MVR_ERROR_MESSAGE_SIZE] = "";
    char opened[PATH_MAX + 64] = "";
    char file[PATH_MAX + 64];
    void *h = NULL;
    /* not for a set-user-ID program: another user would choose the code it runs */
    const char *forced = secure_getenv(MVR_IMAGE_MODULE_ENV);
    if (forced && *forced) {
        h = try_open(forced, opened, sizeof opened, tried, sizeof tried);
    } else {
        char dir[PATH_MAX];
        if (own_folder(dir, sizeof dir)) {
            const char *rel[] = {"", "/..", "/../" MVR_IMAGE_LIBDIR_NAME};
            bool any = false;
            for (size_t i = 0; !h && i < sizeof rel / sizeof rel[0]; ++i) {
                snprintf(file, sizeof file, "%s%s/%s", dir, rel[i], MVR_IMAGE_MODULE_FILE);
                if (access(file, F_OK) == 0) {
                    any = true;
                    h = try_open(file, opened, sizeof opened, tried, sizeof tried);
                }
            }
            if (!any)
                snprintf(tried, sizeof tried, "not in %.300s, its parent or ../%s", dir, MVR_IMAGE_LIBDIR_NAME);
        }
        if (!h)
            h = try_open(MVR_IMAGE_MODULE_FILE, opened, sizeof opened, tried, sizeof tried);
        if (!h && MVR_IMAGE_INSTALL_LIBDIR[0]) {
            snprintf(file, sizeof file, "%s/%s", MVR_IMAGE_INSTALL_LIBDIR, MVR_IMAGE_MODULE_FILE);
            if (access(file, F_OK) == 0)
                h = try_open(file, opened, sizeof opened, tried, sizeof tried);
        }
    }
    if (!h) {
        snprintf(module_failure, sizeof module_failure,
                 "the OpenImageIO module %s could not be loaded (%.380s; set " MVR_IMAGE_MODULE_ENV " to its path)",
                 MVR_IMAGE_MODULE_FILE, tried);
        return;
    }
    /* POSIX: a data pointer converts to a function pointer (dlsym) */
    mvr_image_backend_entry entry;
    void *sym = dlsym(h, MVR_IMAGE_MODULE_ENTRY);
    memcpy(&entry, &sym, sizeof entry);
    const mvr_image_backend *table = entry ? entry(MVR_IMAGE_MODULE_ABI) : NULL;
    if (!table || table->abi != MVR_IMAGE_MODULE_ABI || table->size != sizeof *table) {
        snprintf(module_failure, sizeof module_failure,
                 "the OpenImageIO module %s: %.300s is not of this mvr (no %s for ABI %u)", MVR_IMAGE_MODULE_FILE, opened,
                 MVR_IMAGE_MODULE_ENTRY, MVR_IMAGE_MODULE_ABI);
        /* kept loaded: a library whose initialisers ran is not unloaded */
        return;
    }
    module_table = table;
}

const mvr_image_backend *mvr_image_module(const char *who, mvr_error *error)
{
    if (pthread_once(&module_once, load_module) != 0) {
        mvr_image_fail(error, MVR_ERROR_INTERNAL, "%s: pthread_once failed", who);
        return NULL;
    }
    if (!module_table)
        mvr_image_fail(error, MVR_ERROR_UNSUPPORTED, "%s: %s", who, module_failure);
    return module_table;
}

/* ------------------------------------------------------------ formats, bytes */

/* Formats mvr decodes, told apart by their signatures (PNG: ISO/IEC 15948,
 * 5.2; JPEG: ISO/IEC 10918-1 SOI marker FF D8 FF; WebP: RIFF....WEBP). */
typedef struct image_format {
    const char *name;            /* mvr_image_header.format */
    const char *mime;
} image_format;

static const image_format format_png = {"png", "image/png"};
static const image_format format_jpeg = {"jpeg", "image/jpeg"};
static const image_format format_webp = {"webp", "image/webp"};

static const image_format *format_of_bytes(const unsigned char *p, size_t n)
{
    static const unsigned char png_sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    if (n >= 8 && memcmp(p, png_sig, 8) == 0)
        return &format_png;
    if (n >= 3 && p[0] == 0xFF && p[1] == 0xD8 && p[2] == 0xFF)
        return &format_jpeg;
    if (n >= 12 && memcmp(p, "RIFF", 4) == 0 && memcmp(p + 8, "WEBP", 4) == 0)
        return &format_webp;
    return NULL;
}

/* The declared MIME type (glTF 2.0, 5.19: image/jpeg or image/png; WebP by
 * EXT_texture_webp) must name what the bytes are. */
static bool mime_agrees(const char *mime, const image_format *f)
{
    if (!mime || !*mime)
        return true;
    if (strcmp(mime, "image/jpg") == 0)
        mime = "image/jpeg"; /* a common misspelling, same format */
    return strcmp(mime, f->mime) == 0;
}

/* At most 80 characters of a value that came from a file, quoted, for a message. */
static const char *short_value(const char *v, char *buf, size_t size)
{
    char text[88];
    size_t n = v ? strlen(v) : 0;
    snprintf(text, sizeof text, "%.80s%s", v ? v : "", n > 80 ? "..." : "");
    for (char *c = text; *c; ++c)
        if ((unsigned char)*c < 0x20)
            *c = '?';
    snprintf(buf, size, "'%s'", text);
    return buf;
}

/* PNG framing (ISO/IEC 15948, 5.3): the signature, then chunks of length +
 * type + data + CRC, the last one IEND, all inside the bytes. Checked before
 * either decoder runs: a truncated file is refused with a clear message
 * (and OpenImageIO 2.4's PNG reader leaks when libpng stops it mid-read). */
static bool png_framing_ok(const unsigned char *p, size_t n, char *why, size_t why_size)
{
    size_t at = 8;
    while (at + 12 <= n) {
        uint32_t len = (uint32_t)p[at] << 24 | (uint32_t)p[at + 1] << 16 | (uint32_t)p[at + 2] << 8 | p[at + 3];
        if (len > 0x7FFFFFFFu || (uint64_t)at + 12 + len > n) {
            snprintf(why, why_size, "PNG chunk at byte %zu runs past the end of the data (truncated?)", at);
            return false;
        }
        if (memcmp(p + at + 4, "IEND", 4) == 0)
            return true;
        at += 12 + (size_t)len;
    }
    snprintf(why, why_size, "PNG has no IEND chunk (truncated?)");
    return false;
}

/* Bytes to walk: in memory (p, n, at) or a file (f). */
typedef struct byte_stream {
    const unsigned char *p;
    size_t n, at;
    FILE *f;
} byte_stream;

static int next_byte(byte_stream *s)
{
    if (s->f)
        return getc(s->f);
    return s->at < s->n ? s->p[s->at++] : EOF;
}

/* Consumes everything up to and including the next 0xFF; false at the end.
 * In memory this is memchr: the entropy-coded data (nearly all of a JPEG)
 * is skipped at memory speed, not a byte at a time. */
static bool to_ff(byte_stream *s)
{
    if (s->f) {
        int c;
        while ((c = getc(s->f)) != EOF)
            if (c == 0xFF)
                return true;
        return false;
    }
    const unsigned char *q = s->at < s->n ? memchr(s->p + s->at, 0xFF, s->n - s->at) : NULL;
    s->at = q ? (size_t)(q - s->p) + 1 : s->n;
    return q != NULL;
}

/* Skips k bytes; false where the stream ends first. */
static bool skip_bytes(byte_stream *s, long k)
{
    if (s->f)
        return fseek(s->f, k, SEEK_CUR) == 0;
    if (k < 0 || (size_t)k > s->n - s->at)
        return false;
    s->at += (size_t)k;
    return true;
}

/* JPEG framing (ISO/IEC 10918-1, B.1.1): after SOI, marker segments (a
 * length after every marker but SOI, EOI, RSTn and TEM), each SOS followed by
 * entropy-coded data in which 0xFF is stuffed as FF 00 and the only markers
 * are RSTn; the image ends at EOI. A JPEG that ends before EOI is truncated:
 * libjpeg would only warn ("premature end") and fill the rest with grey, so
 * it is refused here. Reads bytes in memory or a file; false with `why` set
 * when they end first. *held: what libjpeg holds besides the pixels: a
 * progressive JPEG (SOF2, 6, 10, 14) keeps every DCT coefficient until its
 * last scan, 2 bytes a sample (ISO/IEC 10918-1 G.1.1; libjpeg's whole-image
 * coefficient buffer), from its SOF's size. */
static bool jpeg_framing_ok(byte_stream *s, uint64_t *held, char *why, size_t why_size)
{
    *held = 0;
    if (next_byte(s) != 0xFF || next_byte(s) != 0xD8) {
        snprintf(why, why_size, "JPEG has no SOI marker");
        return false;
    }
    /* bytes other than 0xFF: entropy-coded data after an SOS, or stray bytes
     * before a marker (libjpeg skips those with a warning; so does this) */
    while (to_ff(s)) {
        int m;
        while ((m = next_byte(s)) == 0xFF) {
        } /* fill bytes */
        if (m == EOF)
            break;
        if (m == 0xD9)
            return true;                            /* EOI */
        if (m == 0x00 || (m >= 0xD0 && m <= 0xD7) || m == 0x01)
            continue;                               /* stuffed 0xFF, RSTn, TEM: no length */
        int hi = next_byte(s), lo = next_byte(s);
        if (lo == EOF)
            break;
        long len = hi << 8 | lo;
        if (len < 2) {
            snprintf(why, why_size, "JPEG marker 0xFF%02X has a length of %ld", m, len);
            return false;
        }
        bool sof = m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC;
        if (sof && (m & 3) == 2 && len >= 8) {
            int p = next_byte(s), y1 = next_byte(s), y0 = next_byte(s), x1 = next_byte(s), x0 = next_byte(s),
                nc = next_byte(s);
            if (nc == EOF)
                break;
            (void)p;
            uint64_t samples = (uint64_t)(y1 << 8 | y0) * (uint64_t)(x1 << 8 | x0) * (uint64_t)nc;
            *held = mvr_image_add(*held, samples * 2);
            len -= 6;
        }
        if (!skip_bytes(s, len - 2))
            break;
    }
    snprintf(why, why_size, "JPEG ends before its EOI marker (truncated?)");
    return false;
}

/* jpeg_framing_ok over bytes in memory. */
static bool jpeg_bytes_ok(const unsigned char *p, size_t n, uint64_t *held, char *why, size_t why_size)
{
    byte_stream s = {.p = p, .n = n};
    return jpeg_framing_ok(&s, held, why, why_size);
}

/* The checks every encoded-image call makes; the format, or NULL with the
 * error set. *held: what the decoder holds besides what the module counts
 * (a progressive JPEG's coefficients), 0 for other formats. */
static const image_format *check_encoded(const void *data, size_t size, const char *mime, const char *who,
                                         uint64_t *held, mvr_error *error)
{
    *held = 0;
    char quoted[96];
    const unsigned char *bytes = (const unsigned char *)data;
    const image_format *f = format_of_bytes(bytes, size);
    if (!f) {
        mvr_image_fail(error, MVR_ERROR_UNSUPPORTED, "%s: the bytes are not PNG, JPEG or WebP (declared %s)", who,
                       mime && *mime ? short_value(mime, quoted, sizeof quoted) : "no mimeType");
        return NULL;
    }
    if (!mime_agrees(mime, f)) {
        mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "%s: mimeType %s but the bytes are %s", who,
                       short_value(mime, quoted, sizeof quoted), f->name);
        return NULL;
    }
    char why[128];
    if ((f == &format_png && !png_framing_ok(bytes, size, why, sizeof why)) ||
        (f == &format_jpeg && !jpeg_bytes_ok(bytes, size, held, why, sizeof why))) {
        mvr_image_fail(error, MVR_ERROR_INVALID_ASSET, "%s: %s", who, why);
        return NULL;
    }
    return f;
}

/* A deferred PNG goes to OpenImageIO; where the module cannot be loaded, the
 * libpng front's own reason is the answer (it names the image's problem). */
static const mvr_image_backend *module_for_deferred(const char *who, mvr_error *error)
{
    mvr_error own = *error;
    const mvr_image_backend *m = mvr_image_module(who, error);
    if (!m) {
        char missing[MVR_ERROR_MESSAGE_SIZE];
        snprintf(missing, sizeof missing, "%s", error->message);
        mvr_image_fail(error, own.result, "%s (and %s)", own.message, missing);
    }
    return m;
}

/* ------------------------------------------------------------------ the API */

/* Each call works on an mvr_error of its own when the caller passes none, so
 * results survive; `e` is that or the caller's. */
#define LOCAL_ERROR(error)                                                                                      \
    mvr_error local_error_;                                                                                     \
    mvr_error *e = (error) ? (error) : &local_error_;                                                           \
    e->result = MVR_OK;                                                                                         \
    e->message[0] = '\0'

void mvr_image_free(mvr_image_data *image)
{
    if (!image)
        return;
    free(image->pixels);
    memset(image, 0, sizeof *image);
}

/* The front's answer for a PNG, or OpenImageIO's where it defers. */
#define FRONT_OR_MODULE(st, who, call)                                                                          \
    do {                                                                                                        \
        if ((st) == MVR_FRONT_OK)                                                                                 \
            return MVR_OK;                                                                                      \
        if ((st) == MVR_FRONT_FAILED)                                                                             \
            return e->result;                                                                                   \
        const mvr_image_backend *m_ = module_for_deferred((who), e);                                            \
        return m_ ? m_->call : e->result;                                                                       \
    } while (0)

mvr_result mvr_image_probe(const void *data, size_t size, const char *mime_type, mvr_image_header *out,
                           mvr_error *error)
{
    LOCAL_ERROR(error);
    if (!out || !data || size == 0)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_probe: no data");
    memset(out, 0, sizeof *out);
    uint64_t held = 0;
    const image_format *f = check_encoded(data, size, mime_type, "mvr_image_probe", &held, e);
    if (!f)
        return e->result;
    if (f == &format_png) {
        mvr_bytes_source src = {.data = (const unsigned char *)data, .size = size};
        mvr_front_status st = mvr_png_probe(&src, out, e);
        FRONT_OR_MODULE(st, "mvr_image_probe", probe(data, size, mime_type, out, e));
    }
    if (f == &format_jpeg) {
        mvr_bytes_source src = {.data = (const unsigned char *)data, .size = size};
        mvr_front_status st = mvr_jpeg_probe(&src, out, e);
        FRONT_OR_MODULE(st, "mvr_image_probe", probe(data, size, mime_type, out, e));
    }
    const mvr_image_backend *m = mvr_image_module("mvr_image_probe", e);
    return m ? m->probe(data, size, mime_type, out, e) : e->result;
}

mvr_result mvr_image_decode_cost(const void *data, size_t size, const char *mime_type, uint64_t *out_bytes,
                                 mvr_error *error)
{
    LOCAL_ERROR(error);
    if (!out_bytes || !data || size == 0)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_decode_cost: no data");
    *out_bytes = 0;
    uint64_t held = 0;
    const image_format *f = check_encoded(data, size, mime_type, "mvr_image_decode_cost", &held, e);
    if (!f)
        return e->result;
    if (f == &format_png) {
        mvr_bytes_source src = {.data = (const unsigned char *)data, .size = size};
        mvr_front_status st = mvr_png_decode_cost(&src, out_bytes, e);
        FRONT_OR_MODULE(st, "mvr_image_decode_cost", decode_cost(data, size, mime_type, out_bytes, e));
    }
    const mvr_image_backend *m = NULL;
    if (f == &format_jpeg) {
        mvr_bytes_source src = {.data = (const unsigned char *)data, .size = size};
        mvr_front_status st = mvr_jpeg_decode_cost(&src, held, out_bytes, e);
        if (st == MVR_FRONT_OK)
            return MVR_OK;
        if (st == MVR_FRONT_FAILED)
            return e->result;
        m = module_for_deferred("mvr_image_decode_cost", e);
    } else {
        m = mvr_image_module("mvr_image_decode_cost", e);
    }
    if (!m || m->decode_cost(data, size, mime_type, out_bytes, e) != MVR_OK)
        return e->result;
    *out_bytes = mvr_image_add(*out_bytes, held);
    return MVR_OK;
}

mvr_result mvr_image_decode_within(const void *data, size_t size, const char *mime_type, uint32_t max_dimension,
                                   uint64_t memory_budget, mvr_image_data *out, mvr_error *error)
{
    LOCAL_ERROR(error);
    if (!out || !data || size == 0)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_decode: no data");
    memset(out, 0, sizeof *out);
    uint64_t budget = memory_budget ? memory_budget : MVR_IMAGE_DEFAULT_MEMORY_BUDGET;
    uint64_t held = 0;
    const image_format *f = check_encoded(data, size, mime_type, "mvr_image_decode", &held, e);
    if (!f)
        return e->result;
    if (f == &format_png) {
        mvr_bytes_source src = {.data = (const unsigned char *)data, .size = size};
        mvr_front_status st = mvr_png_decode(&src, max_dimension, budget, "mvr_image_decode", out, e);
        FRONT_OR_MODULE(st, "mvr_image_decode", decode(data, size, mime_type, max_dimension, budget, held, out, e));
    }
    if (f == &format_jpeg) {
        mvr_bytes_source src = {.data = (const unsigned char *)data, .size = size};
        mvr_front_status st = mvr_jpeg_decode(&src, max_dimension, budget, held, "mvr_image_decode", out, e);
        FRONT_OR_MODULE(st, "mvr_image_decode", decode(data, size, mime_type, max_dimension, budget, held, out, e));
    }
    const mvr_image_backend *m = mvr_image_module("mvr_image_decode", e);
    return m ? m->decode(data, size, mime_type, max_dimension, budget, held, out, e) : e->result;
}

mvr_result mvr_image_decode(const void *data, size_t size, const char *mime_type, uint32_t max_dimension,
                            mvr_image_data *out, mvr_error *error)
{
    return mvr_image_decode_within(data, size, mime_type, max_dimension, 0, out, error);
}

mvr_result mvr_image_read_within(const char *path, mvr_pixel_type type, uint64_t memory_budget,
                                 mvr_image_data *out, mvr_error *error)
{
    LOCAL_ERROR(error);
    if (!path || !out)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_read: NULL argument");
    memset(out, 0, sizeof *out);
    uint64_t budget = memory_budget ? memory_budget : MVR_IMAGE_DEFAULT_MEMORY_BUDGET;
    char who[MVR_ERROR_MESSAGE_SIZE / 2];
    snprintf(who, sizeof who, "mvr_image_read(%s)", path);
    FILE *file = fopen(path, "rb");
    if (!file)
        return mvr_image_fail(e, MVR_ERROR_IO, "%s: %s", who, strerror(errno));
    unsigned char sig[8];
    size_t got = fread(sig, 1, sizeof sig, file);
    const image_format *f = format_of_bytes(sig, got);
    char why[128];
    uint64_t held = 0;
    if (f == &format_jpeg) {
        rewind(file);
        byte_stream s = {.f = file};
        if (!jpeg_framing_ok(&s, &held, why, sizeof why)) {
            fclose(file);
            return mvr_image_fail(e, MVR_ERROR_INVALID_ASSET, "%s: %s", who, why);
        }
    }
    /* an 8-bit read of a PNG or JPEG file is the front's; anything else,
     * OpenImageIO's */
    bool front = type == MVR_PIXEL_U8 && (f == &format_png || f == &format_jpeg);
    mvr_front_status st = MVR_FRONT_DEFER;
    if (front) {
        rewind(file);
        mvr_bytes_source src = {.file = file};
        st = f == &format_png ? mvr_png_decode(&src, 0, budget, who, out, e)
                              : mvr_jpeg_decode(&src, 0, budget, held, who, out, e);
    }
    fclose(file);
    if (front)
        FRONT_OR_MODULE(st, who, read(path, type, budget, held, out, e));
    const mvr_image_backend *m = mvr_image_module(who, e);
    return m ? m->read(path, type, budget, held, out, e) : e->result;
}

mvr_result mvr_image_read(const char *path, mvr_pixel_type type, mvr_image_data *out, mvr_error *error)
{
    return mvr_image_read_within(path, type, 0, out, error);
}

/* The name's last four characters, lower case: ".png", ".exr", ... */
static void extension_of(const char *path, char ext[5])
{
    size_t n = strlen(path);
    ext[0] = '\0';
    if (n <= 4)
        return;
    for (int i = 0; i < 4; ++i) {
        char c = path[n - 4 + (size_t)i];
        ext[i] = (char)(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    }
    ext[4] = '\0';
}

mvr_result mvr_image_write(const char *path, const mvr_image_view *image, mvr_error *error)
{
    LOCAL_ERROR(error);
    if (!path || !image || !image->pixels || image->width == 0 || image->height == 0)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_write: NULL or empty image");
    char ext[5];
    extension_of(path, ext);
    bool png = strcmp(ext, ".png") == 0;
    if (!png && strcmp(ext, ".exr") != 0)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_image_write(%s): the name must end in .png or .exr", path);
    if (png && image->type == MVR_PIXEL_U8)
        return mvr_png_write(path, image, e) == MVR_FRONT_OK ? MVR_OK : e->result;
    /* EXR, and float pixels into PNG (OpenImageIO's conversion) */
    const mvr_image_backend *m = mvr_image_module("mvr_image_write", e);
    return m ? m->write(path, image, e) : e->result;
}

mvr_result mvr_image_compare(const mvr_image_view *a, const mvr_image_view *b, double threshold,
                             const char *diff_path, mvr_image_compare_result *out, mvr_error *error)
{
    LOCAL_ERROR(error);
    if (!a || !b || !out)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_compare: NULL argument");
    if (a->width != b->width || a->height != b->height)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT, "mvr_image_compare: sizes differ (%ux%u vs %ux%u)",
                              a->width, a->height, b->width, b->height);
    const mvr_image_backend *m = mvr_image_module("mvr_image_compare", e);
    return m ? m->compare(a, b, threshold, diff_path, out, e) : e->result;
}

static size_t channel_type_size(mvr_channel_type t)
{
    switch (t) {
    case MVR_CHANNEL_U8: return 1;
    case MVR_CHANNEL_U16: return 2;
    case MVR_CHANNEL_U32:
    case MVR_CHANNEL_F16:
    case MVR_CHANNEL_F32: return 4;
    }
    return 0;
}

/* Channel k of the image is readable as described: a known type, strides
 * that hold a value, names (EXR) given, short and not repeated. */
static mvr_result check_channel(const char *path, const mvr_image_channels *image, uint32_t k, bool exr,
                                mvr_error *e)
{
    const mvr_image_channel *c = &image->channels[k];
    size_t size = channel_type_size(c->type);
    if (!c->first || size == 0 || c->pixel_stride < size)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_image_write_channels(%s): channel %u has no pixels, an unknown type or a pixel "
                              "stride under its value's size", path, k);
    uint64_t row = mvr_image_add(mvr_image_mul(image->width - 1u, c->pixel_stride), size);
    if (c->row_stride < row)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_image_write_channels(%s): channel %u: a row stride of %zu bytes holds no row of "
                              "%u pixels", path, k, c->row_stride, image->width);
    if (!exr)
        return MVR_OK;
    if (!c->name || !*c->name || strlen(c->name) > 255)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_image_write_channels(%s): channel %u has no name, or one over 255 bytes", path, k);
    for (uint32_t j = 0; j < k; ++j)
        if (strcmp(image->channels[j].name, c->name) == 0)
            return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_image_write_channels(%s): channels %u and %u are both named '%s'", path, j, k,
                                  c->name);
    return MVR_OK;
}

mvr_result mvr_image_write_channels(const char *path, const mvr_image_channels *image, mvr_error *error)
{
    LOCAL_ERROR(error);
    if (!path || !image || !image->channels || image->width == 0 || image->height == 0 || image->count == 0 ||
        image->count > MVR_IMAGE_MAX_CHANNELS)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_image_write_channels(%s): NULL, empty, or not 1..%u channels", path ? path : "NULL",
                              MVR_IMAGE_MAX_CHANNELS);
    char ext[5];
    extension_of(path, ext);
    bool png = strcmp(ext, ".png") == 0;
    if (!png && strcmp(ext, ".exr") != 0)
        return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_image_write_channels(%s): the name must end in .png or .exr", path);
    for (uint32_t k = 0; k < image->count; ++k)
        if (check_channel(path, image, k, !png, e) != MVR_OK)
            return e->result;
    if (png) {
        const mvr_image_channel *c = &image->channels[0];
        if (image->count != 1 || (c->type != MVR_CHANNEL_U8 && c->type != MVR_CHANNEL_U16))
            return mvr_image_fail(e, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_image_write_channels(%s): a PNG takes one U8 or U16 channel (%u given)", path,
                                  image->count);
        return mvr_png_write_gray(path, c, image->width, image->height, image->bottom_up, e) == MVR_FRONT_OK
                   ? MVR_OK
                   : e->result;
    }
    const mvr_image_backend *m = mvr_image_module("mvr_image_write_channels", e);
    return m ? m->write_channels(path, image, e) : e->result;
}
