/* Inside the camera file reader (camera_file.h): what its formats share.
 * camera_file.c reads the JSON formats, camera_csv.c CSV, camera_pose.c
 * turns poses and pinholes into view descriptions. Each refusal writes its
 * message into a camf_report and returns false. */
#ifndef MVR_APP_CAMERA_FILE_INTERNAL_H
#define MVR_APP_CAMERA_FILE_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "camera_file.h"

/* |angle| the library takes for a frustum edge (core/view_set.c) */
#define CAMF_MAX_EDGE_ANGLE 1.5707
/* positions beyond this from the origin are refused: the GPU sees them
 * relative to the views' centroid, in float */
#define CAMF_MAX_COORDINATE 1e12
#define CAMF_MAX_ZNEAR 1e9
/* a field of view narrower than this (radians) is refused: its projection
 * would not survive the narrowing to float */
#define CAMF_MIN_FIELD_OF_VIEW 1e-7

typedef struct camf_report {
    char *why;
    size_t size;
} camf_report;

/* Writes the message; returns false. */
bool camf_refuse(camf_report *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* A cell or string for messages: printable ASCII only, at most 32 bytes. */
void camf_show_cell(char *buf, size_t size, const char *cell, size_t len);

/* where: "view 3 (line 17)"; field: the name the file gave the value. */
bool camf_check_position(camf_report *rp, const char *where, const char *field, const double p[3]);

/* A camera-to-world matrix (rows m[r][c], OpenGL camera) into v's position
 * and orientation: the last row 0 0 0 1, the rotation within
 * CAMERA_FILE_ROTATION_TOLERANCE of orthonormal (then normalised), not a
 * reflection. */
bool camf_pose_from_matrix(camf_report *rp, const char *where, const char *field, double m[4][4],
                           mvr_view_desc *v);

/* A quaternion (x, y, z, w) within the tolerance of unit length, normalised into out. */
bool camf_unit_quaternion(camf_report *rp, const char *where, const char *field, const double in[4],
                          double out[4]);

/* Pinhole intrinsics (pixels, OpenCV camera, image w x h) as the frustum
 * whose mvr_view_set_get_camera at w x h gives them back; names: the
 * file's names of fx, fy, cx, cy for messages. */
bool camf_frustum_from_pinhole(camf_report *rp, const char *where, const char *names[4], double fx, double fy,
                               double cx, double cy, uint32_t w, uint32_t h, double znear, mvr_projection *p);

bool camf_check_znear(camf_report *rp, const char *where, const char *field, double znear);

/* One image size for every view (0 x 0: the view names none); view 0 sets it. */
bool camf_same_size(camf_report *rp, camera_file *f, const char *where, uint32_t index, uint32_t w, uint32_t h);

/* CSV text into f (camera_csv.c). */
bool camf_parse_csv(camf_report *rp, const char *text, size_t size, uint32_t width, uint32_t height,
                    camera_file *f);

#endif
