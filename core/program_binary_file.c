#define _POSIX_C_SOURCE 200809L
#include "program_binary_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core_util.h"

static const char magic[8] = {'M', 'V', 'R', 'P', 'B', 'I', 'N', '2'};
static const char old_magic[8] = {'M', 'V', 'R', 'P', 'B', 'I', 'N', '1'};
enum { HEADER_SIZE = 8 + 4 + 4 + 8 + 8, TAG_SIZE = 8 };
#define MIN_FILE_SIZE ((uint64_t)HEADER_SIZE + 1 + TAG_SIZE)
#define MAX_FILE_SIZE \
    ((uint64_t)HEADER_SIZE + MVR_PROGRAM_BINARY_MAX_DRIVER + MVR_PROGRAM_BINARY_MAX_PAYLOAD + TAG_SIZE)

/* FNV-1a, 64-bit (Fowler, Noll, Vo; offset basis 14695981039346656037,
 * prime 1099511628211): a lookup key, not an adversary. */
uint64_t mvr_fnv1a64(uint64_t hash, const void *data, size_t size)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < size; ++i) {
        hash ^= p[i];
        hash *= 0x100000001b3ull;
    }
    return hash;
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

/* ---- SipHash-2-4: J.-P. Aumasson, D. J. Bernstein, "SipHash: a fast
 * short-input PRF", INDOCRYPT 2012, section 2 (two compression rounds per
 * message word, four finalization rounds, 64-bit output). */

static uint64_t rotl64(uint64_t x, int b)
{
    return (x << b) | (x >> (64 - b));
}

static void sip_round(uint64_t v[4])
{
    v[0] += v[1];
    v[2] += v[3];
    v[1] = rotl64(v[1], 13);
    v[3] = rotl64(v[3], 16);
    v[1] ^= v[0];
    v[3] ^= v[2];
    v[0] = rotl64(v[0], 32);
    v[2] += v[1];
    v[0] += v[3];
    v[1] = rotl64(v[1], 17);
    v[3] = rotl64(v[3], 21);
    v[1] ^= v[2];
    v[3] ^= v[0];
    v[2] = rotl64(v[2], 32);
}

static void sip_compress(uint64_t v[4], uint64_t m)
{
    v[3] ^= m;
    sip_round(v);
    sip_round(v);
    v[0] ^= m;
}

uint64_t mvr_siphash24(const unsigned char key[MVR_PROGRAM_CACHE_KEY_SIZE], const void *data, size_t size)
{
    const unsigned char *p = data;
    uint64_t k0 = get_u64(key), k1 = get_u64(key + 8);
    /* the initialisation constants spell "somepseudorandomlygeneratedbytes" */
    uint64_t v[4] = {k0 ^ 0x736f6d6570736575ull, k1 ^ 0x646f72616e646f6dull, k0 ^ 0x6c7967656e657261ull,
                     k1 ^ 0x7465646279746573ull};
    size_t whole = size - size % 8;
    for (size_t i = 0; i < whole; i += 8)
        sip_compress(v, get_u64(p + i));
    /* last word: the 0..7 remaining bytes, and the length mod 256 in the top byte */
    uint64_t last = (uint64_t)(size & 0xff) << 56;
    for (size_t i = 0; i < size % 8; ++i)
        last |= (uint64_t)p[whole + i] << (8 * i);
    sip_compress(v, last);
    v[2] ^= 0xff;
    for (int i = 0; i < 4; ++i)
        sip_round(v);
    return v[0] ^ v[1] ^ v[2] ^ v[3];
}

/* ---- files */

static int random_bytes(void *out, size_t size)
{
    unsigned char *p = out;
    while (size > 0) {
        ssize_t n = getrandom(p, size, 0);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return 0;
        p += n;
        size -= (size_t)n;
    }
    return 1;
}

static int read_full(int fd, void *out, size_t size)
{
    unsigned char *p = out;
    while (size > 0) {
        ssize_t n = read(fd, p, size);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return 0;
        p += n;
        size -= (size_t)n;
    }
    return 1;
}

static int write_full(int fd, const void *data, size_t size)
{
    const unsigned char *p = data;
    while (size > 0) {
        ssize_t n = write(fd, p, size);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return 0;
        p += n;
        size -= (size_t)n;
    }
    return 1;
}

/* True at end of file: a file that grew after fstat has more to read. */
static int at_end(int fd)
{
    unsigned char extra;
    ssize_t n;
    do {
        n = read(fd, &extra, 1);
    } while (n < 0 && errno == EINTR);
    return n == 0;
}

static const char *file_kind(mode_t mode)
{
    if (S_ISDIR(mode))
        return "a directory";
    if (S_ISFIFO(mode))
        return "a FIFO";
    if (S_ISSOCK(mode))
        return "a socket";
    if (S_ISCHR(mode) || S_ISBLK(mode))
        return "a device";
    return "not a regular file";
}

