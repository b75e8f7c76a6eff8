// views.glsl: the view set of a pass and how a vertex finds its view (both
// stages of the mesh program declare the block; the fragment stage reads the
// views' light masks).
// Matrices are relative to the view set's origin (camera-relative precision:
// the CPU subtracts the origin in double before narrowing to float).
layout(std140) uniform mvr_views {
    mat4 mvr_view_proj[MVR_MAX_VIEWS];
    vec4 mvr_eye_position[MVR_MAX_VIEWS];   // xyz relative to the origin
    ivec4 mvr_view_info[MVR_MAX_VIEWS];     // x: bit i set = light i shines in the view
    mat4 mvr_view_matrix[MVR_MAX_VIEWS];    // world (relative) to camera; sent only for extra outputs
};

// First view of this pass: a multiview pass covers views
// [mvr_view_base, mvr_view_base + MVR_NUM_VIEWS); a loop pass covers one view.
uniform int mvr_view_base;

int mvr_view_index()
{
#ifdef MVR_MULTIVIEW
    return mvr_view_base + int(gl_ViewID_OVR);
#else
    return mvr_view_base;
#endif
}
