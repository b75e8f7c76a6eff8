/* core: camera sampling of mvr_view_set_frame_scene (issue 33): the field of
 * view, a fixed camera distance, the bounding box fitted with a margin
 * (objects filled only 4-41% of a ring view when the sphere was fitted), the
 * upper hemisphere, the seeded random layout with its minimum spacing, a
 * Z-up world, and every new field refused when out of range. Checked
 * through the public camera metadata (mvr_view_set_get_camera), as a data
 * pipeline reads the views. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mvr/mvr.h"
#include "mvr_test.h"

#define PI_ 3.14159265358979323846
#define W 640u
#define H 480u

static const double box_lo[3] = {1.0, -0.5, 2.0}, box_hi[3] = {5.0, 0.5, 4.0};

/* A scene whose bounds are box_lo .. box_hi (4 x 1 x 2, off the origin):
 * two triangles spanning the corners. */
static mvr_scene *box_scene(void)
{
    mvr_scene *s = NULL;
    if (mvr_scene_create(NULL, &s, NULL) != MVR_OK)
        return NULL;
    const double *a = box_lo, *b = box_hi;
    const float pos[18] = {(float)a[0], (float)a[1], (float)a[2], (float)b[0], (float)a[1], (float)a[2],
                           (float)b[0], (float)b[1], (float)a[2], (float)a[0], (float)a[1], (float)b[2],
                           (float)b[0], (float)b[1], (float)b[2], (float)a[0], (float)b[1], (float)b[2]};
    mvr_primitive_desc p = {0};
    p.vertex_count = 6;
    p.positions = pos;
    mvr_mesh_desc m = {.primitives = &p, .primitive_count = 1, .name = "box"};
    mvr_mesh_id mesh;
    mvr_node_desc n = {0};
    mvr_node_id node;
    if (mvr_scene_add_mesh(s, &m, &mesh) != MVR_OK || (n.mesh = mesh, mvr_scene_add_node(s, &n, &node)) != MVR_OK) {
        mvr_scene_destroy(s);
        return NULL;
    }
    return s;
}

static void centre(double c[3])
{
    for (int k = 0; k < 3; ++k)
        c[k] = 0.5 * (box_lo[k] + box_hi[k]);
}

static mvr_view_set *frame(mvr_test_state *t, const mvr_scene *s, const mvr_framing_desc *fd)
{
    mvr_view_set *vs = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_view_set_frame_scene(s, fd, &vs, &err) == MVR_OK, "layout %s: %s",
              mvr_view_layout_name(fd->layout), err.message);
    return vs;
}

static mvr_view_camera camera(const mvr_view_set *vs, uint32_t i)
{
    mvr_view_camera c;
    memset(&c, 0, sizeof c);
    mvr_view_set_get_camera(vs, i, W, H, &c);
    return c;
}

/* The position of view i relative to the box's centre. */
static void offset(const mvr_view_set *vs, uint32_t i, double out[3])
{
    mvr_view_camera c = camera(vs, i);
    double ctr[3];
    centre(ctr);
    for (int k = 0; k < 3; ++k)
        out[k] = c.camera_to_world[12 + k] - ctr[k];
}

static const mvr_view_layout around[] = {MVR_LAYOUT_RING, MVR_LAYOUT_SPHERE, MVR_LAYOUT_ORBIT, MVR_LAYOUT_RANDOM};

/* --fov: every framed view has that vertical field of view, so fy is the
 * pinhole's for it: (H / 2) / tan(yfov / 2). */
static void fov_is_the_asked_one(mvr_test_state *t)
{
    mvr_scene *s = box_scene();
    CHECK(t, s != NULL);
    const mvr_view_layout layouts[] = {MVR_LAYOUT_STEREO, MVR_LAYOUT_GRID, MVR_LAYOUT_RING, MVR_LAYOUT_SPHERE,
                                       MVR_LAYOUT_ORBIT, MVR_LAYOUT_RANDOM};
    for (size_t l = 0; s && l < sizeof layouts / sizeof *layouts; ++l) {
        for (int fit = 0; fit < 2; ++fit) {
            double yfov = 30.0 * PI_ / 180.0;
            mvr_framing_desc fd = {.layout = layouts[l], .views = 12, .aspect = (double)W / H, .yfov = yfov,
                                   .fit_box = fit == 1, .margin = fit ? 0.05 : 0.0};
            mvr_view_set *vs = frame(t, s, &fd);
            for (uint32_t i = 0; vs && i < 12; ++i) {
                mvr_view_camera c = camera(vs, i);
                double expect = 0.5 * H / tan(0.5 * yfov);
                CHECK_MSG(t, c.perspective && fabs(c.fy - expect) < 1e-9 * expect && fabs(c.fx - expect) < 1e-9 * expect,
                          "%s view %u: fy %.12g, fx %.12g (yfov 30 degrees: %.12g)", mvr_view_layout_name(layouts[l]),
                          i, c.fy, c.fx, expect);
            }
            mvr_view_set_destroy(vs);
        }
    }
    mvr_scene_destroy(s);
}

