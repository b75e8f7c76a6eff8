// material_anisotropy.glsl: KHR_materials_anisotropy's state of a fragment
// (main sets it; the specular lobes of material_specular.glsl and ibl.glsl
// read it).

#ifdef MVR_ANISOTROPY
uniform MVR_SAMPLER mvr_anisotropy_tex;
// KHR_materials_anisotropy of this fragment (set in main, read by the
// specular lobes): the direction of stretch and its bitangent, the strength
vec3 g_aniso_t = vec3(1.0, 0.0, 0.0);
vec3 g_aniso_b = vec3(0.0, 1.0, 0.0);
float g_aniso_strength = 0.0;
#endif
