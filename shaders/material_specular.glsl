// material_specular.glsl: KHR_materials_ior and _specular (and the
// dielectric code that transmission, spec-gloss, iridescence and
// anisotropy draw with).

// Transmission and spec-gloss are drawn by the specular extension's
// dielectric code (core/material.c sets SPECULAR with them; a variant asked
// for without it compiles that code all the same).
#if (defined(MVR_TRANSMISSION) || defined(MVR_SPEC_GLOSS) || defined(MVR_IRIDESCENCE) || defined(MVR_ANISOTROPY)) && \
    !defined(MVR_SPECULAR)
#define MVR_SPECULAR
#endif

#ifdef MVR_SPECULAR
uniform MVR_SAMPLER mvr_specular_tex;
uniform MVR_SAMPLER mvr_specular_color_tex;
#endif
#ifdef MVR_SPEC_GLOSS
uniform MVR_SAMPLER mvr_spec_gloss_tex;
#endif

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
    float x5 = mvr_pow5(1.0 - v_dot_h);
    vec3 f_dielectric = f0 * w + (w - f0 * w) * x5;
    vec3 f_metal = base + (1.0 - base) * x5;
    vec3 diffuse = (1.0 - f_dielectric) * base / MVR_PI;
    float ggx = mvr_specular_lobe(n, v, l, h, alpha, n_dot_l, n_dot_v, n_dot_h);
    vec3 dielectric = diffuse + f_dielectric * ggx;
    return mix(dielectric, f_metal * ggx, metallic) * n_dot_l;
}
#endif
