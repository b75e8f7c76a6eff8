// material_transmission.glsl: KHR_materials_transmission, _volume and
// _dispersion.

#ifdef MVR_TRANSMISSION
uniform MVR_SAMPLER mvr_transmission_tex;
uniform MVR_SAMPLER mvr_thickness_tex;
// What the opaque sub-passes drew, per view of the chunk (layer = view -
// mvr_transmission_base), mip-mapped (gl/transmission.c)
uniform sampler2DArray mvr_transmission_source;
uniform int mvr_transmission_base;
uniform vec4 mvr_transmission_rect; // the chunk's viewport in the array: offset, size (0..1)
uniform float mvr_transmission_lod; // log2 of the viewport's width in texels

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
    vec3 f = f0 + (1.0 - f0) * mvr_pow5(1.0 - clamp(dot(v, h), 0.0, 1.0));
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
