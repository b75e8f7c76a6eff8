#define _POSIX_C_SOURCE 200809L
/* gl: the program binary cache folder is untrusted input. A forged entry (its
 * binary changed and every unkeyed check fixed up) is refused before
 * glProgramBinary; a FIFO or a symbolic link in place of an entry is neither
 * opened for long nor followed; an unsafe key file turns the cache off with a
 * warning naming it, and rendering goes on. Pixels never change. */
#include <dirent.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gl_test_util.h"
#include "program_binary_file.h"
#include "program_cache_files.h"

#define W 48
#define H 32

/* Every message the renderer logs, one a line, and the warnings counted. */
typedef struct trust_log {
    int warnings;
    char text[16384];
} trust_log;

static void trust_log_fn(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    (void)id;
    trust_log *log = user;
    size_t used = strlen(log->text);
    snprintf(log->text + used, sizeof log->text - used, "%s\n", message);
    log->warnings += level == MVR_LOG_WARNING;
}

typedef struct cache_run {
    mvr_frame_stats stats;
    uint8_t pixels[2 * W * H * 4];
} cache_run;

/* The stereo demo rendered with its binary cache in dir (NULL: none). */
static bool render_run(mvr_test_state *t, mvr_context *ctx, const char *dir, trust_log *log, cache_run *out)
{
    mvr_scene *scene = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {2, W, H, {0}};
    mvr_error err;
    if (mvr_demo_create("stereo", &dd, &scene, &vs, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s", err.message);
        return false;
    }
    mvr_renderer_desc rd = {.context = ctx, .program_cache_dir = dir};
    if (log) {
        memset(log, 0, sizeof *log);
        rd.logger.fn = trust_log_fn;
        rd.logger.user_data = log;
    }
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_target_desc td = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    bool ok = mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
              mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK;
    CHECK_MSG(t, ok, "%s", r ? mvr_renderer_last_error(r) : err.message);
    if (ok)
        mvr_renderer_get_stats(r, &out->stats);
    for (uint32_t k = 0; ok && k < 2; ++k)
        ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, out->pixels + (size_t)k * W * H * 4,
                                     (size_t)W * H * 4) == MVR_OK;
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    return ok;
}

/* Removes everything directly in dir, then dir. */
static void remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        char path[1024];
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) {
                snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
                unlink(path);
            }
        }
        closedir(d);
    }
    rmdir(dir);
}

static uint64_t get_le(const unsigned char *p, int bytes)
{
    uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i)
        v = v << 8 | p[i];
    return v;
}

/* What an attacker without the user's key can do to an entry: change a byte
 * in the middle of the driver's binary and fix every check that needs no key.
 * The first entry format (MVRPBIN1) had only an FNV-1a checksum over driver,
 * key, format and payload at offset 32; later ones have nothing to fix. */
