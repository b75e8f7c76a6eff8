/* Views laid out around a scene's bounds (mvr_view_set_frame_scene): by
 * default from above, each as close as keeps the bounding box's corners
 * inside it; or a row of eyes on a camera node of the scene
 * (mvr_view_set_from_camera). */
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
    case MVR_LAYOUT_RANDOM: return "random";
    }
    return NULL;
}

double mvr_stereo_default_ipd(double viewing_distance)
{
    return viewing_distance > 0 && isfinite(viewing_distance) ? viewing_distance / 30.0 : 0.064;
}

/* The centre of the scene's bounding sphere and its radius (the origin and
 * 1 for a scene that draws nothing: false then). */
static bool bounding_sphere(const mvr_scene *scene, double c[3], double *radius)
{
    bool real = false;
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
        real = r > 1e-9 && isfinite(r);
        if (!real)
            r = 1.0;
    }
    *radius = r;
    return real;
}

/* The smallest and the largest field of view a framing takes: near 0 the
 * framing distance grows without bound, near pi the frustum's edge reaches
 * the 90 degrees the view set refuses. */
#define MIN_YFOV 1e-3
#define MAX_YFOV 3.1
/* Camera distances past this many scene units are refused, as MAX_IPD. */
#define MAX_RADIUS 1e9
#define MAX_MARGIN 0.9

/* What every view of one framing shares: the scene's bounds, the lens and
 * how far the cameras stand. */
typedef struct framing {
    double c[3], r;              /* the bounds' centre and half-diagonal (the bounding sphere) */
    double lo[3], hi[3];         /* the bounding box */
    double yfov;                 /* radians */
    double tan_x, tan_y;         /* tangents of the half fields of view */
    double dist;                 /* the sphere fit's distance, or desc.radius (stereo, grid: their fit's) */
    double radius, margin;       /* desc's (margin: the default's when the box fit is the default) */
    bool fit_box;                /* the box fit: the default, unless radius, fit_sphere or cube */
    double elevation;            /* stereo, ring, grid: radians above the horizon */
    mvr_up_axis up;
} framing;

/* A vector of the layouts' own frame (+Y up, the stereo eyes on +Z) in the
 * world's: identity for Y-up; for Z-up (x, y, z) -> (x, -z, y), the
 * rotation Blender's glTF exporter undoes ((x, y, z) -> (x, z, -y)). */
