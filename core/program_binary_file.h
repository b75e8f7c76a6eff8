/*
 * Program binary cache files: one file per shader variant, driver and user,
 * holding what glGetProgramBinary returned. Backend-free (POSIX files only):
 * the GL side (gl/program.c) decides what to do with a payload; this module
 * only makes sure a payload it hands back is exactly what this user wrote for
 * the same key.
 *
 * The cache folder is untrusted: other users, or anything that can write
 * there, may put any bytes, FIFOs, links or devices in it, and a driver fed
 * a forged binary corrupts memory (Mesa checks its blob with a CRC32, which
 * a forger recomputes). So every entry carries a SipHash-2-4 tag under a
 * 16-byte key only this user can read, the key file <dir>/.mvr-key-<euid>;
 * an entry whose tag does not verify is never handed back.
 *
 * File name: <dir>/<variant name>-<driver hash, 16 hex>-u<euid>.mvrbin, so a
 * new driver gets new files, users sharing a folder do not overwrite each
 * other's entries, and a new mvr (other shader source, same variant name)
 * finds its old file stale by the key in the header and overwrites it.
 *
 * Layout (little-endian):
 *   8  magic "MVRPBIN2"
 *   4  binary format (GLenum from glGetProgramBinary)
 *   4  driver string length D (<= 1024)
 *   8  key (FNV-1a 64 of driver string and both stage sources)
 *   8  payload size P (1 .. 64 MiB)
 *   D  driver string
 *   P  payload
 *   8  tag: SipHash-2-4, under the user's key, of every byte before it
 * and nothing after it. Writes go to a new temporary file (O_EXCL, never
 * following a link) in the same folder, renamed into place.
 */
#ifndef MVR_PROGRAM_BINARY_FILE_H
#define MVR_PROGRAM_BINARY_FILE_H

#include <stddef.h>
#include <stdint.h>

#define MVR_PROGRAM_BINARY_MAX_PAYLOAD ((uint64_t)64 << 20)
#define MVR_PROGRAM_BINARY_MAX_DRIVER 1024u
#define MVR_PROGRAM_CACHE_KEY_SIZE 16u

typedef enum mvr_program_binary_status {
    MVR_PROGRAM_BINARY_MISS = 0,        /* no file */
    MVR_PROGRAM_BINARY_HIT,             /* payload authenticated and returned */
    MVR_PROGRAM_BINARY_STALE,           /* an authentic file for another key or driver, or an older format */
    MVR_PROGRAM_BINARY_CORRUPT,         /* wrong magic, sizes out of range, trailing or missing bytes */
    MVR_PROGRAM_BINARY_NOT_AUTHENTIC,   /* well-sized, but its tag does not verify under the user's key */
    MVR_PROGRAM_BINARY_UNUSABLE         /* not a regular file (link, FIFO, directory, device) or unreadable */
} mvr_program_binary_status;

/* The user's secret for the cache folder (from the key file). */
typedef struct mvr_program_cache_key {
    unsigned char bytes[MVR_PROGRAM_CACHE_KEY_SIZE];
} mvr_program_cache_key;

uint64_t mvr_fnv1a64(uint64_t hash, const void *data, size_t size);
#define MVR_FNV1A64_INIT 0xcbf29ce484222325ull

/* SipHash-2-4 of data under a 16-byte key (Aumasson & Bernstein 2012). */
uint64_t mvr_siphash24(const unsigned char key[MVR_PROGRAM_CACHE_KEY_SIZE], const void *data, size_t size);

/* The key file's path in dir (<dir>/.mvr-key-<euid>): false if it does not fit. */
int mvr_program_cache_key_path(const char *dir, char *out, size_t size);

/* Reads this user's key from dir, creating the key file (random, mode 0600)
 * when there is none. 0 and why (naming the file and what is wrong) when it
 * is not a regular file owned by this user, is open to group or others, does
 * not hold exactly 16 bytes, or cannot be made: then the cache is not to be
 * used at all. */
int mvr_program_cache_key_load(const char *dir, mvr_program_cache_key *key, char *why, size_t why_size);

/* Key of a variant's binary: driver identity and both stage sources. */
uint64_t mvr_program_binary_key(const char *driver, const char *vertex_source, const char *fragment_source);

/* The cache file's path for a variant name and driver: false if it does not fit. */
int mvr_program_binary_path(const char *dir, const char *variant_name, const char *driver, char *out,
                            size_t size);

/* Reads and checks one file. On HIT *payload is malloc'd (caller frees) and
 * *format / *payload_size are set. why[why_size] says what was wrong on every
 * status but HIT and MISS. Never blocks on a FIFO, never follows a link. */
mvr_program_binary_status mvr_program_binary_read(const char *path, const mvr_program_cache_key *mac_key,
                                                  const char *driver, uint64_t key, uint32_t *format,
                                                  void **payload, size_t *payload_size, char *why,
                                                  size_t why_size);

/* Writes one file (a new temporary file, then rename). 0 and why on failure. */
int mvr_program_binary_write(const char *path, const mvr_program_cache_key *mac_key, const char *driver,
                             uint64_t key, uint32_t format, const void *payload, size_t payload_size, char *why,
                             size_t why_size);

/* Writes size bytes to path as the cache's files are written: a new temporary
 * file beside it (O_EXCL, O_NOFOLLOW, 0600), then rename, so no reader sees a
 * half-written file. 0 and why on failure (the temporary file removed). */
int mvr_cache_file_write(const char *path, const void *bytes, size_t size, char *why, size_t why_size);

/* Reads a whole cache file of 1..cap bytes into buf as the cache's files are
 * read: never following a link or waiting on a FIFO, only a regular file,
 * and only if it did not change size while read. 1 and *size on success;
 * 0 with *missing set where there is no file, else 0 and why. */
int mvr_cache_file_read(const char *path, void *buf, size_t cap, size_t *size, int *missing, char *why,
                        size_t why_size);

#endif
