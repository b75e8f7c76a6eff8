/* mvr bench reports: the terminal table, CSV, JSON, images and the plot. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"
#include "cli_write.h"
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

/* --env-axes: the prefilter's time against the error. */
static void print_env_table(const bench_run *run, FILE *out)
{
    fprintf(out, "mvr bench --env-axes: %s under %s, %u views of %ux%u, prefilter timed %u times each, on %s\n",
            run->scene_name, run->environment, run->views, run->width, run->height, run->frames, run->renderer);
    fprintf(out, "%-28s %5s %7s %10s %15s %6s %9s %8s %6s %4s %7s %9s %5s\n", "configuration", "size", "samples",
            "prefilter", "min..max", "passes", "1st frame", "RMSE", "PSNR", "max", ">2/255", "maps RMSE", "max");
    for (uint32_t k = 0; k < run->count; ++k) {
        const bench_config *c = &run->configs[k];
        const bench_result *r = &run->results[k];
        if (!r->ran) {
            fprintf(out, "%-28s skipped: %s\n", c->name, r->skipped);
            continue;
        }
        char psnr[16], range[48], name[64];
        if (isinf(r->psnr_db))
            snprintf(psnr, sizeof psnr, "inf");
        else
            snprintf(psnr, sizeof psnr, "%.1f", r->psnr_db);
        snprintf(range, sizeof range, "%.1f..%.1f", r->prefilter_min, r->prefilter_max);
        snprintf(name, sizeof name, "%s%s%s%s", c->name, r->pareto ? "*" : "", r->maps_pareto ? "+" : "",
                 r->library_default ? " default" : "");
        fprintf(out, "%-28s %5u %7u %10.1f %15s %6u %9.1f %8.5f %6s %4.0f %6.2f%% %9.5f %5.0f\n", name,
                c->specular_size, c->specular_samples, r->prefilter_median, range, r->prefilter_passes,
                r->wall_median, r->rmse, psnr, r->max_abs, r->over_2, r->maps_rmse, r->maps_max_abs);
    }
    fprintf(out, "prefilter: median env_prefilter_ms of the first frame with a fresh environment (ms); 1st frame:\n"
                 "  that frame's wall ms. RMSE (0..1), PSNR, max (1/255 steps) and >2/255 are against the\n"
                 "  reference (the environment integrated per pixel, environment_samples %u, loop path), over\n"
                 "  the %llu pixels the scene covers (every view), neither side anti-aliased; maps RMSE and\n"
                 "  max against the converged maps instead (the prefilter's own error). The reference and the\n"
                 "  converged maps ran once, programs compiled in that frame. * Pareto front over (prefilter\n"
                 "  time, RMSE), + over (prefilter time, maps RMSE); default: the same pixels as the library's\n"
                 "  default prefilter.\n",
            run->reference_samples, (unsigned long long)run->compared_pixels);
}

/* Whether forced configuration c is one auto configuration a is compared with. */
static bool comparable(const bench_config *a, const bench_config *c)
{
    if (c->view_path == MVR_VIEW_PATH_AUTO || c->reference || c->material_path == MVR_MATERIAL_PATH_AUTO ||
        c->material_path == MVR_MATERIAL_PATH_PER_DRAW ||
        (a->material_path != MVR_MATERIAL_PATH_AUTO && c->material_path != a->material_path) ||
        c->supersample != a->supersample || c->msaa != a->msaa || c->order != a->order ||
        c->disable_features != a->disable_features || c->skinning_axis != a->skinning_axis)
        return false;
    /* auto skinning on the skinning axis: against both forced skinning paths */
    if (a->skinning_axis && a->skinning_path == MVR_SKINNING_PATH_AUTO)
        return c->skinning_path != MVR_SKINNING_PATH_AUTO;
    return c->skinning_path == a->skinning_path;
}

/* The fraction slower's median is above faster's, 0 within the noise. */
static double above(const bench_result *slower, const bench_result *faster)
{
    return slower->wall_q1 <= faster->wall_q3 ? 0.0 : slower->wall_median / faster->wall_median - 1.0;
}

