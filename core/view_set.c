#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"
#include "view_set.h"

#define DEFAULT_YFOV (60.0 * 3.14159265358979323846 / 180.0)
#define DEFAULT_ZNEAR 0.05
/* Standard depth needs a finite far plane; this one keeps 24+ bits of depth
 * useful at ordinary scales. */
#define STANDARD_DEFAULT_ZFAR 1000.0

static bool finite_n(const double *v, int n)
{
    for (int i = 0; i < n; ++i)
        if (!isfinite(v[i]))
            return false;
    return true;
}

static bool check_view(const mvr_view_desc *v, uint32_t i, char *why, size_t why_size)
{
    const mvr_projection *p = &v->projection;
    if (!finite_n(v->position, 3) || !finite_n(v->orientation, 4)) {
        mvr_str_format(why, why_size, "view %u: pose is not finite", i);
        return false;
    }
    if ((unsigned)p->type > MVR_PROJECTION_MATRIX) {
        mvr_str_format(why, why_size, "view %u: unknown projection type %d", i, (int)p->type);
        return false;
    }
    if (p->znear < 0 || !isfinite(p->znear) || p->zfar < 0 || !isfinite(p->zfar) ||
        (p->zfar > 0 && p->zfar <= (p->znear > 0 ? p->znear : DEFAULT_ZNEAR))) {
        mvr_str_format(why, why_size, "view %u: znear %g / zfar %g invalid (0 < znear < zfar, zfar 0 = infinite)",
                       i, p->znear, p->zfar);
        return false;
    }
    switch (p->type) {
    case MVR_PROJECTION_PERSPECTIVE:
        if (p->yfov < 0 || p->yfov >= 3.14159 || p->aspect < 0 || !isfinite(p->aspect)) {
            mvr_str_format(why, why_size, "view %u: yfov %g / aspect %g invalid", i, p->yfov, p->aspect);
            return false;
        }
        break;
    case MVR_PROJECTION_FRUSTUM:
        if (!(p->angle_left < p->angle_right) || !(p->angle_down < p->angle_up) ||
            fabs(p->angle_left) >= 1.5707 || fabs(p->angle_right) >= 1.5707 ||
            fabs(p->angle_down) >= 1.5707 || fabs(p->angle_up) >= 1.5707) {
            mvr_str_format(why, why_size, "view %u: frustum angles must satisfy left < right, down < up, |angle| < pi/2", i);
            return false;
        }
        break;
    case MVR_PROJECTION_ORTHOGRAPHIC:
        if (!(p->xmag > 0) || !(p->ymag > 0) || !isfinite(p->xmag) || !isfinite(p->ymag)) {
            mvr_str_format(why, why_size, "view %u: orthographic xmag / ymag must be > 0", i);
            return false;
        }
        break;
    case MVR_PROJECTION_MATRIX:
        if (!finite_n(p->matrix, 16)) {
            mvr_str_format(why, why_size, "view %u: projection matrix is not finite", i);
            return false;
        }
        break;
    }
    return true;
}

static void update_origin(mvr_view_set *s)
{
    if (s->origin_set || s->count == 0)
        return;
    mvr_dvec3 c = mvr_dvec3_make(0, 0, 0);
    for (uint32_t i = 0; i < s->count; ++i)
        c = mvr_dvec3_add(c, mvr_dvec3_make(s->views[i].position[0], s->views[i].position[1],
                                            s->views[i].position[2]));
    s->origin = mvr_dvec3_scale(c, 1.0 / s->count);
}

mvr_result mvr_view_set_create(const mvr_view_set_desc *d, mvr_view_set **out, mvr_error *error)
{
    if (!out || !d)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_create: NULL argument");
    *out = NULL;
    if (d->view_count == 0 || !d->views)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_create: no views");
    if (d->view_count > MVR_VIEW_SET_MAX_VIEWS)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_create: %u views (at most %u)",
                             d->view_count, MVR_VIEW_SET_MAX_VIEWS);
    char why[256];
    for (uint32_t i = 0; i < d->view_count; ++i)
        if (!check_view(&d->views[i], i, why, sizeof why))
            return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_create: %s", why);
    if (d->origin_set && !finite_n(d->origin, 3))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_create: origin is not finite");
    mvr_view_set *s = calloc(1, sizeof *s);
    if (s)
        s->views = malloc(d->view_count * sizeof *s->views);
    if (!s || !s->views) {
        free(s);
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_view_set_create: out of memory");
    }
    memcpy(s->views, d->views, d->view_count * sizeof *s->views);
    s->count = d->view_count;
    s->origin_set = d->origin_set;
    s->origin = mvr_dvec3_make(d->origin[0], d->origin[1], d->origin[2]);
    s->version = 1;
    update_origin(s);
    *out = s;
    return MVR_OK;
}

void mvr_view_set_destroy(mvr_view_set *s)
{
    if (!s)
        return;
    free(s->views);
    free(s);
}

