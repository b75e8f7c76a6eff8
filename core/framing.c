/* Views laid out around a scene's bounding sphere (mvr_view_set_frame_scene),
 * or a row of eyes on a camera node of the scene (mvr_view_set_from_camera). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core_util.h"

#define PI 3.14159265358979323846
/* Eye separations past this many scene units are refused: the eyes' row
 * ((views - 1) x ipd wide) then stays where double poses and the float
 * matrices relative to the origin hold it (1e300 overflowed them to inf). */
#define MAX_IPD 1e9
/* Layer aspect ratios outside [1 / MAX_ASPECT, MAX_ASPECT] are refused: a
 * 16384 x 1 layer is inside; near 0 the framing distance grows without
 * bound (the narrow direction's field of view goes to 0). */
#define MAX_ASPECT 65536.0

/* ipd as the framing functions take it: 0 (the default), or a finite
 * distance in (0, MAX_IPD]; NaN, infinite, negative and larger refused. */
static bool ipd_ok(double ipd)
{
    return ipd >= 0 && ipd <= MAX_IPD;
}

const char *mvr_view_layout_name(mvr_view_layout layout)
{
    switch (layout) {
    case MVR_LAYOUT_STEREO: return "stereo";
    case MVR_LAYOUT_CUBE: return "cube";
    case MVR_LAYOUT_RING: return "ring";
    case MVR_LAYOUT_GRID: return "grid";
    case MVR_LAYOUT_SPHERE: return "sphere";
    case MVR_LAYOUT_ORBIT: return "orbit";
    }
    return NULL;
}

double mvr_stereo_default_ipd(double viewing_distance)
{
    return viewing_distance > 0 && isfinite(viewing_distance) ? viewing_distance / 30.0 : 0.064;
}

/* The centre of the scene's bounding sphere and its radius (the origin and
 * 1 for a scene that draws nothing). */
static void bounding_sphere(const mvr_scene *scene, double c[3], double *radius)
{
    mvr_scene_info info;
    mvr_scene_get_info(scene, &info);
    c[0] = c[1] = c[2] = 0;
    double r = 1.0;
    if (info.bounds_min[0] <= info.bounds_max[0]) {
        double ext2 = 0;
        for (int i = 0; i < 3; ++i) {
            c[i] = 0.5 * (info.bounds_min[i] + info.bounds_max[i]);
            double e = 0.5 * (info.bounds_max[i] - info.bounds_min[i]);
            ext2 += e * e;
        }
        r = sqrt(ext2);
        if (!(r > 1e-9) || !isfinite(r))
            r = 1.0;
    }
    *radius = r;
}

static void look(mvr_view_desc *v, const double eye[3], const double target[3], const double up[3])
{
    mvr_view_look_at(v, eye, target, up);
}

