/* What the camera file formats share (camera_file_internal.h): refusals,
 * poses from matrices and quaternions, pinholes as frusta, one image size. */
#define _POSIX_C_SOURCE 200809L
#include "camera_file_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

bool camf_refuse(camf_report *r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->why, r->size, fmt, ap);
    va_end(ap);
    return false;
}

/* "'abc'" of a cell for messages, printable ASCII only, shortened. */
void camf_show_cell(char *buf, size_t size, const char *cell, size_t len)
{
    size_t n = 0;
    for (size_t i = 0; i < len && n + 4 < size && i < 32; ++i)
        buf[n++] = cell[i] >= 0x20 && cell[i] < 0x7f ? cell[i] : '?';
    if (len > 32 && n + 4 < size)
        buf[n++] = '.', buf[n++] = '.', buf[n++] = '.';
    buf[n] = '\0';
}

/* A unit quaternion from a rotation matrix (rows r[i][j]), Shepperd's way:
 * the largest of w, x, y, z first, so no division by a small number. */
static void quat_from_rotation(double r[3][3], double q[4])
{
    double tr = r[0][0] + r[1][1] + r[2][2], x, y, z, w;
    if (tr > 0) {
        double s = 2.0 * sqrt(tr + 1.0);
        w = 0.25 * s, x = (r[2][1] - r[1][2]) / s, y = (r[0][2] - r[2][0]) / s, z = (r[1][0] - r[0][1]) / s;
    } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
        double s = 2.0 * sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]);
        w = (r[2][1] - r[1][2]) / s, x = 0.25 * s, y = (r[0][1] + r[1][0]) / s, z = (r[0][2] + r[2][0]) / s;
    } else if (r[1][1] > r[2][2]) {
        double s = 2.0 * sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]);
        w = (r[0][2] - r[2][0]) / s, x = (r[0][1] + r[1][0]) / s, y = 0.25 * s, z = (r[1][2] + r[2][1]) / s;
    } else {
        double s = 2.0 * sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]);
        w = (r[1][0] - r[0][1]) / s, x = (r[0][2] + r[2][0]) / s, y = (r[1][2] + r[2][1]) / s, z = 0.25 * s;
    }
    double n = sqrt(x * x + y * y + z * z + w * w);
    q[0] = x / n, q[1] = y / n, q[2] = z / n, q[3] = w / n;
}

bool camf_check_position(camf_report *rp, const char *where, const char *field, const double p[3])
{
    for (int i = 0; i < 3; ++i)
        if (!(fabs(p[i]) <= CAMF_MAX_COORDINATE))
            return camf_refuse(rp, "%s: %s: the position (%g, %g, %g) is more than %g from the origin", where, field,
                               p[0], p[1], p[2], CAMF_MAX_COORDINATE);
    return true;
}

/* A camera-to-world matrix (rows m[r][c], OpenGL camera) into the view's
 * position and orientation. The last row must be 0 0 0 1 and the rotation
 * within CAMERA_FILE_ROTATION_TOLERANCE of orthonormal, not a reflection. */
bool camf_pose_from_matrix(camf_report *rp, const char *where, const char *field, double m[4][4],
                                       mvr_view_desc *v)
{
    if (!(fabs(m[3][0]) <= 1e-9 && fabs(m[3][1]) <= 1e-9 && fabs(m[3][2]) <= 1e-9 && fabs(m[3][3] - 1.0) <= 1e-9))
        return camf_refuse(rp, "%s: %s: the last row must be 0, 0, 0, 1 (got %g, %g, %g, %g)", where, field, m[3][0],
                           m[3][1], m[3][2], m[3][3]);
    double r[3][3], off = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r[i][j] = m[i][j];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double dot = r[0][i] * r[0][j] + r[1][i] * r[1][j] + r[2][i] * r[2][j];
            off = fmax(off, fabs(dot - (i == j ? 1.0 : 0.0)));
        }
    if (!(off <= CAMERA_FILE_ROTATION_TOLERANCE))
        return camf_refuse(rp,
                           "%s: %s: the rotation (upper 3x3) is not orthonormal: its columns' lengths and angles are "
                           "off by %.3g (at most %g is normalised; a scaled or sheared camera is not a pinhole pose)",
                           where, field, off, CAMERA_FILE_ROTATION_TOLERANCE);
    double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                 r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    if (det < 0)
        return camf_refuse(rp, "%s: %s: the rotation is a reflection (determinant %.3g): a camera-to-world pose has +1",
                           where, field, det);
    quat_from_rotation(r, v->orientation);
    for (int i = 0; i < 3; ++i)
        v->position[i] = m[i][3];
    return camf_check_position(rp, where, field, v->position);
}

/* A quaternion given as such (x, y, z, w): within the tolerance of unit
 * length, normalised. */