static bool forge(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    unsigned char bytes[1 << 20];
    size_t n = fread(bytes, 1, sizeof bytes, f);
    fclose(f);
    if (n < 64 || n == sizeof bytes)
        return false;
    bytes[n / 2] ^= 0x41;
    if (memcmp(bytes, "MVRPBIN1", 8) == 0) {
        size_t driver_len = (size_t)get_le(bytes + 12, 4);
        uint64_t size = get_le(bytes + 24, 8);
        if (40 + driver_len + size != n)
            return false;
        uint64_t h = mvr_fnv1a64(MVR_FNV1A64_INIT, bytes + 40, driver_len);
        h = mvr_fnv1a64(h, bytes + 16, 8); /* key */
        h = mvr_fnv1a64(h, bytes + 8, 4);  /* format */
        h = mvr_fnv1a64(h, bytes + 40 + driver_len, (size_t)size);
        for (int i = 0; i < 8; ++i)
            bytes[32 + i] = (unsigned char)(h >> (8 * i));
    }
    f = fopen(path, "wb");
    if (!f)
        return false;
    bool ok = fwrite(bytes, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

static size_t count_lines_with(const char *text, const char *needle)
{
    size_t n = 0;
    for (const char *p = strstr(text, needle); p; p = strstr(p + 1, needle))
        ++n;
    return n;
}

/* Context, program binary support and a fresh cache folder with one cold run in it. */
typedef struct cache_fixture {
    mvr_context *ctx;
    char dir[64];
    char files[16][512];
    uint32_t n;
    cache_run none, cold;
} cache_fixture;

static bool fixture_init(mvr_test_state *t, cache_fixture *fx, bool cold_run)
{
    memset(fx, 0, sizeof *fx);
    fx->ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!fx->ctx)
        return false;
    const mvr_caps *caps = mvr_context_caps(fx->ctx);
    if (!caps->ext.program_binary) {
        mvr_context_destroy(fx->ctx);
        fx->ctx = NULL;
        t->skipped = 1;
        printf("  SKIP: %s offers no program binary format\n", caps->renderer);
        return false;
    }
    strcpy(fx->dir, "/tmp/mvr-trust-XXXXXX");
    CHECK(t, mkdtemp(fx->dir) != NULL);
    if (!render_run(t, fx->ctx, NULL, NULL, &fx->none))
        return false;
    if (cold_run) {
        if (!render_run(t, fx->ctx, fx->dir, NULL, &fx->cold))
            return false;
        fx->n = program_cache_entries(fx->dir, fx->files, 16);
        CHECK_MSG(t, fx->n >= 2 && fx->n == fx->cold.stats.programs_compiled, "%u entries for %u programs", fx->n,
                  fx->cold.stats.programs_compiled);
    }
    return fx->n >= 2 || !cold_run;
}

static void fixture_done(cache_fixture *fx)
{
    remove_dir(fx->dir);
    mvr_context_destroy(fx->ctx);
}

static void forged_entries_never_reach_the_driver(mvr_test_state *t)
{
    static cache_fixture fx;
    static cache_run forged, healed;
    static trust_log log;
    if (fixture_init(t, &fx, true)) {
        for (uint32_t i = 0; i < fx.n; ++i)
            CHECK_MSG(t, forge(fx.files[i]), "cannot forge %s", fx.files[i]);
        if (render_run(t, fx.ctx, fx.dir, &log, &forged)) {
            CHECK_EQ_INT(t, forged.stats.program_binary_loads, 0);
            CHECK_EQ_INT(t, forged.stats.program_binary_rejects, fx.n);
            CHECK_EQ_INT(t, forged.stats.programs_compiled, fx.n);
            /* refused by the cache's own check, never handed to glProgramBinary */
            CHECK_MSG(t, count_lines_with(log.text, "not authentic") == fx.n, "log:\n%s", log.text);
            CHECK_MSG(t, strstr(log.text, "driver refused") == NULL, "log:\n%s", log.text);
            CHECK(t, memcmp(fx.none.pixels, forged.pixels, sizeof forged.pixels) == 0);
        }
        /* rewritten with the user's key: the next start loads every one */
        if (render_run(t, fx.ctx, fx.dir, NULL, &healed))
            CHECK_EQ_INT(t, healed.stats.program_binary_loads, fx.n);
    }
    if (fx.ctx)
        fixture_done(&fx);
}

/* A FIFO in place of an entry: opening it for reading would wait for a writer
 * forever (ctest's TIMEOUT is what catches a hang); it is a miss instead. */
static void fifo_entry_is_a_miss(mvr_test_state *t)
{
    static cache_fixture fx;
    static cache_run warm, healed;
    static trust_log log;
    if (fixture_init(t, &fx, true)) {
        CHECK(t, unlink(fx.files[0]) == 0 && mkfifo(fx.files[0], 0600) == 0);
        if (render_run(t, fx.ctx, fx.dir, &log, &warm)) {
            CHECK_EQ_INT(t, warm.stats.program_binary_rejects, 1);
            CHECK_EQ_INT(t, warm.stats.programs_compiled, 1);
            CHECK_EQ_INT(t, warm.stats.program_binary_loads, fx.n - 1);
            CHECK_MSG(t, strstr(log.text, "FIFO") != NULL, "log:\n%s", log.text);
            CHECK(t, memcmp(fx.none.pixels, warm.pixels, sizeof warm.pixels) == 0);
        }
        /* the rebuilt entry replaced the FIFO */
        struct stat st;
        CHECK(t, lstat(fx.files[0], &st) == 0 && S_ISREG(st.st_mode));
        if (render_run(t, fx.ctx, fx.dir, NULL, &healed))
            CHECK_EQ_INT(t, healed.stats.program_binary_loads, fx.n);
    }
    if (fx.ctx)
        fixture_done(&fx);
}

/* A symbolic link in place of an entry, to a valid copy of it elsewhere: a
 * reader that followed it would load it; it is not followed. */
static void symlinked_entry_is_not_followed(mvr_test_state *t)
{
    static cache_fixture fx;
    static cache_run warm;
    static trust_log log;
    char elsewhere[64] = "/tmp/mvr-trust-link-XXXXXX";
    bool have_elsewhere = mkdtemp(elsewhere) != NULL;
    char target[600];
    snprintf(target, sizeof target, "%s/entry", elsewhere);
    if (have_elsewhere && fixture_init(t, &fx, true)) {
        CHECK(t, rename(fx.files[0], target) == 0 && symlink(target, fx.files[0]) == 0);
        if (render_run(t, fx.ctx, fx.dir, &log, &warm)) {
            CHECK_EQ_INT(t, warm.stats.program_binary_rejects, 1);
            CHECK_EQ_INT(t, warm.stats.program_binary_loads, fx.n - 1);
            CHECK_MSG(t, strstr(log.text, "symbolic link") != NULL, "log:\n%s", log.text);
        }
        /* the rewrite replaced the link itself and left its target alone */
        struct stat st;
        CHECK(t, lstat(fx.files[0], &st) == 0 && S_ISREG(st.st_mode));
    }
    if (fx.ctx)
        fixture_done(&fx);
    unlink(target);
    rmdir(elsewhere);
}

/* The user's key file is unsafe (readable by others, or a link to a file
 * elsewhere): nothing is read from or written to the cache, a warning names
 * the file and why, and the frame renders as without a cache. */
static void unsafe_key_file_turns_the_cache_off(mvr_test_state *t)
{
    static const unsigned char bytes[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
    for (int as_link = 0; as_link < 2; ++as_link) {
        static cache_fixture fx;
        static cache_run first, second;
        static trust_log log;
        if (!fixture_init(t, &fx, false)) {
            if (fx.ctx)
                fixture_done(&fx);
            return;
        }
        char key[600], real[600];
        snprintf(key, sizeof key, "%s/.mvr-key-%u", fx.dir, (unsigned)geteuid());
        snprintf(real, sizeof real, "%s/real-key", fx.dir);
        int fd = open(as_link ? real : key, O_WRONLY | O_CREAT | O_EXCL, 0600);
        CHECK(t, fd >= 0 && write(fd, bytes, sizeof bytes) == (ssize_t)sizeof bytes);
        if (fd >= 0)
            close(fd);
        if (as_link)
            CHECK(t, symlink(real, key) == 0);
        else
            CHECK(t, chmod(key, 0644) == 0);
        bool ok = render_run(t, fx.ctx, fx.dir, NULL, &first) && render_run(t, fx.ctx, fx.dir, &log, &second);
        char files[16][512];
        if (ok) {
            CHECK_EQ_INT(t, program_cache_entries(fx.dir, files, 16), 0);
            CHECK_EQ_INT(t, second.stats.program_binary_loads, 0);
            CHECK(t, second.stats.programs_compiled > 0);
            CHECK_MSG(t, log.warnings >= 1 && strstr(log.text, key) != NULL, "%s key; log:\n%s",
                      as_link ? "linked" : "0644", log.text);
            CHECK(t, memcmp(fx.none.pixels, second.pixels, sizeof second.pixels) == 0);
            printf("  %s key: %s", as_link ? "linked" : "0644", log.text);
        }
        fixture_done(&fx);
    }
}

MVR_TEST_MAIN(TEST(forged_entries_never_reach_the_driver), TEST(symlinked_entry_is_not_followed),
              TEST(unsafe_key_file_turns_the_cache_off), TEST(fifo_entry_is_a_miss))
