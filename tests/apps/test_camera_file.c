/* apps: camera files for --cameras (apps/mvr/camera_file.c, json_read.c),
 * without GL. CSV and NeRF pinholes with off-centre principal points and
 * fx != fy come back from mvr_view_set_get_camera within 1e-9 (relative) at
 * the file's size, and scaled at another; camera-to-world matrices come back
 * within 1e-12; cameras.json's mvr_view is taken bit for bit while it agrees
 * with the frame's matrices, and the matrices win once they were edited;
 * hostile files (bad numbers, missing or mistyped fields, huge counts,
 * non-orthonormal rotations, sizes that disagree, ...) are refused with a
 * message naming the view, the field and the line; and thousands of
 * truncated and mutated files are refused or read without a crash (ASan in
 * CI) and never give a non-finite view. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera_file.h"
#include "json_read.h"
#include "mvr_test.h"

static bool load(const char *text, uint32_t w, uint32_t h, camera_file *f, char *why, size_t size)
{
    return camera_file_parse(text, strlen(text), w, h, f, why, size);
}

static double rel(double a, double b)
{
    return fabs(a - b) / fmax(fabs(b), 1e-300);
}

/* A view's camera at w x h against the pinhole it was read from. */
static void check_pinhole(mvr_test_state *t, const camera_file *f, uint32_t k, uint32_t w, uint32_t h,
                          const double want[4])
{
    mvr_view_set_desc d = {.view_count = f->count, .views = f->views};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_create(&d, &vs, NULL) == MVR_OK);
    if (!vs)
        return;
    mvr_view_camera cam;
    CHECK(t, mvr_view_set_get_camera(vs, k, w, h, &cam) == MVR_OK && cam.perspective);
    double got[4] = {cam.fx, cam.fy, cam.cx, cam.cy};
    for (int i = 0; i < 4; ++i)
        CHECK_MSG(t, rel(got[i], want[i]) < 1e-9, "view %u intrinsic %d: %.17g, want %.17g", k, i, got[i], want[i]);
    mvr_view_set_destroy(vs);
}

static void csv_pinholes_map_exactly(mvr_test_state *t)
{
    /* columns in another order than documented, a comment, blank cells
     * around values, CRLF ends */
    const char *csv = "# made by a test\r\n"
                      "fx, fy, cx, cy, x, y, z, qw, qx, qy, qz, width, height, znear\r\n"
                      "500, 420.25, 301.5, 190.75, 1, 2, 3, 1, 0, 0, 0, 640, 400, 0.1\r\n"
                      "\r\n"
                      "812.5,799.0,100.0,350.0,-4,0.5,9,0.9238795325112867,0,0.3826834323650898,0,640,400,0\r\n";
    camera_file f;
    char why[512] = "";
    CHECK_MSG(t, load(csv, 64, 64, &f, why, sizeof why), "%s", why);
    CHECK_EQ_INT(t, f.count, 2);
    CHECK(t, f.width == 640 && f.height == 400 && strcmp(f.format, "CSV") == 0);
    if (f.count == 2) {
        const double a[4] = {500, 420.25, 301.5, 190.75}, b[4] = {812.5, 799.0, 100.0, 350.0};
        check_pinhole(t, &f, 0, 640, 400, a);
        check_pinhole(t, &f, 1, 640, 400, b);
        /* at twice the size: the same field of view, intrinsics scaled */
        const double a2[4] = {1000, 840.5, 603, 381.5};
        check_pinhole(t, &f, 0, 1280, 800, a2);
        CHECK(t, f.views[0].position[0] == 1 && f.views[0].position[2] == 3 && f.views[0].projection.znear == 0.1);
        CHECK(t, fabs(f.views[1].orientation[1] - 0.3826834323650898) < 1e-15 &&
                     fabs(f.views[1].orientation[3] - 0.9238795325112867) < 1e-15);
    }
    camera_file_free(&f);
    /* without width and height: the pixels are the given size's */
    CHECK(t, load("x,y,z,qx,qy,qz,qw,fx,fy,cx,cy\n0,0,0,0,0,0,1,100,90,40,30\n", 80, 60, &f, why, sizeof why));
    CHECK(t, f.count == 1 && f.width == 0);
    if (f.count == 1) {
        const double want[4] = {100, 90, 40, 30};
        check_pinhole(t, &f, 0, 80, 60, want);
    }
    camera_file_free(&f);
}

