/* mvr bench: one scene under a matrix of configurations (view path,
 * material path, anti-aliasing, transparency order, and the reference),
 * each timed over F frames and compared with the reference render; or,
 * with --env-axes, the environment prefilter's axes (specular map size x
 * GGX samples per texel), each timed by its prefilter and compared with the
 * environment integrated per pixel. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "cli_common.h"
#include "cli_env.h"
#include "cli_options.h"
#include "cli_scene.h"
#include "commands.h"
#include "mvr/mvr_image.h"

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#endif
#endif
#ifndef CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#define CALLGRIND_TOGGLE_COLLECT
#endif


/* ss: supersampling per side; ss 0 = 4x MSAA instead */
static void add_config(bench_config *list, uint32_t *n, mvr_view_path vp, mvr_material_path mp, uint32_t ss,
                       mvr_transparency_order order, bool reference)
{
    bench_config *c = &list[(*n)++];
    memset(c, 0, sizeof *c);
    c->skinning_path = MVR_SKINNING_PATH_AUTO;
    c->view_path = vp;
    c->material_path = mp;
    c->supersample = ss ? ss : 1;
    c->msaa = ss ? 0 : 4;
    c->order = order;
    c->reference = reference;
    if (reference) {
        snprintf(c->name, sizeof c->name, "reference");
        snprintf(c->group, sizeof c->group, "reference");
        return;
    }
    const char *aa = ss == 0 ? "msaa4x" : ss > 1 ? (ss == 2 ? "ss2x2" : "ss4x4") : "noaa";
    const char *ord = mvr_transparency_order_name(order);
    snprintf(c->name, sizeof c->name, "%s/%s/%s%s%s", mvr_view_path_name(vp), mvr_material_path_name(mp), aa,
             order != MVR_TRANSPARENCY_ORDER_AUTO ? "/" : "", order != MVR_TRANSPARENCY_ORDER_AUTO ? ord : "");
    snprintf(c->group, sizeof c->group, "%s/%s", aa, ord);
}

/* quick: both view paths and auto on the array path, both explicit paths on
 * the per-material path, 4x MSAA, 2x2 supersampling, per-view transparency
 * order, the reference. full: every view path x material path x
 * anti-aliasing x transparency order (MSAA resolves view by view, so not
 * with multiview). The reference comes first (everything is compared with
 * it). */
/* The feature bits of the material extensions a configuration may draw as
 * absent (overrides.disable_features), found by their public names. */
static uint32_t extension_features(void)
{
    uint32_t bits = 0;
    for (uint32_t b = 1; b; b <<= 1) {
        const char *name = mvr_program_feature_name(b);
        if (name && (strcmp(name, "SPECULAR") == 0 || strcmp(name, "CLEARCOAT") == 0 ||
                     strcmp(name, "TRANSMISSION") == 0 || strcmp(name, "SHEEN") == 0 ||
                     strcmp(name, "IRIDESCENCE") == 0 || strcmp(name, "ANISOTROPY") == 0))
            bits |= b;
    }
    return bits;
}

/* The skinning axis (a scene with skins or morph targets): each view path
 * with the vertex and the pre-skinning path, no anti-aliasing; one group,
 * so the report checks they give the same pixels. */
static void add_skinning_axis(bench_config *out, uint32_t *n)
{
    const mvr_view_path vps[3] = {MVR_VIEW_PATH_MULTIVIEW, MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_AUTO};
    const mvr_skinning_path sps[2] = {MVR_SKINNING_PATH_VERTEX, MVR_SKINNING_PATH_PRESKIN};
    for (int v = 0; v < 3; ++v)
        for (int k = 0; k < 3; ++k) {
            if (k == 2 && vps[v] != MVR_VIEW_PATH_AUTO)
                continue; /* both paths auto: against the four forced pairs */
            add_config(out, n, vps[v], MVR_MATERIAL_PATH_ARRAYS, 1, MVR_TRANSPARENCY_ORDER_AUTO, false);
            bench_config *c = &out[*n - 1];
            c->skinning_path = k < 2 ? sps[k] : MVR_SKINNING_PATH_AUTO;
            c->skinning_axis = true;
            size_t l = strlen(c->name);
            snprintf(c->name + l, sizeof c->name - l, "/%s", mvr_skinning_path_name(c->skinning_path));
        }
}