/* Opens a cache file for reading without following a link or waiting on a
 * FIFO (O_NONBLOCK), and keeps it only if fstat says it is a regular file.
 * -1 with *missing set when there is no file; -1 and why otherwise. */
static int open_regular(const char *path, struct stat *st, int *missing, char *why, size_t why_size)
{
    *missing = 0;
    int fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT)
            *missing = 1;
        else if (errno == ELOOP)
            mvr_str_copy(why, why_size, "a symbolic link (not followed)");
        else
            mvr_str_format(why, why_size, "cannot be opened (%s)", strerror(errno));
        return -1;
    }
    if (fstat(fd, st) != 0) {
        mvr_str_format(why, why_size, "cannot be examined (%s)", strerror(errno));
        close(fd);
        return -1;
    }
    if (!S_ISREG(st->st_mode)) {
        mvr_str_format(why, why_size, "%s, not a regular file", file_kind(st->st_mode));
        close(fd);
        return -1;
    }
    return fd;
}

/* ---- the user's key file */

int mvr_program_cache_key_path(const char *dir, char *out, size_t size)
{
    int n = snprintf(out, size, "%s/.mvr-key-%lu", dir, (unsigned long)geteuid());
    return n > 0 && (size_t)n < size;
}

/* A new temporary name beside `path`: <path>.<16 random hex>.tmp. */
static int temporary_name(const char *path, char *out, size_t size)
{
    uint64_t r = 0;
    if (!random_bytes(&r, sizeof r))
        return 0;
    int n = snprintf(out, size, "%s.%016llx.tmp", path, (unsigned long long)r);
    return n > 0 && (size_t)n < size;
}

/* Creates a new file beside `path` that nobody else can have opened or
 * linked: O_EXCL never reuses a name, O_NOFOLLOW never follows a planted
 * link; a name that is taken is retried a few times with another. */
static int create_temporary(const char *path, char *tmp, size_t tmp_size, char *why, size_t why_size)
{
    for (int attempt = 0; attempt < 4; ++attempt) {
        if (!temporary_name(path, tmp, tmp_size)) {
            mvr_str_format(why, why_size, "cannot name a temporary file beside %s", path);
            return -1;
        }
        int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
        if (fd >= 0)
            return fd;
        if (errno != EEXIST) {
            mvr_str_format(why, why_size, "cannot create %s (%s)", tmp, strerror(errno));
            return -1;
        }
    }
    mvr_str_format(why, why_size, "cannot create a temporary file beside %s: every name tried was taken", path);
    return -1;
}

/* Makes the key file from fresh random bytes: written under a temporary name
 * and linked into place, so no reader sees it half written and two creators
 * cannot both win. 1: made; -1: another process made it first; 0: why. */
static int create_key(const char *path, char *why, size_t why_size)
{
    unsigned char bytes[MVR_PROGRAM_CACHE_KEY_SIZE];
    if (!random_bytes(bytes, sizeof bytes)) {
        mvr_str_format(why, why_size, "key file %s: no random bytes to make it (%s)", path, strerror(errno));
        return 0;
    }
    char tmp[4096];
    char tmp_why[512] = "";
    int fd = create_temporary(path, tmp, sizeof tmp, tmp_why, sizeof tmp_why);
    if (fd < 0) {
        mvr_str_format(why, why_size, "key file %s: %s", path, tmp_why);
        return 0;
    }
    int ok = write_full(fd, bytes, sizeof bytes);
    ok = close(fd) == 0 && ok;
    int made = ok ? (link(tmp, path) == 0 ? 1 : errno == EEXIST ? -1 : 0) : 0;
    if (made == 0)
        mvr_str_format(why, why_size, "key file %s cannot be made (%s)", path, strerror(errno));
    unlink(tmp);
    return made;
}

/* The checks a key file must pass: anybody else able to read it could forge
 * entries, anybody able to write it could pick the key. */
static int read_key(int fd, const struct stat *st, const char *path, mvr_program_cache_key *key, char *why,
                    size_t why_size)
{
    if (st->st_uid != geteuid()) {
        mvr_str_format(why, why_size, "key file %s is owned by uid %lu, not by this user (%lu)", path,
                       (unsigned long)st->st_uid, (unsigned long)geteuid());
        return 0;
    }
    if ((st->st_mode & 077) != 0) {
        mvr_str_format(why, why_size, "key file %s has mode %04o: group or others may read or change it "
                       "(it must be 0600 or stricter)", path, (unsigned)(st->st_mode & 07777));
        return 0;
    }
    if (st->st_size != (off_t)MVR_PROGRAM_CACHE_KEY_SIZE) {
        mvr_str_format(why, why_size, "key file %s holds %lld bytes, not %u", path, (long long)st->st_size,
                       MVR_PROGRAM_CACHE_KEY_SIZE);
        return 0;
    }
    if (!read_full(fd, key->bytes, sizeof key->bytes) || !at_end(fd)) {
        mvr_str_format(why, why_size, "key file %s cannot be read whole", path);
        return 0;
    }
    return 1;
}

