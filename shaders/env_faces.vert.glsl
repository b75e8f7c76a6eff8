// env_faces.vert.glsl: one full-screen triangle per cube face. A multiview
// pass draws the six faces of a level as six views (face = view); a loop
// pass draws one face into the cube map directly.
flat out int v_face;

uniform int mvr_face_base;   // the face of view 0 of this pass

void main()
{
    vec2 p = mvr_full_screen_corner();
#ifdef MVR_MULTIVIEW
    v_face = mvr_face_base + int(gl_ViewID_OVR);
#else
    v_face = mvr_face_base;
#endif
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