static void to_world(mvr_up_axis up, const double l[3], double w[3])
{
    if (up == MVR_UP_Z) {
        w[0] = l[0];
        w[1] = -l[2];
        w[2] = l[1];
    } else {
        w[0] = l[0];
        w[1] = l[1];
        w[2] = l[2];
    }
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static bool normalize3(double v[3])
{
    double len = sqrt(dot3(v, v));
    if (!(len > 0) || !isfinite(len))
        return false;
    for (int k = 0; k < 3; ++k)
        v[k] /= len;
    return true;
}

/* The least distance from the centre along back (unit, world; the camera
 * looks along -back with up as its up hint) at which every corner of the
 * bounding box projects inside the image less the margin: a corner q
 * (relative to the centre) at x, y in the camera's right and up axes and
 * `along` on back is inside where |x| <= k_x (d - along), likewise y. The
 * largest of these bounds is met with equality, so the box touches the
 * inset on that axis. A stereo row of parallel eyes shifted up to
 * `shift` + `spread` d along the right axis moves x by as much: the worst
 * eye's bound is (k_x d - shift - spread d >= k_x along + |x|), solved
 * for d; where the eyes spread faster than the view widens (spread >=
 * k_x, hundreds of eyes) no distance fits them all and the central view's
 * fit is taken. */
static double row_fit_distance(const framing *f, const double back[3], const double up[3], double shift,
                               double spread)
{
    double fwd[3] = {-back[0], -back[1], -back[2]}, right[3], cam_up[3];
    cross3(fwd, up, right);
    if (!normalize3(right))
        return f->dist;
    cross3(right, fwd, cam_up);
    double kx = (1.0 - f->margin) * f->tan_x, ky = (1.0 - f->margin) * f->tan_y;
    if (!(kx - spread > kx * 1e-3))
        shift = spread = 0;
    double d = 0, along_max = -INFINITY;
    for (int corner = 0; corner < 8; ++corner) {
        double q[3];
        for (int k = 0; k < 3; ++k)
            q[k] = ((corner >> k) & 1 ? f->hi[k] : f->lo[k]) - f->c[k];
        double along = dot3(q, back);
        d = fmax(d, (kx * along + fabs(dot3(q, right)) + shift) / (kx - spread));
        d = fmax(d, along + fabs(dot3(q, cam_up)) / ky);
        along_max = fmax(along_max, along);
    }
    /* a box seen end-on along the axis: keep its nearest corner in front */
    return fmax(d, along_max + f->r * 1e-3);
}

static double box_fit_distance(const framing *f, const double back[3], const double up[3])
{
    return row_fit_distance(f, back, up, 0, 0);
}

/* View v at the centre plus offset (the layout's frame), looking at the
 * centre plus target (NULL: the centre) with up (the layout's frame). An
 * orbiting view (around the centre) stands at the framing's distance along
 * its direction when radius or the box fit ask; znear keeps the whole
 * bounding sphere in front. */
static void place(const framing *f, mvr_view_desc *v, const double offset[3], const double target[3],
                  const double up[3], bool orbiting)
{
    double eye_w[3], target_w[3] = {0, 0, 0}, up_w[3];
    to_world(f->up, offset, eye_w);
    to_world(f->up, up, up_w);
    if (target)
        to_world(f->up, target, target_w);
    if (orbiting && (f->fit_box || f->radius > 0)) {
        double back[3] = {eye_w[0], eye_w[1], eye_w[2]};
        if (normalize3(back)) {
            double d = f->fit_box ? box_fit_distance(f, back, up_w) : f->radius;
            for (int k = 0; k < 3; ++k)
                eye_w[k] = back[k] * d;
            v->projection.znear = fmax(d - f->r, d * 1e-3) * 0.5;
        }
    }
    double eye[3], at[3];
    for (int k = 0; k < 3; ++k) {
        eye[k] = f->c[k] + eye_w[k];
        at[k] = f->c[k] + target_w[k];
    }
    mvr_view_look_at(v, eye, at, up_w);
}

/* splitmix64 (Steele, Lea and Flood 2014, "Fast splittable pseudorandom
 * number generators"): a whole sequence from one 64-bit seed, any seed. */
static uint64_t splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* uniform in [0, 1): the top 53 bits */
static double uniform01(uint64_t *state)
{
    return (double)(splitmix64(state) >> 11) * (1.0 / 9007199254740992.0);
}

/* n unit directions (the layout's frame) in the band of heights [h_lo,
 * h_hi] on +Y, uniform by area (Archimedes: height and azimuth uniform),
 * each at least min_spacing radians from those before (dart throwing, the
 * Poisson-disk sampling of Cook 1986), in at most 100 n + 10000 throws. */
static mvr_result random_directions(double (*dirs)[3], uint32_t n, double h_lo, double h_hi, uint64_t seed,
                                    double min_spacing, mvr_error *error)
{
    uint64_t state = seed;
    double cos_min = cos(min_spacing);
    uint64_t tries = 0, max_tries = 100ull * n + 10000ull;
    uint32_t placed = 0;
    while (placed < n) {
        if (tries++ >= max_tries)
            return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_view_set_frame_scene: random layout: min_spacing %g rad leaves room for %u of "
                                 "%u views (after %llu tries); ask for a smaller spacing, fewer views or a wider "
                                 "elevation band",
                                 min_spacing, placed, n, (unsigned long long)max_tries);
        double h = h_lo + (h_hi - h_lo) * uniform01(&state), a = 2.0 * PI * uniform01(&state);
        double ring = sqrt(fmax(1.0 - h * h, 0.0));
        double d[3] = {ring * sin(a), h, ring * cos(a)};
        bool apart = true;
        for (uint32_t j = 0; j < placed && apart; ++j)
            apart = !(min_spacing > 0) || dot3(d, dirs[j]) < cos_min;
        if (apart)
            memcpy(dirs[placed++], d, sizeof d);
    }
    return MVR_OK;
}

/* The descriptor's camera sampling fields, checked: NaN fails every
 * comparison, so each test is written to pass only in range. */
