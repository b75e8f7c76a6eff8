#include "program_binary_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core_util.h"

static const char magic[8] = {'M', 'V', 'R', 'P', 'B', 'I', 'N', '1'};
enum { HEADER_SIZE = 8 + 4 + 4 + 8 + 8 + 8 };

/* FNV-1a, 64-bit (Fowler, Noll, Vo; offset basis 14695981039346656037,
 * prime 1099511628211): enough to notice corruption, not an adversary. */
uint64_t mvr_fnv1a64(uint64_t hash, const void *data, size_t size)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < size; ++i) {
        hash ^= p[i];
        hash *= 0x100000001b3ull;
    }
    return hash;
}

uint64_t mvr_program_binary_key(const char *driver, const char *vs, const char *fs)
{
    /* lengths go in too, so moving text between the parts changes the key */
    uint64_t h = MVR_FNV1A64_INIT;
    const char *parts[3] = {driver, vs, fs};
    for (int i = 0; i < 3; ++i) {
        uint64_t n = strlen(parts[i]);
        h = mvr_fnv1a64(h, &n, sizeof n);
        h = mvr_fnv1a64(h, parts[i], (size_t)n);
    }
    return h;
}

int mvr_program_binary_path(const char *dir, const char *variant_name, const char *driver, char *out,
                            size_t size)
{
    uint64_t dh = mvr_fnv1a64(MVR_FNV1A64_INIT, driver, strlen(driver));
    int n = snprintf(out, size, "%s/%s-%016llx.mvrbin", dir, variant_name, (unsigned long long)dh);
    return n > 0 && (size_t)n < size;
}

/* The checksum covers the driver string, the key, the format and the
 * payload, so any flipped bit reads as damage, not as another driver. */
static uint64_t file_checksum(const char *driver, size_t driver_len, uint64_t key, uint32_t format,
                              const void *payload, size_t size)
{
    uint64_t h = mvr_fnv1a64(MVR_FNV1A64_INIT, driver, driver_len);
    h = mvr_fnv1a64(h, &key, sizeof key);
    h = mvr_fnv1a64(h, &format, sizeof format);
    return mvr_fnv1a64(h, payload, size);
}

static void put_u32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}

static void put_u64(unsigned char *p, uint64_t v)
{
    for (int i = 0; i < 8; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}

static uint32_t get_u32(const unsigned char *p)
{
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i)
        v = (v << 8) | p[i];
    return v;
}

static uint64_t get_u64(const unsigned char *p)
{
    uint64_t v = 0;
    for (int i = 7; i >= 0; --i)
        v = (v << 8) | p[i];
    return v;
}

mvr_program_binary_status mvr_program_binary_read(const char *path, const char *driver, uint64_t key,
                                                  uint32_t *format, void **payload, size_t *payload_size,
                                                  char *why, size_t why_size)
{
    *payload = NULL;
    *payload_size = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return MVR_PROGRAM_BINARY_MISS;
    mvr_program_binary_status status = MVR_PROGRAM_BINARY_CORRUPT;
    unsigned char header[HEADER_SIZE];
    char stored_driver[MVR_PROGRAM_BINARY_MAX_DRIVER + 1];
    unsigned char *data = NULL;
    if (fread(header, 1, sizeof header, f) != sizeof header || memcmp(header, magic, sizeof magic) != 0) {
        mvr_str_copy(why, why_size, "not an mvr program binary (short file or wrong magic)");
        goto done;
    }
    uint32_t fmt = get_u32(header + 8);
    uint32_t driver_len = get_u32(header + 12);
    uint64_t stored_key = get_u64(header + 16);
    uint64_t size = get_u64(header + 24);
    uint64_t checksum = get_u64(header + 32);
    if (driver_len > MVR_PROGRAM_BINARY_MAX_DRIVER || size == 0 || size > MVR_PROGRAM_BINARY_MAX_PAYLOAD) {
        mvr_str_format(why, why_size, "header sizes out of range (driver %u bytes, payload %llu bytes)",
                       (unsigned)driver_len, (unsigned long long)size);
        goto done;
    }
    if (fread(stored_driver, 1, driver_len, f) != driver_len) {
        mvr_str_copy(why, why_size, "truncated in the driver string");
        goto done;
    }
    stored_driver[driver_len] = '\0';
    data = malloc((size_t)size);
    if (!data) {
        mvr_str_copy(why, why_size, "out of memory");
        goto done;
    }
    if (fread(data, 1, (size_t)size, f) != size) {
        mvr_str_format(why, why_size, "truncated: payload of %llu bytes announced", (unsigned long long)size);
        goto done;
    }
    if (fgetc(f) != EOF) {
        mvr_str_copy(why, why_size, "bytes after the payload");
        goto done;
    }
    if (file_checksum(stored_driver, driver_len, stored_key, fmt, data, (size_t)size) != checksum) {
        mvr_str_copy(why, why_size, "checksum mismatch");
        goto done;
    }
    /* well-formed from here on: a mismatch means stale, not damaged */
    if (strcmp(stored_driver, driver) != 0) {
        mvr_str_format(why, why_size, "written by another driver (%s)", stored_driver);
        status = MVR_PROGRAM_BINARY_STALE;
        goto done;
    }
    if (stored_key != key) {
        mvr_str_copy(why, why_size, "written for other shader source (key mismatch)");
        status = MVR_PROGRAM_BINARY_STALE;
        goto done;
    }
    *format = fmt;
    *payload = data;
    *payload_size = (size_t)size;
    data = NULL;
    status = MVR_PROGRAM_BINARY_HIT;
done:
    free(data);
    fclose(f);
    return status;
}

int mvr_program_binary_write(const char *path, const char *driver, uint64_t key, uint32_t format,
                             const void *payload, size_t payload_size, char *why, size_t why_size)
{
    size_t driver_len = strlen(driver);
    if (driver_len > MVR_PROGRAM_BINARY_MAX_DRIVER || payload_size == 0 ||
        (uint64_t)payload_size > MVR_PROGRAM_BINARY_MAX_PAYLOAD) {
        mvr_str_format(why, why_size, "cannot store a %zu-byte binary", payload_size);
        return 0;
    }
    /* the temporary name differs per writer object and call site address;
     * a clash between processes is caught by the reader's checks */
    char tmp[4096];
    int n = snprintf(tmp, sizeof tmp, "%s.%p.tmp", path, (const void *)&driver_len);
    if (n <= 0 || (size_t)n >= sizeof tmp) {
        mvr_str_copy(why, why_size, "path too long");
        return 0;
    }
    unsigned char header[HEADER_SIZE];
    memcpy(header, magic, sizeof magic);
    put_u32(header + 8, format);
    put_u32(header + 12, (uint32_t)driver_len);
    put_u64(header + 16, key);
    put_u64(header + 24, (uint64_t)payload_size);
    put_u64(header + 32, file_checksum(driver, driver_len, key, format, payload, payload_size));
    FILE *f = fopen(tmp, "wb");
    if (!f) {
        mvr_str_format(why, why_size, "cannot create %s", tmp);
        return 0;
    }
    int ok = fwrite(header, 1, sizeof header, f) == sizeof header &&
             fwrite(driver, 1, driver_len, f) == driver_len &&
             fwrite(payload, 1, payload_size, f) == payload_size;
    ok = (fclose(f) == 0) && ok;
    if (!ok) {
        remove(tmp);
        mvr_str_format(why, why_size, "cannot write %s", tmp);
        return 0;
    }
    if (rename(tmp, path) != 0) {
        remove(tmp);
        mvr_str_format(why, why_size, "cannot rename %s into place", tmp);
        return 0;
    }
    return 1;
}
