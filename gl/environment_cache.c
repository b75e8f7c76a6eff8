/*
 * The environment's disk cache (environment_cache.h). Prefiltering the
 * neutral studio is most of a small first render's work on a software GL
 * (llvmpipe, callgrind, a 64x64 render of the cube demo: 1.9 G of its 2.4 G
 * instructions; the GGX chain's draws 1.4 G, the JIT compile of the
 * source cube's shader 0.2 G, the DFG table 0.12 G), and the result depends
 * only on inputs we can name: the environment's pixels, the cubes' sizes
 * and samples, the prefilter's shader sources and the GL. So both cubes
 * (the source with its mips and the specular chain) are read back once
 * (RGBA16F texels, through float, stored as the same halves) and later
 * renderers upload them instead of drawing anything.
 *
 * Entries: one file per slot, <dir>/ibl-<what>-<driver hash>-u<uid>.mvrbin,
 * written and checked by core/program_binary_file.c (a SipHash tag under the
 * user's key, the driver string, a 64-bit key of every input; temporary
 * file and rename). A slot per environment source, size and path keeps the
 * folder bounded: a new image overwrites its slot's entry.
 *
 * Payloads (little-endian), inside the entry:
 *   DFG:   u32 size, u32 samples, then size*size*2 float bit patterns (u32)
 *   maps:  u32 2 (cubes), u32 0, then u32 size and u32 levels of the source
 *          cube and of the specular chain; then the source's levels and the
 *          chain's, each level k face by face (+X -X +Y -Y +Z -Z), (size >> k)^2
 *          RGBA halves (u16), rows bottom first (glReadPixels' order and
 *          glTexSubImage2D's)
 */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>

#include "environment.h"
#include "environment_cache.h"
#include "errors.h"
#include "program.h"
#include "program_binary_file.h"
#include "renderer.h"
#include "shader_gen.h"

/* Changed whenever what an entry holds changes without its key changing
 * (the CPU code behind the DFG table, the payload layout). */
#define ENV_CACHE_VERSION "mvr-environment-cache-1"
#define FORMAT_DFG 0x4d564431u   /* "MVD1" */
#define FORMAT_MAPS 0x4d564d31u /* "MVM1" */
#define MAPS_HEADER 24u

typedef struct cache_slot {
    char path[4096];
    char driver[MVR_PROGRAM_BINARY_MAX_DRIVER];
    mvr_program_cache_key mac;
    uint64_t key;
} cache_slot;

/* ------------------------------------------------------------------ half floats */

float mvr_half_to_float(uint16_t h)
{
    uint32_t sign = (uint32_t)(h & 0x8000u) << 16, e = (h >> 10) & 0x1fu, m = h & 0x3ffu, bits;
    if (e == 0 && m == 0) {
        bits = sign;
    } else if (e == 0) { /* subnormal: m 2^-24, normalised */
        uint32_t fe = 113;
        while (!(m & 0x400u)) {
            m <<= 1;
            --fe;
        }
        bits = sign | (fe << 23) | ((m & 0x3ffu) << 13);
    } else if (e == 31) {
        bits = sign | 0x7f800000u | (m << 13);
    } else {
        bits = sign | ((e + 112u) << 23) | (m << 13);
    }
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

bool mvr_half_from_float_exact(float f, uint16_t *out)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    uint32_t sign = (b >> 16) & 0x8000u, e = (b >> 23) & 0xffu, m = b & 0x7fffffu;
    int32_t exp = (int32_t)e - 127;
    uint32_t h;
    if (e == 0xffu)
        h = sign | 0x7c00u | (m >> 13);
    else if (e == 0 && m == 0)
        h = sign;
    else if (e != 0 && exp >= -14 && exp <= 15)
        h = sign | ((uint32_t)(exp + 15) << 10) | (m >> 13);
    else if (e != 0 && exp >= -24 && exp < -14)
        h = sign | ((m | 0x800000u) >> (uint32_t)(-exp - 1)); /* subnormal half */
    else
        return false;
    float back = mvr_half_to_float((uint16_t)h);
    uint32_t bb;
    memcpy(&bb, &back, sizeof bb);
    if (bb != b)
        return false; /* bits a half cannot hold: never stored */
    *out = (uint16_t)h;
    return true;
}

/* ------------------------------------------------------------------ keys and slots */

static void put_u32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}

static uint32_t get_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t key_u32(uint64_t h, uint32_t v)
{
    unsigned char b[4];
    put_u32(b, v);
    return mvr_fnv1a64(h, b, sizeof b);
}

/* Length first, so moving text between parts changes the key. */
static uint64_t key_text(uint64_t h, const char *text)
{
    size_t n = strlen(text);
    h = key_u32(h, (uint32_t)n);
    return mvr_fnv1a64(h, text, n);
}

