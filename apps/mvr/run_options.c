/* mvr render's sharded-run options (run_options.h). */
#define _POSIX_C_SOURCE 200809L
#include "run_options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"

enum { R_SHARD = RUN_ID_FIRST, R_RESUME, R_SERVE, R_WORKER, R_RUN_PLAN, R_UNIT_VIEWS, R_UNIT_FRAMES, R_MERGE };

const cli_option render_run_table[] = {
    {CLI_OPT_TEXT, 0, NULL, NULL, NULL, 0, 0, NULL, "\nsharded runs (docs/guide.md, \"Sharded runs\"):", NULL, NULL,
     NULL},
    {CLI_OPT_STRING, R_SHARD, "--shard", NULL, "K/N", 0, 0, NULL,
     "render the K-th of N shards of the run's units (unit u with\n"
     "u % N == K - 1) into --out DIR: each unit's files, then its\n"
     "record in DIR/.mvr-run/units/; DIR/.mvr-run/plan.json must\n"
     "match (or is written); the run's own files come from --merge",
     NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_RESUME, "--resume", NULL, NULL, 0, 0, NULL,
     "skip the units DIR's records say are done (their files there\n"
     "with the recorded sizes); alone: every unit", NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_SERVE, "--serve", NULL, NULL, 0, 0, NULL,
     "render the units whose numbers come on stdin, one a line,\n"
     "answering each with its record (one JSON line on stdout); a\n"
     "done unit is not rendered again; ends at EOF", NULL, "--shard", "--serve takes its units from stdin"},
    {CLI_OPT_STRING, R_WORKER, "--worker", NULL, "NAME", 0, 0, NULL,
     "the records' worker name (default: host:pid)", NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_RUN_PLAN, "--run-plan", NULL, NULL, 0, 0, NULL,
     "write (or check) DIR/.mvr-run/plan.json, print it, render\n"
     "nothing", NULL, "--shard --serve", "--run-plan renders nothing"},
    {CLI_OPT_U32, R_UNIT_VIEWS, "--unit-views", NULL, "V", 1, 1024, NULL,
     "views per unit (default: all of a file's)", NULL, NULL, NULL},
    {CLI_OPT_U32, R_UNIT_FRAMES, "--unit-frames", NULL, "F", 1, 100000, NULL,
     "frames per unit (default: all)", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_MERGE, "--merge", NULL, "DIR", 0, 0, NULL,
     "check DIR's records (every unit done, every file's sha256),\n"
     "write the run's own files (contact sheets, cameras.json,\n"
     "transforms.json, COLMAP, ids.json, COCO) and manifest.jsonl;\n"
     "takes no other option but --quiet", NULL, NULL, NULL},
    {CLI_OPT_END, 0, NULL, NULL, NULL, 0, 0, NULL, NULL, NULL, NULL, NULL},
};

/* "K/N" with 1 <= K <= N <= RUN_SHARDS_MAX. */
static bool parse_shard(const char *v, uint32_t *k, uint32_t *n)
{
    const char *slash = strchr(v, '/');
    char left[32];
    if (!slash || (size_t)(slash - v) >= sizeof left)
        return false;
    memcpy(left, v, (size_t)(slash - v));
    left[slash - v] = '\0';
    return cli_parse_u32(left, 1, RUN_SHARDS_MAX, k) && cli_parse_u32(slash + 1, 1, RUN_SHARDS_MAX, n) && *k <= *n;
}

int render_run_apply(const cli_arg *arg, render_run_options *run)
{
    switch (arg->opt->id) {
    case R_SHARD:
        if (!parse_shard(arg->value, &run->shard_k, &run->shard_n)) {
            fprintf(stderr, "mvr render: --shard takes K/N with 1 <= K <= N <= %u (got '%s')\n", RUN_SHARDS_MAX,
                    arg->value);
            return -1;
        }
        break;
    case R_RESUME: run->resume = true; break;
    case R_SERVE: run->serve = true; break;
    case R_WORKER: run->worker = arg->value; break;
    case R_RUN_PLAN: run->plan = true; break;
    case R_UNIT_VIEWS: run->unit_views = arg->number; break;
    case R_UNIT_FRAMES: run->unit_frames = arg->number; break;
    case R_MERGE: run->merge = arg->value; break;
    default: return 0;
    }
    return 1;
}

bool render_run_option_is_control(int id)
{
    return id == R_SHARD || id == R_RESUME || id == R_SERVE || id == R_WORKER || id == R_RUN_PLAN || id == R_MERGE;
}

bool render_run_active(const render_run_options *run)
{
    return run->shard_n || run->resume || run->serve || run->plan;
}
