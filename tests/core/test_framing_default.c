/* core: the default framing of mvr_view_set_frame_scene (issue 35). Every
 * layout but cube fits the bounding box: each of its 8 corners projects
 * inside every view less MVR_FRAMING_DEFAULT_MARGIN of the half-image, and
 * the box reaches that inset (in each orbiting view; in one view of the
 * stereo row and the grid). Stereo, ring and grid look down from 30
 * degrees (or the elevation asked, or level). Degenerate bounds (a point, a
 * plane of no thickness, a line, one along the view), huge and tiny scenes
 * far from the origin, and elevations near the pole give finite views that
 * keep the box. Checked through the public camera metadata. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mvr/mvr.h"
#include "mvr_test.h"

#define PI_ 3.14159265358979323846
#define W 320u
#define H 240u

/* A scene whose bounds are lo .. hi: two triangles spanning the corners
 * (for a line or a point they are degenerate; the bounds still are). */
static mvr_scene *bounds_scene(const double lo[3], const double hi[3])
{
    mvr_scene *s = NULL;
    if (mvr_scene_create(NULL, &s, NULL) != MVR_OK)
        return NULL;
    /* the node carries the offset, so the float positions stay exact */
    double c[3];
    float a[3], b[3];
    for (int k = 0; k < 3; ++k) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        a[k] = (float)(lo[k] - c[k]);
        b[k] = (float)(hi[k] - c[k]);
    }
    const float pos[18] = {a[0], a[1], a[2], b[0], a[1], a[2], b[0], b[1], a[2],
                           a[0], a[1], b[2], b[0], b[1], b[2], a[0], b[1], b[2]};
    mvr_primitive_desc p = {0};
    p.vertex_count = 6;
    p.positions = pos;
    mvr_mesh_desc m = {.primitives = &p, .primitive_count = 1, .name = "bounds"};
    mvr_mesh_id mesh;
    mvr_node_desc n = {0};
    memcpy(n.translation, c, sizeof c);
    mvr_node_id node;
    if (mvr_scene_add_mesh(s, &m, &mesh) != MVR_OK || (n.mesh = mesh, mvr_scene_add_node(s, &n, &node)) != MVR_OK) {
        mvr_scene_destroy(s);
        return NULL;
    }
    return s;
}

/* The largest |u|, |v| of the scene's box corners in view i, as fractions
 * of the half-image (1 = the image's edge); false if a corner is behind the
 * near plane or any value is not finite. */
static bool corner_reach(const mvr_view_set *vs, uint32_t i, const mvr_scene *s, double *reach)
{
    mvr_view_camera c;
    memset(&c, 0, sizeof c);
    if (mvr_view_set_get_camera(vs, i, W, H, &c) != MVR_OK || !c.perspective)
        return false;
    mvr_view_desc v;
    if (mvr_view_set_get_view(vs, i, &v) != MVR_OK)
        return false;
    mvr_scene_info info;
    mvr_scene_get_info(s, &info);
    *reach = 0;
    for (int corner = 0; corner < 8; ++corner) {
        double p[3], q[3];
        for (int k = 0; k < 3; ++k)
            p[k] = (corner >> k) & 1 ? info.bounds_max[k] : info.bounds_min[k];
        for (int r = 0; r < 3; ++r) /* column-major: element (r, col) at col * 4 + r */
            q[r] = c.world_to_camera[r] * p[0] + c.world_to_camera[4 + r] * p[1] + c.world_to_camera[8 + r] * p[2] +
                   c.world_to_camera[12 + r];
        double depth = -q[2];
        if (!(depth >= v.projection.znear) || !isfinite(depth))
            return false;
        double u = (c.fx * q[0] / depth + c.cx) / (0.5 * W) - 1.0, w = (c.fy * -q[1] / depth + c.cy) / (0.5 * H) - 1.0;
        *reach = fmax(*reach, fmax(fabs(u), fabs(w)));
    }
    return isfinite(*reach);
}

/* Every view keeps every corner inside 1 - margin, to 1e-7 plus what
 * double rounding of world positions allows (1e-15 of the distance from
 * the origin, relative to the scene's size: 2e-4 for a 1e-4 scene 1e7
 * away); the largest reach, over all views, is returned. */