bool bench_auto_excess(const bench_run *run, uint32_t k, bench_auto_verdict *v)
{
    const bench_config *a = &run->configs[k];
    const bench_result *ra = &run->results[k];
    memset(v, 0, sizeof *v);
    if (a->view_path != MVR_VIEW_PATH_AUTO || !ra->ran || a->reference)
        return false;
    /* what auto settled on: its view path (the rule's where not tuned), and
     * its skinning path where that was auto too */
    const mvr_auto_choice *ac = &ra->auto_choice;
    mvr_view_path view = ac->state == MVR_AUTO_SETTLED ? ac->chosen : ac->prior;
    mvr_skinning_path skin = a->skinning_path;
    if (a->skinning_axis && skin == MVR_SKINNING_PATH_AUTO)
        skin = ra->auto_skinning.state == MVR_AUTO_SETTLED ? ra->auto_skinning.chosen : ra->auto_skinning.prior;
    mvr_material_path material = a->material_path;
    if (material == MVR_MATERIAL_PATH_AUTO)
        material = ra->auto_material.state == MVR_AUTO_SETTLED ? ra->auto_material.chosen : ra->auto_material.prior;
    bool found = false;
    for (uint32_t i = 0; i < run->count; ++i) {
        const bench_config *c = &run->configs[i];
        if (i == k || !run->results[i].ran || !comparable(a, c))
            continue;
        if (!found || run->results[i].wall_median < run->results[v->best].wall_median)
            v->best = i;
        found = true;
        if (c->view_path == view && c->skinning_path == skin && c->material_path == material) {
            v->chosen_found = true;
            v->chosen = i;
        }
    }
    if (!found)
        return false;
    const bench_result *rb = &run->results[v->best];
    v->excess = above(ra, rb);
    if (v->chosen_found) {
        const bench_result *rc = &run->results[v->chosen];
        v->choice_excess = above(rc, rb);
        v->same_work = ra->wall_median / rc->wall_median - 1.0;
    }
    return true;
}

/* Each auto configuration: what its tuners measured, and how far it is from
 * the best forced path; then the worst over the matrix, of auto's own frames
 * and of its choice (the forced configuration of the path it settled on). */
static void print_auto_lines(const bench_run *run, FILE *out)
{
    double worst = -1.0, worst_choice = -1.0, noise = 0.0;
    uint32_t worst_k = 0, worst_choice_k = 0;
    for (uint32_t k = 0; k < run->count; ++k) {
        bench_auto_verdict v;
        if (!bench_auto_excess(run, k, &v))
            continue;
        const bench_result *r = &run->results[k];
        const mvr_auto_choice *a = &r->auto_choice;
        if (a->state == MVR_AUTO_SETTLED)
            fprintf(out, "auto %s: settled in %u frames on %s (tuner: multiview %.2f, loop %.2f ms; prior %s, margin %.0f%%)",
                    run->configs[k].name, r->tuning_frames, mvr_view_path_name(a->chosen), a->cost_ms[0], a->cost_ms[1],
                    mvr_view_path_name(a->prior), 100.0 * a->margin);
        else
            fprintf(out, "auto %s: %s (%s)", run->configs[k].name, mvr_auto_state_name(a->state),
                    a->state == MVR_AUTO_RULE ? "tuning off: the caps rule" : "one path works here");
        const mvr_auto_material_choice *m = &r->auto_material;
        if (m->state == MVR_AUTO_SETTLED)
            fprintf(out, "; material settled on %s (per_material %.2f, arrays %.2f ms)",
                    mvr_material_path_name(m->chosen), m->cost_ms[0], m->cost_ms[1]);
        const mvr_auto_skinning_choice *s = &r->auto_skinning;
        if (s->state == MVR_AUTO_SETTLED)
            fprintf(out, "; skinning settled on %s (vertex %.2f, preskin %.2f ms; prior %s)",
                    mvr_skinning_path_name(s->chosen), s->cost_ms[0], s->cost_ms[1], mvr_skinning_path_name(s->prior));
        char verdict[64];
        if (v.excess > 0.0)
            snprintf(verdict, sizeof verdict, "%.1f%% slower beyond the noise", 100.0 * v.excess);
        else
            snprintf(verdict, sizeof verdict, "within the noise");
        fprintf(out, "; %.2f ms against %s's %.2f: %s", r->wall_median, run->configs[v.best].name,
                run->results[v.best].wall_median, verdict);
        if (v.chosen_found && v.chosen != v.best)
            fprintf(out, "; its choice %s %.2f ms (%s), auto's run of that %+.1f%%", run->configs[v.chosen].name,
                    run->results[v.chosen].wall_median,
                    v.choice_excess > 0.0 ? "slower beyond the noise" : "within the noise", 100.0 * v.same_work);
        fputc('\n', out);
        if (v.excess > worst) {
            worst = v.excess;
            worst_k = k;
        }
        double choice = v.chosen_found ? v.choice_excess : v.excess;
        if (choice > worst_choice) {
            worst_choice = choice;
            worst_choice_k = k;
        }
        if (v.chosen_found && fabs(v.same_work) > noise)
            noise = fabs(v.same_work);
    }
    if (worst < 0.0)
        return;
    fprintf(out, "auto against the best forced path over the matrix: %s (worst: %s, +%.1f%% beyond the noise; "
                 "target at most 5%%)\n",
            worst <= 0.05 ? "within 5%" : "MORE than 5% slower", run->configs[worst_k].name, 100.0 * worst);
    fprintf(out, "auto's choice (the forced path it settled on) against the best: %s (worst: %s, +%.1f%%); "
                 "auto against its own choice forced, the same work: up to %.1f%% apart in this run\n",
            worst_choice <= 0.05 ? "within 5%" : "MORE than 5% slower", run->configs[worst_choice_k].name,
            100.0 * worst_choice, 100.0 * noise);
}

