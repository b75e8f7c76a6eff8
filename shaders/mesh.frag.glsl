// mesh.frag.glsl: glTF 2.0 metallic-roughness (Appendix B of the glTF 2.0
// specification: Lambertian diffuse, GGX / Trowbridge-Reitz distribution,
// height-correlated Smith visibility, Schlick Fresnel) with KHR_lights_punctual
// lights, and image-based lighting from a prefiltered environment (the
// split-sum approximation, Karis 2013, as the Khronos glTF Sample Renderer
// applies it). Everything this stage reads is constant across a pass: the material
// table and the lights are whole uniform blocks, the draw picks its material
// through a flat varying.

// Transmission and spec-gloss are drawn by the specular extension's
// dielectric code (core/material.c sets SPECULAR with them; a variant asked
// for without it compiles that code all the same).
#if (defined(MVR_TRANSMISSION) || defined(MVR_SPEC_GLOSS) || defined(MVR_IRIDESCENCE) || defined(MVR_ANISOTROPY)) && \
    !defined(MVR_SPECULAR)
#define MVR_SPECULAR
#endif

struct mvr_material {
    vec4 base_color_factor;
    vec4 emissive;           // rgb: emissive factor * strength, a: alpha cutoff
    vec4 params;             // x: metallic, y: roughness (spec-gloss: glossiness), z: normal scale,
                             // w: occlusion strength
    ivec4 layers[3];         // per texture role: its array layer, 16 bits each (mvr_layer)
    ivec4 uv;                // xyz: per role 4 bits (TEXCOORD_1, transform slot); w: bit per role
                             // with a texture (mvr_uv, mvr_has_texture)
    vec4 uv_transform[16];   // per transform slot: two rows of a 2x3 affine (KHR_texture_transform)
    vec4 specular;           // rgb: dielectric F0 (KHR_materials_ior x _specular color, unclamped),
                             // a: specular weight
    vec4 clearcoat;          // factor, roughness, F0, normal scale (KHR_materials_clearcoat)
    vec4 sheen;              // rgb: color, a: roughness (KHR_materials_sheen)
    vec4 transmission;       // factor, thickness, attenuation distance (0: none), dispersion
    vec4 volume;             // rgb: attenuation color, a: ior
    vec4 iridescence;        // factor, ior, thickness minimum, maximum (nm)
    vec4 anisotropy;         // strength, cos and sin of the rotation
};                           // 480 bytes in std140, whatever the features (core/frame.h)

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

layout(std140) uniform mvr_materials {
    mvr_material mvr_material_table[MVR_MAX_MATERIALS];
};

struct mvr_light {
    vec4 position_range;     // xyz relative to the view origin; w: range (0 = infinite)
    vec4 direction;          // xyz: direction the light points to (unit)
    vec4 color;              // rgb: color * intensity
    vec4 spot;               // x: angle scale, y: angle offset (KHR_lights_punctual)
};

#define MVR_LIGHT_COUNT (MVR_DIRECTIONAL_LIGHTS + MVR_POINT_LIGHTS + MVR_SPOT_LIGHTS)
#if MVR_LIGHT_COUNT > 0
layout(std140) uniform mvr_lights {
    mvr_light mvr_light_list[MVR_LIGHT_COUNT]; // directional, then point, then spot
};
#endif
#ifdef MVR_SHADOWS
uniform sampler2DArrayShadow mvr_shadow_map; // compare mode: GEQUAL (reversed-Z) or LEQUAL
layout(std140) uniform mvr_shadows {
    mat4 mvr_shadow_matrix[MVR_MAX_SHADOW_LAYERS]; // world (relative to the origin) -> (u, v, depth)
    vec4 mvr_shadow_params[MVR_MAX_SHADOW_LAYERS]; // x: texel size (world; perspective: per unit of
                                                   // distance), y: 1 = perspective, z: normal bias
                                                   // in texels, w: 1 / map size
    ivec4 mvr_light_shadow[MVR_MAX_LIGHTS];        // x: first layer, y: layers (0 = no shadow)
};
#endif
uniform vec3 mvr_ambient;    // rgb radiance of a uniform environment

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
#ifdef MVR_SPECULAR
uniform MVR_SAMPLER mvr_specular_tex;
uniform MVR_SAMPLER mvr_specular_color_tex;
#endif
#ifdef MVR_SPEC_GLOSS
uniform MVR_SAMPLER mvr_spec_gloss_tex;
#endif
#ifdef MVR_ANISOTROPY
uniform MVR_SAMPLER mvr_anisotropy_tex;
// KHR_materials_anisotropy of this fragment (set in main, read by the
// specular lobes): the direction of stretch and its bitangent, the strength
vec3 g_aniso_t = vec3(1.0, 0.0, 0.0);
vec3 g_aniso_b = vec3(0.0, 1.0, 0.0);
float g_aniso_strength = 0.0;
#endif
#ifdef MVR_IRIDESCENCE
uniform MVR_SAMPLER mvr_iridescence_tex;
uniform MVR_SAMPLER mvr_iridescence_thickness_tex;
#endif
#ifdef MVR_TRANSMISSION
uniform MVR_SAMPLER mvr_transmission_tex;
uniform MVR_SAMPLER mvr_thickness_tex;
// What the opaque sub-passes drew, per view of the chunk (layer = view -
// mvr_transmission_base), mip-mapped (gl/transmission.c)
uniform sampler2DArray mvr_transmission_source;
uniform int mvr_transmission_base;
uniform vec4 mvr_transmission_rect; // the chunk's viewport in the array: offset, size (0..1)
uniform float mvr_transmission_lod; // log2 of the viewport's width in texels
#endif
#ifdef MVR_CLEARCOAT
uniform MVR_SAMPLER mvr_clearcoat_tex;
uniform MVR_SAMPLER mvr_clearcoat_roughness_tex;
uniform MVR_SAMPLER mvr_clearcoat_normal_tex;
#endif
#ifdef MVR_SHEEN
uniform MVR_SAMPLER mvr_sheen_color_tex;
uniform MVR_SAMPLER mvr_sheen_roughness_tex;
#endif

in vec3 v_position;
in vec3 v_to_eye;
flat in int v_material;
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

layout(location = 0) out vec4 o_color;
// The extra outputs (core/shader_gen.h): location = colour attachment
#ifdef MVR_OUT_GEOMETRY
layout(location = 1) out vec4 o_geometry; // depth along the camera's -Z, distance to the eye, coverage
#endif
#ifdef MVR_OUT_NORMAL
layout(location = 2) out vec4 o_normal;
#endif
#ifdef MVR_OUT_IDS
layout(location = 3) out uvec4 o_ids;     // node, mesh, material, primitive
#endif
#ifdef MVR_OUT_ONLY
uniform float mvr_output_alpha_cutoff;
#endif

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

float mvr_v_smith_ggx_correlated(float n_dot_l, float n_dot_v, float alpha)
{
    float a2 = alpha * alpha;
    float gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    float gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    float s = gv + gl;
    return s > 0.0 ? 0.5 / s : 0.0;
}

