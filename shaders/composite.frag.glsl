// composite.frag.glsl: copies one layer of a color array, each view reading
// its own layer (multiview: the layer follows gl_ViewID_OVR). MVR_DOWNSAMPLE:
// the supersampling resolve, each pixel the mean of its factor x factor
// source texels (linear values; summed in a fixed order, so every path
// gives the same bytes).
uniform sampler2DArray mvr_source;
#ifdef MVR_DOWNSAMPLE
uniform int mvr_factor;
#endif

flat in int v_layer;
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

void main()
{
#ifdef MVR_DOWNSAMPLE
    ivec2 base = ivec2(gl_FragCoord.xy) * mvr_factor;
    vec4 sum = vec4(0.0);
    for (int y = 0; y < mvr_factor; ++y)
        for (int x = 0; x < mvr_factor; ++x)
            sum += texelFetch(mvr_source, ivec3(base + ivec2(x, y), v_layer), 0);
    vec4 c = sum / float(mvr_factor * mvr_factor);
#else
    vec4 c = textureLod(mvr_source, vec3(v_uv, float(v_layer)), 0.0);
#endif
#ifdef MVR_SRGB_ENCODE
    c.rgb = mvr_linear_to_srgb(c.rgb);
#endif
    o_color = c;
}
