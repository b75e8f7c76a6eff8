// deform.glsl: a vertex's geometry (position, normal, tangent) as the
// vertex stage reads it, with skinning and morph targets: the mesh
// program's (the vertex path: once per view and pass) or the pre-skinning
// program's (once per frame, captured by transform feedback). Both run
// mvr_vertex_geometry, so both paths give the same vertices.
//
// Per-frame data is one RGBA32F texture shared by every view (uploaded once
// per frame): joint matrices of every skin, relative to the view origin
// (texels base + 7j .. +3: the matrix's columns; +4 .. +6: its normal
// matrix's), and per morphed draw a header texel (active targets, vertices,
// attributes per target, slots) then its active (target, weight) pairs, two
// per texel. Morph deltas (uploaded once per scene) are another texture:
// delta texel = base + (target * attributes + slot) * vertices + vertex.
layout(location = 0) in vec3 a_position;
#ifdef MVR_NORMALS
layout(location = 1) in vec3 a_normal;
#endif
#ifdef MVR_TANGENTS
layout(location = 2) in vec4 a_tangent;
#endif

#if defined(MVR_SKIN) || defined(MVR_MORPH)
#define MVR_DATA_WIDTH_LOG2 10
uniform highp sampler2D mvr_anim_data;

ivec2 mvr_data_texel(int i)
{
    return ivec2(i & ((1 << MVR_DATA_WIDTH_LOG2) - 1), i >> MVR_DATA_WIDTH_LOG2);
}

vec4 mvr_anim_fetch(int i)
{
    return texelFetch(mvr_anim_data, mvr_data_texel(i), 0);
}
#endif

#ifdef MVR_SKIN
layout(location = 6) in uvec4 a_joints0;
layout(location = 7) in vec4 a_weights0;
#ifdef MVR_SKIN8
layout(location = 8) in uvec4 a_joints1;
layout(location = 9) in vec4 a_weights1;
#endif

mat4 mvr_joint(int base, uint j)
{
    int at = base + 7 * int(j);
    return mat4(mvr_anim_fetch(at), mvr_anim_fetch(at + 1), mvr_anim_fetch(at + 2), mvr_anim_fetch(at + 3));
}

mat3 mvr_joint_normal(int base, uint j)
{
    int at = base + 7 * int(j) + 4;
    return mat3(mvr_anim_fetch(at).xyz, mvr_anim_fetch(at + 1).xyz, mvr_anim_fetch(at + 2).xyz);
}
#endif

#ifdef MVR_MORPH
uniform highp sampler2D mvr_morph_deltas;

vec3 mvr_morph_delta(int i)
{
    return texelFetch(mvr_morph_deltas, mvr_data_texel(i), 0).xyz;
}
#endif

#if defined(MVR_SKIN) || defined(MVR_MORPH)
// Morphs then skins (glTF 3.7.2.2 and 3.7.3: targets displace the base
// mesh, the skin poses the result). joint_base < 0: not skinned; morph_base
// < 0: no targets. Normals and tangents are not normalised here: the
// fragment stage does it, after interpolation.
void mvr_deform(int joint_base, int morph_base, int delta_base, inout vec3 position, inout vec3 normal,
                inout vec4 tangent)
{
#ifdef MVR_MORPH
    if (morph_base >= 0) {
        vec4 head = mvr_anim_fetch(morph_base);
        int targets = int(head.x), vertices = int(head.y), attributes = int(head.z), slots = int(head.w);
        int pos_slot = slots & 3, normal_slot = (slots >> 2) & 3, tangent_slot = (slots >> 4) & 3;
        for (int i = 0; i < targets; ++i) {
            vec4 pair = mvr_anim_fetch(morph_base + 1 + (i >> 1));
            vec2 tw = (i & 1) == 0 ? pair.xy : pair.zw;
            int row = delta_base + int(tw.x) * attributes * vertices + gl_VertexID;
            if (pos_slot < 3)
                position += tw.y * mvr_morph_delta(row + pos_slot * vertices);
            if (normal_slot < 3)
                normal += tw.y * mvr_morph_delta(row + normal_slot * vertices);
            if (tangent_slot < 3)
                tangent.xyz += tw.y * mvr_morph_delta(row + tangent_slot * vertices);
        }
    }
#endif
#ifdef MVR_SKIN
    if (joint_base >= 0) {
        mat4 skin = a_weights0.x * mvr_joint(joint_base, a_joints0.x) +
                    a_weights0.y * mvr_joint(joint_base, a_joints0.y) +
                    a_weights0.z * mvr_joint(joint_base, a_joints0.z) +
                    a_weights0.w * mvr_joint(joint_base, a_joints0.w);
        mat3 skin_normal = a_weights0.x * mvr_joint_normal(joint_base, a_joints0.x) +
                           a_weights0.y * mvr_joint_normal(joint_base, a_joints0.y) +
                           a_weights0.z * mvr_joint_normal(joint_base, a_joints0.z) +
                           a_weights0.w * mvr_joint_normal(joint_base, a_joints0.w);
#ifdef MVR_SKIN8
        skin += a_weights1.x * mvr_joint(joint_base, a_joints1.x) + a_weights1.y * mvr_joint(joint_base, a_joints1.y) +
                a_weights1.z * mvr_joint(joint_base, a_joints1.z) + a_weights1.w * mvr_joint(joint_base, a_joints1.w);
        skin_normal += a_weights1.x * mvr_joint_normal(joint_base, a_joints1.x) +
                       a_weights1.y * mvr_joint_normal(joint_base, a_joints1.y) +
                       a_weights1.z * mvr_joint_normal(joint_base, a_joints1.z) +
                       a_weights1.w * mvr_joint_normal(joint_base, a_joints1.w);
#endif
        position = (skin * vec4(position, 1.0)).xyz;
        normal = skin_normal * normal;
        tangent.xyz = mat3(skin) * tangent.xyz;
    }
#endif
}
#endif

// The vertex's geometry in the space its draw's model matrix places: local
// (plain and morph-only draws), or world relative to the view origin
// (skinned: the model is the identity). info as mvr_draw_data.info.
void mvr_vertex_geometry(ivec4 info, out vec3 position, out vec3 normal, out vec4 tangent)
{
    position = a_position;
#ifdef MVR_NORMALS
    normal = a_normal;
#else
    normal = vec3(0.0);
#endif
#ifdef MVR_TANGENTS
    tangent = a_tangent;
#else
    tangent = vec4(0.0);
#endif
#if defined(MVR_SKIN) || defined(MVR_MORPH)
    mvr_deform(info.y, info.z, info.w, position, normal, tangent);
#endif
}