static void nerf_transforms(mvr_test_state *t)
{
    /* instant-ngp's synthetic scenes: camera_angle_x only (size from the caller) */
    const char *synthetic = "{\"camera_angle_x\": 0.6911112070083618, \"frames\": [{\"file_path\": \"./r_0\", "
                            "\"rotation\": 0.0, \"transform_matrix\": [[-0.9999, 0.0042, -0.0133, -0.0538], "
                            "[-0.0140, -0.3049, 0.9523, 3.8389], [0.0, 0.9524, 0.3049, 1.2294], [0.0, 0.0, 0.0, 1.0]]}]}";
    camera_file f;
    char why[512] = "";
    CHECK_MSG(t, load(synthetic, 800, 800, &f, why, sizeof why), "%s", why);
    CHECK(t, f.count == 1 && f.width == 0 && strcmp(f.format, "NeRF transforms.json") == 0);
    if (f.count == 1) {
        double fl = 0.5 * 800 / tan(0.5 * 0.6911112070083618);
        const double want[4] = {fl, fl, 400, 400};
        check_pinhole(t, &f, 0, 800, 800, want);
    }
    camera_file_free(&f);
    /* nerfstudio: top-level intrinsics, one frame overriding cx, exact pose */
    const char *studio =
        "{\"camera_model\": \"OPENCV\", \"fl_x\": 1200.5, \"fl_y\": 1100.25, \"cx\": 500.5, \"cy\": 380.125, "
        "\"w\": 960, \"h\": 720, \"k1\": 0, \"k2\": 0, \"p1\": 0, \"p2\": 0, \"frames\": ["
        "{\"file_path\": \"a.png\", \"transform_matrix\": [[0, 0, 1, 5], [0, 1, 0, 1], [-1, 0, 0, -2], [0, 0, 0, 1]]},"
        "{\"file_path\": \"b.png\", \"cx\": 470, \"transform_matrix\": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 4], "
        "[0, 0, 0, 1]]}]}";
    CHECK_MSG(t, load(studio, 64, 64, &f, why, sizeof why), "%s", why);
    CHECK(t, f.count == 2 && f.width == 960 && f.height == 720);
    if (f.count == 2) {
        const double a[4] = {1200.5, 1100.25, 500.5, 380.125}, b[4] = {1200.5, 1100.25, 470, 380.125};
        check_pinhole(t, &f, 0, 960, 720, a);
        check_pinhole(t, &f, 1, 960, 720, b);
        mvr_view_set_desc d = {.view_count = 2, .views = f.views};
        mvr_view_set *vs = NULL;
        mvr_view_camera cam;
        CHECK(t, mvr_view_set_create(&d, &vs, NULL) == MVR_OK && mvr_view_set_get_camera(vs, 0, 960, 720, &cam) == 0);
        const double c2w[16] = {0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 5, 1, -2, 1}; /* column-major */
        for (int i = 0; vs && i < 16; ++i)
            CHECK_MSG(t, fabs(cam.camera_to_world[i] - c2w[i]) < 1e-12, "c2w[%d] %.17g", i, cam.camera_to_world[i]);
        mvr_view_set_destroy(vs);
    }
    camera_file_free(&f);
}

