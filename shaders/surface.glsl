// surface.glsl: what the mesh program's fragment stage knows of its surface:
// the material table and its texture roles, the varyings, texture
// coordinates, the tangent frame, the normal before normal maps and the
// material's alpha. The material extensions' inputs are read in
// mesh.frag.glsl's main; their functions are in material_*.glsl.

// struct mvr_material (480 bytes in std140, whatever the features) and the
// mvr_materials block: a page of MVR_MAX_MATERIALS of the table, generated
// from the std140 layout table (core/block_layout.c)
#mvr_block mvr_materials

// The texture roles (core/material.h)
#define MVR_ROLE_BASE_COLOR 0
#define MVR_ROLE_METAL_ROUGH 1
#define MVR_ROLE_NORMAL 2
#define MVR_ROLE_OCCLUSION 3
#define MVR_ROLE_EMISSIVE 4
#define MVR_ROLE_CLEARCOAT 5
#define MVR_ROLE_CLEARCOAT_ROUGHNESS 6
#define MVR_ROLE_CLEARCOAT_NORMAL 7
#define MVR_ROLE_SHEEN_COLOR 8
#define MVR_ROLE_SHEEN_ROUGHNESS 9
#define MVR_ROLE_SPECULAR 10
#define MVR_ROLE_SPECULAR_COLOR 11
#define MVR_ROLE_TRANSMISSION 12
#define MVR_ROLE_THICKNESS 13
#define MVR_ROLE_IRIDESCENCE 14
#define MVR_ROLE_IRIDESCENCE_THICKNESS 15
#define MVR_ROLE_ANISOTROPY 16
#define MVR_ROLE_SPEC_GLOSS 17
// uv.w bit: occlusion is the metallic-roughness fetch's red (core/material.h)
#define MVR_OCCLUSION_IN_METAL_ROUGH_BIT 30

#ifdef MVR_MATERIAL_ARRAYS
#define MVR_SAMPLER sampler2DArray
#define MVR_SAMPLE(s, uv, layer) texture(s, vec3(uv, float(layer)))
#else
#define MVR_SAMPLER sampler2D
#define MVR_SAMPLE(s, uv, layer) texture(s, uv)
#endif

#ifdef MVR_BASE_COLOR_TEX
uniform MVR_SAMPLER mvr_base_color_tex;
#endif
#ifdef MVR_METAL_ROUGH_TEX
uniform MVR_SAMPLER mvr_metal_rough_tex;
#endif
#ifdef MVR_NORMAL_TEX
uniform MVR_SAMPLER mvr_normal_tex;
#endif
#ifdef MVR_OCCLUSION_TEX
uniform MVR_SAMPLER mvr_occlusion_tex;
#endif
#ifdef MVR_EMISSIVE_TEX
uniform MVR_SAMPLER mvr_emissive_tex;
#endif

in vec3 v_position;
in vec3 v_to_eye;
flat in int v_material;
// the material's most read fields, fetched per vertex (mesh.vert.glsl)
flat in vec4 v_material_base;
flat in vec4 v_material_emissive;
flat in vec4 v_material_params;
flat in ivec4 v_material_uv;
#if defined(MVR_LIGHT_MASKS) || defined(MVR_TRANSMISSION) || defined(MVR_OUTPUTS)
flat in int v_view;
#endif
#ifdef MVR_OUT_IDS
flat in uvec4 v_ids;
#endif
#ifdef MVR_TRANSMISSION
flat in vec3 v_model_scale;
#endif
#ifdef MVR_NORMALS
in vec3 v_normal;
#endif
#ifdef MVR_TANGENTS
in vec4 v_tangent;
#endif
#ifdef MVR_UV0
in vec2 v_uv0;
#endif
#ifdef MVR_UV1
in vec2 v_uv1;
#endif
#ifdef MVR_COLOR0
in vec4 v_color0;
#endif

// This fragment's material. Its most read fields come from the vertex stage
// as flat varyings, the same bits: on llvmpipe a uniform block read at an
// index that varies by fragment (v_material, flat, but not known to be the
// same across a block of fragments) is a gather per lane and per field, a
// flat varying a constant of the triangle. What is overwritten here is never
// read from the block.
mvr_material mvr_material_fetch()
{
    mvr_material m = mvr_material_table[v_material];
    m.base_color_factor = v_material_base;
    m.emissive = v_material_emissive;
    m.params = v_material_params;
    m.uv = v_material_uv;
    return m;
}

