/* mvr render's options of a sharded run (docs/guide.md, "Sharded runs"):
 * --shard K/N, --resume, --serve, --worker, --run-plan, --unit-views,
 * --unit-frames and --merge DIR; their table, their values and what they
 * refuse. The run itself: run_plan.h. */
#ifndef MVR_APP_RUN_OPTIONS_H
#define MVR_APP_RUN_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>

#include "cli_options.h"

#define RUN_SHARDS_MAX 100000u

typedef struct render_run_options {
    uint32_t shard_k, shard_n;   /* --shard K/N (1 <= K <= N); 0: none */
    bool resume;                 /* --resume: skip units with a done record */
    bool serve;                  /* --serve: unit numbers on stdin, records on stdout */
    bool plan;                   /* --run-plan: write (or check) plan.json, print it, render nothing */
    const char *worker;          /* --worker NAME: the records' worker (default host:pid) */
    uint32_t unit_views;         /* --unit-views V: views per unit (0: all of a file's) */
    uint32_t unit_frames;        /* --unit-frames F: frames per unit (0: all) */
    const char *merge;           /* --merge DIR (handled before the other options: run_merge.c) */
} render_run_options;

#define RUN_ID_FIRST 2000        /* ids of render_run_table's options */

extern const cli_option render_run_table[];

/* One run option's value into run: 1 applied, 0 not one of these, -1 a bad
 * value (printed). */
int render_run_apply(const cli_arg *arg, render_run_options *run);

/* Whether the option (by id) is one that does not change what a run
 * writes (--shard, --resume, --worker, ...): left out of plan.json. */
bool render_run_option_is_control(int id);

/* Whether any of --shard, --resume, --serve, --run-plan was given. */
bool render_run_active(const render_run_options *run);

#endif