/* The pixels' hash: four independent multiply-xorshift lanes over the float
 * bit patterns (a lookup key, not a defence: entries are authenticated), a
 * few ms for the largest environment where byte-wise FNV takes ten times
 * that. */
static uint64_t key_pixels(uint64_t h, const float *px, size_t count)
{
    uint64_t lane[4] = {0x243f6a8885a308d3ull, 0x13198a2e03707344ull, 0xa4093822299f31d0ull,
                        0x082efa98ec4e6c89ull};
    for (size_t i = 0; i < count; ++i) {
        uint32_t w;
        memcpy(&w, px + i, sizeof w);
        uint64_t *l = &lane[i & 3u];
        *l = (*l ^ w) * 0x9e3779b97f4a7c15ull;
        *l ^= *l >> 29;
    }
    h = key_u32(h, (uint32_t)(count >> 32));
    h = key_u32(h, (uint32_t)count);
    return mvr_fnv1a64(h, lane, sizeof lane);
}

/* The cache's folder, key file and entry path for one slot: false (no
 * cache) without a folder, or with a key file that is not safe to use. */
static bool slot_open(mvr_renderer *r, const char *name, cache_slot *s)
{
    if (!r->program_cache_dir)
        return false;
    mvr_gl_driver_identity(r->ctx, s->driver, sizeof s->driver);
    if (!mvr_program_binary_path(r->program_cache_dir, name, s->driver, s->path, sizeof s->path))
        return false;
    char why[512] = "";
    if (!mvr_program_cache_key_load(r->program_cache_dir, &s->mac, why, sizeof why)) {
        mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL, "mvr: environment cache: %s (not used)", why);
        return false;
    }
    s->key = key_text(key_text(MVR_FNV1A64_INIT, ENV_CACHE_VERSION), s->driver);
    return true;
}

/* An entry's payload, or NULL: a missing entry silently, anything else
 * that is not a hit (damaged, truncated, forged, stale) with a log line. */
static unsigned char *slot_read(mvr_renderer *r, const cache_slot *s, uint32_t format, size_t *size)
{
    uint32_t got = 0;
    void *payload = NULL;
    char why[512] = "";
    mvr_program_binary_status st =
        mvr_program_binary_read(s->path, &s->mac, s->driver, s->key, &got, &payload, size, why, sizeof why);
    if (st == MVR_PROGRAM_BINARY_HIT && got != format) {
        mvr_str_format(why, sizeof why, "format %08x, not %08x", got, format);
        st = MVR_PROGRAM_BINARY_STALE;
    }
    if (st == MVR_PROGRAM_BINARY_HIT)
        return payload;
    free(payload);
    if (st != MVR_PROGRAM_BINARY_MISS)
        mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL, "mvr: environment cache: %s: %s; computed again",
                s->path, why);
    return NULL;
}

static void slot_write(mvr_renderer *r, const cache_slot *s, uint32_t format, const void *payload, size_t size)
{
    char why[512] = "";
    if (!mvr_program_binary_write(s->path, &s->mac, s->driver, s->key, format, payload, size, why, sizeof why))
        mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL, "mvr: environment cache: not stored: %s", why);
}

/* ------------------------------------------------------------------ the DFG table */

static bool dfg_slot(mvr_renderer *r, uint32_t size, uint32_t samples, cache_slot *s)
{
    char name[64];
    mvr_str_format(name, sizeof name, "ibl-dfg%u-n%u", size, samples);
    if (!slot_open(r, name, s))
        return false;
    s->key = key_u32(key_u32(key_text(s->key, "dfg"), size), samples);
    return true;
}

bool mvr_env_cache_load_dfg(mvr_renderer *r, uint32_t size, uint32_t samples, float *table)
{
    cache_slot s;
    if (!dfg_slot(r, size, samples, &s))
        return false;
    size_t bytes = 0;
    unsigned char *p = slot_read(r, &s, FORMAT_DFG, &bytes);
    size_t count = (size_t)size * size * 2;
    bool ok = p && bytes == 8 + count * 4 && get_u32(p) == size && get_u32(p + 4) == samples;
    if (p && !ok)
        mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL,
                "mvr: environment cache: %s: %zu bytes do not hold a %ux%u table; computed again", s.path, bytes,
                size, size);
    for (size_t i = 0; ok && i < count; ++i) {
        uint32_t bits = get_u32(p + 8 + i * 4);
        memcpy(&table[i], &bits, sizeof bits);
    }
    free(p);
    return ok;
}

