// composite.frag.glsl: copies one layer of a color array, each view reading
// its own layer (multiview: the layer follows gl_ViewID_OVR).
uniform sampler2DArray mvr_source;

flat in int v_layer;
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

void main()
{
    vec4 c = textureLod(mvr_source, vec3(v_uv, float(v_layer)), 0.0);
#ifdef MVR_SRGB_ENCODE
    c.rgb = mvr_linear_to_srgb(c.rgb);
#endif
    o_color = c;
}
