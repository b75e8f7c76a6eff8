// preskin.vert.glsl: the pre-skinning path. Once per frame, each skinned or
// morphed draw's vertices go through mvr_deform (deform.glsl, the same code
// the mesh program runs on the vertex path) and transform feedback captures
// them into a buffer every view and the shadow pass then draw as plain
// geometry. The rasterizer is off.

layout(location = 0) in vec3 a_position;
#ifdef MVR_NORMALS
layout(location = 1) in vec3 a_normal;
#endif
#ifdef MVR_TANGENTS
layout(location = 2) in vec4 a_tangent;
#endif

uniform ivec4 mvr_deform_info; // as mvr_draw_data.info: y joint base, z morph header, w morph delta base

out vec3 o_position;
out vec3 o_normal;
out vec4 o_tangent;

void main()
{
    vec3 position = a_position;
#ifdef MVR_NORMALS
    vec3 normal = a_normal;
#else
    vec3 normal = vec3(0.0);
#endif
#ifdef MVR_TANGENTS
    vec4 tangent = a_tangent;
#else
    vec4 tangent = vec4(0.0);
#endif
#if defined(MVR_SKIN) || defined(MVR_MORPH)
    mvr_deform(mvr_deform_info.y, mvr_deform_info.z, mvr_deform_info.w, position, normal, tangent);
#endif
    o_position = position;
    o_normal = normal;
    o_tangent = tangent;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
