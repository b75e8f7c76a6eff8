/* COCO-style instance annotations of a run (dataset.h), after every view is written.
 *
 * The format is COCO's object-detection "Data format" (https://cocodataset.org/#format-data):
 * top level info, licenses, images (id, file_name, width, height), categories (id, name,
 * supercategory) and annotations (id, image_id, category_id, segmentation, area, bbox [x, y,
 * width, height] in pixels from the image's top-left corner, iscrowd). The segmentation is
 * uncompressed RLE {"counts": [...], "size": [h, w]} as pycocotools reads it (PythonAPI
 * pycocotools/mask.py and common/maskApi.h: "RLE is a simple yet efficient format for storing
 * binary masks. RLE first divides a vector (or vectorized image) into a series of piecewise
 * constant regions and then for each piece simply stores the length of that piece"; the vector
 * is the mask in column-major (Fortran) order, and the counts start with the number of zeros,
 * 0 when the mask begins with a one; maskApi.c's rleEncode ends with the last piece's length).
 *
 * The masks come from the views' own ids_VVVV.npy (render_aovs.c), one view at a time: channel 0
 * (node) gives instances.json, one annotation per node a view sees; channel 1 (mesh) gives
 * instances_mesh.json, one per mesh. Both files are written as the views are read, so memory is
 * one view's IDs and its runs, plus a few words per node of the scene. */
#define _POSIX_C_SOURCE 200809L
#include "dataset.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_write.h"
#include "json.h"
#include "render_aovs.h"
#include "render_output.h"

enum { COCO_BY_NODE, COCO_BY_MESH, COCO_KINDS };

/* one id's pixels in the view being read */
typedef struct coco_stat {
    uint32_t area;
    uint32_t y0, y1, x0, x1;  /* bounds, inclusive */
    uint32_t runs;            /* pieces of ones in column-major order */
    uint32_t last_end;        /* column-major index one past its last pixel so far */
    size_t first, fill;       /* its counts in coco_file.counts */
} coco_stat;

/* one annotation file: instances of node ids (channel 0) or mesh ids (channel 1) */
typedef struct coco_file {
    const char *name;
    uint32_t id_count;        /* ids run 1..id_count */
    cli_write_file out;
    bool open;
    json_writer jw;
    uint64_t next_annotation;
    coco_stat *stat;          /* id_count + 1 */
    uint32_t *visible;        /* the ids this view shows, id_count at most */
    uint32_t visible_count;
    uint32_t *counts;         /* every visible id's RLE counts, one after another */
    size_t counts_cap;
} coco_file;

typedef struct coco_pass {
    const render_options *o;
    const dataset_views *d;
    const mvr_scene *scene;
    coco_file files[COCO_KINDS];
    uint32_t *planes[COCO_KINDS]; /* this view's node and mesh ids, row-major, rows top to bottom */
    uint32_t *row;                /* one row of the .npy: w x 4 */
    char why[8800];
} coco_pass;

/* View k's ids_VVVV.npy into the node and mesh planes; false with why when the file is not the
 * array mvr wrote for this run (header byte for byte, exact length) or names an id the scene
 * does not have. */