static double check_fit(mvr_test_state *t, const mvr_scene *s, const mvr_framing_desc *fd, const char *what)
{
    mvr_view_set *vs = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_view_set_frame_scene(s, fd, &vs, &err) == MVR_OK, "%s: %s", what, err.message);
    if (!vs)
        return 0;
    double most = 0, inset = 1.0 - (fd->margin > 0 || fd->fit_box ? fd->margin : MVR_FRAMING_DEFAULT_MARGIN);
    mvr_scene_info info;
    mvr_scene_get_info(s, &info);
    double far = 0, size = 0;
    for (int k = 0; k < 3; ++k) {
        far = fmax(far, fmax(fabs(info.bounds_min[k]), fabs(info.bounds_max[k])));
        size = fmax(size, info.bounds_max[k] - info.bounds_min[k]);
    }
    double tol = 1e-7 + (size > 0 ? 1e-15 * far / size : 0);
    for (uint32_t i = 0; i < mvr_view_set_count(vs); ++i) {
        double reach = 0;
        bool front = corner_reach(vs, i, s, &reach);
        CHECK_MSG(t, front && reach <= inset + tol, "%s view %u: the box reaches %.9g of the half-image (inset %g)",
                  what, i, reach, inset);
        most = fmax(most, reach);
    }
    mvr_view_set_destroy(vs);
    return most;
}

static const mvr_view_layout layouts[] = {MVR_LAYOUT_STEREO, MVR_LAYOUT_RING, MVR_LAYOUT_GRID,
                                          MVR_LAYOUT_SPHERE, MVR_LAYOUT_ORBIT, MVR_LAYOUT_RANDOM};

/* A ground plane 40 x 40 with 1-unit objects on it (its box: 40 x 1 x 40),
 * a cube and a tall box: every layout keeps every corner in every view and
 * touches the inset; several views, two aspects, both up axes, the
 * upper hemisphere. */
static void default_fits_every_corner(mvr_test_state *t)
{
    const double boxes[3][6] = {{-20, 0, -20, 20, 1, 20}, {-1, -1, -1, 1, 1, 1}, {3, 0, 3, 4, 10, 5}};
    const double aspects[2] = {4.0 / 3.0, 0.5};
    const uint32_t counts[2] = {0, 5};
    for (int b = 0; b < 3; ++b) {
        mvr_scene *s = bounds_scene(boxes[b], boxes[b] + 3);
        CHECK(t, s != NULL);
        for (size_t l = 0; s && l < sizeof layouts / sizeof *layouts; ++l)
            for (int a = 0; a < 2; ++a)
                for (int up = 0; up < 2; ++up)
                    for (int c = 0; c < 2; ++c) {
                        mvr_framing_desc fd = {.layout = layouts[l], .views = counts[c], .aspect = aspects[a],
                                               .up = up ? MVR_UP_Z : MVR_UP_Y};
                        if (layouts[l] == MVR_LAYOUT_ORBIT && counts[c] == 5)
                            fd.rows = 2;
                        char what[96];
                        snprintf(what, sizeof what, "box %d %s aspect %g up %s views %u", b,
                                 mvr_view_layout_name(layouts[l]), aspects[a], up ? "z" : "y", counts[c]);
                        double most = check_fit(t, s, &fd, what);
                        CHECK_MSG(t, most > 1.0 - MVR_FRAMING_DEFAULT_MARGIN - 1e-6, "%s: reaches only %.6f", what,
                                  most);
                    }
        /* the upper hemisphere and a given margin (0 with fit_box) too */
        mvr_framing_desc fd = {.layout = MVR_LAYOUT_SPHERE, .views = 30, .hemisphere = MVR_HEMISPHERE_UPPER};
        if (s)
            check_fit(t, s, &fd, "upper sphere");
        fd = (mvr_framing_desc){.layout = MVR_LAYOUT_STEREO, .fit_box = true, .margin = 0};
        if (s)
            CHECK(t, check_fit(t, s, &fd, "stereo margin 0") > 1.0 - 1e-6);
        fd = (mvr_framing_desc){.layout = MVR_LAYOUT_STEREO, .views = 4, .ipd = 0.7, .margin = 0.2};
        if (s)
            CHECK(t, check_fit(t, s, &fd, "stereo ipd 0.7 margin 0.2") > 0.8 - 1e-6);
        mvr_scene_destroy(s);
    }
}

/* The angle view i looks down at (the forward axis below the horizon of
 * the up axis). */
static double look_down(const mvr_view_set *vs, uint32_t i, mvr_up_axis up)
{
    mvr_view_camera c;
    mvr_view_set_get_camera(vs, i, W, H, &c);
    const double *back = c.camera_to_world + 8; /* +Z of the camera, world */
    return asin(fmax(-1.0, fmin(1.0, back[up == MVR_UP_Z ? 2 : 1])));
}

/* Stereo, ring and the grid's central view look down from 30 degrees by
 * default, from the elevation asked, or level. */
