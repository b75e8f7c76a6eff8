#define _POSIX_C_SOURCE 200809L
/* gl: the environment's prefiltered maps and DFG table on disk
 * (gl/environment_cache.c). The same bytes with the cache off, cold (the
 * render that writes it) and warm (the render that reads it), on both view
 * paths and for both backgrounds that read the cubes directly; a damaged,
 * forged or truncated entry is logged and ignored (the maps are prefiltered
 * again, the same bytes come out) and rewritten; half floats go through the
 * cache exactly. */
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "environment_cache.h"
#include "gl_test_util.h"
#include "program_cache_files.h"
#include "stress/stress_util.h"

#define W 40
#define H 32
#define VIEWS 2

typedef struct env_log {
    int hits;      /* "maps from <entry>" */
    int rejects;   /* "...; computed again" */
    int warnings;  /* and errors: none expected, a bad entry only costs time */
} env_log;

static void env_log_fn(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    (void)id;
    env_log *log = user;
    log->hits += strstr(message, "environment cache: maps from") != NULL;
    log->rejects += strstr(message, "environment cache:") != NULL && strstr(message, "computed again") != NULL;
    log->warnings += level == MVR_LOG_WARNING || level == MVR_LOG_ERROR;
}

/* Metal and dielectric boxes of a few roughnesses on a rough floor. */
static mvr_scene *scene_make(mvr_test_state *t)
{
    mvr_scene *s = stress_scene();
    for (uint32_t i = 0; i < 4; ++i) {
        mvr_material_desc m = mvr_material_defaults();
        m.base_color_factor[0] = 0.9f, m.base_color_factor[1] = 0.7f, m.base_color_factor[2] = 0.4f;
        m.metallic_factor = (i & 1) ? 1.0f : 0.0f;
        m.roughness_factor = 0.1f + 0.25f * (float)i;
        mvr_material_id mat = {0};
        CHECK(t, mvr_scene_add_material(s, &m, &mat) == MVR_OK);
        stress_node(t, s, stress_add_box(t, s, 0.6f, mat), -2.25 + 1.5 * i, 0.8, 0.0, 1.0);
    }
    mvr_material_desc fm = mvr_material_defaults();
    fm.roughness_factor = 0.6f;
    mvr_material_id floor_mat = {0};
    CHECK(t, mvr_scene_add_material(s, &fm, &floor_mat) == MVR_OK);
    const double h = 0.70710678118654752;
    mvr_node_desc floor = {.mesh = stress_add_quad(t, s, floor_mat), .rotation = {-h, 0, 0, h}, .scale = {5, 5, 5}};
    mvr_node_id id;
    CHECK(t, mvr_scene_add_node(s, &floor, &id) == MVR_OK);
    return s;
}

static mvr_view_set *views_make(mvr_test_state *t)
{
    mvr_projection proj = {.yfov = 1.0, .znear = 0.1};
    mvr_view_desc v[VIEWS];
    for (int i = 0; i < VIEWS; ++i) {
        double eye[3] = {-1.0 + 2.0 * i, 2.5, 6}, target[3] = {0, 0.5, 0};
        v[i] = stress_view(eye, target, proj);
    }
    return stress_view_set(t, v, VIEWS, NULL);
}

typedef struct fixture {
    mvr_context *ctx;
    mvr_scene *scene;
    mvr_view_set *views;
    mvr_environment *env;
} fixture;

/* One render of every view, float pixels (no rounding hides a texel), with
 * the cache in dir (NULL: off). NULL after a failed check. */
static float *render(mvr_test_state *t, const fixture *fx, const char *dir, mvr_view_path path, mvr_background bg,
                     env_log *log)
{
    memset(log, 0, sizeof *log);
    mvr_renderer_desc rd = {.context = fx->ctx, .program_cache_dir = dir, .view_path = path};
    rd.logger.fn = env_log_fn;
    rd.logger.user_data = log;
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_error err;
    mvr_target_desc td = {W, H, VIEWS, MVR_COLOR_FORMAT_RGBA32F, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    mvr_render_desc desc = {.exposure = 1.0f, .tone_map = MVR_TONE_MAP_NONE, .environment = fx->env,
                            .background = bg, .background_blur = 0.35f};
    size_t layer = (size_t)W * H * 4;
    float *px = malloc(layer * VIEWS * sizeof *px);
    bool ok = px && mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
              mvr_renderer_render(r, fx->scene, fx->views, target, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "render: %s", r ? mvr_renderer_last_error(r) : err.message);
    for (uint32_t k = 0; ok && k < VIEWS; ++k)
        ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA32F, px + layer * k, layer * sizeof *px) ==
             MVR_OK;
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    if (!ok) {
        free(px);
        return NULL;
    }
    return px;
}

static bool same(const float *a, const float *b)
{
    return a && b && memcmp(a, b, (size_t)W * H * 4 * VIEWS * sizeof *a) == 0;
}

/* The cache's own entries (ibl-*) in dir, sorted. */
static uint32_t ibl_entries(const char *dir, char names[][512], uint32_t max)
{
    static char all[64][512];
    uint32_t n = program_cache_entries(dir, all, 64), m = 0;
    for (uint32_t i = 0; i < n && m < max; ++i)
        if (strstr(all[i], "/ibl-"))
            memcpy(names[m++], all[i], 512);
    return m;
}

/* Flips one byte in the middle (damage, or a forgery without the key), or
 * cuts the file to half its size. */
