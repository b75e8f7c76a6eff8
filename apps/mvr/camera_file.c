/* Camera files (camera_file.h): mvr's cameras.json, NeRF's transforms.json
 * and CSV, told apart by their content, into view descriptions. Every value
 * is checked before it is used; a refusal says which view, field and line. */
#define _POSIX_C_SOURCE 200809L
#include "camera_file_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "json_read.h"

/* ------------------------------------------------------------------ JSON fields */

/* 1: present (a finite number), 0: absent, -1: refused (not a number) */
static int json_number_field(camf_report *rp, const char *where, const json_value *obj, const char *key, double *out)
{
    const json_value *v = json_member(obj, key);
    if (!v)
        return 0;
    if (v->type != JSON_NUMBER) {
        camf_refuse(rp, "%s: %s is %s, not a number", where, key, json_type_name(v->type));
        return -1;
    }
    *out = v->number;
    return 1;
}

static int json_size_field(camf_report *rp, const char *where, const json_value *obj, const char *key, uint32_t *out)
{
    double d = 0;
    int got = json_number_field(rp, where, obj, key, &d);
    if (got <= 0)
        return got;
    if (!(d >= 1 && d <= CAMERA_FILE_MAX_SIDE && d == floor(d))) {
        camf_refuse(rp, "%s: %s: %g is not an image side in pixels (a whole number, 1..%u)", where, key, d,
                    CAMERA_FILE_MAX_SIDE);
        return -1;
    }
    *out = (uint32_t)d;
    return 1;
}

/* n numbers (an array of them) into out. */
static bool json_numbers(camf_report *rp, const char *where, const char *key, const json_value *v, double *out,
                         uint32_t n)
{
    if (!v || v->type != JSON_ARRAY || v->count != n)
        return camf_refuse(rp, "%s: %s: expected an array of %u numbers%s", where, key, n, v ? "" : " (missing)");
    for (uint32_t i = 0; i < n; ++i) {
        if (v->items[i].type != JSON_NUMBER)
            return camf_refuse(rp, "%s: %s[%u] is %s, not a number", where, key, i, json_type_name(v->items[i].type));
        out[i] = v->items[i].number;
    }
    return true;
}

/* A 4x4 matrix as 4 rows of 4 numbers. */
static bool json_matrix(camf_report *rp, const char *where, const json_value *obj, const char *key, double m[4][4])
{
    const json_value *v = json_member(obj, key);
    if (!v)
        return camf_refuse(rp, "%s: %s is missing (4 rows of 4 numbers)", where, key);
    if (v->type != JSON_ARRAY || v->count != 4)
        return camf_refuse(rp, "%s: %s: expected 4 rows of 4 numbers, got %s%s", where, key, json_type_name(v->type),
                           v->type == JSON_ARRAY ? " of another length" : "");
    for (int r = 0; r < 4; ++r) {
        const json_value *row = &v->items[r];
        if (row->type != JSON_ARRAY || row->count != 4)
            return camf_refuse(rp, "%s: %s: row %d is not 4 numbers", where, key, r);
        for (int c = 0; c < 4; ++c) {
            if (row->items[c].type != JSON_NUMBER)
                return camf_refuse(rp, "%s: %s[%d][%d] is %s, not a number", where, key, r, c,
                                   json_type_name(row->items[c].type));
            m[r][c] = row->items[c].number;
        }
    }
    return true;
}

/* ------------------------------------------------------------------ mvr cameras.json */

