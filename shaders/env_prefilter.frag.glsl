// env_prefilter.frag.glsl: one level of a cube map from the environment.
// Without MVR_ENV_GGX: the source cube map's level 0 from the
// equirectangular image. With it: the specular prefilter of one roughness,
// the split sum's first factor (Karis 2013, "Real Shading in Unreal Engine
// 4"), with v = n = r, GGX importance sampling and filtered importance
// sampling (Colbert and Krivanek, GPU Gems 3, ch. 20: each sample reads the
// source level whose texel solid angle matches the sample's, so few samples
// give no fireflies). With MVR_ENV_CHARLIE (KHR_materials_sheen, built only
// for a scene with sheen): the same prefilter for the sheen lobe, the
// Charlie distribution of Estevez and Kulla 2017 instead of GGX.
uniform float mvr_face_size;     // texels per side of the level drawn

#if defined(MVR_ENV_GGX) || defined(MVR_ENV_CHARLIE)
uniform samplerCube mvr_env_source;
uniform float mvr_roughness;
uniform int mvr_samples;
uniform float mvr_source_size;   // texels per side of the source's level 0
uniform float mvr_source_max_lod;
#else
uniform sampler2D mvr_env_equirect;
uniform float mvr_equirect_lod;  // the image level whose texels match a face texel
#endif

flat in int v_face;
layout(location = 0) out vec4 o_color;

#ifdef MVR_ENV_GGX
vec3 mvr_prefilter_ggx(vec3 n)
{
    // the level of the source whose texels match this level's
    float base_lod = max(log2(mvr_source_size / mvr_face_size), 0.0);
    if (mvr_roughness <= 0.0)
        return textureLod(mvr_env_source, n, base_lod).rgb;
    float alpha = mvr_roughness * mvr_roughness;
    vec3 up = abs(n.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 t = normalize(cross(up, n));
    vec3 b = cross(n, t);
    // solid angle of a source texel at level 0 (the average over the cube)
    float omega_p = 4.0 * MVR_PI / (6.0 * mvr_source_size * mvr_source_size);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int i = 0; i < mvr_samples; ++i) {
        vec3 ht = mvr_ggx_half_vector(mvr_hammersley(i, mvr_samples), alpha);
        vec3 h = t * ht.x + b * ht.y + n * ht.z;
        vec3 l = 2.0 * dot(n, h) * h - n;
        float n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0)
            continue;
        // v = n: pdf(l) = D(h) cos(theta_h) / (4 v.h) = D(h) / 4
        float pdf = mvr_d_ggx(ht.z, alpha) * 0.25;
        float omega_s = 1.0 / (float(mvr_samples) * pdf + 1e-8);
        // + 1: the bias Colbert and Krivanek recommend (a smoother result)
        float lod = clamp(0.5 * log2(omega_s / omega_p) + 1.0, base_lod, mvr_source_max_lod);
        sum += textureLod(mvr_env_source, l, lod).rgb * n_dot_l;
        weight += n_dot_l;
    }
    return weight > 0.0 ? sum / weight : vec3(0.0);
}
#endif

#ifdef MVR_ENV_CHARLIE
// The sheen lobe's prefilter of one sheen roughness r (alpha = r^2), as the
// Khronos glTF Sample Renderer builds its Charlie cube chain: v = n,
// half vectors h sampled with pdf D(h) (n.h) of the Charlie distribution
// D = (2 + 1/alpha) sin^(1/alpha)(theta_h) / (2 pi): its inverse CDF in
// s = sin(theta_h) is s = xi^(alpha / (2 alpha + 1)); l = reflect(-n, h),
// weighted by n.l, and filtered importance sampling as for GGX (pdf(l) =
// D(h) / 4 at v = n). Roughness 0 has no lobe: black, as theirs.
vec3 mvr_prefilter_charlie(vec3 n)
{
    float alpha = max(mvr_roughness * mvr_roughness, 1e-4);
    float base_lod = max(log2(mvr_source_size / mvr_face_size), 0.0);
    vec3 up = abs(n.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 t = normalize(cross(up, n));
    vec3 b = cross(n, t);
    float omega_p = 4.0 * MVR_PI / (6.0 * mvr_source_size * mvr_source_size);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int i = 0; i < mvr_samples; ++i) {
        vec2 xi = mvr_hammersley(i, mvr_samples);
        float sin_h = pow(xi.y, alpha / (2.0 * alpha + 1.0));
        float cos_h = sqrt(max(1.0 - sin_h * sin_h, 0.0));
        float phi = 2.0 * MVR_PI * xi.x;
        vec3 h = t * (sin_h * cos(phi)) + b * (sin_h * sin(phi)) + n * cos_h;
        vec3 l = 2.0 * dot(n, h) * h - n;
        float n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0)
            continue;
        float d = (2.0 + 1.0 / alpha) * pow(sin_h, 1.0 / alpha) / (2.0 * MVR_PI);
        float omega_s = 1.0 / (float(mvr_samples) * d * 0.25 + 1e-8);
        float lod = clamp(0.5 * log2(omega_s / omega_p) + 1.0, base_lod, mvr_source_max_lod);
        sum += textureLod(mvr_env_source, l, lod).rgb * n_dot_l;
        weight += n_dot_l;
    }
    return weight > 0.0 ? sum / weight : vec3(0.0);
}
#endif

void main()
{
    vec2 st = gl_FragCoord.xy / mvr_face_size * 2.0 - 1.0;
    vec3 d = normalize(mvr_cube_direction(v_face, st));
#if defined(MVR_ENV_CHARLIE)
    o_color = vec4(mvr_prefilter_charlie(d), 1.0);
#elif defined(MVR_ENV_GGX)
    o_color = vec4(mvr_prefilter_ggx(d), 1.0);
#else
    o_color = vec4(textureLod(mvr_env_equirect, mvr_equirect_uv(d), mvr_equirect_lod).rgb, 1.0);
#endif
}
