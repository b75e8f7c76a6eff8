/* COLMAP's text model of a run (dataset.h), after every view is written.
 *
 * The format is COLMAP's "Output Format" page (https://colmap.github.io/format.html#text-format):
 * cameras.txt "CAMERA_ID MODEL WIDTH HEIGHT PARAMS[]" (PINHOLE: fx fy cx cy); images.txt two lines
 * per image, "IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME" (the world-to-camera rotation as a
 * Hamilton quaternion and translation, camera x right, y down, looking along +Z) then "POINTS2D[]
 * as (X, Y, POINT3D_ID)", -1 for none; points3D.txt "POINT3D_ID X Y Z R G B ERROR TRACK[] as
 * (IMAGE_ID, POINT2D_IDX)", POINT2D_IDX 0-based in that image's list. Pixel coordinates put the
 * centre of the top-left pixel at (0.5, 0.5), as mvr_view_camera's cx, cy do.
 *
 * The points come from the views' own files, one view at a time, with no hook into rendering:
 * pass 1 reads each depth_VVVV.npy and image, samples a few pixels on smooth surfaces (depth > 0
 * and within a slope's tolerance of their 8 neighbours), unprojects them with the view's camera
 * and takes their colour, and keeps a coarse depth per view (the min and max of each block of
 * pixels); pass 2 projects each point into every other view and keeps the view when the point
 * lands inside it on a block whose depths are smooth and agree with the point's depth. */
#define _POSIX_C_SOURCE 200809L
#include "dataset.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_write.h"
#include "mvr/mvr_image.h"
#include "render_aovs.h"
#include "render_output.h"

#define POINTS_PER_VIEW 20u
#define MAX_POINTS 100000u
#define MAX_OBSERVATIONS 4000000u /* bounds the tracks: fewer points per view past ~450 views */
#define COARSE_SIDE 96u           /* a view's coarse depth: at most this many blocks a side */

typedef struct point3d {
    double x[3];
    uint8_t rgb[3];
    uint32_t first, count; /* its observations */
} point3d;

typedef struct observation {
    uint32_t view, index; /* index: POINT2D_IDX in the view's list */
    uint32_t point;       /* its point's (0-based; POINT3D_ID - 1) */
    double u, v;
} observation;

typedef struct coarse_depth {
    uint32_t cols, rows, step;
    float *lo, *hi; /* per block: the least and greatest depth; lo = INFINITY where a pixel has none */
} coarse_depth;

typedef struct points_pass {
    const render_options *o;
    const dataset_views *d;
    coarse_depth *coarse;  /* per view */
    point3d *points;
    uint32_t point_count, point_cap;
    observation *obs;
    uint32_t obs_count, obs_cap;
    uint32_t *per_view;    /* 2D points of each view */
    char why[8800];
} points_pass;

/* A float32 H x W depth .npy as render_aovs.c writes it (its header byte
 * for byte: render_aovs_npy_header), into a new array; false with why. */
static bool read_depth_npy(const char *path, uint32_t w, uint32_t h, float **out, char *why, size_t why_size)
{
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(why, why_size, "cannot read %s: %s", path, strerror(errno));
        return false;
    }
    char want[256], got[256];
    size_t head = render_aovs_npy_header(want, sizeof want, MVR_OUTPUT_DEPTH, h, w);
    bool ok = head && fread(got, 1, head, f) == head && memcmp(got, want, head) == 0;
    if (!ok) {
        fclose(f);
        snprintf(why, why_size, "%s is not the float32 %u x %u depth array mvr wrote", path, h, w);
        return false;
    }
    size_t count = (size_t)w * h; /* w, h <= 16384: no overflow */
    float *depth = malloc(count * sizeof *depth);
    int extra = EOF;
    ok = depth && fread(depth, sizeof *depth, count, f) == count && (extra = fgetc(f)) == EOF;
    fclose(f);
    if (!ok) {
        free(depth);
        snprintf(why, why_size, "%s: %s", path, !depth ? "out of memory" : extra != EOF ? "bytes after its array"
                                                                                         : "truncated");
        return false;
    }
    *out = depth;
    return true;
}

/* the largest depth step between neighbouring pixels a smooth surface at depth z makes:
 * a pixel spans z / f, and a surface up to ~76 degrees off the view changes by 4 times that */