static bool mvr_projection_from_json(camf_report *rp, const char *where, const json_value *pj, mvr_projection *p)
{
    memset(p, 0, sizeof *p);
    const json_value *type = json_member(pj, "type");
    static const char *const types[] = {"perspective", "frustum", "orthographic", "matrix"};
    int t = -1;
    for (int k = 0; type && type->type == JSON_STRING && k < 4; ++k)
        if (strcmp(type->string, types[k]) == 0)
            t = k;
    if (t < 0)
        return camf_refuse(rp, "%s: mvr_view.projection.type: expected perspective, frustum, orthographic or matrix",
                           where);
    p->type = (mvr_projection_type)t;
    static const char *const fields[][4] = {{"yfov", "aspect", NULL, NULL},
                                            {"angle_left", "angle_right", "angle_down", "angle_up"},
                                            {"xmag", "ymag", NULL, NULL},
                                            {NULL, NULL, NULL, NULL}};
    double *dst[][4] = {{&p->yfov, &p->aspect, NULL, NULL},
                        {&p->angle_left, &p->angle_right, &p->angle_down, &p->angle_up},
                        {&p->xmag, &p->ymag, NULL, NULL},
                        {NULL, NULL, NULL, NULL}};
    for (int k = 0; k < 4 && fields[t][k]; ++k)
        if (json_number_field(rp, where, pj, fields[t][k], dst[t][k]) != 1)
            return json_member(pj, fields[t][k]) ? false
                                                 : camf_refuse(rp, "%s: mvr_view.projection.%s is missing", where,
                                                               fields[t][k]);
    if (json_number_field(rp, where, pj, "znear", &p->znear) < 0 ||
        json_number_field(rp, where, pj, "zfar", &p->zfar) < 0)
        return false;
    if (p->type == MVR_PROJECTION_MATRIX) {
        double m[4][4];
        if (!json_matrix(rp, where, pj, "matrix", m))
            return false;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                p->matrix[c * 4 + r] = m[r][c];
    }
    return true;
}

/* Whether a's and b's numbers agree to about 1e-9 of their magnitude: the
 * file's matrices were written from the view with 17 digits. */
static bool close_to(const double *a, const double *b, int n)
{
    for (int i = 0; i < n; ++i)
        if (!(fabs(a[i] - b[i]) <= 1e-9 * fmax(1.0, fmax(fabs(a[i]), fabs(b[i])))))
            return false;
    return true;
}

/* mvr_view, as mvr render writes it: the view's own description, used as
 * written when it still gives the frame's camera_to_world and intrinsics
 * (or projection); false (nothing refused) when it does not. */
