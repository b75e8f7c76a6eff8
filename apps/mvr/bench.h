/* mvr bench: configurations, their measurements, and the reports. */
#ifndef MVR_APP_BENCH_H
#define MVR_APP_BENCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#include "camera_file.h"
#include "cli_env.h"
#include "cli_scene.h"
#include "mvr/mvr.h"

typedef struct bench_chunks bench_chunks;

typedef struct bench_options {
    mvr_context_desc context;
    cli_scene_options scene;
    uint32_t frames, warmup;
    uint32_t rounds;             /* --rounds: the frames are taken in this many rounds over all configurations */
    bool full;
    const char *out_dir;
    bool callgrind;
    int only;                    /* internal: run one configuration (the callgrind child) */
    const char *configs;         /* --configs: the names to run (comma-separated), NULL = the whole matrix */
    bool quiet;
    /* --env-axes */
    bool env_axes;
    cli_env_options env;
    const char *env_option;              /* the last option only --env-axes takes, if any */
    bool demo_set, frames_set, warmup_set, matrix_set, size_set;
    const char *cameras_file;            /* --cameras: its views (scene.given_views) */
    bool camera_set, layout_set;         /* --camera K, --layout L (scene.camera, scene.layout) */
    const char *program_cache;           /* --program-cache: NULL = the user's cache folder; "off" */
    char program_cache_buf[4096];
    const char *program_cache_dir;       /* resolved (cli_program_cache_dir); NULL = none */
    uint64_t reference_memory;           /* --reference-memory: bytes of the reference target at once */
    const struct bench_chunks *reference_chunks; /* the reference's plan (bench_reference.c); NULL = 4x4 at once */
    camera_file cameras;
    uint32_t sizes[8], n_sizes;          /* --specular-sizes */
    uint32_t samples[8], n_samples;      /* --specular-samples */
    uint32_t reference_samples;          /* --reference-samples */
    /* the MVR_* variables (mvr_renderer_overrides_from_env), in every renderer desc */
    mvr_renderer_overrides overrides;
    /* a scene with animations: every frame poses it anew (all animations,
     * alternately at their start and their middle), so skinning and morph
     * work is redone each frame as in playback */
    bool animate;
    double pose_times[2];
    /* the frame matrix's render settings: the environment mvr render would
     * take (--env, default neutral for a glTF file, none for a demo) */
    mvr_render_desc render;
} bench_options;

/* bench_options.c: argv (after "bench") into o, checked: MVR_EXIT_OK, -1
 * after --help (printed: nothing to run), or a usage error's exit code
 * (printed); o->cameras is freed by the caller either way. */
int bench_options_parse(int argc, char **argv, bench_options *o);

/* "mvr bench ..." as given, for the reports. */
void bench_command_line(int argc, char **argv, char *buf, size_t size);

#define BENCH_MAX_CONFIGS 80

typedef struct bench_config {
    char name[48];
    mvr_view_path view_path;
    mvr_material_path material_path;
    uint32_t supersample;        /* samples per pixel side (1 = none) */
    uint32_t msaa;               /* multisamples per pixel (0 = none) */
    mvr_transparency_order order;
    mvr_skinning_path skinning_path; /* AUTO except on the skinning axis (scenes with skins or morphs) */
    uint32_t disable_features;   /* material extensions drawn as absent (overrides.disable_features) */
    bool skinning_axis;          /* one of the skinning axis's configurations */
    bool reference;
    /* Configurations of one group must give the same pixels (they differ
     * only in view or material path): the report checks it. */
    char group[32];
    /* --env-axes: the environment's prefilter (mvr_environment_desc's
     * specular_size and specular_samples); 0 on the frame axes */
    uint32_t specular_size, specular_samples;
    bool converged;              /* --env-axes: the maps at the largest size and 4096 samples */
} bench_config;

/* --configs LIST: keeps the reference and the named configurations, in the
 * matrix's order; false (printing the names the matrix has) when a name is
 * not in it (bench_options.c). */
bool bench_select_configs(const char *list, bench_config *configs, uint32_t *count);

typedef struct bench_result {
    bool ran;
    char skipped[160];           /* why not, when !ran */
    double wall_median, wall_min, wall_max; /* ms per frame: render + finish */
    double wall_q1, wall_q3;     /* its quartiles: the interquartile range is the noise the front allows */
    double cpu_median;           /* ms of the submitting thread */
    double gpu_median;           /* ms from timer queries; < 0 where there are none */
    uint64_t instructions;       /* per frame, submitting thread (--callgrind); 0 = not measured */
    /* error against the reference, over every view, RGB of the display bytes */
    double rmse;                 /* in 0..1 units */
    double psnr_db;              /* INFINITY when identical */
    double max_abs;              /* in 1/255 steps */
    double over_2;               /* % of pixels with a channel more than 2/255 off */
    int group_diff;              /* max byte difference to its group's first configuration; -1: it is the first */
    const char *view_path_ran;
    const char *material_path_ran;
    uint32_t draws, draw_calls, passes, program_binds, texture_binds, ubo_range_binds;
    bool pareto;                 /* no other is both faster and more accurate (--env-axes: the
                                    prefilter's median time is the time; the reference is left out) */
    /* --env-axes: env_prefilter_ms of the first frame with a fresh
     * environment (ms, over the repeats), its passes, and whether its pixels
     * are those of the library's default prefilter (the environment
     * mvr render would make: specular fields 0) */
    double prefilter_median, prefilter_min, prefilter_max;
    uint32_t prefilter_passes;
    bool library_default;
    /* --env-axes: the error against the converged maps instead (the
     * prefilter's own error, without the split sum's and the spherical
     * harmonics'), and the Pareto front over it */
    double maps_rmse, maps_psnr_db, maps_max_abs;
    bool maps_pareto;
    uint8_t *display;            /* views x w x h x RGBA8, sRGB-encoded */
    /* view path auto: what its tuner measured and chose (measured frames
     * start once it settled), and the frames that took */
    mvr_auto_choice auto_choice;
    mvr_auto_skinning_choice auto_skinning;
    mvr_auto_material_choice auto_material;
    uint32_t tuning_frames;
} bench_result;