/* The largest |u - cx| / (W / 2), |v - cy| / (H / 2) of the box's corners
 * in view i (1 = the image's edge); false if a corner is behind it. */
static bool box_extent(const mvr_view_set *vs, uint32_t i, double *extent)
{
    mvr_view_camera c = camera(vs, i);
    const double *m = c.world_to_camera;
    *extent = 0;
    for (int corner = 0; corner < 8; ++corner) {
        double p[3], q[3];
        for (int k = 0; k < 3; ++k)
            p[k] = (corner >> k) & 1 ? box_hi[k] : box_lo[k];
        for (int r = 0; r < 3; ++r)
            q[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
        double z = -q[2]; /* OpenCV's Z: in front is positive */
        if (!(z > 0))
            return false;
        double u = c.fx * q[0] / z + c.cx, v = c.fy * -q[1] / z + c.cy;
        *extent = fmax(*extent, fmax(fabs(u - c.cx) / (0.5 * W), fabs(v - c.cy) / (0.5 * H)));
    }
    return true;
}

/* --margin: every corner of the bounds projects inside the image less the
 * margin, and the box reaches that inset on one axis: it fills the view
 * (the sphere fit left it at a fraction). */
static void margin_fits_the_box(mvr_test_state *t)
{
    mvr_scene *s = box_scene();
    CHECK(t, s != NULL);
    const double margins[] = {0.0, 0.1, 0.3};
    for (size_t l = 0; s && l < sizeof around / sizeof *around; ++l) {
        for (int up = 0; up < 2; ++up) {
            for (size_t k = 0; k < 3; ++k) {
                mvr_framing_desc fd = {.layout = around[l], .views = 16, .aspect = (double)W / H, .fit_box = true,
                                       .margin = margins[k], .up = up ? MVR_UP_Z : MVR_UP_Y};
                mvr_view_set *vs = frame(t, s, &fd);
                fd.fit_box = false;
                fd.margin = 0;
                fd.fit_sphere = true;
                mvr_view_set *sphere_fit = frame(t, s, &fd);
                for (uint32_t i = 0; vs && sphere_fit && i < 16; ++i) {
                    double e = 0, e_sphere = 0;
                    bool front = box_extent(vs, i, &e);
                    CHECK(t, box_extent(sphere_fit, i, &e_sphere));
                    CHECK_MSG(t, front && fabs(e - (1.0 - margins[k])) < 1e-9,
                              "%s up %s margin %g view %u: the box reaches %.12g of the half-image (expected %g)",
                              mvr_view_layout_name(around[l]), up ? "z" : "y", margins[k], i, e, 1.0 - margins[k]);
                    /* the sphere fit leaves the box short of the edge in every view */
                    if (k == 0)
                        CHECK_MSG(t, e_sphere < e - 0.01, "view %u: sphere fit %.3f, box fit %.3f", i, e_sphere, e);
                }
                mvr_view_set_destroy(vs);
                mvr_view_set_destroy(sphere_fit);
            }
        }
    }
    /* stereo: fitted in the central view, so each eye (ipd / 2 off) is near */
    mvr_framing_desc fd = {.layout = MVR_LAYOUT_STEREO, .views = 1, .aspect = 1.0, .fit_box = true, .margin = 0.2};
    mvr_view_set *vs = s ? frame(t, s, &fd) : NULL;
    double e = 0;
    CHECK(t, vs && box_extent(vs, 0, &e) && fabs(e - 0.8) < 1e-9);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
}

/* --radius: every orbiting camera stands that far from the centre. */
static void radius_is_the_distance(mvr_test_state *t)
{
    mvr_scene *s = box_scene();
    CHECK(t, s != NULL);
    for (size_t l = 0; s && l < sizeof around / sizeof *around; ++l) {
        mvr_framing_desc fd = {.layout = around[l], .views = 10, .radius = 7.25};
        mvr_view_set *vs = frame(t, s, &fd);
        for (uint32_t i = 0; vs && i < 10; ++i) {
            double o[3];
            offset(vs, i, o);
            double d = sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
            CHECK_MSG(t, fabs(d - 7.25) < 1e-9, "%s view %u at %.12g", mvr_view_layout_name(around[l]), i, d);
        }
        mvr_view_set_destroy(vs);
    }
    mvr_scene_destroy(s);
}

/* --hemisphere upper: no camera below the centre's height, along the
 * world's up (Y or Z); the full sphere has some (so the check can fail). */
static void upper_hemisphere_stays_above(mvr_test_state *t)
{
    mvr_scene *s = box_scene();
    CHECK(t, s != NULL);
    const mvr_view_layout layouts[] = {MVR_LAYOUT_SPHERE, MVR_LAYOUT_RANDOM, MVR_LAYOUT_ORBIT};
    for (size_t l = 0; s && l < 3; ++l) {
        for (int up = 0; up < 2; ++up) {
            for (int upper = 0; upper < 2; ++upper) {
                mvr_framing_desc fd = {.layout = layouts[l], .views = 40, .up = up ? MVR_UP_Z : MVR_UP_Y,
                                       .hemisphere = upper ? MVR_HEMISPHERE_UPPER : MVR_HEMISPHERE_FULL};
                mvr_view_set *vs = frame(t, s, &fd);
                uint32_t below = 0;
                for (uint32_t i = 0; vs && i < 40; ++i) {
                    double o[3];
                    offset(vs, i, o);
                    below += o[up ? 2 : 1] < -1e-9;
                }
                CHECK_MSG(t, vs && (upper ? below == 0 : below > 0), "%s up %s %s: %u of 40 views below the centre",
                          mvr_view_layout_name(layouts[l]), up ? "z" : "y", upper ? "upper" : "full", below);
                mvr_view_set_destroy(vs);
            }
        }
    }
    mvr_scene_destroy(s);
}

/* The least angle between two views' directions from the centre. */
static double closest_pair(const mvr_view_set *vs, uint32_t n)
{
    double closest = 10.0;
    for (uint32_t i = 0; i < n; ++i) {
        double a[3];
        offset(vs, i, a);
        double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for (uint32_t j = i + 1; j < n; ++j) {
            double b[3];
            offset(vs, j, b);
            double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
            double cosine = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
            closest = fmin(closest, acos(fmax(-1.0, fmin(1.0, cosine))));
        }
    }
    return closest;
}

/* --layout random --seed S: the same views for a seed, others for another,
 * never two closer than the spacing asked for; elevations in their band. */
static void random_is_seeded_and_spaced(mvr_test_state *t)
{
    mvr_scene *s = box_scene();
    CHECK(t, s != NULL);
    if (!s)
        return;
    mvr_framing_desc fd = {.layout = MVR_LAYOUT_RANDOM, .views = 60, .seed = 42, .min_spacing = 0.3};
    mvr_view_set *a = frame(t, s, &fd), *b = frame(t, s, &fd);
    fd.seed = 43;
    mvr_view_set *other = frame(t, s, &fd);
    if (a && b && other) {
        uint32_t same = 0, differ = 0;
        for (uint32_t i = 0; i < 60; ++i) {
            double pa[3], pb[3], po[3];
            offset(a, i, pa);
            offset(b, i, pb);
            offset(other, i, po);
            same += memcmp(pa, pb, sizeof pa) == 0;
            differ += memcmp(pa, po, sizeof pa) != 0;
        }
        CHECK_EQ_INT(t, same, 60);
        CHECK_EQ_INT(t, differ, 60);
        double ca = closest_pair(a, 60), co = closest_pair(other, 60);
        printf("  random 60 views, min_spacing 0.3: closest pairs %.4f and %.4f rad\n", ca, co);
        CHECK(t, ca >= 0.3 && co >= 0.3);
    }
    mvr_view_set_destroy(a);
    mvr_view_set_destroy(b);
    mvr_view_set_destroy(other);
    /* the default spacing, 0.5 sqrt(4 pi / n), in a band of 10 .. 40 degrees */
    fd = (mvr_framing_desc){.layout = MVR_LAYOUT_RANDOM, .views = 100, .seed = 7,
                            .elevation_min = 10.0 * PI_ / 180.0, .elevation_max = 40.0 * PI_ / 180.0};
    mvr_view_set *band = frame(t, s, &fd);
    if (band) {
        double area = 2.0 * PI_ * (sin(fd.elevation_max) - sin(fd.elevation_min));
        CHECK(t, closest_pair(band, 100) >= 0.5 * sqrt(area / 100.0));
        for (uint32_t i = 0; i < 100; ++i) {
            double o[3];
            offset(band, i, o);
            double el = asin(o[1] / sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]));
            CHECK_MSG(t, el >= fd.elevation_min - 1e-12 && el <= fd.elevation_max + 1e-12, "view %u at %g rad", i,
                      el);
        }
    }
    mvr_view_set_destroy(band);
    /* more views than the spacing leaves room for: refused, naming it */
    fd = (mvr_framing_desc){.layout = MVR_LAYOUT_RANDOM, .views = 100, .min_spacing = 1.0};
    mvr_view_set *vs = NULL;
    mvr_error err;
    CHECK(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_ERROR_INVALID_ARGUMENT && !vs);
    CHECK_MSG(t, strstr(err.message, "min_spacing 1") != NULL, "%s", err.message);
    mvr_scene_destroy(s);
}

