// mesh.vert.glsl: scene geometry. Per-draw data is read only here and passed
// on as flat varyings: on llvmpipe a change to anything the fragment stage
// reads costs a full state snapshot, vertex-only data is much cheaper.

// One block per draw; an instanced draw reads consecutive blocks by
// gl_InstanceID (a plain draw has gl_InstanceID 0). std140 gives the struct
// a 144-byte array stride, the size of one block, plus MVR_DRAW_PAD vec4s
// where the GL's uniform offset alignment spaces blocks further apart
// (256 bytes on many desktop GPUs).
// struct mvr_draw_data and the mvr_draw block of MVR_DRAW_CAPACITY of them,
// from the std140 layout table (core/block_layout.c)
#mvr_block mvr_draw
// struct mvr_material and the mvr_materials block (the fragment stage's, surface.glsl)
#mvr_block mvr_materials

// locations 0-2 (position, normal, tangent) and 6-9 (joints, weights):
// deform.glsl
#ifdef MVR_UV0
layout(location = 3) in vec2 a_uv0;
#endif
#ifdef MVR_UV1
layout(location = 4) in vec2 a_uv1;
#endif
#ifdef MVR_COLOR0
layout(location = 5) in vec4 a_color0;
#endif

out vec3 v_position;         // world, relative to the view origin
out vec3 v_to_eye;           // eye - position: linear, so interpolation is exact
flat out int v_material;
// the material's most read fields, once per vertex rather than per fragment (surface.glsl)
flat out vec4 v_material_base;
flat out vec4 v_material_emissive;
flat out vec4 v_material_params;
flat out ivec4 v_material_uv;
#if defined(MVR_LIGHT_MASKS) || defined(MVR_TRANSMISSION) || defined(MVR_OUTPUTS)
flat out int v_view;         // within the view block
#endif
#ifdef MVR_OUT_IDS
flat out uvec4 v_ids;
#endif
#ifdef MVR_TRANSMISSION
flat out vec3 v_model_scale; // the model matrix's axis scales (KHR_materials_volume's thickness is in model units)
#endif
#ifdef MVR_NORMALS
out vec3 v_normal;
#endif
#ifdef MVR_TANGENTS
out vec4 v_tangent;
#endif
#ifdef MVR_UV0
out vec2 v_uv0;
#endif
#ifdef MVR_UV1
out vec2 v_uv1;
#endif
#ifdef MVR_COLOR0
out vec4 v_color0;
#endif

void main()
{
    int view = mvr_view_index();
    mat4 mvr_model = mvr_draws[gl_InstanceID].model;
    vec3 position, normal;
    vec4 tangent;
    mvr_vertex_geometry(mvr_draws[gl_InstanceID].info, position, normal, tangent);
    vec4 world = mvr_model * vec4(position, 1.0);
    v_position = world.xyz;
    v_to_eye = mvr_eye_position[view].xyz - world.xyz;
    v_material = mvr_draws[gl_InstanceID].info.x;
    v_material_base = mvr_material_table[v_material].base_color_factor;
    v_material_emissive = mvr_material_table[v_material].emissive;
    v_material_params = mvr_material_table[v_material].params;
    v_material_uv = mvr_material_table[v_material].uv;
#if defined(MVR_LIGHT_MASKS) || defined(MVR_TRANSMISSION) || defined(MVR_OUTPUTS)
    v_view = view;
#endif
#ifdef MVR_OUT_IDS
    v_ids = mvr_draws[gl_InstanceID].ids;
#endif
#ifdef MVR_TRANSMISSION
    v_model_scale = vec3(length(mvr_model[0].xyz), length(mvr_model[1].xyz), length(mvr_model[2].xyz));
#endif
#ifdef MVR_NORMALS
    v_normal = mat3(mvr_draws[gl_InstanceID].normal_matrix[0].xyz, mvr_draws[gl_InstanceID].normal_matrix[1].xyz,
                    mvr_draws[gl_InstanceID].normal_matrix[2].xyz) * normal;
#endif
#ifdef MVR_TANGENTS
    v_tangent = vec4(mat3(mvr_model) * tangent.xyz, tangent.w);
#endif
#ifdef MVR_UV0
    v_uv0 = a_uv0;
#endif
#ifdef MVR_UV1
    v_uv1 = a_uv1;
#endif
#ifdef MVR_COLOR0
    v_color0 = a_color0;
#endif
    gl_Position = mvr_view_proj[view] * world;
}