void bench_print_table(const bench_run *run, FILE *out)
{
    if (run->env_axes) {
        print_env_table(run, out);
        return;
    }
    fprintf(out, "mvr bench: %s, %u views of %ux%u, %u frames each in %u interleaved rounds, on %s\n",
            run->scene_name, run->views, run->width, run->height, run->frames, run->rounds, run->renderer);
    fprintf(out, "%-34s %-9s %9s %17s %8s %8s %8s %8s %7s %5s %7s %5s %6s %5s %6s\n", "configuration", "ran",
            "wall ms", "q1..q3", "cpu ms", "gpu ms", "Minstr", "RMSE", "PSNR", "max", ">2/255", "same", "draws",
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
        snprintf(range, sizeof range, "%.1f..%.1f", r->wall_q1, r->wall_q3);
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
    print_auto_lines(run, out);
    fprintf(out, "wall ms: the median frame, q1..q3 its interquartile range (the noise), over frames taken in\n"
                 "  rounds that visit every configuration in turn (so a load change hits all of them).\n"
                 "* Pareto front: nothing else is at least as close to the reference and faster by more than\n"
                 "  the noise (its q3 below this one's q1), or closer and not slower beyond the noise (its\n"
                 "  median at most this one's q3). worst_diff_x8_<configuration>.png: |image - reference| x 8\n"
                 "  of the configuration farthest from the reference, clamped at 255. RMSE, PSNR, max\n"
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
    "program_binds,texture_binds,ubo_range_binds,pareto,"
    "axis,specular_size,specular_samples,reference_env_samples,prefilter_ms_median,prefilter_ms_min,"
    "prefilter_ms_max,prefilter_passes,library_default,maps_rmse,maps_psnr_db,maps_max_abs_255,maps_pareto,"
    "wall_ms_q1,wall_ms_q3\n";

/* The environment axes' columns (empty on the frame axes), the frame
 * time's quartiles (empty on the environment axes), and the line's end. */
static void csv_env_columns(FILE *f, const bench_run *run, const bench_config *c, const bench_result *r)
{
    if (!run->env_axes) {
        if (r->ran)
            fprintf(f, ",frame,,,,,,,,,,,,,%.4f,%.4f\n", r->wall_q1, r->wall_q3);
        else
            fprintf(f, ",frame,,,,,,,,,,,,,,\n");
        return;
    }
    fprintf(f, ",environment,%u,%u,%u,", c->specular_size, c->specular_samples, run->reference_samples);
    if (!r->ran) {
        fprintf(f, ",,,,0,,,,0,,\n");
        return;
    }
    char psnr[32] = "inf";
    if (!isinf(r->maps_psnr_db))
        snprintf(psnr, sizeof psnr, "%.4f", r->maps_psnr_db);
    fprintf(f, "%.4f,%.4f,%.4f,%u,%d,%.6f,%s,%.0f,%d,,\n", r->prefilter_median, r->prefilter_min, r->prefilter_max,
            r->prefilter_passes, r->library_default, r->maps_rmse, psnr, r->maps_max_abs, r->maps_pareto);
}

/* Opens a report file (cli_write.h: every write checked, renamed into
 * place whole); NULL, printed, when it cannot be. */
static FILE *report_open(cli_write_file *out, const char *path)
{
    char why[4200];
    if (cli_write_open(out, path, why, sizeof why))
        return out->f;
    fprintf(stderr, "mvr bench: %s\n", why);
    return NULL;
}

/* Closes it: renamed into place when ok and every write, the flush and the
 * close succeeded; removed otherwise. */
static bool report_close(cli_write_file *out, bool ok)
{
    if (!ok) {
        cli_write_abandon(out);
        return false;
    }
    char why[4200];
    if (cli_write_close(out, why, sizeof why))
        return true;
    fprintf(stderr, "mvr bench: %s\n", why);
    return false;
}

bool bench_write_csv(const bench_run *run, const char *path)
{
    cli_write_file out;
    FILE *f = report_open(&out, path);
    if (!f)
        return false;
    fputs(csv_header, f);
    for (uint32_t k = 0; k < run->count; ++k) {
        const bench_config *c = &run->configs[k];
        const bench_result *r = &run->results[k];
        fprintf(f, "%s,%s,%s,%u,%u,%s,%d,%d,\"%s\",", c->name, mvr_view_path_name(c->view_path),
                mvr_material_path_name(c->material_path), c->supersample, c->msaa, mvr_transparency_order_name(c->order),
                c->reference, r->ran, r->skipped);
        if (!r->ran) {
            fprintf(f, ",,,,,,,,,,,%s,,,,,,,,0", c->group);
            csv_env_columns(f, run, c, r);
            continue;
        }
        char gpu[32] = "", instr[32] = "", psnr[32] = "inf";
        if (r->gpu_median >= 0)
            snprintf(gpu, sizeof gpu, "%.4f", r->gpu_median);
        if (r->instructions)
            snprintf(instr, sizeof instr, "%llu", (unsigned long long)r->instructions);
        if (!isinf(r->psnr_db))
            snprintf(psnr, sizeof psnr, "%.4f", r->psnr_db);
        fprintf(f, "%s,%.4f,%.4f,%.4f,%.4f,%s,%s,%.6f,%s,%.0f,%.4f,%s,%d,%u,%u,%u,%u,%u,%u,%d", r->view_path_ran,
                r->wall_median, r->wall_min, r->wall_max, r->cpu_median, gpu, instr, r->rmse, psnr, r->max_abs,
                r->over_2, c->group, r->group_diff, r->draws, r->draw_calls, r->passes, r->program_binds,
                r->texture_binds, r->ubo_range_binds, r->pareto);
        csv_env_columns(f, run, c, r);
    }
    return report_close(&out, true);
}

/* The run: what was measured, where, and how. */
static void write_run_json(json_writer *jw, const bench_run *run)
{
    json_string(jw, "scene", run->scene_name);
    json_string(jw, "command", run->command_line);
    json_string(jw, "renderer", run->renderer);
    json_int(jw, "views", run->views);
    json_int(jw, "width", run->width);
    json_int(jw, "height", run->height);
    json_int(jw, "frames", run->frames);
    json_string(jw, "omitted", run->omitted);
    json_string(jw, "axis", run->env_axes ? "environment" : "frame");
    if (run->env_axes) {
        /* errors over the covered pixels; times: the prefilter's */
        json_string(jw, "environment", run->environment);
        json_int(jw, "reference_env_samples", run->reference_samples);
        json_int(jw, "prefilter_repeats", run->frames);
        json_int(jw, "compared_pixels", (long long)run->compared_pixels);
    }
}

/* auto's decisions for configuration k and its verdict against the forced
 * paths (v NULL: none ran to compare with; the decisions alone). */
static void write_auto_json(json_writer *jw, const bench_run *run, uint32_t k, const bench_auto_verdict *v)
{
    const bench_result *r = &run->results[k];
    const mvr_auto_choice *a = &r->auto_choice;
    json_begin_object(jw, "auto");
    json_string(jw, "state", mvr_auto_state_name(a->state));
    json_string(jw, "prior", mvr_view_path_name(a->prior));
    json_string(jw, "chosen", mvr_view_path_name(a->chosen));
    json_double(jw, "tuner_multiview_ms", a->cost_ms[0]);
    json_double(jw, "tuner_loop_ms", a->cost_ms[1]);
    json_double(jw, "margin", a->margin);
    json_int(jw, "tuning_frames", r->tuning_frames);
    const mvr_auto_material_choice *mc = &r->auto_material;
    if (mc->state != MVR_AUTO_NONE) {
        json_string(jw, "material_state", mvr_auto_state_name(mc->state));
        json_string(jw, "material_chosen", mvr_material_path_name(mc->chosen));
        json_double(jw, "tuner_per_material_ms", mc->cost_ms[0]);
        json_double(jw, "tuner_arrays_ms", mc->cost_ms[1]);
    }
    const mvr_auto_skinning_choice *sk = &r->auto_skinning;
    if (sk->state != MVR_AUTO_NONE) {
        json_string(jw, "skinning_state", mvr_auto_state_name(sk->state));
        json_string(jw, "skinning_prior", mvr_skinning_path_name(sk->prior));
        json_string(jw, "skinning_chosen", mvr_skinning_path_name(sk->chosen));
        json_double(jw, "tuner_vertex_ms", sk->cost_ms[0]);
        json_double(jw, "tuner_preskin_ms", sk->cost_ms[1]);
    }
    if (!v) { /* nothing forced to compare with (e.g. --configs auto/auto/noaa alone) */
        json_end_object(jw);
        return;
    }
    json_string(jw, "best_forced", run->configs[v->best].name);
    json_double(jw, "excess_beyond_noise", v->excess);
    if (v->chosen_found) {
        json_string(jw, "chosen_forced", run->configs[v->chosen].name);
        json_double(jw, "choice_excess_beyond_noise", v->choice_excess);
        json_double(jw, "against_chosen_forced", v->same_work);
    }
    json_end_object(jw);
}

/* --env-axes: the prefilter's time and the error against the converged maps. */
static void write_env_result_json(json_writer *jw, const bench_config *c, const bench_result *r)
{
    json_double(jw, "prefilter_ms_median", r->prefilter_median);
    json_double(jw, "prefilter_ms_min", r->prefilter_min);
    json_double(jw, "prefilter_ms_max", r->prefilter_max);
    json_int(jw, "prefilter_passes", r->prefilter_passes);
    json_bool(jw, "library_default", r->library_default);
    json_bool(jw, "converged", c->converged);
    json_double(jw, "maps_rmse", r->maps_rmse);
    if (isinf(r->maps_psnr_db))
        json_null(jw, "maps_psnr_db");
    else
        json_double(jw, "maps_psnr_db", r->maps_psnr_db);
    json_double(jw, "maps_max_abs_255", r->maps_max_abs);
    json_bool(jw, "maps_pareto", r->maps_pareto);
}

/* One configuration and its result. */
static void write_config_json(json_writer *jw, const bench_run *run, uint32_t k)
{
    const bench_config *c = &run->configs[k];
    const bench_result *r = &run->results[k];
    json_begin_object(jw, NULL);
    json_string(jw, "config", c->name);
    json_string(jw, "view_path", mvr_view_path_name(c->view_path));
    json_string(jw, "material_path", mvr_material_path_name(c->material_path));
    json_int(jw, "supersample", c->supersample);
    json_int(jw, "msaa", c->msaa);
    json_string(jw, "transparency_order", mvr_transparency_order_name(c->order));
    json_bool(jw, "reference", c->reference);
    json_string(jw, "group", c->group);
    if (run->env_axes) {
        json_int(jw, "specular_size", c->specular_size);
        json_int(jw, "specular_samples", c->specular_samples);
    }
    json_bool(jw, "ran", r->ran);
    if (!r->ran) {
        json_string(jw, "skipped", r->skipped);
        json_end_object(jw);
        return;
    }
    json_string(jw, "view_path_ran", r->view_path_ran);
    bench_auto_verdict v;
    if (bench_auto_excess(run, k, &v))
        write_auto_json(jw, run, k, &v);
    else if (c->view_path == MVR_VIEW_PATH_AUTO && !c->reference)
        write_auto_json(jw, run, k, NULL);
    json_double(jw, "wall_ms_median", r->wall_median);
    json_double(jw, "wall_ms_min", r->wall_min);
    json_double(jw, "wall_ms_max", r->wall_max);
    json_double(jw, "wall_ms_q1", r->wall_q1);
    json_double(jw, "wall_ms_q3", r->wall_q3);
    json_double(jw, "cpu_ms_median", r->cpu_median);
    if (r->gpu_median >= 0)
        json_double(jw, "gpu_ms_median", r->gpu_median);
    else
        json_null(jw, "gpu_ms_median");
    if (r->instructions)
        json_int(jw, "instructions_per_frame", (long long)r->instructions);
    else
        json_null(jw, "instructions_per_frame");
    json_double(jw, "rmse", r->rmse);
    if (isinf(r->psnr_db)) /* identical to the reference */
        json_null(jw, "psnr_db");
    else
        json_double(jw, "psnr_db", r->psnr_db);
    json_double(jw, "max_abs_255", r->max_abs);
    json_double(jw, "pct_over_2_255", r->over_2);
    json_int(jw, "same_as_group_max_diff", r->group_diff);
    json_int(jw, "draws", r->draws);
    json_int(jw, "draw_calls", r->draw_calls);
    json_int(jw, "passes", r->passes);
    json_int(jw, "program_binds", r->program_binds);
    json_int(jw, "texture_binds", r->texture_binds);
    json_int(jw, "ubo_range_binds", r->ubo_range_binds);
    json_bool(jw, "pareto", r->pareto);
    if (run->env_axes)
        write_env_result_json(jw, c, r);
    json_end_object(jw);
}

bool bench_write_json(const bench_run *run, const char *path)
{
    cli_write_file out;
    FILE *f = report_open(&out, path);
    if (!f)
        return false;
    json_writer jw = {f, 0, {false}, {0}};
    json_begin_object(&jw, NULL);
    write_run_json(&jw, run);
    json_begin_array(&jw, "configurations");
    for (uint32_t k = 0; k < run->count; ++k)
        write_config_json(&jw, run, k);
    json_end_array(&jw);
    json_end_object(&jw);
    fputc('\n', f);
    return report_close(&out, true);
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
    char name[sizeof run->configs[worst].name];
    snprintf(name, sizeof name, "%s", run->configs[worst].name);
    for (char *p = name; *p; ++p) /* "multiview/arrays/noaa": one file name */
        if (*p == '/')
            *p = '-';
    snprintf(path, sizeof path, "%s/worst_diff_x8_%s.png", run->out_dir, name);
    ok = write_strip(path, diff, run->views, run->width, run->height) && ok;
    free(diff);
    return ok;
}

/* Runs gnuplot on `script` in the output directory. */
static bool run_gnuplot(const bench_run *run, const char *script, const char *rerun)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        if (chdir(run->out_dir) != 0)
            _exit(126);
        freopen("/dev/null", "w", stdout);
        execlp("gnuplot", "gnuplot", script, (char *)NULL);
        _exit(127);
    }
    int status = 0;
    bool ok = pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (!ok)
        fprintf(stderr, "mvr bench: gnuplot failed (status %d; is gnuplot installed? scripts/setup installs it); "
                        "%s is left for a rerun\n", status, rerun);
    return ok;
}

/* The front, by time: name, time (ms), rmse. time: the prefilter's under
 * --env-axes, else the frame's; maps: the front over the error against the
 * converged maps. */
static bool write_front(const bench_run *run, const char *path, bool maps)
{
    cli_write_file out;
    FILE *f = report_open(&out, path);
    if (!f)
        return false;
    bool *done = calloc(run->count, sizeof *done);
    for (uint32_t i = 0; done && i < run->count; ++i) {
        int next = -1;
        double next_ms = 0.0;
        for (uint32_t k = 0; k < run->count; ++k) {
            const bench_result *r = &run->results[k];
            double ms = run->env_axes ? r->prefilter_median : r->wall_median;
            if (r->ran && (maps ? r->maps_pareto : r->pareto) && !done[k] && (next < 0 || ms < next_ms)) {
                next = (int)k;
                next_ms = ms;
            }
        }
        if (next < 0)
            break;
        done[next] = true;
        fprintf(f, "%s,%.4f,%.6f\n", run->configs[next].name, next_ms,
                maps ? run->results[next].maps_rmse : run->results[next].rmse);
    }
    bool ok = done != NULL;
    free(done);
    if (!ok)
        fprintf(stderr, "mvr bench: cannot write %s: out of memory\n", path);
    return report_close(&out, ok);
}

/* --env-axes: plot_env.gp, plot_env.png and plot_env.svg: against the
 * reference on the left, against the converged maps on the right. */
static bool env_plot(const bench_run *run)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/plot_env.gp", run->out_dir);
    cli_write_file out;
    FILE *f = report_open(&out, path);
    if (!f)
        return false;
    /* columns of results.csv: 8 ran, 17 rmse, 21 group, 31 specular size,
     * 32 specular samples, 34 prefilter ms median, 38 library default,
     * 39 maps rmse */
    fprintf(f,
            "# mvr bench --env-axes: median prefilter time against RMSE, to the reference (left) and to\n"
            "# the converged maps (right), from results.csv; pareto_env.dat and pareto_env_maps.dat hold\n"
            "# the fronts, sorted by time\n"
            "set datafile separator ','\n"
            "set key top right\n"
            "set grid\n"
            "set logscale x 2\n"
            "set yrange [0:*]\n"
            "set offsets graph 0.05, graph 0.12, graph 0.15, 0\n"
            "set style line 1 pt 7 ps 1.2 lc rgb '#3060c0'\n"
            "set style line 2 pt 6 ps 2.2 lw 2 lc rgb '#d04020'\n"
            "set style line 3 pt 4 ps 2.6 lw 2 lc rgb '#20a040'\n"
            "set style line 4 pt 9 ps 1.6 lc rgb '#808080'\n"
            "axes(c) = (column(8) == 1 && strcol(21) eq 'environment' ? c : 1/0)\n"
            "conv(c) = (column(8) == 1 && strcol(21) eq 'converged' ? c : 1/0)\n"
            "dflt(c) = (column(8) == 1 && column(38) == 1 ? c : 1/0)\n"
            "label(c) = sprintf('%%d/%%d', column(31), column(32))\n"
            "set xlabel 'median prefilter time (ms, env_prefilter_ms of the first frame; log scale)'\n"
            "left = \"set title 'against the reference (environment_samples %u)'; set ylabel 'RMSE (0..1, covered "
            "pixels)'; plot 'results.csv' skip 1 using (axes($34)):(axes($17)) with points ls 1 title "
            "'size/samples', 'results.csv' skip 1 using (conv($34)):(conv($17)) with points ls 4 title "
            "'converged maps (limit)', 'results.csv' skip 1 using (dflt($34)):(dflt($17)) with points ls 3 title "
            "'library default', 'pareto_env.dat' using 2:3 with linespoints ls 2 title 'Pareto front', "
            "'results.csv' skip 1 using (axes($34)):(axes($17)):(label(0)) with labels offset 1,0.8 left font ',9' "
            "notitle\"\n"
            "right = \"set title 'against the converged maps (the prefilter alone)'; set ylabel 'RMSE (0..1, "
            "covered pixels)'; plot 'results.csv' skip 1 using (axes($34)):(axes($39)) with points ls 1 title "
            "'size/samples', 'results.csv' skip 1 using (dflt($34)):(dflt($39)) with points ls 3 title "
            "'library default', 'pareto_env_maps.dat' using 2:3 with linespoints ls 2 title 'Pareto front', "
            "'results.csv' skip 1 using (axes($34)):(axes($39)):(label(0)) with labels offset 1,0.8 left font ',9' "
            "notitle\"\n"
            "plot_it = \"set multiplot layout 1,2 title '%s under %s, %u views of %ux%u on %s'; eval left; "
            "eval right; unset multiplot\"\n"
            "set terminal png size 1500,650 noenhanced\n"
            "set output 'plot_env.png'\n"
            "eval plot_it\n"
            "set terminal svg size 1500,650 noenhanced\n"
            "set output 'plot_env.svg'\n"
            "eval plot_it\n",
            run->reference_samples, run->scene_name, run->environment, run->views, run->width, run->height,
            run->renderer);
    if (!report_close(&out, true))
        return false; /* no gnuplot on a partial script */
    snprintf(path, sizeof path, "%s/pareto_env.dat", run->out_dir);
    if (!write_front(run, path, false))
        return false;
    snprintf(path, sizeof path, "%s/pareto_env_maps.dat", run->out_dir);
    if (!write_front(run, path, true))
        return false;
    snprintf(path, sizeof path, "%s/plot_env.gp", run->out_dir);
    return run_gnuplot(run, "plot_env.gp", path);
}