void mvr_env_cache_store_dfg(mvr_renderer *r, uint32_t size, uint32_t samples, const float *table)
{
    cache_slot s;
    if (!dfg_slot(r, size, samples, &s))
        return;
    size_t count = (size_t)size * size * 2;
    unsigned char *p = malloc(8 + count * 4);
    if (!p)
        return;
    put_u32(p, size);
    put_u32(p + 4, samples);
    for (size_t i = 0; i < count; ++i) {
        uint32_t bits;
        memcpy(&bits, &table[i], sizeof bits);
        put_u32(p + 8 + i * 4, bits);
    }
    slot_write(r, &s, FORMAT_DFG, p, 8 + count * 4);
    free(p);
}

/* ------------------------------------------------------------------ the cube maps */

/* Hashes both stages of an environment program (the prefilter's code is an
 * input of the chain's bytes). False when a source cannot be made. */
static bool key_program(uint64_t *h, uint32_t features, bool multiview)
{
    mvr_shader_variant v;
    memset(&v, 0, sizeof v);
    v.program = MVR_PROGRAM_ENVIRONMENT;
    v.features = features;
    v.num_views = multiview ? 6u : 0u;
    char why[256];
    bool ok = true;
    for (int stage = 0; stage < 2 && ok; ++stage) {
        mvr_str_builder sb = {0};
        ok = mvr_shader_source(&v, stage ? MVR_SHADER_STAGE_FRAGMENT : MVR_SHADER_STAGE_VERTEX, &sb, why,
                               sizeof why);
        if (ok)
            *h = key_text(*h, sb.data);
        mvr_sb_free(&sb);
    }
    return ok;
}

static bool maps_slot(mvr_renderer *r, const mvr_env_cache_maps *m, cache_slot *s)
{
    const mvr_environment *env = m->env;
    char name[96];
    mvr_str_format(name, sizeof name, "ibl-%s-s%u-n%u-%s", mvr_environment_source_name(env->source), m->size,
                   env->specular_samples, m->multiview ? "mv6" : "loop");
    if (!slot_open(r, name, s))
        return false;
    uint64_t h = key_text(s->key, "maps");
    const uint32_t params[8] = {env->width,   env->height, env->specular_samples, m->source_size,
                                m->source_levels, m->size, m->levels,          m->multiview ? 1u : 0u};
    for (size_t i = 0; i < 8; ++i)
        h = key_u32(h, params[i]);
    h = key_pixels(h, env->pixels, (size_t)env->width * env->height * 4);
    /* the source cube's own program, then the GGX filter's */
    if (!key_program(&h, 0u, m->multiview) || !key_program(&h, MVR_FEATURE_ENV_GGX, m->multiview))
        return false;
    s->key = h;
    return true;
}

/* Bytes of one cube's levels as halves; 0 for levels the size cannot have. */
static size_t cube_bytes(uint32_t size, uint32_t levels)
{
    if (levels < 1 || levels > 16 || size > (1u << 15) || (size >> (levels - 1)) < 1)
        return 0;
    size_t total = 0;
    for (uint32_t k = 0; k < levels; ++k) {
        size_t side = size >> k;
        total += side * side * 6 * 4 * 2;
    }
    return total;
}

static size_t maps_bytes(const mvr_env_cache_maps *m)
{
    size_t a = cube_bytes(m->source_size, m->source_levels), b = cube_bytes(m->size, m->levels);
    return a && b ? MAPS_HEADER + a + b : 0;
}

/* Uploads one cube's levels from the payload at *q (advanced). */
static void upload_cube(mvr_renderer *r, GLuint cube, uint32_t size, uint32_t levels, const unsigned char **q,
                        uint16_t *texels)
{
    const mvr_gl_api_table *gl = r->gl;
    mvr_state_texture(&r->state, MVR_UNIT_ENV_INPUT, GL_TEXTURE_CUBE_MAP, cube);
    for (uint32_t k = 0; k < levels; ++k) {
        size_t side = size >> k, count = side * side * 4;
        for (GLenum f = 0; f < 6; ++f) {
            const unsigned char *p = *q;
            for (size_t i = 0; i < count; ++i)
                texels[i] = (uint16_t)(p[i * 2] | p[i * 2 + 1] << 8);
            *q += count * 2;
            gl->TexSubImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, (GLint)k, 0, 0, (GLsizei)side, (GLsizei)side,
                              GL_RGBA, GL_HALF_FLOAT, texels);
        }
    }
}