vec3 mvr_brdf(vec3 n, vec3 v, vec3 l, vec3 base, float metallic, float alpha)
{
    float n_dot_l = clamp(dot(n, l), 0.0, 1.0);
    if (n_dot_l <= 0.0)
        return vec3(0.0);
    vec3 h = mvr_safe_normalize(l + v, n);
    float n_dot_v = clamp(abs(dot(n, v)), 1e-4, 1.0);
    float n_dot_h = clamp(dot(n, h), 0.0, 1.0);
    float v_dot_h = clamp(dot(v, h), 0.0, 1.0);
    vec3 f0 = mix(vec3(0.04), base, metallic);
    vec3 f = f0 + (1.0 - f0) * pow(1.0 - v_dot_h, 5.0);
    vec3 diffuse = (1.0 - f) * (1.0 - metallic) * base / MVR_PI;
    vec3 specular = f * mvr_d_ggx(n_dot_h, alpha) * mvr_v_smith_ggx_correlated(n_dot_l, n_dot_v, alpha);
    return (diffuse + specular) * n_dot_l;
}

#ifdef MVR_SPECULAR
// KHR_materials_ior and _specular, as the Khronos glTF Sample Renderer
// evaluates them: the dielectric's Fresnel is Schlick's with F0 = f0 * w and
// F90 = w (f0 from the index of refraction, tinted), the metal's with the
// base color and 1; diffuse under the dielectric's Fresnel. With f0 = 0.04
// and w = 1 it is mvr_brdf.
// D x Vis of the specular lobe: GGX, or with KHR_materials_anisotropy its
// anisotropic form (Kulla and Conty 2017's tangent roughness, as the Khronos
// Sample Renderer's BRDF_specularGGXAnisotropy: alpha along the direction
// raised to mix(alpha, 1, strength^2), the height-correlated visibility).
float mvr_specular_lobe(vec3 n, vec3 v, vec3 l, vec3 h, float alpha, float n_dot_l, float n_dot_v, float n_dot_h)
{
#ifdef MVR_ANISOTROPY
    if (g_aniso_strength > 0.0) {
        vec3 t = g_aniso_t, b = g_aniso_b;
        float at = mix(alpha, 1.0, g_aniso_strength * g_aniso_strength);
        float ab = clamp(alpha, 0.001, 1.0);
        float a2 = at * ab;
        vec3 f = vec3(ab * dot(t, h), at * dot(b, h), a2 * max(n_dot_h, 0.001));
        float w2 = a2 / dot(f, f);
        float d = a2 * w2 * w2 / MVR_PI;
        float gv = n_dot_l * length(vec3(at * dot(t, v), ab * dot(b, v), n_dot_v));
        float gl = n_dot_v * length(vec3(at * dot(t, l), ab * dot(b, l), n_dot_l));
        return d * clamp(0.5 / (gv + gl), 0.0, 1.0);
    }
#endif
    return mvr_d_ggx(n_dot_h, alpha) * mvr_v_smith_ggx_correlated(n_dot_l, n_dot_v, alpha);
}

vec3 mvr_brdf_specular(vec3 n, vec3 v, vec3 l, vec3 base, float metallic, float alpha, vec3 f0, float w)
{
    float n_dot_l = clamp(dot(n, l), 0.0, 1.0);
    if (n_dot_l <= 0.0)
        return vec3(0.0);
    vec3 h = mvr_safe_normalize(l + v, n);
    float n_dot_v = clamp(abs(dot(n, v)), 1e-4, 1.0);
    float n_dot_h = clamp(dot(n, h), 0.0, 1.0);
    float v_dot_h = clamp(dot(v, h), 0.0, 1.0);
    float x5 = pow(1.0 - v_dot_h, 5.0);
    vec3 f_dielectric = f0 * w + (w - f0 * w) * x5;
    vec3 f_metal = base + (1.0 - base) * x5;
    vec3 diffuse = (1.0 - f_dielectric) * base / MVR_PI;
    float ggx = mvr_specular_lobe(n, v, l, h, alpha, n_dot_l, n_dot_v, n_dot_h);
    vec3 dielectric = diffuse + f_dielectric * ggx;
    return mix(dielectric, f_metal * ggx, metallic) * n_dot_l;
}
#endif

#ifdef MVR_IRIDESCENCE
// KHR_materials_iridescence: the Fresnel reflectance of a thin film over the
// base (Belcour and Barla, "A Practical Extension to Microfacet Theory for
// the Modeling of Varying Iridescence", SIGGRAPH 2017), as the Khronos
// glTF Sample Renderer's evalIridescence evaluates it: Airy summation of
// two orders, each order's spectral sensitivity from the paper's Gaussian
// fit of the CIE XYZ curves, converted to linear Rec. 709.
const mat3 MVR_XYZ_TO_REC709 = mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259,
                                    -0.4985314, 0.0415560, 1.0572252);

vec3 mvr_film_sensitivity(float opd, vec3 shift)
{
    float phase = 2.0 * MVR_PI * opd * 1.0e-9;
    vec3 val = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
    vec3 pos = vec3(1.6810e+06, 1.7953e+06, 2.2084e+06);
    vec3 var = vec3(4.3278e+09, 9.3046e+09, 6.6121e+09);
    vec3 xyz = val * sqrt(2.0 * MVR_PI * var) * cos(pos * phase + shift) * exp(-phase * phase * var);
    xyz.x += 9.7470e-14 * sqrt(2.0 * MVR_PI * 4.5282e+09) * cos(2.2399e+06 * phase + shift[0]) *
             exp(-4.5282e+09 * phase * phase);
    return MVR_XYZ_TO_REC709 * (xyz / 1.0685e-7);
}

float mvr_ior_to_f0(float transmitted, float incident)
{
    float r = (transmitted - incident) / (transmitted + incident);
    return r * r;
}

// The film's reflectance at cos_theta1 (n.v) over a base of F0 base_f0;
// film of index film_ior (outside 1) and thickness nm nanometres.
vec3 mvr_iridescence_fresnel(float film_ior, float cos_theta1, float nm, vec3 base_f0)
{
    float ior = mix(1.0, film_ior, smoothstep(0.0, 0.03, nm));
    float sin2 = (1.0 / (ior * ior)) * (1.0 - cos_theta1 * cos_theta1);
    float cos2_sq = 1.0 - sin2;
    if (cos2_sq < 0.0)
        return vec3(1.0); // total internal reflection
    float cos_theta2 = sqrt(cos2_sq);
    float r0 = mvr_ior_to_f0(ior, 1.0);
    float x = clamp(1.0 - cos_theta1, 0.0, 1.0);
    float r12 = r0 + (1.0 - r0) * x * x * x * x * x;
    float t121 = 1.0 - r12;
    float phi12 = ior < 1.0 ? MVR_PI : 0.0;
    float phi21 = MVR_PI - phi12;
    vec3 sq_f0 = sqrt(clamp(base_f0, 0.0, 0.9999));
    vec3 base_ior = (1.0 + sq_f0) / (1.0 - sq_f0);
    vec3 r1 = (base_ior - ior) / (base_ior + ior);
    r1 *= r1;
    float x2 = clamp(1.0 - cos_theta2, 0.0, 1.0);
    vec3 r23 = r1 + (1.0 - r1) * x2 * x2 * x2 * x2 * x2;
    vec3 phi23 = vec3(lessThan(base_ior, vec3(ior))) * MVR_PI;
    float opd = 2.0 * ior * nm * cos_theta2;
    vec3 phi = vec3(phi21) + phi23;
    vec3 r123 = clamp(r12 * r23, 1e-5, 0.9999);
    vec3 rr = sqrt(r123);
    vec3 rs = t121 * t121 * r23 / (1.0 - r123);
    vec3 result = r12 + rs;
    vec3 cm = rs - t121;
    for (int k = 1; k <= 2; ++k) {
        cm *= rr;
        result += cm * 2.0 * mvr_film_sensitivity(float(k) * opd, float(k) * phi);
    }
    return max(result, vec3(0.0));
}

