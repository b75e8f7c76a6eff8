/*
 * glTF 2.0 animation samplers, backend-free and in double precision: keyframe
 * times in seconds, values with any number of components, STEP, LINEAR (slerp
 * along the shorter arc for rotation quaternions) and CUBICSPLINE (the Hermite
 * formula of the glTF 2.0 specification, Appendix C). Times outside the keys
 * clamp to the first / last value, as glTF asks. Internal: not public API.
 */
#ifndef MVR_ANIMATION_H
#define MVR_ANIMATION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mvr/mvr.h"

/* mvr_interpolation (LINEAR, STEP, CUBICSPLINE) is the public enum of mvr.h */

/* One sampler. The arrays are borrowed, not owned.
 * values holds count * components doubles, or for CUBICSPLINE
 * count * 3 * components: per key its in-tangent, value and out-tangent,
 * in that order, as glTF lays them out. Tangents are per second (the
 * Hermite formula multiplies them by the interval's length). */
typedef struct mvr_anim_sampler {
    const double *times;     /* count keys, finite, strictly increasing */
    const double *values;
    size_t count;            /* keys, >= 1 */
    size_t value_count;      /* doubles readable at values (checked against count) */
    uint32_t components;     /* per value, >= 1; 4 for a quaternion */
    mvr_interpolation interpolation;
    bool quaternion;         /* values are rotations (x, y, z, w): slerp, normalised */
} mvr_anim_sampler;

/* The doubles a sampler of count keys needs (count * components, three times
 * that for CUBICSPLINE); false on overflow or an unknown interpolation. */
bool mvr_anim_sampler_value_count(size_t count, uint32_t components, mvr_interpolation interpolation,
                                  size_t *out);

/* Whether the sampler can be evaluated: arrays present, count >= 1, times
 * finite and strictly increasing, values finite and enough of them (no
 * overflow), a known interpolation, 4 components for a quaternion. Writes why
 * not into why[why_size] (may be NULL). */
bool mvr_anim_sampler_valid(const mvr_anim_sampler *sampler, char *why, size_t why_size);

/* The index k of the key interval holding t: times[k] <= t < times[k + 1],
 * 0 before the first key and count - 1 at or after the last. O(log count). */
size_t mvr_anim_find_key(const double *times, size_t count, double t);

/* Evaluates a valid sampler at time t (seconds) into out[components]. Before
 * the first key: the first value; at or after the last: the last value; a
 * NaN t gives the first value. STEP: the value of the key at or before t.
 * LINEAR: lerp, or for quaternions slerp along the shorter arc (normalised
 * lerp when nearly parallel), normalised. CUBICSPLINE: glTF's Hermite
 * spline, quaternions normalised after. */
void mvr_anim_sample(const mvr_anim_sampler *sampler, double t, double *out);

/* Maps a playback time to a clip [start, end]: clamped, or with loop
 * wrapped into [start, end) (negative times wrap backwards, t = end maps to
 * start, one period on). A zero-length, reversed or non-finite clip, a NaN t,
 * or an infinite t when looping, gives start (0 if start is not finite). */
double mvr_anim_time(double t, double start, double end, bool loop);

#endif