bool mvr_env_cache_load(mvr_renderer *r, const mvr_env_cache_maps *m, GLuint source, GLuint specular)
{
    cache_slot s;
    size_t want = maps_bytes(m);
    if (!want || !maps_slot(r, m, &s))
        return false;
    size_t bytes = 0;
    unsigned char *p = slot_read(r, &s, FORMAT_MAPS, &bytes);
    if (!p)
        return false;
    bool ok = bytes == want && get_u32(p) == 2u && get_u32(p + 4) == 0u && get_u32(p + 8) == m->source_size &&
              get_u32(p + 12) == m->source_levels && get_u32(p + 16) == m->size && get_u32(p + 20) == m->levels;
    uint32_t largest = m->source_size > m->size ? m->source_size : m->size;
    uint16_t *texels = ok ? malloc((size_t)largest * largest * 4 * sizeof *texels) : NULL;
    if (!texels) {
        if (!ok)
            mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL,
                    "mvr: environment cache: %s: %zu bytes do not hold cubes of %u and %u texels; computed again",
                    s.path, bytes, m->source_size, m->size);
        free(p);
        return false;
    }
    const mvr_gl_api_table *gl = r->gl;
    mvr_gl_clear_errors(gl);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const unsigned char *q = p + MAPS_HEADER;
    upload_cube(r, source, m->source_size, m->source_levels, &q, texels);
    upload_cube(r, specular, m->size, m->levels, &q, texels);
    ok = gl->GetError() == GL_NO_ERROR;
    mvr_gl_clear_errors(gl);
    if (ok) {
        r->upload_bytes += bytes - MAPS_HEADER;
        mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL, "mvr: environment cache: maps from %s", s.path);
    } else {
        mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL,
                "mvr: environment cache: the GL refused %s's texels; computed again", s.path);
    }
    free(texels);
    free(p);
    return ok;
}

/* One face of one level back from the GL, as exact halves: false when the
 * read fails or a value is no half (then nothing is stored). */
static bool read_face(mvr_renderer *r, GLuint cube, uint32_t level, GLenum face, uint32_t side, float *px,
                      unsigned char *out)
{
    const mvr_gl_api_table *gl = r->gl;
    gl->FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, face, cube, (GLint)level);
    if (gl->CheckFramebufferStatus(GL_READ_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return false;
    gl->ReadPixels(0, 0, (GLsizei)side, (GLsizei)side, GL_RGBA, GL_FLOAT, px);
    for (size_t i = 0; i < (size_t)side * side * 4; ++i) {
        uint16_t h;
        if (!mvr_half_from_float_exact(px[i], &h))
            return false;
        out[i * 2] = (unsigned char)(h & 0xffu);
        out[i * 2 + 1] = (unsigned char)(h >> 8);
    }
    return true;
}

static bool read_cube(mvr_renderer *r, GLuint cube, uint32_t size, uint32_t levels, float *px, unsigned char **q)
{
    for (uint32_t k = 0; k < levels; ++k) {
        uint32_t side = size >> k;
        for (GLenum f = 0; f < 6; ++f) {
            if (!read_face(r, cube, k, GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, side, px, *q))
                return false;
            *q += (size_t)side * side * 4 * 2;
        }
    }
    return true;
}

void mvr_env_cache_store(mvr_renderer *r, const mvr_env_cache_maps *m, GLuint source, GLuint specular)
{
    cache_slot s;
    size_t bytes = maps_bytes(m);
    /* maps larger than an entry may be (a 1024-texel chain) are filtered every time */
    if (!bytes || bytes > MVR_PROGRAM_BINARY_MAX_PAYLOAD || !maps_slot(r, m, &s))
        return;
    uint32_t largest = m->source_size > m->size ? m->source_size : m->size;
    unsigned char *p = malloc(bytes);
    float *px = malloc((size_t)largest * largest * 4 * sizeof *px);
    bool ok = p && px;
    if (ok) {
        const uint32_t head[6] = {2u, 0u, m->source_size, m->source_levels, m->size, m->levels};
        for (int i = 0; i < 6; ++i)
            put_u32(p + 4 * i, head[i]);
        const mvr_gl_api_table *gl = r->gl;
        mvr_gl_clear_errors(gl);
        GLuint fbo = 0;
        gl->GenFramebuffers(1, &fbo);
        mvr_state_read_framebuffer(&r->state, fbo);
        gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
        gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
        unsigned char *q = p + MAPS_HEADER;
        ok = read_cube(r, source, m->source_size, m->source_levels, px, &q) &&
             read_cube(r, specular, m->size, m->levels, px, &q);
        ok = gl->GetError() == GL_NO_ERROR && ok;
        mvr_gl_clear_errors(gl);
        mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &fbo);
    }
    if (ok)
        slot_write(r, &s, FORMAT_MAPS, p, bytes);
    else
        mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL,
                "mvr: environment cache: the maps could not be read back exactly; not stored");
    free(px);
    free(p);
}
