// ibl.glsl: image-based lighting from a prefiltered environment (the
// split-sum approximation), and its per-pixel reference (MVR_IBL_REFERENCE).

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

// What the split-sum Fresnel of one pixel shares between its lobes (the
// dielectric's and the metal's): the DFG table's scale and bias at (n.v,
// roughness), one fetch, and Schlick's (1 - n.v)^5.
struct mvr_dfg {
    vec2 ab;
    float x5;
};

mvr_dfg mvr_dfg_at(float n_dot_v, float roughness)
{
    return mvr_dfg(texture(mvr_env_dfg, clamp(vec2(n_dot_v, roughness), 0.0, 1.0)).rg, mvr_pow5(1.0 - n_dot_v));
}

// Single- plus multiple-scattering specular albedo of GGX for F0: the
// roughness-dependent Fresnel and energy compensation of Fdez-Aguera, "A
// Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting"
// (JCGT 8(1), 2019), as the Khronos glTF Sample Renderer's getIBLGGXFresnel.
vec3 mvr_ibl_fresnel(mvr_dfg g, float roughness, vec3 f0)
{
    vec3 fr = max(vec3(1.0 - roughness), f0) - f0;
    vec3 k_s = f0 + fr * g.x5;
    vec3 fss_ess = k_s * g.ab.x + g.ab.y;
    float ems = 1.0 - (g.ab.x + g.ab.y);
    vec3 f_avg = f0 + (1.0 - f0) * (1.0 / 21.0);
    vec3 fms_ems = ems * fss_ess * f_avg / (1.0 - f_avg * ems);
    return fss_ess + fms_ems;
}

#ifdef MVR_SPECULAR
// The same with the specular weight w of KHR_materials_specular (the
// Khronos renderer's getIBLGGXFresnel with specularWeight).
vec3 mvr_ibl_fresnel_weighted(mvr_dfg g, float roughness, vec3 f0, float w)
{
    vec3 fr = max(vec3(1.0 - roughness), f0) - f0;
    vec3 k_s = f0 + fr * g.x5;
    vec3 fss_ess = w * (k_s * g.ab.x + g.ab.y);
    float ems = 1.0 - (g.ab.x + g.ab.y);
    vec3 f_avg = w * (f0 + (1.0 - f0) * (1.0 / 21.0));
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
        vec3 f = f0 + (1.0 - f0) * mvr_pow5(1.0 - clamp(dot(v, h), 0.0, 1.0));
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
            f = f0 + (1.0 - f0) * mvr_pow5(clamp(1.0 - v_dot_h, 0.0, 1.0));
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
    mvr_dfg g = mvr_dfg_at(n_dot_v, roughness);
    vec3 dielectric = mix(diffuse, specular, mvr_ibl_fresnel(g, roughness, vec3(0.04)));
    vec3 metal = specular * mvr_ibl_fresnel(g, roughness, base);
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
    mvr_dfg g = mvr_dfg_at(n_dot_v, roughness);
    vec3 dielectric = mix(diffuse, specular, mvr_ibl_fresnel_weighted(g, roughness, f0, w));
    vec3 metal = specular * mvr_ibl_fresnel(g, roughness, base);
#ifdef MVR_IRIDESCENCE
    dielectric = mix(dielectric, mvr_rgb_mix(diffuse, specular, irid.rgb), irid.a);
    metal = mix(metal, specular * irid_metal, irid.a);
#endif
    return mix(dielectric, metal, metallic) * mvr_env_intensity;
}
#endif
#endif // MVR_IBL_REFERENCE
#endif
