/* transforms.json as NeRF trainers read it (dataset.h).
 *
 * The fields follow the two published readers:
 * - instant-ngp, docs/nerf_dataset_tips.md and src/nerf_loader.cu
 *   (https://github.com/NVlabs/instant-ngp/blob/master/docs/nerf_dataset_tips.md): per frame
 *   file_path, transform_matrix (camera-to-world, OpenGL camera), fl_x, fl_y, cx, cy, w, h,
 *   camera_angle_x, depth_path; top level aabb_scale (a power of two, 1..128: the training box is
 *   aabb_scale times its unit cube, centred on (0.5, 0.5, 0.5)), scale and offset (a camera at p
 *   sits at p * scale + offset in that unit cube; defaults 0.33 and 0.5, which is what clipped
 *   scenes larger than 3 units), integer_depth_scale (a 16-bit depth PNG's value times it is the
 *   depth in the file's units);
 * - nerfstudio, "Data conventions" (https://docs.nerf.studio/quickstart/data_conventions.html) and
 *   nerfstudio_dataparser.py: per frame depth_file_path and mask_path (a one-channel image, 0 =
 *   ignore the pixel), top level train_filenames / val_filenames / test_filenames (its "filename"
 *   split), images sorted by name otherwise (hence view_VVVV).
 * The split is also written as the Blender synthetic dataset's files
 * transforms_train.json, transforms_val.json and transforms_test.json. */
#include "dataset.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_write.h"
#include "json.h"
#include "render_output.h"

bool dataset_views_capture(dataset_views *d, const render_options *o, const mvr_view_set *views, uint32_t n,
                           const mvr_scene *scene)
{
    memset(d, 0, sizeof *d);
    d->cams = calloc(n ? n : 1, sizeof *d->cams);
    if (!d->cams) {
        fprintf(stderr, "mvr render: out of memory keeping %u views' cameras\n", n);
        return false;
    }
    d->n = n;
    for (uint32_t k = 0; k < n; ++k)
        if (mvr_view_set_get_camera(views, k, o->width, o->height, &d->cams[k]) != MVR_OK) {
            fprintf(stderr, "mvr render: view %u has no camera to write\n", k);
            return false;
        }
    mvr_scene_info info;
    mvr_scene_get_info(scene, &info);
    d->have_bounds = true;
    for (int i = 0; i < 3; ++i) {
        d->bounds_min[i] = info.bounds_min[i];
        d->bounds_max[i] = info.bounds_max[i];
        if (!(info.bounds_min[i] <= info.bounds_max[i]) || !isfinite(info.bounds_min[i]) ||
            !isfinite(info.bounds_max[i]))
            d->have_bounds = false; /* an empty scene's bounds are inverted */
    }
    return true;
}

void dataset_views_free(dataset_views *d)
{
    free(d->cams);
    memset(d, 0, sizeof *d);
}

void dataset_file_name(char *buf, size_t size, const render_options *o, const char *prefix, const char *ext,
                       uint32_t view)
{
    render_output_file_name(buf, size, NULL, prefix, view, o->frames_set ? 0 : -1,
                            render_output_frame_digits(o->frames), ext);
}

/* floor(k * part / n) without overflow (n <= 2^32) */
static uint64_t share(uint64_t k, uint64_t part, uint64_t n)
{
    return n ? k * part / n : 0;
}

int dataset_split_of(const render_options *o, uint32_t n, uint32_t view)
{
    if (!o->split_set || n == 0)
        return 0;
    uint64_t nv = (uint64_t)llround(o->split[1] * n), nt = (uint64_t)llround(o->split[2] * n);
    if (nv > n)
        nv = n;
    if (nt > n - nv)
        nt = n - nv;
    /* val: every (n / nv)-th view; test: likewise among the rest */
    if (share(view + 1u, nv, n) > share(view, nv, n))
        return 1;
    uint64_t j = view - share(view + 1u, nv, n), m = n - nv;
    if (share(j + 1, nt, m) > share(j, nt, m))
        return 2;
    return 0;
}

/* How the file's coordinates and instant-ngp's unit cube relate. */
typedef struct placement {
    double norm_scale, norm_offset[3]; /* file = world * norm_scale + norm_offset (1, 0 unless --normalize) */
    double ngp_scale, ngp_offset[3];   /* instant-ngp's cube = file * ngp_scale + ngp_offset */
    bool have_aabb;
    double aabb_min[3], aabb_max[3];   /* the scene's bounds in the file's coordinates */
    int aabb_scale;
} placement;

