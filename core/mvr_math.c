#include <math.h>
#include <string.h>

#include "mvr_math.h"

mvr_dvec3 mvr_dvec3_make(double x, double y, double z)
{
    mvr_dvec3 v = {x, y, z};
    return v;
}

mvr_dvec3 mvr_dvec3_add(mvr_dvec3 a, mvr_dvec3 b)
{
    return mvr_dvec3_make(a.x + b.x, a.y + b.y, a.z + b.z);
}

mvr_dvec3 mvr_dvec3_sub(mvr_dvec3 a, mvr_dvec3 b)
{
    return mvr_dvec3_make(a.x - b.x, a.y - b.y, a.z - b.z);
}

mvr_dvec3 mvr_dvec3_scale(mvr_dvec3 a, double s)
{
    return mvr_dvec3_make(a.x * s, a.y * s, a.z * s);
}

double mvr_dvec3_dot(mvr_dvec3 a, mvr_dvec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

mvr_dvec3 mvr_dvec3_cross(mvr_dvec3 a, mvr_dvec3 b)
{
    return mvr_dvec3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

double mvr_dvec3_length(mvr_dvec3 a)
{
    return sqrt(mvr_dvec3_dot(a, a));
}

mvr_dvec3 mvr_dvec3_normalize(mvr_dvec3 a, mvr_dvec3 fallback)
{
    double len = mvr_dvec3_length(a);
    if (!(len > 1e-300) || !isfinite(len))
        return fallback;
    return mvr_dvec3_scale(a, 1.0 / len);
}

mvr_dquat mvr_dquat_normalize(mvr_dquat q)
{
    double len = sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    if (!(len > 1e-300) || !isfinite(len)) {
        mvr_dquat id = {0, 0, 0, 1};
        return id;
    }
    mvr_dquat r = {q.x / len, q.y / len, q.z / len, q.w / len};
    return r;
}

mvr_dquat mvr_dquat_from_axis_angle(mvr_dvec3 axis, double radians)
{
    mvr_dvec3 a = mvr_dvec3_normalize(axis, mvr_dvec3_make(0, 1, 0));
    double s = sin(radians * 0.5);
    mvr_dquat q = {a.x * s, a.y * s, a.z * s, cos(radians * 0.5)};
    return q;
}

mvr_dquat mvr_dquat_mul(mvr_dquat a, mvr_dquat b)
{
    mvr_dquat r = {
        a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
        a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
        a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
        a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
    };
    return r;
}

mvr_dvec3 mvr_dquat_rotate(mvr_dquat q, mvr_dvec3 v)
{
    mvr_dvec3 u = mvr_dvec3_make(q.x, q.y, q.z);
    mvr_dvec3 t = mvr_dvec3_scale(mvr_dvec3_cross(u, v), 2.0);
    return mvr_dvec3_add(mvr_dvec3_add(v, mvr_dvec3_scale(t, q.w)), mvr_dvec3_cross(u, t));
}

/* Quaternion of an orthonormal basis given as columns (x, y, z). */
static mvr_dquat quat_from_basis(mvr_dvec3 x, mvr_dvec3 y, mvr_dvec3 z)
{
    double trace = x.x + y.y + z.z;
    mvr_dquat q;
    if (trace > 0) {
        double s = sqrt(trace + 1.0) * 2;
        q.w = 0.25 * s;
        q.x = (y.z - z.y) / s;
        q.y = (z.x - x.z) / s;
        q.z = (x.y - y.x) / s;
    } else if (x.x > y.y && x.x > z.z) {
        double s = sqrt(1.0 + x.x - y.y - z.z) * 2;
        q.w = (y.z - z.y) / s;
        q.x = 0.25 * s;
        q.y = (y.x + x.y) / s;
        q.z = (z.x + x.z) / s;
    } else if (y.y > z.z) {
        double s = sqrt(1.0 + y.y - x.x - z.z) * 2;
        q.w = (z.x - x.z) / s;
        q.x = (y.x + x.y) / s;
        q.y = 0.25 * s;
        q.z = (z.y + y.z) / s;
    } else {
        double s = sqrt(1.0 + z.z - x.x - y.y) * 2;
        q.w = (x.y - y.x) / s;
        q.x = (z.x + x.z) / s;
        q.y = (z.y + y.z) / s;
        q.z = 0.25 * s;
    }
    return mvr_dquat_normalize(q);
}

mvr_dquat mvr_dquat_look_rotation(mvr_dvec3 forward, mvr_dvec3 up)
{
    mvr_dvec3 z = mvr_dvec3_scale(mvr_dvec3_normalize(forward, mvr_dvec3_make(0, 0, -1)), -1.0);
    mvr_dvec3 x = mvr_dvec3_cross(up, z);
    if (mvr_dvec3_length(x) < 1e-12) /* up parallel to forward: pick another up */
        x = mvr_dvec3_cross(fabs(z.y) < 0.9 ? mvr_dvec3_make(0, 1, 0) : mvr_dvec3_make(1, 0, 0), z);
    x = mvr_dvec3_normalize(x, mvr_dvec3_make(1, 0, 0));
    mvr_dvec3 y = mvr_dvec3_cross(z, x);
    return quat_from_basis(x, y, z);
}

mvr_dmat4 mvr_dmat4_identity(void)
{
    mvr_dmat4 r;
    memset(&r, 0, sizeof r);
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0;
    return r;
}

mvr_dmat4 mvr_dmat4_mul(const mvr_dmat4 *a, const mvr_dmat4 *b)
{
    mvr_dmat4 r;
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            double s = 0;
            for (int k = 0; k < 4; ++k)
                s += a->m[k * 4 + row] * b->m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}

mvr_dmat4 mvr_dmat4_trs(mvr_dvec3 t, mvr_dquat q, mvr_dvec3 s)
{
    q = mvr_dquat_normalize(q);
    double xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
    double xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
    double wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
    mvr_dmat4 r;
    r.m[0] = (1 - 2 * (yy + zz)) * s.x;
    r.m[1] = (2 * (xy + wz)) * s.x;
    r.m[2] = (2 * (xz - wy)) * s.x;
    r.m[3] = 0;
    r.m[4] = (2 * (xy - wz)) * s.y;
    r.m[5] = (1 - 2 * (xx + zz)) * s.y;
    r.m[6] = (2 * (yz + wx)) * s.y;
    r.m[7] = 0;
    r.m[8] = (2 * (xz + wy)) * s.z;
    r.m[9] = (2 * (yz - wx)) * s.z;
    r.m[10] = (1 - 2 * (xx + yy)) * s.z;
    r.m[11] = 0;
    r.m[12] = t.x;
    r.m[13] = t.y;
    r.m[14] = t.z;
    r.m[15] = 1;
    return r;
}

mvr_dvec3 mvr_dmat4_transform_point(const mvr_dmat4 *m, mvr_dvec3 p)
{
    const double *a = m->m;
    return mvr_dvec3_make(a[0] * p.x + a[4] * p.y + a[8] * p.z + a[12],
                          a[1] * p.x + a[5] * p.y + a[9] * p.z + a[13],
                          a[2] * p.x + a[6] * p.y + a[10] * p.z + a[14]);
}

mvr_dvec3 mvr_dmat4_transform_dir(const mvr_dmat4 *m, mvr_dvec3 d)
{
    const double *a = m->m;
    return mvr_dvec3_make(a[0] * d.x + a[4] * d.y + a[8] * d.z,
                          a[1] * d.x + a[5] * d.y + a[9] * d.z,
                          a[2] * d.x + a[6] * d.y + a[10] * d.z);
}

bool mvr_dmat4_invert(const mvr_dmat4 *in, mvr_dmat4 *out)
{
    const double *m = in->m;
    double inv[16];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] +
             m[9] * m[7] * m[14] + m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] -
             m[8] * m[7] * m[14] - m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] +
             m[8] * m[7] * m[13] + m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] -
              m[8] * m[6] * m[13] - m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] -
             m[9] * m[3] * m[14] - m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] +
             m[8] * m[3] * m[14] + m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] -
             m[8] * m[3] * m[13] - m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] +
              m[8] * m[2] * m[13] + m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] +
             m[5] * m[3] * m[14] + m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] -
             m[4] * m[3] * m[14] - m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] +
              m[4] * m[3] * m[13] + m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] -
              m[4] * m[2] * m[13] - m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] -
             m[5] * m[3] * m[10] - m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] +
             m[4] * m[3] * m[10] + m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] -
              m[4] * m[3] * m[9] - m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] +
              m[4] * m[2] * m[9] + m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (det == 0.0 || !isfinite(det)) {
        *out = mvr_dmat4_identity();
        return false;
    }
    for (int i = 0; i < 16; ++i)
        out->m[i] = inv[i] / det;
    return true;
}

