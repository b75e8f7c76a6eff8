/* PNG (ISO/IEC 15948): signature, IHDR, IDAT with a zlib stream of stored
 * (uncompressed) deflate blocks (RFC 1950/1951), IEND. CRC-32 over chunk type
 * and data; Adler-32 over the uncompressed scanlines. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "png_write.h"

static uint32_t crc_update(uint32_t crc, const uint8_t *p, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        crc ^= p[i];
        for (int k = 0; k < 8; ++k)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return crc;
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static bool write_chunk(FILE *f, const char type[4], const uint8_t *data, size_t n)
{
    uint8_t head[8];
    put32(head, (uint32_t)n);
    memcpy(head + 4, type, 4);
    uint32_t crc = crc_update(0xFFFFFFFFu, (const uint8_t *)type, 4);
    crc = crc_update(crc, data, n) ^ 0xFFFFFFFFu;
    uint8_t tail[4];
    put32(tail, crc);
    return fwrite(head, 1, 8, f) == 8 && (n == 0 || fwrite(data, 1, n, f) == n) && fwrite(tail, 1, 4, f) == 4;
}

bool png_write_rgba8(const char *path, const uint8_t *rgba, uint32_t width, uint32_t height, bool bottom_up)
{
    size_t row = (size_t)width * 4 + 1; /* filter byte + pixels */
    size_t raw_size = row * height;
    size_t blocks = (raw_size + 65534) / 65535;
    size_t z_size = 2 + raw_size + blocks * 5 + 4;
    uint8_t *raw = malloc(raw_size), *z = malloc(z_size);
    if (!raw || !z) {
        free(raw);
        free(z);
        return false;
    }
    for (uint32_t y = 0; y < height; ++y) {
        uint32_t src = bottom_up ? height - 1 - y : y;
        raw[y * row] = 0; /* filter: none */
        memcpy(raw + y * row + 1, rgba + (size_t)src * width * 4, (size_t)width * 4);
    }
    size_t o = 0;
    z[o++] = 0x78; /* deflate, 32 KiB window */
    z[o++] = 0x01; /* (0x7801 % 31 == 0), no dictionary, fastest */
    uint32_t a = 1, b = 0;
    for (size_t done = 0; done < raw_size;) {
        size_t n = raw_size - done > 65535 ? 65535 : raw_size - done;
        z[o++] = done + n == raw_size ? 1 : 0; /* BFINAL, BTYPE = 00 (stored) */
        z[o++] = (uint8_t)n;
        z[o++] = (uint8_t)(n >> 8);
        z[o++] = (uint8_t)~n;
        z[o++] = (uint8_t)(~n >> 8);
        memcpy(z + o, raw + done, n);
        for (size_t i = 0; i < n; ++i) {
            a = (a + raw[done + i]) % 65521u;
            b = (b + a) % 65521u;
        }
        o += n;
        done += n;
    }
    put32(z + o, (b << 16) | a);
    o += 4;
    uint8_t ihdr[13];
    put32(ihdr, width);
    put32(ihdr + 4, height);
    ihdr[8] = 8;  /* bit depth */
    ihdr[9] = 6;  /* RGBA */
    ihdr[10] = ihdr[11] = ihdr[12] = 0;
    FILE *f = fopen(path, "wb");
    bool ok = f != NULL;
    static const uint8_t signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    ok = ok && fwrite(signature, 1, 8, f) == 8;
    ok = ok && write_chunk(f, "IHDR", ihdr, sizeof ihdr);
    ok = ok && write_chunk(f, "IDAT", z, o);
    ok = ok && write_chunk(f, "IEND", NULL, 0);
    if (f && fclose(f) != 0)
        ok = false;
    free(raw);
    free(z);
    return ok;
}