mvr_result mvr_view_set_frame_scene(const mvr_scene *scene, const mvr_framing_desc *desc, mvr_view_set **out,
                                    mvr_error *error)
{
    if (!scene || !out)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_frame_scene: NULL argument");
    *out = NULL;
    mvr_framing_desc d;
    if (desc)
        d = *desc;
    else
        memset(&d, 0, sizeof d);
    if (!mvr_view_layout_name(d.layout))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_frame_scene: unknown layout %d",
                             (int)d.layout);
    static const uint32_t defaults[] = {2, 6, 8, 9, 50, 24};
    uint32_t n = d.views ? d.views : defaults[d.layout];
    if (n > MVR_VIEW_SET_MAX_VIEWS)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_frame_scene: %u views (at most %u)", n,
                             MVR_VIEW_SET_MAX_VIEWS);
    /* 0 = the default; NaN fails every comparison */
    if (!(d.aspect == 0 || (d.aspect >= 1.0 / MAX_ASPECT && d.aspect <= MAX_ASPECT)))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_view_set_frame_scene: aspect %g (width / height in [1/%g, %g]; 0 = 1)", d.aspect,
                             MAX_ASPECT, MAX_ASPECT);
    if (!ipd_ok(d.ipd))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_view_set_frame_scene: ipd %g (a distance in [0, %g] scene units; 0 = scaled to the "
                             "scene)",
                             d.ipd, MAX_IPD);
    uint32_t rows = d.rows ? d.rows : 3u;
    double el_lo = d.elevation_min, el_hi = d.elevation_max;
    if (el_lo == 0.0 && el_hi == 0.0) {
        el_lo = -15.0 * PI / 180.0;
        el_hi = 60.0 * PI / 180.0;
    }
    if (d.layout == MVR_LAYOUT_ORBIT) {
        if (rows > n)
            return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_view_set_frame_scene: %u orbit rings for %u views", rows, n);
        if (!(el_lo > -PI / 2 && el_lo < PI / 2 && el_hi > -PI / 2 && el_hi < PI / 2 && el_lo <= el_hi))
            return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_view_set_frame_scene: orbit elevations %g .. %g rad are not an interval inside "
                                 "(-pi/2, pi/2)",
                                 el_lo, el_hi);
    }
    double aspect = d.aspect > 0 ? d.aspect : 1.0;

    double c[3], r;
    bounding_sphere(scene, c, &r);
    /* vertical field of view 50 degrees; far enough that the sphere fits
     * the narrower of the two directions, with a margin */
    double yfov = 50.0 * PI / 180.0;
    double half = fmin(yfov * 0.5, atan(tan(yfov * 0.5) * aspect));
    double dist = r / sin(half) * 1.05;
    double ipd = d.ipd > 0 ? d.ipd : mvr_stereo_default_ipd(dist);
    double znear = fmax(dist - r, dist * 1e-3) * 0.5;
    if (d.layout == MVR_LAYOUT_CUBE)
        znear = r * 1e-3;

    mvr_view_desc *views = calloc(n, sizeof *views);
    if (!views)
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_view_set_frame_scene: out of memory");
    const double up[3] = {0, 1, 0};
    uint32_t cols = (uint32_t)ceil(sqrt((double)n));
    for (uint32_t i = 0; i < n; ++i) {
        mvr_view_desc *v = &views[i];
        v->projection.type = MVR_PROJECTION_PERSPECTIVE;
        v->projection.yfov = yfov;
        v->projection.aspect = aspect;
        v->projection.znear = znear;
        switch (d.layout) {
        case MVR_LAYOUT_STEREO: {
            double offset = ((double)i - (double)(n - 1) * 0.5) * ipd;
            double eye[3] = {c[0] + offset, c[1], c[2] + dist}, target[3] = {c[0] + offset, c[1], c[2]};
            look(v, eye, target, up);
            break;
        }
        case MVR_LAYOUT_CUBE: {
            static const double dirs[6][6] = {{1, 0, 0, 0, 1, 0}, {-1, 0, 0, 0, 1, 0}, {0, 1, 0, 0, 0, 1},
                                              {0, -1, 0, 0, 0, -1}, {0, 0, 1, 0, 1, 0}, {0, 0, -1, 0, 1, 0}};
            const double *q = dirs[i % 6];
            double target[3] = {c[0] + q[0], c[1] + q[1], c[2] + q[2]}, u[3] = {q[3], q[4], q[5]};
            look(v, c, target, u);
            v->projection.type = MVR_PROJECTION_FRUSTUM;
            v->projection.angle_left = v->projection.angle_down = -PI / 4;
            v->projection.angle_right = v->projection.angle_up = PI / 4;
            break;
        }
        case MVR_LAYOUT_RING: {
            double a = 2.0 * PI * (double)i / (double)n;
            double eye[3] = {c[0] + dist * sin(a), c[1] + r * 0.25, c[2] + dist * cos(a)};
            look(v, eye, c, up);
            break;
        }
        case MVR_LAYOUT_SPHERE: {
            /* the Fibonacci lattice: heights evenly spaced, each point
             * turned by the golden angle from the last (Gonzalez 2010,
             * "Measurement of areas on a sphere using Fibonacci and
             * latitude-longitude lattices") */
            double y = 1.0 - 2.0 * ((double)i + 0.5) / (double)n;
            double ring = sqrt(fmax(1.0 - y * y, 0.0)), a = (double)i * PI * (3.0 - sqrt(5.0));
            double eye[3] = {c[0] + dist * ring * sin(a), c[1] + dist * y, c[2] + dist * ring * cos(a)};
            /* near a pole the world's up is nearly the view axis: -Z instead */
            const double pole_up[3] = {0, 0, -1};
            look(v, eye, c, fabs(y) > 0.999 ? pole_up : up);
            break;
        }
        case MVR_LAYOUT_ORBIT: {
            /* ring k of rows holds n / rows views, the first n % rows one more */
            uint32_t per = n / rows, extra = n % rows, k = 0, first = 0;
            while (i >= first + per + (k < extra ? 1u : 0u)) {
                first += per + (k < extra ? 1u : 0u);
                k++;
            }
            uint32_t count = per + (k < extra ? 1u : 0u);
            double el = rows > 1 ? el_lo + (el_hi - el_lo) * (double)k / (double)(rows - 1) : 0.5 * (el_lo + el_hi);
            double a = 2.0 * PI * ((double)(i - first) + 0.5 * (double)(k % 2)) / (double)count;
            double eye[3] = {c[0] + dist * cos(el) * sin(a), c[1] + dist * sin(el), c[2] + dist * cos(el) * cos(a)};
            look(v, eye, c, up);
            break;
        }
        case MVR_LAYOUT_GRID: {
            /* cameras r/4 apart on a plane in front of the scene, toed in */
            double spacing = r * 0.25;
            double x = ((double)(i % cols) - (double)(cols - 1) * 0.5) * spacing;
            double y = ((double)(cols - 1) * 0.5 - (double)(i / cols)) * spacing;
            double eye[3] = {c[0] + x, c[1] + y, c[2] + dist};
            look(v, eye, c, up);
            break;
        }
        }
    }
    mvr_view_set_desc vd;
    memset(&vd, 0, sizeof vd);
    vd.view_count = n;
    vd.views = views;
    vd.origin_set = true; /* the scene's center: every view is near it */
    memcpy(vd.origin, c, sizeof c);
    mvr_result res = mvr_view_set_create(&vd, out, error);
    free(views);
    return res;
}