static double slope_tolerance(double z, double f, double pixels)
{
    return z * (0.003 + 4.0 * pixels / f);
}

static bool make_coarse(coarse_depth *c, const float *depth, uint32_t w, uint32_t h)
{
    uint32_t side = w > h ? w : h;
    c->step = (side + COARSE_SIDE - 1) / COARSE_SIDE;
    c->cols = (w + c->step - 1) / c->step;
    c->rows = (h + c->step - 1) / c->step;
    size_t blocks = (size_t)c->cols * c->rows;
    c->lo = malloc(blocks * sizeof *c->lo);
    c->hi = malloc(blocks * sizeof *c->hi);
    if (!c->lo || !c->hi)
        return false;
    for (size_t b = 0; b < blocks; ++b)
        c->lo[b] = INFINITY, c->hi[b] = 0.0f;
    bool *empty = calloc(blocks, sizeof *empty);
    if (!empty)
        return false;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            size_t b = (size_t)(y / c->step) * c->cols + x / c->step;
            float z = depth[(size_t)y * w + x];
            if (!(z > 0.0f) || !isfinite(z)) {
                empty[b] = true;
                continue;
            }
            c->lo[b] = fminf(c->lo[b], z);
            c->hi[b] = fmaxf(c->hi[b], z);
        }
    for (size_t b = 0; b < blocks; ++b)
        if (empty[b])
            c->lo[b] = INFINITY; /* a block with a hole is an edge: no visibility decided there */
    free(empty);
    return true;
}

/* splitmix64's finaliser: the sample pixels, the same every run */
static uint64_t mix(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/* the world point pixel (x, y) at depth z sees (its centre, COLMAP's x + 0.5) */
static void unproject(const mvr_view_camera *cam, double u, double v, double z, double out[3])
{
    /* OpenCV camera (X, Y, Z) is the OpenGL camera's (X, -Y, -Z) */
    double gl[3] = {(u - cam->cx) / cam->fx * z, -(v - cam->cy) / cam->fy * z, -z};
    const double *m = cam->camera_to_world;
    for (int i = 0; i < 3; ++i)
        out[i] = m[i] * gl[0] + m[4 + i] * gl[1] + m[8 + i] * gl[2] + m[12 + i];
}

/* pixel coordinates and depth of a world point in a view; false behind it */
static bool project(const mvr_view_camera *cam, const double p[3], double *u, double *v, double *z)
{
    const double *m = cam->world_to_camera;
    double gl[3];
    for (int i = 0; i < 3; ++i)
        gl[i] = m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i];
    *z = -gl[2];
    if (!(*z > 0))
        return false;
    *u = cam->fx * gl[0] / *z + cam->cx;
    *v = cam->fy * -gl[1] / *z + cam->cy;
    return true;
}

static bool smooth_pixel(const float *depth, uint32_t w, uint32_t h, uint32_t x, uint32_t y, double f)
{
    if (x == 0 || y == 0 || x + 1 >= w || y + 1 >= h)
        return false;
    double z = depth[(size_t)y * w + x], tol = slope_tolerance(z, f, 1.0);
    for (uint32_t ny = y - 1; ny <= y + 1; ++ny)
        for (uint32_t nx = x - 1; nx <= x + 1; ++nx) {
            double n = depth[(size_t)ny * w + nx];
            if (!(n > 0) || fabs(n - z) > tol)
                return false;
        }
    return true;
}

static bool add_observation(points_pass *s, uint32_t view, double u, double v)
{
    if (s->obs_count == s->obs_cap) {
        uint32_t cap = s->obs_cap ? s->obs_cap * 2 : 4096;
        observation *grown = realloc(s->obs, (size_t)cap * sizeof *grown);
        if (!grown)
            return false;
        s->obs = grown, s->obs_cap = cap;
    }
    s->obs[s->obs_count++] = (observation){view, s->per_view[view]++, 0, u, v};
    return true;
}

