/* glTF 2.0 animation samplers in double precision (see animation.h). */
#include "animation.h"

#include <math.h>
#include <string.h>

#include "core_util.h"

/* Below this angle (radians, between the quaternions as 4-vectors)
 * normalised lerp is used: it differs from slerp by about angle^3, far below
 * double precision, and slerp's sin(theta) would divide by almost zero. */
#define SLERP_MIN_ANGLE 1e-6

bool mvr_anim_sampler_value_count(size_t count, uint32_t components, mvr_interpolation interpolation,
                                  size_t *out)
{
    size_t per_key = components;
    switch (interpolation) {
    case MVR_INTERPOLATION_LINEAR:
    case MVR_INTERPOLATION_STEP: break;
    case MVR_INTERPOLATION_CUBICSPLINE:
        if (!mvr_size_mul(per_key, 3, &per_key))
            return false;
        break;
    default: return false;
    }
    return mvr_size_mul(count, per_key, out) != 0;
}

bool mvr_anim_sampler_valid(const mvr_anim_sampler *s, char *why, size_t why_size)
{
    if (!s) {
        mvr_str_copy(why, why_size, "sampler is NULL");
        return false;
    }
    if (s->interpolation != MVR_INTERPOLATION_LINEAR && s->interpolation != MVR_INTERPOLATION_STEP &&
        s->interpolation != MVR_INTERPOLATION_CUBICSPLINE) {
        mvr_str_format(why, why_size, "unknown interpolation %d", (int)s->interpolation);
        return false;
    }
    if (s->count < 1) {
        mvr_str_copy(why, why_size, "sampler has no keys");
        return false;
    }
    if (s->components < 1) {
        mvr_str_copy(why, why_size, "sampler values have no components");
        return false;
    }
    if (s->quaternion && s->components != 4) {
        mvr_str_format(why, why_size, "a rotation sampler has 4 components, not %u", (unsigned)s->components);
        return false;
    }
    if (!s->times || !s->values) {
        mvr_str_copy(why, why_size, s->times ? "sampler values are NULL" : "sampler times are NULL");
        return false;
    }
    size_t needed = 0;
    if (!mvr_anim_sampler_value_count(s->count, s->components, s->interpolation, &needed)) {
        mvr_str_format(why, why_size, "%zu keys of %u components overflow", s->count, (unsigned)s->components);
        return false;
    }
    if (s->value_count < needed) {
        mvr_str_format(why, why_size, "%zu keys need %zu values, the sampler has %zu", s->count, needed,
                       s->value_count);
        return false;
    }
    for (size_t i = 0; i < s->count; ++i) {
        if (!isfinite(s->times[i])) {
            mvr_str_format(why, why_size, "key %zu has a non-finite time", i);
            return false;
        }
        if (i > 0 && !(s->times[i] > s->times[i - 1])) {
            mvr_str_format(why, why_size, "key times are not strictly increasing at key %zu (%.17g after %.17g)", i,
                           s->times[i], s->times[i - 1]);
            return false;
        }
    }
    for (size_t i = 0; i < needed; ++i) {
        if (!isfinite(s->values[i])) {
            mvr_str_format(why, why_size, "value %zu is not finite", i);
            return false;
        }
    }
    return true;
}