bool camf_unit_quaternion(camf_report *rp, const char *where, const char *field, const double in[4], double out[4])
{
    double n = sqrt(in[0] * in[0] + in[1] * in[1] + in[2] * in[2] + in[3] * in[3]);
    if (!(fabs(n - 1.0) <= CAMERA_FILE_ROTATION_TOLERANCE))
        return camf_refuse(rp, "%s: %s: the quaternion (%g, %g, %g, %g) has length %.6g; a rotation's is 1 (within %g)",
                           where, field, in[0], in[1], in[2], in[3], n, CAMERA_FILE_ROTATION_TOLERANCE);
    for (int i = 0; i < 4; ++i)
        out[i] = in[i] / n;
    return true;
}

/* Pinhole intrinsics (pixels, OpenCV camera, image w x h) as the frustum
 * whose mvr_view_set_get_camera at w x h gives them back: the image's edges
 * at u = 0, w and v = 0, h seen from the centre, as tangents. */
bool camf_frustum_from_pinhole(camf_report *rp, const char *where, const char *names[4], double fx, double fy,
                               double cx, double cy, uint32_t w, uint32_t h, double znear, mvr_projection *p)
{
    if (!(fx > 0))
        return camf_refuse(rp, "%s: %s: %g is not a focal length (pixels, > 0)", where, names[0], fx);
    if (!(fy > 0))
        return camf_refuse(rp, "%s: %s: %g is not a focal length (pixels, > 0)", where, names[1], fy);
    if (!((double)w / fx >= CAMF_MIN_FIELD_OF_VIEW))
        return camf_refuse(rp, "%s: %s: %g pixels on an image %u wide is a field of view under %g radians", where,
                           names[0], fx, w, CAMF_MIN_FIELD_OF_VIEW);
    if (!((double)h / fy >= CAMF_MIN_FIELD_OF_VIEW))
        return camf_refuse(rp, "%s: %s: %g pixels on an image %u high is a field of view under %g radians", where,
                           names[1], fy, h, CAMF_MIN_FIELD_OF_VIEW);
    double left = atan(-cx / fx), right = atan(((double)w - cx) / fx);
    double up = atan(cy / fy), down = atan(-((double)h - cy) / fy);
    if (!(fabs(left) < CAMF_MAX_EDGE_ANGLE && fabs(right) < CAMF_MAX_EDGE_ANGLE))
        return camf_refuse(rp, "%s: %s %g with %s %g puts an image edge %.6g degrees off the axis (at most %.6g: the "
                               "focal length is too short or the principal point too far out)", where, names[0], fx,
                           names[2], cx, fmax(fabs(left), fabs(right)) * 180.0 / 3.14159265358979323846,
                           CAMF_MAX_EDGE_ANGLE * 180.0 / 3.14159265358979323846);
    if (!(fabs(up) < CAMF_MAX_EDGE_ANGLE && fabs(down) < CAMF_MAX_EDGE_ANGLE))
        return camf_refuse(rp, "%s: %s %g with %s %g puts an image edge %.6g degrees off the axis (at most %.6g: the "
                               "focal length is too short or the principal point too far out)", where, names[1], fy,
                           names[3], cy, fmax(fabs(up), fabs(down)) * 180.0 / 3.14159265358979323846,
                           CAMF_MAX_EDGE_ANGLE * 180.0 / 3.14159265358979323846);
    memset(p, 0, sizeof *p);
    p->type = MVR_PROJECTION_FRUSTUM;
    p->angle_left = left;
    p->angle_right = right;
    p->angle_down = down;
    p->angle_up = up;
    p->znear = znear;
    return true;
}

bool camf_check_znear(camf_report *rp, const char *where, const char *field, double znear)
{
    if (!(znear >= 0 && znear <= CAMF_MAX_ZNEAR))
        return camf_refuse(rp, "%s: %s: %g is not a near plane distance (> 0 up to %g; 0 = the library's 0.05)", where,
                           field, znear, CAMF_MAX_ZNEAR);
    return true;
}

static void size_text(char *buf, size_t size, uint32_t w, uint32_t h)
{
    if (w)
        snprintf(buf, size, "%ux%u", w, h);
    else
        snprintf(buf, size, "not given");
}

/* One image size for every view (0 x 0: the view names none): the renderer
 * draws all views into one array. */
bool camf_same_size(camf_report *rp, camera_file *f, const char *where, uint32_t index, uint32_t w, uint32_t h)
{
    if (index == 0) {
        f->width = w;
        f->height = h;
        return true;
    }
    if (w != f->width || h != f->height) {
        char mine[32], first[32];
        size_text(mine, sizeof mine, w, h);
        size_text(first, sizeof first, f->width, f->height);
        return camf_refuse(rp, "%s: its image size is %s, view 0's %s: mvr renders every view at one size (give views "
                               "of one size per file)", where, mine, first);
    }
    return true;
}
