// mesh.frag.glsl: glTF 2.0 metallic-roughness (Appendix B of the glTF 2.0
// specification: Lambertian diffuse, GGX / Trowbridge-Reitz distribution,
// height-correlated Smith visibility, Schlick Fresnel) with KHR_lights_punctual
// lights, and image-based lighting from a prefiltered environment (the
// split-sum approximation, Karis 2013, as the Khronos glTF Sample Renderer
// applies it). Everything this stage reads is constant across a pass: the material
// table and the lights are whole uniform blocks, the draw picks its material
// through a flat varying.
//
// This file keeps the main flow; the generator (core/shader_gen.c) puts in
// front of it, in this order: surface.glsl (material table, varyings),
// lights.glsl, shadows.glsl, brdf.glsl, the material extensions
// (material_anisotropy, _specular, _iridescence, _clearcoat), ibl.glsl,
// material_transmission.glsl and material_sheen.glsl.

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
    mvr_material m = mvr_material_fetch();
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
    mvr_material m = mvr_material_fetch();
    float alpha = mvr_material_alpha(m);
    if (alpha < m.emissive.a)
        discard;
#endif
    o_color = vec4(0.0);
}
#else
void main()
{
    mvr_material m = mvr_material_fetch();
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
    float cf = m.clearcoat.z + (1.0 - m.clearcoat.z) * mvr_pow5(1.0 - clamp(dot(n_coat, v), 0.0, 1.0));
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
            float x5 = mvr_pow5(1.0 - clamp(dot(v, h), 0.0, 1.0));
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
#ifdef MVR_METAL_ROUGH_TEX
    // occlusion in the metallic-roughness texture's red channel, fetched
    // alike (core/material.h, mvr_material_occlusion_in_metal_rough): the
    // fetch above serves both (on the array path a program may also sample
    // this material's white occlusion layer; this value replaces it)
    if (((m.uv.w >> MVR_OCCLUSION_IN_METAL_ROUGH_BIT) & 1) != 0)
        ao = 1.0 + m.params.w * (mr.r - 1.0);
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