static mvr_result check_sampling(const mvr_framing_desc *d, mvr_error *error)
{
    const char *fn = "mvr_view_set_frame_scene";
    if (!(d->yfov == 0 || (d->yfov >= MIN_YFOV && d->yfov <= MAX_YFOV)))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "%s: yfov %g (radians in [%g, %g]; 0 = 50 degrees)",
                             fn, d->yfov, MIN_YFOV, MAX_YFOV);
    if (!(d->radius >= 0 && d->radius <= MAX_RADIUS))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "%s: radius %g (a distance in (0, %g] scene units; 0 = fitted)", fn, d->radius,
                             MAX_RADIUS);
    if (!(d->margin >= 0 && d->margin <= MAX_MARGIN))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "%s: margin %g (a fraction of the image in [0, %g])", fn, d->margin, MAX_MARGIN);
    if (d->radius > 0 && d->fit_box)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "%s: radius %g and fit_box: give the distance or fit the box, not both", fn, d->radius);
    if (d->radius > 0 && d->margin > 0)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "%s: radius %g and margin %g: give the distance or fit the box, not both", fn, d->radius,
                             d->margin);
    if (d->fit_sphere && (d->fit_box || d->margin > 0 || d->radius > 0))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "%s: fit_sphere fits the bounding sphere: not with fit_box, margin or radius", fn);
    bool elevated = d->layout == MVR_LAYOUT_STEREO || d->layout == MVR_LAYOUT_RING || d->layout == MVR_LAYOUT_GRID;
    if (!(fabs(d->elevation) < PI / 2))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "%s: elevation %g (radians in (-pi/2, pi/2))", fn,
                             d->elevation);
    if ((d->elevation != 0 || d->level) && !elevated)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "%s: %s is for the stereo, ring and grid layouts (not %s; sphere, random and orbit take "
                             "elevation_min and elevation_max)",
                             fn, d->level ? "level" : "elevation", mvr_view_layout_name(d->layout));
    if (d->level && d->elevation != 0)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "%s: level and elevation %g: one or the other", fn,
                             d->elevation);
    if (!(d->min_spacing >= 0 && d->min_spacing <= PI))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "%s: min_spacing %g (radians in [0, pi])", fn,
                             d->min_spacing);
    if (d->up != MVR_UP_Y && d->up != MVR_UP_Z)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "%s: up %d (MVR_UP_Y or MVR_UP_Z)", fn, (int)d->up);
    if (d->hemisphere != MVR_HEMISPHERE_FULL && d->hemisphere != MVR_HEMISPHERE_UPPER)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "%s: hemisphere %d (FULL or UPPER)", fn,
                             (int)d->hemisphere);
    bool around = d->layout == MVR_LAYOUT_SPHERE || d->layout == MVR_LAYOUT_RANDOM || d->layout == MVR_LAYOUT_ORBIT;
    if (d->hemisphere == MVR_HEMISPHERE_UPPER && !around)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "%s: hemisphere UPPER is for the sphere, random and orbit layouts (not %s)", fn,
                             mvr_view_layout_name(d->layout));
    if (d->layout == MVR_LAYOUT_CUBE && (d->yfov != 0 || d->radius > 0 || d->fit_box || d->margin > 0 ||
                                         d->fit_sphere))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "%s: the cube layout's six 90-degree views stand at the centre: yfov, radius, fit_box, "
                             "margin and fit_sphere do not apply", fn);
    return MVR_OK;
}

/* The elevation band (radians) of the sphere, random and orbit layouts,
 * checked, with the upper hemisphere's clip. */
static mvr_result elevation_band(const mvr_framing_desc *d, double *lo, double *hi, mvr_error *error)
{
    double el_lo = d->elevation_min, el_hi = d->elevation_max;
    bool orbit = d->layout == MVR_LAYOUT_ORBIT;
    if (el_lo == 0.0 && el_hi == 0.0) {
        el_lo = orbit ? -15.0 * PI / 180.0 : -PI / 2;
        el_hi = orbit ? 60.0 * PI / 180.0 : PI / 2;
    }
    /* an orbit ring at a pole would be one point with up along the view */
    bool inside = orbit ? (el_lo > -PI / 2 && el_hi < PI / 2) : (el_lo >= -PI / 2 && el_hi <= PI / 2);
    if (!(inside && el_lo <= el_hi))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_view_set_frame_scene: %s elevations %g .. %g rad are not an interval inside "
                             "%s-pi/2, pi/2%s",
                             mvr_view_layout_name(d->layout), el_lo, el_hi, orbit ? "(" : "[", orbit ? ")" : "]");
    if (d->hemisphere == MVR_HEMISPHERE_UPPER) {
        if (el_hi < 0)
            return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_view_set_frame_scene: hemisphere UPPER with elevations %g .. %g rad: no view "
                                 "is above the horizon",
                                 el_lo, el_hi);
        el_lo = fmax(el_lo, 0.0);
    }
    *lo = el_lo;
    *hi = el_hi;
    return MVR_OK;
}

