/* mvr bench's options: the table (name, value kind and range, help,
 * conflicts), the help printed from it, and the parse that turns argv into
 * bench_options and checks their combination; running them is
 * cmd_bench.c's (the frame matrix) and bench_env.c's (--env-axes). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "cli_common.h"
#include "cli_env.h"
#include "cli_options.h"
#include "cli_scene.h"
#include "commands.h"

enum {
    B_DEMO = 1, B_VIEWS, B_SIZE, B_FRAMES, B_WARMUP, B_ROUNDS, B_MATRIX, B_OUT, B_CALLGRIND, B_QUIET, B_VERBOSE,
    B_ONLY, B_CONFIGS, B_ENV_AXES, B_SPECULAR_SIZES, B_SPECULAR_SAMPLES, B_REFERENCE_SAMPLES, B_CAMERAS, B_CAMERA,
    B_LAYOUT, B_PROGRAM_CACHE, B_REFERENCE_MEMORY
};

#define END {CLI_OPT_END, 0, NULL, NULL, NULL, 0, 0, NULL, NULL, NULL, NULL, NULL}
#define ENV_AXES_WHY "--env-axes times the prefilter, not frames"

/* name, value and range, help, conflicts; the order is --help's */
static const cli_option bench_table[] = {
    {CLI_OPT_STRING, B_DEMO, "--demo", NULL, "NAME", 0, 0, NULL, "stereo | cube | city | ring (default: city)", NULL,
     NULL, NULL},
    {CLI_OPT_U32, B_VIEWS, "--views", NULL, "N", 1, 64, NULL,
     "views (default: the demo's own), 1..64; --demo stereo and city\n"
     "frame at most 39 at 256x256 (fewer on wider layers)", NULL, NULL, NULL},
    {CLI_OPT_STRING, B_SIZE, "--size", NULL, "WxH", 0, 0, NULL, "layer size (default: 256x256)", NULL, NULL, NULL},
    {CLI_OPT_STRING, B_CAMERAS, "--cameras", NULL, "FILE", 0, 0, NULL,
     "the views from a camera file, as mvr render --cameras takes\n"
     "it (cameras.json, transforms.json, CSV; at most 64 views);\n"
     "its image size unless --size is given", NULL, "--views", "the camera file gives every view"},
    {CLI_OPT_U32, B_CAMERA, "--camera", NULL, "K", 0, 1u << 20, NULL,
     "SCENE: view from the file's K-th camera node (0-based), as\n"
     "mvr render does; N views are eyes apart along its right\n"
     "axis (default: the first camera when the file has one)", NULL, "--layout --cameras",
     "--layout and --cameras give the views without a camera"},
    {CLI_OPT_CHOICE, B_LAYOUT, "--layout", NULL, "L", 0, 0, "stereo|cube|ring|grid|sphere|orbit|random",
     "SCENE without --camera: frame it as mvr render --layout L\n"
     "does (default: stereo)", NULL, "--cameras", "the camera file gives every view"},
    {CLI_OPT_U32, B_FRAMES, "--frames", NULL, "F", 1, 1000, NULL, "measured frames per configuration (default: 10)",
     NULL, NULL, NULL},
    {CLI_OPT_U32, B_WARMUP, "--warmup", NULL, "W", 0, 1000, NULL, "frames before measuring (default: 2)", NULL, NULL,
     NULL},
    {CLI_OPT_U32, B_ROUNDS, "--rounds", NULL, "R", 1, 100, NULL,
     "take the frames in R rounds over all configurations\n"
     "(default: 5, at most F)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, B_MATRIX, "--matrix", NULL, "M", 0, 0, "quick|full", "quick | full (default: quick)", NULL, NULL,
     NULL},
    {CLI_OPT_STRING, B_CONFIGS, "--configs", NULL, "LIST", 0, 0, NULL,
     "only these configurations of the matrix (comma-separated,\n"
     "as results.csv names them: auto/auto/noaa,loop/arrays/noaa),\n"
     "besides the reference the errors are measured against", NULL, "--env-axes",
     "--env-axes has no configuration matrix"},
    {CLI_OPT_STRING, B_OUT, "--out", NULL, "DIR", 0, 0, NULL, "output directory (default: bench-out)", NULL, NULL,
     NULL},
    {CLI_OPT_FLAG, B_CALLGRIND, "--callgrind", NULL, NULL, 0, 0, NULL,
     "also count the submitting thread's instructions per frame\n"
     "under valgrind --tool=callgrind (repeatable to < 1% on a\n"
     "shared machine, unlike wall time; slow)", NULL, NULL, NULL},
    {CLI_OPT_STRING, B_PROGRAM_CACHE, "--program-cache", NULL, "D", 0, 0, NULL,
     "program binaries and auto's settled choices in D, as mvr\n"
     "render keeps them (a later run starts on the measured\n"
     "choice); off disables both (default: $XDG_CACHE_HOME/mvr/\n"
     "programs or ~/.cache/mvr/programs)", NULL, NULL, NULL},
    {CLI_OPT_U32, B_REFERENCE_MEMORY, "--reference-memory", NULL, "MIB", 1, 65536, NULL,
     "the most the reference's 4x4-supersampled float target\n"
     "takes at once: views are rendered in chunks that fit\n"
     "(default: 256)", NULL, NULL, NULL},
    {CLI_OPT_FLAG, B_QUIET, "--quiet", NULL, NULL, 0, 0, NULL, "no progress bar", NULL, NULL, NULL},
    {CLI_OPT_FLAG, B_VERBOSE, "--verbose", NULL, NULL, 0, 0, NULL, "log what the library does to stderr", NULL, NULL,
     NULL},
    /* internal: --callgrind runs each configuration alone in a child */
    {CLI_OPT_U32, B_ONLY, "--only", NULL, "K", 0, 1000, NULL, NULL, NULL, NULL, NULL},
    {CLI_OPT_TEXT, 0, NULL, NULL, NULL, 0, 0, NULL,
     "\nThe matrix renders under the environment mvr render takes (--env\n"
     "below; neutral for a glTF file, none for a demo). A scene with skins\n"
     "or morph targets adds each view path with --skinning vertex and\n"
     "preskin, and auto with both paths auto (against those four); one\n"
     "whose materials use KHR_materials_specular / _ior or\n"
     "_clearcoat or _sheen adds auto/arrays/noaa with each drawn as absent\n"
     "(no_...).\n"
     "\nenvironment prefilter axes:\n", NULL, NULL, NULL},
    {CLI_OPT_FLAG, B_ENV_AXES, "--env-axes", NULL, NULL, 0, 0, NULL,
     "instead of the matrix above: the image-based lighting's\n"
     "prefilter, specular map size x GGX samples per texel\n"
     "(mvr_environment_desc.specular_size, .specular_samples),\n"
     "on a grid of spheres of 8 roughnesses, dielectric and\n"
     "metal, under --env (default: neutral); or SCENE.gltf, or\n"
     "--demo NAME with --env. Each is timed by its prefilter\n"
     "(env_prefilter_ms of the first frame with a fresh\n"
     "environment: median of --frames runs, default 5, after\n"
     "--warmup untimed ones, default 1) and compared, over the\n"
     "pixels the scene covers, neither side anti-aliased, with\n"
     "the reference (the environment integrated per pixel, loop\n"
     "path) and with the converged maps (the largest size, 4096\n"
     "samples: the prefilter's own error). Marks the one with the\n"
     "library default's pixels. Writes results.csv, results.json,\n"
     "plot_env.png, plot_env.svg, reference.png,\n"
     "worst_diff_x8_<configuration>.png", NULL, "--matrix --callgrind", ENV_AXES_WHY},
    {CLI_OPT_STRING, B_SPECULAR_SIZES, "--specular-sizes", NULL, "L", 0, 0, NULL,
     "face sizes, powers of two 16..1024 (default: 32,64,128,256)", NULL, NULL, NULL},
    {CLI_OPT_STRING, B_SPECULAR_SAMPLES, "--specular-samples", NULL, "L", 0, 0, NULL,
     "samples per texel, 1..4096 (default: 16,64,256)", NULL, NULL, NULL},
    {CLI_OPT_U32, B_REFERENCE_SAMPLES, "--reference-samples", NULL, "N", 1, 65536, NULL,
     "samples per lobe of the reference (default: 1024)", NULL, NULL, NULL},
    END,
};

