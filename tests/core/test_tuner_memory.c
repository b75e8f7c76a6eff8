/* core: auto's remembered choices on disk (core/tuner_memory.h): an entry
 * written is read back exactly; one for other inputs is stale; a missing
 * one is a miss; a corrupted, truncated, forged, oversized, linked or
 * non-regular one is refused (corrupt, with a reason), never handed back. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mvr_test.h"
#include "tuner_memory.h"

static const char *const key = "v1 scene 0123456789abcdef views 6 size 256x256 decision view gl llvmpipe | 4.5";

static bool slurp(const char *path, char *buf, size_t size, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    *n = fread(buf, 1, size, f);
    fclose(f);
    return true;
}

static bool spit(const char *path, const char *buf, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return false;
    bool ok = fwrite(buf, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

static void written_entries_read_back(mvr_test_state *t)
{
    char dir[] = "/tmp/mvr-tuner-XXXXXX", path[4096], why[256];
    CHECK(t, mkdtemp(dir) != NULL);
    mvr_program_cache_key mac;
    CHECK(t, mvr_program_cache_key_load(dir, &mac, why, sizeof why));
    CHECK(t, mvr_tuner_memory_path(dir, key, path, sizeof path));
    CHECK(t, strstr(path, "/tuner-") != NULL);
    /* no entry: a miss */
    mvr_tuner_memory m;
    CHECK(t, mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_MISS);
    mvr_tuner_memory w = {1, -0.0421, 0.0016, 3};
    CHECK(t, mvr_tuner_memory_write(path, &mac, key, &w, why, sizeof why));
    CHECK_MSG(t, mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_HIT, "%s", why);
    CHECK(t, m.chosen == 1 && m.runs == 3 && m.log_ratio > -0.04211 && m.log_ratio < -0.04209);
    /* rewritten in place: the new values */
    w.chosen = 0;
    w.runs = 4;
    CHECK(t, mvr_tuner_memory_write(path, &mac, key, &w, why, sizeof why));
    CHECK(t, mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_HIT && m.chosen == 0 &&
                 m.runs == 4);
    /* another key at the same name (a collision): stale */
    CHECK(t, mvr_tuner_memory_read(path, &mac, "v1 other inputs", &m, why, sizeof why) == MVR_TUNER_MEMORY_STALE);
    /* another user's key (a forger without this user's key file): refused */
    mvr_program_cache_key other = mac;
    other.bytes[0] ^= 1;
    CHECK(t, mvr_tuner_memory_read(path, &other, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_CORRUPT);
    /* nothing invalid is written */
    mvr_tuner_memory bad = {2, 0.0, 0.0, 1};
    CHECK(t, !mvr_tuner_memory_write(path, &mac, key, &bad, why, sizeof why));
    bad = (mvr_tuner_memory){0, 0.0, 0.0, 0};
    CHECK(t, !mvr_tuner_memory_write(path, &mac, key, &bad, why, sizeof why));
    CHECK(t, !mvr_tuner_memory_write(path, &mac, "a\nkey", &w, why, sizeof why));
    CHECK(t, !mvr_tuner_memory_path(dir, "", path, sizeof path));
    CHECK(t, mvr_tuner_memory_path(dir, key, path, sizeof path));
    /* only the entry and the key file: no temporary left behind */
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "test $(ls -A %s | wc -l) -eq 2", dir);
    CHECK(t, system(cmd) == 0);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    CHECK(t, system(cmd) == 0);
}

static void corrupted_entries_are_refused(mvr_test_state *t)
{
    char dir[] = "/tmp/mvr-tuner-XXXXXX", path[4096], why[256];
    CHECK(t, mkdtemp(dir) != NULL);
    mvr_program_cache_key mac;
    CHECK(t, mvr_program_cache_key_load(dir, &mac, why, sizeof why));
    CHECK(t, mvr_tuner_memory_path(dir, key, path, sizeof path));
    mvr_tuner_memory w = {1, 0.125, 0.01, 2}, m;
    CHECK(t, mvr_tuner_memory_write(path, &mac, key, &w, why, sizeof why));
    char good[4096];
    size_t n = 0;
    CHECK(t, slurp(path, good, sizeof good, &n) && n > 40);
    char buf[4096];
    /* every single byte changed, and every truncation: refused */
    uint32_t refused = 0, tried = 0;
    for (size_t i = 0; i < n; ++i) {
        memcpy(buf, good, n);
        buf[i] = (char)(buf[i] == '1' ? '0' : '1');
        tried++;
        refused += spit(path, buf, n) &&
                   mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_CORRUPT;
        tried++;
        refused += spit(path, good, i) &&
                   mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) != MVR_TUNER_MEMORY_HIT;
    }
    CHECK_MSG(t, refused == tried, "%u of %u damaged entries refused", refused, tried);
    /* a byte appended: refused */
    memcpy(buf, good, n);
    buf[n] = '\n';
    CHECK(t, spit(path, buf, n + 1) &&
                 mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_CORRUPT);
    /* garbage and an oversized file: refused, with a reason */
    memset(buf, 'x', sizeof buf);
    CHECK(t, spit(path, buf, sizeof buf) &&
                 mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_CORRUPT && why[0]);
    CHECK(t, spit(path, "mvr-tuner 1\n", 12) &&
                 mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_CORRUPT);
    /* a link to a good entry and a directory: not followed, refused */
    char target[4200];
    snprintf(target, sizeof target, "%s/elsewhere", dir);
    CHECK(t, spit(target, good, n) && unlink(path) == 0 && symlink(target, path) == 0);
    CHECK(t, mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_CORRUPT);
    CHECK(t, unlink(path) == 0 && mkdir(path, 0700) == 0);
    CHECK(t, mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_CORRUPT);
    CHECK(t, rmdir(path) == 0);
    /* the good bytes again: a hit */
    CHECK(t, spit(path, good, n) && mvr_tuner_memory_read(path, &mac, key, &m, why, sizeof why) == MVR_TUNER_MEMORY_HIT &&
                 m.chosen == 1 && m.runs == 2);
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    CHECK(t, system(cmd) == 0);
}

MVR_TEST_MAIN(TEST(written_entries_read_back), TEST(corrupted_entries_are_refused))