static bool read_ids(coco_pass *s, uint32_t k)
{
    const render_options *o = s->o;
    uint32_t w = o->width, h = o->height;
    char name[256], path[4400];
    dataset_file_name(name, sizeof name, o, "ids", "npy", k);
    snprintf(path, sizeof path, "%s/%s", o->out_dir, name);
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(s->why, sizeof s->why, "cannot read %s: %s", path, strerror(errno));
        return false;
    }
    char want[256], got[256];
    size_t head = render_aovs_npy_header(want, sizeof want, MVR_OUTPUT_IDS, h, w);
    bool ok = head && fread(got, 1, head, f) == head && memcmp(got, want, head) == 0;
    if (!ok) {
        fclose(f);
        snprintf(s->why, sizeof s->why, "%s is not the uint32 %u x %u x 4 ID array mvr wrote", path, h, w);
        return false;
    }
    for (uint32_t y = 0; ok && y < h; ++y) {
        ok = fread(s->row, 4 * sizeof *s->row, w, f) == w;
        for (uint32_t x = 0; ok && x < w; ++x)
            for (int c = 0; c < COCO_KINDS; ++c) {
                uint32_t id = s->row[(size_t)x * 4 + (size_t)c];
                if (id > s->files[c].id_count) {
                    snprintf(s->why, sizeof s->why, "%s: pixel (%u, %u) names %s %u; the scene has %u", path, x, y,
                             c == COCO_BY_NODE ? "node" : "mesh", id, s->files[c].id_count);
                    fclose(f);
                    return false;
                }
                s->planes[c][(size_t)y * w + x] = id;
            }
    }
    int extra = ok ? fgetc(f) : EOF;
    fclose(f);
    if (!ok || extra != EOF) {
        snprintf(s->why, sizeof s->why, "%s: %s", path, ok ? "bytes after its array" : "truncated");
        return false;
    }
    return true;
}