/* The bounds, the lens and the framing distance of a scene. */
static void framing_init(const mvr_scene *scene, const mvr_framing_desc *d, double aspect, framing *f)
{
    memset(f, 0, sizeof *f);
    bool has_bounds = bounding_sphere(scene, f->c, &f->r);
    mvr_scene_info info;
    mvr_scene_get_info(scene, &info);
    for (int k = 0; k < 3; ++k) {
        /* a scene that draws nothing: the cube inside the unit sphere */
        f->lo[k] = has_bounds ? info.bounds_min[k] : f->c[k] - f->r / sqrt(3.0);
        f->hi[k] = has_bounds ? info.bounds_max[k] : f->c[k] + f->r / sqrt(3.0);
    }
    double yfov = d->yfov > 0 ? d->yfov : 50.0 * PI / 180.0;
    f->yfov = yfov;
    f->tan_y = tan(yfov * 0.5);
    f->tan_x = f->tan_y * aspect;
    /* far enough that the sphere fits the narrower of the two directions,
     * with a margin */
    double half = fmin(yfov * 0.5, atan(tan(yfov * 0.5) * aspect));
    f->dist = d->radius > 0 ? d->radius : f->r / sin(half) * 1.05;
    f->radius = d->radius;
    f->fit_box = d->layout != MVR_LAYOUT_CUBE && !d->fit_sphere && !(d->radius > 0);
    f->margin = d->fit_box || d->margin > 0 ? d->margin : MVR_FRAMING_DEFAULT_MARGIN;
    f->elevation = d->level ? 0.0 : d->elevation != 0 ? d->elevation : MVR_FRAMING_DEFAULT_ELEVATION;
    f->up = d->up;
}

/* The stereo, ring and grid views' axes (the layouts' frame) at an
 * elevation: back (from the centre toward the camera) and the camera's up,
 * both normal to the horizontal right axis +X, so up is never along the
 * view whatever the elevation. */
static void elevated_axes(double elevation, double back[3], double cam_up[3])
{
    double s = sin(elevation), c = cos(elevation);
    back[0] = 0;
    back[1] = s;
    back[2] = c;
    cam_up[0] = 0;
    cam_up[1] = c;
    cam_up[2] = -s;
}

/* View i of n of the layouts around the centre (all but random's, whose
 * directions come in dirs): its pose and projection. */