typedef struct bench_run {
    const char *scene_name;
    const char *out_dir;
    const char *command_line;
    const char *renderer;        /* GL_RENDERER */
    uint32_t views, width, height, frames; /* --env-axes: frames = prefilter repeats per configuration */
    uint32_t count;
    bench_config *configs;
    bench_result *results;
    uint32_t reference;          /* index of the reference */
    const char *omitted;         /* configurations left out, and why ("" = none) */
    /* --env-axes: the environment prefilter axes instead of the frame
     * matrix. Errors are over the pixels the scene covers (the reference's
     * alpha > 0), compared_pixels of them, every view. */
    bool env_axes;
    const char *environment;     /* neutral | uniform | the image's path */
    uint32_t reference_samples;  /* the reference's mvr_render_desc.environment_samples */
    uint64_t compared_pixels;
    uint32_t rounds;             /* the frames were taken in this many interleaved rounds (frame axes) */
} bench_run;

/* bench_report.c: the terminal table, results.csv / results.json, the
 * reference and worst-difference images, and the gnuplot plot. Each returns
 * false after printing what failed. */
void bench_print_table(const bench_run *run, FILE *out);
bool bench_write_csv(const bench_run *run, const char *path);
bool bench_write_json(const bench_run *run, const char *path);
bool bench_write_images(const bench_run *run);
/* Writes plot.gp and runs gnuplot for plot.png and plot.svg (--env-axes:
 * plot_env.gp, plot_env.png and plot_env.svg, prefilter time against error);
 * false (with a message) when gnuplot is missing or fails. */
bool bench_plot(const bench_run *run);
/* All of the above: the table on stdout and every file into run->out_dir;
 * false when any failed (each says why). */
bool bench_write_reports(const bench_run *run);
/* An auto configuration against the forced paths of the same configuration
 * (the same material path, anti-aliasing, order and features; auto material
 * against both material paths; on the skinning axis, auto skinning against
 * both skinning paths): the best of
 * them, and the one auto settled on (the same work as auto's). A fraction
 * "above" is 0 within the noise (the slower one's q1 at most the faster's
 * q3). */
typedef struct bench_auto_verdict {
    uint32_t best;               /* the fastest forced configuration */
    double excess;               /* auto's median above the best's */
    bool chosen_found;           /* a forced configuration of what auto settled on ran */
    uint32_t chosen;
    double choice_excess;        /* the chosen forced configuration above the best: what the choice costs */
    double same_work;            /* auto's median against the chosen's - 1 (identical work measured
                                    twice: the noise of this run), signed */
} bench_auto_verdict;
/* false when k is not an auto configuration with forced ones beside it */
bool bench_auto_excess(const bench_run *run, uint32_t k, bench_auto_verdict *v);


/* cmd_bench.c, shared with bench_env.c */
double bench_now_ms(clockid_t clock);
double bench_median(double *v, uint32_t n); /* sorts v */
/* RMSE, PSNR, max and % over 2/255 of img against ref (RGBA8), over every
 * pixel or (covered) only those the reference covers (alpha > 0); returns
 * the pixels compared. */
size_t bench_compare(const uint8_t *ref, const uint8_t *img, size_t pixels, bool covered, bench_result *res);
void bench_progress(const bench_options *o, uint32_t done, uint32_t total, const char *what);
/* What a result keeps of a frame's stats: the paths that ran, draws and binds. */
void bench_take_stats(bench_result *res, const mvr_frame_stats *st);

/* bench_reference.c: the reference's views in chunks whose supersampled
 * target fits o->reference_memory (count 0: all at once), at supersample
 * x supersample samples per pixel (4, less where one view at 4x4 does not
 * fit). */
struct bench_chunks {
    mvr_view_set **sets;         /* count view sets of per_chunk views (the last fewer) */
    uint32_t count, per_chunk;
    uint32_t supersample;
};
/* Plans the reference for vs; note (appended to the report's omissions)
 * says what differs from one 4x4 target; false (printed) when out of memory. */
bool bench_reference_plan(const bench_options *o, mvr_view_set *vs, bench_chunks *out, char *note, size_t note_size);
void bench_chunks_free(bench_chunks *c);
/* One frame of every view: vs at once, or chunk after chunk (chunks NULL or empty: at once). */
mvr_result bench_render_views(mvr_renderer *r, mvr_scene *s, mvr_view_set *vs, const bench_chunks *chunks,
                              mvr_target *t, const mvr_render_desc *desc);
/* Every view's display bytes (views x w x h x RGBA8) from the target:
 * chunk by chunk, each drawn again first. */
bool bench_read_views(mvr_renderer *r, mvr_scene *s, mvr_view_set *vs, const bench_chunks *chunks, mvr_target *t,
                      const mvr_render_desc *desc, uint32_t w, uint32_t h, uint32_t ss, uint8_t *display);

/* bench_env.c: mvr bench --env-axes (after the options are parsed and the context made). */
int bench_run_env_axes(int argc, char **argv, const bench_options *o, mvr_context *ctx);

#endif