static int compare_ids(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* Pass 1 over the view in column-major order (index x * h + y): each id's area, bounds and
 * number of runs; then room for its counts (a zeros count and a ones count per run, and the
 * trailing zeros). */
static bool measure(coco_file *cf, const uint32_t *plane, uint32_t w, uint32_t h, char *why, size_t why_size)
{
    cf->visible_count = 0;
    for (uint32_t x = 0; x < w; ++x)
        for (uint32_t y = 0; y < h; ++y) {
            uint32_t id = plane[(size_t)y * w + x];
            if (!id)
                continue;
            coco_stat *st = &cf->stat[id];
            uint32_t p = x * h + y; /* w * h <= 2^28 (the CLI's size limit) */
            if (!st->area) {
                cf->visible[cf->visible_count++] = id;
                st->x0 = x, st->y0 = y, st->y1 = y;
            }
            if (!st->area || st->last_end != p)
                st->runs++;
            st->x1 = x;
            st->y0 = y < st->y0 ? y : st->y0;
            st->y1 = y > st->y1 ? y : st->y1;
            st->area++;
            st->last_end = p + 1;
        }
    qsort(cf->visible, cf->visible_count, sizeof *cf->visible, compare_ids);
    size_t total = 0;
    for (uint32_t i = 0; i < cf->visible_count; ++i) {
        coco_stat *st = &cf->stat[cf->visible[i]];
        st->first = st->fill = total;
        total += 2 * (size_t)st->runs + 1; /* runs <= pixels / 2 + 1: no overflow */
        st->last_end = 0;
    }
    if (total > cf->counts_cap) {
        uint32_t *grown = realloc(cf->counts, total * sizeof *grown);
        if (!grown) {
            snprintf(why, why_size, "out of memory for %zu run lengths of %s", total, cf->name);
            return false;
        }
        cf->counts = grown, cf->counts_cap = total;
    }
    return true;
}

/* Pass 2: each visible id's counts, zeros first. */
static void encode(coco_file *cf, const uint32_t *plane, uint32_t w, uint32_t h)
{
    for (uint32_t x = 0; x < w; ++x)
        for (uint32_t y = 0; y < h; ++y) {
            uint32_t id = plane[(size_t)y * w + x];
            if (!id)
                continue;
            coco_stat *st = &cf->stat[id];
            uint32_t p = x * h + y;
            if (st->fill == st->first || st->last_end != p) {
                cf->counts[st->fill++] = p - st->last_end; /* the zeros before this run (0 at index 0) */
                cf->counts[st->fill++] = 0;
            }
            cf->counts[st->fill - 1]++;
            st->last_end = p + 1;
        }
    uint32_t pixels = w * h;
    for (uint32_t i = 0; i < cf->visible_count; ++i) {
        coco_stat *st = &cf->stat[cf->visible[i]];
        if (st->last_end < pixels)
            cf->counts[st->fill++] = pixels - st->last_end;
    }
}

/* "key": [a, b, c] on one line (the writer puts each member on its own line otherwise; an RLE
 * has thousands) */
static void inline_uints(json_writer *jw, const char *key, const uint32_t *values, size_t n)
{
    json_begin_array(jw, key);
    for (size_t i = 0; i < n; ++i)
        fprintf(jw->out, i ? ",%u" : "%u", values[i]);
    jw->need_comma[jw->depth] = false; /* nothing went through the writer: it closes the array in place */
    json_end_array(jw);
}

static void write_annotations(coco_pass *s, int kind, uint32_t view)
{
    coco_file *cf = &s->files[kind];
    json_writer *jw = &cf->jw;
    uint32_t size[2] = {s->o->height, s->o->width};
    for (uint32_t i = 0; i < cf->visible_count; ++i) {
        uint32_t id = cf->visible[i];
        coco_stat *st = &cf->stat[id];
        uint32_t category = kind == COCO_BY_MESH ? id : mvr_scene_node_mesh(s->scene, (mvr_node_id){id}).id;
        uint32_t bbox[4] = {st->x0, st->y0, st->x1 - st->x0 + 1, st->y1 - st->y0 + 1};
        json_begin_object(jw, NULL);
        json_int(jw, "id", (long long)++cf->next_annotation);
        json_int(jw, "image_id", (long long)view + 1);
        json_int(jw, "category_id", category);
        inline_uints(jw, "bbox", bbox, 4);
        json_int(jw, "area", st->area);
        json_int(jw, "iscrowd", 0);
        json_begin_object(jw, "segmentation");
        inline_uints(jw, "counts", cf->counts + st->first, st->fill - st->first);
        inline_uints(jw, "size", size, 2);
        json_end_object(jw);
        if (kind == COCO_BY_NODE) {
            json_int(jw, "mvr_node_id", id);
            json_string(jw, "mvr_node_name", mvr_scene_node_name(s->scene, (mvr_node_id){id}));
        } else {
            json_int(jw, "mvr_mesh_id", id);
        }
        json_end_object(jw);
        memset(st, 0, sizeof *st); /* ready for the next view */
    }
}

/* info, licenses, images and categories; annotations opened, filled view by view */
static void write_head(coco_pass *s, coco_file *cf, const char *what)
{
    const render_options *o = s->o;
    json_writer *jw = &cf->jw;
    json_begin_object(jw, NULL);
    json_begin_object(jw, "info");
    json_string(jw, "description", what);
    json_string(jw, "version", "1.0");
    json_string(jw, "contributor", "mvr render");
    json_end_object(jw);
    json_begin_array(jw, "licenses");
    json_end_array(jw);
    json_begin_array(jw, "images");
    for (uint32_t k = 0; k < s->d->n; ++k) {
        char image[4096];
        render_output_view_file(image, sizeof image, o, k, o->frames_set ? 0 : -1);
        const char *slash = strrchr(image, '/');
        json_begin_object(jw, NULL);
        json_int(jw, "id", (long long)k + 1);
        json_string(jw, "file_name", slash ? slash + 1 : image);
        json_int(jw, "width", o->width);
        json_int(jw, "height", o->height);
        json_end_object(jw);
    }
    json_end_array(jw);
    json_begin_array(jw, "categories");
    uint32_t meshes = s->files[COCO_BY_MESH].id_count;
    for (uint32_t k = 1; k <= meshes; ++k) {
        const char *mesh = mvr_scene_mesh_name(s->scene, (mvr_mesh_id){k});
        char fallback[32];
        snprintf(fallback, sizeof fallback, "mesh_%u", k);
        json_begin_object(jw, NULL);
        json_int(jw, "id", k);
        json_string(jw, "name", mesh && *mesh ? mesh : fallback);
        json_string(jw, "supercategory", "mesh");
        json_end_object(jw);
    }
    json_end_array(jw);
    json_begin_array(jw, "annotations");
}

static bool open_files(coco_pass *s)
{
    static const char *const names[COCO_KINDS] = {"instances.json", "instances_mesh.json"};
    static const char *const what[COCO_KINDS] = {
        "mvr render: one instance per node a view sees, category its mesh",
        "mvr render: one instance per mesh a view sees (every node drawing it)"};
    char dir[4096], path[4096 + 32];
    snprintf(dir, sizeof dir, "%s/annotations", s->o->out_dir);
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        snprintf(s->why, sizeof s->why, "cannot create %s: %s", dir, strerror(errno));
        return false;
    }
    for (int c = 0; c < COCO_KINDS; ++c) {
        coco_file *cf = &s->files[c];
        cf->name = names[c];
        cf->stat = calloc((size_t)cf->id_count + 1, sizeof *cf->stat);
        cf->visible = calloc((size_t)cf->id_count + 1, sizeof *cf->visible);
        if (!cf->stat || !cf->visible) {
            snprintf(s->why, sizeof s->why, "out of memory for %u ids of %s", cf->id_count, cf->name);
            return false;
        }
        snprintf(path, sizeof path, "%s/%s", dir, names[c]);
        if (!cli_write_open(&cf->out, path, s->why, sizeof s->why))
            return false;
        cf->open = true;
        cf->jw = (json_writer){.out = cf->out.f};
        write_head(s, cf, what[c]);
    }
    return true;
}