/* Pass 1 for view k: its coarse depth, and up to `quota` points with their colour. */
static bool sample_view(points_pass *s, uint32_t k, uint32_t quota)
{
    const render_options *o = s->o;
    const mvr_view_camera *cam = &s->d->cams[k];
    char name[256], path[4400], image[4096];
    dataset_file_name(name, sizeof name, o, "depth", "npy", k);
    snprintf(path, sizeof path, "%s/%s", o->out_dir, name);
    float *depth = NULL;
    if (!read_depth_npy(path, o->width, o->height, &depth, s->why, sizeof s->why))
        return false;
    render_output_view_file(image, sizeof image, o, k, o->frames_set ? 0 : -1);
    mvr_image_data color = {0};
    mvr_error err;
    bool ok = mvr_image_read(image, MVR_PIXEL_U8, &color, &err) == MVR_OK;
    if (!ok)
        snprintf(s->why, sizeof s->why, "%s", err.message);
    else if (color.width != o->width || color.height != o->height)
        ok = false, snprintf(s->why, sizeof s->why, "%s is %u x %u, not the run's %u x %u", image, color.width,
                             color.height, o->width, o->height);
    if (ok && !make_coarse(&s->coarse[k], depth, o->width, o->height))
        ok = false, snprintf(s->why, sizeof s->why, "out of memory keeping view %u's depth", k);
    uint64_t pixels = (uint64_t)o->width * o->height;
    /* a few candidates per point: most of a view may be empty */
    for (uint32_t tries = 0, got = 0; ok && got < quota && tries < quota * 64 && s->point_count < s->point_cap;
         ++tries) {
        uint64_t at = mix(((uint64_t)k << 32) | tries) % pixels;
        uint32_t x = (uint32_t)(at % o->width), y = (uint32_t)(at / o->width);
        float z = depth[at];
        if (!(z > 0.0f) || !isfinite(z) || !smooth_pixel(depth, o->width, o->height, x, y, cam->fx))
            continue;
        point3d *p = &s->points[s->point_count];
        unproject(cam, x + 0.5, y + 0.5, z, p->x);
        const uint8_t *c = (const uint8_t *)color.pixels + at * 4;
        memcpy(p->rgb, c, 3);
        p->first = s->obs_count, p->count = 0;
        s->point_count++;
        got++;
    }
    mvr_image_free(&color);
    free(depth);
    return ok;
}

/* Pass 2: the views that see point p (its source view among them). */
static bool track_point(points_pass *s, point3d *p)
{
    const dataset_views *d = s->d;
    for (uint32_t j = 0; j < d->n; ++j) {
        const mvr_view_camera *cam = &d->cams[j];
        const coarse_depth *c = &s->coarse[j];
        double u, v, z;
        if (!cam->perspective || !c->lo || !project(cam, p->x, &u, &v, &z))
            continue;
        if (!(u >= 0 && v >= 0 && u < cam->width && v < cam->height))
            continue;
        size_t b = (size_t)((uint32_t)v / c->step) * c->cols + (uint32_t)u / c->step;
        /* a smooth block, and the point within half a pixel's slope of its depths */
        double tol = slope_tolerance(z, cam->fx, 0.5);
        if (!(c->hi[b] - c->lo[b] <= slope_tolerance(z, cam->fx, c->step) && z >= c->lo[b] - tol &&
              z <= c->hi[b] + tol))
            continue;
        if (!add_observation(s, j, u, v))
            return false;
        p->count++;
    }
    return true;
}

/* Every point, tracked; points seen by one view alone are dropped when
 * there are several views (nothing to triangulate). */
static bool build_points(points_pass *s)
{
    const dataset_views *d = s->d;
    uint64_t perspective = 0;
    for (uint32_t k = 0; k < d->n; ++k)
        perspective += d->cams[k].perspective;
    if (!perspective)
        return true;
    uint64_t quota = MAX_OBSERVATIONS / (perspective * perspective);
    quota = quota < 1 ? 1 : quota > POINTS_PER_VIEW ? POINTS_PER_VIEW : quota;
    s->point_cap = (uint32_t)(perspective * quota < MAX_POINTS ? perspective * quota : MAX_POINTS);
    s->points = calloc(s->point_cap, sizeof *s->points);
    s->coarse = calloc(d->n, sizeof *s->coarse);
    s->per_view = calloc(d->n, sizeof *s->per_view);
    if (!s->points || !s->coarse || !s->per_view) {
        snprintf(s->why, sizeof s->why, "out of memory sampling %u views' points", d->n);
        return false;
    }
    for (uint32_t k = 0; k < d->n; ++k)
        if (d->cams[k].perspective && !sample_view(s, k, (uint32_t)quota))
            return false;
    uint32_t kept = 0;
    for (uint32_t i = 0; i < s->point_count; ++i) {
        point3d p = s->points[i];
        uint32_t obs_before = s->obs_count;
        p.first = s->obs_count, p.count = 0;
        if (!track_point(s, &p)) {
            snprintf(s->why, sizeof s->why, "out of memory tracking %u points", s->point_count);
            return false;
        }
        if (p.count < 2 && perspective > 1) {
            for (uint32_t o = obs_before; o < s->obs_count; ++o)
                s->per_view[s->obs[o].view]--;
            s->obs_count = obs_before;
            continue;
        }
        s->points[kept++] = p;
    }
    s->point_count = kept;
    return true;
}

