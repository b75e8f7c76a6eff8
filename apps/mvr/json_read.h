/* A small JSON reader for files the CLI is handed (camera files): the whole
 * text into a tree, strictly (RFC 8259: no NaN, no comments, no trailing
 * commas), with limits on nesting, number of values and number length, and
 * the line of each value for messages. Numbers that overflow a double, a
 * NUL inside a string and duplicate keys in one object are refused. Time is
 * linear in the text's size (duplicates: a hash set per object, keyed
 * afresh for each parse, so no file can flood it). */
#ifndef MVR_APP_JSON_READ_H
#define MVR_APP_JSON_READ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef enum json_type {
    JSON_NULL = 0,
    JSON_FALSE,
    JSON_TRUE,
    JSON_NUMBER,
    JSON_STRING,
    JSON_ARRAY,
    JSON_OBJECT
} json_type;

typedef struct json_value json_value;
struct json_value {
    json_type type;
    uint32_t line;         /* 1-based line where the value starts */
    double number;         /* JSON_NUMBER: finite */
    char *string;          /* JSON_STRING: UTF-8, NUL-terminated, no NUL inside */
    uint32_t count;        /* JSON_ARRAY items, JSON_OBJECT members */
    json_value *items;     /* the items, or the members' values */
    char **keys;           /* JSON_OBJECT: the members' names */
};

#define JSON_READ_MAX_DEPTH 64
#define JSON_READ_MAX_VALUES 2000000u
#define JSON_READ_MAX_NUMBER_CHARS 400

/* Parses text[0..size) (a leading UTF-8 byte order mark is skipped) into
 * *out. false with why ("line 3: expected ',' or ']' after an array item")
 * on malformed or over-limit input; nothing to free then. */
bool json_read(const char *text, size_t size, json_value *out, char *why, size_t why_size);
void json_read_free(json_value *v);

/* The member named key of an object; NULL when v is no object or has none. */
const json_value *json_member(const json_value *v, const char *key);

/* "a number", "an object", ... for messages. */
const char *json_type_name(json_type type);

#endif
