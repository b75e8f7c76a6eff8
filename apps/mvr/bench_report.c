/* mvr bench reports: the terminal table, CSV, JSON, images and the plot. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"
#include "json.h"
#include "mvr/mvr_image.h"

static const char *fmt_gpu(double ms, char *buf, size_t size)
{
    if (ms < 0)
        snprintf(buf, size, "n/a");
    else
        snprintf(buf, size, "%.2f", ms);
    return buf;
}

void bench_print_table(const bench_run *run, FILE *out)
{
    fprintf(out, "mvr bench: %s, %u views of %ux%u, %u frames each, on %s\n", run->scene_name, run->views,
            run->width, run->height, run->frames, run->renderer);
    fprintf(out, "%-34s %-9s %9s %17s %8s %8s %8s %8s %7s %5s %7s %5s %6s %5s %6s\n", "configuration", "ran",
            "wall ms", "min..max", "cpu ms", "gpu ms", "Minstr", "RMSE", "PSNR", "max", ">2/255", "same", "draws",
            "calls", "binds");
    for (uint32_t k = 0; k < run->count; ++k) {
        const bench_config *c = &run->configs[k];
        const bench_result *r = &run->results[k];
        if (!r->ran) {
            fprintf(out, "%-34s skipped: %s\n", c->name, r->skipped);
            continue;
        }
        char gpu[16], minstr[16], psnr[16], range[48], same[16];
        if (r->instructions)
            snprintf(minstr, sizeof minstr, "%.1f", (double)r->instructions / 1e6);
        else
            snprintf(minstr, sizeof minstr, "-");
        if (isinf(r->psnr_db))
            snprintf(psnr, sizeof psnr, "inf");
        else
            snprintf(psnr, sizeof psnr, "%.1f", r->psnr_db);
        snprintf(range, sizeof range, "%.1f..%.1f", r->wall_min, r->wall_max);
        if (r->group_diff < 0)
            snprintf(same, sizeof same, "-");
        else
            snprintf(same, sizeof same, "%d", r->group_diff);
        fprintf(out, "%-33s%s %-9s %9.2f %17s %8.2f %8s %8s %8.5f %7s %5.0f %6.2f%% %5s %6u %5u %2u/%u/%u\n", c->name,
                r->pareto ? "*" : " ", r->view_path_ran, r->wall_median, range, r->cpu_median,
                fmt_gpu(r->gpu_median, gpu, sizeof gpu), minstr, r->rmse, psnr, r->max_abs, r->over_2, same, r->draws,
                r->draw_calls, r->program_binds, r->texture_binds, r->ubo_range_binds);
    }
    if (run->omitted[0])
        fprintf(out, "(%s)\n", run->omitted);
    fprintf(out, "* Pareto front (nothing else is both faster and closer to the reference). RMSE, PSNR, max\n"
                 "  (in 1/255 steps) and >2/255 are against the reference; \"same\" is the largest byte\n"
                 "  difference to the first configuration with the same anti-aliasing and transparency\n"
                 "  order (view and material paths must not change pixels: 0). binds: program/texture/\n"
                 "  uniform range per frame. Quote Minstr (--callgrind) for CPU cost: wall time on a\n"
                 "  shared machine varies by tens of percent.\n");
}

static const char *csv_header =
    "config,view_path,material_path,supersample,msaa,transparency_order,reference,ran,skipped,view_path_ran,"
    "wall_ms_median,wall_ms_min,wall_ms_max,cpu_ms_median,gpu_ms_median,instructions_per_frame,"
    "rmse,psnr_db,max_abs_255,pct_over_2_255,group,same_as_group_max_diff,draws,draw_calls,passes,"
    "program_binds,texture_binds,ubo_range_binds,pareto\n";

bool bench_write_csv(const bench_run *run, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "mvr bench: cannot write %s: %s\n", path, strerror(errno));
        return false;
    }
    fputs(csv_header, f);
    for (uint32_t k = 0; k < run->count; ++k) {
        const bench_config *c = &run->configs[k];
        const bench_result *r = &run->results[k];
        fprintf(f, "%s,%s,%s,%u,%u,%s,%d,%d,\"%s\",", c->name, mvr_view_path_name(c->view_path),
                mvr_material_path_name(c->material_path), c->supersample, c->msaa, mvr_transparency_order_name(c->order),
                c->reference, r->ran, r->skipped);
        if (!r->ran) {
            fprintf(f, ",,,,,,,,,,,%s,,,,,,,,0\n", c->group);
            continue;
        }
        char gpu[32] = "", instr[32] = "", psnr[32] = "inf";
        if (r->gpu_median >= 0)
            snprintf(gpu, sizeof gpu, "%.4f", r->gpu_median);
        if (r->instructions)
            snprintf(instr, sizeof instr, "%llu", (unsigned long long)r->instructions);
        if (!isinf(r->psnr_db))
            snprintf(psnr, sizeof psnr, "%.4f", r->psnr_db);
        fprintf(f, "%s,%.4f,%.4f,%.4f,%.4f,%s,%s,%.6f,%s,%.0f,%.4f,%s,%d,%u,%u,%u,%u,%u,%u,%d\n", r->view_path_ran,
                r->wall_median, r->wall_min, r->wall_max, r->cpu_median, gpu, instr, r->rmse, psnr, r->max_abs,
                r->over_2, c->group, r->group_diff, r->draws, r->draw_calls, r->passes, r->program_binds,
                r->texture_binds, r->ubo_range_binds, r->pareto);
    }
    bool ok = fclose(f) == 0;
    if (!ok)
        fprintf(stderr, "mvr bench: cannot write %s\n", path);
    return ok;
}

bool bench_write_json(const bench_run *run, const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "mvr bench: cannot write %s: %s\n", path, strerror(errno));
        return false;
    }
    json_writer jw = {f, 0, {false}, {0}};
    json_begin_object(&jw, NULL);
    json_string(&jw, "scene", run->scene_name);
    json_string(&jw, "command", run->command_line);
    json_string(&jw, "renderer", run->renderer);
    json_int(&jw, "views", run->views);
    json_int(&jw, "width", run->width);
    json_int(&jw, "height", run->height);
    json_int(&jw, "frames", run->frames);
    json_string(&jw, "omitted", run->omitted);
    json_begin_array(&jw, "configurations");
    for (uint32_t k = 0; k < run->count; ++k) {
        const bench_config *c = &run->configs[k];
        const bench_result *r = &run->results[k];
        json_begin_object(&jw, NULL);
        json_string(&jw, "config", c->name);
        json_string(&jw, "view_path", mvr_view_path_name(c->view_path));
        json_string(&jw, "material_path", mvr_material_path_name(c->material_path));
        json_int(&jw, "supersample", c->supersample);
        json_int(&jw, "msaa", c->msaa);
        json_string(&jw, "transparency_order", mvr_transparency_order_name(c->order));
        json_bool(&jw, "reference", c->reference);
        json_string(&jw, "group", c->group);
        json_bool(&jw, "ran", r->ran);
        if (!r->ran) {
            json_string(&jw, "skipped", r->skipped);
            json_end_object(&jw);
            continue;
        }
        json_string(&jw, "view_path_ran", r->view_path_ran);
        json_double(&jw, "wall_ms_median", r->wall_median);
        json_double(&jw, "wall_ms_min", r->wall_min);
        json_double(&jw, "wall_ms_max", r->wall_max);
        json_double(&jw, "cpu_ms_median", r->cpu_median);
        if (r->gpu_median >= 0)
            json_double(&jw, "gpu_ms_median", r->gpu_median);
        else
            json_null(&jw, "gpu_ms_median");
        if (r->instructions)
            json_int(&jw, "instructions_per_frame", (long long)r->instructions);
        else
            json_null(&jw, "instructions_per_frame");
        json_double(&jw, "rmse", r->rmse);
        if (isinf(r->psnr_db)) /* identical to the reference */
            json_null(&jw, "psnr_db");
        else
            json_double(&jw, "psnr_db", r->psnr_db);
        json_double(&jw, "max_abs_255", r->max_abs);
        json_double(&jw, "pct_over_2_255", r->over_2);
        json_int(&jw, "same_as_group_max_diff", r->group_diff);
        json_int(&jw, "draws", r->draws);
        json_int(&jw, "draw_calls", r->draw_calls);
        json_int(&jw, "passes", r->passes);
        json_int(&jw, "program_binds", r->program_binds);
        json_int(&jw, "texture_binds", r->texture_binds);
        json_int(&jw, "ubo_range_binds", r->ubo_range_binds);
        json_bool(&jw, "pareto", r->pareto);
        json_end_object(&jw);
    }
    json_end_array(&jw);
    json_end_object(&jw);
    fputc('\n', f);
    bool ok = fclose(f) == 0;
    if (!ok)
        fprintf(stderr, "mvr bench: cannot write %s\n", path);
    return ok;
}