/* One frame of mvr's cameras.json for a view: what render_output.c writes. */
static void mvr_frame_text(char *buf, size_t size, const mvr_view_desc *v, uint32_t w, uint32_t h, bool edit)
{
    mvr_view_set_desc d = {.view_count = 1, .views = v};
    mvr_view_set *vs = NULL;
    mvr_view_camera cam;
    memset(&cam, 0, sizeof cam);
    if (mvr_view_set_create(&d, &vs, NULL) == MVR_OK)
        mvr_view_set_get_camera(vs, 0, w, h, &cam);
    mvr_view_set_destroy(vs);
    if (edit)
        cam.camera_to_world[12] += 0.5; /* moved along x by hand */
    size_t n = (size_t)snprintf(buf, size, "{\"frames\": [{\"w\": %u, \"h\": %u, \"fl_x\": %.17g, \"fl_y\": %.17g, "
                                           "\"cx\": %.17g, \"cy\": %.17g, \"perspective\": true, \"camera_to_world\": [",
                                w, h, cam.fx, cam.fy, cam.cx, cam.cy);
    for (int r = 0; r < 4; ++r)
        n += (size_t)snprintf(buf + n, size - n, "%s[%.17g, %.17g, %.17g, %.17g]", r ? ", " : "",
                              cam.camera_to_world[r], cam.camera_to_world[4 + r], cam.camera_to_world[8 + r],
                              cam.camera_to_world[12 + r]);
    snprintf(buf + n, size - n, "], \"projection\": [[%.17g, 0, %.17g, 0], [0, %.17g, %.17g, 0], [0, 0, %.17g, "
                                "%.17g], [0, 0, -1, 0]], \"mvr_view\": {\"position\": [%.17g, %.17g, %.17g], "
                                "\"orientation\": [%.17g, %.17g, %.17g, %.17g], \"projection\": {\"type\": "
                                "\"perspective\", \"yfov\": %.17g, \"aspect\": 0, \"znear\": %.17g, \"zfar\": 0}}}]}",
             cam.projection[0], cam.projection[8], cam.projection[5], cam.projection[9], cam.projection[10],
             cam.projection[14], v->position[0], v->position[1], v->position[2], v->orientation[0], v->orientation[1],
             v->orientation[2], v->orientation[3], v->projection.yfov, v->projection.znear);
}

static void mvr_view_taken_exactly(mvr_test_state *t)
{
    mvr_view_desc v;
    memset(&v, 0, sizeof v);
    double eye[3] = {1.25, 2.5, 7.75}, at[3] = {0.1, 0.2, 0.3}, up[3] = {0, 1, 0};
    mvr_view_look_at(&v, eye, at, up);
    v.projection.yfov = 0.7;
    v.projection.znear = 0.01;
    char text[4096];
    mvr_frame_text(text, sizeof text, &v, 320, 200, false);
    camera_file f;
    char why[512] = "";
    CHECK_MSG(t, load(text, 64, 64, &f, why, sizeof why), "%s", why);
    CHECK(t, f.count == 1 && f.exact == 1 && f.edited == 0 && strcmp(f.format, "mvr cameras.json") == 0);
    /* bit for bit: the same view renders the same pixels */
    CHECK(t, f.count == 1 && memcmp(&f.views[0], &v, sizeof v) == 0);
    camera_file_free(&f);
    /* an edited camera_to_world wins over mvr_view (and is counted) */
    mvr_frame_text(text, sizeof text, &v, 320, 200, true);
    CHECK_MSG(t, load(text, 64, 64, &f, why, sizeof why), "%s", why);
    CHECK(t, f.count == 1 && f.exact == 0 && f.edited == 1 && f.first_edited == 0);
    if (f.count == 1) {
        CHECK_MSG(t, fabs(f.views[0].position[0] - (eye[0] + 0.5)) < 1e-12, "x %.17g", f.views[0].position[0]);
        CHECK(t, f.views[0].projection.type == MVR_PROJECTION_FRUSTUM);
        CHECK_MSG(t, rel(f.views[0].projection.znear, 0.01) < 1e-9, "znear from the matrix %.17g",
                  f.views[0].projection.znear);
    }
    camera_file_free(&f);
}

typedef struct hostile {
    const char *what;
    const char *text;
    const char *expect[3]; /* substrings of the message */
} hostile;

