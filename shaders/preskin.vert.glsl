// preskin.vert.glsl: the pre-skinning path. Once per frame, each skinned or
// morphed draw's vertices go through mvr_vertex_geometry (deform.glsl, the same code
// the mesh program runs on the vertex path) and transform feedback captures
// them into a buffer every view and the shadow pass then draw as plain
// geometry. The rasterizer is off.

// locations 0-2 and 6-9: deform.glsl

uniform ivec4 mvr_deform_info; // as mvr_draw_data.info: y joint base, z morph header, w morph delta base

out vec3 o_position;
out vec3 o_normal;
out vec4 o_tangent;

void main()
{
    vec3 position, normal;
    vec4 tangent;
    mvr_vertex_geometry(mvr_deform_info, position, normal, tangent);
    o_position = position;
    o_normal = normal;
    o_tangent = tangent;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
