/* mvr render --merge DIR (run_plan.h): checks a sharded run's records
 * against its plan (every unit done, every file's size and SHA-256), then
 * writes what a plain run writes once a file's views are all there: the
 * contact sheet (from the written views), cameras.json, transforms.json
 * (and its splits), COLMAP's model, ids.json and the COCO annotations, and
 * DIR/manifest.jsonl. No GL: the scenes are loaded on the CPU. A file any
 * of whose units is missing, failed or damaged gets none of its files; the
 * others do, and the merge exits 1 naming what is missing. */
#define _POSIX_C_SOURCE 200809L
#include "run_plan.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_scene.h"
#include "cli_write.h"
#include "commands.h"
#include "dataset.h"
#include "json_read.h"
#include "mvr/mvr_image.h"
#include "render_aovs.h"
#include "render_output.h"
#include "render_sheet.h"
#include "run_record.h"
#include "sha256.h"

/* plan.json's "args" as the argv of mvr render --run-plan --out DIR: the
 * run's options again (argv[0] "render"). NULL (printed) when unreadable. */
static char **plan_argv(const char *dir, bool quiet, int *argc)
{
    char path[8192], why[256];
    run_format(path, sizeof path, "%s/.mvr-run/plan.json", dir);
    size_t size = 0;
    char *text = run_read_text(path, &size);
    if (!text) {
        fprintf(stderr, "mvr render: --merge %s: cannot read %s: %s\n", dir, path, strerror(errno));
        return NULL;
    }
    json_value v;
    bool ok = json_read(text, size, &v, why, sizeof why);
    free(text);
    const json_value *args = ok ? json_member(&v, "args") : NULL;
    char **argv = args && args->type == JSON_ARRAY ? calloc(args->count + 6, sizeof *argv) : NULL;
    int n = 0;
    if (argv) {
        argv[n++] = strdup("render");
        for (uint32_t k = 0; k < args->count && argv; ++k)
            argv[n++] = args->items[k].type == JSON_STRING ? strdup(args->items[k].string) : NULL;
        argv[n++] = strdup("--run-plan");
        argv[n++] = strdup("--out");
        argv[n++] = strdup(dir);
        if (quiet)
            argv[n++] = strdup("--quiet");
        for (int k = 0; k < n; ++k)
            ok = ok && argv[k];
    }
    if (ok)
        json_read_free(&v);
    if (!ok || !argv) {
        fprintf(stderr, "mvr render: --merge %s: %s is no plan of mvr render%s%s\n", dir, path, ok ? "" : ": ",
                ok ? "" : why);
        for (int k = 0; argv && k < n; ++k)
            free(argv[k]);
        free(argv);
        return NULL;
    }
    *argc = n;
    return argv;
}

/* Checks unit u's record and files; false (printed) when it is missing,
 * failed or a file differs. The record's line goes to the manifest. */
static bool check_unit(const char *dir, const run_plan *p, uint32_t u, FILE *manifest)
{
    char id[16], why[1024];
    run_unit_id(u, id);
    const run_unit *t = &p->units[u];
    const char *file = p->files[t->file] ? p->files[t->file] : "the demo";
    run_record rec;
    if (!run_record_read(dir, u, &rec, why, sizeof why)) {
        fprintf(stderr, "mvr render: --merge %s: %s\n", dir, why);
        return false;
    }
    bool ok = rec.present && rec.done;
    if (!rec.present)
        fprintf(stderr, "mvr render: --merge %s: %s (%s, views %u..%u) has no record: not rendered yet\n", dir, id,
                file, t->v0, t->v1);
    else if (!rec.done)
        fprintf(stderr, "mvr render: --merge %s: %s (%s) failed: %s\n", dir, id, file, rec.message);
    for (uint32_t k = 0; ok && k < rec.files.count; ++k) {
        const run_file *f = &rec.files.items[k];
        char path[8192], hex[65];
        uint64_t bytes = 0;
        run_format(path, sizeof path, "%s/%s", dir, f->path);
        if (!sha256_file(path, hex, &bytes)) {
            fprintf(stderr, "mvr render: --merge %s: %s: %s: %s\n", dir, id, path, strerror(errno));
            ok = false;
        } else if (bytes != f->bytes || strcmp(hex, f->sha256) != 0) {
            fprintf(stderr, "mvr render: --merge %s: %s: %s is not the file its record names (%s)\n", dir, id,
                    path, bytes != f->bytes ? "its size differs" : "its sha256 differs");
            ok = false;
        }
    }
    if (rec.present)
        fprintf(manifest, "%s\n", rec.line);
    run_record_free(&rec);
    return ok;
}

/* The first frame's pose (as cmd_render.c's step_frame poses frame 0):
 * the animation at --time, and the views of a camera it moves. */