#define T4 "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]"
#define NERF(frames) "{\"fl_x\": 100, \"w\": 64, \"h\": 48, \"frames\": [" frames "]}"
#define F(extra) "{\"transform_matrix\": " T4 extra "}"
#define CSVH "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy\n"
#define ROW "0,0,0,0,0,0,1,100,100,32,24\n"

static const hostile hostile_files[] = {
    {"NaN", NERF(F(", \"fl_y\": NaN")), {"line 1", "NaN"}},
    {"overflow", NERF(F("") "," F(", \"cx\": 1e999")), {"line 1", "out of range"}},
    {"no frames", "{\"fl_x\": 100}", {"frames", "missing"}},
    {"frames not an array", "{\"frames\": {}}", {"frames", "an object"}},
    {"no views", "{\"frames\": []}", {"frames", "empty"}},
    {"frame not an object", NERF(F("") ", 3"), {"view 1", "a number, not an object"}},
    {"neither format", "{\"frames\": [{\"pose\": 1}]}", {"view 0", "transform_matrix", "camera_to_world"}},
    {"matrix missing", NERF(F("") ",\n" F("") ",\n{\"fl_x\": 3}"), {"view 2 (line 3)", "transform_matrix", "missing"}},
    {"matrix rows", NERF(F("") ", {\"transform_matrix\": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]}"),
     {"view 1", "transform_matrix", "4 rows"}},
    {"matrix string", NERF("{\"transform_matrix\": [[1,0,0,0],[0,1,\"0\",0],[0,0,1,0],[0,0,0,1]]}"),
     {"view 0", "transform_matrix[1][2]", "a string"}},
    {"scaled rotation", NERF(F("") ", {\"transform_matrix\": [[2,0,0,0],[0,2,0,0],[0,0,2,0],[0,0,0,1]]}"),
     {"view 1", "transform_matrix", "not orthonormal"}},
    {"reflection", NERF("{\"transform_matrix\": [[-1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}"),
     {"view 0", "transform_matrix", "reflection"}},
    {"projective row", NERF("{\"transform_matrix\": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0.5,0,1]]}"),
     {"view 0", "transform_matrix", "last row"}},
    {"far position", NERF("{\"transform_matrix\": [[1,0,0,1e13],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}"),
     {"view 0", "transform_matrix", "from the origin"}},
    {"negative focal", NERF(F(", \"fl_x\": -100")), {"view 0", "fl_x", "not a focal length"}},
    {"focal string", NERF(F(", \"fl_y\": \"100\"")), {"view 0", "fl_y", "a string, not a number"}},
    {"focal null", NERF(F(", \"cx\": null")), {"view 0", "cx", "null"}},
    {"no focal", "{\"frames\": [" F("") "]}", {"view 0", "fl_x", "camera_angle_x"}},
    {"angle", "{\"camera_angle_x\": 3.5, \"frames\": [" F("") "]}", {"top level", "camera_angle_x", "field of view"}},
    {"wide principal point", NERF(F(", \"cx\": 2000000")), {"view 0", "fl_x", "cx"}},
    {"narrow", NERF(F(", \"fl_x\": 1e12")), {"view 0", "fl_x", "field of view under"}},
    {"fractional size", NERF(F(", \"w\": 64.5")), {"view 0", "w", "whole number"}},
    {"huge size", NERF(F(", \"w\": 100000, \"h\": 10")), {"view 0", "w", "1..16384"}},
    {"w without h", "{\"fl_x\": 100, \"frames\": [" F(", \"w\": 64") "]}", {"view 0", "w is given without h"}},
    {"sizes differ", NERF(F("") ", " F(", \"w\": 32, \"h\": 32")), {"view 1", "32x32", "64x48"}},
    {"distortion", NERF(F(", \"k1\": 0.01")), {"view 0", "k1", "distortion"}},
    {"fisheye", "{\"camera_model\": \"OPENCV_FISHEYE\", \"fl_x\": 9, \"frames\": [" F("") "]}",
     {"top level", "camera_model", "'OPENCV_FISHEYE'"}},
    {"duplicate key", NERF(F(", \"fl_x\": 1, \"fl_x\": 2")), {"line 1", "fl_x", "twice"}},
    {"truncated", "{\"frames\": [{\"transform_matrix\": [[1,0", {"line 1", "end of the file"}},
    {"trailing", NERF(F("")) " x", {"line 1", "after the end"}},
    {"trailing comma", NERF(F("") ","), {"line 1", "expected a value"}},
    {"deep", "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[",
     {"line 1", "nested deeper"}},
    {"array root", "[1, 2]", {"object", "an array"}},
    {"mvr missing focal", "{\"frames\": [{\"w\": 8, \"h\": 8, \"camera_to_world\": " T4 ", \"fl_x\": 8}]}",
     {"view 0", "fl_y", "missing"}},
    {"mvr missing size", "{\"frames\": [{\"camera_to_world\": " T4 "}]}", {"view 0", "w", "missing"}},
    {"mvr_view orientation",
     "{\"frames\": [{\"w\": 8, \"h\": 8, \"camera_to_world\": " T4 ", \"fl_x\": 8, \"fl_y\": 8, \"cx\": 4, "
     "\"cy\": 4, \"mvr_view\": {\"position\": [0,0,0], \"orientation\": [0,0,0,3], \"projection\": {\"type\": "
     "\"perspective\", \"yfov\": 1, \"aspect\": 0}}}]}",
     {"view 0", "mvr_view.orientation", "length 3"}},
    {"mvr_view type",
     "{\"frames\": [{\"w\": 8, \"h\": 8, \"camera_to_world\": " T4 ", \"mvr_view\": {\"position\": [0,0,0], "
     "\"orientation\": [0,0,0,1], \"projection\": {\"type\": \"fisheye\"}}}]}",
     {"view 0", "mvr_view.projection.type"}},
    /* CSV */
    {"csv unknown column", "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,focal\n", {"line 1", "'focal'"}},
    {"csv missing column", "x,y,z,qx,qy,qz,fx,fy,cx,cy\n" ROW, {"line 1", "'qw'"}},
    {"csv duplicate column", "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,x\n", {"line 1", "'x'", "twice"}},
    {"csv cells", CSVH ROW "0,0,0,0,0,0,1,100,100,32\n", {"view 1 (line 3)", "10 cells", "11 columns"}},
    {"csv nan", CSVH ROW ROW "0,0,0,0,0,0,1,nan,100,32,24\n", {"view 2 (line 4)", "fx", "'nan'"}},
    {"csv inf", CSVH "0,0,inf,0,0,0,1,100,100,32,24\n", {"view 0", "z", "'inf'"}},
    {"csv hex", CSVH "0,0,0,0,0,0,1,0x64,100,32,24\n", {"view 0", "fx", "'0x64'"}},
    {"csv empty cell", CSVH "0,,0,0,0,0,1,100,100,32,24\n", {"view 0", "y", "not a finite number"}},
    {"csv overflow", CSVH "0,0,0,0,0,0,1,1e999,100,32,24\n", {"view 0", "fx", "1e999"}},
    {"csv quaternion", CSVH ROW "0,0,0,0,0,0,2,100,100,32,24\n", {"view 1", "qx, qy, qz, qw", "length 2"}},
    {"csv zero quaternion", CSVH "0,0,0,0,0,0,0,100,100,32,24\n", {"view 0", "quaternion", "length 0"}},
    {"csv focal", CSVH "0,0,0,0,0,0,1,100,0,32,24\n", {"view 0", "fy", "focal length"}},
    {"csv width without height", "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,width\n", {"line 1", "width without height"}},
    {"csv width", "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,width,height\n0,0,0,0,0,0,1,100,100,32,24,0,48\n",
     {"view 0", "width", "whole number"}},
    {"csv sizes differ",
     "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,width,height\n0,0,0,0,0,0,1,100,100,32,24,64,48\n"
     "0,0,0,0,0,0,1,100,100,32,24,64,50\n",
     {"view 1 (line 3)", "64x50", "64x48"}},
    {"csv znear", "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,znear\n0,0,0,0,0,0,1,100,100,32,24,-1\n",
     {"view 0", "znear", "near plane"}},
    {"csv far", CSVH "0,-2e12,0,0,0,0,1,100,100,32,24\n", {"view 0", "x, y, z", "from the origin"}},
    {"csv header only", "# c\n" CSVH "\n# nothing\n", {"no views", "line 2"}},
    {"empty", "", {"no views", "empty"}},
    {"binary", "x,y\0,z", {"NUL"}},
};

