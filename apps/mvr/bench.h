/* mvr bench: configurations, their measurements, and the reports. */
#ifndef MVR_APP_BENCH_H
#define MVR_APP_BENCH_H

#include <stdbool.h>
#include <stdint.h>

#include "mvr/mvr.h"

typedef struct bench_config {
    char name[48];
    mvr_view_path view_path;
    mvr_material_path material_path;
    uint32_t supersample;        /* samples per pixel side (1 = none) */
    uint32_t msaa;               /* multisamples per pixel (0 = none) */
    mvr_transparency_order order;
    bool reference;
    /* Configurations of one group must give the same pixels (they differ
     * only in view or material path): the report checks it. */
    char group[32];
} bench_config;

typedef struct bench_result {
    bool ran;
    char skipped[160];           /* why not, when !ran */
    double wall_median, wall_min, wall_max; /* ms per frame: render + finish */
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
    bool pareto;                 /* no other is both faster and more accurate */
    uint8_t *display;            /* views x w x h x RGBA8, sRGB-encoded */
} bench_result;

typedef struct bench_run {
    const char *scene_name;
    const char *out_dir;
    const char *command_line;
    const char *renderer;        /* GL_RENDERER */
    uint32_t views, width, height, frames;
    uint32_t count;
    bench_config *configs;
    bench_result *results;
    uint32_t reference;          /* index of the reference */
    const char *omitted;         /* configurations left out, and why ("" = none) */
} bench_run;

/* bench_report.c: the terminal table, results.csv / results.json, the
 * reference and worst-difference images, and the gnuplot plot. Each returns
 * false after printing what failed. */
void bench_print_table(const bench_run *run, FILE *out);
bool bench_write_csv(const bench_run *run, const char *path);
bool bench_write_json(const bench_run *run, const char *path);
bool bench_write_images(const bench_run *run);
/* Writes plot.gp and runs gnuplot for plot.png and plot.svg; false (with a
 * message) when gnuplot is missing or fails. */
bool bench_plot(const bench_run *run);

#endif