static bool pose_first_frame(const render_options *o, mvr_scene *scene, mvr_view_set **views)
{
    render_animation anim;
    if (!render_output_choose_animation(o, scene, &anim))
        return false;
    if (!anim.applied)
        return true;
    if (mvr_scene_apply_animation(scene, anim.index, o->time, o->loop ? MVR_ANIMATION_LOOP : MVR_ANIMATION_CLAMP) !=
        MVR_OK) {
        fprintf(stderr, "mvr render: animation %s at %g s: %s\n", anim.label, o->time, mvr_scene_last_error(scene));
        return false;
    }
    if (!o->scene_file ||
        !(o->camera >= 0 || (o->camera == CLI_CAMERA_IF_ANY && mvr_scene_camera_node_count(scene) > 0)))
        return true;
    mvr_node_id node = mvr_scene_camera_node(scene, o->camera >= 0 ? (uint32_t)o->camera : 0);
    mvr_view_set *posed = NULL;
    mvr_error err;
    if (node.id &&
        mvr_view_set_from_camera(scene, node, mvr_view_set_count(*views), o->ipd, &posed, &err) != MVR_OK) {
        fprintf(stderr, "mvr render: the camera at %g s: %s\n", o->time, err.message);
        return false;
    }
    if (posed) {
        mvr_view_set_destroy(*views);
        *views = posed;
    }
    return true;
}

/* The contact sheet from the first frame's written view images. */
static bool write_sheet(const render_options *o, uint32_t n)
{
    render_sheet sheet;
    if (!render_sheet_create(&sheet, n, o->width, o->height)) {
        fprintf(stderr, "mvr render: out of memory for the contact sheet\n");
        return false;
    }
    uint8_t *flipped = malloc((size_t)o->width * o->height * 4);
    bool ok = flipped != NULL;
    for (uint32_t k = 0; ok && k < n; ++k) {
        char name[512], path[8192];
        dataset_file_name(name, sizeof name, o, "view", "png", k);
        run_format(path, sizeof path, "%s/%s", o->out_dir, name);
        mvr_image_data img;
        mvr_error err;
        if (mvr_image_read(path, MVR_PIXEL_U8, &img, &err) != MVR_OK) {
            fprintf(stderr, "mvr render: %s\n", err.message);
            ok = false;
            break;
        }
        ok = img.width == o->width && img.height == o->height;
        size_t row = (size_t)o->width * 4;
        for (uint32_t y = 0; ok && y < o->height; ++y) /* rows bottom-up, as read back from the GL */
            memcpy(flipped + (o->height - 1 - y) * row, (const uint8_t *)img.pixels + y * row, row);
        if (ok)
            render_sheet_put(&sheet, k, flipped, o->width, o->height);
        else
            fprintf(stderr, "mvr render: %s is %ux%u, not %ux%u\n", path, img.width, img.height, o->width, o->height);
        mvr_image_free(&img);
    }
    char path[8192];
    run_format(path, sizeof path, "%s/contact_sheet.png", o->out_dir);
    mvr_image_view view = {sheet.width, sheet.height, MVR_PIXEL_U8, false, sheet.pixels};
    mvr_error err;
    if (ok && mvr_image_write(path, &view, &err) != MVR_OK) {
        fprintf(stderr, "mvr render: %s\n", err.message);
        ok = false;
    }
    free(flipped);
    free(sheet.pixels);
    return ok;
}

/* One file's own files, as a plain run writes them after its views. */
static bool write_file_level(const render_options *base, const char *file, const char *out_dir)
{
    render_options o = *base;
    if (file)
        o.scene_file = file;
    o.out_dir = out_dir;
    cli_scene_options so = {.demo = o.demo, .scene_file = o.scene_file, .camera = o.camera, .layout = o.layout,
                            .ipd = o.ipd, .framing = &o.framing, .gltf_scene = o.gltf_scene, .views = o.views,
                            .width = o.width, .height = o.height, .logger = o.context.logger, .strict = o.strict,
                            .memory_budget = o.memory_budget, .given_views = o.camera_views,
                            .given_view_count = o.camera_count};
    mvr_scene *scene = NULL;
    mvr_view_set *views = NULL;
    dataset_views d = {0};
    uint32_t variant = 0;
    bool ok = cli_load_scene("mvr render", &so, &scene, &views) == MVR_EXIT_OK;
    if (ok && o.variant)
        ok = cli_find_variant("mvr render", o.scene_file, scene, o.variant, &variant) &&
             mvr_scene_select_variant(scene, variant) == MVR_OK;
    ok = ok && pose_first_frame(&o, scene, &views);
    uint32_t n = ok ? mvr_view_set_count(views) : 0;
    if (ok && (o.outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH)))
        o.depth_png_scale = render_aovs_depth_scale(scene, views);
    ok = ok && write_sheet(&o, n) && render_output_write_cameras(&o, views, n) &&
         dataset_views_capture(&d, &o, views, n, scene) && dataset_write_transforms(&o, &d);
    if (ok && (o.outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_IDS)))
        ok = render_aovs_write_ids(o.out_dir, scene);
    if (ok && o.colmap)
        ok = dataset_write_colmap(&o, &d);
    if (ok && (o.outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_IDS)))
        ok = dataset_write_coco(&o, &d, scene);
    dataset_views_free(&d);
    mvr_view_set_destroy(views);
    mvr_scene_destroy(scene);
    return ok;
}