// layer over base by a per-channel fraction (the Khronos renderer's rgb_mix)
vec3 mvr_rgb_mix(vec3 base, vec3 layer, vec3 a)
{
    return (1.0 - max(a.r, max(a.g, a.b))) * base + a * layer;
}
#endif

#ifdef MVR_CLEARCOAT
// KHR_materials_clearcoat's layer for one light: GGX of the coat's
// roughness about the geometry's normal, without Fresnel (the layer is
// blended in by factor x Fresnel(n.v), as the Khronos renderer does).
vec3 mvr_clearcoat_brdf(vec3 n, vec3 v, vec3 l, float alpha)
{
    float n_dot_l = clamp(dot(n, l), 0.0, 1.0);
    if (n_dot_l <= 0.0)
        return vec3(0.0);
    vec3 h = mvr_safe_normalize(l + v, n);
    float n_dot_v = clamp(abs(dot(n, v)), 1e-4, 1.0);
    float n_dot_h = clamp(dot(n, h), 0.0, 1.0);
    return vec3(mvr_d_ggx(n_dot_h, alpha) * mvr_v_smith_ggx_correlated(n_dot_l, n_dot_v, alpha) * n_dot_l);
}
#endif

#ifdef MVR_IBL
// The environment (gl/environment.c): diffuse from third-order spherical
// harmonics of its irradiance (Ramamoorthi and Hanrahan 2001; coefficients
// already convolved and divided by pi, core/environment.c), specular from a
// GGX-prefiltered cube map chain (roughness r at lod r * mvr_env_max_lod) and
// the DFG table (x: NdotV, y: roughness -> scale A, bias B of F0).
uniform vec3 mvr_env_sh[9];
uniform mat3 mvr_env_rotation;   // world direction -> environment direction
uniform float mvr_env_intensity;
uniform float mvr_env_max_lod;   // prefiltered levels - 1
uniform samplerCube mvr_env_specular;
uniform sampler2D mvr_env_dfg;

vec3 mvr_env_diffuse(vec3 e)
{
    // the real SH basis of core/environment.h, in its order
    vec3 c = mvr_env_sh[0] * 0.28209479177387814;
    c += mvr_env_sh[1] * (0.4886025119029199 * e.y);
    c += mvr_env_sh[2] * (0.4886025119029199 * e.z);
    c += mvr_env_sh[3] * (0.4886025119029199 * e.x);
    c += mvr_env_sh[4] * (1.0925484305920792 * e.x * e.y);
    c += mvr_env_sh[5] * (1.0925484305920792 * e.y * e.z);
    c += mvr_env_sh[6] * (0.31539156525252005 * (3.0 * e.z * e.z - 1.0));
    c += mvr_env_sh[7] * (1.0925484305920792 * e.x * e.z);
    c += mvr_env_sh[8] * (0.5462742152960396 * (e.x * e.x - e.y * e.y));
    return max(c, vec3(0.0));
}

// Single- plus multiple-scattering specular albedo of GGX for F0: the
// roughness-dependent Fresnel and energy compensation of Fdez-Aguera, "A
// Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting"
// (JCGT 8(1), 2019), as the Khronos glTF Sample Renderer's getIBLGGXFresnel.
vec3 mvr_ibl_fresnel(float n_dot_v, float roughness, vec3 f0)
{
    vec2 ab = texture(mvr_env_dfg, clamp(vec2(n_dot_v, roughness), 0.0, 1.0)).rg;
    vec3 fr = max(vec3(1.0 - roughness), f0) - f0;
    vec3 k_s = f0 + fr * pow(1.0 - n_dot_v, 5.0);
    vec3 fss_ess = k_s * ab.x + ab.y;
    float ems = 1.0 - (ab.x + ab.y);
    vec3 f_avg = f0 + (1.0 - f0) / 21.0;
    vec3 fms_ems = ems * fss_ess * f_avg / (1.0 - f_avg * ems);
    return fss_ess + fms_ems;
}

#ifdef MVR_SPECULAR
// The same with the specular weight w of KHR_materials_specular (the
// Khronos renderer's getIBLGGXFresnel with specularWeight).
vec3 mvr_ibl_fresnel_weighted(float n_dot_v, float roughness, vec3 f0, float w)
{
    vec2 ab = texture(mvr_env_dfg, clamp(vec2(n_dot_v, roughness), 0.0, 1.0)).rg;
    vec3 fr = max(vec3(1.0 - roughness), f0) - f0;
    vec3 k_s = f0 + fr * pow(1.0 - n_dot_v, 5.0);
    vec3 fss_ess = w * (k_s * ab.x + ab.y);
    float ems = 1.0 - (ab.x + ab.y);
    vec3 f_avg = w * (f0 + (1.0 - f0) / 21.0);
    vec3 fms_ems = ems * fss_ess * f_avg / (1.0 - f_avg * ems);
    return fss_ess + fms_ems;
}
#endif

#ifdef MVR_CLEARCOAT
// The coat's prefiltered radiance along its reflection (blended in by
// factor x Fresnel(n.v) as for the lights).
vec3 mvr_ibl_clearcoat(vec3 n, vec3 v, float roughness)
{
    vec3 r = reflect(-v, n);
    return textureLod(mvr_env_specular, mvr_env_rotation * r, roughness * mvr_env_max_lod).rgb * mvr_env_intensity;
}
#endif

#ifdef MVR_IBL_REFERENCE
// The ground truth of mvr_ibl (mvr render --reference): the environment
// integrated per pixel with mvr_env_samples importance samples each for the
// diffuse (cosine-weighted) and the specular (GGX) lobes of the
// single-scattering BRDF the punctual lights use (mvr_brdf), read from the
// unfiltered source cube map (its level 0: no prefilter, no split sum, no
// spherical harmonics). The multiple-scattering energy mvr_ibl adds
// (Fdez-Aguera 2019) is added here as well, over the sampled cosine-weighted
// radiance, so the two differ only by the approximations being measured.
uniform int mvr_env_samples;