mvr_result mvr_view_set_update(mvr_view_set *s, uint32_t index, const mvr_view_desc *v)
{
    if (!s || !v)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (index >= s->count) {
        mvr_str_format(s->last_error, sizeof s->last_error,
                       "mvr_view_set_update: view %u of %u", index, s->count);
        return MVR_ERROR_INVALID_ARGUMENT;
    }
    char why[256];
    if (!check_view(v, index, why, sizeof why)) {
        mvr_str_format(s->last_error, sizeof s->last_error, "mvr_view_set_update: %s", why);
        return MVR_ERROR_INVALID_ARGUMENT;
    }
    s->views[index] = *v;
    s->version++;
    update_origin(s);
    return MVR_OK;
}

uint32_t mvr_view_set_count(const mvr_view_set *s)
{
    return s ? s->count : 0;
}

mvr_result mvr_view_set_get_view(const mvr_view_set *s, uint32_t index, mvr_view_desc *out)
{
    if (!s || !out || index >= s->count)
        return MVR_ERROR_INVALID_ARGUMENT;
    *out = s->views[index];
    return MVR_OK;
}

mvr_result mvr_view_set_get_origin(const mvr_view_set *s, double out[3])
{
    if (!s || !out)
        return MVR_ERROR_INVALID_ARGUMENT;
    out[0] = s->origin.x;
    out[1] = s->origin.y;
    out[2] = s->origin.z;
    return MVR_OK;
}

const char *mvr_view_set_last_error(const mvr_view_set *s)
{
    return s ? s->last_error : "mvr_view_set_last_error: view set is NULL";
}

void mvr_view_look_at(mvr_view_desc *v, const double eye[3], const double target[3], const double up[3])
{
    mvr_dvec3 e = mvr_dvec3_make(eye[0], eye[1], eye[2]);
    mvr_dvec3 f = mvr_dvec3_sub(mvr_dvec3_make(target[0], target[1], target[2]), e);
    mvr_dquat q = mvr_dquat_look_rotation(f, mvr_dvec3_make(up[0], up[1], up[2]));
    memcpy(v->position, eye, sizeof v->position);
    v->orientation[0] = q.x;
    v->orientation[1] = q.y;
    v->orientation[2] = q.z;
    v->orientation[3] = q.w;
}

mvr_viewport mvr_view_viewport(const mvr_view_desc *v, uint32_t width, uint32_t height)
{
    mvr_viewport vp = v->viewport;
    if (vp.width == 0 || vp.height == 0) {
        vp.x = vp.y = 0;
        vp.width = width;
        vp.height = height;
    }
    return vp;
}

mvr_dmat4 mvr_view_projection(const mvr_view_desc *v, mvr_viewport vp, bool reversed)
{
    const mvr_projection *p = &v->projection;
    double znear = p->znear > 0 ? p->znear : DEFAULT_ZNEAR;
    double zfar = p->zfar;
    if (!reversed && zfar <= 0)
        zfar = fmax(STANDARD_DEFAULT_ZFAR, znear * 1e4);
    switch (p->type) {
    case MVR_PROJECTION_PERSPECTIVE: {
        double yfov = p->yfov > 0 ? p->yfov : DEFAULT_YFOV;
        double aspect = p->aspect > 0 ? p->aspect : (double)vp.width / (double)(vp.height ? vp.height : 1);
        return mvr_dmat4_perspective(yfov, aspect, znear, zfar, reversed);
    }
    case MVR_PROJECTION_FRUSTUM:
        return mvr_dmat4_frustum(p->angle_left, p->angle_right, p->angle_down, p->angle_up, znear,
                                 zfar, reversed);
    case MVR_PROJECTION_ORTHOGRAPHIC:
        return mvr_dmat4_orthographic(p->xmag, p->ymag, znear, p->zfar > 0 ? p->zfar : 1000.0, reversed);
    case MVR_PROJECTION_MATRIX: {
        mvr_dmat4 m;
        memcpy(m.m, p->matrix, sizeof m.m);
        return reversed ? mvr_dmat4_gl_to_reversed(&m) : m;
    }
    }
    return mvr_dmat4_identity();
}

mvr_dmat4 mvr_view_relative_view_proj(const mvr_view_desc *v, mvr_dvec3 origin, mvr_viewport vp, bool reversed)
{
    mvr_dvec3 rel = mvr_dvec3_sub(mvr_dvec3_make(v->position[0], v->position[1], v->position[2]), origin);
    mvr_dquat q = {v->orientation[0], v->orientation[1], v->orientation[2], v->orientation[3]};
    if (q.x == 0 && q.y == 0 && q.z == 0 && q.w == 0)
        q.w = 1;
    mvr_dmat4 view = mvr_dmat4_view(rel, q);
    mvr_dmat4 proj = mvr_view_projection(v, vp, reversed);
    return mvr_dmat4_mul(&proj, &view);
}

void mvr_view_gpu_matrices(const mvr_view_desc *v, mvr_dvec3 origin, mvr_viewport vp, bool reversed,
                           float view_proj[16], float eye_rel[4])
{
    mvr_dvec3 rel = mvr_dvec3_sub(mvr_dvec3_make(v->position[0], v->position[1], v->position[2]), origin);
    mvr_dmat4 vpm = mvr_view_relative_view_proj(v, origin, vp, reversed);
    mvr_mat4f f = mvr_dmat4_to_float(&vpm);
    memcpy(view_proj, f.m, sizeof f.m);
    eye_rel[0] = (float)rel.x;
    eye_rel[1] = (float)rel.y;
    eye_rel[2] = (float)rel.z;
    eye_rel[3] = 1.0f;
}