/* The box of the scene (and with cameras, of the views' positions too);
 * false when it is empty. */
static bool box_of(const dataset_views *d, bool cameras, double lo[3], double hi[3])
{
    bool any = d->have_bounds;
    for (int i = 0; i < 3; ++i) {
        lo[i] = any ? d->bounds_min[i] : INFINITY;
        hi[i] = any ? d->bounds_max[i] : -INFINITY;
    }
    for (uint32_t k = 0; cameras && k < d->n; ++k) {
        for (int i = 0; i < 3; ++i) {
            double p = d->cams[k].camera_to_world[12 + i];
            lo[i] = fmin(lo[i], p);
            hi[i] = fmax(hi[i], p);
        }
        any = true;
    }
    return any;
}

/* scale, offset taking the box to one centred on 0.5 whose longest side is 1 */
static void fit_unit_cube(const double lo[3], const double hi[3], double *scale, double offset[3])
{
    double extent = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    *scale = extent > 0 && isfinite(extent) ? 1.0 / extent : 1.0;
    for (int i = 0; i < 3; ++i)
        offset[i] = 0.5 - 0.5 * (lo[i] + hi[i]) * *scale;
}

static placement place(const render_options *o, const dataset_views *d)
{
    placement p = {.norm_scale = 1.0, .ngp_scale = 1.0, .aabb_scale = 1};
    double lo[3], hi[3];
    /* --normalize: the scene and every camera into [0, 1]^3, instant-ngp's unit cube */
    if (o->normalize && box_of(d, true, lo, hi))
        fit_unit_cube(lo, hi, &p.norm_scale, p.norm_offset);
    p.have_aabb = d->have_bounds;
    for (int i = 0; i < 3 && p.have_aabb; ++i) {
        p.aabb_min[i] = d->bounds_min[i] * p.norm_scale + p.norm_offset[i];
        p.aabb_max[i] = d->bounds_max[i] * p.norm_scale + p.norm_offset[i];
    }
    /* the file's poses as they are: the scene's box fitted into instant-ngp's unit cube */
    if (!o->normalize && box_of(d, !d->have_bounds, lo, hi))
        fit_unit_cube(lo, hi, &p.ngp_scale, p.ngp_offset);
    /* aabb_scale: the least power of two whose box (centred on 0.5) holds the scene's */
    double reach = 0;
    for (int i = 0; i < 3 && p.have_aabb; ++i) {
        reach = fmax(reach, fabs(p.aabb_min[i] * p.ngp_scale + p.ngp_offset[i] - 0.5));
        reach = fmax(reach, fabs(p.aabb_max[i] * p.ngp_scale + p.ngp_offset[i] - 0.5));
    }
    while (p.aabb_scale < 128 && 2.0 * reach > p.aabb_scale * (1.0 + 1e-9))
        p.aabb_scale *= 2;
    return p;
}

static void json_vec3(json_writer *jw, const char *key, const double v[3])
{
    json_begin_array(jw, key);
    for (int i = 0; i < 3; ++i)
        json_double_exact(jw, NULL, v[i]);
    json_end_array(jw);
}

static void write_header(json_writer *jw, const render_options *o, const placement *p)
{
    json_string(jw, "convention", "NeRF (instant-ngp, nerfstudio): transform_matrix is camera-to-world with the "
                                  "OpenGL camera (x right, y up, looking along -Z); world glTF's");
    /* the world's up as the views were placed (--up; glTF's own is +Y):
     * a Z-up world (Blender's) is stated so, not turned */
    bool z_up = o->framing.up == MVR_UP_Z;
    const double up[3] = {0, z_up ? 0 : 1, z_up ? 1 : 0};
    json_vec3(jw, "up", up);
    json_string(jw, "up_axis", z_up ? "+Z (--up z: right-handed, +Z up, as Blender's)"
                                    : "+Y (glTF's world: right-handed, +Y up)");
    if (p->have_aabb) {
        json_begin_array(jw, "aabb");
        json_vec3(jw, NULL, p->aabb_min);
        json_vec3(jw, NULL, p->aabb_max);
        json_end_array(jw);
    }
    json_int(jw, "aabb_scale", p->aabb_scale);
    json_double_exact(jw, "scale", p->ngp_scale);
    json_vec3(jw, "offset", p->ngp_offset);
    json_string(jw, "scale_offset", "instant-ngp's: a point p of this file is at p * scale + offset in its unit cube "
                                    "(the scene's aabb centred on 0.5, its longest side 1 unless --normalize)");
    if (o->normalize) {
        json_begin_object(jw, "normalization");
        json_double_exact(jw, "scale", p->norm_scale);
        json_vec3(jw, "offset", p->norm_offset);
        json_string(jw, "applied", "--normalize: positions (poses, aabb, depths) are world * scale + offset, the "
                                   "scene and every camera inside [0, 1]^3");
        json_end_object(jw);
    }
    bool depth = o->outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH);
    if (depth && o->depth_png_scale > 0) /* the PNG's steps in the file's units */
        json_double_exact(jw, "integer_depth_scale", o->depth_png_scale * p->norm_scale);
}

