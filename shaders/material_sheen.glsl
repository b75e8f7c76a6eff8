// material_sheen.glsl: KHR_materials_sheen.

#ifdef MVR_SHEEN
uniform MVR_SAMPLER mvr_sheen_color_tex;
uniform MVR_SAMPLER mvr_sheen_roughness_tex;

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