static bool mvr_view_agrees(camf_report *rp, const char *where, const json_value *frame, const json_value *mv,
                            uint32_t w, uint32_t h, double c2w[4][4], mvr_view_desc *out, bool *refused)
{
    *refused = true;
    mvr_view_desc v;
    memset(&v, 0, sizeof v);
    double q[4];
    if (!json_numbers(rp, where, "mvr_view.position", json_member(mv, "position"), v.position, 3) ||
        !json_numbers(rp, where, "mvr_view.orientation", json_member(mv, "orientation"), q, 4))
        return false;
    const json_value *pj = json_member(mv, "projection");
    if (!pj || pj->type != JSON_OBJECT)
        return camf_refuse(rp, "%s: mvr_view.projection: expected an object", where);
    if (!mvr_projection_from_json(rp, where, pj, &v.projection))
        return false;
    /* all zero is the library's identity; the quaternion is kept as written
     * (not normalised again), bit for bit */
    bool zero = q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0;
    double unit[4];
    if (!camf_check_position(rp, where, "mvr_view.position", v.position) ||
        (!zero && !camf_unit_quaternion(rp, where, "mvr_view.orientation", q, unit)) ||
        !camf_check_znear(rp, where, "mvr_view.projection.znear", v.projection.znear))
        return false;
    memcpy(v.orientation, q, sizeof q);
    *refused = false;
    /* the library checks the rest (angles, planes) and gives the camera back */
    mvr_view_set_desc d = {.view_count = 1, .views = &v};
    mvr_view_set *vs = NULL;
    mvr_view_camera cam;
    if (mvr_view_set_create(&d, &vs, NULL) != MVR_OK)
        return false;
    bool ok = mvr_view_set_get_camera(vs, 0, w, h, &cam) == MVR_OK;
    mvr_view_set_destroy(vs);
    double file_c2w[16], intr[4] = {0, 0, 0, 0}, proj[4][4];
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            file_c2w[c * 4 + r] = c2w[r][c];
    ok = ok && cam.width == w && cam.height == h && close_to(cam.camera_to_world, file_c2w, 16);
    if (ok && cam.perspective) {
        ok = json_number_field(rp, where, frame, "fl_x", &intr[0]) == 1 &&
             json_number_field(rp, where, frame, "fl_y", &intr[1]) == 1 &&
             json_number_field(rp, where, frame, "cx", &intr[2]) == 1 &&
             json_number_field(rp, where, frame, "cy", &intr[3]) == 1;
        double mine[4] = {cam.fx, cam.fy, cam.cx, cam.cy};
        ok = ok && close_to(mine, intr, 4);
    } else if (ok) {
        double file_proj[16];
        ok = json_member(frame, "projection") && json_matrix(rp, where, frame, "projection", proj);
        for (int r = 0; ok && r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                file_proj[c * 4 + r] = proj[r][c];
        ok = ok && close_to(cam.projection, file_proj, 16);
    }
    if (ok)
        *out = v;
    return ok;
}

static bool mvr_frame(camf_report *rp, camera_file *f, const char *where, uint32_t index, const json_value *frame)
{
    uint32_t w = 0, h = 0;
    int gw = json_size_field(rp, where, frame, "w", &w), gh = json_size_field(rp, where, frame, "h", &h);
    if (gw < 0 || gh < 0)
        return false;
    if (!gw || !gh)
        return camf_refuse(rp, "%s: %s is missing (cameras.json gives each view's image size)", where, gw ? "h" : "w");
    if (!camf_same_size(rp, f, where, index, w, h))
        return false;
    double c2w[4][4];
    if (!json_matrix(rp, where, frame, "camera_to_world", c2w))
        return false;
    mvr_view_desc *v = &f->views[index];
    const json_value *mv = json_member(frame, "mvr_view");
    if (mv) {
        if (mv->type != JSON_OBJECT)
            return camf_refuse(rp, "%s: mvr_view is %s, not an object", where, json_type_name(mv->type));
        bool refused = false;
        if (mvr_view_agrees(rp, where, frame, mv, w, h, c2w, v, &refused)) {
            f->exact++;
            return true;
        }
        if (refused)
            return false;
        if (f->edited++ == 0)
            f->first_edited = index;
        memset(v, 0, sizeof *v);
    }
    if (!camf_pose_from_matrix(rp, where, "camera_to_world", c2w, v))
        return false;
    const json_value *persp = json_member(frame, "perspective");
    if (persp && persp->type != JSON_TRUE && persp->type != JSON_FALSE)
        return camf_refuse(rp, "%s: perspective is %s, not true or false", where, json_type_name(persp->type));
    double proj[4][4];
    bool have_proj = json_member(frame, "projection") != NULL;
    if (have_proj && !json_matrix(rp, where, frame, "projection", proj))
        return false;
    if (persp && persp->type == JSON_FALSE) {
        /* orthographic: its clip matrix as given (OpenGL, z in [-1, 1]) */
        if (!have_proj)
            return camf_refuse(rp, "%s: projection is missing (an orthographic view has no pinhole intrinsics)", where);
        if (proj[0][0] == 0 || proj[1][1] == 0)
            return camf_refuse(rp, "%s: projection: a zero scale on x or y maps the view to a line", where);
        v->projection.type = MVR_PROJECTION_MATRIX;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                v->projection.matrix[c * 4 + r] = proj[r][c];
        return true;
    }
    double in[4];
    static const char *names[4] = {"fl_x", "fl_y", "cx", "cy"};
    for (int k = 0; k < 4; ++k) {
        int got = json_number_field(rp, where, frame, names[k], &in[k]);
        if (got < 0)
            return false;
        if (!got)
            return camf_refuse(rp, "%s: %s is missing (a perspective view's intrinsics: fl_x, fl_y, cx, cy)", where,
                               names[k]);
    }
    /* the near plane from an OpenGL perspective matrix: P[2][3] / (P[2][2] - 1) */
    double znear = 0;
    if (have_proj && proj[3][2] == -1.0 && proj[2][2] != 1.0) {
        double n = proj[2][3] / (proj[2][2] - 1.0);
        znear = n > 0 && n <= CAMF_MAX_ZNEAR ? n : 0;
    }
    return camf_frustum_from_pinhole(rp, where, names, in[0], in[1], in[2], in[3], w, h, znear, &v->projection);
}

/* ------------------------------------------------------------------ NeRF transforms.json */

/* The intrinsics a frame inherits from the file's top level and may override. */
typedef struct nerf_intrinsics {
    double fl_x, fl_y, cx, cy, angle_x, angle_y;
    bool has_fl_x, has_fl_y, has_cx, has_cy, has_angle_x, has_angle_y;
    uint32_t w, h;
} nerf_intrinsics;

static bool nerf_read_intrinsics(camf_report *rp, const char *where, const json_value *obj, nerf_intrinsics *in)
{
    static const char *const lens[] = {"k1", "k2", "k3", "k4", "p1", "p2"};
    for (int k = 0; k < 6; ++k) {
        double d = 0;
        int got = json_number_field(rp, where, obj, lens[k], &d);
        if (got < 0)
            return false;
        if (got && d != 0.0)
            return camf_refuse(rp, "%s: %s is %g: mvr renders an ideal pinhole, without lens distortion (undistort the "
                                   "images, or set it to 0)", where, lens[k], d);
    }
    const json_value *model = json_member(obj, "camera_model");
    if (model && (model->type != JSON_STRING ||
                  (strcmp(model->string, "OPENCV") != 0 && strcmp(model->string, "PINHOLE") != 0 &&
                   strcmp(model->string, "SIMPLE_PINHOLE") != 0))) {
        char shown[48] = "";
        if (model->type == JSON_STRING)
            camf_show_cell(shown, sizeof shown, model->string, strlen(model->string));
        return camf_refuse(
            rp, "%s: camera_model: mvr renders pinhole cameras (OPENCV, PINHOLE, SIMPLE_PINHOLE), not %s%s%s", where,
            model->type == JSON_STRING ? "'" : json_type_name(model->type), shown,
            model->type == JSON_STRING ? "'" : "");
    }
    const json_value *fisheye = json_member(obj, "is_fisheye");
    if (fisheye && fisheye->type != JSON_FALSE)
        return camf_refuse(rp, "%s: is_fisheye: mvr renders pinhole cameras, not fisheye ones", where);
    struct {
        const char *key;
        double *dst;
        bool *has;
    } fields[] = {{"fl_x", &in->fl_x, &in->has_fl_x}, {"fl_y", &in->fl_y, &in->has_fl_y},
                  {"cx", &in->cx, &in->has_cx},       {"cy", &in->cy, &in->has_cy},
                  {"camera_angle_x", &in->angle_x, &in->has_angle_x},
                  {"camera_angle_y", &in->angle_y, &in->has_angle_y}};
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; ++k) {
        int got = json_number_field(rp, where, obj, fields[k].key, fields[k].dst);
        if (got < 0)
            return false;
        if (got)
            *fields[k].has = true;
    }
    for (int k = 0; k < 2; ++k) {
        double a = k ? in->angle_y : in->angle_x;
        if ((k ? in->has_angle_y : in->has_angle_x) && !(a > 0 && a < 3.14159))
            return camf_refuse(rp, "%s: %s: %g is not a field of view (radians, 0 < angle < pi)", where,
                               k ? "camera_angle_y" : "camera_angle_x", a);
    }
    if (json_size_field(rp, where, obj, "w", &in->w) < 0 || json_size_field(rp, where, obj, "h", &in->h) < 0)
        return false;
    return true;
}

