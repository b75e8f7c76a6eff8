#include "json.h"
#include <math.h>

static void write_escaped(FILE *out, const char *s)
{
    fputc('"', out);
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; ++p) {
        switch (*p) {
        case '"': fputs("\\\"", out); break;
        case '\\': fputs("\\\\", out); break;
        case '\n': fputs("\\n", out); break;
        case '\r': fputs("\\r", out); break;
        case '\t': fputs("\\t", out); break;
        default:
            if (*p < 0x20)
                fprintf(out, "\\u%04x", *p);
            else
                fputc(*p, out);
        }
    }
    fputc('"', out);
}

void json_escaped(FILE *out, const char *s)
{
    write_escaped(out, s);
}

static void key_prefix(json_writer *w, const char *key)
{
    if (w->depth > 0 && w->need_comma[w->depth])
        fputc(',', w->out);
    if (w->depth > 0) {
        fputc('\n', w->out);
        for (int i = 0; i < w->depth; ++i)
            fputs("  ", w->out);
        w->need_comma[w->depth] = true;
    }
    if (key) {
        write_escaped(w->out, key);
        fputs(": ", w->out);
    }
}

static void begin(json_writer *w, const char *key, char open, char close)
{
    key_prefix(w, key);
    fputc(open, w->out);
    if (w->depth + 1 < (int)(sizeof w->need_comma / sizeof w->need_comma[0]))
        w->depth++;
    w->need_comma[w->depth] = false;
    w->closer[w->depth] = close;
}

static void end(json_writer *w)
{
    bool had_members = w->need_comma[w->depth];
    char close = w->closer[w->depth] ? w->closer[w->depth] : '}';
    if (w->depth > 0)
        w->depth--;
    if (had_members) {
        fputc('\n', w->out);
        for (int i = 0; i < w->depth; ++i)
            fputs("  ", w->out);
    }
    fputc(close, w->out);
    if (w->depth == 0)
        fputc('\n', w->out);
}

void json_begin_object(json_writer *w, const char *key)
{
    begin(w, key, '{', '}');
}

void json_end_object(json_writer *w)
{
    end(w);
}

void json_begin_array(json_writer *w, const char *key)
{
    begin(w, key, '[', ']');
}

void json_end_array(json_writer *w)
{
    end(w);
}

void json_string(json_writer *w, const char *key, const char *value)
{
    key_prefix(w, key);
    write_escaped(w->out, value);
}

void json_int(json_writer *w, const char *key, long long value)
{
    key_prefix(w, key);
    fprintf(w->out, "%lld", value);
}

void json_double(json_writer *w, const char *key, double value)
{
    key_prefix(w, key);
    if (isfinite(value))
        fprintf(w->out, "%.9g", value);
    else
        fputs("null", w->out); /* JSON has no NaN or infinity */
}

void json_double_exact(json_writer *w, const char *key, double value)
{
    key_prefix(w, key);
    if (isfinite(value))
        fprintf(w->out, "%.17g", value); /* round-trips every double */
    else
        fputs("null", w->out);
}

void json_bool(json_writer *w, const char *key, bool value)
{
    key_prefix(w, key);
    fputs(value ? "true" : "false", w->out);
}

void json_null(json_writer *w, const char *key)
{
    key_prefix(w, key);
    fputs("null", w->out);
}