/* Every point's label (labels.dat, comma-separated as results.csv: time, height, name): points close
 * together (configurations of the same error and about the same time) get
 * their labels stacked upwards, so each stays readable. */
static bool write_labels(const bench_run *run, const char *path)
{
    cli_write_file out;
    FILE *f = report_open(&out, path);
    if (!f)
        return false;
    double t_max = 0, e_max = 0;
    for (uint32_t k = 0; k < run->count; ++k)
        if (run->results[k].ran) {
            t_max = fmax(t_max, run->results[k].wall_median);
            e_max = fmax(e_max, run->results[k].rmse);
        }
    double dt = 0.15 * (t_max > 0 ? t_max : 1), de = 0.04 * (e_max > 0 ? e_max : 1);
    for (uint32_t k = 0; k < run->count; ++k) {
        const bench_result *r = &run->results[k];
        if (!r->ran)
            continue;
        uint32_t level = 0;
        for (uint32_t j = 0; j < k; ++j)
            level += run->results[j].ran && fabs(run->results[j].wall_median - r->wall_median) < dt &&
                     fabs(run->results[j].rmse - r->rmse) < de;
        fprintf(f, "%.4f,%.6f,%s\n", r->wall_median, r->rmse + level * de, run->configs[k].name);
    }
    return report_close(&out, true);
}