static const cli_option *const bench_tables[] = {bench_table, cli_env_option_table, cli_context_options,
                                                 cli_help_option, NULL};

static void bench_usage(FILE *out)
{
    fprintf(out,
            "usage: mvr bench [--demo NAME | SCENE.gltf | SCENE.glb] [options]\n"
            "\n"
            "Renders the scene under a matrix of configurations and reports, for each,\n"
            "frame time (wall: median and interquartile range, over frames taken in rounds\n"
            "that visit every configuration in turn), CPU time of the submitting thread, GPU\n"
            "time where timer queries exist, and the error against the reference render\n"
            "(loop path, per-view transparency order, 4x4 supersampling): RMSE, PSNR, max\n"
            "abs, %% of pixels over 2/255. Writes results.csv, results.json, plot.png and\n"
            "plot.svg (time against error, every point labelled with its q1..q3 bar; the\n"
            "Pareto front counts only differences beyond that noise), reference.png and\n"
            "worst_diff_x8_<configuration>.png (|image - reference| x 8) into --out.\n"
            "\n"
            "options:\n");
    cli_print_options(out, bench_tables, 20);
}

/* "32,64,128": up to 8 distinct values in lo..hi (powers of two if pow2),
 * kept in the order given. */
static bool parse_list(const char *v, uint32_t lo, uint32_t hi, bool pow2, uint32_t *out, uint32_t *n)
{
    char buf[256];
    if (strlen(v) >= sizeof buf)
        return false;
    strcpy(buf, v);
    *n = 0;
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        uint32_t x = 0;
        if (*n == 8 || !cli_parse_u32(tok, lo, hi, &x) || (pow2 && (x & (x - 1u)) != 0))
            return false;
        for (uint32_t k = 0; k < *n; ++k)
            if (out[k] == x)
                return false;
        out[(*n)++] = x;
    }
    return *n > 0 && v[0] != ',' && v[strlen(v) - 1] != ',' && !strstr(v, ",,");
}

