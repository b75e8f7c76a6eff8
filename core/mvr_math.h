/*
 * Math for the frame model: double precision on the CPU (scene transforms,
 * view poses), narrowed to float only after subtracting the view set's origin.
 * Matrices are column-major (m[col * 4 + row]), as GL reads them.
 */
#ifndef MVR_MATH_H
#define MVR_MATH_H

#include <stdbool.h>

typedef struct mvr_dvec3 {
    double x, y, z;
} mvr_dvec3;

typedef struct mvr_dquat {
    double x, y, z, w;
} mvr_dquat;

typedef struct mvr_dmat4 {
    double m[16];
} mvr_dmat4;

typedef struct mvr_mat4f {
    float m[16];
} mvr_mat4f;

mvr_dvec3 mvr_dvec3_make(double x, double y, double z);
mvr_dvec3 mvr_dvec3_add(mvr_dvec3 a, mvr_dvec3 b);
mvr_dvec3 mvr_dvec3_sub(mvr_dvec3 a, mvr_dvec3 b);
mvr_dvec3 mvr_dvec3_scale(mvr_dvec3 a, double s);
double mvr_dvec3_dot(mvr_dvec3 a, mvr_dvec3 b);
mvr_dvec3 mvr_dvec3_cross(mvr_dvec3 a, mvr_dvec3 b);
double mvr_dvec3_length(mvr_dvec3 a);
/* Unit vector, or fallback for a zero / non-finite input. */
mvr_dvec3 mvr_dvec3_normalize(mvr_dvec3 a, mvr_dvec3 fallback);

/* Normalized; identity for a zero or non-finite quaternion. */
mvr_dquat mvr_dquat_normalize(mvr_dquat q);
mvr_dquat mvr_dquat_from_axis_angle(mvr_dvec3 axis, double radians);
mvr_dquat mvr_dquat_mul(mvr_dquat a, mvr_dquat b);
mvr_dvec3 mvr_dquat_rotate(mvr_dquat q, mvr_dvec3 v);
/* Rotation whose -Z looks along forward with +Y as close to up as possible. */
mvr_dquat mvr_dquat_look_rotation(mvr_dvec3 forward, mvr_dvec3 up);

mvr_dmat4 mvr_dmat4_identity(void);
mvr_dmat4 mvr_dmat4_mul(const mvr_dmat4 *a, const mvr_dmat4 *b);
/* T * R * S, the glTF node transform. */
mvr_dmat4 mvr_dmat4_trs(mvr_dvec3 t, mvr_dquat r, mvr_dvec3 s);
mvr_dvec3 mvr_dmat4_transform_point(const mvr_dmat4 *m, mvr_dvec3 p);
mvr_dvec3 mvr_dmat4_transform_dir(const mvr_dmat4 *m, mvr_dvec3 d);
/* General inverse; false (and identity) when singular. */
bool mvr_dmat4_invert(const mvr_dmat4 *m, mvr_dmat4 *out);
/* Determinant of the upper 3x3 (sign tells mirrored transforms). */
double mvr_dmat4_det3(const mvr_dmat4 *m);
/* Inverse-transpose of the upper 3x3, in a mat4 (for normals). A singular
 * 3x3 (zero scale) gives the cofactor matrix, which keeps normals finite. */
mvr_dmat4 mvr_dmat4_normal_matrix(const mvr_dmat4 *m);
/* m with its translation made relative to origin, narrowed to float. */
mvr_mat4f mvr_dmat4_relative_to(const mvr_dmat4 *m, mvr_dvec3 origin);
mvr_mat4f mvr_dmat4_to_float(const mvr_dmat4 *m);

/* View matrix (world relative to origin -> eye) from a pose: position
 * relative to the origin, orientation. */
mvr_dmat4 mvr_dmat4_view(mvr_dvec3 position_rel, mvr_dquat orientation);

/*
 * Projections. Depth conventions:
 * - reversed: clip z in [0, 1] with near -> 1 and far -> 0 (GL_EXT_clip_control
 *   ZERO_TO_ONE, depth test GREATER, clear 0). far = 0 means an infinite far
 *   plane, built directly (not as a limit of a finite one, which overflows or
 *   divides 0 by 0 in naive helpers).
 * - standard: GL's clip z in [-w, w], near -> -1, far -> +1 (LESS, clear 1);
 *   needs a finite far.
 * Frustum angles are OpenXR's XrFovf: left and down negative, radians.
 */
mvr_dmat4 mvr_dmat4_frustum(double angle_left, double angle_right, double angle_down,
                            double angle_up, double znear, double zfar, bool reversed);
mvr_dmat4 mvr_dmat4_perspective(double yfov, double aspect, double znear, double zfar,
                                bool reversed);
mvr_dmat4 mvr_dmat4_orthographic(double xmag, double ymag, double znear, double zfar,
                                 bool reversed);
/* Converts a standard-GL projection (z in [-w, w]) to the reversed
 * zero-to-one convention: z' = (w - z) / 2. */
mvr_dmat4 mvr_dmat4_gl_to_reversed(const mvr_dmat4 *proj);

#endif