/* closes (renamed into place) when ok, else abandons; frees the file's memory */
static bool close_files(coco_pass *s, bool ok)
{
    for (int c = 0; c < COCO_KINDS; ++c) {
        coco_file *cf = &s->files[c];
        if (cf->open && ok) {
            json_end_array(&cf->jw);
            json_end_object(&cf->jw);
            ok = cli_write_close(&cf->out, s->why, sizeof s->why);
        } else if (cf->open) {
            cli_write_abandon(&cf->out);
        }
        free(cf->stat);
        free(cf->visible);
        free(cf->counts);
    }
    return ok;
}

bool dataset_write_coco(const render_options *o, const dataset_views *d, const mvr_scene *scene)
{
    uint32_t files = o->output_files ? o->output_files : RENDER_AOV_FILES_DEFAULT;
    if (!(files & RENDER_AOV_NPY)) {
        if (!o->quiet)
            fprintf(stderr, "mvr render: warning: no annotations/instances.json: they are read from ids_VVVV.npy "
                            "(add npy to --output-files)\n");
        return true;
    }
    mvr_scene_info info;
    mvr_scene_get_info(scene, &info);
    coco_pass s = {.o = o, .d = d, .scene = scene};
    s.files[COCO_BY_NODE].id_count = info.nodes;
    s.files[COCO_BY_MESH].id_count = info.meshes;
    size_t pixels = (size_t)o->width * o->height;
    s.row = malloc(((size_t)o->width ? o->width : 1) * 4 * sizeof *s.row);
    for (int c = 0; c < COCO_KINDS; ++c)
        s.planes[c] = malloc((pixels ? pixels : 1) * sizeof *s.planes[c]);
    bool ok = s.row && s.planes[0] && s.planes[1];
    if (!ok)
        snprintf(s.why, sizeof s.why, "out of memory for a %u x %u view's IDs", o->width, o->height);
    ok = ok && open_files(&s);
    for (uint32_t k = 0; ok && k < d->n; ++k) {
        ok = read_ids(&s, k);
        for (int c = 0; ok && c < COCO_KINDS; ++c) {
            ok = measure(&s.files[c], s.planes[c], o->width, o->height, s.why, sizeof s.why);
            if (ok) {
                encode(&s.files[c], s.planes[c], o->width, o->height);
                write_annotations(&s, c, k);
            }
        }
    }
    ok = close_files(&s, ok);
    if (!ok)
        fprintf(stderr, "mvr render: annotations: %s\n", s.why);
    free(s.row);
    free(s.planes[0]);
    free(s.planes[1]);
    return ok;
}
