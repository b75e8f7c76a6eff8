// common.glsl: shared by every stage of every program. The generator
// (core/shader_gen.c) puts #version, the multiview extension and the feature
// #defines in front of this file.
//
// highp everywhere: llvmpipe really computes medium precision in fp16, and world
// positions relative to the view origin need the full float mantissa.
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler2DArrayShadow;
precision highp samplerCube;

const float MVR_PI = 3.14159265358979323846;

// Normalizes v, or returns fallback when v is zero, denormal or NaN, so no NaN
// reaches a pixel from degenerate input. (!(x > eps) is true for NaN too.)
vec3 mvr_safe_normalize(vec3 v, vec3 fallback)
{
    float len2 = dot(v, v);
    if (!(len2 > 1e-24) || isinf(len2))
        return fallback;
    return v * inversesqrt(len2);
}

// x^5 (Schlick's Fresnel) as three multiplications: llvmpipe evaluates pow()
// as exp2(y log2 x), two polynomial approximations per lane, and is less exact.
float mvr_pow5(float x)
{
    float x2 = x * x;
    return x2 * x2 * x;
}

// Exact piecewise sRGB encode (IEC 61966-2-1), not a gamma approximation.
vec3 mvr_linear_to_srgb(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    vec3 lo = c * 12.92;
    vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
    return mix(hi, lo, vec3(lessThanEqual(c, vec3(0.0031308))));
}

// Its inverse (IEC 61966-2-1).
vec3 mvr_srgb_to_linear(vec3 c)
{
    vec3 lo = c / 12.92;
    vec3 hi = pow((c + 0.055) / 1.055, vec3(2.4));
    return mix(hi, lo, vec3(lessThanEqual(c, vec3(0.04045))));
}

#ifdef MVR_VERTEX_STAGE
// A corner of the full-screen triangle of an attributeless draw of 3
// vertices: (0, 0), (2, 0), (0, 2), in units of the viewport (so the
// triangle covers [0, 1]^2).
vec2 mvr_full_screen_corner()
{
    return vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
}
#endif