static uint32_t make_matrix(bool full, bool deformed, bench_config *out)
{
    uint32_t n = 0;
    add_config(out, &n, MVR_VIEW_PATH_LOOP, MVR_MATERIAL_PATH_ARRAYS, 4, MVR_TRANSPARENCY_ORDER_PER_VIEW, true);
    if (deformed)
        add_skinning_axis(out, &n);
    const mvr_view_path vps[3] = {MVR_VIEW_PATH_MULTIVIEW, MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_AUTO};
    const mvr_material_path mps[2] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL};
    if (!full) {
        for (int v = 0; v < 3; ++v)
            add_config(out, &n, vps[v], mps[0], 1, MVR_TRANSPARENCY_ORDER_AUTO, false);
        for (int v = 0; v < 2; ++v)
            add_config(out, &n, vps[v], mps[1], 1, MVR_TRANSPARENCY_ORDER_AUTO, false);
        add_config(out, &n, MVR_VIEW_PATH_AUTO, MVR_MATERIAL_PATH_AUTO, 1, MVR_TRANSPARENCY_ORDER_AUTO, false);
        add_config(out, &n, MVR_VIEW_PATH_AUTO, mps[0], 0, MVR_TRANSPARENCY_ORDER_AUTO, false);
        add_config(out, &n, MVR_VIEW_PATH_MULTIVIEW, mps[0], 2, MVR_TRANSPARENCY_ORDER_AUTO, false);
        add_config(out, &n, MVR_VIEW_PATH_AUTO, mps[0], 2, MVR_TRANSPARENCY_ORDER_AUTO, false);
        add_config(out, &n, MVR_VIEW_PATH_MULTIVIEW, mps[0], 1, MVR_TRANSPARENCY_ORDER_CENTROID, false);
        add_config(out, &n, MVR_VIEW_PATH_MULTIVIEW, mps[0], 1, MVR_TRANSPARENCY_ORDER_PER_VIEW, false);
        return n;
    }
    const uint32_t aas[3] = {1, 0, 2};
    const mvr_transparency_order orders[3] = {MVR_TRANSPARENCY_ORDER_AUTO, MVR_TRANSPARENCY_ORDER_CENTROID,
                                              MVR_TRANSPARENCY_ORDER_PER_VIEW};
    for (int o = 0; o < 3; ++o)
        for (int a = 0; a < 3; ++a)
            for (int m = 0; m < 2; ++m)
                for (int v = 0; v < 3; ++v)
                    if (aas[a] != 0 || vps[v] != MVR_VIEW_PATH_MULTIVIEW)
                        add_config(out, &n, vps[v], mps[m], aas[a], orders[o], false);
    /* both paths auto: against the four forced pairs */
    for (int o = 0; o < 3; ++o)
        for (int a = 0; a < 3; ++a)
            add_config(out, &n, MVR_VIEW_PATH_AUTO, MVR_MATERIAL_PATH_AUTO, aas[a], orders[o], false);
    return n;
}

