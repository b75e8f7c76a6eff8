/*
 * Program binary cache files: one file per shader variant and driver, holding
 * what glGetProgramBinary returned. Backend-free (C stdio only): the GL side
 * (gl/program.c) decides what to do with a payload; this module only makes
 * sure a payload it hands back is exactly what was written for the same key.
 *
 * File name: <dir>/<variant name>-<driver hash, 16 hex>.mvrbin, so a new
 * driver gets new files and a new mvr (other shader source, same variant
 * name) finds its old file stale by the key in the header and overwrites it.
 *
 * Layout (little-endian):
 *   8  magic "MVRPBIN1"
 *   4  binary format (GLenum from glGetProgramBinary)
 *   4  driver string length D (<= 1024)
 *   8  key (FNV-1a 64 of driver string and both stage sources)
 *   8  payload size P (<= 64 MiB)
 *   8  checksum (FNV-1a 64 of driver string, key, format and payload)
 *   D  driver string
 *   P  payload
 * and nothing after it. Writes go to a temporary file renamed into place, so
 * readers never see half a file from this process; anything else (a crash, a
 * disk error, a concurrent writer, an edit) fails the checks above.
 */
#ifndef MVR_PROGRAM_BINARY_FILE_H
#define MVR_PROGRAM_BINARY_FILE_H

#include <stddef.h>
#include <stdint.h>

#define MVR_PROGRAM_BINARY_MAX_PAYLOAD ((uint64_t)64 << 20)
#define MVR_PROGRAM_BINARY_MAX_DRIVER 1024u

typedef enum mvr_program_binary_status {
    MVR_PROGRAM_BINARY_MISS = 0,    /* no file */
    MVR_PROGRAM_BINARY_HIT,         /* payload checked and returned */
    MVR_PROGRAM_BINARY_STALE,       /* a well-formed file for another key or driver */
    MVR_PROGRAM_BINARY_CORRUPT      /* anything else: bad magic, sizes, checksum, trailing bytes */
} mvr_program_binary_status;

uint64_t mvr_fnv1a64(uint64_t hash, const void *data, size_t size);
#define MVR_FNV1A64_INIT 0xcbf29ce484222325ull

/* Key of a variant's binary: driver identity and both stage sources. */
uint64_t mvr_program_binary_key(const char *driver, const char *vertex_source, const char *fragment_source);

/* The cache file's path for a variant name and driver: false if it does not fit. */
int mvr_program_binary_path(const char *dir, const char *variant_name, const char *driver, char *out,
                            size_t size);

/* Reads and checks one file. On HIT *payload is malloc'd (caller frees) and
 * *format / *payload_size are set. why[why_size] says what was wrong on
 * STALE / CORRUPT. */
mvr_program_binary_status mvr_program_binary_read(const char *path, const char *driver, uint64_t key,
                                                  uint32_t *format, void **payload, size_t *payload_size,
                                                  char *why, size_t why_size);

/* Writes one file (temporary name, then rename). 0 and why on failure. */
int mvr_program_binary_write(const char *path, const char *driver, uint64_t key, uint32_t format,
                             const void *payload, size_t payload_size, char *why, size_t why_size);

#endif
