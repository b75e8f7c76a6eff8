// material_clearcoat.glsl: KHR_materials_clearcoat.

#ifdef MVR_CLEARCOAT
uniform MVR_SAMPLER mvr_clearcoat_tex;
uniform MVR_SAMPLER mvr_clearcoat_roughness_tex;
uniform MVR_SAMPLER mvr_clearcoat_normal_tex;

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