double bench_now_ms(clockid_t clock)
{
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_median(double *v, uint32_t n)
{
    qsort(v, n, sizeof *v, compare_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The frames callgrind counts (collection is toggled around them). */
/* An animated scene's pose for a configuration's frame number `frame`
 * (warm-up frames counted): every configuration's last frame has the same
 * pose. Outside the timed span: posing is the scene's CPU work, not the
 * renderer's. */
static void pose(const bench_options *o, mvr_scene *s, uint32_t frame)
{
    if (o->animate)
        mvr_scene_apply_animation(s, MVR_ANIMATION_ALL, o->pose_times[frame % 2], MVR_ANIMATION_CLAMP);
}

__attribute__((noinline)) static bool measured_frames(const bench_options *o, uint32_t first, mvr_renderer *r,
                                                      mvr_scene *s, mvr_view_set *vs, const bench_chunks *chunks,
                                                      mvr_target *t, uint32_t frames, double *wall, double *cpu,
                                                      double *gpu)
{
    bool ok = true;
    CALLGRIND_START_INSTRUMENTATION;
    CALLGRIND_TOGGLE_COLLECT;
    for (uint32_t f = 0; f < frames && ok; ++f) {
        CALLGRIND_TOGGLE_COLLECT;
        pose(o, s, first + f);
        CALLGRIND_TOGGLE_COLLECT;
        double w0 = bench_now_ms(CLOCK_MONOTONIC), c0 = bench_now_ms(CLOCK_THREAD_CPUTIME_ID);
        ok = bench_render_views(r, s, vs, chunks, t, &o->render) == MVR_OK && mvr_renderer_finish(r) == MVR_OK;
        wall[f] = bench_now_ms(CLOCK_MONOTONIC) - w0;
        cpu[f] = bench_now_ms(CLOCK_THREAD_CPUTIME_ID) - c0;
        mvr_frame_stats st;
        mvr_renderer_get_stats(r, &st);
        gpu[f] = st.gpu_ms;
    }
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_STOP_INSTRUMENTATION;
    return ok;
}

/* One configuration while it is measured: its renderer and target stay
 * alive across the rounds, frames append to its time arrays. */
typedef struct config_run {
    mvr_renderer *r;
    mvr_target *t;
    double *times;               /* wall, cpu and gpu, o->frames each */
    uint32_t measured;
    uint32_t cpu_ss;
    const bench_chunks *chunks;  /* the reference: its views in chunks (bench_reference.c); else NULL */
} config_run;

static void release_run(config_run *cr)
{
    free(cr->times);
    mvr_target_destroy(cr->t);
    mvr_renderer_destroy(cr->r);
    memset(cr, 0, sizeof *cr);
}

/* Creates the configuration's renderer and target and warms it up; false
 * on failure (printed). A configuration the GL cannot run is skipped (true,
 * res->skipped set, nothing made). */
static bool setup_config(const bench_options *o, mvr_context *ctx, mvr_scene *scene, mvr_view_set *vs,
                         const bench_config *c, bench_result *res, config_run *cr)
{
    memset(cr, 0, sizeof *cr);
    const mvr_caps *caps = mvr_context_caps(ctx);
    if (c->view_path == MVR_VIEW_PATH_MULTIVIEW && !caps->ext.ovr_multiview2) {
        snprintf(res->skipped, sizeof res->skipped, "no GL_OVR_multiview2");
        return true;
    }
    uint32_t n = mvr_view_set_count(vs), w = o->scene.width, h = o->scene.height, ss = c->supersample;
    if (c->reference && o->reference_chunks) {
        /* at a size that fits: fewer samples, or chunks of views */
        cr->chunks = o->reference_chunks;
        ss = cr->chunks->supersample;
        n = cr->chunks->count ? cr->chunks->per_chunk : n;
    }
    mvr_renderer_desc rd = {.context = ctx, .view_path = c->view_path, .material_path = c->material_path,
                            .transparency_order = c->order, .logger = o->context.logger,
                            .overrides = o->overrides, .skinning_path = c->skinning_path,
                            .program_cache_dir = o->program_cache_dir};
    rd.overrides.disable_features |= c->disable_features;
    mvr_error err;
    if (mvr_renderer_create(&rd, &cr->r, &err) != MVR_OK) {
        fprintf(stderr, "mvr bench: %s: %s\n", c->name, err.message);
        return false;
    }
    /* the reference resolves its 4x4 samples on the CPU, in double (an
     * independent check); other supersampled configurations use the
     * renderer's own resolve pass, which works on the multiview path too */
    cr->cpu_ss = c->reference ? ss : 1;
    mvr_target_desc td = {w * cr->cpu_ss, h * cr->cpu_ss, n,
                          cr->cpu_ss > 1 ? MVR_COLOR_FORMAT_RGBA32F : MVR_COLOR_FORMAT_DEFAULT,
                          0, 0, 0, c->msaa, c->reference ? 0 : (ss > 1 ? ss : 0),
                          /* noaa (and the CPU-resolved reference) pin none: the default anti-aliases */
                          c->msaa > 1 || (!c->reference && ss > 1) ? MVR_ANTI_ALIASING_DEFAULT : MVR_ANTI_ALIASING_NONE, 0};
    cr->times = calloc((size_t)o->frames * 3, sizeof *cr->times);
    mvr_result rr = cr->times ? mvr_target_create(cr->r, &td, &cr->t) : MVR_ERROR_OUT_OF_MEMORY;
    /* auto renders one frame even without warm-up: its stats say whether it tunes */
    bool tuned = c->view_path == MVR_VIEW_PATH_AUTO || c->material_path == MVR_MATERIAL_PATH_AUTO ||
                 c->skinning_path == MVR_SKINNING_PATH_AUTO;
    uint32_t f = 0;
    for (; rr == MVR_OK && (f < o->warmup || (tuned && f == 0)); ++f) {
        pose(o, scene, f);
        rr = bench_render_views(cr->r, scene, vs, cr->chunks, cr->t, &o->render);
    }
    /* auto is measured after tuning: more warm-up frames until its tuner settled */
    mvr_frame_stats st;
    mvr_renderer_get_stats(cr->r, &st);
    for (;
         rr == MVR_OK &&
         (st.auto_choice.state == MVR_AUTO_TUNING || st.auto_material.state == MVR_AUTO_TUNING ||
          st.auto_skinning.state == MVR_AUTO_TUNING) &&
         f < o->warmup + 120; /* three decisions of at most 36 frames each */
         ++f) {
        pose(o, scene, f);
        rr = bench_render_views(cr->r, scene, vs, cr->chunks, cr->t, &o->render);
        mvr_renderer_get_stats(cr->r, &st);
        res->tuning_frames = f + 1;
    }
    bool ok = rr == MVR_OK;
    if (rr == MVR_ERROR_OUT_OF_MEMORY && !c->reference) {
        /* what the GL cannot allocate at this size is left out, not the whole bench */
        snprintf(res->skipped, sizeof res->skipped, "out of GL memory: %s", mvr_renderer_last_error(cr->r));
        fprintf(stderr, "mvr bench: %s left out: %s\n", c->name, res->skipped);
        release_run(cr);
        return true;
    }
    res->auto_choice = st.auto_choice;
    res->auto_skinning = st.auto_skinning;
    res->auto_material = st.auto_material;
    if (!ok) {
        fprintf(stderr, "mvr bench: %s: %s\n", c->name, mvr_renderer_last_error(cr->r));
        release_run(cr);
    }
    return ok;
}

/* `frames` more measured frames of a configuration set up. */
static bool measure_config(const bench_options *o, mvr_scene *scene, mvr_view_set *vs, const bench_config *c,
                           config_run *cr, uint32_t frames)
{
    if (frames > o->frames - cr->measured)
        frames = o->frames - cr->measured;
    double *wall = cr->times, *cpu = cr->times + o->frames, *gpu = cr->times + 2 * o->frames;
    uint32_t at = cr->measured;
    bool ok = measured_frames(o, o->warmup + at, cr->r, scene, vs, cr->chunks, cr->t, frames, wall + at, cpu + at,
                              gpu + at);
    cr->measured += frames;
    if (!ok)
        fprintf(stderr, "mvr bench: %s: %s\n", c->name, mvr_renderer_last_error(cr->r));
    return ok;
}

/* The value at fraction q of sorted v (linear between neighbours). */
static double quantile(const double *v, uint32_t n, double q)
{
    double x = q * (double)(n - 1);
    uint32_t i = (uint32_t)x;
    return i + 1 < n ? v[i] + (x - i) * (v[i + 1] - v[i]) : v[n - 1];
}

/* What a result keeps of a frame's stats: the paths that ran, draws and binds. */
void bench_take_stats(bench_result *res, const mvr_frame_stats *st)
{
    res->view_path_ran = mvr_view_path_name(st->view_path);
    res->material_path_ran = mvr_material_path_name(st->material_path);
    res->draws = st->draws;
    res->draw_calls = st->draw_calls;
    res->passes = st->passes;
    res->program_binds = st->program_binds;
    res->texture_binds = st->texture_binds;
    res->ubo_range_binds = st->ubo_range_binds;
}

/* Statistics of the measured frames and the read-back; releases the run. */
static bool finish_config(const bench_options *o, mvr_scene *scene, mvr_view_set *vs, const bench_config *c,
                          config_run *cr, bench_result *res)
{
    uint32_t n = mvr_view_set_count(vs), w = o->scene.width, h = o->scene.height, frames = cr->measured;
    mvr_frame_stats st;
    mvr_renderer_get_stats(cr->r, &st);
    bench_take_stats(res, &st);
    double *wall = cr->times, *cpu = cr->times + o->frames, *gpu = cr->times + 2 * o->frames;
    res->wall_median = bench_median(wall, frames); /* sorts wall */
    res->wall_min = wall[0];
    res->wall_max = wall[frames - 1];
    res->wall_q1 = quantile(wall, frames, 0.25);
    res->wall_q3 = quantile(wall, frames, 0.75);
    res->cpu_median = bench_median(cpu, frames);
    res->gpu_median = gpu[0] < 0 ? -1.0 : bench_median(gpu, frames);
    size_t layer = (size_t)w * h * 4;
    res->display = malloc(layer * n);
    if (cr->chunks && cr->chunks->count)
        pose(o, scene, o->warmup + o->frames - 1); /* the last measured frame's pose, drawn again chunk by chunk */
    bool ok = res->display != NULL &&
              bench_read_views(cr->r, scene, vs, cr->chunks, cr->t, &o->render, w, h, cr->cpu_ss, res->display);
    res->ran = ok;
    if (!ok)
        fprintf(stderr, "mvr bench: %s: %s\n", c->name, mvr_renderer_last_error(cr->r));
    release_run(cr);
    return ok;
}

/* Runs one configuration alone: warm-up, F measured frames, read-back (the
 * callgrind child). */
static bool run_config(const bench_options *o, mvr_context *ctx, mvr_scene *scene, mvr_view_set *vs,
                       const bench_config *c, bench_result *res)
{
    config_run cr;
    if (!setup_config(o, ctx, scene, vs, c, res, &cr))
        return false;
    if (!cr.r)
        return true; /* skipped */
    if (!measure_config(o, scene, vs, c, &cr, o->frames)) {
        release_run(&cr);
        return false;
    }
    return finish_config(o, scene, vs, c, &cr, res);
}

/* Error of a display image against the reference: RGB channels; covered:
 * only the pixels the reference covers (alpha > 0). Returns the pixels
 * compared. */
size_t bench_compare(const uint8_t *ref, const uint8_t *img, size_t pixels, bool covered, bench_result *res)
{
    double sum2 = 0;
    unsigned max = 0;
    size_t over = 0, n = 0;
    for (size_t i = 0; i < pixels; ++i) {
        if (covered && ref[i * 4 + 3] == 0)
            continue;
        ++n;
        bool off = false;
        for (size_t c = 0; c < 3; ++c) {
            int d = abs((int)img[i * 4 + c] - (int)ref[i * 4 + c]);
            sum2 += (double)d * d;
            max = (unsigned)d > max ? (unsigned)d : max;
            off |= d > 2;
        }
        over += off;
    }
    double mse = n ? sum2 / (3.0 * (double)n) / (255.0 * 255.0) : 0.0;
    res->rmse = sqrt(mse);
    res->psnr_db = mse > 0 ? 10.0 * log10(1.0 / mse) : INFINITY;
    res->max_abs = max;
    res->over_2 = n ? 100.0 * (double)over / (double)n : 0.0;
    return n;
}

static int max_byte_diff(const uint8_t *a, const uint8_t *b, size_t bytes)
{
    int m = 0;
    for (size_t i = 0; i < bytes; ++i) {
        int d = abs((int)a[i] - (int)b[i]);
        m = d > m ? d : m;
    }
    return m;
}

/* --callgrind: each configuration again in a child under callgrind, which
 * counts only the measured frames (collection toggled around them). */
static bool count_instructions(int argc, char **argv, const bench_options *o, uint32_t k, uint64_t *per_frame)
{
    char out[4096];
    snprintf(out, sizeof out, "%s/callgrind.%u", o->out_dir, k);
    char only[16];
    snprintf(only, sizeof only, "%u", k);
    char file_arg[4200];
    snprintf(file_arg, sizeof file_arg, "--callgrind-out-file=%s", out);
    char **args = calloc((size_t)argc + 12, sizeof *args);
    if (!args)
        return false;
    int n = 0;
    args[n++] = "valgrind";
    args[n++] = "--tool=callgrind";
    args[n++] = "--instr-atstart=no";
    args[n++] = "--collect-atstart=no";
    args[n++] = "--separate-threads=yes";
    args[n++] = file_arg;
    args[n++] = "/proc/self/exe";
    for (int i = 0; i < argc; ++i)
        if (strcmp(argv[i], "--callgrind") != 0)
            args[n++] = argv[i];
    args[n++] = "--only";
    args[n++] = only;
    args[n++] = "--quiet";
    args[n] = NULL;
    char self[4096];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len > 0) {
        self[len] = 0;
        args[6] = self;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        freopen("/dev/null", "w", stdout);
        freopen("/dev/null", "w", stderr);
        execvp("valgrind", args);
        _exit(127);
    }
    free(args);
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "mvr bench: callgrind run of configuration %u failed (is valgrind installed?)\n", k);
        return false;
    }
    /* thread 1 (the submitting thread): its "totals:" line */
    char thread1[4200];
    snprintf(thread1, sizeof thread1, "%s-01", out);
    FILE *f = fopen(thread1, "r");
    unsigned long long total = 0;
    char line[512];
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "totals: %llu", &total) == 1)
            break;
    if (f)
        fclose(f);
    /* callgrind writes one file per thread: keep none */
    for (int th = 0; th <= 64; ++th) {
        char p[4300];
        snprintf(p, sizeof p, th ? "%s-%02d" : "%s", out, th);
        remove(p);
    }
    *per_frame = total / o->frames;
    return total > 0;
}

