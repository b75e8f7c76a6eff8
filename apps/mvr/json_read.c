/* The CLI's JSON reader (json_read.h): recursive descent over the whole
 * text, bounded in depth, value count and number length, so a hostile file
 * costs at most its own size in memory and a fixed stack. */
#define _POSIX_C_SOURCE 200809L
#include "json_read.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct reader {
    const char *p, *end;
    uint32_t line;
    uint32_t values;
    char *why;
    size_t why_size;
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

static bool value(reader *r, json_value *v, int depth);

/* Items or members into a growing array (doubling), then handed to v. */
static bool container(reader *r, json_value *v, int depth, bool object)
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
            for (uint32_t k = 0; k < v->count; ++k)
                if (strcmp(v->keys[k], key) == 0) {
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
    reader r = {text, text + size, 1, 0, why, why_size};
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
