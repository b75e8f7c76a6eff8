#define _POSIX_C_SOURCE 200809L
/* core: program binary cache files. A payload comes back only from a file
 * written for the same key and driver; every damaged file is told apart from
 * a missing one (so it is rebuilt and rewritten), and a well-formed file for
 * another driver or shader source reads as stale. */
#include <stdlib.h>
#include <unistd.h>

#include "mvr_test.h"
#include "program_binary_file.h"

static const char *driver = "gles|Mesa|llvmpipe|3.2";

typedef struct fixture {
    char dir[64];
    char path[4096];
    unsigned char payload[300];
    uint64_t key;
} fixture;

static int fixture_init(mvr_test_state *t, fixture *fx)
{
    strcpy(fx->dir, "/tmp/mvr-pbin-XXXXXX");
    CHECK(t, mkdtemp(fx->dir) != NULL);
    CHECK(t, mvr_program_binary_path(fx->dir, "mesh-mv2-f00001-l1.0.0", driver, fx->path, sizeof fx->path));
    for (size_t i = 0; i < sizeof fx->payload; ++i)
        fx->payload[i] = (unsigned char)(i * 7 + 3);
    fx->key = mvr_program_binary_key(driver, "void main() {}", "out vec4 c; void main() { c = vec4(1); }");
    char why[256] = "";
    int ok = mvr_program_binary_write(fx->path, driver, fx->key, 0x1234u, fx->payload, sizeof fx->payload, why,
                                      sizeof why);
    CHECK_MSG(t, ok, "%s", why);
    return ok;
}

static void fixture_done(fixture *fx)
{
    remove(fx->path);
    rmdir(fx->dir);
}

static mvr_program_binary_status read_back(fixture *fx, const char *drv, uint64_t key, char *why, size_t n)
{
    uint32_t format = 0;
    void *data = NULL;
    size_t size = 0;
    mvr_program_binary_status st = mvr_program_binary_read(fx->path, drv, key, &format, &data, &size, why, n);
    if (st == MVR_PROGRAM_BINARY_HIT) {
        int same = size == sizeof fx->payload && memcmp(data, fx->payload, size) == 0 && format == 0x1234u;
        free(data);
        return same ? st : MVR_PROGRAM_BINARY_CORRUPT;
    }
    return data ? MVR_PROGRAM_BINARY_CORRUPT : st; /* no payload unless it is a hit */
}

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

/* Rewrites the file with byte `at` xor'ed, or cut to `at` bytes, or with one byte appended. */
typedef enum { FLIP, TRUNCATE, APPEND } damage;
static void damage_file(const char *path, damage how, long at)
{
    long n = file_size(path);
    unsigned char *bytes = malloc((size_t)n + 1);
    FILE *f = fopen(path, "rb");
    size_t got = fread(bytes, 1, (size_t)n, f);
    fclose(f);
    size_t keep = got;
    if (how == FLIP)
        bytes[at] ^= 0x20;
    else if (how == TRUNCATE)
        keep = (size_t)at;
    else
        bytes[keep++] = 0;
    f = fopen(path, "wb");
    fwrite(bytes, 1, keep, f);
    fclose(f);
    free(bytes);
}

static void round_trip_and_missing(mvr_test_state *t)
{
    fixture fx;
    if (!fixture_init(t, &fx))
        return;
    char why[256] = "";
    CHECK_EQ_INT(t, read_back(&fx, driver, fx.key, why, sizeof why), MVR_PROGRAM_BINARY_HIT);
    /* the file name carries the driver: another driver never opens this one */
    char other[4096];
    CHECK(t, mvr_program_binary_path(fx.dir, "mesh-mv2-f00001-l1.0.0", "gl|NVIDIA|RTX|4.6", other, sizeof other));
    CHECK(t, strcmp(other, fx.path) != 0);
    uint32_t format = 0;
    void *data = (void *)1;
    size_t size = 1;
    CHECK_EQ_INT(t, mvr_program_binary_read(other, driver, fx.key, &format, &data, &size, why, sizeof why),
                 MVR_PROGRAM_BINARY_MISS);
    CHECK(t, data == NULL && size == 0);
    /* keys differ when any part differs, also when text moves between parts */
    CHECK(t, mvr_program_binary_key(driver, "ab", "c") != mvr_program_binary_key(driver, "a", "bc"));
    CHECK(t, mvr_program_binary_key(driver, "a", "b") != mvr_program_binary_key("gl|x|y|z", "a", "b"));
    /* a path that does not fit is refused, not cut */
    char small[16];
    CHECK(t, !mvr_program_binary_path(fx.dir, "mesh", driver, small, sizeof small));
    /* an unwritable place fails with a reason */
    why[0] = '\0';
    CHECK(t, !mvr_program_binary_write("/nonexistent-mvr-dir/x.mvrbin", driver, 1, 1, fx.payload, 8, why, sizeof why));
    CHECK(t, why[0] != '\0');
    fixture_done(&fx);
}

static void stale_entries_are_told_apart(mvr_test_state *t)
{
    fixture fx;
    if (!fixture_init(t, &fx))
        return;
    char why[256] = "";
    CHECK_EQ_INT(t, read_back(&fx, driver, fx.key + 1, why, sizeof why), MVR_PROGRAM_BINARY_STALE);
    CHECK_MSG(t, strstr(why, "key") != NULL, "%s", why);
    CHECK_EQ_INT(t, read_back(&fx, "gles|Mesa|llvmpipe|3.1", fx.key, why, sizeof why), MVR_PROGRAM_BINARY_STALE);
    CHECK_MSG(t, strstr(why, "driver") != NULL, "%s", why);
    fixture_done(&fx);
}

static void damaged_files_are_corrupt(mvr_test_state *t)
{
    struct {
        damage how;
        long at;                 /* < 0: from the end */
        const char *what;
    } cases[] = {
        {FLIP, 0, "magic"},
        {FLIP, 12, "driver length"},
        {FLIP, 29, "payload size"},
        {FLIP, 16, "key"},
        {FLIP, 40, "driver string"},
        {FLIP, -1, "last payload byte"},
        {FLIP, -150, "middle of the payload"},
        {TRUNCATE, 0, "empty file"},
        {TRUNCATE, 20, "cut in the header"},
        {TRUNCATE, -1, "cut by one byte"},
        {APPEND, 0, "a byte after the payload"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        fixture fx;
        if (!fixture_init(t, &fx))
            return;
        long n = file_size(fx.path);
        long at = cases[i].at < 0 ? n + cases[i].at : cases[i].at;
        damage_file(fx.path, cases[i].how, at);
        char why[256] = "";
        mvr_program_binary_status st = read_back(&fx, driver, fx.key, why, sizeof why);
        CHECK_MSG(t, st == MVR_PROGRAM_BINARY_CORRUPT, "%s: status %d", cases[i].what, (int)st);
        CHECK_MSG(t, why[0] != '\0', "%s: no reason given", cases[i].what);
        printf("  %-26s -> %s\n", cases[i].what, why);
        fixture_done(&fx);
    }
}

MVR_TEST_MAIN(TEST(round_trip_and_missing), TEST(stale_entries_are_told_apart), TEST(damaged_files_are_corrupt))