void bench_progress(const bench_options *o, uint32_t done, uint32_t total, const char *what)
{
    if (o->quiet)
        return;
    if (isatty(STDERR_FILENO)) {
        char bar[31];
        uint32_t fill = total ? 30 * done / total : 30;
        for (uint32_t i = 0; i < 30; ++i)
            bar[i] = i < fill ? '#' : '.';
        bar[30] = 0;
        fprintf(stderr, "\r[%s] %u/%u %-40s", bar, done, total, what);
        if (done == total)
            fprintf(stderr, "\n");
    } else {
        fprintf(stderr, "mvr bench: %u/%u %s\n", done, total, what);
    }
}

/* The frame matrix's scene: loaded, under the environment mvr render takes,
 * the configurations for it, and the poses of an animated one. */
static int load_matrix_scene(bench_options *o, mvr_scene **scene, mvr_view_set **vs, mvr_environment **env,
                             bench_config *configs, uint32_t *count)
{
    int rc = cli_load_scene("mvr bench", &o->scene, scene, vs);
    if (rc != MVR_EXIT_OK)
        return rc;
    memset(&o->render, 0, sizeof o->render);
    o->render.exposure = 1.0f;
    rc = cli_env_create("mvr bench", &o->env, o->scene.scene_file != NULL, &o->render, env, NULL);
    if (rc != MVR_EXIT_OK)
        return rc;
    mvr_scene_info info;
    mvr_scene_get_info(*scene, &info);
    *count = make_matrix(o->full, info.skins || info.morph_targets, configs);
    /* an animated scene is posed anew every frame: at the start and the
     * middle of its animations, alternately */
    double start = INFINITY, end = -INFINITY;
    for (uint32_t i = 0; i < info.animations; ++i) {
        mvr_animation_info ai;
        if (mvr_scene_get_animation_info(*scene, i, &ai) == MVR_OK) {
            start = fmin(start, ai.start);
            end = fmax(end, ai.end);
        }
    }
    o->animate = info.animations > 0 && end > start;
    o->pose_times[0] = o->animate ? start : 0.0;
    o->pose_times[1] = o->animate ? 0.5 * (start + end) : 0.0;
    return MVR_EXIT_OK;
}