static void frame_view(const framing *f, const mvr_framing_desc *d, uint32_t i, uint32_t n, double ipd, double el_lo,
                       double el_hi, const double (*dirs)[3], mvr_view_desc *v)
{
    const double up[3] = {0, 1, 0}, pole_up[3] = {0, 0, -1};
    double dist = f->dist, r = f->r;
    switch (d->layout) {
    case MVR_LAYOUT_STEREO: {
        /* the row along the horizontal right axis, each eye looking down
         * the elevation's axis: parallel axes */
        double back[3], cam_up[3], offset = ((double)i - (double)(n - 1) * 0.5) * ipd;
        elevated_axes(f->elevation, back, cam_up);
        double eye[3] = {offset, back[1] * dist, back[2] * dist}, target[3] = {offset, 0, 0};
        place(f, v, eye, target, cam_up, false);
        break;
    }
    case MVR_LAYOUT_CUBE: {
        static const double dirs6[6][6] = {{1, 0, 0, 0, 1, 0}, {-1, 0, 0, 0, 1, 0}, {0, 1, 0, 0, 0, 1},
                                           {0, -1, 0, 0, 0, -1}, {0, 0, 1, 0, 1, 0}, {0, 0, -1, 0, 1, 0}};
        const double *q = dirs6[i % 6], at_centre[3] = {0, 0, 0};
        place(f, v, at_centre, q, q + 3, false);
        v->projection.type = MVR_PROJECTION_FRUSTUM;
        v->projection.angle_left = v->projection.angle_down = -PI / 4;
        v->projection.angle_right = v->projection.angle_up = PI / 4;
        break;
    }
    case MVR_LAYOUT_RING: {
        /* the elevation's axes turned by a about the up axis */
        double a = 2.0 * PI * (double)i / (double)n, back[3], cam_up[3];
        elevated_axes(f->elevation, back, cam_up);
        double eye[3] = {dist * back[2] * sin(a), dist * back[1], dist * back[2] * cos(a)};
        double view_up[3] = {cam_up[2] * sin(a), cam_up[1], cam_up[2] * cos(a)};
        place(f, v, eye, NULL, view_up, true);
        break;
    }
    case MVR_LAYOUT_SPHERE: {
        /* the Fibonacci lattice: heights evenly spaced over the band (so
         * evenly by area), each point turned by the golden angle from the
         * last (Gonzalez 2010, "Measurement of areas on a sphere using
         * Fibonacci and latitude-longitude lattices") */
        double h_hi = sin(el_hi), h_lo = sin(el_lo);
        double y = h_hi - (h_hi - h_lo) * ((double)i + 0.5) / (double)n;
        double ring = sqrt(fmax(1.0 - y * y, 0.0)), a = (double)i * PI * (3.0 - sqrt(5.0));
        double eye[3] = {dist * ring * sin(a), dist * y, dist * ring * cos(a)};
        /* near a pole the world's up is nearly the view axis: -Z instead */
        place(f, v, eye, NULL, fabs(y) > 0.999 ? pole_up : up, true);
        break;
    }
    case MVR_LAYOUT_RANDOM: {
        const double *q = dirs[i];
        double eye[3] = {dist * q[0], dist * q[1], dist * q[2]};
        place(f, v, eye, NULL, fabs(q[1]) > 0.999 ? pole_up : up, true);
        break;
    }
    case MVR_LAYOUT_ORBIT: {
        /* ring k of rows holds n / rows views, the first n % rows one more */
        uint32_t rows = d->rows ? d->rows : 3u;
        uint32_t per = n / rows, extra = n % rows, k = 0, first = 0;
        while (i >= first + per + (k < extra ? 1u : 0u)) {
            first += per + (k < extra ? 1u : 0u);
            k++;
        }
        uint32_t count = per + (k < extra ? 1u : 0u);
        double el = rows > 1 ? el_lo + (el_hi - el_lo) * (double)k / (double)(rows - 1) : 0.5 * (el_lo + el_hi);
        double a = 2.0 * PI * ((double)(i - first) + 0.5 * (double)(k % 2)) / (double)count;
        double eye[3] = {dist * cos(el) * sin(a), dist * sin(el), dist * cos(el) * cos(a)};
        place(f, v, eye, NULL, up, true);
        break;
    }
    case MVR_LAYOUT_GRID: {
        /* cameras r/4 apart on a plane in front of the scene (normal to the
         * elevation's axis), toed in */
        uint32_t cols = (uint32_t)ceil(sqrt((double)n));
        double spacing = r * 0.25, back[3], cam_up[3];
        elevated_axes(f->elevation, back, cam_up);
        double x = ((double)(i % cols) - (double)(cols - 1) * 0.5) * spacing;
        double y = ((double)(cols - 1) * 0.5 - (double)(i / cols)) * spacing;
        double eye[3] = {x, back[1] * dist + cam_up[1] * y, back[2] * dist + cam_up[2] * y};
        place(f, v, eye, NULL, cam_up, false);
        break;
    }
    }
}

/* Whether every corner of the bounding box lies in front of the posed
 * view v and inside its image less the margin. */
static bool corners_inside(const framing *f, const mvr_view_desc *v)
{
    double x = v->orientation[0], y = v->orientation[1], z = v->orientation[2], w = v->orientation[3];
    const double right[3] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    const double up[3] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
    const double fwd[3] = {-2 * (x * z + w * y), -2 * (y * z - w * x), -(1 - 2 * (x * x + y * y))};
    double kx = (1.0 - f->margin) * f->tan_x, ky = (1.0 - f->margin) * f->tan_y;
    for (int corner = 0; corner < 8; ++corner) {
        double p[3];
        for (int k = 0; k < 3; ++k)
            p[k] = ((corner >> k) & 1 ? f->hi[k] : f->lo[k]) - v->position[k];
        double depth = dot3(p, fwd);
        if (!(depth > 0 && fabs(dot3(p, right)) <= kx * depth && fabs(dot3(p, up)) <= ky * depth))
            return false;
    }
    return true;
}

/* Whether every view of the grid at plane distance dist keeps the box. */
static bool grid_fits(const framing *f, const mvr_framing_desc *d, uint32_t n, double dist)
{
    framing at = *f;
    at.dist = dist;
    for (uint32_t i = 0; i < n; ++i) {
        mvr_view_desc v;
        memset(&v, 0, sizeof v);
        frame_view(&at, d, i, n, 0, 0, 0, NULL, &v);
        if (!corners_inside(&at, &v))
            return false;
    }
    return true;
}