static void hostile_files_refused(mvr_test_state *t)
{
    for (size_t i = 0; i < sizeof hostile_files / sizeof hostile_files[0]; ++i) {
        const hostile *h = &hostile_files[i];
        camera_file f;
        char why[512] = "";
        size_t len = strcmp(h->what, "binary") == 0 ? 7 : strlen(h->text);
        bool ok = camera_file_parse(h->text, len, 64, 48, &f, why, sizeof why);
        CHECK_MSG(t, !ok, "%s: accepted", h->what);
        CHECK_MSG(t, f.views == NULL && f.count == 0, "%s: views left behind", h->what);
        for (int k = 0; k < 3 && h->expect[k]; ++k)
            CHECK_MSG(t, strstr(why, h->expect[k]) != NULL, "%s: '%s' not in \"%s\"", h->what, h->expect[k], why);
        camera_file_free(&f);
    }
}

static void too_many_views(mvr_test_state *t)
{
    size_t cap = 64 + (CAMERA_FILE_MAX_VIEWS + 1) * 64;
    char *text = malloc(cap);
    if (!text)
        return;
    /* CSV: the 1025th row is refused */
    size_t n = (size_t)snprintf(text, cap, CSVH);
    for (uint32_t k = 0; k <= CAMERA_FILE_MAX_VIEWS; ++k)
        n += (size_t)snprintf(text + n, cap - n, ROW);
    camera_file f;
    char why[512] = "";
    CHECK(t, !camera_file_parse(text, n, 64, 48, &f, why, sizeof why) && strstr(why, "view 1024") &&
                 strstr(why, "more than 1024"));
    /* exactly the limit reads */
    n -= strlen(ROW);
    CHECK_MSG(t, camera_file_parse(text, n, 64, 48, &f, why, sizeof why) && f.count == CAMERA_FILE_MAX_VIEWS, "%s",
              why);
    camera_file_free(&f);
    /* JSON: counted before anything is made */
    n = (size_t)snprintf(text, cap, "{\"fl_x\": 9, \"frames\": [");
    for (uint32_t k = 0; k <= CAMERA_FILE_MAX_VIEWS; ++k)
        n += (size_t)snprintf(text + n, cap - n, "%s{}", k ? "," : "");
    n += (size_t)snprintf(text + n, cap - n, "]}");
    CHECK(t, !camera_file_parse(text, n, 64, 48, &f, why, sizeof why) && strstr(why, "1025 views"));
    free(text);
    /* larger than the reader takes */
    CHECK(t, !camera_file_parse("{}", CAMERA_FILE_MAX_BYTES + 1, 64, 48, &f, why, sizeof why) && strstr(why, "bytes"));
}