/* The views side by side, as one image (rows top-down, as read). */
static bool write_strip(const char *path, const uint8_t *views, uint32_t n, uint32_t w, uint32_t h)
{
    uint8_t *strip = malloc((size_t)n * w * h * 4);
    if (!strip)
        return false;
    for (uint32_t k = 0; k < n; ++k)
        for (uint32_t y = 0; y < h; ++y)
            memcpy(strip + ((size_t)y * n * w + (size_t)k * w) * 4, views + (((size_t)k * h + y) * w) * 4,
                   (size_t)w * 4);
    mvr_image_view view = {n * w, h, MVR_PIXEL_U8, true, strip};
    mvr_error err;
    bool ok = mvr_image_write(path, &view, &err) == MVR_OK;
    if (!ok)
        fprintf(stderr, "mvr bench: %s\n", err.message);
    free(strip);
    return ok;
}

bool bench_write_images(const bench_run *run)
{
    const bench_result *ref = &run->results[run->reference];
    if (!ref->ran)
        return false;
    char path[4096];
    snprintf(path, sizeof path, "%s/reference.png", run->out_dir);
    bool ok = write_strip(path, ref->display, run->views, run->width, run->height);
    /* the worst configuration by RMSE: its difference, x8 and clamped */
    int worst = -1;
    for (uint32_t k = 0; k < run->count; ++k)
        if (k != run->reference && run->results[k].ran && (worst < 0 || run->results[k].rmse > run->results[worst].rmse))
            worst = (int)k;
    if (worst < 0)
        return ok;
    size_t pixels = (size_t)run->views * run->width * run->height;
    uint8_t *diff = malloc(pixels * 4);
    if (!diff)
        return false;
    const uint8_t *img = run->results[worst].display;
    for (size_t i = 0; i < pixels; ++i) {
        for (size_t c = 0; c < 3; ++c) {
            int d = abs((int)img[i * 4 + c] - (int)ref->display[i * 4 + c]) * 8;
            diff[i * 4 + c] = (uint8_t)(d > 255 ? 255 : d);
        }
        diff[i * 4 + 3] = 255;
    }
    snprintf(path, sizeof path, "%s/worst_diff.png", run->out_dir);
    ok = write_strip(path, diff, run->views, run->width, run->height) && ok;
    free(diff);
    return ok;
}

