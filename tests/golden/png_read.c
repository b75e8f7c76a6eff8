#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "png_read.h"

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static uint8_t *fail(char *why, size_t n, const char *msg, uint8_t *a, uint8_t *b)
{
    snprintf(why, n, "%s", msg);
    free(a);
    free(b);
    return NULL;
}

uint8_t *png_read_rgba8(const char *path, uint32_t *width, uint32_t *height, char *why, size_t why_size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return fail(why, why_size, "cannot open", NULL, NULL);
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *file = size > 0 ? malloc((size_t)size) : NULL;
    if (!file || fread(file, 1, (size_t)size, f) != (size_t)size) {
        fclose(f);
        return fail(why, why_size, "cannot read", file, NULL);
    }
    fclose(f);
    static const uint8_t sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    if (size < 8 + 25 || memcmp(file, sig, 8) != 0)
        return fail(why, why_size, "not a PNG", file, NULL);
    uint8_t *z = NULL;
    size_t z_len = 0;
    uint32_t w = 0, h = 0;
    for (size_t at = 8; at + 12 <= (size_t)size;) {
        uint32_t len = get32(file + at);
        if (at + 12 + (size_t)len > (size_t)size)
            return fail(why, why_size, "truncated chunk", file, z);
        const uint8_t *type = file + at + 4, *data = file + at + 8;
        if (memcmp(type, "IHDR", 4) == 0) {
            if (len != 13 || data[8] != 8 || data[9] != 6 || data[12] != 0)
                return fail(why, why_size, "not 8-bit RGBA, non-interlaced", file, z);
            w = get32(data);
            h = get32(data + 4);
        } else if (memcmp(type, "IDAT", 4) == 0) {
            uint8_t *n = realloc(z, z_len + len);
            if (!n)
                return fail(why, why_size, "out of memory", file, z);
            z = n;
            memcpy(z + z_len, data, len);
            z_len += len;
        }
        at += 12 + (size_t)len;
    }
    if (!w || !h || !z || z_len < 2 || (z[1] & 0x20))
        return fail(why, why_size, "no image data", file, z);
    size_t row = (size_t)w * 4 + 1, raw_len = row * h;
    uint8_t *raw = malloc(raw_len);
    if (!raw)
        return fail(why, why_size, "out of memory", file, z);
    size_t o = 0;
    for (size_t at = 2; o < raw_len;) {
        if (at + 5 > z_len || (z[at] & 6) != 0) {
            free(raw);
            return fail(why, why_size, "compressed deflate blocks: only mvr's stored PNGs are read", file, z);
        }
        size_t n = (size_t)z[at + 1] | (size_t)z[at + 2] << 8;
        if (at + 5 + n > z_len || o + n > raw_len) {
            free(raw);
            return fail(why, why_size, "truncated deflate block", file, z);
        }
        memcpy(raw + o, z + at + 5, n);
        o += n;
        at += 5 + n;
    }
    uint8_t *rgba = malloc((size_t)w * h * 4);
    if (!rgba) {
        free(raw);
        return fail(why, why_size, "out of memory", file, z);
    }
    for (uint32_t y = 0; y < h; ++y) {
        if (raw[y * row] != 0) {
            free(raw);
            free(rgba);
            return fail(why, why_size, "filtered scanlines: only mvr's stored PNGs are read", file, z);
        }
        memcpy(rgba + (size_t)y * w * 4, raw + y * row + 1, (size_t)w * 4);
    }
    free(raw);
    free(file);
    free(z);
    *width = w;
    *height = h;
    return rgba;
}