/* Does the scene draw anything blended? (a small frame's sub-passes
 * tell). Without, the per-view transparency order changes nothing: those
 * configurations are left out rather than listed without results. Adds a
 * configuration for each material extension the scene's programs use. */
static bool probe_scene(const bench_options *o, mvr_context *ctx, mvr_scene *scene, mvr_view_set *vs,
                        bench_config *configs, uint32_t *count)
{
    mvr_renderer_desc rd = {.context = ctx, .overrides = o->overrides, .program_cache_dir = o->program_cache_dir};
    mvr_renderer *r = NULL;
    mvr_target *t = NULL;
    mvr_target_desc td = {16, 16, mvr_view_set_count(vs), MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0,
                          MVR_ANTI_ALIASING_NONE, 0};
    mvr_frame_stats st;
    memset(&st, 0, sizeof st);
    if (mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &t) == MVR_OK &&
        mvr_renderer_render(r, scene, vs, t, &o->render) == MVR_OK)
        mvr_renderer_get_stats(r, &st);
    bool has_blend = st.sub_passes[2] > 0; /* [2]: blended sub-passes */
    /* the material extensions the scene's programs use: each gets a
     * configuration with it drawn as absent (what it costs, what it
     * changes) */
    uint32_t extensions = 0, extension_bits = extension_features();
    for (uint32_t i = 0; r && i < mvr_renderer_program_count(r); ++i) {
        mvr_program_info info;
        if (mvr_renderer_get_program_info(r, i, &info) && info.mesh)
            extensions |= info.features & extension_bits;
    }
    for (uint32_t bit = 1; bit && *count < BENCH_MAX_CONFIGS; bit <<= 1) {
        if (!(extensions & bit))
            continue;
        add_config(configs, count, MVR_VIEW_PATH_AUTO, MVR_MATERIAL_PATH_ARRAYS, 1, MVR_TRANSPARENCY_ORDER_AUTO,
                   false);
        bench_config *c = &configs[*count - 1];
        c->disable_features = bit;
        size_t l = strlen(c->name);
        snprintf(c->name + l, sizeof c->name - l, "/no_%s", mvr_program_feature_name(bit));
        snprintf(c->group, sizeof c->group, "no_%s", mvr_program_feature_name(bit));
    }
    mvr_target_destroy(t);
    mvr_renderer_destroy(r);
    return has_blend;
}