/* --cameras: the views of every configuration; the file's image size
 * unless --size was given. */
static bool load_cameras(bench_options *o)
{
    char why[512];
    if (!camera_file_load(o->cameras_file, o->scene.width, o->scene.height, &o->cameras, why, sizeof why)) {
        fprintf(stderr, "mvr bench: --cameras %s: %s\n", o->cameras_file, why);
        return false;
    }
    if (o->cameras.count > 64) {
        fprintf(stderr, "mvr bench: --cameras %s: %u views; mvr bench takes at most 64 (the reference renders each "
                        "one 4x4 times over)\n", o->cameras_file, o->cameras.count);
        camera_file_free(&o->cameras);
        return false;
    }
    if (o->cameras.width && !o->size_set &&
        (o->cameras.width > 4096 || o->cameras.height > 4096)) {
        fprintf(stderr, "mvr bench: --cameras %s: its images are %ux%u; mvr bench takes at most 4096x4096 (give "
                        "--size)\n", o->cameras_file, o->cameras.width, o->cameras.height);
        camera_file_free(&o->cameras);
        return false;
    }
    if (o->cameras.width && !o->size_set) {
        o->scene.width = o->cameras.width;
        o->scene.height = o->cameras.height;
    }
    o->scene.given_views = o->cameras.views;
    o->scene.given_view_count = o->cameras.count;
    return true;
}