int mvr_program_cache_key_load(const char *dir, mvr_program_cache_key *key, char *why, size_t why_size)
{
    char path[4096];
    if (!mvr_program_cache_key_path(dir, path, sizeof path)) {
        mvr_str_copy(why, why_size, "key file path too long");
        return 0;
    }
    /* a second round only when another process created the file meanwhile */
    for (int round = 0; round < 2; ++round) {
        struct stat st;
        int missing = 0;
        char open_why[256] = "";
        int fd = open_regular(path, &st, &missing, open_why, sizeof open_why);
        if (fd >= 0) {
            int ok = read_key(fd, &st, path, key, why, why_size);
            close(fd);
            return ok;
        }
        if (!missing) {
            mvr_str_format(why, why_size, "key file %s is %s", path, open_why);
            return 0;
        }
        if (create_key(path, why, why_size) == 0)
            return 0;
    }
    mvr_str_format(why, why_size, "key file %s keeps changing", path);
    return 0;
}

/* ---- entries */

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
    int n = snprintf(out, size, "%s/%s-%016llx-u%lu.mvrbin", dir, variant_name, (unsigned long long)dh,
                     (unsigned long)geteuid());
    return n > 0 && (size_t)n < size;
}

/* Compares tags without an early exit, so timing tells nothing of how much matched. */
static int same_tag(uint64_t a, uint64_t b)
{
    uint64_t d = a ^ b;
    return ((d | (0 - d)) >> 63) == 0;
}

/* Reads a whole entry of a size fstat vouched for into a new buffer. */
static unsigned char *read_entry(const char *path, size_t *size, mvr_program_binary_status *status, char *why,
                                 size_t why_size)
{
    struct stat st;
    int missing = 0;
    int fd = open_regular(path, &st, &missing, why, why_size);
    *status = missing ? MVR_PROGRAM_BINARY_MISS : MVR_PROGRAM_BINARY_UNUSABLE;
    if (fd < 0)
        return NULL;
    *status = MVR_PROGRAM_BINARY_CORRUPT;
    unsigned char *bytes = NULL;
    if (st.st_size < 0 || (uint64_t)st.st_size < MIN_FILE_SIZE || (uint64_t)st.st_size > MAX_FILE_SIZE) {
        mvr_str_format(why, why_size, "%lld bytes: no entry is that size", (long long)st.st_size);
    } else if (!(bytes = malloc((size_t)st.st_size))) {
        mvr_str_copy(why, why_size, "out of memory");
    } else if (!read_full(fd, bytes, (size_t)st.st_size) || !at_end(fd)) {
        mvr_str_copy(why, why_size, "changed size while it was read");
        free(bytes);
        bytes = NULL;
    }
    close(fd);
    *size = (size_t)st.st_size;
    return bytes;
}