double mvr_dmat4_det3(const mvr_dmat4 *a)
{
    const double *m = a->m;
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

mvr_dmat4 mvr_dmat4_normal_matrix(const mvr_dmat4 *a)
{
    /* The cofactor matrix of the 3x3 equals det * inverse-transpose: the same
     * direction for normals, and finite when det = 0. Normalized by |det|
     * where det != 0 keeps lengths sensible; the shader renormalizes anyway. */
    const double *m = a->m;
    double c[9];
    c[0] = m[5] * m[10] - m[6] * m[9];
    c[1] = m[6] * m[8] - m[4] * m[10];
    c[2] = m[4] * m[9] - m[5] * m[8];
    c[3] = m[2] * m[9] - m[1] * m[10];
    c[4] = m[0] * m[10] - m[2] * m[8];
    c[5] = m[1] * m[8] - m[0] * m[9];
    c[6] = m[1] * m[6] - m[2] * m[5];
    c[7] = m[2] * m[4] - m[0] * m[6];
    c[8] = m[0] * m[5] - m[1] * m[4];
    /* c[col * 3 + row] is the cofactor C[row][col]; the inverse-transpose is
     * C / det, stored column-major like every matrix here */
    double det = mvr_dmat4_det3(a);
    double s = (det != 0.0 && isfinite(det)) ? 1.0 / det : 1.0;
    mvr_dmat4 r = mvr_dmat4_identity();
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row)
            r.m[col * 4 + row] = c[col * 3 + row] * s;
    return r;
}

