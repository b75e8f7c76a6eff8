/* Camera files for mvr render --cameras and mvr bench --cameras: a list of
 * views (pose and pinhole intrinsics) read into mvr_view_desc, whose format
 * is told from the content, never the file's name:
 *   - mvr's own cameras.json (what mvr render writes next to its images):
 *     each frame's mvr_view, when it still agrees with the frame's matrices
 *     and intrinsics, gives the view exactly as it was rendered; otherwise
 *     (an edited or hand-made file) camera_to_world and fl_x .. cy do;
 *   - NeRF's transforms.json (instant-ngp, nerfstudio): transform_matrix
 *     (camera-to-world, OpenGL camera), camera_angle_x[/y] or fl_x, fl_y, cx,
 *     cy, w, h at the top or per frame;
 *   - CSV with a header, one view per row (columns in any order): x, y, z
 *     (position), qx, qy, qz, qw (rotation, OpenGL camera looking along -Z,
 *     glTF world), fx, fy, cx, cy (pixels, OpenCV / COLMAP: from the image's
 *     top-left, pixel k covering [k, k + 1)); optional width, height, znear.
 * Pinhole intrinsics become an asymmetric frustum (MVR_PROJECTION_FRUSTUM,
 * infinite far): mvr_view_set_get_camera of the view gives back fx, fy, cx,
 * cy at the file's size, and the same field of view at any other size.
 * Everything in the file is checked: a refusal names the view (0-based, as
 * the images view_VVVV are numbered), the field and the line. */
#ifndef MVR_APP_CAMERA_FILE_H
#define MVR_APP_CAMERA_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mvr/mvr.h"

#define CAMERA_FILE_MAX_BYTES (16u << 20)
#define CAMERA_FILE_MAX_VIEWS 1024u
#define CAMERA_FILE_MAX_SIDE 16384u
/* a rotation further than this from orthonormal (max |R^T R - I|, or a
 * quaternion's length from 1) is refused; nearer ones are normalised */
#define CAMERA_FILE_ROTATION_TOLERANCE 1e-3

typedef struct camera_file {
    mvr_view_desc *views;
    uint32_t count;
    uint32_t width, height;  /* the image size the file names; 0 x 0: none */
    const char *format;      /* "mvr cameras.json", "NeRF transforms.json" or "CSV" */
    uint32_t exact;          /* views taken from cameras.json's mvr_view as written */
    uint32_t edited;         /* cameras.json views whose mvr_view disagreed with their matrices */
    uint32_t first_edited;   /* the first of those */
} camera_file;

/* Reads path. width x height: the image size that pixel intrinsics refer
 * to when the file names none (a NeRF file with camera_angle_x only, a CSV
 * without width and height). false with why (no path in it) when the file
 * cannot be read or is refused; *out is then empty. */
bool camera_file_load(const char *path, uint32_t width, uint32_t height, camera_file *out, char *why,
                      size_t why_size);

/* The same from text in memory (size bytes). */
bool camera_file_parse(const char *text, size_t size, uint32_t width, uint32_t height, camera_file *out, char *why,
                       size_t why_size);

void camera_file_free(camera_file *f);

#endif