bool bench_plot(const bench_run *run)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/plot.gp", run->out_dir);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "mvr bench: cannot write %s: %s\n", path, strerror(errno));
        return false;
    }
    /* columns of results.csv: 1 config, 8 ran, 11 wall ms median, 17 rmse */
    fprintf(f,
            "# mvr bench: median frame time against RMSE to the reference (from results.csv;\n"
            "# pareto.dat holds the front, sorted by time)\n"
            "set datafile separator ','\n"
            "set key top right\n"
            "set title '%s, %u views of %ux%u on %s'\n"
            "set xlabel 'median frame time (ms, wall)'\n"
            "set ylabel 'RMSE to the reference (0..1)'\n"
            "set grid\n"
            "set xrange [0:*]\n"
            "set yrange [0:*]\n"
            "set offsets 0, graph 0.2, graph 0.1, 0\n"
            "set style line 1 pt 7 ps 1.2 lc rgb '#3060c0'\n"
            "set style line 2 pt 6 ps 2.2 lw 2 lc rgb '#d04020'\n"
            "ran(c) = (column(8) == 1 ? c : 1/0)\n"
            "plot_it = \"plot 'results.csv' skip 1 using (ran($11)):(ran($17)) with points ls 1 title 'configuration', "
            "'pareto.dat' using 2:3 with linespoints ls 2 title 'Pareto front', "
            "'pareto.dat' using 2:3:1 with labels offset 1,0.8 left font ',9' notitle\"\n"
            "set terminal png size 1000,700 noenhanced\n" /* underscores in names are not subscripts */
            "set output 'plot.png'\n"
            "eval plot_it\n"
            "set terminal svg size 1000,700 noenhanced\n"
            "set output 'plot.svg'\n"
            "eval plot_it\n",
            run->scene_name, run->views, run->width, run->height, run->renderer);
    fclose(f);
    /* the front, by time: name, wall ms, rmse */
    snprintf(path, sizeof path, "%s/pareto.dat", run->out_dir);
    f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "mvr bench: cannot write %s: %s\n", path, strerror(errno));
        return false;
    }
    bool *done = calloc(run->count, sizeof *done);
    for (uint32_t i = 0; done && i < run->count; ++i) {
        int next = -1;
        for (uint32_t k = 0; k < run->count; ++k)
            if (run->results[k].ran && run->results[k].pareto && !done[k] &&
                (next < 0 || run->results[k].wall_median < run->results[next].wall_median))
                next = (int)k;
        if (next < 0)
            break;
        done[next] = true;
        fprintf(f, "%s,%.4f,%.6f\n", run->configs[next].name, run->results[next].wall_median,
                run->results[next].rmse);
    }
    free(done);
    fclose(f);
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        if (chdir(run->out_dir) != 0)
            _exit(126);
        freopen("/dev/null", "w", stdout);
        execlp("gnuplot", "gnuplot", "plot.gp", (char *)NULL);
        _exit(127);
    }
    int status = 0;
    bool ok = pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (!ok)
        fprintf(stderr, "mvr bench: gnuplot failed (status %d; is gnuplot installed? scripts/setup installs it); "
                        "%s is left for a rerun\n", status, path);
    return ok;
}
