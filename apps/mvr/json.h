/* A minimal streaming JSON writer for the CLI's machine-readable output. */
#ifndef MVR_APP_JSON_H
#define MVR_APP_JSON_H

#include <stdbool.h>
#include <stdio.h>

typedef struct json_writer {
    FILE *out;
    int depth;
    bool need_comma[32];
    char closer[32];             /* '}' or ']' per depth */
} json_writer;

/* s as a JSON string (quoted, escaped), for hand-written one-line JSON. */
void json_escaped(FILE *out, const char *s);
void json_begin_object(json_writer *w, const char *key); /* key NULL: top level or array element */
void json_end_object(json_writer *w);
void json_begin_array(json_writer *w, const char *key);
void json_end_array(json_writer *w);
void json_string(json_writer *w, const char *key, const char *value);
void json_int(json_writer *w, const char *key, long long value);
void json_double(json_writer *w, const char *key, double value);       /* 9 significant digits */
void json_double_exact(json_writer *w, const char *key, double value); /* 17: the same double read back */
void json_bool(json_writer *w, const char *key, bool value);
void json_null(json_writer *w, const char *key);

#endif
