#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core_util.h"

void mvr_str_copy(char *dst, size_t size, const char *src)
{
    if (!dst || size == 0)
        return;
    if (!src)
        src = "";
    size_t n = strlen(src);
    if (n >= size)
        n = size - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

void mvr_str_vformat(char *dst, size_t size, const char *fmt, va_list ap)
{
    if (!dst || size == 0)
        return;
    int n = vsnprintf(dst, size, fmt, ap);
    if (n < 0)
        dst[0] = '\0';
}

void mvr_str_format(char *dst, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    mvr_str_vformat(dst, size, fmt, ap);
    va_end(ap);
}

int mvr_size_mul(size_t a, size_t b, size_t *out)
{
    if (a != 0 && b > SIZE_MAX / a)
        return 0;
    *out = a * b;
    return 1;
}

int mvr_size_add(size_t a, size_t b, size_t *out)
{
    if (b > SIZE_MAX - a)
        return 0;
    *out = a + b;
    return 1;
}

static int sb_reserve(mvr_str_builder *sb, size_t extra)
{
    size_t need;
    if (sb->failed || !mvr_size_add(sb->length, extra, &need) || !mvr_size_add(need, 1, &need)) {
        sb->failed = 1;
        return 0;
    }
    if (need <= sb->capacity)
        return 1;
    size_t cap = sb->capacity ? sb->capacity : 256;
    while (cap < need) {
        if (!mvr_size_mul(cap, 2, &cap)) {
            sb->failed = 1;
            return 0;
        }
    }
    char *data = realloc(sb->data, cap);
    if (!data) {
        sb->failed = 1;
        return 0;
    }
    sb->data = data;
    sb->capacity = cap;
    return 1;
}

void mvr_sb_append(mvr_str_builder *sb, const char *text)
{
    size_t n = strlen(text);
    if (!sb_reserve(sb, n))
        return;
    memcpy(sb->data + sb->length, text, n + 1);
    sb->length += n;
}

void mvr_sb_appendf(mvr_str_builder *sb, const char *fmt, ...)
{
    va_list ap, ap2;
    va_start(ap, fmt);
    va_copy(ap2, ap);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0 || !sb_reserve(sb, (size_t)n)) {
        sb->failed = 1;
        va_end(ap2);
        return;
    }
    vsnprintf(sb->data + sb->length, (size_t)n + 1, fmt, ap2);
    va_end(ap2);
    sb->length += (size_t)n;
}

void mvr_sb_free(mvr_str_builder *sb)
{
    free(sb->data);
    sb->data = NULL;
    sb->length = sb->capacity = 0;
    sb->failed = 0;
}

bool mvr_array_grow(void **items, uint32_t *cap, uint32_t count, size_t elem)
{
    if (count < *cap)
        return true;
    uint32_t new_cap = *cap ? *cap * 2 : 8;
    size_t bytes;
    if (new_cap <= *cap || !mvr_size_mul(new_cap, elem, &bytes))
        return false;
    void *p = realloc(*items, bytes);
    if (!p)
        return false;
    *items = p;
    *cap = new_cap;
    return true;
}