static void json_reader_strings(mvr_test_state *t)
{
    const char *text = "{\"a\\u00e9\\ud83d\\ude00\\n\": [true, false, null, -0.5e-3, \"\\\"/\"]}";
    json_value v;
    char why[256] = "";
    CHECK_MSG(t, json_read(text, strlen(text), &v, why, sizeof why), "%s", why);
    const json_value *a = json_member(&v, "a\xc3\xa9\xf0\x9f\x98\x80\n");
    CHECK(t, a && a->type == JSON_ARRAY && a->count == 5);
    if (a && a->count == 5) {
        CHECK(t, a->items[0].type == JSON_TRUE && a->items[1].type == JSON_FALSE && a->items[2].type == JSON_NULL);
        CHECK(t, a->items[3].type == JSON_NUMBER && a->items[3].number == -0.5e-3);
        CHECK(t, a->items[4].type == JSON_STRING && strcmp(a->items[4].string, "\"/") == 0);
    }
    json_read_free(&v);
    static const char *const bad[] = {"\"\\ud83d\"", "\"\\u0000\"", "\"a\nb\"", "01", "1.", "-", "+1", "\"\\x\"",
                                      "tru", "{\"a\" 1}", "{1: 2}", "[1 2]", "\"abc"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        CHECK_MSG(t, !json_read(bad[i], strlen(bad[i]), &v, why, sizeof why), "accepted %s", bad[i]);
        CHECK(t, strncmp(why, "line ", 5) == 0);
    }
}