static bool nerf_frame(camf_report *rp, camera_file *f, const char *where, uint32_t index, const json_value *frame,
                       const nerf_intrinsics *top, uint32_t width, uint32_t height)
{
    nerf_intrinsics in = *top;
    if (!nerf_read_intrinsics(rp, where, frame, &in))
        return false;
    if ((in.w != 0) != (in.h != 0))
        return camf_refuse(rp, "%s: %s is given without %s", where, in.w ? "w" : "h", in.w ? "h" : "w");
    if (!camf_same_size(rp, f, where, index, in.w, in.h))
        return false;
    uint32_t w = in.w ? in.w : width, h = in.h ? in.h : height;
    /* focal lengths: fl_x / fl_y, else from the angles; one given serves both */
    double fx = in.has_fl_x ? in.fl_x : in.has_angle_x ? 0.5 * w / tan(0.5 * in.angle_x) : 0;
    double fy = in.has_fl_y ? in.fl_y : in.has_angle_y ? 0.5 * h / tan(0.5 * in.angle_y) : 0;
    bool have_x = in.has_fl_x || in.has_angle_x, have_y = in.has_fl_y || in.has_angle_y;
    if (!have_x && !have_y)
        return camf_refuse(rp, "%s: no focal length: give fl_x (pixels) or camera_angle_x (radians), at the top or in "
                               "the frame", where);
    if (!have_x)
        fx = fy;
    if (!have_y)
        fy = fx;
    double cx = in.has_cx ? in.cx : 0.5 * w, cy = in.has_cy ? in.cy : 0.5 * h;
    const char *names[4] = {in.has_fl_x ? "fl_x" : have_x ? "camera_angle_x" : "fl_y",
                            in.has_fl_y ? "fl_y" : have_y ? "camera_angle_y" : "fl_x", "cx", "cy"};
    mvr_view_desc *v = &f->views[index];
    double m[4][4];
    return json_matrix(rp, where, frame, "transform_matrix", m) &&
           camf_pose_from_matrix(rp, where, "transform_matrix", m, v) &&
           camf_frustum_from_pinhole(rp, where, names, fx, fy, cx, cy, w, h, 0, &v->projection);
}

