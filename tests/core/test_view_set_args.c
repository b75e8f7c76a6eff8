/* core: the view-set arguments a caller can get wrong. Framing refuses a
 * layer aspect that is NaN, infinite, negative or absurd and an eye
 * separation (ipd) that is NaN, infinite, negative or past 1e9 scene units
 * (both used to be taken: NaN aspect gave NaN matrices, ipd 1e300 eyes
 * whose float matrices overflow); mvr_view_set_create and the framing
 * functions share one view cap, MVR_VIEW_SET_MAX_VIEWS (create took 4096
 * while framing stopped at 1024). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mvr_test.h"
#include "view_set.h"

/* a unit box at the origin, and a camera node 5 units in front of it */
static mvr_scene *box_scene(mvr_node_id *camera_node)
{
    mvr_scene *s = NULL;
    if (mvr_scene_create(NULL, &s, NULL) != MVR_OK)
        return NULL;
    const float pos[9] = {-1, -1, -1, 1, -1, 1, 1, 1, 1};
    mvr_primitive_desc p = {0};
    p.vertex_count = 3;
    p.positions = pos;
    mvr_mesh_desc m = {.primitives = &p, .primitive_count = 1, .name = "box"};
    mvr_mesh_id mesh;
    mvr_node_desc n = {0};
    mvr_node_id node;
    mvr_projection cp = {0};
    cp.yfov = 0.7;
    cp.znear = 0.01;
    mvr_camera_id cam;
    mvr_node_desc cn = {0};
    cn.translation[2] = 5.0;
    bool ok = mvr_scene_add_mesh(s, &m, &mesh) == MVR_OK && (n.mesh = mesh, mvr_scene_add_node(s, &n, &node)) == MVR_OK &&
              mvr_scene_add_camera(s, &cp, &cam) == MVR_OK &&
              (cn.camera = cam, mvr_scene_add_node(s, &cn, camera_node)) == MVR_OK;
    if (!ok) {
        mvr_scene_destroy(s);
        return NULL;
    }
    return s;
}

/* Whether every number a view's GPU matrices hold is finite. */
static bool views_finite(const mvr_view_set *vs)
{
    mvr_viewport vp = {0, 0, 64, 64};
    for (uint32_t i = 0; i < vs->count; ++i) {
        float vpm[16], eye[4];
        mvr_view_gpu_matrices(&vs->views[i], vs->origin, vp, true, vpm, eye);
        for (int k = 0; k < 16; ++k)
            if (!isfinite(vpm[k]))
                return false;
        for (int k = 0; k < 4; ++k)
            if (!isfinite(eye[k]))
                return false;
    }
    return true;
}

static void bad_aspect_is_refused(mvr_test_state *t)
{
    mvr_node_id cam;
    mvr_scene *s = box_scene(&cam);
    CHECK(t, s != NULL);
    if (!s)
        return;
    const double bad[] = {NAN, INFINITY, -INFINITY, -1.0, 1e-300, 1e300};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        mvr_framing_desc fd = {.layout = MVR_LAYOUT_STEREO, .aspect = bad[i]};
        mvr_view_set *vs = NULL;
        mvr_error err = {0};
        mvr_result r = mvr_view_set_frame_scene(s, &fd, &vs, &err);
        CHECK_MSG(t, r == MVR_ERROR_INVALID_ARGUMENT && !vs && strstr(err.message, "aspect"), "aspect %g: %s %s",
                  bad[i], mvr_result_name(r), err.message);
        mvr_view_set_destroy(vs);
    }
    /* 0 is the default (1); the extremes of a 16384 x 1 layer are fine */
    const double good[] = {0.0, 16.0 / 9.0, 16384.0, 1.0 / 16384.0};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; ++i) {
        mvr_framing_desc fd = {.layout = MVR_LAYOUT_RING, .aspect = good[i]};
        mvr_view_set *vs = NULL;
        mvr_error err = {0};
        CHECK_MSG(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_OK, "aspect %g: %s", good[i], err.message);
        if (vs) {
            CHECK_MSG(t, views_finite(vs), "aspect %g: a matrix is not finite", good[i]);
            CHECK(t, vs->views[0].projection.aspect == (good[i] > 0 ? good[i] : 1.0));
        }
        mvr_view_set_destroy(vs);
    }
    mvr_scene_destroy(s);
}

