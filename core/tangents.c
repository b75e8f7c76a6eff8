/* tangents.c: MikkTSpace-style per-vertex tangents (see tangents.h). */
#include "tangents.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void sub3(const float *a, const float *b, double *o)
{
    for (int k = 0; k < 3; ++k)
        o[k] = (double)a[k] - (double)b[k];
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* v minus its component along the unit normal n, normalized; false if ~0 */
static bool tangent_plane(const double *v, const double *n, double *o)
{
    double d = dot3(v, n);
    for (int k = 0; k < 3; ++k)
        o[k] = v[k] - n[k] * d;
    double len = sqrt(dot3(o, o));
    if (!(len > 1e-20))
        return false;
    for (int k = 0; k < 3; ++k)
        o[k] /= len;
    return true;
}

static void unit_normal(const float *normals, uint32_t v, double *n)
{
    for (int k = 0; k < 3; ++k)
        n[k] = normals[(size_t)v * 3 + (size_t)k];
    double len = sqrt(dot3(n, n));
    if (len > 1e-20)
        for (int k = 0; k < 3; ++k)
            n[k] /= len;
    else
        n[0] = 0.0, n[1] = 0.0, n[2] = 1.0;
}

typedef struct weld_key {
    float a[8]; /* position, normal, uv */
    uint32_t vertex;
} weld_key;

static int weld_cmp(const void *x, const void *y)
{
    const weld_key *a = x, *b = y;
    int c = memcmp(a->a, b->a, sizeof a->a);
    return c ? c : (a->vertex > b->vertex) - (a->vertex < b->vertex);
}

/* rep[v]: the first vertex with v's position, normal and UV (bit-equal) */
static bool weld(const float *p, const float *n, const float *uv, uint32_t count, uint32_t *rep)
{
    weld_key *keys = malloc((size_t)count * sizeof *keys);
    if (!keys)
        return false;
    for (uint32_t v = 0; v < count; ++v) {
        memset(&keys[v], 0, sizeof keys[v]);
        memcpy(keys[v].a, p + (size_t)v * 3, 3 * sizeof(float));
        memcpy(keys[v].a + 3, n + (size_t)v * 3, 3 * sizeof(float));
        memcpy(keys[v].a + 6, uv + (size_t)v * 2, 2 * sizeof(float));
        keys[v].vertex = v;
    }
    qsort(keys, count, sizeof *keys, weld_cmp);
    for (uint32_t i = 0; i < count; ++i)
        rep[keys[i].vertex] = i && !memcmp(keys[i].a, keys[i - 1].a, sizeof keys[i].a) ? rep[keys[i - 1].vertex]
                                                                                        : keys[i].vertex;
    free(keys);
    return true;
}

/* one corner's contribution: its triangle's dP/du in the normal plane of
 * the corner's vertex, weighted by the corner's angle in that plane */
static void add_corner(const float *p, const float *nr, const float *uv, const uint32_t *tri, int c, double *sum,
                       double *sign)
{
    uint32_t i0 = tri[c], i1 = tri[(c + 1) % 3], i2 = tri[(c + 2) % 3];
    double e1[3], e2[3], n[3];
    sub3(p + (size_t)i1 * 3, p + (size_t)i0 * 3, e1);
    sub3(p + (size_t)i2 * 3, p + (size_t)i0 * 3, e2);
    double du1 = (double)uv[i1 * 2] - uv[i0 * 2], dv1 = (double)uv[i1 * 2 + 1] - uv[i0 * 2 + 1];
    double du2 = (double)uv[i2 * 2] - uv[i0 * 2], dv2 = (double)uv[i2 * 2 + 1] - uv[i0 * 2 + 1];
    double det = du1 * dv2 - du2 * dv1;
    if (det == 0.0 || !isfinite(det))
        return;
    double s = det > 0.0 ? 1.0 : -1.0, dpdu[3], dpdv[3], t[3], a[3], b[3];
    for (int k = 0; k < 3; ++k) {
        dpdu[k] = s * (e1[k] * dv2 - e2[k] * dv1);
        dpdv[k] = s * (e2[k] * du1 - e1[k] * du2);
    }
    unit_normal(nr, i0, n);
    if (!tangent_plane(dpdu, n, t) || !tangent_plane(e1, n, a) || !tangent_plane(e2, n, b))
        return;
    double angle = acos(fmax(-1.0, fmin(1.0, dot3(a, b))));
    for (int k = 0; k < 3; ++k)
        sum[k] += angle * t[k];
    /* the normal map's +Y is -dP/dv: w = +1 where cross(n, t) points that way */
    double bt[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
    *sign += angle * (dot3(bt, dpdv) <= 0.0 ? 1.0 : -1.0);
}

bool mvr_mesh_tangents(const float *positions, const float *normals, const float *uvs, uint32_t vertex_count,
                       const uint32_t *indices, size_t index_count, float *out)
{
    uint32_t *rep = malloc((size_t)vertex_count * sizeof *rep);
    double *acc = calloc((size_t)vertex_count * 4, sizeof *acc);
    if (!rep || !acc || !weld(positions, normals, uvs, vertex_count, rep)) {
        free(rep);
        free(acc);
        return false;
    }
    for (size_t f = 0; f + 2 < index_count; f += 3)
        for (int c = 0; c < 3; ++c) {
            uint32_t v = rep[indices[f + (size_t)c]];
            add_corner(positions, normals, uvs, indices + f, c, acc + (size_t)v * 4, acc + (size_t)v * 4 + 3);
        }
    for (uint32_t v = 0; v < vertex_count; ++v) {
        const double *a = acc + (size_t)rep[v] * 4;
        double n[3], t[3];
        unit_normal(normals, v, n);
        if (!tangent_plane(a, n, t)) {
            /* no usable triangle: any direction in the normal's plane */
            double up[3] = {fabs(n[0]) < 0.9 ? 1.0 : 0.0, fabs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0};
            tangent_plane(up, n, t);
        }
        for (int k = 0; k < 3; ++k)
            out[(size_t)v * 4 + (size_t)k] = (float)t[k];
        out[(size_t)v * 4 + 3] = a[3] < 0.0 ? -1.0f : 1.0f;
    }
    free(rep);
    free(acc);
    return true;
}