static bool parse_json(camf_report *rp, const char *text, size_t size, uint32_t width, uint32_t height, camera_file *f)
{
    json_value root;
    char why[256];
    if (!json_read(text, size, &root, why, sizeof why))
        return camf_refuse(rp, "not valid JSON: %s", why);
    bool ok = false;
    const json_value *frames = json_member(&root, "frames");
    if (root.type != JSON_OBJECT) {
        camf_refuse(rp, "a JSON camera file is an object with \"frames\"; this one is %s", json_type_name(root.type));
        goto done;
    }
    if (!frames || frames->type != JSON_ARRAY) {
        camf_refuse(rp, "frames: %s (expected the array of views of a cameras.json or transforms.json)",
                    frames ? json_type_name(frames->type) : "missing");
        goto done;
    }
    if (frames->count == 0) {
        camf_refuse(rp, "frames (line %u) is empty: no views", frames->line);
        goto done;
    }
    if (frames->count > CAMERA_FILE_MAX_VIEWS) {
        camf_refuse(rp, "frames (line %u) holds %u views; at most %u", frames->line, frames->count,
                    CAMERA_FILE_MAX_VIEWS);
        goto done;
    }
    const json_value *first = &frames->items[0];
    bool nerf = json_member(first, "transform_matrix") != NULL;
    if (!nerf && !json_member(first, "camera_to_world")) {
        camf_refuse(rp, "view 0 (line %u): neither transform_matrix (NeRF transforms.json) nor camera_to_world (mvr "
                        "cameras.json)", first->line);
        goto done;
    }
    f->format = nerf ? "NeRF transforms.json" : "mvr cameras.json";
    f->views = calloc(frames->count, sizeof *f->views);
    if (!f->views) {
        camf_refuse(rp, "out of memory for %u views", frames->count);
        goto done;
    }
    nerf_intrinsics top;
    memset(&top, 0, sizeof top);
    if (nerf && !nerf_read_intrinsics(rp, "the top level", &root, &top))
        goto done;
    if (nerf && (top.w != 0) != (top.h != 0)) {
        camf_refuse(rp, "the top level: %s is given without %s", top.w ? "w" : "h", top.w ? "h" : "w");
        goto done;
    }
    for (uint32_t k = 0; k < frames->count; ++k) {
        char where[64];
        const json_value *frame = &frames->items[k];
        snprintf(where, sizeof where, "view %u (line %u)", k, frame->line);
        if (frame->type != JSON_OBJECT) {
            camf_refuse(rp, "%s: %s, not an object", where, json_type_name(frame->type));
            goto done;
        }
        if (!(nerf ? nerf_frame(rp, f, where, k, frame, &top, width, height) : mvr_frame(rp, f, where, k, frame)))
            goto done;
    }
    f->count = frames->count;
    ok = true;
done:
    json_read_free(&root);
    return ok;
}