/* Leaves out what cannot run or changes nothing here (4x MSAA without 4
 * samples, other transparency orders without blending), said in omitted. */
static void leave_out_configs(mvr_context *ctx, bool has_blend, bench_config *configs, uint32_t *count,
                              char *omitted, size_t size)
{
    int max_samples = mvr_context_caps(ctx)->limits.max_samples;
    if (max_samples < 4) {
        uint32_t kept = 0;
        for (uint32_t k = 0; k < *count; ++k)
            if (configs[k].msaa == 0)
                configs[kept++] = configs[k];
        snprintf(omitted, size, "4x MSAA left out: GL_MAX_SAMPLES is %d; ", max_samples);
        *count = kept;
    }
    if (!has_blend) {
        uint32_t kept = 0;
        for (uint32_t k = 0; k < *count; ++k)
            if (configs[k].reference || configs[k].order == MVR_TRANSPARENCY_ORDER_AUTO)
                configs[kept++] = configs[k];
        size_t l = strlen(omitted);
        if (kept < *count)
            snprintf(omitted + l, size - l,
                     "%u configurations with another transparency order left out: the scene draws nothing blended",
                     *count - kept);
        *count = kept;
    }
}

/* What the matrix runs on: the scene, its views, and the configurations. */
typedef struct bench_matrix {
    mvr_context *ctx;
    mvr_scene *scene;
    mvr_view_set *vs;
    bench_config *configs;
    bench_result *results;
    uint32_t count;
    size_t pixels;               /* of all views */
} bench_matrix;