mvr_mat4f mvr_dmat4_relative_to(const mvr_dmat4 *m, mvr_dvec3 origin)
{
    mvr_dmat4 r = *m;
    /* translation minus origin, in double, then narrowed */
    r.m[12] = m->m[12] - origin.x * m->m[15];
    r.m[13] = m->m[13] - origin.y * m->m[15];
    r.m[14] = m->m[14] - origin.z * m->m[15];
    return mvr_dmat4_to_float(&r);
}

mvr_mat4f mvr_dmat4_to_float(const mvr_dmat4 *m)
{
    mvr_mat4f r;
    for (int i = 0; i < 16; ++i)
        r.m[i] = (float)m->m[i];
    return r;
}

mvr_dmat4 mvr_dmat4_view(mvr_dvec3 p, mvr_dquat q)
{
    /* inverse of T(p) * R(q): R^T * T(-p) */
    q = mvr_dquat_normalize(q);
    mvr_dmat4 r = mvr_dmat4_trs(mvr_dvec3_make(0, 0, 0), q, mvr_dvec3_make(1, 1, 1));
    mvr_dmat4 v = mvr_dmat4_identity();
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row)
            v.m[c * 4 + row] = r.m[row * 4 + c];
    mvr_dvec3 t = mvr_dmat4_transform_dir(&v, mvr_dvec3_scale(p, -1.0));
    v.m[12] = t.x;
    v.m[13] = t.y;
    v.m[14] = t.z;
    return v;
}

mvr_dmat4 mvr_dmat4_frustum(double angle_left, double angle_right, double angle_down,
                            double angle_up, double znear, double zfar, bool reversed)
{
    double l = tan(angle_left), r = tan(angle_right);
    double d = tan(angle_down), u = tan(angle_up);
    mvr_dmat4 p;
    memset(&p, 0, sizeof p);
    p.m[0] = 2.0 / (r - l);
    p.m[5] = 2.0 / (u - d);
    p.m[8] = (r + l) / (r - l);
    p.m[9] = (u + d) / (u - d);
    p.m[11] = -1.0;
    if (reversed) {
        if (zfar > 0.0 && isfinite(zfar)) {
            /* z_ndc = near (far - z_eye... ) : near -> 1, far -> 0 */
            p.m[10] = znear / (zfar - znear);
            p.m[14] = znear * zfar / (zfar - znear);
        } else {
            /* infinite far: z_clip = near, w = -z_eye, so z_ndc = near / -z_eye */
            p.m[10] = 0.0;
            p.m[14] = znear;
        }
    } else {
        p.m[10] = -(zfar + znear) / (zfar - znear);
        p.m[14] = -2.0 * zfar * znear / (zfar - znear);
    }
    return p;
}

mvr_dmat4 mvr_dmat4_perspective(double yfov, double aspect, double znear, double zfar,
                                bool reversed)
{
    double t = tan(yfov * 0.5);
    double a = atan(t * aspect);
    return mvr_dmat4_frustum(-a, a, -yfov * 0.5, yfov * 0.5, znear, zfar, reversed);
}

mvr_dmat4 mvr_dmat4_orthographic(double xmag, double ymag, double znear, double zfar,
                                 bool reversed)
{
    mvr_dmat4 p = mvr_dmat4_identity();
    p.m[0] = 1.0 / xmag;
    p.m[5] = 1.0 / ymag;
    if (reversed) {
        /* z_eye = -near -> 1, z_eye = -far -> 0 */
        p.m[10] = 1.0 / (zfar - znear);
        p.m[14] = zfar / (zfar - znear);
    } else {
        p.m[10] = -2.0 / (zfar - znear);
        p.m[14] = -(zfar + znear) / (zfar - znear);
    }
    return p;
}

mvr_dmat4 mvr_dmat4_gl_to_reversed(const mvr_dmat4 *proj)
{
    mvr_dmat4 r = *proj;
    for (int c = 0; c < 4; ++c)
        r.m[c * 4 + 2] = 0.5 * (proj->m[c * 4 + 3] - proj->m[c * 4 + 2]);
    return r;
}