// The array layer of texture role `role` (0 on the per-material path).
int mvr_layer(mvr_material m, int role)
{
    return (m.layers[role >> 3][(role >> 1) & 3] >> ((role & 1) * 16)) & 0xFFFF;
}

// Whether the material has a texture in role `role` (the extensions' roles
// are sampled only then: a uniform branch per draw).
bool mvr_has_texture(mvr_material m, int role)
{
    return ((m.uv.w >> role) & 1) != 0;
}

// Texture coordinates of texture role `role`.
vec2 mvr_uv(int role, mvr_material m)
{
    int field = (m.uv[role >> 3] >> ((role & 7) * 4)) & 15;
    vec2 uv = vec2(0.0);
#ifdef MVR_UV0
    uv = v_uv0;
#endif
#ifdef MVR_UV1
    if ((field & 1) != 0)
        uv = v_uv1;
#endif
#ifdef MVR_TEXTURE_TRANSFORM
    int slot = field >> 1;
    vec3 h = vec3(uv, 1.0);
    uv = vec2(dot(m.uv_transform[2 * slot].xyz, h), dot(m.uv_transform[2 * slot + 1].xyz, h));
#endif
    return uv;
}

#define MVR_SAMPLE_ROLE(s, role, m) MVR_SAMPLE(s, mvr_uv(role, m), mvr_layer(m, role))

#if defined(MVR_NORMAL_TEX) || defined(MVR_CLEARCOAT) || defined(MVR_ANISOTROPY)
// The tangent and bitangent of a normal map sampled at uv, about the
// (front side's) normal nf: the vertex tangents where given; else t =
// dP/du from position and UV derivatives and b = n x t, turned to point
// towards -v (image up: glTF normal maps are +Y up with uv (0,0) at the
// image's top-left). Degenerate UVs (zero determinant) give t = b = 0,
// which leaves the normal unperturbed.
void mvr_tangent_frame(vec3 nf, vec2 uv, out vec3 t, out vec3 b)
{
#ifdef MVR_TANGENTS
    t = mvr_safe_normalize(v_tangent.xyz - nf * dot(nf, v_tangent.xyz), vec3(0.0));
    b = cross(nf, t) * (v_tangent.w < 0.0 ? -1.0 : 1.0);
#else
    vec3 dp1 = dFdx(v_position), dp2 = dFdy(v_position);
    vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
    float det = duv1.x * duv2.y - duv1.y * duv2.x;
    t = vec3(0.0);
    b = vec3(0.0);
    if (abs(det) > 1e-20) {
        vec3 dpdu = (dp1 * duv2.y - dp2 * duv1.y) / det;
        vec3 dpdv = (dp2 * duv1.x - dp1 * duv2.x) / det;
        t = mvr_safe_normalize(dpdu - nf * dot(nf, dpdu), vec3(0.0));
        b = cross(nf, t);
        if (dot(b, dpdv) > 0.0)
            b = -b;
    }
#endif
}
#endif

#ifndef MVR_SHADOW_CASTER
// The surface's normal before normal maps: the interpolated vertex normal, or
// the geometric normal from screen-space derivatives (always defined for a
// rasterized triangle) where there is none or it is degenerate; negated on
// the back of a double-sided surface.
vec3 mvr_surface_normal()
{
    vec3 face_n = mvr_safe_normalize(cross(dFdx(v_position), dFdy(v_position)), vec3(0.0, 0.0, 1.0));
#ifdef MVR_NORMALS
    vec3 n = mvr_safe_normalize(v_normal, face_n);
#else
    vec3 n = face_n;
#endif
#ifdef MVR_DOUBLE_SIDED
    if (!gl_FrontFacing)
        n = -n;
#endif
    return n;
}
#endif

// The material's alpha at this fragment: factor x vertex colour x texture
// (the shadow casters' alpha test, the outputs' cutoff).
float mvr_material_alpha(mvr_material m)
{
    float alpha = m.base_color_factor.a;
#ifdef MVR_COLOR0
    alpha *= v_color0.a;
#endif
#ifdef MVR_BASE_COLOR_TEX
    alpha *= MVR_SAMPLE_ROLE(mvr_base_color_tex, MVR_ROLE_BASE_COLOR, m).a;
#endif
    return alpha;
}