/* One option of bench_table into o: false on a bad value. */
static bool apply(const cli_arg *arg, bench_options *o, bool *verbose)
{
    const char *a = arg->opt->name, *v = arg->value;
    bool ok = true;
    switch (arg->opt->id) {
    case B_ENV_AXES: o->env_axes = true; break;
    case B_QUIET: o->quiet = true; break;
    case B_VERBOSE: *verbose = true; break;
    case B_CALLGRIND: o->callgrind = true; break;
    case B_DEMO:
        o->scene.demo = v;
        o->demo_set = true;
        break;
    case B_VIEWS: o->scene.views = arg->number; break;
    case B_FRAMES:
        o->frames = arg->number;
        o->frames_set = true;
        break;
    case B_WARMUP:
        o->warmup = arg->number;
        o->warmup_set = true;
        break;
    case B_ROUNDS: o->rounds = arg->number; break;
    case B_SPECULAR_SIZES:
        ok = parse_list(v, 16, 1024, true, o->sizes, &o->n_sizes);
        o->env_option = a;
        break;
    case B_SPECULAR_SAMPLES:
        ok = parse_list(v, 1, 4096, false, o->samples, &o->n_samples);
        o->env_option = a;
        break;
    case B_REFERENCE_SAMPLES:
        o->reference_samples = arg->number;
        o->env_option = a;
        break;
    case B_OUT: o->out_dir = v; break;
    case B_ONLY: o->only = (int)arg->number; break;
    case B_CONFIGS:
        o->configs = v;
        ok = v[0] != '\0';
        break;
    case B_MATRIX:
        o->matrix_set = true;
        o->full = arg->choice == 1;
        break;
    case B_SIZE:
        ok = cli_parse_size(v, 1, 4096, &o->scene.width, &o->scene.height);
        o->size_set = true;
        break;
    case B_CAMERAS:
        o->cameras_file = v;
        ok = v[0] != '\0';
        break;
    case B_CAMERA:
        o->scene.camera = (int)arg->number;
        o->camera_set = true;
        break;
    case B_LAYOUT:
        o->scene.layout = (mvr_view_layout)(MVR_LAYOUT_STEREO + arg->choice);
        o->layout_set = true;
        break;
    case B_PROGRAM_CACHE:
        o->program_cache = v;
        ok = v[0] != '\0';
        break;
    case B_REFERENCE_MEMORY: o->reference_memory = (uint64_t)arg->number << 20; break;
    default: ok = false;
    }
    return ok;
}

/* The arguments into o; -1 after --help (printed). */
static int parse_args(cli_parser *p, bench_options *o, bool *verbose)
{
    cli_arg arg;
    int c;
    while ((c = cli_next(p, &arg)) > 0) {
        if (!arg.opt) { /* the SCENE (the parser refuses a second) */
            o->scene.scene_file = arg.value;
            continue;
        }
        if (arg.opt->id == CLI_ID_HELP) {
            bench_usage(stdout);
            return -1;
        }
        const char *a = arg.opt->name, *v = arg.value;
        int done = cli_context_apply("mvr bench", &arg, &o->context);
        if (done == 0 && (done = cli_env_apply("mvr bench", &arg, &o->env)) > 0)
            o->env_option = a;
        if (done < 0)
            return MVR_EXIT_USAGE;
        if (done == 0 && !apply(&arg, o, verbose)) {
            fprintf(stderr, "mvr bench: bad value '%s' for %s\n", v, a);
            return MVR_EXIT_USAGE;
        }
    }
    return c < 0 ? MVR_EXIT_USAGE : MVR_EXIT_OK;
}

/* The options together: the camera file, the demo's views, the context,
 * the environment, and --env-axes' own defaults. */