/* --up z: the layouts orbit +Z and the cameras' up follows it: a level
 * stereo camera's up is +Z exactly; every orbiting camera's right axis is
 * horizontal (no Z) and its up leans to +Z. */
static void up_z_is_upright(mvr_test_state *t)
{
    mvr_scene *s = box_scene();
    CHECK(t, s != NULL);
    mvr_framing_desc fd = {.layout = MVR_LAYOUT_STEREO, .up = MVR_UP_Z, .level = true};
    mvr_view_set *vs = s ? frame(t, s, &fd) : NULL;
    for (uint32_t i = 0; vs && i < 2; ++i) {
        mvr_view_camera c = camera(vs, i);
        const double *up = c.camera_to_world + 4, *back = c.camera_to_world + 8;
        CHECK_MSG(t, fabs(up[0]) < 1e-12 && fabs(up[1]) < 1e-12 && fabs(up[2] - 1.0) < 1e-12,
                  "stereo eye %u: up (%g, %g, %g)", i, up[0], up[1], up[2]);
        /* Blender's front view: from -Y, looking along +Y */
        CHECK(t, fabs(back[1] + 1.0) < 1e-12);
    }
    mvr_view_set_destroy(vs);
    for (size_t l = 0; s && l < sizeof around / sizeof *around; ++l) {
        fd = (mvr_framing_desc){.layout = around[l], .views = 30, .up = MVR_UP_Z};
        vs = frame(t, s, &fd);
        for (uint32_t i = 0; vs && i < 30; ++i) {
            mvr_view_camera c = camera(vs, i);
            const double *right = c.camera_to_world, *up = c.camera_to_world + 4;
            double o[3];
            offset(vs, i, o);
            /* the sphere's views at a pole turn their up to the layout's -Z (world +Y) */
            bool pole = fabs(o[2]) > 0.999 * sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
            CHECK_MSG(t, pole || (fabs(right[2]) < 1e-12 && up[2] > 0), "%s view %u: right z %g, up z %g",
                      mvr_view_layout_name(around[l]), i, right[2], up[2]);
        }
        mvr_view_set_destroy(vs);
    }
    mvr_scene_destroy(s);
}