/* ------------------------------------------------------------------ entry points */

bool camera_file_parse(const char *text, size_t size, uint32_t width, uint32_t height, camera_file *out, char *why,
                       size_t why_size)
{
    memset(out, 0, sizeof *out);
    camf_report rp = {why, why_size};
    if (width == 0 || height == 0 || width > CAMERA_FILE_MAX_SIDE || height > CAMERA_FILE_MAX_SIDE)
        return camf_refuse(&rp, "the size intrinsics refer to (%ux%u) is not 1..%u per side", width, height,
                           CAMERA_FILE_MAX_SIDE);
    if (size > CAMERA_FILE_MAX_BYTES)
        return camf_refuse(&rp, "%zu bytes; a camera file may have at most %u", size, CAMERA_FILE_MAX_BYTES);
    /* told by the content: JSON starts with '{' (after blanks and a BOM) */
    size_t i = size >= 3 && memcmp(text, "\xef\xbb\xbf", 3) == 0 ? 3 : 0;
    while (i < size && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n'))
        ++i;
    bool ok = i < size && (text[i] == '{' || text[i] == '[') ? parse_json(&rp, text, size, width, height, out)
                                                             : camf_parse_csv(&rp, text, size, width, height, out);
    if (!ok)
        camera_file_free(out);
    return ok;
}

bool camera_file_load(const char *path, uint32_t width, uint32_t height, camera_file *out, char *why,
                      size_t why_size)
{
    memset(out, 0, sizeof *out);
    camf_report rp = {why, why_size};
    FILE *file = fopen(path, "rb");
    if (!file)
        return camf_refuse(&rp, "cannot open it: %s", strerror(errno));
    struct stat st;
    if (fstat(fileno(file), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(file);
        return camf_refuse(&rp, "a directory, not a file");
    }
    /* read at most one byte past the limit: a pipe or a growing file says no size */
    char *text = malloc(CAMERA_FILE_MAX_BYTES + 1);
    if (!text) {
        fclose(file);
        return camf_refuse(&rp, "out of memory");
    }
    size_t size = fread(text, 1, CAMERA_FILE_MAX_BYTES + 1, file);
    bool read_error = ferror(file) != 0;
    fclose(file);
    bool ok;
    if (read_error)
        ok = camf_refuse(&rp, "cannot read it");
    else if (size > CAMERA_FILE_MAX_BYTES)
        ok = camf_refuse(&rp, "more than %u bytes: not a camera file this reader takes", CAMERA_FILE_MAX_BYTES);
    else
        ok = camera_file_parse(text, size, width, height, out, why, why_size);
    free(text);
    return ok;
}

void camera_file_free(camera_file *f)
{
    if (!f)
        return;
    free(f->views);
    memset(f, 0, sizeof *f);
}
