/* Backend-free helpers shared by every module: messages, logging, strings,
 * overflow-safe sizes. No GL header, no global state. */
#ifndef MVR_CORE_UTIL_H
#define MVR_CORE_UTIL_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mvr/mvr.h"

#if defined(__GNUC__) || defined(__clang__)
#define MVR_PRINTF(fmt_index, first_arg) __attribute__((format(printf, fmt_index, first_arg)))
#else
#define MVR_PRINTF(fmt_index, first_arg)
#endif

#define MVR_ARRAY_COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* Copies src into dst[size], always terminated, truncating if needed. */
void mvr_str_copy(char *dst, size_t size, const char *src);
/* snprintf into dst[size]; never overflows, always terminated. */
void mvr_str_format(char *dst, size_t size, const char *fmt, ...) MVR_PRINTF(3, 4);
void mvr_str_vformat(char *dst, size_t size, const char *fmt, va_list ap) MVR_PRINTF(3, 0);

/* A growable string for generated text (shader sources, JSON). A failed
 * allocation sets failed and later appends do nothing. */
typedef struct mvr_str_builder {
    char *data;
    size_t length;
    size_t capacity;
    int failed;
} mvr_str_builder;

void mvr_sb_append(mvr_str_builder *sb, const char *text);
void mvr_sb_appendf(mvr_str_builder *sb, const char *fmt, ...) MVR_PRINTF(2, 3);
void mvr_sb_free(mvr_str_builder *sb);

/* Grows a malloc'd array *items (capacity *cap, elem bytes each) to hold
 * count + 1 elements: doubling from 8; false on overflow or out of memory. */
bool mvr_array_grow(void **items, uint32_t *cap, uint32_t count, size_t elem);

/* Overflow-checked arithmetic: returns 0 and leaves *out alone on overflow. */
int mvr_size_mul(size_t a, size_t b, size_t *out);
int mvr_size_add(size_t a, size_t b, size_t *out);

/* Sends a formatted message through the logger if its level passes. */
void mvr_log(const mvr_logger *logger, mvr_log_level level, mvr_log_id id, const char *fmt, ...)
    MVR_PRINTF(4, 5);

/* Records a failure of a call on an object: formats the message into the
 * object's last-error buffer, logs it as MVR_LOG_ID_ERROR_RESULT, returns result. */
mvr_result mvr_error_record(char *buf, size_t size, const mvr_logger *logger, mvr_result result,
                            const char *fmt, va_list ap) MVR_PRINTF(5, 0);

/* Fills an optional mvr_error and returns result, for create calls. */
mvr_result mvr_error_set(mvr_error *error, mvr_result result, const char *fmt, ...)
    MVR_PRINTF(3, 4);

#endif