static int check(bench_options *o)
{
    if (!o->scene.scene_file && (o->camera_set || o->layout_set)) {
        fprintf(stderr, "mvr bench: --camera and --layout are for a SCENE file\n");
        return MVR_EXIT_USAGE;
    }
    /* the views mvr render gives the file */
    o->scene.camera =
        cli_scene_camera_choice(o->scene.scene_file != NULL, o->scene.camera, o->layout_set, o->cameras_file != NULL);
    if (o->program_cache && strcmp(o->program_cache, "off") != 0 &&
        !cli_check_writable_dir("mvr bench", "--program-cache", o->program_cache))
        return MVR_EXIT_USAGE;
    if (o->cameras_file && !load_cameras(o))
        return MVR_EXIT_USAGE;
    if (!o->cameras_file && !o->scene.scene_file && !cli_check_demo_views("mvr bench", o->scene.demo, o->scene.views, o->scene.width,
                                                      o->scene.height))
        return MVR_EXIT_USAGE;
    if (!cli_context_check("mvr bench", &o->context))
        return MVR_EXIT_USAGE;
    if (!o->env_axes) {
        /* the frame matrix renders under the environment mvr render takes */
        if (!cli_env_check("mvr bench", &o->env, !o->demo_set))
            return MVR_EXIT_USAGE;
    } else {
        if (!cli_env_check("mvr bench", &o->env, !o->demo_set))
            return MVR_EXIT_USAGE;
        if (o->env.env ? strcmp(o->env.env, "none") == 0 : o->demo_set && !o->scene.scene_file) {
            fprintf(stderr, "mvr bench: --env-axes needs an environment (--env FILE|neutral|uniform; %s)\n",
                    o->env.env ? "not none" : "the demos have none of their own");
            return MVR_EXIT_USAGE;
        }
        if (!o->n_sizes) {
            const uint32_t sizes[4] = {32, 64, 128, 256};
            memcpy(o->sizes, sizes, sizeof sizes);
            o->n_sizes = 4;
        }
        if (!o->n_samples) {
            const uint32_t samples[3] = {16, 64, 256};
            memcpy(o->samples, samples, sizeof samples);
            o->n_samples = 3;
        }
        if (!o->frames_set)
            o->frames = 5;
        if (!o->warmup_set)
            o->warmup = 1;
    }
    return MVR_EXIT_OK;
}

int bench_options_parse(int argc, char **argv, bench_options *o)
{
    memset(o, 0, sizeof *o);
    o->scene.demo = "city";
    o->scene.camera = -1;
    o->scene.width = o->scene.height = 256;
    o->frames = 10;
    o->warmup = 2;
    o->rounds = 5;
    o->out_dir = "bench-out";
    o->only = -1;
    o->reference_samples = 1024;
    o->reference_memory = (uint64_t)256 << 20;
    bool verbose = false;
    cli_parser p;
    cli_parser_init(&p, "mvr bench", bench_tables, argc, argv);
    int rc = parse_args(&p, o, &verbose);
    if (rc == MVR_EXIT_OK)
        rc = check(o);
    if (rc != MVR_EXIT_OK)
        return rc;
    cli_logger(&o->context.logger, "mvr bench", verbose);
    o->scene.logger = o->context.logger;
    return MVR_EXIT_OK;
}

/* --configs: keep the reference and the named configurations, in the
 * matrix's order; a name the matrix does not have is an error that lists
 * the names it has. */
bool bench_select_configs(const char *list, bench_config *configs, uint32_t *count)
{
    bool keep[BENCH_MAX_CONFIGS] = {false};
    for (const char *p = list; *p;) {
        size_t len = strcspn(p, ",");
        bool found = false;
        for (uint32_t k = 0; k < *count; ++k)
            if (!configs[k].reference && strlen(configs[k].name) == len && strncmp(configs[k].name, p, len) == 0)
                found = keep[k] = true;
        if (!found) {
            fprintf(stderr, "mvr bench: --configs: no configuration '%.*s' in this matrix; it has:", (int)len, p);
            for (uint32_t k = 0; k < *count; ++k)
                if (!configs[k].reference)
                    fprintf(stderr, " %s", configs[k].name);
            fprintf(stderr, "\n");
            return false;
        }
        p += len + (p[len] == ',');
    }
    uint32_t kept = 0;
    for (uint32_t k = 0; k < *count; ++k)
        if (configs[k].reference || keep[k])
            configs[kept++] = configs[k];
    *count = kept;
    return true;
}

void bench_command_line(int argc, char **argv, char *buf, size_t size)
{
    snprintf(buf, size, "mvr");
    for (int i = 0; i < argc; ++i) {
        size_t l = strlen(buf);
        snprintf(buf + l, size - l, " %s", argv[i]);
    }
}