/* every configuration set up and warmed, then its frames taken in
 * rounds that visit all of them in turn (starting one further each
 * round), so a change of load on the machine falls on all alike */
static bool measure_rounds(const bench_options *o, const bench_matrix *m, config_run *runs, uint32_t rounds)
{
    bool all_ok = true;
    uint32_t count = m->count;
    for (uint32_t k = 0; k < count && all_ok; ++k) {
        m->results[k].group_diff = -1;
        bench_progress(o, k, count * 2, m->configs[k].name);
        all_ok = setup_config(o, m->ctx, m->scene, m->vs, &m->configs[k], &m->results[k], &runs[k]);
    }
    for (uint32_t round = 0; round < rounds && all_ok; ++round) {
        /* frames of this round: the F frames spread as evenly as they go */
        uint32_t per = o->frames * (round + 1) / rounds - o->frames * round / rounds;
        for (uint32_t i = 0; i < count && all_ok; ++i) {
            uint32_t k = (i + round) % count;
            if (runs[k].r)
                all_ok = measure_config(o, m->scene, m->vs, &m->configs[k], &runs[k], per);
        }
        bench_progress(o, count + (round + 1) * count / rounds, count * 2, "rounds");
    }
    return all_ok;
}

/* Each configuration's statistics and read-back, compared with the
 * reference and with the first of its group; with --callgrind, its
 * instructions counted in a child. */
static bool finish_all(int argc, char **argv, const bench_options *o, const bench_matrix *m, config_run *runs)
{
    bool all_ok = true;
    bench_result *results = m->results;
    for (uint32_t k = 0; k < m->count && all_ok; ++k) {
        const bench_config *c = &m->configs[k];
        bench_result *res = &results[k];
        if (runs[k].r)
            all_ok = finish_config(o, m->scene, m->vs, c, &runs[k], res);
        if (all_ok && res->ran) {
            bench_compare(results[0].display, res->display, m->pixels, false, res);
            for (uint32_t j = 0; j < k; ++j)
                if (results[j].ran && strcmp(m->configs[j].group, c->group) == 0) {
                    res->group_diff = max_byte_diff(results[j].display, res->display, m->pixels * 4);
                    break;
                }
        }
        if (all_ok && o->callgrind && res->ran && !count_instructions(argc, argv, o, k, &res->instructions))
            all_ok = false;
    }
    return all_ok;
}

/* Pareto front over (frame time, RMSE), the noise counted: k is
 * dominated by a j at least as close to the reference that is faster by
 * more than the noise (j's q3 below k's q1: the interquartile ranges
 * apart), or by a j closer to it and not slower beyond the noise (j's
 * median at most k's q3) */
static void mark_pareto(bench_result *results, uint32_t count)
{
    for (uint32_t k = 0; k < count; ++k) {
        if (!results[k].ran)
            continue;
        const bench_result *rk = &results[k];
        bool dominated = false;
        for (uint32_t j = 0; j < count && !dominated; ++j) {
            const bench_result *rj = &results[j];
            if (j == k || !rj->ran || rj->rmse > rk->rmse)
                continue;
            dominated = rj->wall_q3 < rk->wall_q1 || (rj->rmse < rk->rmse && rj->wall_median <= rk->wall_q3);
        }
        results[k].pareto = !dominated;
    }
}