bool bench_plot(const bench_run *run)
{
    if (run->env_axes)
        return env_plot(run);
    char path[4096];
    snprintf(path, sizeof path, "%s/plot.gp", run->out_dir);
    cli_write_file out;
    FILE *f = report_open(&out, path);
    if (!f)
        return false;
    /* columns of results.csv: 1 config, 8 ran, 11 wall ms median, 17 rmse, 43/44 wall ms q1/q3 */
    fprintf(f,
            "# mvr bench: median frame time (bars: q1..q3) against RMSE to the reference (from results.csv;\n"
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
            "set style line 3 lw 1 lc rgb '#3060c0'\n"
            "plot_it = \"plot 'results.csv' skip 1 using (ran($11)):(ran($17)):(ran($43)):(ran($44)) with xerrorbars "
            "ls 3 pt 7 ps 1.2 title 'configuration (median, q1..q3)', "
            "'pareto.dat' using 2:3 with linespoints ls 2 title 'Pareto front', "
            "'labels.dat' using 1:2:3 with labels offset 1,0.8 left font ',8' notitle\"\n"
            "set terminal png size 1000,700 noenhanced\n" /* underscores in names are not subscripts */
            "set output 'plot.png'\n"
            "eval plot_it\n"
            "set terminal svg size 1000,700 noenhanced\n"
            "set output 'plot.svg'\n"
            "eval plot_it\n",
            run->scene_name, run->views, run->width, run->height, run->renderer);
    if (!report_close(&out, true))
        return false; /* no gnuplot on a partial script */
    snprintf(path, sizeof path, "%s/pareto.dat", run->out_dir);
    if (!write_front(run, path, false))
        return false;
    snprintf(path, sizeof path, "%s/labels.dat", run->out_dir);
    if (!write_labels(run, path))
        return false;
    snprintf(path, sizeof path, "%s/plot.gp", run->out_dir);
    return run_gnuplot(run, "plot.gp", path);
}

bool bench_write_reports(const bench_run *run)
{
    char path[4096];
    bench_print_table(run, stdout);
    snprintf(path, sizeof path, "%s/results.csv", run->out_dir);
    bool ok = bench_write_csv(run, path);
    snprintf(path, sizeof path, "%s/results.json", run->out_dir);
    ok = bench_write_json(run, path) && ok;
    ok = bench_write_images(run) && ok;
    return bench_plot(run) && ok;
}