vec3 mvr_ibl(vec3 n, vec3 v, vec3 base, float metallic, float roughness)
{
    float alpha = max(roughness * roughness, 1e-3);
    vec3 up = abs(n.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 t = normalize(cross(up, n));
    vec3 b = cross(n, t);
    vec3 f0 = mix(vec3(0.04), base, metallic);
    float n_dot_v = clamp(abs(dot(n, v)), 1e-4, 1.0);
    vec3 diffuse = vec3(0.0), specular = vec3(0.0), cosine = vec3(0.0);
    for (int i = 0; i < mvr_env_samples; ++i) {
        vec2 xi = mvr_hammersley(i, mvr_env_samples);
        // diffuse: pdf = n.l / pi, so each sample weighs (1 - F) (1 - metallic) base L
        float r = sqrt(xi.y), phi = 2.0 * MVR_PI * xi.x;
        vec3 l = t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(max(1.0 - xi.y, 0.0));
        vec3 h = mvr_safe_normalize(l + v, n);
        vec3 radiance = textureLod(mvr_env_specular, mvr_env_rotation * l, 0.0).rgb;
        vec3 f = f0 + (1.0 - f0) * pow(1.0 - clamp(dot(v, h), 0.0, 1.0), 5.0);
        diffuse += (1.0 - f) * radiance;
        cosine += radiance;
        // specular: pdf(l) = D(h) (n.h) / (4 v.h), so each sample weighs
        // F Vis 4 (v.h) (n.l) / (n.h) L
        vec3 hs = mvr_ggx_half_vector(xi, alpha);
        h = t * hs.x + b * hs.y + n * hs.z;
        float v_dot_h = dot(v, h);
        l = 2.0 * v_dot_h * h - v;
        float n_dot_l = dot(n, l);
        if (n_dot_l > 0.0 && v_dot_h > 0.0) {
            // (v.h may round above 1: pow of a negative base is undefined)
            f = f0 + (1.0 - f0) * pow(clamp(1.0 - v_dot_h, 0.0, 1.0), 5.0);
            float vis = mvr_v_smith_ggx_correlated(n_dot_l, n_dot_v, alpha);
            specular += f * (vis * 4.0 * v_dot_h * n_dot_l / max(hs.z, 1e-6)) *
                        textureLod(mvr_env_specular, mvr_env_rotation * l, 0.0).rgb;
        }
    }
    float inv = 1.0 / float(mvr_env_samples);
    // the multiple-scattering energy: mvr_ibl_fresnel's second term, but over
    // the single-scattering albedo the DFG table integrates (f0 A + B), not
    // over its roughness-dependent Fresnel k_s (an approximation of the maps,
    // which the reference is there to measure)
    vec2 ab = texture(mvr_env_dfg, clamp(vec2(n_dot_v, roughness), 0.0, 1.0)).rg;
    vec3 fss_ess = f0 * ab.x + ab.y;
    float ems = 1.0 - (ab.x + ab.y);
    vec3 f_avg = f0 + (1.0 - f0) / 21.0;
    vec3 ms = ems * fss_ess * f_avg / (1.0 - f_avg * ems);
    return (diffuse * (1.0 - metallic) * base + specular + ms * cosine) * inv * mvr_env_intensity;
}
#else
// Radiance leaving towards v from the environment: Lambertian diffuse under
// a dielectric GGX layer (mixed by its Fresnel albedo) and GGX metal.
vec3 mvr_ibl(vec3 n, vec3 v, vec3 base, float metallic, float roughness)
{
    float n_dot_v = clamp(dot(n, v), 0.0, 1.0);
    vec3 r = reflect(-v, n);
    vec3 diffuse = mvr_env_diffuse(mvr_env_rotation * n) * base;
    vec3 specular = textureLod(mvr_env_specular, mvr_env_rotation * r, roughness * mvr_env_max_lod).rgb;
    vec3 dielectric = mix(diffuse, specular, mvr_ibl_fresnel(n_dot_v, roughness, vec3(0.04)));
    vec3 metal = specular * mvr_ibl_fresnel(n_dot_v, roughness, base);
    return mix(dielectric, metal, metallic) * mvr_env_intensity;
}

#ifdef MVR_SPECULAR
// replace_diffuse: rgb replaces the diffuse lobe by the fraction a (light
// through the surface, KHR_materials_transmission; a = 0: none, exactly)
// irid: the thin film's Fresnel over the dielectric (rgb) and its weight
// (a: 0 = none, exactly); irid_metal: over the metal
vec3 mvr_ibl_specular(vec3 n, vec3 v, vec3 base, float metallic, float roughness, vec3 f0, float w,
                      vec4 replace_diffuse, vec4 irid, vec3 irid_metal)
{
    float n_dot_v = clamp(dot(n, v), 0.0, 1.0);
    vec3 r = reflect(-v, n);
    vec3 diffuse = mvr_env_diffuse(mvr_env_rotation * n) * base;
    diffuse = mix(diffuse, replace_diffuse.rgb, replace_diffuse.a);
    #ifdef MVR_ANISOTROPY
    if (g_aniso_strength > 0.0) {
        // the Khronos renderer's getIBLRadianceAnisotropy: the reflection of
        // a normal bent towards the stretch (more so when smoother)
        vec3 at = cross(g_aniso_b, v);
        vec3 an = cross(at, g_aniso_b);
        float bend = 1.0 - g_aniso_strength * (1.0 - roughness);
        bend *= bend;
        r = reflect(-v, mvr_safe_normalize(mix(an, n, bend * bend), n));
    }
#endif
    vec3 specular = textureLod(mvr_env_specular, mvr_env_rotation * r, roughness * mvr_env_max_lod).rgb;
    vec3 dielectric = mix(diffuse, specular, mvr_ibl_fresnel_weighted(n_dot_v, roughness, f0, w));
    vec3 metal = specular * mvr_ibl_fresnel(n_dot_v, roughness, base);
#ifdef MVR_IRIDESCENCE
    dielectric = mix(dielectric, mvr_rgb_mix(diffuse, specular, irid.rgb), irid.a);
    metal = mix(metal, specular * irid_metal, irid.a);
#endif
    return mix(dielectric, metal, metallic) * mvr_env_intensity;
}
#endif
#endif // MVR_IBL_REFERENCE
#endif

#ifdef MVR_TRANSMISSION
// KHR_materials_transmission and _volume, as the Khronos glTF Sample
// Renderer evaluates them (its getVolumeTransmissionRay, applyIorToRoughness,
// applyVolumeAttenuation, getPunctualRadianceTransmission and
// getIBLVolumeRefraction).

// The ray through the volume: refracted, thickness long in model units
// (thin-walled: thickness 0, no displacement).
vec3 mvr_transmission_ray(vec3 n, vec3 v, float thickness, float ior)
{
    vec3 r = refract(-v, n, 1.0 / ior);
    return mvr_safe_normalize(r, -v) * thickness * v_model_scale;
}

// Rough surfaces blur what they transmit, less so near ior 1.
float mvr_ior_roughness(float roughness, float ior)
{
    return roughness * clamp(ior * 2.0 - 2.0, 0.0, 1.0);
}

// Beer-Lambert through distance d: the attenuation color after distance
// attenuation.w (0: no absorption).
vec3 mvr_volume_attenuation(vec3 radiance, float d, vec4 attenuation)
{
    if (attenuation.w == 0.0)
        return radiance;
    return pow(attenuation.rgb, vec3(d / attenuation.w)) * radiance;
}

// A light seen through the surface: GGX about the light mirrored through
// the surface (the transmission lobe), its Fresnel's complement, the base
// color; no cosine (the Khronos renderer's BTDF).
vec3 mvr_light_transmission(vec3 n, vec3 v, vec3 l, float alpha, vec3 f0, vec3 base, float ior)
{
    float a = mvr_ior_roughness(alpha, ior);
    vec3 l_mirror = mvr_safe_normalize(l + 2.0 * n * dot(-l, n), n);
    vec3 h = mvr_safe_normalize(l_mirror + v, n);
    float d = mvr_d_ggx(clamp(dot(n, h), 0.0, 1.0), a);
    vec3 f = f0 + (1.0 - f0) * pow(1.0 - clamp(dot(v, h), 0.0, 1.0), 5.0);
    float vis = mvr_v_smith_ggx_correlated(clamp(dot(n, l_mirror), 0.0, 1.0), clamp(dot(n, v), 0.0, 1.0), a);
    return (1.0 - f) * base * d * vis;
}

// What the opaque views show where a ray leaving p along ray lands, blurred
// by roughness: the view's own layer of the chunk's copy. Radiance before
// exposure (the copy holds exposed values).
vec3 mvr_transmission_sample(vec3 p, vec3 ray, float roughness, float ior)
{
    vec4 clip = mvr_view_proj[v_view] * vec4(p + ray, 1.0);
    vec2 uv = clip.w != 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : vec2(0.5);
    uv = mvr_transmission_rect.xy + clamp(uv, 0.0, 1.0) * mvr_transmission_rect.zw;
    // the Khronos renderer samples a 1024-wide copy at level 10 x roughness':
    // the same footprint (a fraction 2^(10 (r' - 1)) of the view) at any size
    float lod = max(mvr_transmission_lod + 10.0 * (mvr_ior_roughness(roughness, ior) - 1.0), 0.0);
    vec3 c = textureLod(mvr_transmission_source, vec3(uv, float(v_view - mvr_transmission_base)), lod).rgb;
#ifdef MVR_SRGB_OUTPUT
    c = mvr_srgb_to_linear(c); // an 8-bit UNORM target holds sRGB-encoded values
#endif
    return mvr_exposure > 0.0 ? c / mvr_exposure : c;
}

// The radiance transmitted towards v (the Khronos renderer's
// getIBLVolumeRefraction): along the refracted ray (one per color channel
// with KHR_materials_dispersion), attenuated by the volume, times the
// base color and the complement of the split-sum specular albedo.
vec3 mvr_transmitted(vec3 n, vec3 v, vec3 p, float roughness, vec3 base, vec3 f0, float ior, float thickness,
                     vec4 attenuation, float dispersion)
{
    vec3 light;
    float len;
    if (dispersion > 0.0) {
        // the Abbe spread of the index of refraction (KHR_materials_dispersion)
        float half_spread = (ior - 1.0) * 0.025 * dispersion;
        vec3 iors = vec3(ior - half_spread, ior, ior + half_spread);
        for (int i = 0; i < 3; ++i) {
            vec3 ray = mvr_transmission_ray(n, v, thickness, iors[i]);
            len = length(ray);
            light[i] = mvr_transmission_sample(p, ray, roughness, iors[i])[i];
        }
    } else {
        vec3 ray = mvr_transmission_ray(n, v, thickness, ior);
        len = length(ray);
        light = mvr_transmission_sample(p, ray, roughness, ior);
    }
    light = mvr_volume_attenuation(light, len, attenuation);
#ifdef MVR_IBL
    vec2 ab = texture(mvr_env_dfg, clamp(vec2(clamp(dot(n, v), 0.0, 1.0), roughness), 0.0, 1.0)).rg;
    vec3 albedo = f0 * ab.x + ab.y;
#else
    vec3 albedo = vec3(0.0);
#endif
    return (1.0 - albedo) * light * base;
}
#endif

#ifdef MVR_SHEEN
// KHR_materials_sheen, as the Khronos glTF Sample Renderer evaluates it
// (formulas and sources in core/sheen_lut.c, which evaluates them on the
// CPU): f_sheen = color * D_Charlie * V_sheen, the Charlie distribution of
// Estevez and Kulla 2017 (alpha = sheen roughness^2) and their fitted
// visibility; the layer below scaled by 1 - max(color) * E, E the sheen
// lobe's directional albedo (the table's R; its G is the environment's
// split-sum factor for the Charlie-prefiltered cube map).
uniform sampler2D mvr_sheen_lut; // x: cos theta, y: sheen roughness

float mvr_d_charlie(float roughness, float n_dot_h)
{
    float alpha = max(roughness * roughness, 1e-6);
    float inv = 1.0 / alpha;
    float sin2 = max(1.0 - n_dot_h * n_dot_h, 0.0);
    return (2.0 + inv) * pow(sin2, 0.5 * inv) / (2.0 * MVR_PI);
}

float mvr_sheen_lambda_fit(float x, float alpha)
{
    float t = (1.0 - alpha) * (1.0 - alpha);
    float a = mix(21.5473, 25.3245, t);
    float b = mix(3.82987, 3.32435, t);
    float c = mix(0.19823, 0.16801, t);
    float d = mix(-1.97760, -1.27393, t);
    float e = mix(-4.32054, -4.85967, t);
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}

float mvr_sheen_lambda(float cos_theta, float alpha)
{
    if (abs(cos_theta) < 0.5)
        return exp(mvr_sheen_lambda_fit(cos_theta, alpha));
    return exp(2.0 * mvr_sheen_lambda_fit(0.5, alpha) - mvr_sheen_lambda_fit(1.0 - cos_theta, alpha));
}

float mvr_v_sheen(float n_dot_l, float n_dot_v, float roughness)
{
    float alpha = max(roughness * roughness, 1e-6);
    float s = (1.0 + mvr_sheen_lambda(n_dot_v, alpha) + mvr_sheen_lambda(n_dot_l, alpha)) * (4.0 * n_dot_v * n_dot_l);
    return clamp(1.0 / s, 0.0, 1.0);
}

// The table at (cos theta, sheen roughness): r: E, g: the split-sum factor.
vec2 mvr_sheen_table(float cos_theta, float roughness)
{
    return texture(mvr_sheen_lut, clamp(vec2(cos_theta, roughness), 0.0, 1.0)).rg;
}

// One light: the base layer's radiance `lit` (times n.l) under the sheen.
vec3 mvr_sheen_light(vec3 n, vec3 v, vec3 l, vec3 color, float roughness, vec3 lit)
{
    float n_dot_l = clamp(dot(n, l), 0.0, 1.0);
    if (n_dot_l <= 0.0)
        return lit;
    vec3 h = mvr_safe_normalize(l + v, n);
    float n_dot_v = clamp(abs(dot(n, v)), 1e-4, 1.0);
    float n_dot_h = clamp(dot(n, h), 0.0, 1.0);
    float c = max(max(color.r, color.g), color.b);
    float scale = min(1.0 - c * mvr_sheen_table(n_dot_v, roughness).r, 1.0 - c * mvr_sheen_table(n_dot_l, roughness).r);
    vec3 sheen = color * (mvr_d_charlie(roughness, n_dot_h) * mvr_v_sheen(n_dot_l, n_dot_v, roughness) * n_dot_l);
    return sheen + lit * scale;
}

#ifdef MVR_IBL
uniform samplerCube mvr_env_charlie; // level k: Charlie of sheen roughness k / mvr_env_max_lod
#endif

// The environment (and the uniform ambient): `ambient`, the base layer's,
// under the sheen; the sheen lobe reads the Charlie-prefiltered cube map
// along the reflection (plus the uniform ambient radiance) times the
// table's split-sum factor.
vec3 mvr_sheen_ambient(vec3 n, vec3 v, vec3 color, float roughness, vec3 ambient)
{
    float n_dot_v = clamp(dot(n, v), 0.0, 1.0);
    vec2 e = mvr_sheen_table(n_dot_v, roughness);
    vec3 radiance = mvr_ambient;
#ifdef MVR_IBL
    vec3 r = reflect(-v, n);
    radiance += textureLod(mvr_env_charlie, mvr_env_rotation * r, roughness * mvr_env_max_lod).rgb * mvr_env_intensity;
#endif
    return radiance * color * e.g + ambient * (1.0 - max(max(color.r, color.g), color.b) * e.r);
}
#endif

// KHR_lights_punctual range attenuation: smooth window to zero at range,
// inverse square inside; distance clamped so a light at the surface is finite.
float mvr_range_attenuation(float range, float dist)
{
    float d2 = max(dist * dist, 1e-8);
    if (range <= 0.0)
        return 1.0 / d2;
    float r = clamp(1.0 - pow(dist / range, 4.0), 0.0, 1.0);
    return r * r / d2;
}

#ifdef MVR_SHADOWS
// Fraction of a light reaching p: the first of the light's layers whose map
// holds p (cascades nest from near to far; outside all of them: lit), 3x3
// taps of the GL's bilinear depth comparison (percentage-closer filtering,
// Reeves, Salesin and Cook, SIGGRAPH 1987). The receiver moves along its
// normal by normal-bias texels first (normal offset), so a lit surface does
// not shadow itself; the casters' slope-scaled polygon offset does the rest.
float mvr_shadow(int light, vec3 p, vec3 n_offset, float dist)
{
    ivec4 info = mvr_light_shadow[light];
    for (int k = 0; k < info.y; ++k) {
        int layer = info.x + k;
        vec4 prm = mvr_shadow_params[layer];
        float texel = prm.x * (prm.y > 0.0 ? dist : 1.0);
        vec4 c = mvr_shadow_matrix[layer] * vec4(p + n_offset * (texel * prm.z), 1.0);
        if (!(c.w > 0.0))
            continue;
        vec3 s = c.xyz / c.w;
        float edge = 2.0 * prm.w;
        if (any(lessThan(s.xy, vec2(edge))) || any(greaterThan(s.xy, vec2(1.0 - edge))) ||
            s.z < 0.0 || s.z > 1.0)
            continue;
        float sum = 0.0;
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x)
                sum += texture(mvr_shadow_map, vec4(s.xy + vec2(float(x), float(y)) * prm.w, float(layer), s.z));
        return sum / 9.0;
    }
    return 1.0;
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

#ifdef MVR_OUTPUTS
// The extra outputs of a fragment: its depth along the view's axis and its
// distance to the eye (both from the eye-to-point vector, which is
// interpolated exactly), and the geometry's normal: the interpolated vertex
// normal (the face's where there is none), turned to the viewer on the back of
// a double-sided surface. Normal maps are not applied: the normal describes
// the same surface as the depth.
void mvr_write_outputs()
{
    mat4 view = mvr_view_matrix[v_view];
#ifdef MVR_OUT_GEOMETRY
    vec3 axis = vec3(view[0][2], view[1][2], view[2][2]); // the camera's +Z in the world; it looks along -Z
    o_geometry = vec4(dot(v_to_eye, axis), length(v_to_eye), 1.0, 0.0);
#endif
#ifdef MVR_OUT_NORMAL
    vec3 n = mvr_surface_normal();
#ifdef MVR_OUT_NORMAL_CAMERA
    n = mvr_safe_normalize(mat3(view) * n, n);
#endif
    o_normal = vec4(n, 0.0);
#endif
#ifdef MVR_OUT_IDS
    o_ids = v_ids;
#endif
}
#endif

#ifdef MVR_OUT_ONLY
// The blended draws' outputs pass (after their colour): the front-most
// surface whose alpha reaches the cutoff is recorded (depth test and write);
// nothing is lit, the colour attachment is not a draw buffer.
void main()
{
    mvr_material m = mvr_material_table[v_material];
    float alpha = 1.0;
#ifdef MVR_ALPHA_BLEND
    alpha = mvr_material_alpha(m);
#endif
    if (alpha < mvr_output_alpha_cutoff)
        discard;
    o_color = vec4(0.0);
    mvr_write_outputs();
}
#elif defined(MVR_SHADOW_CASTER)
// The shadow map pass: depth only (the color attachment is masked), with the
// material's alpha test for masked casters.
void main()
{
#ifdef MVR_ALPHA_MASK
    mvr_material m = mvr_material_table[v_material];
    float alpha = mvr_material_alpha(m);
    if (alpha < m.emissive.a)
        discard;
#endif
    o_color = vec4(0.0);
}
#else
void main()
{
    mvr_material m = mvr_material_table[v_material];
    vec4 base = m.base_color_factor;
#ifdef MVR_COLOR0
    base *= v_color0;
#endif
#ifdef MVR_BASE_COLOR_TEX
    base *= MVR_SAMPLE_ROLE(mvr_base_color_tex, MVR_ROLE_BASE_COLOR, m);
#endif

#ifdef MVR_ALPHA_MASK
    if (base.a < m.emissive.a)
        discard;
    base.a = 1.0;
#elif !defined(MVR_ALPHA_BLEND)
    base.a = 1.0;
#endif

#ifdef MVR_UNLIT
    // KHR_materials_unlit: the base color is the result; emissive is ignored.
    o_color = mvr_output(base);
#ifdef MVR_OUTPUTS
    mvr_write_outputs();
#endif
#else
    float metallic = m.params.x;
    float roughness = m.params.y;
#ifdef MVR_METAL_ROUGH_TEX
    vec4 mr = MVR_SAMPLE_ROLE(mvr_metal_rough_tex, MVR_ROLE_METAL_ROUGH, m);
    roughness *= mr.g;
    metallic *= mr.b;
#endif
    metallic = clamp(metallic, 0.0, 1.0);
    roughness = clamp(roughness, 0.0, 1.0);
    float alpha = max(roughness * roughness, 1e-3);

    vec3 n = mvr_surface_normal();
    vec3 n_offset = n;       // shadow receivers move along the surface normal, not the normal map's
#if defined(MVR_NORMAL_TEX) || defined(MVR_CLEARCOAT) || defined(MVR_ANISOTROPY)
    // The tangent frame is the front side's; a back face of a double-sided
    // material takes the whole frame negated (t, b and n), so its relief is
    // the front's seen from behind, as in the Khronos glTF Sample Viewer.
    // (Negating n alone mirrors the map's x: cross() flips b, not t.)
    float side = 1.0;
    vec3 nf = n;
#ifdef MVR_DOUBLE_SIDED
    if (!gl_FrontFacing) {
        side = -1.0;
        nf = -n;
    }
#endif
#endif
#ifdef MVR_CLEARCOAT
    // KHR_materials_clearcoat: the coat's normal is the geometry's, or its
    // own normal map's (in the same tangent frame); its factor and roughness
    // scaled by the R and G of their textures
    vec3 n_coat = n;
    float coat = m.clearcoat.x;
    float coat_roughness = m.clearcoat.y;
    vec2 cuv = mvr_uv(MVR_ROLE_CLEARCOAT_NORMAL, m);
    vec3 ct, cb;
    mvr_tangent_frame(nf, cuv, ct, cb); // derivatives outside the branch
    if (mvr_has_texture(m, MVR_ROLE_CLEARCOAT_NORMAL)) {
        vec3 ctn = MVR_SAMPLE(mvr_clearcoat_normal_tex, cuv, mvr_layer(m, MVR_ROLE_CLEARCOAT_NORMAL)).xyz * 2.0 - 1.0;
        ctn.xy *= m.clearcoat.w;
        n_coat = mvr_safe_normalize(side * (ct * ctn.x + cb * ctn.y + nf * ctn.z), n);
    }
    if (mvr_has_texture(m, MVR_ROLE_CLEARCOAT))
        coat *= MVR_SAMPLE_ROLE(mvr_clearcoat_tex, MVR_ROLE_CLEARCOAT, m).r;
    if (mvr_has_texture(m, MVR_ROLE_CLEARCOAT_ROUGHNESS))
        coat_roughness *= MVR_SAMPLE_ROLE(mvr_clearcoat_roughness_tex, MVR_ROLE_CLEARCOAT_ROUGHNESS, m).g;
    coat = clamp(coat, 0.0, 1.0);
    coat_roughness = clamp(coat_roughness, 0.0, 1.0);
    float coat_alpha = max(coat_roughness * coat_roughness, 1e-3);
#endif
#ifdef MVR_SPECULAR
    // KHR_materials_specular: the weight scaled by its texture's A, the
    // dielectric's F0 tinted by its color texture, then clamped to 1
    vec3 spec_f0 = m.specular.rgb;
    float spec_w = m.specular.a;
    if (mvr_has_texture(m, MVR_ROLE_SPECULAR))
        spec_w *= MVR_SAMPLE_ROLE(mvr_specular_tex, MVR_ROLE_SPECULAR, m).a;
    if (mvr_has_texture(m, MVR_ROLE_SPECULAR_COLOR))
        spec_f0 *= MVR_SAMPLE_ROLE(mvr_specular_color_tex, MVR_ROLE_SPECULAR_COLOR, m).rgb;
#ifdef MVR_SPEC_GLOSS
    // KHR_materials_pbrSpecularGlossiness, as the Khronos glTF Sample
    // Renderer reads it: the specular color is the dielectric's F0 (weight
    // 1), roughness is 1 - glossiness, each scaled by the texture's RGB / A;
    // there is no metal (params.x is 0) and base is the diffuse color
    float gloss = m.params.y;
    if (mvr_has_texture(m, MVR_ROLE_SPEC_GLOSS)) {
        vec4 sg = MVR_SAMPLE_ROLE(mvr_spec_gloss_tex, MVR_ROLE_SPEC_GLOSS, m);
        gloss *= sg.a;
        spec_f0 *= sg.rgb;
    }
    roughness = clamp(1.0 - gloss, 0.0, 1.0);
    alpha = max(roughness * roughness, 1e-3);
#endif
    spec_f0 = min(spec_f0, vec3(1.0));
#endif
#ifdef MVR_TRANSMISSION
    // KHR_materials_transmission: the fraction (x its texture's R) of the
    // dielectric's diffuse lobe replaced by light through the surface;
    // KHR_materials_volume: the thickness (x its texture's G) and absorption
    float transmission = m.transmission.x;
    if (mvr_has_texture(m, MVR_ROLE_TRANSMISSION))
        transmission *= MVR_SAMPLE_ROLE(mvr_transmission_tex, MVR_ROLE_TRANSMISSION, m).r;
    transmission = clamp(transmission, 0.0, 1.0);
    float thickness = m.transmission.y;
    if (mvr_has_texture(m, MVR_ROLE_THICKNESS))
        thickness *= MVR_SAMPLE_ROLE(mvr_thickness_tex, MVR_ROLE_THICKNESS, m).g;
    vec4 absorption = vec4(m.volume.rgb, m.transmission.z); // KHR_materials_volume: color, distance
    float ior = m.volume.a;
#endif
#ifdef MVR_SHEEN
    // KHR_materials_sheen: the color scaled by its texture's RGB (sRGB),
    // the roughness by its texture's A
    vec3 sheen_color = m.sheen.rgb;
    float sheen_roughness = m.sheen.a;
    if (mvr_has_texture(m, MVR_ROLE_SHEEN_COLOR))
        sheen_color *= MVR_SAMPLE_ROLE(mvr_sheen_color_tex, MVR_ROLE_SHEEN_COLOR, m).rgb;
    if (mvr_has_texture(m, MVR_ROLE_SHEEN_ROUGHNESS))
        sheen_roughness *= MVR_SAMPLE_ROLE(mvr_sheen_roughness_tex, MVR_ROLE_SHEEN_ROUGHNESS, m).a;
    sheen_color = clamp(sheen_color, 0.0, 1.0);
    sheen_roughness = clamp(sheen_roughness, 0.0, 1.0);
#endif

#ifdef MVR_NORMAL_TEX
    vec2 nuv = mvr_uv(MVR_ROLE_NORMAL, m);
    vec3 t, b;
    mvr_tangent_frame(nf, nuv, t, b);
    vec3 tn = MVR_SAMPLE(mvr_normal_tex, nuv, mvr_layer(m, MVR_ROLE_NORMAL)).xyz * 2.0 - 1.0;
    tn.xy *= m.params.z;
    n = mvr_safe_normalize(side * (t * tn.x + b * tn.y + nf * tn.z), n);
#endif
#ifdef MVR_ANISOTROPY
    // KHR_materials_anisotropy, as the Khronos Sample Renderer reads it: the
    // direction (1, 0), or the texture's RG mapped to [-1, 1], rotated by the
    // material's rotation, in the tangent frame (any frame about the normal
    // without tangents or usable coordinates); strength x the texture's B
    {
        vec2 auv = mvr_uv(MVR_ROLE_ANISOTROPY, m);
        vec3 at, ab;
        mvr_tangent_frame(nf, auv, at, ab);
        if (dot(at, at) == 0.0) {
            vec3 up = abs(nf.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
            at = normalize(cross(up, nf));
            ab = cross(nf, at);
        }
        vec2 dir = vec2(1.0, 0.0);
        float strength = m.anisotropy.x;
        if (mvr_has_texture(m, MVR_ROLE_ANISOTROPY)) {
            vec3 a = MVR_SAMPLE(mvr_anisotropy_tex, auv, mvr_layer(m, MVR_ROLE_ANISOTROPY)).rgb;
            dir = a.xy * 2.0 - 1.0;
            strength *= a.z;
        }
        dir = vec2(m.anisotropy.y * dir.x - m.anisotropy.z * dir.y, m.anisotropy.z * dir.x + m.anisotropy.y * dir.y);
        g_aniso_t = mvr_safe_normalize(side * (at * dir.x + ab * dir.y), at);
        g_aniso_b = mvr_safe_normalize(cross(n_offset, g_aniso_t), ab);
        g_aniso_strength = clamp(strength, 0.0, 1.0);
    }
#endif

    vec3 v = mvr_safe_normalize(v_to_eye, n);
    vec3 color = vec3(0.0);
#ifdef MVR_IRIDESCENCE
    // KHR_materials_iridescence: the film's weight (x its texture's R) and
    // thickness (between the minimum and maximum by its texture's G, else the
    // maximum; 0 nm is no film), its Fresnel at n.v over the dielectric's F0
    // and over the metal's (the base color)
    float irid_factor = m.iridescence.x;
    if (mvr_has_texture(m, MVR_ROLE_IRIDESCENCE))
        irid_factor *= MVR_SAMPLE_ROLE(mvr_iridescence_tex, MVR_ROLE_IRIDESCENCE, m).r;
    float irid_nm = m.iridescence.w;
    if (mvr_has_texture(m, MVR_ROLE_IRIDESCENCE_THICKNESS))
        irid_nm = mix(m.iridescence.z, m.iridescence.w,
                      MVR_SAMPLE_ROLE(mvr_iridescence_thickness_tex, MVR_ROLE_IRIDESCENCE_THICKNESS, m).g);
    irid_factor = irid_nm == 0.0 ? 0.0 : clamp(irid_factor, 0.0, 1.0);
    float irid_nv = clamp(dot(n, v), 0.0, 1.0);
    vec3 irid_d = mvr_iridescence_fresnel(m.iridescence.y, irid_nv, irid_nm, spec_f0);
    vec3 irid_m = mvr_iridescence_fresnel(m.iridescence.y, irid_nv, irid_nm, base.rgb);
#endif
#ifdef MVR_CLEARCOAT
    // the coat's Fresnel at n.v: how much of what lies under it shows
    float cf = m.clearcoat.z + (1.0 - m.clearcoat.z) * pow(1.0 - clamp(dot(n_coat, v), 0.0, 1.0), 5.0);
    float coat_mix = coat * cf;
#endif
#if MVR_LIGHT_COUNT > 0
#ifdef MVR_LIGHT_MASKS
    int light_mask = mvr_view_info[v_view].x;
#endif
    for (int i = 0; i < MVR_LIGHT_COUNT; ++i) {
#ifdef MVR_LIGHT_MASKS
        if (((light_mask >> i) & 1) == 0)
            continue; // masked out of this view: contributes nothing
#endif
        mvr_light light = mvr_light_list[i];
        vec3 l;
        float attenuation = 1.0;
        float dist = 0.0;
        if (i < MVR_DIRECTIONAL_LIGHTS) {
            l = -light.direction.xyz;
        } else {
            vec3 to_light = light.position_range.xyz - v_position;
            dist = length(to_light);
            l = mvr_safe_normalize(to_light, n);
            attenuation = mvr_range_attenuation(light.position_range.w, dist);
            if (i >= MVR_DIRECTIONAL_LIGHTS + MVR_POINT_LIGHTS) {
                float cd = dot(light.direction.xyz, -l);
                float s = clamp(cd * light.spot.x + light.spot.y, 0.0, 1.0);
                attenuation *= s * s;
            }
        }
#ifdef MVR_SHADOWS
        if (attenuation > 0.0)
            attenuation *= mvr_shadow(i, v_position, n_offset, dist);
#endif
#ifdef MVR_SPECULAR
        vec3 lit = mvr_brdf_specular(n, v, l, base.rgb, metallic, alpha, spec_f0, spec_w);
#ifdef MVR_TRANSMISSION
        if (transmission > 0.0) {
            // the dielectric's diffuse part (1 - F) base / pi n.l becomes
            // mix(it, light through the surface toward the light's exit point, transmission)
            vec3 tray = mvr_transmission_ray(n, v, thickness, ior);
            vec3 lt = mvr_safe_normalize(l * (i < MVR_DIRECTIONAL_LIGHTS ? 1.0 : dist) - tray, l);
            vec3 through = mvr_volume_attenuation(mvr_light_transmission(n, v, lt, alpha, spec_f0, base.rgb, ior),
                                                  length(tray), absorption);
            vec3 h = mvr_safe_normalize(l + v, n);
            float x5 = pow(1.0 - clamp(dot(v, h), 0.0, 1.0), 5.0);
            vec3 f_dielectric = spec_f0 * spec_w + (spec_w - spec_f0 * spec_w) * x5;
            vec3 diffuse = base.rgb / MVR_PI * clamp(dot(n, l), 0.0, 1.0);
            lit += (1.0 - metallic) * (1.0 - f_dielectric) * transmission * (through - diffuse);
        }
#endif
#ifdef MVR_IRIDESCENCE
        if (irid_factor > 0.0) {
            // the film's Fresnel in place of Schlick's, over the dielectric
            // (its diffuse under the film's brightest channel) and the metal
            float n_dot_l = clamp(dot(n, l), 0.0, 1.0);
            vec3 h = mvr_safe_normalize(l + v, n);
            float ggx = mvr_specular_lobe(n, v, l, h, alpha, n_dot_l, clamp(abs(dot(n, v)), 1e-4, 1.0),
                                          clamp(dot(n, h), 0.0, 1.0));
            vec3 dielectric = mvr_rgb_mix(base.rgb / MVR_PI, vec3(ggx), irid_d);
            lit = mix(lit, mix(dielectric, ggx * irid_m, metallic) * n_dot_l, irid_factor);
        }
#endif
#else
        vec3 lit = mvr_brdf(n, v, l, base.rgb, metallic, alpha);
#endif
#ifdef MVR_SHEEN
        lit = mvr_sheen_light(n, v, l, sheen_color, sheen_roughness, lit);
#endif
#ifdef MVR_CLEARCOAT
        lit = mix(lit, mvr_clearcoat_brdf(n_coat, v, l, coat_alpha), coat_mix);
#endif
        color += light.color.rgb * attenuation * lit;
    }
#endif
    float ao = 1.0;
#ifdef MVR_OCCLUSION_TEX
    ao = 1.0 + m.params.w * (MVR_SAMPLE_ROLE(mvr_occlusion_tex, MVR_ROLE_OCCLUSION, m).r - 1.0);
#endif
    vec3 ambient = mvr_ambient * base.rgb;
#ifdef MVR_TRANSMISSION
    // what the surface lets through from behind, towards the eye
    vec3 transmitted = transmission > 0.0 ? mvr_transmitted(n, v, v_position, roughness, base.rgb, spec_f0, ior,
                                                            thickness, absorption, m.transmission.w)
                                          : vec3(0.0);
#ifndef MVR_IBL
    // a uniform ambient only: its diffuse part gives way to it
    ambient = mix(ambient, transmitted, transmission * (1.0 - metallic));
#endif
#endif
#ifdef MVR_IBL
#if defined(MVR_SPECULAR) && !defined(MVR_IBL_REFERENCE)
    vec4 replace_diffuse = vec4(0.0);
#ifdef MVR_TRANSMISSION
    replace_diffuse = vec4(transmitted, transmission);
#endif
    vec4 irid = vec4(0.0);
    vec3 irid_metal = vec3(0.0);
#ifdef MVR_IRIDESCENCE
    irid = vec4(irid_d, irid_factor);
    irid_metal = irid_m;
#endif
    ambient += mvr_ibl_specular(n, v, base.rgb, metallic, roughness, spec_f0, spec_w, replace_diffuse, irid, irid_metal);
#else
    ambient += mvr_ibl(n, v, base.rgb, metallic, roughness);
#endif
#ifdef MVR_SHEEN
    // the sheen over the base, under the coat
    ambient = mvr_sheen_ambient(n, v, sheen_color, sheen_roughness, ambient);
#endif
#if defined(MVR_CLEARCOAT) && !defined(MVR_IBL_REFERENCE)
    ambient = mix(ambient, mvr_ibl_clearcoat(n_coat, v, coat_roughness), coat_mix);
#endif
#endif
#if defined(MVR_SHEEN) && !defined(MVR_IBL)
    ambient = mvr_sheen_ambient(n, v, sheen_color, sheen_roughness, ambient);
#endif
    color += ambient * ao;
    vec3 emissive = m.emissive.rgb;
#ifdef MVR_EMISSIVE_TEX
    emissive *= MVR_SAMPLE_ROLE(mvr_emissive_tex, MVR_ROLE_EMISSIVE, m).rgb;
#endif
#ifdef MVR_CLEARCOAT
    emissive *= 1.0 - coat_mix; // under the coat
#endif
    o_color = mvr_output(vec4(color + emissive, base.a));
#ifdef MVR_OUTPUTS
    mvr_write_outputs();
#endif
#endif
}
#endif // MVR_SHADOW_CASTER
