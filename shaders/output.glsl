// output.glsl: what a lit fragment stage writes (mesh and background
// programs). Exposure and (for UNORM targets) the exact sRGB encode; sRGB
// targets encode in hardware with the same piecewise function. Tone mapping
// is the post pass's (composite.frag.glsl), after lighting is summed and
// blended in linear HDR; there mvr_exposure is the pre-exposure that keeps
// the half float target in range. The min() keeps inf out of a half float
// target.
uniform float mvr_exposure;  // multiplies the lit color (the linear exposure, or a post pass's pre-exposure)

vec4 mvr_output(vec4 c)
{
    vec3 rgb = min(max(c.rgb, vec3(0.0)) * mvr_exposure, vec3(65000.0));
#ifdef MVR_SRGB_OUTPUT
    rgb = mvr_linear_to_srgb(rgb);
#endif
    return vec4(rgb, clamp(c.a, 0.0, 1.0));
}
