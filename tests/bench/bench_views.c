/*
 * bench_views: frame time of a demo (default: city) with 1, 2, 4 and 6 views
 * on the multiview and loop paths, and on auto (the column "ran" says which
 * path auto took). Not a test: it asserts nothing and prints
 * a table. Run through tests/bench/run_bench_views.sh, which also counts the
 * submitting thread's instructions with callgrind (--toggle-collect on
 * measured_frames, so compiles, uploads and the driver's worker threads are
 * left out): those counts repeat to < 1% on a shared machine, wall time does not.
 *
 * usage: bench_views [--demo NAME] [--size WxH] [--frames N] [--only VIEWS:PATH]
 *                    [--views 1,2,4,6] [--material-path arrays|per_material|per_draw]
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "mvr/mvr.h"

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

static double now_ms(clockid_t clock)
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

typedef struct frame_times {
    double wall[256], cpu[256];
} frame_times;

/* The frames callgrind counts.
 * Each frame waits for its GPU timer result, so the GPU work is inside it. */
__attribute__((noinline)) void measured_frames(mvr_renderer *r, mvr_scene *s, mvr_view_set *v, mvr_target *t,
                                               int frames, frame_times *out)
{
    CALLGRIND_START_INSTRUMENTATION;
    CALLGRIND_TOGGLE_COLLECT;
    for (int f = 0; f < frames; ++f) {
        double w0 = now_ms(CLOCK_MONOTONIC), c0 = now_ms(CLOCK_THREAD_CPUTIME_ID);
        mvr_renderer_render(r, s, v, t, NULL);
        mvr_frame_stats st;
        mvr_renderer_get_stats(r, &st); /* waits for the GPU timer = the frame's end */
        out->wall[f] = now_ms(CLOCK_MONOTONIC) - w0;
        out->cpu[f] = now_ms(CLOCK_THREAD_CPUTIME_ID) - c0;
    }
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_STOP_INSTRUMENTATION;
}

int main(int argc, char **argv)
{
    const char *demo = "city";
    uint32_t w = 640, h = 480;
    int frames = 20;
    const char *only = NULL;
    const char *views_list = "1,2,4,6";
    mvr_material_path material_path = MVR_MATERIAL_PATH_ARRAYS;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--demo") == 0)
            demo = argv[i + 1];
        else if (strcmp(argv[i], "--size") == 0)
            sscanf(argv[i + 1], "%ux%u", &w, &h);
        else if (strcmp(argv[i], "--frames") == 0)
            frames = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--only") == 0)
            only = argv[i + 1];
        else if (strcmp(argv[i], "--views") == 0)
            views_list = argv[i + 1];
        else if (strcmp(argv[i], "--material-path") == 0)
            for (int k = MVR_MATERIAL_PATH_ARRAYS; k <= MVR_MATERIAL_PATH_PER_DRAW; ++k)
                if (strcmp(argv[i + 1], mvr_material_path_name((mvr_material_path)k)) == 0)
                    material_path = (mvr_material_path)k;
    }
    if (frames < 1 || frames > 256)
        frames = 20;
    mvr_context *ctx = NULL;
    mvr_error err;
    if (mvr_context_create(NULL, &ctx, &err) != MVR_OK) {
        fprintf(stderr, "bench_views: %s\n", err.message);
        return 1;
    }
    const mvr_caps *c = mvr_context_caps(ctx);
    printf("# %s, %ux%u, %d frames after 3 warm-up, material path %s, %s\n", demo, w, h, frames,
           mvr_material_path_name(material_path), c->renderer);
    printf("%-6s %-10s %-10s %6s %6s %7s %10s %10s %10s %10s\n", "views", "path", "ran", "passes", "draws", "tbinds",
           "wall_med", "wall_min", "cpu_med", "cpu_min");
    uint32_t counts[16], ncounts = 0;
    for (const char *p = views_list; *p && ncounts < 16;) {
        counts[ncounts++] = (uint32_t)strtoul(p, (char **)&p, 10);
        if (*p == ',')
            ++p;
        else
            break;
    }
    static const mvr_view_path paths[] = {MVR_VIEW_PATH_MULTIVIEW, MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_AUTO};
    for (size_t p = 0; p < 3; ++p)
        for (size_t k = 0; k < ncounts; ++k) {
            char tag[32];
            snprintf(tag, sizeof tag, "%u:%s", counts[k], mvr_view_path_name(paths[p]));
            if (only && strcmp(only, tag) != 0)
                continue;
            if (paths[p] == MVR_VIEW_PATH_MULTIVIEW && !c->ext.ovr_multiview2)
                continue;
            mvr_scene *scene = NULL;
            mvr_view_set *views = NULL;
            mvr_renderer *r = NULL;
            mvr_target *t = NULL;
            mvr_demo_desc dd = {counts[k], w, h, {0}};
            mvr_renderer_desc rd = {.context = ctx, .view_path = paths[p], .material_path = material_path};
            mvr_target_desc td = {w, h, counts[k], MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
            if (mvr_demo_create(demo, &dd, &scene, &views, &err) != MVR_OK ||
                mvr_renderer_create(&rd, &r, &err) != MVR_OK || mvr_target_create(r, &td, &t) != MVR_OK) {
                fprintf(stderr, "bench_views: %s\n", err.message);
                return 1;
            }
            frame_times times;
            for (int f = 0; f < 3; ++f) /* compile, upload, fill the ring */
                mvr_renderer_render(r, scene, views, t, NULL);
            mvr_frame_stats st;
            mvr_renderer_get_stats(r, &st);
            measured_frames(r, scene, views, t, frames, &times);
            mvr_renderer_get_stats(r, &st);
            qsort(times.wall, (size_t)frames, sizeof(double), compare_double);
            qsort(times.cpu, (size_t)frames, sizeof(double), compare_double);
            printf("%-6u %-10s %-10s %6u %6u %7u %10.2f %10.2f %10.2f %10.2f\n", counts[k],
                   mvr_view_path_name(paths[p]), mvr_view_path_name(st.view_path), st.passes, st.draws, st.texture_binds, times.wall[frames / 2], times.wall[0], times.cpu[frames / 2],
                   times.cpu[0]);
            fflush(stdout);
            mvr_target_destroy(t);
            mvr_renderer_destroy(r);
            mvr_view_set_destroy(views);
            mvr_scene_destroy(scene);
        }
    mvr_context_destroy(ctx);
    return 0;
}