/* --merge DIR [--quiet]: DIR, or NULL (printed) for anything else. */
static const char *merge_args(int argc, char **argv, bool *quiet)
{
    const char *dir = NULL;
    for (int k = 1; k < argc; ++k) {
        if (strcmp(argv[k], "--merge") == 0 && k + 1 < argc && !dir) {
            dir = argv[++k];
        } else if (strcmp(argv[k], "--quiet") == 0 || strcmp(argv[k], "-q") == 0) {
            *quiet = true;
        } else {
            fprintf(stderr, "mvr render: --merge DIR takes no other option but --quiet (got '%s'): the run's "
                            "options are its plan's\n", argv[k]);
            return NULL;
        }
    }
    if (!dir)
        fprintf(stderr, "mvr render: --merge needs a value (DIR)\n");
    return dir;
}

/* Checks every unit (their records into DIR/manifest.jsonl, in unit order)
 * and writes the file-level files of each file whose units are all done;
 * the count of files left without them. */
static uint32_t merge_files(const char *dir, const render_options *o, const run_plan *p, FILE *manifest,
                            bool *bad, uint32_t *units_bad)
{
    for (uint32_t u = 0; u < p->unit_count; ++u)
        if (!check_unit(dir, p, u, manifest)) {
            bad[p->units[u].file] = true;
            ++*units_bad;
        }
    uint32_t left = 0;
    for (uint32_t k = 0; k < p->file_count; ++k) {
        char out[8192];
        run_format(out, sizeof out, "%s%s%s", dir, p->dirs[k][0] ? "/" : "", p->dirs[k]);
        if (!bad[k] && !write_file_level(o, p->files[k], out))
            bad[k] = true;
        left += bad[k];
    }
    return left;
}

/* The summary: on stderr naming the files left without their files, or
 * on stdout unless quiet. */
static void print_merge(const char *dir, const run_plan *p, const bool *bad, uint32_t units_bad, uint32_t left,
                        bool quiet)
{
    if (!left && !units_bad) {
        if (!quiet)
            printf("mvr render: --merge %s: %u unit%s of %u file%s done and checked; the run's files and "
                   "manifest.jsonl written\n", dir, p->unit_count, p->unit_count == 1 ? "" : "s", p->file_count,
                   p->file_count == 1 ? "" : "s");
        return;
    }
    fprintf(stderr, "mvr render: --merge %s: %u of %u units not done or damaged; the run's files written for %u "
                    "of %u files, not for:", dir, units_bad, p->unit_count, p->file_count - left, p->file_count);
    for (uint32_t k = 0; k < p->file_count; ++k)
        if (bad[k])
            fprintf(stderr, " %s", p->files[k] ? p->files[k] : "the demo");
    fputc('\n', stderr);
}

int run_merge_main(int argc, char **argv)
{
    bool quiet = false;
    const char *dir = merge_args(argc, argv, &quiet);
    if (!dir)
        return MVR_EXIT_USAGE;
    int pargc = 0;
    char **pargv = plan_argv(dir, quiet, &pargc);
    if (!pargv)
        return MVR_EXIT_FAILURE;
    render_options o;
    render_inputs in;
    memset(&in, 0, sizeof in);
    run_plan p;
    memset(&p, 0, sizeof p);
    int rc = render_options_parse(pargc, pargv, &o, &in);
    if (rc != MVR_EXIT_OK)
        fprintf(stderr, "mvr render: --merge %s: the options of its plan do not parse here (above)\n", dir);
    else if (!run_plan_make(&o, &in, &p))
        rc = MVR_EXIT_FAILURE;
    else
        rc = run_plan_settle(dir, &p);
    bool *bad = rc == MVR_EXIT_OK ? calloc(p.file_count, sizeof *bad) : NULL;
    cli_write_file manifest;
    char path[8192], why[8400];
    run_format(path, sizeof path, "%s/manifest.jsonl", dir);
    if (rc == MVR_EXIT_OK && (!bad || !cli_write_open(&manifest, path, why, sizeof why))) {
        fprintf(stderr, "mvr render: %s\n", bad ? why : "out of memory");
        rc = MVR_EXIT_FAILURE;
    }
    if (rc == MVR_EXIT_OK) {
        uint32_t units_bad = 0, left = merge_files(dir, &o, &p, manifest.f, bad, &units_bad);
        if (!cli_write_close(&manifest, why, sizeof why)) {
            fprintf(stderr, "mvr render: %s\n", why);
            rc = MVR_EXIT_FAILURE;
        }
        print_merge(dir, &p, bad, units_bad, left, quiet);
        if (left || units_bad)
            rc = MVR_EXIT_FAILURE;
    }
    free(bad);
    run_plan_free(&p);
    render_files_free(&in.files);
    camera_file_free(&in.cameras);
    free(in.plan_args);
    for (int k = 0; k < pargc; ++k)
        free(pargv[k]);
    free(pargv);
    return rc;
}
