/* A sharded run's plan (run_plan.h): the units and plan.json. */
#define _POSIX_C_SOURCE 200809L
#include "run_plan.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <unistd.h>

#include "cli_common.h"
#include "cli_scene.h"
#include "cli_write.h"
#include "commands.h"
#include "json.h"
#include "run_record.h"
#include "sha256.h"

#define PLAN_VERSION 1

void run_unit_id(uint32_t unit, char buf[16])
{
    run_format(buf, 16, "u%06u", unit);
}

/* A file's view count: --cameras' views, --views, else the scene loaded on
 * the CPU (no GL) and its views counted; 0 when it does not load (its one
 * unit fails when rendered, with mvr's message). */
static uint32_t count_views(const render_options *o, const char *file)
{
    if (o->cameras_file)
        return o->camera_count;
    if (o->views)
        return o->views;
    cli_scene_options so = {.demo = o->demo, .scene_file = file, .camera = o->camera, .layout = o->layout,
                            .ipd = o->ipd, .framing = &o->framing, .gltf_scene = o->gltf_scene, .views = o->views,
                            .width = o->width, .height = o->height, .logger = {0}, .strict = o->strict,
                            .memory_budget = o->memory_budget};
    mvr_scene *scene = NULL;
    mvr_view_set *views = NULL;
    int rc = cli_load_scene("mvr render", &so, &scene, &views);
    uint32_t n = rc == MVR_EXIT_OK ? mvr_view_set_count(views) : 0;
    mvr_view_set_destroy(views);
    mvr_scene_destroy(scene);
    return n;
}

/* Units: each file's views in ranges of unit_views, each range's frames in
 * ranges of unit_frames; a file without views is one unit. */
static bool make_units(const render_options *o, run_plan *p)
{
    uint64_t total = 0;
    uint32_t uv = o->run.unit_views, uf = o->run.unit_frames ? o->run.unit_frames : p->frames;
    uint64_t frame_ranges = (p->frames + uf - 1) / uf;
    for (uint32_t k = 0; k < p->file_count; ++k) {
        uint32_t step = uv && uv < p->views[k] ? uv : (p->views[k] ? p->views[k] : 1);
        total += p->views[k] ? (uint64_t)((p->views[k] + step - 1) / step) * frame_ranges : 1;
    }
    if (total > UINT32_MAX / 2 || !(p->units = calloc(total ? total : 1, sizeof *p->units)))
        return false;
    for (uint32_t k = 0; k < p->file_count; ++k) {
        if (!p->views[k]) {
            p->units[p->unit_count++] = (run_unit){.file = k, .f0 = 0, .f1 = p->frames};
            continue;
        }
        uint32_t step = uv && uv < p->views[k] ? uv : p->views[k];
        for (uint32_t v = 0; v < p->views[k]; v += step)
            for (uint32_t f = 0; f < p->frames; f += uf) {
                uint32_t v1 = p->views[k] - v < step ? p->views[k] : v + step;
                uint32_t f1 = p->frames - f < uf ? p->frames : f + uf;
                p->units[p->unit_count++] = (run_unit){.file = k, .v0 = v, .v1 = v1, .f0 = f, .f1 = f1};
            }
    }
    return true;
}

/* plan.json: one value a line where it helps a diff, one unit a line. */
static void write_text(FILE *out, const render_options *o, const render_inputs *in, const run_plan *p)
{
    fprintf(out, "{\n  \"format\": \"mvr-run-plan\",\n  \"version\": %d,\n  \"args\": [", PLAN_VERSION);
    for (uint32_t k = 0; k < in->plan_arg_count; ++k) {
        fputs(k ? ", " : "", out);
        json_escaped(out, in->plan_args[k]);
    }
    fputs("],\n  \"demo\": ", out);
    json_escaped(out, o->scene_file ? "" : o->demo);
    fputs(",\n  \"files\": [", out);
    for (uint32_t k = 0; k < p->file_count; ++k) {
        fputs(k ? ",\n    {\"path\": " : "\n    {\"path\": ", out);
        json_escaped(out, p->files[k] ? p->files[k] : "");
        fputs(", \"dir\": ", out);
        json_escaped(out, p->dirs[k]);
        fprintf(out, ", \"views\": %u}", p->views[k]);
    }
    fprintf(out, "\n  ],\n  \"frames\": %u,\n  \"units\": [", p->frames);
    for (uint32_t u = 0; u < p->unit_count; ++u) {
        const run_unit *t = &p->units[u];
        char id[16];
        run_unit_id(u, id);
        fprintf(out, "%s\n    {\"unit\": %u, \"id\": \"%s\", \"file_index\": %u, \"views\": [%u, %u], "
                     "\"frames\": [%u, %u]}", u ? "," : "", u, id, t->file, t->v0, t->v1, t->f0, t->f1);
    }
    fputs("\n  ]", out);
}