mvr_result mvr_view_set_from_camera(const mvr_scene *scene, mvr_node_id camera_node, uint32_t views, double ipd,
                                    mvr_view_set **out, mvr_error *error)
{
    if (!scene || !out)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_from_camera: NULL argument");
    *out = NULL;
    uint32_t n = views ? views : 2;
    if (n > MVR_VIEW_SET_MAX_VIEWS)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_view_set_from_camera: %u views (at most %u)", n,
                             MVR_VIEW_SET_MAX_VIEWS);
    if (!ipd_ok(ipd))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_view_set_from_camera: ipd %g (a distance in [0, %g] scene units; 0 = scaled to the "
                             "scene)",
                             ipd, MAX_IPD);
    mvr_view_desc base;
    mvr_result got = mvr_scene_camera_view(scene, camera_node, &base);
    if (got == MVR_ERROR_OUT_OF_MEMORY)
        return mvr_error_set(error, got, "mvr_view_set_from_camera: out of memory");
    if (got != MVR_OK)
        return mvr_error_set(error, got, "mvr_view_set_from_camera: node %u is not a camera node (the scene has %u)",
                             camera_node.id, mvr_scene_camera_node_count(scene));
    if (!(ipd > 0)) {
        /* the stereo rule of mvr_stereo_default_ipd (1/30 of the distance to
         * the subject), the subject being the scene's bounding sphere */
        double c[3], r, d2 = 0;
        bounding_sphere(scene, c, &r);
        for (int i = 0; i < 3; ++i)
            d2 += (c[i] - base.position[i]) * (c[i] - base.position[i]);
        ipd = mvr_stereo_default_ipd(sqrt(d2));
    }
    mvr_view_desc *v = calloc(n, sizeof *v);
    if (!v)
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_view_set_from_camera: out of memory");
    /* the camera's x axis: its orientation applied to +X */
    double x = base.orientation[0], y = base.orientation[1], z = base.orientation[2], w = base.orientation[3];
    double right[3] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    for (uint32_t i = 0; i < n; ++i) {
        double offset = ((double)i - (double)(n - 1) * 0.5) * ipd;
        v[i] = base; /* same orientation and projection: parallel axes */
        for (int k = 0; k < 3; ++k)
            v[i].position[k] += right[k] * offset;
    }
    mvr_view_set_desc vd;
    memset(&vd, 0, sizeof vd);
    vd.view_count = n;
    vd.views = v;
    vd.origin_set = true; /* the camera: every eye is near it */
    memcpy(vd.origin, base.position, sizeof vd.origin);
    mvr_result res = mvr_view_set_create(&vd, out, error);
    free(v);
    return res;
}
