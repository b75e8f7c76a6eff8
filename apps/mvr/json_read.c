/* The CLI's JSON reader (json_read.h): recursive descent over the whole
 * text, bounded in depth, value count and number length, so a hostile file
 * costs at most its own size in memory and a fixed stack, and time linear in
 * its size: each byte is scanned a bounded number of times, containers grow
 * by doubling, and duplicate keys are found through a hash set per object
 * (expected O(1) per key) rather than by comparing each key with all the
 * earlier ones. */
#define _DEFAULT_SOURCE /* getrandom */
#include "json_read.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <time.h>
#include <unistd.h>

typedef struct reader {
    const char *p, *end;
    uint32_t line;
    uint32_t values;
    char *why;
    size_t why_size;
    uint64_t seed[2]; /* the key of the member-name hash, fresh per parse */
} reader;

static bool fail(reader *r, const char *fmt, ...)
{
    int n = snprintf(r->why, r->why_size, "line %u: ", r->line);
    if (n >= 0 && (size_t)n < r->why_size) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(r->why + n, r->why_size - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return false;
}

/* What is at the cursor, for messages: a printable character or a name. */
static const char *here(const reader *r, char buf[8])
{
    if (r->p >= r->end)
        return "the end of the file";
    unsigned char c = (unsigned char)*r->p;
    if (c >= 0x21 && c < 0x7f)
        snprintf(buf, 8, "'%c'", c);
    else
        snprintf(buf, 8, "0x%02x", c);
    return buf;
}

static void skip_space(reader *r)
{
    while (r->p < r->end) {
        char c = *r->p;
        if (c == '\n')
            r->line++;
        else if (c != ' ' && c != '\t' && c != '\r')
            return;
        r->p++;
    }
}

static bool literal(reader *r, const char *word)
{
    size_t n = strlen(word);
    if ((size_t)(r->end - r->p) < n || memcmp(r->p, word, n) != 0)
        return false;
    r->p += n;
    return true;
}

static bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* JSON's number grammar checked first, then strtod on a bounded copy (the
 * text is not NUL-terminated, and strtod accepts more than JSON: hex, inf). */
static bool number(reader *r, double *out)
{
    const char *s = r->p, *p = s;
    if (p < r->end && *p == '-')
        p++;
    if (p >= r->end || !is_digit(*p))
        return fail(r, "not a number");
    if (*p == '0')
        p++;
    else
        while (p < r->end && is_digit(*p))
            p++;
    if (p < r->end && *p == '.') {
        p++;
        if (p >= r->end || !is_digit(*p))
            return fail(r, "a digit must follow a number's '.'");
        while (p < r->end && is_digit(*p))
            p++;
    }
    if (p < r->end && (*p == 'e' || *p == 'E')) {
        p++;
        if (p < r->end && (*p == '+' || *p == '-'))
            p++;
        if (p >= r->end || !is_digit(*p))
            return fail(r, "a digit must follow a number's exponent");
        while (p < r->end && is_digit(*p))
            p++;
    }
    size_t len = (size_t)(p - s);
    if (len > JSON_READ_MAX_NUMBER_CHARS)
        return fail(r, "a number of %zu characters (at most %d)", len, JSON_READ_MAX_NUMBER_CHARS);
    char buf[JSON_READ_MAX_NUMBER_CHARS + 1];
    memcpy(buf, s, len);
    buf[len] = '\0';
    errno = 0;
    double v = strtod(buf, NULL);
    if (!isfinite(v)) /* underflow to 0 or a denormal is a number; overflow is not */
        return fail(r, "the number %.40s%s is out of range", buf, len > 40 ? "..." : "");
    r->p = p;
    *out = v;
    return true;
}

static int hex4(const char *p)
{
    int v = 0;
    for (int i = 0; i < 4; ++i) {
        char c = p[i];
        int d = -1;
        if (c >= '0' && c <= '9')
            d = c - '0';
        else if (c >= 'a' && c <= 'f')
            d = c - 'a' + 10;
        else if (c >= 'A' && c <= 'F')
            d = c - 'A' + 10;
        if (d < 0)
            return -1;
        v = v * 16 + d;
    }
    return v;
}

