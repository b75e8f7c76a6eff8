/*
 * auto's settled choices across processes (core/tuner.h's mvr_tuner_memory):
 * one small text file per decision and inputs, in the program cache folder,
 * so a later run with the same scene, views, size, outputs and GL starts on
 * the measured choice. Backend-free (POSIX files only).
 *
 * The folder is untrusted like the program binaries' (program_binary_file.h):
 * an entry carries a SipHash-2-4 tag under the user's key file, and is
 * ignored (a message says why) unless it is a regular file of at most
 * MVR_TUNER_MEMORY_MAX_FILE bytes, exactly in this layout, for exactly this
 * key, with values in range and a tag that verifies:
 *
 *   mvr-tuner 1
 *   key <the inputs, one line>
 *   chosen <0|1>
 *   log_ratio <%.9f, |x| <= 4>
 *   spread <%.9f, 0..16>
 *   runs <1..MVR_TUNER_MEMORY_RUNS>
 *   tag <16 hex digits: SipHash of every byte before this line>
 *
 * File name: <dir>/tuner-<FNV-1a 64 of the key, 16 hex>-u<euid>.txt. Written
 * to a new temporary file (O_EXCL, never following a link) beside it and
 * renamed into place, so a reader sees the old entry or the new, whole.
 */
#ifndef MVR_TUNER_MEMORY_H
#define MVR_TUNER_MEMORY_H

#include <stddef.h>

#include "program_binary_file.h" /* the user's key: mvr_program_cache_key */
#include "tuner.h"

#define MVR_TUNER_MEMORY_MAX_KEY 1024u
#define MVR_TUNER_MEMORY_MAX_FILE 2048u

typedef enum mvr_tuner_memory_status {
    MVR_TUNER_MEMORY_MISS = 0,   /* no file */
    MVR_TUNER_MEMORY_HIT,
    MVR_TUNER_MEMORY_STALE,      /* an authentic entry for other inputs (a hash collision) */
    MVR_TUNER_MEMORY_CORRUPT     /* anything else: unreadable, not a file, bad layout, values or tag */
} mvr_tuner_memory_status;

/* The entry's path for a key: false if it does not fit (or the key is empty,
 * too long or holds a line break). */
bool mvr_tuner_memory_path(const char *dir, const char *key, char *out, size_t size);

/* Reads and checks one entry; why[why_size] says what was wrong for STALE
 * and CORRUPT. Never blocks on a FIFO, never follows a link. */
mvr_tuner_memory_status mvr_tuner_memory_read(const char *path, const mvr_program_cache_key *mac_key,
                                              const char *key, mvr_tuner_memory *out, char *why, size_t why_size);

/* Writes one entry (temporary file, then rename); false and why on failure. */
bool mvr_tuner_memory_write(const char *path, const mvr_program_cache_key *mac_key, const char *key,
                            const mvr_tuner_memory *m, char *why, size_t why_size);

#endif
