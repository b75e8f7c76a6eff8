#define _POSIX_C_SOURCE 200809L
/* core: program binary cache files. A payload comes back only from a file
 * this user wrote (its SipHash-2-4 tag verifies under the user's key) for the
 * same key and driver; a damaged or forged file is told apart from a missing
 * one (so it is rebuilt and rewritten), a well-formed file for another driver
 * or shader source reads as stale, and anything that is not a regular file
 * (a FIFO, a link, a directory) is refused without blocking or following it.
 * The key file itself must be a private regular file of 16 bytes. */
#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mvr_test.h"
#include "program_binary_file.h"

static const char *driver = "gles|Mesa|llvmpipe|3.2";

typedef struct fixture {
    char dir[64];
    char path[4096];
    char key_path[4096];
    unsigned char payload[300];
    uint64_t key;
    mvr_program_cache_key mac;
} fixture;

static int fixture_init(mvr_test_state *t, fixture *fx)
{
    strcpy(fx->dir, "/tmp/mvr-pbin-XXXXXX");
    CHECK(t, mkdtemp(fx->dir) != NULL);
    CHECK(t, mvr_program_binary_path(fx->dir, "mesh-mv2-f00001-l1.0.0", driver, fx->path, sizeof fx->path));
    CHECK(t, mvr_program_cache_key_path(fx->dir, fx->key_path, sizeof fx->key_path));
    for (size_t i = 0; i < sizeof fx->payload; ++i)
        fx->payload[i] = (unsigned char)(i * 7 + 3);
    fx->key = mvr_program_binary_key(driver, "void main() {}", "out vec4 c; void main() { c = vec4(1); }");
    char why[512] = "";
    int ok = mvr_program_cache_key_load(fx->dir, &fx->mac, why, sizeof why);
    CHECK_MSG(t, ok, "%s", why);
    ok = ok && mvr_program_binary_write(fx->path, &fx->mac, driver, fx->key, 0x1234u, fx->payload,
                                        sizeof fx->payload, why, sizeof why);
    CHECK_MSG(t, ok, "%s", why);
    return ok;
}

/* Removes the entry (whatever it is now), the key file and the folder. */
static void fixture_done(fixture *fx)
{
    if (unlink(fx->path) != 0)
        rmdir(fx->path);
    if (unlink(fx->key_path) != 0)
        rmdir(fx->key_path);
    rmdir(fx->dir);
}

static mvr_program_binary_status read_with(fixture *fx, const mvr_program_cache_key *mac, const char *drv,
                                           uint64_t key, char *why, size_t n)
{
    uint32_t format = 0;
    void *data = NULL;
    size_t size = 0;
    mvr_program_binary_status st =
        mvr_program_binary_read(fx->path, mac, drv, key, &format, &data, &size, why, n);
    if (st == MVR_PROGRAM_BINARY_HIT) {
        int same = size == sizeof fx->payload && memcmp(data, fx->payload, size) == 0 && format == 0x1234u;
        free(data);
        return same ? st : MVR_PROGRAM_BINARY_CORRUPT;
    }
    return data ? MVR_PROGRAM_BINARY_CORRUPT : st; /* no payload unless it is a hit */
}

static mvr_program_binary_status read_back(fixture *fx, const char *drv, uint64_t key, char *why, size_t n)
{
    return read_with(fx, &fx->mac, drv, key, why, n);
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

static size_t slurp(const char *path, unsigned char *bytes, size_t cap)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    size_t n = fread(bytes, 1, cap, f);
    fclose(f);
    return n;
}