static void views_look_from_above(mvr_test_state *t)
{
    const double lo[3] = {-20, 0, -20}, hi[3] = {20, 1, 20};
    mvr_scene *s = bounds_scene(lo, hi);
    CHECK(t, s != NULL);
    const mvr_view_layout which[3] = {MVR_LAYOUT_STEREO, MVR_LAYOUT_RING, MVR_LAYOUT_GRID};
    const double asked[4] = {0, 20.0 * PI_ / 180.0, -0.4, 1.5};
    for (int l = 0; s && l < 3; ++l)
        for (int e = 0; e < 5; ++e)
            for (int up = 0; up < 2; ++up) {
                mvr_framing_desc fd = {.layout = which[l], .aspect = 4.0 / 3.0, .up = up ? MVR_UP_Z : MVR_UP_Y};
                if (e < 4)
                    fd.elevation = asked[e];
                else
                    fd.level = true;
                double want = e == 4 ? 0.0 : e == 0 ? MVR_FRAMING_DEFAULT_ELEVATION : asked[e];
                mvr_view_set *vs = NULL;
                mvr_error err;
                CHECK_MSG(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_OK, "%s", err.message);
                uint32_t n = vs ? mvr_view_set_count(vs) : 0;
                for (uint32_t i = 0; i < n; ++i) {
                    if (which[l] == MVR_LAYOUT_GRID && i != n / 2)
                        continue; /* toed in: only the central view is on the axis */
                    double got = look_down(vs, i, fd.up);
                    CHECK_MSG(t, fabs(got - want) < 1e-9, "%s up %s view %u: looks down %.9f rad, not %.9f",
                              mvr_view_layout_name(which[l]), up ? "z" : "y", i, got, want);
                }
                mvr_view_set_destroy(vs);
                char what[64];
                snprintf(what, sizeof what, "%s elevation %g", mvr_view_layout_name(which[l]), want);
                check_fit(t, s, &fd, what);
            }
    mvr_scene_destroy(s);
}

/* Degenerate and extreme bounds: a point, a plane of no thickness (seen
 * level: edge-on), a line across and one along the view, a scene 1e6 wide
 * and one 1e-4 wide 1e7 from the origin. Each gives finite views that keep
 * the box; a point is framed as the unit sphere around it. */
static void degenerate_bounds(mvr_test_state *t)
{
    const double cases[][6] = {
        {2, 3, 4, 2, 3, 4},                                      /* a point */
        {-5, 1, -5, 5, 1, 5},                                    /* a plane, no thickness */
        {-5, 0, 0, 5, 0, 0},                                     /* a line across the view */
        {0, 0, 0, 0, 10 * 0.5, 10 * 0.8660254037844386},         /* a line along the default stereo view */
        {1e7, 1e7, 1e7, 1e7 + 1e6, 1e7 + 1e3, 1e7 + 1e6},        /* huge, far */
        {1e7, -1e7, 1e7, 1e7 + 1e-4, -1e7 + 1e-4, 1e7 + 1e-4},   /* tiny, far */
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; ++k) {
        mvr_scene *s = bounds_scene(cases[k], cases[k] + 3);
        CHECK(t, s != NULL);
        for (size_t l = 0; s && l < sizeof layouts / sizeof *layouts; ++l)
            for (int level = 0; level < 2; ++level) {
                bool elevated = layouts[l] <= MVR_LAYOUT_GRID && layouts[l] != MVR_LAYOUT_CUBE;
                if (level && !elevated)
                    continue;
                mvr_framing_desc fd = {.layout = layouts[l], .aspect = 4.0 / 3.0, .level = level != 0};
                char what[64];
                snprintf(what, sizeof what, "case %zu %s%s", k, mvr_view_layout_name(layouts[l]),
                         level ? " level" : "");
                check_fit(t, s, &fd, what);
            }
        mvr_scene_destroy(s);
    }
}

/* Elevations near the pole: the views' up stays normal to the view axis,
 * so the views are finite and keep the box. */
static void near_the_pole(mvr_test_state *t)
{
    const double lo[3] = {-1, 0, -2}, hi[3] = {1, 0.5, 2};
    mvr_scene *s = bounds_scene(lo, hi);
    CHECK(t, s != NULL);
    const double el[2] = {1.5707963, -1.5707963};
    const mvr_view_layout which[3] = {MVR_LAYOUT_STEREO, MVR_LAYOUT_RING, MVR_LAYOUT_GRID};
    for (int l = 0; s && l < 3; ++l)
        for (int e = 0; e < 2; ++e)
            for (int up = 0; up < 2; ++up) {
                mvr_framing_desc fd = {.layout = which[l], .elevation = el[e], .up = up ? MVR_UP_Z : MVR_UP_Y};
                char what[64];
                snprintf(what, sizeof what, "%s elevation %g up %s", mvr_view_layout_name(which[l]), el[e],
                         up ? "z" : "y");
                check_fit(t, s, &fd, what);
            }
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(default_fits_every_corner), TEST(views_look_from_above), TEST(degenerate_bounds),
              TEST(near_the_pole))