/* Each file's directory under DIR: "" for one file, else its stem's. */
static bool make_dirs(const render_inputs *in, run_plan *p)
{
    if (p->file_count == 1 && in->files.count <= 1)
        return (p->dirs[0] = strdup("")) != NULL;
    if (!render_files_out_dirs(&in->files, "", p->dirs))
        return false;
    for (uint32_t k = 0; k < p->file_count; ++k)
        memmove(p->dirs[k], p->dirs[k] + 1, strlen(p->dirs[k])); /* "/stem" -> "stem" */
    return true;
}

bool run_plan_make(const render_options *o, const render_inputs *in, run_plan *p)
{
    memset(p, 0, sizeof *p);
    p->file_count = in->files.count > 1 ? in->files.count : 1;
    p->frames = o->frames;
    p->files = calloc(p->file_count, sizeof *p->files);
    p->dirs = calloc(p->file_count, sizeof *p->dirs);
    p->views = calloc(p->file_count, sizeof *p->views);
    bool ok = p->files && p->dirs && p->views && make_dirs(in, p);
    /* the planner's loads say nothing: their units will say it */
    fflush(stderr);
    int saved = ok ? dup(2) : -1, null = saved >= 0 ? open("/dev/null", O_WRONLY) : -1;
    if (null >= 0) {
        dup2(null, 2);
        close(null);
    }
    for (uint32_t k = 0; ok && k < p->file_count; ++k) {
        p->files[k] = in->files.count > 1 ? in->files.paths[k] : o->scene_file;
        p->views[k] = count_views(o, p->files[k]);
    }
    if (saved >= 0) {
        fflush(stderr);
        dup2(saved, 2);
        close(saved);
    }
    ok = ok && make_units(o, p);
    size_t size = 0;
    FILE *mem = ok ? open_memstream(&p->text, &size) : NULL;
    if (mem) {
        write_text(mem, o, in, p);
        ok = fflush(mem) == 0;
        char hash[65];
        sha256_hex(p->text, size, hash); /* the plan's identity: its text before the hash */
        fprintf(mem, ",\n  \"plan_hash\": \"%s\"\n}\n", hash);
        ok = fclose(mem) == 0 && ok;
    }
    if (!ok || !mem)
        fprintf(stderr, "mvr render: out of memory for the run's plan\n");
    return ok && mem;
}

void run_plan_free(run_plan *p)
{
    for (uint32_t k = 0; p->dirs && k < p->file_count; ++k)
        free(p->dirs[k]);
    free(p->dirs);
    free(p->files);
    free(p->views);
    free(p->units);
    free(p->text);
    memset(p, 0, sizeof *p);
}

/* The first line where a and b differ, into why. */
static void first_difference(const char *a, const char *b, char *why, size_t size)
{
    unsigned line = 1;
    const char *la = a, *lb = b;
    while (*a && *a == *b) {
        if (*a == '\n')
            ++line, la = a + 1, lb = b + 1;
        ++a, ++b;
    }
    int na = (int)strcspn(la, "\n"), nb = (int)strcspn(lb, "\n");
    run_format(why, size, "line %u is '%.*s' there, '%.*s' here", line, na > 160 ? 160 : na, la, nb > 160 ? 160 : nb,
             lb);
}

int run_plan_settle(const char *dir, const run_plan *p)
{
    char path[4200], why[4400];
    run_format(path, sizeof path, "%s/.mvr-run", dir);
    if (!cli_make_dirs("mvr render", path))
        return MVR_EXIT_FAILURE;
    run_format(path, sizeof path, "%s/.mvr-run/plan.json", dir);
    char *old = run_read_text(path, NULL);
    if (old) {
        bool same = strcmp(old, p->text) == 0;
        if (!same) {
            first_difference(old, p->text, why, sizeof why);
            fprintf(stderr, "mvr render: %s holds another run's plan: %s (%s)\n", dir, why, path);
        }
        free(old);
        return same ? MVR_EXIT_OK : MVR_EXIT_USAGE;
    }
    if (errno != ENOENT) {
        fprintf(stderr, "mvr render: cannot read %s: %s\n", path, strerror(errno));
        return MVR_EXIT_FAILURE;
    }
    /* atomic: another shard writing the same text at once renames the same bytes */
    cli_write_file w;
    bool ok = cli_write_open(&w, path, why, sizeof why);
    if (ok) {
        fputs(p->text, w.f);
        ok = cli_write_close(&w, why, sizeof why);
    }
    if (!ok) {
        fprintf(stderr, "mvr render: %s\n", why);
        return MVR_EXIT_FAILURE;
    }
    return MVR_EXIT_OK;
}
