// brdf.glsl: the glTF 2.0 metallic-roughness BRDF of one light (Appendix B
// of the glTF 2.0 specification) and the visibility term its layers share.

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
    vec3 f = f0 + (1.0 - f0) * mvr_pow5(1.0 - v_dot_h);
    vec3 diffuse = (1.0 - f) * (1.0 - metallic) * base / MVR_PI;
    vec3 specular = f * mvr_d_ggx(n_dot_h, alpha) * mvr_v_smith_ggx_correlated(n_dot_l, n_dot_v, alpha);
    return (diffuse + specular) * n_dot_l;
}
