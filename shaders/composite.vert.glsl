// composite.vert.glsl: one full-screen triangle, no vertex buffer needed.
flat out int v_layer;
out vec2 v_uv;

uniform int mvr_layer_base;  // source layer of view 0 of this pass

void main()
{
    vec2 p = mvr_full_screen_corner();
    v_uv = p;
#ifdef MVR_MULTIVIEW
    v_layer = mvr_layer_base + int(gl_ViewID_OVR);
#else
    v_layer = mvr_layer_base;
#endif
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