static void bad_ipd_is_refused(mvr_test_state *t)
{
    mvr_node_id cam;
    mvr_scene *s = box_scene(&cam);
    CHECK(t, s != NULL);
    if (!s)
        return;
    const double bad[] = {NAN, INFINITY, -1.0, -1e-9, 1e300, 1.0000001e9};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        mvr_framing_desc fd = {.layout = MVR_LAYOUT_STEREO, .views = 8, .ipd = bad[i]};
        mvr_view_set *vs = NULL;
        mvr_error err = {0};
        mvr_result r = mvr_view_set_frame_scene(s, &fd, &vs, &err);
        CHECK_MSG(t, r == MVR_ERROR_INVALID_ARGUMENT && !vs && strstr(err.message, "ipd"), "frame ipd %g: %s %s",
                  bad[i], mvr_result_name(r), err.message);
        mvr_view_set_destroy(vs);
        vs = NULL;
        r = mvr_view_set_from_camera(s, cam, 8, bad[i], &vs, &err);
        CHECK_MSG(t, r == MVR_ERROR_INVALID_ARGUMENT && !vs && strstr(err.message, "ipd"), "camera ipd %g: %s %s",
                  bad[i], mvr_result_name(r), err.message);
        mvr_view_set_destroy(vs);
    }
    /* the limit itself and ordinary values are taken, with finite matrices */
    const double good[] = {0.0, 0.064, 1e9};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; ++i) {
        mvr_framing_desc fd = {.layout = MVR_LAYOUT_STEREO, .views = 8, .ipd = good[i]};
        mvr_view_set *vs = NULL;
        mvr_error err = {0};
        CHECK_MSG(t, mvr_view_set_frame_scene(s, &fd, &vs, &err) == MVR_OK, "frame ipd %g: %s", good[i], err.message);
        if (vs)
            CHECK_MSG(t, views_finite(vs), "frame ipd %g: a matrix is not finite", good[i]);
        mvr_view_set_destroy(vs);
        vs = NULL;
        CHECK_MSG(t, mvr_view_set_from_camera(s, cam, 8, good[i], &vs, &err) == MVR_OK, "camera ipd %g: %s", good[i],
                  err.message);
        if (vs)
            CHECK_MSG(t, views_finite(vs), "camera ipd %g: a matrix is not finite", good[i]);
        mvr_view_set_destroy(vs);
    }
    mvr_scene_destroy(s);
}

/* One cap: create, frame_scene and from_camera all take exactly
 * MVR_VIEW_SET_MAX_VIEWS views and refuse one more, naming the same cap. */
static void one_view_cap(mvr_test_state *t)
{
    CHECK_EQ_INT(t, MVR_VIEW_SET_MAX_VIEWS, 1024);
    mvr_node_id cam;
    mvr_scene *s = box_scene(&cam);
    mvr_view_desc *views = calloc(MVR_VIEW_SET_MAX_VIEWS + 1, sizeof *views);
    CHECK(t, s != NULL && views != NULL);
    if (!s || !views) {
        free(views);
        mvr_scene_destroy(s);
        return;
    }
    char cap[32];
    snprintf(cap, sizeof cap, "at most %u", MVR_VIEW_SET_MAX_VIEWS);
    for (uint32_t extra = 0; extra < 2; ++extra) {
        uint32_t n = MVR_VIEW_SET_MAX_VIEWS + extra;
        const char *what[3] = {"create", "frame_scene", "from_camera"};
        mvr_view_set *vs[3] = {NULL, NULL, NULL};
        mvr_error err[3];
        mvr_result r[3];
        mvr_view_set_desc d = {.view_count = n, .views = views};
        r[0] = mvr_view_set_create(&d, &vs[0], &err[0]);
        mvr_framing_desc fd = {.layout = MVR_LAYOUT_SPHERE, .views = n};
        r[1] = mvr_view_set_frame_scene(s, &fd, &vs[1], &err[1]);
        r[2] = mvr_view_set_from_camera(s, cam, n, 0.0, &vs[2], &err[2]);
        for (int k = 0; k < 3; ++k) {
            if (extra == 0)
                CHECK_MSG(t, r[k] == MVR_OK && mvr_view_set_count(vs[k]) == n, "%s of %u views: %s", what[k], n,
                          err[k].message);
            else
                CHECK_MSG(t, r[k] == MVR_ERROR_INVALID_ARGUMENT && !vs[k] && strstr(err[k].message, cap),
                          "%s of %u views: %s %s", what[k], n, mvr_result_name(r[k]), err[k].message);
            mvr_view_set_destroy(vs[k]);
        }
    }
    free(views);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(bad_aspect_is_refused), TEST(bad_ipd_is_refused), TEST(one_view_cap))
