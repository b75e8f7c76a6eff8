/* A sharded run of mvr render (docs/guide.md, "Sharded runs"): its units
 * (file x view range x frame range, decided up front), DIR/.mvr-run/plan.json
 * that names them, the units' rendering and records (run_units.c) and the
 * merge (run_merge.c). Messages on stderr, prefixed "mvr render". */
#ifndef MVR_APP_RUN_PLAN_H
#define MVR_APP_RUN_PLAN_H

#include <stdbool.h>
#include <stdint.h>

#include "render_options.h"

typedef struct run_unit {
    uint32_t file;               /* index in the run's files */
    uint32_t v0, v1, f0, f1;     /* views [v0, v1), frames [f0, f1) */
} run_unit;

typedef struct run_plan {
    uint32_t file_count;
    const char **files;          /* SCENE paths as given (NULL: the demo) */
    char **dirs;                 /* each file's outputs relative to DIR: "" (one file) or "<stem>" */
    uint32_t *views;             /* each file's view count (0: it failed to load while planning) */
    uint32_t frames;
    run_unit *units;
    uint32_t unit_count;
    char *text;                  /* plan.json */
} run_plan;

/* The units of the run o and in describe: each file's views (from --views
 * or --cameras, else the scene loaded on the CPU and its views counted) in
 * ranges of --unit-views, their frames in ranges of --unit-frames; and
 * plan.json's text. false (printed) when out of memory. */
bool run_plan_make(const render_options *o, const render_inputs *in, run_plan *p);
void run_plan_free(run_plan *p);

/* DIR/.mvr-run/plan.json: written (atomically) when there is none, else
 * compared with p's: MVR_EXIT_OK, or MVR_EXIT_USAGE naming DIR and the
 * first difference ("DIR holds another run's plan: ..."). */
int run_plan_settle(const char *dir, const run_plan *p);

/* "u000012": the unit's id (6 digits or more). */
void run_unit_id(uint32_t unit, char buf[16]);

/* Renders one unit: base is the run's options with the unit's range
 * (render_options.unit ...), file the SCENE (NULL: the demo), out_dir
 * where its files go; an MVR_EXIT_ code, *fatal set when no later unit can
 * render either (no context or renderer). cmd_render.c's. */
typedef int (*run_unit_fn)(void *user, const render_options *base, const char *file, const char *out_dir,
                           bool *fatal);

/* --shard, --resume, --serve, --run-plan: the run's units (run_units.c),
 * each rendered through fn; an MVR_EXIT_ code. */
int run_units_main(const render_options *o, const render_inputs *in, run_unit_fn fn, void *user);

/* mvr render --merge DIR [--quiet] (run_merge.c); an MVR_EXIT_ code. */
int run_merge_main(int argc, char **argv);

#endif