static void write_frame(json_writer *jw, const render_options *o, const mvr_view_camera *cam, const placement *p,
                        uint32_t k)
{
    char image[4096], name[256];
    render_output_view_file(image, sizeof image, o, k, o->frames_set ? 0 : -1);
    json_begin_object(jw, NULL);
    json_string(jw, "file_path", strrchr(image, '/') ? strrchr(image, '/') + 1 : image);
    json_int(jw, "w", cam->width);
    json_int(jw, "h", cam->height);
    if (cam->perspective) {
        json_double_exact(jw, "fl_x", cam->fx);
        json_double_exact(jw, "fl_y", cam->fy);
        json_double_exact(jw, "cx", cam->cx);
        json_double_exact(jw, "cy", cam->cy);
        json_double_exact(jw, "camera_angle_x", 2.0 * atan(0.5 * cam->width / cam->fx));
    }
    if (o->outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH)) {
        dataset_file_name(name, sizeof name, o, "depth", "png", k);
        json_string(jw, "depth_file_path", name); /* nerfstudio */
        json_string(jw, "depth_path", name);      /* instant-ngp */
    }
    if (o->outputs & (MVR_OUTPUT_BIT(MVR_OUTPUT_COVERAGE) | MVR_OUTPUT_BIT(MVR_OUTPUT_IDS) |
                      MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH))) {
        dataset_file_name(name, sizeof name, o, "mask", "png", k);
        json_string(jw, "mask_path", name);
    }
    json_begin_array(jw, "transform_matrix");
    for (int r = 0; r < 4; ++r) {
        json_begin_array(jw, NULL);
        for (int c = 0; c < 4; ++c) {
            double v = cam->camera_to_world[c * 4 + r];
            if (c == 3 && r < 3)
                v = v * p->norm_scale + p->norm_offset[r];
            json_double_exact(jw, NULL, v);
        }
        json_end_array(jw);
    }
    json_end_array(jw);
    json_end_object(jw);
}

static const char *const split_names[3] = {"train", "val", "test"};

/* One file: every frame (part -1, with the split's file lists) or a split's. */
static bool write_file(const render_options *o, const dataset_views *d, const placement *p, int part)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/transforms%s%s.json", o->out_dir, part < 0 ? "" : "_",
             part < 0 ? "" : split_names[part]);
    cli_write_file out;
    char why[4200];
    if (!cli_write_open(&out, path, why, sizeof why)) {
        fprintf(stderr, "mvr render: %s\n", why);
        return false;
    }
    json_writer jw = {.out = out.f};
    json_begin_object(&jw, NULL);
    write_header(&jw, o, p);
    if (part < 0 && o->split_set) {
        for (int s = 0; s < 3; ++s) {
            char key[32], image[4096];
            snprintf(key, sizeof key, "%s_filenames", split_names[s]);
            json_begin_array(&jw, key);
            for (uint32_t k = 0; k < d->n; ++k) {
                if (dataset_split_of(o, d->n, k) != s)
                    continue;
                render_output_view_file(image, sizeof image, o, k, o->frames_set ? 0 : -1);
                json_string(&jw, NULL, strrchr(image, '/') ? strrchr(image, '/') + 1 : image);
            }
            json_end_array(&jw);
        }
    }
    json_begin_array(&jw, "frames");
    for (uint32_t k = 0; k < d->n; ++k)
        if (part < 0 || dataset_split_of(o, d->n, k) == part)
            write_frame(&jw, o, &d->cams[k], p, k);
    json_end_array(&jw);
    json_end_object(&jw);
    fputc('\n', out.f);
    if (!cli_write_close(&out, why, sizeof why)) {
        fprintf(stderr, "mvr render: %s\n", why);
        return false;
    }
    return true;
}

bool dataset_write_transforms(const render_options *o, const dataset_views *d)
{
    placement p = place(o, d);
    bool ok = write_file(o, d, &p, -1);
    for (int s = 0; s < 3 && ok && o->split_set; ++s)
        ok = write_file(o, d, &p, s);
    return ok;
}
