// shadows.glsl: shadow maps of the lights (mesh fragment stage, MVR_SHADOWS).

#ifdef MVR_SHADOWS
uniform sampler2DArrayShadow mvr_shadow_map; // compare mode: GEQUAL (reversed-Z) or LEQUAL
// mvr_shadows: per layer, per light (core/block_layout.c)
#mvr_block mvr_shadows

// Fraction of a light reaching p: the first of the light's layers whose map
// holds p (cascades nest from near to far; outside all of them: lit), 3x3
// taps of the GL's bilinear depth comparison (percentage-closer filtering,
// Reeves, Salesin and Cook, SIGGRAPH 1987). The receiver moves along its
// normal by normal-bias texels first (normal offset), so a lit surface does
// not shadow itself; the casters' slope-scaled polygon offset does the rest.
float mvr_shadow(int light, vec3 p, vec3 n_offset, float dist)
{
    ivec4 info = mvr_light_shadow[light];
    for (int k = 0; k < info.y; ++k) {
        int layer = info.x + k;
        vec4 prm = mvr_shadow_params[layer];
        float texel = prm.x * (prm.y > 0.0 ? dist : 1.0);
        vec4 c = mvr_shadow_matrix[layer] * vec4(p + n_offset * (texel * prm.z), 1.0);
        if (!(c.w > 0.0))
            continue;
        vec3 s = c.xyz / c.w;
        float edge = 2.0 * prm.w;
        if (any(lessThan(s.xy, vec2(edge))) || any(greaterThan(s.xy, vec2(1.0 - edge))) ||
            s.z < 0.0 || s.z > 1.0)
            continue;
        float sum = 0.0;
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x)
                sum += texture(mvr_shadow_map, vec4(s.xy + vec2(float(x), float(y)) * prm.w, float(layer), s.z));
        return sum / 9.0;
    }
    return 1.0;
}
#endif