static size_t put_utf8(char *o, uint32_t cp)
{
    if (cp < 0x80) {
        o[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        o[0] = (char)(0xc0 | (cp >> 6));
        o[1] = (char)(0x80 | (cp & 0x3f));
        return 2;
    }
    if (cp < 0x10000) {
        o[0] = (char)(0xe0 | (cp >> 12));
        o[1] = (char)(0x80 | ((cp >> 6) & 0x3f));
        o[2] = (char)(0x80 | (cp & 0x3f));
        return 3;
    }
    o[0] = (char)(0xf0 | (cp >> 18));
    o[1] = (char)(0x80 | ((cp >> 12) & 0x3f));
    o[2] = (char)(0x80 | ((cp >> 6) & 0x3f));
    o[3] = (char)(0x80 | (cp & 0x3f));
    return 4;
}

/* A string at the cursor ('"'), escapes decoded; the result is never longer
 * than its source text, which bounds the allocation. */
static bool string(reader *r, char **out)
{
    const char *p = r->p + 1;
    const char *close = p;
    while (close < r->end && *close != '"')
        close += *close == '\\' && close + 1 < r->end ? 2 : 1;
    if (close >= r->end)
        return fail(r, "a string that never ends");
    char *s = malloc((size_t)(close - p) + 1), *o = s;
    if (!s)
        return fail(r, "out of memory");
    while (p < close) {
        unsigned char c = (unsigned char)*p;
        if (c < 0x20) {
            free(s);
            return fail(r, "a control character (0x%02x) inside a string: write it escaped", c);
        }
        if (c != '\\') {
            *o++ = (char)c;
            p++;
            continue;
        }
        char e = p[1];
        p += 2;
        switch (e) {
        case '"': *o++ = '"'; break;
        case '\\': *o++ = '\\'; break;
        case '/': *o++ = '/'; break;
        case 'b': *o++ = '\b'; break;
        case 'f': *o++ = '\f'; break;
        case 'n': *o++ = '\n'; break;
        case 'r': *o++ = '\r'; break;
        case 't': *o++ = '\t'; break;
        case 'u': {
            int hi = close - p >= 4 ? hex4(p) : -1;
            if (hi < 0) {
                free(s);
                return fail(r, "\\u needs four hexadecimal digits");
            }
            p += 4;
            uint32_t cp = (uint32_t)hi;
            if (hi >= 0xdc00 && hi <= 0xdfff) {
                free(s);
                return fail(r, "a lone low surrogate \\u%04x in a string", hi);
            }
            if (hi >= 0xd800 && hi <= 0xdbff) {
                int lo = close - p >= 6 && p[0] == '\\' && p[1] == 'u' ? hex4(p + 2) : -1;
                if (lo < 0xdc00 || lo > 0xdfff) {
                    free(s);
                    return fail(r, "a high surrogate \\u%04x without its low half", hi);
                }
                p += 6;
                cp = 0x10000 + (((uint32_t)hi - 0xd800) << 10) + ((uint32_t)lo - 0xdc00);
            }
            if (cp == 0) {
                free(s);
                return fail(r, "\\u0000 inside a string");
            }
            o += put_utf8(o, cp); /* 6 or 12 source bytes give at most 4 */
            break;
        }
        default:
            free(s);
            return fail(r, "an unknown escape '\\%c' in a string", e >= 0x21 && e < 0x7f ? e : '?');
        }
    }
    *o = '\0';
    r->p = close + 1;
    *out = s;
    return true;
}

/* ------------------------------------------------------------ member names
 * Duplicate member names are found with a hash set of the object's names
 * (their decoded bytes). The file is hostile, so the hash is SipHash-2-4, a
 * keyed pseudorandom function (Aumasson and Bernstein, "SipHash: a fast
 * short-input PRF", INDOCRYPT 2012), keyed with 128 random bits drawn per
 * parse: whoever writes the file cannot tell which names share a slot, so
 * no file makes the probes long (hash flooding); the seeded hashes of many
 * tables (MurmurHash2/3, CityHash) have collisions computed offline whatever
 * the seed (Aumasson, Bernstein and Bosslet, "Hash-flooding DoS reloaded",
 * 2012). Open addressing with linear probing, kept at most half full:
 * expected O(1) probes per name. */

static uint64_t rotl64(uint64_t x, int b)
{
    return (x << b) | (x >> (64 - b));
}

/* One SipRound (the paper's section 2) on the state v[0..3]. */
static void sip_round(uint64_t v[4])
{
    v[0] += v[1], v[1] = rotl64(v[1], 13), v[1] ^= v[0], v[0] = rotl64(v[0], 32);
    v[2] += v[3], v[3] = rotl64(v[3], 16), v[3] ^= v[2];
    v[0] += v[3], v[3] = rotl64(v[3], 21), v[3] ^= v[0];
    v[2] += v[1], v[1] = rotl64(v[1], 17), v[1] ^= v[2], v[2] = rotl64(v[2], 32);
}

/* SipHash-2-4 of data[0..len) under the key k[0], k[1] (the paper's k0, k1:
 * the key's bytes read little-endian); words of the message little-endian,
 * the last one carrying len mod 256 in its top byte. */
static uint64_t siphash24(const uint64_t k[2], const unsigned char *data, size_t len)
{
    uint64_t v[4] = {k[0] ^ 0x736f6d6570736575ull, k[1] ^ 0x646f72616e646f6dull, k[0] ^ 0x6c7967656e657261ull,
                     k[1] ^ 0x7465646279746573ull};
    size_t full = len / 8 * 8;
    for (size_t i = 0; i <= full; i += 8) {
        uint64_t m = 0;
        if (i < full) {
            for (int b = 7; b >= 0; --b)
                m = m << 8 | data[i + (size_t)b];
        } else { /* the final word: the tail bytes and the length */
            for (size_t b = len - full; b-- > 0;)
                m = m << 8 | data[full + b];
            m |= (uint64_t)(len & 0xff) << 56;
        }
        v[3] ^= m;
        sip_round(v);
        sip_round(v);
        v[0] ^= m;
    }
    v[2] ^= 0xff;
    for (int i = 0; i < 4; ++i)
        sip_round(v);
    return v[0] ^ v[1] ^ v[2] ^ v[3];
}

/* 128 bits from the kernel; where it has none to give (no getrandom, a
 * sandbox that forbids it), the clock, the process and an address, so at
 * least no build of mvr has one fixed key. */
static void fresh_seed(uint64_t seed[2])
{
    if (getrandom(seed, 2 * sizeof seed[0], GRND_NONBLOCK) == (ssize_t)(2 * sizeof seed[0]))
        return;
    struct timespec ts = {0, 0};
    clock_gettime(CLOCK_REALTIME, &ts);
    seed[0] = (uint64_t)ts.tv_sec * 0x9e3779b97f4a7c15ull ^ (uint64_t)ts.tv_nsec;
    seed[1] = ((uint64_t)getpid() << 32) ^ (uint64_t)(uintptr_t)seed ^ rotl64(seed[0], 29);
}

typedef struct key_set {
    uint32_t *slots; /* a member's index + 1; 0: empty */
    uint32_t mask;   /* the slot count - 1 (a power of two); 0 before the first name */
} key_set;

static uint32_t key_slot(const reader *r, const key_set *set, const char *key)
{
    return (uint32_t)siphash24(r->seed, (const unsigned char *)key, strlen(key)) & set->mask;
}

/* Adds key (not yet in keys[0..count)) to the set of keys[0..count);
 * *added false: an equal name is there already. false (failed): out of
 * memory. Grows first, so at most half the slots are ever taken. */
static bool key_set_add(reader *r, key_set *set, char *const *keys, uint32_t count, const char *key, bool *added)
{
    if (((uint64_t)count + 1) * 2 > (uint64_t)set->mask + (set->slots ? 1 : 0)) {
        uint64_t slots = set->slots ? ((uint64_t)set->mask + 1) * 2 : 8;
        while (slots < ((uint64_t)count + 1) * 2)
            slots *= 2;
        /* count <= JSON_READ_MAX_VALUES, so slots <= 2^23: no overflow */
        uint32_t *grown = calloc((size_t)slots, sizeof *grown);
        if (!grown)
            return fail(r, "out of memory");
        free(set->slots);
        set->slots = grown;
        set->mask = (uint32_t)(slots - 1);
        for (uint32_t k = 0; k < count; ++k) {
            uint32_t s = key_slot(r, set, keys[k]);
            while (set->slots[s])
                s = (s + 1) & set->mask;
            set->slots[s] = k + 1;
        }
    }
    uint32_t s = key_slot(r, set, key);
    for (; set->slots[s]; s = (s + 1) & set->mask)
        if (strcmp(keys[set->slots[s] - 1], key) == 0) {
            *added = false;
            return true;
        }
    set->slots[s] = count + 1;
    *added = true;
    return true;
}

static bool value(reader *r, json_value *v, int depth);

static bool members(reader *r, json_value *v, int depth, bool object, key_set *names);

/* Items or members into a growing array (doubling), then handed to v; an
 * object's names in a hash set while it is read. */
static bool container(reader *r, json_value *v, int depth, bool object)
{
    key_set names = {NULL, 0};
    bool ok = members(r, v, depth, object, &names);
    free(names.slots);
    return ok;
}

static bool members(reader *r, json_value *v, int depth, bool object, key_set *names)
{
    char close = object ? '}' : ']';
    uint32_t cap = 0;
    r->p++;
    skip_space(r);
    if (r->p < r->end && *r->p == close) {
        r->p++;
        return true;
    }
    for (;;) {
        if (v->count == cap) {
            uint32_t ncap = cap ? cap * 2 : 4;
            json_value *items = realloc(v->items, ncap * sizeof *items);
            if (items)
                v->items = items;
            char **keys = object ? realloc(v->keys, ncap * sizeof *keys) : NULL;
            if (keys)
                v->keys = keys;
            if (!items || (object && !keys))
                return fail(r, "out of memory");
            cap = ncap;
        }
        skip_space(r);
        char buf[8];
        if (object) {
            if (r->p >= r->end || *r->p != '"')
                return fail(r, "expected a member name (a string) in an object, found %s", here(r, buf));
            char *key = NULL;
            if (!string(r, &key))
                return false;
            bool added = false;
            if (!key_set_add(r, names, v->keys, v->count, key, &added)) {
                free(key);
                return false;
            }
            if (!added) {
                bool ok = fail(r, "the key \"%.60s\" appears twice in one object", key);
                free(key);
                return ok;
            }
            v->keys[v->count] = key;
            skip_space(r);
            if (r->p >= r->end || *r->p != ':') {
                free(key);
                return fail(r, "expected ':' after the member name, found %s", here(r, buf));
            }
            r->p++;
        }
        json_value *item = &v->items[v->count];
        memset(item, 0, sizeof *item);
        bool ok = value(r, item, depth + 1);
        v->count++; /* freed with the rest, whole or half-made */
        if (!ok)
            return false;
        skip_space(r);
        if (r->p < r->end && *r->p == ',') {
            r->p++;
            continue;
        }
        if (r->p < r->end && *r->p == close) {
            r->p++;
            return true;
        }
        return fail(r, "expected ',' or '%c' after %s, found %s", close, object ? "an object member" : "an array item",
                    here(r, buf));
    }
}

static bool value(reader *r, json_value *v, int depth)
{
    skip_space(r);
    v->line = r->line;
    if (depth > JSON_READ_MAX_DEPTH)
        return fail(r, "nested deeper than %d arrays and objects", JSON_READ_MAX_DEPTH);
    if (++r->values > JSON_READ_MAX_VALUES)
        return fail(r, "more than %u values", JSON_READ_MAX_VALUES);
    char buf[8];
    if (r->p >= r->end)
        return fail(r, "expected a value, found the end of the file");
    switch (*r->p) {
    case '{': v->type = JSON_OBJECT; return container(r, v, depth, true);
    case '[': v->type = JSON_ARRAY; return container(r, v, depth, false);
    case '"': v->type = JSON_STRING; return string(r, &v->string);
    case 't': v->type = JSON_TRUE; break;
    case 'f': v->type = JSON_FALSE; break;
    case 'n': v->type = JSON_NULL; break;
    default:
        if (*r->p == '-' || is_digit(*r->p)) {
            v->type = JSON_NUMBER;
            return number(r, &v->number);
        }
        return fail(r, "expected a value, found %s%s", here(r, buf),
                    *r->p == 'N' || *r->p == 'I' ? " (JSON has no NaN or Infinity)" : "");
    }
    static const char *const words[] = {[JSON_TRUE] = "true", [JSON_FALSE] = "false", [JSON_NULL] = "null"};
    if (!literal(r, words[v->type]))
        return fail(r, "expected a value, found %s", here(r, buf));
    return true;
}

bool json_read(const char *text, size_t size, json_value *out, char *why, size_t why_size)
{
    memset(out, 0, sizeof *out);
    reader r = {text, text + size, 1, 0, why, why_size, {0, 0}};
    fresh_seed(r.seed);
    if (size >= 3 && memcmp(text, "\xef\xbb\xbf", 3) == 0)
        r.p += 3;
    bool ok = value(&r, out, 0);
    if (ok) {
        skip_space(&r);
        char buf[8];
        if (r.p < r.end)
            ok = fail(&r, "%s after the end of the JSON value", here(&r, buf));
    }
    if (!ok) {
        json_read_free(out);
        memset(out, 0, sizeof *out);
    }
    return ok;
}

void json_read_free(json_value *v)
{
    if (!v)
        return;
    for (uint32_t k = 0; k < v->count; ++k) {
        json_read_free(&v->items[k]);
        if (v->keys)
            free(v->keys[k]);
    }
    free(v->items);
    free(v->keys);
    free(v->string);
    v->items = NULL;
    v->keys = NULL;
    v->string = NULL;
    v->count = 0;
}

const json_value *json_member(const json_value *v, const char *key)
{
    if (!v || v->type != JSON_OBJECT)
        return NULL;
    for (uint32_t k = 0; k < v->count; ++k)
        if (strcmp(v->keys[k], key) == 0)
            return &v->items[k];
    return NULL;
}

const char *json_type_name(json_type type)
{
    switch (type) {
    case JSON_NULL: return "null";
    case JSON_FALSE:
    case JSON_TRUE: return "a boolean";
    case JSON_NUMBER: return "a number";
    case JSON_STRING: return "a string";
    case JSON_ARRAY: return "an array";
    case JSON_OBJECT: return "an object";
    }
    return "a value";
}