/* Each new field out of range is refused with a message naming it. */
static void bad_fields_are_named(mvr_test_state *t)
{
    mvr_scene *s = box_scene();
    CHECK(t, s != NULL);
    if (!s)
        return;
    struct {
        mvr_framing_desc fd;
        const char *names;
    } cases[] = {
        {{.layout = MVR_LAYOUT_RING, .yfov = NAN}, "yfov"},
        {{.layout = MVR_LAYOUT_RING, .yfov = -0.5}, "yfov"},
        {{.layout = MVR_LAYOUT_RING, .yfov = 3.2}, "yfov"},
        {{.layout = MVR_LAYOUT_RING, .radius = -1}, "radius"},
        {{.layout = MVR_LAYOUT_RING, .radius = INFINITY}, "radius"},
        {{.layout = MVR_LAYOUT_RING, .radius = NAN}, "radius"},
        {{.layout = MVR_LAYOUT_RING, .radius = 2, .fit_box = true}, "radius"},
        {{.layout = MVR_LAYOUT_RING, .fit_box = true, .margin = 0.95}, "margin"},
        {{.layout = MVR_LAYOUT_RING, .fit_box = true, .margin = NAN}, "margin"},
        {{.layout = MVR_LAYOUT_RING, .margin = 0.1, .radius = 2}, "margin"},
        {{.layout = MVR_LAYOUT_RING, .elevation = NAN}, "elevation"},
        {{.layout = MVR_LAYOUT_STEREO, .elevation = -1.6}, "elevation"},
        {{.layout = MVR_LAYOUT_ORBIT, .elevation = 0.3}, "elevation"},
        {{.layout = MVR_LAYOUT_SPHERE, .level = true}, "level"},
        {{.layout = MVR_LAYOUT_GRID, .level = true, .elevation = 0.2}, "level"},
        {{.layout = MVR_LAYOUT_RING, .fit_sphere = true, .margin = 0.1}, "fit_sphere"},
        {{.layout = MVR_LAYOUT_STEREO, .fit_sphere = true, .radius = 2}, "fit_sphere"},
        {{.layout = MVR_LAYOUT_CUBE, .fit_sphere = true}, "fit_sphere"},
        {{.layout = MVR_LAYOUT_RANDOM, .min_spacing = -0.1}, "min_spacing"},
        {{.layout = MVR_LAYOUT_RANDOM, .min_spacing = NAN}, "min_spacing"},
        {{.layout = MVR_LAYOUT_RANDOM, .min_spacing = 4.0}, "min_spacing"},
        {{.layout = MVR_LAYOUT_RING, .up = (mvr_up_axis)5}, "up"},
        {{.layout = MVR_LAYOUT_SPHERE, .hemisphere = (mvr_hemisphere)9}, "hemisphere"},
        {{.layout = MVR_LAYOUT_RING, .hemisphere = MVR_HEMISPHERE_UPPER}, "hemisphere"},
        {{.layout = MVR_LAYOUT_CUBE, .yfov = 1.0}, "yfov"},
        {{.layout = MVR_LAYOUT_SPHERE, .elevation_min = NAN, .elevation_max = 1}, "elevations"},
        {{.layout = MVR_LAYOUT_RANDOM, .elevation_min = 0.5, .elevation_max = 0.2}, "elevations"},
        {{.layout = MVR_LAYOUT_RANDOM, .elevation_min = -1, .elevation_max = 1.6}, "elevations"},
        {{.layout = MVR_LAYOUT_RANDOM, .elevation_min = -1, .elevation_max = -0.5,
          .hemisphere = MVR_HEMISPHERE_UPPER}, "hemisphere"},
        {{.layout = (mvr_view_layout)(MVR_LAYOUT_RANDOM + 1)}, "layout"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; ++k) {
        mvr_view_set *vs = NULL;
        mvr_error err;
        memset(&err, 0, sizeof err);
        mvr_result r = mvr_view_set_frame_scene(s, &cases[k].fd, &vs, &err);
        CHECK_MSG(t, r == MVR_ERROR_INVALID_ARGUMENT && !vs && strstr(err.message, cases[k].names),
                  "case %zu (%s): result %d, '%s'", k, cases[k].names, (int)r, err.message);
        mvr_view_set_destroy(vs);
    }
    /* the edges of the ranges are taken */
    mvr_framing_desc ok[] = {{.layout = MVR_LAYOUT_SPHERE, .yfov = 3.1, .elevation_min = -PI_ / 2,
                              .elevation_max = PI_ / 2},
                             {.layout = MVR_LAYOUT_RING, .fit_box = true, .margin = 0.9},
                             {.layout = MVR_LAYOUT_RANDOM, .views = 1, .min_spacing = PI_},
                             {.layout = MVR_LAYOUT_GRID, .radius = 1e9, .up = MVR_UP_Z}};
    for (size_t k = 0; k < sizeof ok / sizeof *ok; ++k) {
        mvr_view_set *vs = frame(t, s, &ok[k]);
        CHECK_MSG(t, vs != NULL, "edge case %zu", k);
        mvr_view_set_destroy(vs);
    }
    CHECK(t, strcmp(mvr_view_layout_name(MVR_LAYOUT_RANDOM), "random") == 0);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(fov_is_the_asked_one), TEST(margin_fits_the_box), TEST(radius_is_the_distance),
              TEST(upper_hemisphere_stays_above), TEST(random_is_seeded_and_spaced), TEST(up_z_is_upright),
              TEST(bad_fields_are_named))