/* The frame matrix on a loaded scene: measured, compared, reported. */
static int run_matrix(int argc, char **argv, const bench_options *o, const bench_matrix *m, const char *omitted)
{
    /* every configuration's renderer and target live across the rounds */
    config_run runs[BENCH_MAX_CONFIGS];
    memset(runs, 0, sizeof runs);
    uint32_t rounds = o->rounds < o->frames ? o->rounds : o->frames;
    bool all_ok = measure_rounds(o, m, runs, rounds) && finish_all(argc, argv, o, m, runs);
    for (uint32_t k = 0; k < m->count; ++k)
        release_run(&runs[k]);
    if (!all_ok)
        return MVR_EXIT_FAILURE;
    bench_progress(o, m->count, m->count, "done");
    mark_pareto(m->results, m->count);
    char cmdline[1024];
    bench_command_line(argc, argv, cmdline, sizeof cmdline);
    bench_run run = {o->scene.scene_file ? o->scene.scene_file : o->scene.demo, o->out_dir, cmdline,
                     mvr_context_caps(m->ctx)->renderer, mvr_view_set_count(m->vs), o->scene.width, o->scene.height,
                     o->frames, m->count, m->configs, m->results, 0, omitted, false, NULL, 0, m->pixels, rounds};
    return bench_write_reports(&run) ? MVR_EXIT_OK : MVR_EXIT_FAILURE;
}

int mvr_cmd_bench(int argc, char **argv)
{
    bench_options o;
    int rc = bench_options_parse(argc, argv, &o);
    if (rc != MVR_EXIT_OK) {
        camera_file_free(&o.cameras);
        return rc < 0 ? MVR_EXIT_OK : rc;
    }
    if (!cli_make_dirs("mvr bench", o.out_dir)) {
        camera_file_free(&o.cameras);
        return MVR_EXIT_FAILURE;
    }
    o.program_cache_dir = cli_program_cache_dir("mvr bench", o.program_cache, o.program_cache_buf,
                                                sizeof o.program_cache_buf);
    mvr_error err;
    /* mvr bench reads the library's MVR_* debugging variables (docs/guide.md) */
    if (mvr_renderer_overrides_from_env(&o.overrides, &err) != MVR_OK) {
        fprintf(stderr, "mvr bench: %s\n", err.message);
        camera_file_free(&o.cameras);
        return MVR_EXIT_USAGE;
    }
    mvr_environment *env = NULL;
    bench_config configs[BENCH_MAX_CONFIGS];
    bench_result results[BENCH_MAX_CONFIGS];
    memset(results, 0, sizeof results);
    bench_matrix m = {.configs = configs, .results = results};
    bench_chunks chunks;
    memset(&chunks, 0, sizeof chunks);
    rc = MVR_EXIT_FAILURE;
    if (mvr_context_create(&o.context, &m.ctx, &err) != MVR_OK) {
        fprintf(stderr, "mvr bench: %s\n", err.message);
        goto done;
    }
    if (o.env_axes) {
        rc = bench_run_env_axes(argc, argv, &o, m.ctx);
        goto done;
    }
    rc = load_matrix_scene(&o, &m.scene, &m.vs, &env, configs, &m.count);
    if (rc != MVR_EXIT_OK)
        goto done;
    rc = MVR_EXIT_FAILURE;
    m.pixels = (size_t)mvr_view_set_count(m.vs) * o.scene.width * o.scene.height;
    bool has_blend = probe_scene(&o, m.ctx, m.scene, m.vs, configs, &m.count);
    char omitted[512] = "";
    leave_out_configs(m.ctx, has_blend, configs, &m.count, omitted, sizeof omitted);
    if (o.configs && !bench_select_configs(o.configs, configs, &m.count)) {
        rc = MVR_EXIT_USAGE;
        goto done;
    }
    size_t used = strlen(omitted);
    if (used && omitted[used - 1] != ' ')
        used += (size_t)snprintf(omitted + used, sizeof omitted - used, "; ");
    if (!bench_reference_plan(&o, m.vs, &chunks, omitted + used, sizeof omitted - used))
        goto done;
    for (size_t l = strlen(omitted); l >= 2 && strcmp(omitted + l - 2, "; ") == 0; l -= 2)
        omitted[l - 2] = 0; /* the parts end in "; " */
    o.reference_chunks = &chunks;
    if (o.only >= 0) { /* the callgrind child: one configuration's frames (of the same, filtered list) */
        if ((uint32_t)o.only < m.count)
            rc = run_config(&o, m.ctx, m.scene, m.vs, &configs[o.only], &results[0]) ? MVR_EXIT_OK
                                                                                     : MVR_EXIT_FAILURE;
        goto done;
    }
    rc = run_matrix(argc, argv, &o, &m, omitted);
done:
    for (uint32_t k = 0; k < m.count; ++k)
        free(results[k].display);
    bench_chunks_free(&chunks);
    mvr_view_set_destroy(m.vs);
    mvr_scene_destroy(m.scene);
    mvr_environment_destroy(env);
    mvr_context_destroy(m.ctx);
    camera_file_free(&o.cameras);
    return rc;
}
