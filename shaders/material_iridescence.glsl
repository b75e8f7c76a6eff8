// material_iridescence.glsl: KHR_materials_iridescence.

#ifdef MVR_IRIDESCENCE
uniform MVR_SAMPLER mvr_iridescence_tex;
uniform MVR_SAMPLER mvr_iridescence_thickness_tex;

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
