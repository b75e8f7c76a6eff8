/* auto's settled choices across processes (tuner_memory.h). */
#define _POSIX_C_SOURCE 200809L
#include "tuner_memory.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core_util.h"

static const char header[] = "mvr-tuner 1\n";

static bool key_ok(const char *key)
{
    size_t n = key ? strlen(key) : 0;
    return n > 0 && n <= MVR_TUNER_MEMORY_MAX_KEY && !strpbrk(key, "\r\n");
}

bool mvr_tuner_memory_path(const char *dir, const char *key, char *out, size_t size)
{
    if (!dir || !dir[0] || !key_ok(key))
        return false;
    uint64_t h = mvr_fnv1a64(MVR_FNV1A64_INIT, key, strlen(key));
    int n = snprintf(out, size, "%s/tuner-%016" PRIx64 "-u%lu.txt", dir, h, (unsigned long)geteuid());
    return n > 0 && (size_t)n < size;
}

/* The body (every line before the tag's) for an entry; its length, 0 if it does not fit. */
static size_t body(char *out, size_t size, const char *key, const mvr_tuner_memory *m)
{
    int n = snprintf(out, size, "%skey %s\nchosen %u\nlog_ratio %.9f\nspread %.9f\nruns %u\n", header, key,
                     m->chosen, m->log_ratio, m->spread, m->runs);
    return n > 0 && (size_t)n < size ? (size_t)n : 0;
}

static bool values_ok(const mvr_tuner_memory *m)
{
    return m->chosen < MVR_TUNER_CANDIDATES && isfinite(m->log_ratio) && fabs(m->log_ratio) <= 4.0 &&
           isfinite(m->spread) && m->spread >= 0.0 && m->spread <= 16.0 && m->runs >= 1 &&
           m->runs <= MVR_TUNER_MEMORY_RUNS;
}

/* The whole file as a string, if it is a regular file of a plausible size
 * without a NUL byte: its length, or -1 and why. */
static long slurp(const char *path, char *buf, size_t size, bool *missing, char *why, size_t why_size)
{
    size_t got = 0;
    int absent = 0;
    int ok = mvr_cache_file_read(path, buf, size - 1, &got, &absent, why, why_size);
    *missing = absent != 0;
    if (!ok) {
        if (absent)
            mvr_str_copy(why, why_size, "no file");
        return -1;
    }
    buf[got] = 0;
    if (strlen(buf) != got) {
        mvr_str_copy(why, why_size, "a NUL byte");
        return -1;
    }
    return (long)got;
}

mvr_tuner_memory_status mvr_tuner_memory_read(const char *path, const mvr_program_cache_key *mac_key,
                                              const char *key, mvr_tuner_memory *out, char *why, size_t why_size)
{
    memset(out, 0, sizeof *out);
    char buf[MVR_TUNER_MEMORY_MAX_FILE + 1];
    bool missing;
    long n = slurp(path, buf, sizeof buf, &missing, why, why_size);
    if (n < 0)
        return missing ? MVR_TUNER_MEMORY_MISS : MVR_TUNER_MEMORY_CORRUPT;
    /* the tag line: the last one */
    char *tag = NULL;
    if (n >= 22 && buf[n - 1] == '\n') {
        buf[n - 1] = 0;
        tag = strrchr(buf, '\n');
    }
    if (!tag || strncmp(tag + 1, "tag ", 4) != 0 || strlen(tag + 5) != 16 ||
        strspn(tag + 5, "0123456789abcdef") != 16) {
        mvr_str_copy(why, why_size, "no tag line at the end");
        return MVR_TUNER_MEMORY_CORRUPT;
    }
    size_t body_len = (size_t)(tag + 1 - buf);
    uint64_t want = strtoull(tag + 5, NULL, 16);
    if (mvr_siphash24(mac_key->bytes, buf, body_len) != want) {
        mvr_str_copy(why, why_size, "its tag does not verify");
        return MVR_TUNER_MEMORY_CORRUPT;
    }
    tag[1] = 0;
    /* authentic: the layout, exactly as written */
    const char *line = buf + strlen(header);
    const char *key_end = strncmp(buf, header, strlen(header)) == 0 && strncmp(line, "key ", 4) == 0
                              ? strchr(line + 4, '\n') : NULL;
    mvr_tuner_memory m;
    char check[MVR_TUNER_MEMORY_MAX_FILE + 1];
    int used = 0;
    if (!key_end || sscanf(key_end + 1, "chosen %u\nlog_ratio %lf\nspread %lf\nruns %u\n%n", &m.chosen, &m.log_ratio,
                           &m.spread, &m.runs, &used) != 4 || key_end[1 + used] != 0 || !values_ok(&m)) {
        mvr_str_copy(why, why_size, "not an mvr-tuner 1 entry, or values out of range");
        return MVR_TUNER_MEMORY_CORRUPT;
    }
    if ((size_t)(key_end - (line + 4)) != strlen(key) || strncmp(line + 4, key, strlen(key)) != 0) {
        mvr_str_copy(why, why_size, "written for other inputs");
        return MVR_TUNER_MEMORY_STALE;
    }
    /* and canonical: what writing these values gives (no stray spaces or digits) */
    if (body(check, sizeof check, key, &m) != body_len || memcmp(check, buf, body_len) != 0) {
        mvr_str_copy(why, why_size, "not in the written form");
        return MVR_TUNER_MEMORY_CORRUPT;
    }
    *out = m;
    return MVR_TUNER_MEMORY_HIT;
}

bool mvr_tuner_memory_write(const char *path, const mvr_program_cache_key *mac_key, const char *key,
                            const mvr_tuner_memory *m, char *why, size_t why_size)
{
    char buf[MVR_TUNER_MEMORY_MAX_FILE + 1];
    size_t n = key_ok(key) && values_ok(m) ? body(buf, sizeof buf - 24, key, m) : 0;
    if (!n) {
        mvr_str_copy(why, why_size, "nothing valid to store");
        return false;
    }
    n += (size_t)snprintf(buf + n, sizeof buf - n, "tag %016" PRIx64 "\n", mvr_siphash24(mac_key->bytes, buf, n));
    return mvr_cache_file_write(path, buf, n, why, why_size) != 0;
}