/* xorshift: the same mutations on every run */
static uint32_t next_random(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static void mutated_files_never_crash(mvr_test_state *t)
{
    char text[4096];
    mvr_view_desc v;
    memset(&v, 0, sizeof v);
    double eye[3] = {1, 2, 3}, at[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    mvr_view_look_at(&v, eye, at, up);
    mvr_frame_text(text, sizeof text, &v, 64, 48, false);
    const char *seeds[3] = {text,
                            "{\"camera_angle_x\": 0.8, \"w\": 64, \"h\": 48, \"frames\": [{\"transform_matrix\": "
                            "[[1,0,0,1],[0,1,0,2],[0,0,1,3],[0,0,0,1]], \"cx\": 30}]}",
                            "x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,width,height,znear\n1,2,3,0,0,0,1,80,70,30,20,64,48,0.5\n"
                            "1,2,3,0,0.7071067811865476,0,0.7071067811865476,80,70,30,20,64,48,0\n"};
    uint32_t state = 12345, accepted = 0, refused = 0;
    static const char alphabet[] = "0123456789.-+eE,:[]{}\"\n naxyzNI";
    for (int s = 0; s < 3; ++s) {
        size_t len = strlen(seeds[s]);
        char buf[4096];
        for (int round = 0; round < 2000; ++round) {
            memcpy(buf, seeds[s], len);
            size_t n = len;
            if (round % 4 == 0) {
                n = next_random(&state) % len; /* truncated */
            } else {
                for (int k = 1 + (int)(next_random(&state) % 4); k > 0; --k)
                    buf[next_random(&state) % len] = alphabet[next_random(&state) % (sizeof alphabet - 1)];
            }
            camera_file f;
            char why[512];
            if (camera_file_parse(buf, n, 64, 48, &f, why, sizeof why)) {
                accepted++;
                mvr_view_set_desc d = {.view_count = f.count, .views = f.views};
                mvr_view_set *vs = NULL;
                bool finite = f.count > 0 && mvr_view_set_create(&d, &vs, NULL) == MVR_OK;
                for (uint32_t k = 0; finite && k < f.count; ++k) {
                    mvr_view_camera cam;
                    finite = mvr_view_set_get_camera(vs, k, 64, 48, &cam) == MVR_OK;
                    for (int i = 0; finite && i < 16; ++i)
                        finite = isfinite(cam.projection[i]) && isfinite(cam.camera_to_world[i]);
                }
                CHECK_MSG(t, finite, "seed %d round %d: a view that is not finite or not valid", s, round);
                mvr_view_set_destroy(vs);
                camera_file_free(&f);
            } else {
                refused++;
                CHECK(t, why[0] != '\0' && f.views == NULL);
            }
        }
    }
    printf("  mutated files: %u read, %u refused\n", accepted, refused);
    CHECK(t, accepted > 0 && refused > 0);
}

MVR_TEST_MAIN(TEST(csv_pinholes_map_exactly), TEST(nerf_transforms), TEST(mvr_view_taken_exactly),
              TEST(hostile_files_refused), TEST(too_many_views), TEST(json_reader_strings),
              TEST(mutated_files_never_crash))