/* the rotation's quaternion, w first (Shepperd's method: the largest of w, x, y, z first) */
static void quaternion_of(double r[3][3], double q[4])
{
    double tr = r[0][0] + r[1][1] + r[2][2];
    if (tr > 0) {
        double s = 2.0 * sqrt(tr + 1.0);
        q[0] = 0.25 * s, q[1] = (r[2][1] - r[1][2]) / s, q[2] = (r[0][2] - r[2][0]) / s, q[3] = (r[1][0] - r[0][1]) / s;
    } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
        double s = 2.0 * sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]);
        q[0] = (r[2][1] - r[1][2]) / s, q[1] = 0.25 * s, q[2] = (r[0][1] + r[1][0]) / s, q[3] = (r[0][2] + r[2][0]) / s;
    } else if (r[1][1] > r[2][2]) {
        double s = 2.0 * sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]);
        q[0] = (r[0][2] - r[2][0]) / s, q[1] = (r[0][1] + r[1][0]) / s, q[2] = 0.25 * s, q[3] = (r[1][2] + r[2][1]) / s;
    } else {
        double s = 2.0 * sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]);
        q[0] = (r[1][0] - r[0][1]) / s, q[1] = (r[0][2] + r[2][0]) / s, q[2] = (r[1][2] + r[2][1]) / s, q[3] = 0.25 * s;
    }
}

/* images.txt's lines of view k: the pose, then its 2D points in POINT2D_IDX order */
static void write_image(FILE *f, const points_pass *s, const uint32_t *by_view, const uint32_t *start, uint32_t k)
{
    const mvr_view_camera *cam = &s->d->cams[k];
    /* R, t of COLMAP's camera: rows 1 and 2 of the OpenGL world_to_camera negated */
    double r[3][3], t[3], q[4];
    for (int i = 0; i < 3; ++i) {
        double sign = i == 0 ? 1.0 : -1.0;
        for (int j = 0; j < 3; ++j)
            r[i][j] = sign * cam->world_to_camera[j * 4 + i];
        t[i] = sign * cam->world_to_camera[3 * 4 + i];
    }
    quaternion_of(r, q);
    char image[4096];
    render_output_view_file(image, sizeof image, s->o, k, s->o->frames_set ? 0 : -1);
    const char *name = strrchr(image, '/') ? strrchr(image, '/') + 1 : image;
    fprintf(f, "%u %.17g %.17g %.17g %.17g %.17g %.17g %.17g %u %s\n", k + 1, q[0], q[1], q[2], q[3], t[0], t[1],
            t[2], k + 1, name);
    uint32_t count = s->per_view ? s->per_view[k] : 0;
    for (uint32_t i = 0; i < count; ++i) {
        const observation *ob = &s->obs[by_view[start[k] + i]];
        fprintf(f, "%s%.17g %.17g %u", i ? " " : "", ob->u, ob->v, ob->point + 1);
    }
    fputc('\n', f);
}

