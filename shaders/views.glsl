// views.glsl: the view set of a pass and how a vertex finds its view (both
// stages of the mesh program declare the block; the fragment stage reads the
// views' light masks).
// Matrices are relative to the view set's origin (camera-relative precision:
// the CPU subtracts the origin in double before narrowing to float).
// The mvr_views block, from the std140 layout table (core/block_layout.c)
#mvr_block mvr_views

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