void mvr_view_gpu_view_matrix(const mvr_view_desc *v, mvr_dvec3 origin, float view_matrix[16])
{
    mvr_dvec3 rel = mvr_dvec3_sub(mvr_dvec3_make(v->position[0], v->position[1], v->position[2]), origin);
    mvr_dquat q = {v->orientation[0], v->orientation[1], v->orientation[2], v->orientation[3]};
    if (q.x == 0 && q.y == 0 && q.z == 0 && q.w == 0)
        q.w = 1;
    mvr_dmat4 view = mvr_dmat4_view(rel, q);
    mvr_mat4f f = mvr_dmat4_to_float(&view);
    memcpy(view_matrix, f.m, sizeof f.m);
}

mvr_result mvr_view_set_get_camera(const mvr_view_set *s, uint32_t index, uint32_t layer_width, uint32_t layer_height,
                                   mvr_view_camera *out)
{
    if (!s || !out || index >= s->count || layer_width == 0 || layer_height == 0)
        return MVR_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    const mvr_view_desc *v = &s->views[index];
    mvr_viewport vp = mvr_view_viewport(v, layer_width, layer_height);
    out->width = vp.width;
    out->height = vp.height;
    mvr_dmat4 proj = mvr_view_projection(v, vp, false);
    mvr_dquat q = {v->orientation[0], v->orientation[1], v->orientation[2], v->orientation[3]};
    if (q.x == 0 && q.y == 0 && q.z == 0 && q.w == 0)
        q.w = 1;
    mvr_dmat4 view = mvr_dmat4_view(mvr_dvec3_make(v->position[0], v->position[1], v->position[2]), q);
    mvr_dmat4 inv;
    if (!mvr_dmat4_invert(&view, &inv))
        return MVR_ERROR_INVALID_ARGUMENT;
    memcpy(out->projection, proj.m, sizeof out->projection);
    memcpy(out->world_to_camera, view.m, sizeof out->world_to_camera);
    memcpy(out->camera_to_world, inv.m, sizeof out->camera_to_world);
    /* a projective clip matrix has w = -Z (its row 3 is (0, 0, -1, 0)):
     * u = (x_ndc + 1) w / 2 with x_ndc = (P00 X + P01 Y + P02 Z) / -Z, and
     * in the OpenCV camera (Xc, Yc, Zc) = (X, -Y, -Z) that is
     * u = (w / 2) P00 Xc / Zc + (w / 2)(1 - P02), likewise
     * v = (1 - y_ndc) h / 2 = (h / 2) P11 Yc / Zc + (h / 2)(1 + P12) */
    const double *p = proj.m; /* column-major: p[col * 4 + row] */
    out->perspective = p[3 * 4 + 3] == 0.0 && p[2 * 4 + 3] == -1.0 && p[1 * 4 + 0] == 0.0 && p[0 * 4 + 1] == 0.0;
    if (out->perspective) {
        double w = (double)vp.width, h = (double)vp.height;
        out->fx = 0.5 * w * p[0];
        out->fy = 0.5 * h * p[1 * 4 + 1];
        out->cx = 0.5 * w * (1.0 - p[2 * 4 + 0]);
        out->cy = 0.5 * h * (1.0 + p[2 * 4 + 1]);
    }
    return MVR_OK;
}

mvr_result mvr_scene_camera_view(const mvr_scene *s, mvr_node_id node, mvr_view_desc *out)
{
    if (!s || !out || node.id == 0 || node.id > s->node_count)
        return MVR_ERROR_INVALID_ARGUMENT;
    const scene_node *n = &s->nodes[node.id - 1];
    if (n->camera == MVR_NO_INDEX)
        return MVR_ERROR_INVALID_ARGUMENT;
    mvr_dmat4 *world = malloc(s->node_count * sizeof *world);
    if (!world)
        return MVR_ERROR_OUT_OF_MEMORY;
    mvr_scene_world_matrices(s, world);
    mvr_dmat4 w = world[node.id - 1];
    free(world);
    memset(out, 0, sizeof *out);
    out->projection = s->cameras[n->camera];
    mvr_dvec3 p = mvr_dmat4_transform_point(&w, mvr_dvec3_make(0, 0, 0));
    mvr_dvec3 fwd = mvr_dmat4_transform_dir(&w, mvr_dvec3_make(0, 0, -1));
    mvr_dvec3 up = mvr_dmat4_transform_dir(&w, mvr_dvec3_make(0, 1, 0));
    mvr_dquat q = mvr_dquat_look_rotation(fwd, up);
    out->position[0] = p.x;
    out->position[1] = p.y;
    out->position[2] = p.z;
    out->orientation[0] = q.x;
    out->orientation[1] = q.y;
    out->orientation[2] = q.z;
    out->orientation[3] = q.w;
    return MVR_OK;
}