static bool damage(const char *path, bool truncate_it)
{
    struct stat st;
    if (stat(path, &st) != 0 || st.st_size < 64)
        return false;
    if (truncate_it)
        return truncate(path, st.st_size / 2) == 0;
    FILE *f = fopen(path, "r+b");
    if (!f)
        return false;
    bool ok = fseek(f, st.st_size / 2, SEEK_SET) == 0;
    int c = ok ? fgetc(f) : EOF;
    ok = c != EOF && fseek(f, st.st_size / 2, SEEK_SET) == 0 && fputc(c ^ 0x5a, f) != EOF;
    return fclose(f) == 0 && ok;
}

static void remove_dir(const char *dir)
{
    static char names[64][512];
    uint32_t n = program_cache_entries(dir, names, 64);
    for (uint32_t i = 0; i < n; ++i)
        unlink(names[i]);
    char key[600];
    snprintf(key, sizeof key, "%s/.mvr-key-%lu", dir, (unsigned long)geteuid());
    unlink(key);
    rmdir(dir);
}

/* cache off == cold == warm, on one path and background; then every entry
 * damaged, then truncated: logged, ignored, the same bytes, rewritten (the
 * next render reads it again). */
static void check_path(mvr_test_state *t, const fixture *fx, mvr_view_path path, mvr_background bg)
{
    char dir[] = "/tmp/mvr-env-cache-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK_MSG(t, 0, "mkdtemp failed");
        return;
    }
    const char *what = path == MVR_VIEW_PATH_LOOP ? "loop" : "multiview";
    const char *bg_name = mvr_background_name(bg);
    env_log log;
    float *off = render(t, fx, NULL, path, bg, &log);
    CHECK_MSG(t, log.hits == 0 && log.rejects == 0, "%s: the cache was used while off", what);
    float *cold = render(t, fx, dir, path, bg, &log);
    CHECK_MSG(t, log.hits == 0, "%s: a fresh folder gave a hit", what);
    char names[4][512];
    uint32_t n = ibl_entries(dir, names, 4);
    CHECK_MSG(t, n == 2, "%s: %u entries written (the maps and the DFG table expected)", what, n);
    float *warm = render(t, fx, dir, path, bg, &log);
    CHECK_MSG(t, log.hits == 1 && log.rejects == 0, "%s: warm render: %d hits, %d rejects", what, log.hits,
              log.rejects);
    CHECK_MSG(t, same(off, cold), "%s, background %s: cold render differs from cache off", what, bg_name);
    CHECK_MSG(t, same(off, warm), "%s, background %s: warm render differs from cache off", what, bg_name);
    for (int mode = 0; mode < 2; ++mode) {
        for (uint32_t i = 0; i < n; ++i)
            CHECK_MSG(t, damage(names[i], mode == 1), "cannot damage %s", names[i]);
        float *bad = render(t, fx, dir, path, bg, &log);
        CHECK_MSG(t, log.hits == 0 && log.rejects == (int)n && log.warnings == 0,
                  "%s, %s entries: %d hits, %d rejects logged, %d warnings", what,
                  mode ? "truncated" : "damaged", log.hits, log.rejects, log.warnings);
        CHECK_MSG(t, same(off, bad), "%s, %s entries: the pixels changed", what, mode ? "truncated" : "damaged");
        free(bad);
        float *again = render(t, fx, dir, path, bg, &log);
        CHECK_MSG(t, log.hits == 1 && log.rejects == 0, "%s: after a rewrite: %d hits, %d rejects", what,
                  log.hits, log.rejects);
        CHECK_MSG(t, same(off, again), "%s: the rewritten entry gives other pixels", what);
        free(again);
    }
    printf("  %s, background %s: cache off == cold == warm; damaged and truncated entries ignored\n", what,
           bg_name);
    free(off);
    free(cold);
    free(warm);
    remove_dir(dir);
}

static void same_bytes_with_and_without_cache(mvr_test_state *t)
{
    fixture fx = {0};
    fx.ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!fx.ctx)
        return;
    fx.scene = scene_make(t);
    fx.views = views_make(t);
    mvr_error err;
    CHECK_MSG(t, mvr_environment_create(NULL, &fx.env, &err) == MVR_OK, "%s", err.message);
    if (fx.env) {
        /* blur shows the specular chain itself, env the source cube */
        check_path(t, &fx, MVR_VIEW_PATH_MULTIVIEW, MVR_BACKGROUND_BLUR);
        check_path(t, &fx, MVR_VIEW_PATH_LOOP, MVR_BACKGROUND_ENVIRONMENT);
    }
    mvr_environment_destroy(fx.env);
    mvr_view_set_destroy(fx.views);
    mvr_scene_destroy(fx.scene);
    mvr_context_destroy(fx.ctx);
}

/* Every half value (NaNs with their payload, infinities, subnormals, both
 * zeros) goes to float and back unchanged; floats no half holds are refused. */
static void halves_round_trip(mvr_test_state *t)
{
    uint32_t bad = 0;
    for (uint32_t h = 0; h < 65536u; ++h) {
        uint16_t back = 0;
        if (!mvr_half_from_float_exact(mvr_half_to_float((uint16_t)h), &back) || back != h)
            ++bad;
    }
    CHECK_MSG(t, bad == 0, "%u of 65536 halves do not round-trip", bad);
    CHECK(t, mvr_half_to_float(0x3c00u) == 1.0f && mvr_half_to_float(0x0001u) == 0x1p-24f &&
                 mvr_half_to_float(0x7bffu) == 65504.0f && mvr_half_to_float(0xc000u) == -2.0f);
    const float refused[5] = {0.1f, 65520.0f, 0x1p-25f, 1.0f + 0x1p-11f, 3e38f};
    for (int i = 0; i < 5; ++i) {
        uint16_t h;
        CHECK_MSG(t, !mvr_half_from_float_exact(refused[i], &h), "%g taken as a half", (double)refused[i]);
    }
}

MVR_TEST_MAIN(TEST(halves_round_trip), TEST(same_bytes_with_and_without_cache))
