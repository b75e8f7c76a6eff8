/* SHA-256 (FIPS 180-4), written from the standard: the checksums of a
 * sharded run's records and manifest (run_units.c, run_merge.c). */
#ifndef MVR_APP_SHA256_H
#define MVR_APP_SHA256_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct sha256_state {
    uint32_t h[8];
    uint64_t length;             /* bytes hashed so far */
    uint8_t block[64];
    size_t used;                 /* bytes in block */
} sha256_state;

void sha256_init(sha256_state *s);
void sha256_update(sha256_state *s, const void *data, size_t size);
/* The digest as 64 lowercase hex digits and a NUL. */
void sha256_final_hex(sha256_state *s, char hex[65]);

/* The digest of data[0..size) as hex. */
void sha256_hex(const void *data, size_t size, char hex[65]);

/* The digest of a file's bytes and its size; false (errno set) when it
 * cannot be read. */
bool sha256_file(const char *path, char hex[65], uint64_t *size);

#endif