mvr_program_binary_status mvr_program_binary_read(const char *path, const mvr_program_cache_key *mac_key,
                                                  const char *driver, uint64_t key, uint32_t *format,
                                                  void **payload, size_t *payload_size, char *why,
                                                  size_t why_size)
{
    *payload = NULL;
    *payload_size = 0;
    size_t total = 0;
    mvr_program_binary_status status;
    unsigned char *bytes = read_entry(path, &total, &status, why, why_size);
    if (!bytes)
        return status;
    status = MVR_PROGRAM_BINARY_CORRUPT;
    uint32_t fmt = get_u32(bytes + 8);
    uint32_t driver_len = get_u32(bytes + 12);
    uint64_t size = get_u64(bytes + 24);
    if (memcmp(bytes, old_magic, sizeof old_magic) == 0) {
        mvr_str_copy(why, why_size, "an entry of an older mvr (no authentication tag)");
        status = MVR_PROGRAM_BINARY_STALE;
    } else if (memcmp(bytes, magic, sizeof magic) != 0) {
        mvr_str_copy(why, why_size, "not an mvr program binary (wrong magic)");
    } else if (driver_len > MVR_PROGRAM_BINARY_MAX_DRIVER || size == 0 || size > MVR_PROGRAM_BINARY_MAX_PAYLOAD ||
               HEADER_SIZE + driver_len + size + TAG_SIZE != total) {
        mvr_str_format(why, why_size, "sizes do not add up (driver %u bytes, payload %llu bytes, file %zu bytes)",
                       (unsigned)driver_len, (unsigned long long)size, total);
    } else if (!same_tag(mvr_siphash24(mac_key->bytes, bytes, total - TAG_SIZE), get_u64(bytes + total - TAG_SIZE))) {
        /* damage, another user's key, or a forgery: nothing of it is used */
        mvr_str_copy(why, why_size, "not authentic (its SipHash tag does not verify under this user's key)");
        status = MVR_PROGRAM_BINARY_NOT_AUTHENTIC;
    } else if (driver_len != strlen(driver) || memcmp(bytes + HEADER_SIZE, driver, driver_len) != 0) {
        /* authentic from here on: a mismatch means stale, not damaged */
        mvr_str_format(why, why_size, "written by another driver (%.*s)", (int)driver_len,
                       (const char *)bytes + HEADER_SIZE);
        status = MVR_PROGRAM_BINARY_STALE;
    } else if (get_u64(bytes + 16) != key) {
        mvr_str_copy(why, why_size, "written for other shader source (key mismatch)");
        status = MVR_PROGRAM_BINARY_STALE;
    } else {
        /* the payload moves to the front of the buffer the caller frees */
        memmove(bytes, bytes + HEADER_SIZE + driver_len, (size_t)size);
        *format = fmt;
        status = MVR_PROGRAM_BINARY_HIT;
    }
    if (status != MVR_PROGRAM_BINARY_HIT) {
        free(bytes);
        return status;
    }
    *payload = bytes;
    *payload_size = (size_t)size;
    return status;
}

int mvr_program_binary_write(const char *path, const mvr_program_cache_key *mac_key, const char *driver,
                             uint64_t key, uint32_t format, const void *payload, size_t payload_size, char *why,
                             size_t why_size)
{
    size_t driver_len = strlen(driver);
    if (driver_len > MVR_PROGRAM_BINARY_MAX_DRIVER || payload_size == 0 ||
        (uint64_t)payload_size > MVR_PROGRAM_BINARY_MAX_PAYLOAD) {
        mvr_str_format(why, why_size, "cannot store a %zu-byte binary", payload_size);
        return 0;
    }
    /* one buffer, so the tag is computed over exactly the bytes written */
    size_t total = HEADER_SIZE + driver_len + payload_size + TAG_SIZE;
    unsigned char *bytes = malloc(total);
    if (!bytes) {
        mvr_str_format(why, why_size, "out of memory for a %zu-byte entry", total);
        return 0;
    }
    memcpy(bytes, magic, sizeof magic);
    put_u32(bytes + 8, format);
    put_u32(bytes + 12, (uint32_t)driver_len);
    put_u64(bytes + 16, key);
    put_u64(bytes + 24, (uint64_t)payload_size);
    memcpy(bytes + HEADER_SIZE, driver, driver_len);
    memcpy(bytes + HEADER_SIZE + driver_len, payload, payload_size);
    put_u64(bytes + total - TAG_SIZE, mvr_siphash24(mac_key->bytes, bytes, total - TAG_SIZE));
    int ok = mvr_cache_file_write(path, bytes, total, why, why_size);
    free(bytes);
    return ok;
}

int mvr_cache_file_write(const char *path, const void *bytes, size_t size, char *why, size_t why_size)
{
    char tmp[4096];
    int fd = create_temporary(path, tmp, sizeof tmp, why, why_size);
    int ok = fd >= 0;
    if (ok) {
        ok = write_full(fd, bytes, size);
        ok = close(fd) == 0 && ok;
        if (!ok)
            mvr_str_format(why, why_size, "cannot write %s (%s)", tmp, strerror(errno));
        /* rename replaces whatever the name held (a link is replaced, not followed) */
        else if (!(ok = rename(tmp, path) == 0))
            mvr_str_format(why, why_size, "cannot rename %s into place (%s)", tmp, strerror(errno));
        if (!ok)
            unlink(tmp);
    }
    return ok;
}

int mvr_cache_file_read(const char *path, void *buf, size_t cap, size_t *size, int *missing, char *why,
                        size_t why_size)
{
    struct stat st;
    *size = 0;
    int fd = open_regular(path, &st, missing, why, why_size);
    if (fd < 0)
        return 0;
    int ok = 0;
    if (st.st_size <= 0 || (uint64_t)st.st_size > cap)
        mvr_str_format(why, why_size, "%lld bytes (at most %zu)", (long long)st.st_size, cap);
    else if (!read_full(fd, buf, (size_t)st.st_size) || !at_end(fd))
        mvr_str_copy(why, why_size, "changed size while it was read");
    else
        ok = 1, *size = (size_t)st.st_size;
    close(fd);
    return ok;
}