/* The grid's plane distance: its toed-in cameras have no closed form, so
 * the least distance that keeps the box in every view is searched, from
 * the central view's fit growing by 1/4 until every view fits, then
 * bisected to 1e-12 of it; where none fits (not in 60 steps) the central
 * view's fit is kept. */
static double grid_fit_distance(const framing *f, const mvr_framing_desc *d, uint32_t n, double central)
{
    double lo = central, hi = central;
    int steps = 0;
    while (!grid_fits(f, d, n, hi)) {
        if (++steps > 60)
            return central;
        lo = hi;
        hi *= 1.25;
    }
    if (steps == 0)
        return hi;
    while (hi - lo > hi * 1e-12) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
            break;
        if (grid_fits(f, d, n, mid))
            hi = mid;
        else
            lo = mid;
    }
    return hi;
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
    static const uint32_t defaults[] = {2, 6, 8, 9, 50, 24, 50};
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
    mvr_result checked = check_sampling(&d, error);
    if (checked != MVR_OK)
        return checked;
    uint32_t rows = d.rows ? d.rows : 3u;
    if (d.layout == MVR_LAYOUT_ORBIT && rows > n)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_view_set_frame_scene: %u orbit rings for %u views", rows, n);
    double el_lo = 0, el_hi = 0;
    if (d.layout == MVR_LAYOUT_ORBIT || d.layout == MVR_LAYOUT_SPHERE || d.layout == MVR_LAYOUT_RANDOM) {
        checked = elevation_band(&d, &el_lo, &el_hi, error);
        if (checked != MVR_OK)
            return checked;
    }
    double aspect = d.aspect > 0 ? d.aspect : 1.0;
    framing f;
    framing_init(scene, &d, aspect, &f);
    if (f.fit_box && (d.layout == MVR_LAYOUT_STEREO || d.layout == MVR_LAYOUT_GRID)) {
        /* one distance for the row or plane: the least at which every view
         * keeps every corner (the row's eyes reach (n - 1) / 2 ipd out;
         * the default ipd is d / 30) */
        double back_l[3], up_l[3], back[3], up_w[3];
        elevated_axes(f.elevation, back_l, up_l);
        to_world(f.up, back_l, back);
        to_world(f.up, up_l, up_w);
        double reach = (double)(n - 1) * 0.5;
        if (d.layout == MVR_LAYOUT_STEREO)
            f.dist = d.ipd > 0 ? row_fit_distance(&f, back, up_w, reach * d.ipd, 0)
                               : row_fit_distance(&f, back, up_w, 0, reach / 30.0);
        else
            f.dist = grid_fit_distance(&f, &d, n, box_fit_distance(&f, back, up_w));
    }
    double ipd = d.ipd > 0 ? d.ipd : mvr_stereo_default_ipd(f.dist);
    double znear = fmax(f.dist - f.r, f.dist * 1e-3) * 0.5;
    if (d.layout == MVR_LAYOUT_CUBE)
        znear = f.r * 1e-3;

    double(*dirs)[3] = NULL;
    if (d.layout == MVR_LAYOUT_RANDOM) {
        dirs = calloc(n, sizeof *dirs);
        if (!dirs)
            return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_view_set_frame_scene: out of memory");
        double h_lo = sin(el_lo), h_hi = sin(el_hi);
        /* the band's area on the unit sphere is 2 pi (h_hi - h_lo) */
        double spacing = d.min_spacing > 0 ? d.min_spacing : 0.5 * sqrt(2.0 * PI * (h_hi - h_lo) / (double)n);
        checked = random_directions(dirs, n, h_lo, h_hi, d.seed, spacing, error);
        if (checked != MVR_OK) {
            free(dirs);
            return checked;
        }
    }
    mvr_view_desc *views = calloc(n, sizeof *views);
    if (!views) {
        free(dirs);
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_view_set_frame_scene: out of memory");
    }
    for (uint32_t i = 0; i < n; ++i) {
        mvr_view_desc *v = &views[i];
        v->projection.type = MVR_PROJECTION_PERSPECTIVE;
        v->projection.yfov = f.yfov;
        v->projection.aspect = aspect;
        v->projection.znear = znear;
        frame_view(&f, &d, i, n, ipd, el_lo, el_hi, (const double(*)[3])dirs, v);
    }
    free(dirs);
    mvr_view_set_desc vd;
    memset(&vd, 0, sizeof vd);
    vd.view_count = n;
    vd.views = views;
    vd.origin_set = true; /* the scene's center: every view is near it */
    memcpy(vd.origin, f.c, sizeof f.c);
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