size_t mvr_anim_find_key(const double *times, size_t count, double t)
{
    if (count < 2 || !(t > times[0]))
        return 0;
    if (t >= times[count - 1])
        return count - 1;
    /* times[lo] <= t < times[hi] */
    size_t lo = 0, hi = count - 1;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (times[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static void normalize_quat(double q[4])
{
    double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (n > 0 && isfinite(n)) {
        for (int i = 0; i < 4; ++i)
            q[i] /= n;
    } else {
        q[0] = q[1] = q[2] = 0.0;
        q[3] = 1.0;
    }
}

/* Slerp from a to b by s along the shorter arc, normalised. */
static void slerp(const double *a, const double *b, double s, double *out)
{
    double qa[4], qb[4];
    memcpy(qa, a, sizeof qa);
    memcpy(qb, b, sizeof qb);
    normalize_quat(qa);
    normalize_quat(qb);
    double dot = qa[0] * qb[0] + qa[1] * qb[1] + qa[2] * qb[2] + qa[3] * qb[3];
    if (dot < 0) {  /* q and -q are the same rotation: take the shorter arc */
        for (int i = 0; i < 4; ++i)
            qb[i] = -qb[i];
    }
    /* The angle from |a - b| and |a + b| keeps its precision near 0, where
     * acos(dot) loses half the digits. */
    double d2 = 0.0, s2 = 0.0;
    for (int i = 0; i < 4; ++i) {
        d2 += (qa[i] - qb[i]) * (qa[i] - qb[i]);
        s2 += (qa[i] + qb[i]) * (qa[i] + qb[i]);
    }
    double theta = 2.0 * atan2(sqrt(d2), sqrt(s2));
    double wa, wb;
    if (theta < SLERP_MIN_ANGLE) {
        wa = 1.0 - s;
        wb = s;
    } else {
        double sin_theta = sin(theta);
        wa = sin((1.0 - s) * theta) / sin_theta;
        wb = sin(s * theta) / sin_theta;
    }
    for (int i = 0; i < 4; ++i)
        out[i] = wa * qa[i] + wb * qb[i];
    normalize_quat(out);
}

void mvr_anim_sample(const mvr_anim_sampler *s, double t, double *out)
{
    const size_t c = s->components;
    const bool cubic = s->interpolation == MVR_INTERPOLATION_CUBICSPLINE;
    const size_t stride = cubic ? 3 * c : c;  /* doubles per key */
    const size_t value_at = cubic ? c : 0;    /* the value within a key */
    size_t k = mvr_anim_find_key(s->times, s->count, t);
    const double *vk = s->values + k * stride + value_at;

    /* Clamped before the first key / at or after the last, STEP, or a time
     * exactly on a key: the key's value. */
    if (k + 1 >= s->count || !(t > s->times[0]) || s->interpolation == MVR_INTERPOLATION_STEP || t == s->times[k]) {
        memcpy(out, vk, c * sizeof *out);
        if (s->quaternion && s->interpolation != MVR_INTERPOLATION_STEP)
            normalize_quat(out);
        return;
    }

    double t0 = s->times[k], t1 = s->times[k + 1], td = t1 - t0;
    double u = (t - t0) / td;
    if (u < 0.0)
        u = 0.0;
    else if (u > 1.0)
        u = 1.0;
    const double *vk1 = s->values + (k + 1) * stride + value_at;

    if (!cubic) {
        if (s->quaternion) {
            slerp(vk, vk1, u, out);
        } else {
            for (size_t i = 0; i < c; ++i)
                out[i] = vk[i] + (vk1[i] - vk[i]) * u;
        }
        return;
    }

    /* glTF 2.0 Appendix C: b_k is key k's out-tangent, a_k+1 key k+1's in-tangent. */
    const double *bk = vk + c, *ak1 = vk1 - c;
    double u2 = u * u, u3 = u2 * u;
    double h00 = 2.0 * u3 - 3.0 * u2 + 1.0, h10 = (u3 - 2.0 * u2 + u) * td;
    double h01 = -2.0 * u3 + 3.0 * u2, h11 = (u3 - u2) * td;
    for (size_t i = 0; i < c; ++i)
        out[i] = h00 * vk[i] + h10 * bk[i] + h01 * vk1[i] + h11 * ak1[i];
    if (s->quaternion)
        normalize_quat(out);
}

double mvr_anim_time(double t, double start, double end, bool loop)
{
    if (!isfinite(start))
        return 0.0;
    if (!isfinite(end) || !(end > start) || isnan(t))
        return start;
    if (!loop)
        return t < start ? start : t > end ? end : t;
    if (!isfinite(t))
        return start;
    double d = end - start, r = fmod(t - start, d);
    if (r < 0.0)
        r += d;
    if (!(r < d))  /* r + d rounded up to d */
        r = 0.0;
    return start + r;
}