static int spill(const char *path, const unsigned char *bytes, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    int ok = fwrite(bytes, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

/* Rewrites the file with byte `at` xor'ed, or cut to `at` bytes, or with one byte appended. */
typedef enum { FLIP, TRUNCATE, APPEND } damage;
static void damage_file(const char *path, damage how, long at)
{
    static unsigned char bytes[4096];
    size_t keep = slurp(path, bytes, sizeof bytes - 1);
    if (how == FLIP)
        bytes[at] ^= 0x20;
    else if (how == TRUNCATE)
        keep = (size_t)at;
    else
        bytes[keep++] = 0;
    spill(path, bytes, keep);
}

/* The paper's Appendix A: key 00 01 .. 0f, message 00 01 .. 0e (15 bytes).
 * Lengths 0 and 8 (a message of whole words only) from the reference
 * implementation's vectors.h (github.com/veorq/SipHash), same key. */
static void siphash_matches_the_paper(mvr_test_state *t)
{
    unsigned char key[16], message[16];
    for (int i = 0; i < 16; ++i)
        key[i] = message[i] = (unsigned char)i;
    CHECK(t, mvr_siphash24(key, message, 15) == 0xa129ca6149be45e5ull);
    CHECK(t, mvr_siphash24(key, message, 0) == 0x726fdb47dd0e0e31ull);
    CHECK(t, mvr_siphash24(key, message, 8) == 0x93f5f5799a932462ull);
    key[15] ^= 1;
    CHECK(t, mvr_siphash24(key, message, 15) != 0xa129ca6149be45e5ull);
}

static void round_trip_and_missing(mvr_test_state *t)
{
    fixture fx;
    if (!fixture_init(t, &fx))
        return;
    char why[512] = "";
    CHECK_EQ_INT(t, read_back(&fx, driver, fx.key, why, sizeof why), MVR_PROGRAM_BINARY_HIT);
    /* written private, and nothing left behind but the entry and the key */
    struct stat st;
    CHECK(t, lstat(fx.path, &st) == 0 && S_ISREG(st.st_mode) && (st.st_mode & 077) == 0);
    /* the file name carries the driver: another driver never opens this one */
    char other[4096];
    CHECK(t, mvr_program_binary_path(fx.dir, "mesh-mv2-f00001-l1.0.0", "gl|NVIDIA|RTX|4.6", other, sizeof other));
    CHECK(t, strcmp(other, fx.path) != 0);
    uint32_t format = 0;
    void *data = (void *)1;
    size_t size = 1;
    CHECK_EQ_INT(t, mvr_program_binary_read(other, &fx.mac, driver, fx.key, &format, &data, &size, why, sizeof why),
                 MVR_PROGRAM_BINARY_MISS);
    CHECK(t, data == NULL && size == 0);
    /* keys differ when any part differs, also when text moves between parts */
    CHECK(t, mvr_program_binary_key(driver, "ab", "c") != mvr_program_binary_key(driver, "a", "bc"));
    CHECK(t, mvr_program_binary_key(driver, "a", "b") != mvr_program_binary_key("gl|x|y|z", "a", "b"));
    /* a path that does not fit is refused, not cut */
    char small[16];
    CHECK(t, !mvr_program_binary_path(fx.dir, "mesh", driver, small, sizeof small));
    CHECK(t, !mvr_program_cache_key_path(fx.dir, small, sizeof small));
    /* an unwritable place fails with a reason */
    why[0] = '\0';
    CHECK(t, !mvr_program_binary_write("/nonexistent-mvr-dir/x.mvrbin", &fx.mac, driver, 1, 1, fx.payload, 8, why,
                                       sizeof why));
    CHECK(t, why[0] != '\0');
    fixture_done(&fx);
}

static void stale_entries_are_told_apart(mvr_test_state *t)
{
    fixture fx;
    if (!fixture_init(t, &fx))
        return;
    char why[512] = "";
    CHECK_EQ_INT(t, read_back(&fx, driver, fx.key + 1, why, sizeof why), MVR_PROGRAM_BINARY_STALE);
    CHECK_MSG(t, strstr(why, "key") != NULL, "%s", why);
    CHECK_EQ_INT(t, read_back(&fx, "gles|Mesa|llvmpipe|3.1", fx.key, why, sizeof why), MVR_PROGRAM_BINARY_STALE);
    CHECK_MSG(t, strstr(why, "driver") != NULL, "%s", why);
    fixture_done(&fx);
}

static void damaged_files_are_refused(mvr_test_state *t)
{
    struct {
        damage how;
        long at;                 /* < 0: from the end */
        mvr_program_binary_status want;
        const char *what;
    } cases[] = {
        {FLIP, 0, MVR_PROGRAM_BINARY_CORRUPT, "magic"},
        {FLIP, 12, MVR_PROGRAM_BINARY_CORRUPT, "driver length"},
        {FLIP, 29, MVR_PROGRAM_BINARY_CORRUPT, "payload size"},
        {FLIP, 8, MVR_PROGRAM_BINARY_NOT_AUTHENTIC, "format"},
        {FLIP, 16, MVR_PROGRAM_BINARY_NOT_AUTHENTIC, "key"},
        {FLIP, 40, MVR_PROGRAM_BINARY_NOT_AUTHENTIC, "driver string"},
        {FLIP, -9, MVR_PROGRAM_BINARY_NOT_AUTHENTIC, "last payload byte"},
        {FLIP, -150, MVR_PROGRAM_BINARY_NOT_AUTHENTIC, "middle of the payload"},
        {FLIP, -1, MVR_PROGRAM_BINARY_NOT_AUTHENTIC, "tag"},
        {TRUNCATE, 0, MVR_PROGRAM_BINARY_CORRUPT, "empty file"},
        {TRUNCATE, 20, MVR_PROGRAM_BINARY_CORRUPT, "cut in the header"},
        {TRUNCATE, -1, MVR_PROGRAM_BINARY_CORRUPT, "cut by one byte"},
        {APPEND, 0, MVR_PROGRAM_BINARY_CORRUPT, "a byte after the tag"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        fixture fx;
        if (!fixture_init(t, &fx))
            return;
        long n = file_size(fx.path);
        long at = cases[i].at < 0 ? n + cases[i].at : cases[i].at;
        damage_file(fx.path, cases[i].how, at);
        char why[512] = "";
        mvr_program_binary_status st = read_back(&fx, driver, fx.key, why, sizeof why);
        CHECK_MSG(t, st == cases[i].want, "%s: status %d, want %d", cases[i].what, (int)st, (int)cases[i].want);
        CHECK_MSG(t, why[0] != '\0', "%s: no reason given", cases[i].what);
        printf("  %-26s -> %s\n", cases[i].what, why);
        fixture_done(&fx);
    }
}

static uint64_t fnv_fields(const unsigned char *bytes, size_t driver_len, size_t size)
{
    uint64_t h = mvr_fnv1a64(MVR_FNV1A64_INIT, bytes + 40, driver_len);
    h = mvr_fnv1a64(h, bytes + 16, 8);
    h = mvr_fnv1a64(h, bytes + 8, 4);
    return mvr_fnv1a64(h, bytes + 40 + driver_len, size);
}

/* The forgeries of the review: a binary changed by someone without the key,
 * with every check that needs no key fixed up, is never handed back. */
static void forged_entries_are_not_authentic(mvr_test_state *t)
{
    fixture fx;
    if (!fixture_init(t, &fx))
        return;
    char why[512] = "";
    /* written with another user's key (what a shared folder holds) */
    mvr_program_cache_key other = fx.mac;
    other.bytes[3] ^= 0x80;
    CHECK_EQ_INT(t, read_with(&fx, &other, driver, fx.key, why, sizeof why), MVR_PROGRAM_BINARY_NOT_AUTHENTIC);
    CHECK_MSG(t, strstr(why, "not authentic") != NULL, "%s", why);

    /* the first entry format: an unkeyed FNV-1a checksum (at offset 32) that a
     * forger recomputes after changing the binary; the old reader took it */
    static unsigned char bytes[4096];
    size_t n = slurp(fx.path, bytes, sizeof bytes);
    size_t driver_len = strlen(driver), size = sizeof fx.payload;
    unsigned char forged[4096];
    memcpy(forged, bytes, 32);
    memcpy(forged, "MVRPBIN1", 8);
    memcpy(forged + 40, bytes + 32, driver_len + size);
    forged[40 + driver_len + size / 2] ^= 0x41;
    uint64_t h = fnv_fields(forged, driver_len, size);
    for (int i = 0; i < 8; ++i)
        forged[32 + i] = (unsigned char)(h >> (8 * i));
    CHECK(t, n == 32 + driver_len + size + 8 && spill(fx.path, forged, 40 + driver_len + size));
    mvr_program_binary_status st = read_back(&fx, driver, fx.key, why, sizeof why);
    CHECK_MSG(t, st == MVR_PROGRAM_BINARY_STALE, "old-format forgery: status %d (%s)", (int)st, why);

    /* the current format: the same change, and nothing left to fix without the key */
    bytes[32 + driver_len + size / 2] ^= 0x41;
    CHECK(t, spill(fx.path, bytes, n));
    CHECK_EQ_INT(t, read_back(&fx, driver, fx.key, why, sizeof why), MVR_PROGRAM_BINARY_NOT_AUTHENTIC);
    fixture_done(&fx);
}

/* A FIFO, a symbolic link (to a valid entry) and a directory in place of an
 * entry: refused with a reason, without blocking and without following. A
 * file too big to be an entry is refused before it is read. */
static void odd_files_are_refused(mvr_test_state *t)
{
    fixture fx;
    if (!fixture_init(t, &fx))
        return;
    char why[512] = "";
    char valid[4200];
    snprintf(valid, sizeof valid, "%s/valid-copy", fx.dir);
    CHECK(t, rename(fx.path, valid) == 0 && symlink(valid, fx.path) == 0);
    CHECK_EQ_INT(t, read_back(&fx, driver, fx.key, why, sizeof why), MVR_PROGRAM_BINARY_UNUSABLE);
    CHECK_MSG(t, strstr(why, "symbolic link") != NULL, "%s", why);
    /* a write replaces the link and leaves its target alone */
    long before = file_size(valid);
    CHECK(t, mvr_program_binary_write(fx.path, &fx.mac, driver, fx.key, 0x1234u, fx.payload, 100, why, sizeof why));
    struct stat st;
    CHECK(t, lstat(fx.path, &st) == 0 && S_ISREG(st.st_mode) && file_size(valid) == before);
    unlink(valid);

    CHECK(t, unlink(fx.path) == 0 && mkfifo(fx.path, 0600) == 0);
    CHECK_EQ_INT(t, read_back(&fx, driver, fx.key, why, sizeof why), MVR_PROGRAM_BINARY_UNUSABLE);
    CHECK_MSG(t, strstr(why, "FIFO") != NULL, "%s", why);

    CHECK(t, unlink(fx.path) == 0 && mkdir(fx.path, 0700) == 0);
    CHECK_EQ_INT(t, read_back(&fx, driver, fx.key, why, sizeof why), MVR_PROGRAM_BINARY_UNUSABLE);
    CHECK_MSG(t, strstr(why, "directory") != NULL, "%s", why);
    CHECK(t, rmdir(fx.path) == 0);

    /* sparse: no disk used, and never read */
    int fd = open(fx.path, O_WRONLY | O_CREAT | O_EXCL, 0600);
    CHECK(t, fd >= 0 && ftruncate(fd, (off_t)(MVR_PROGRAM_BINARY_MAX_PAYLOAD + 4096)) == 0);
    if (fd >= 0)
        close(fd);
    CHECK_EQ_INT(t, read_back(&fx, driver, fx.key, why, sizeof why), MVR_PROGRAM_BINARY_CORRUPT);
    CHECK_MSG(t, strstr(why, "size") != NULL, "%s", why);
    fixture_done(&fx);
}

static void key_file_is_made_private_and_kept(mvr_test_state *t)
{
    fixture fx;
    if (!fixture_init(t, &fx))
        return;
    struct stat st;
    CHECK(t, lstat(fx.key_path, &st) == 0 && S_ISREG(st.st_mode) && (st.st_mode & 077) == 0 &&
                 st.st_uid == geteuid() && st.st_size == 16);
    char why[512] = "";
    mvr_program_cache_key again;
    CHECK(t, mvr_program_cache_key_load(fx.dir, &again, why, sizeof why));
    CHECK(t, memcmp(again.bytes, fx.mac.bytes, 16) == 0);
    /* another folder, another random key */
    char dir2[] = "/tmp/mvr-pbin2-XXXXXX", key2[4096];
    CHECK(t, mkdtemp(dir2) != NULL && mvr_program_cache_key_path(dir2, key2, sizeof key2));
    CHECK(t, mvr_program_cache_key_load(dir2, &again, why, sizeof why));
    CHECK(t, memcmp(again.bytes, fx.mac.bytes, 16) != 0);
    unlink(key2);
    rmdir(dir2);
    /* a folder that does not exist: no key, with a reason */
    why[0] = '\0';
    CHECK(t, !mvr_program_cache_key_load("/nonexistent-mvr-dir", &again, why, sizeof why));
    CHECK_MSG(t, strstr(why, "/nonexistent-mvr-dir/.mvr-key-") != NULL, "%s", why);
    fixture_done(&fx);
}

/* Replaces the key file with something unsafe; the load must fail naming
 * the file and saying what is wrong (`expect` in the reason). */
static void unsafe_key_files_are_refused(mvr_test_state *t)
{
    static const struct {
        const char *what, *expect;
    } cases[] = {
        {"mode 0644", "0644"}, {"mode 0660", "0660"},         {"15 bytes", "15 bytes"},
        {"a symbolic link", "symbolic link"}, {"a FIFO", "FIFO"}, {"a directory", "directory"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        fixture fx;
        if (!fixture_init(t, &fx))
            return;
        char real[4200];
        snprintf(real, sizeof real, "%s/real-key", fx.dir);
        const char *what = cases[i].what;
        if (strcmp(what, "mode 0644") == 0)
            CHECK(t, chmod(fx.key_path, 0644) == 0);
        else if (strcmp(what, "mode 0660") == 0)
            CHECK(t, chmod(fx.key_path, 0660) == 0);
        else if (strcmp(what, "15 bytes") == 0)
            CHECK(t, truncate(fx.key_path, 15) == 0);
        else if (strcmp(what, "a symbolic link") == 0)
            CHECK(t, rename(fx.key_path, real) == 0 && symlink(real, fx.key_path) == 0);
        else if (strcmp(what, "a FIFO") == 0)
            CHECK(t, unlink(fx.key_path) == 0 && mkfifo(fx.key_path, 0600) == 0);
        else
            CHECK(t, unlink(fx.key_path) == 0 && mkdir(fx.key_path, 0700) == 0);
        char why[512] = "";
        mvr_program_cache_key key;
        CHECK_MSG(t, !mvr_program_cache_key_load(fx.dir, &key, why, sizeof why), "%s accepted", what);
        CHECK_MSG(t, strstr(why, fx.key_path) != NULL && strstr(why, cases[i].expect) != NULL, "%s: %s", what, why);
        printf("  %-16s -> %s\n", what, why);
        unlink(real);
        fixture_done(&fx);
    }
    /* a key file of another user: only root can hand one over to test it */
    fixture fx;
    if (geteuid() != 0 || !fixture_init(t, &fx))
        return;
    char why[512] = "";
    mvr_program_cache_key key;
    CHECK(t, chown(fx.key_path, 65534, (gid_t)-1) == 0);
    CHECK(t, !mvr_program_cache_key_load(fx.dir, &key, why, sizeof why));
    CHECK_MSG(t, strstr(why, fx.key_path) != NULL && strstr(why, "owned by uid 65534") != NULL, "%s", why);
    printf("  %-16s -> %s\n", "another owner", why);
    fixture_done(&fx);
}

MVR_TEST_MAIN(TEST(siphash_matches_the_paper), TEST(round_trip_and_missing), TEST(stale_entries_are_told_apart),
              TEST(damaged_files_are_refused), TEST(forged_entries_are_not_authentic), TEST(odd_files_are_refused),
              TEST(key_file_is_made_private_and_kept), TEST(unsafe_key_files_are_refused))