static void write_model(FILE *files[3], const points_pass *s, const uint32_t *by_view, const uint32_t *start)
{
    const dataset_views *d = s->d;
    uint64_t observations = s->obs_count;
    fprintf(files[0], "# Camera list with one line of data per camera:\n#   CAMERA_ID, MODEL, WIDTH, HEIGHT, "
                      "PARAMS[]\n# Number of cameras: %u\n", d->n);
    fprintf(files[1], "# Image list with two lines of data per image:\n#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, "
                      "CAMERA_ID, NAME\n#   POINTS2D[] as (X, Y, POINT3D_ID)\n# Number of images: %u, mean "
                      "observations per image: %.6g\n", d->n, d->n ? (double)observations / d->n : 0.0);
    fprintf(files[2], "# 3D point list with one line of data per point:\n#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, "
                      "TRACK[] as (IMAGE_ID, POINT2D_IDX)\n# Number of points: %u, mean track length: %.6g\n",
            s->point_count, s->point_count ? (double)observations / s->point_count : 0.0);
    for (uint32_t k = 0; k < d->n; ++k) {
        const mvr_view_camera *cam = &d->cams[k];
        if (!cam->perspective)
            continue; /* an orthographic view has no pinhole */
        fprintf(files[0], "%u PINHOLE %u %u %.17g %.17g %.17g %.17g\n", k + 1, cam->width, cam->height, cam->fx,
                cam->fy, cam->cx, cam->cy);
        write_image(files[1], s, by_view, start, k);
    }
    for (uint32_t i = 0; i < s->point_count; ++i) {
        const point3d *p = &s->points[i];
        /* ERROR 0: each 2D point is the exact projection of its 3D point */
        fprintf(files[2], "%u %.17g %.17g %.17g %u %u %u 0", i + 1, p->x[0], p->x[1], p->x[2], p->rgb[0], p->rgb[1],
                p->rgb[2]);
        for (uint32_t o = p->first; o < p->first + p->count; ++o)
            fprintf(files[2], " %u %u", s->obs[o].view + 1, s->obs[o].index);
        fputc('\n', files[2]);
    }
}

static bool write_files(points_pass *s, const uint32_t *by_view, const uint32_t *start)
{
    char dir[4096], path[4096 + 16];
    snprintf(dir, sizeof dir, "%s/colmap", s->o->out_dir);
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "mvr render: cannot create %s: %s\n", dir, strerror(errno));
        return false;
    }
    /* each file checked, and renamed into place whole or not at all */
    cli_write_file out[3];
    FILE *files[3] = {NULL, NULL, NULL};
    static const char *const names[3] = {"cameras.txt", "images.txt", "points3D.txt"};
    char why[4200] = "";
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k) {
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        ok = cli_write_open(&out[k], path, why, sizeof why);
        files[k] = ok ? out[k].f : NULL;
    }
    if (ok)
        write_model(files, s, by_view, start);
    for (int k = 0; k < 3; ++k) {
        if (!files[k])
            continue;
        if (!ok)
            cli_write_abandon(&out[k]);
        else
            ok = cli_write_close(&out[k], why, sizeof why);
    }
    if (!ok)
        fprintf(stderr, "mvr render: %s\n", why);
    return ok;
}

static void pass_free(points_pass *s)
{
    for (uint32_t k = 0; s->coarse && k < s->d->n; ++k) {
        free(s->coarse[k].lo);
        free(s->coarse[k].hi);
    }
    free(s->coarse);
    free(s->points);
    free(s->obs);
    free(s->per_view);
}

bool dataset_write_colmap(const render_options *o, const dataset_views *d)
{
    points_pass s = {.o = o, .d = d};
    bool ok = true;
    if (o->outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH)) {
        ok = build_points(&s);
        if (!ok)
            fprintf(stderr, "mvr render: --colmap: the 3D points: %s\n", s.why);
    } else if (!o->quiet) {
        fprintf(stderr, "mvr render: warning: --colmap: points3D.txt is empty: its points come from the depth "
                        "(add --outputs depth)\n");
    }
    /* each view's 2D points in POINT2D_IDX order, and each observation's point */
    uint32_t *start = ok ? calloc(d->n + 1u, sizeof *start) : NULL;
    uint32_t *by_view = ok ? malloc(((size_t)s.obs_count + 1) * sizeof *by_view) : NULL;
    if (ok && (!start || !by_view)) {
        fprintf(stderr, "mvr render: --colmap: out of memory listing %u observations\n", s.obs_count);
        ok = false;
    }
    for (uint32_t k = 0; ok && s.per_view && k < d->n; ++k)
        start[k + 1] = start[k] + s.per_view[k];
    for (uint32_t i = 0; ok && i < s.point_count; ++i)
        for (uint32_t b = s.points[i].first; b < s.points[i].first + s.points[i].count; ++b) {
            s.obs[b].point = i;
            by_view[start[s.obs[b].view] + s.obs[b].index] = b;
        }
    if (ok)
        ok = write_files(&s, by_view, start);
    free(start);
    free(by_view);
    pass_free(&s);
    return ok;
}
