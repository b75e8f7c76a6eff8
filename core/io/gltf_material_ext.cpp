// The PBR material extensions of glTF (their factors and textures, as their
// ratified specifications define them): KHR_materials_ior, _specular,
// _clearcoat, _sheen, _transmission, _volume, _dispersion, _iridescence,
// _anisotropy and the archived KHR_materials_pbrSpecularGlossiness. Values
// out of range are the scene's to repair (and count); malformed JSON (a
// texture without an index, a color of the wrong length) refuses the file,
// naming the material and the field.
#include <cmath>
#include <cstring>

#include "gltf_convert.hpp"

namespace mvr_gltf {

namespace {

// A glTF integer index (a non-negative whole number).
bool is_index(const tinygltf::Value &v)
{
    if (!v.IsNumber())
        return false;
    double d = v.GetNumberAsDouble();
    return d >= 0 && d <= double(INT32_MAX) && d == std::floor(d);
}

}  // namespace

mvr_texture_ref converter::texture_value(const tinygltf::Value &ext, const char *key, const std::string &what,
                                         float *scale)
{
    mvr_texture_ref none;
    std::memset(&none, 0, sizeof none);
    if (!ext.IsObject() || !ext.Has(key))
        return none;
    std::string w = what + "." + key;
    const tinygltf::Value &v = ext.Get(key);
    if (!v.IsObject())
        refuse(w + " is not an object");
    if (!v.Has("index") || !is_index(v.Get("index")))
        refuse(w + ".index is missing or not a valid index");
    int texcoord = 0;
    if (v.Has("texCoord")) {
        if (!is_index(v.Get("texCoord")))
            refuse(w + ".texCoord is not a valid set index");
        texcoord = int(v.Get("texCoord").GetNumberAsDouble());
    }
    if (scale)
        *scale = float(number(v, "scale", 1.0));
    tinygltf::ExtensionMap extensions;
    if (v.Has("extensions") && v.Get("extensions").IsObject()) {
        const tinygltf::Value &e = v.Get("extensions");
        for (const std::string &k : e.Keys())
            extensions[k] = e.Get(k);
    }
    return texture_ref(int(v.Get("index").GetNumberAsDouble()), texcoord, extensions, w);
}

// n numbers of ext.key into out (absent: out unchanged).
static void numbers(const tinygltf::Value &ext, const char *key, float *out, int n,
                    const std::string &what)
{
    if (!ext.Has(key))
        return;
    const tinygltf::Value &v = ext.Get(key);
    std::string w = what + "." + key;
    if (!v.IsArray() || v.ArrayLen() != size_t(n))
        refuse(w + " is not an array of " + std::to_string(n) + " numbers");
    for (int i = 0; i < n; ++i) {
        if (!v.Get(i).IsNumber())
            refuse(w + "[" + std::to_string(i) + "] is not a number");
        out[i] = float(v.Get(i).GetNumberAsDouble());
    }
}

void converter::pbr_extensions(const tinygltf::Material &g, const std::string &w, mvr_material_desc &d)
{
    auto find = [&](const char *name, std::string &ew) -> const tinygltf::Value * {
        auto it = g.extensions.find(name);
        if (it == g.extensions.end())
            return nullptr;
        ew = w + ".extensions." + name;
        if (!it->second.IsObject())
            refuse(ew + " is not an object");
        return &it->second;
    };
    std::string ew;
    if (const tinygltf::Value *e = find("KHR_materials_ior", ew)) {
        d.ior = float(number(*e, "ior", 1.5));
        if (d.ior == 0.0f)
            d.ior = 1.0f; /* the extension's 0 is no reflection at normal incidence (as 1); 0 means "default" here */
    }
    if (const tinygltf::Value *e = find("KHR_materials_specular", ew)) {
        d.specular.enabled = true;
        d.specular.factor = float(number(*e, "specularFactor", 1.0));
        for (float &c : d.specular.color_factor)
            c = 1.0f;
        numbers(*e, "specularColorFactor", d.specular.color_factor, 3, ew);
        d.specular.texture = texture_value(*e, "specularTexture", ew);
        d.specular.color_texture = texture_value(*e, "specularColorTexture", ew);
    }
    if (const tinygltf::Value *e = find("KHR_materials_clearcoat", ew)) {
        d.clearcoat.factor = float(number(*e, "clearcoatFactor", 0.0));
        d.clearcoat.roughness_factor = float(number(*e, "clearcoatRoughnessFactor", 0.0));
        d.clearcoat.texture = texture_value(*e, "clearcoatTexture", ew);
        d.clearcoat.roughness_texture = texture_value(*e, "clearcoatRoughnessTexture", ew);
        d.clearcoat.normal_texture = texture_value(*e, "clearcoatNormalTexture", ew, &d.clearcoat.normal_scale);
        if (d.clearcoat.normal_scale == 0.0f)
            d.clearcoat.normal_scale = 1e-30f; /* a scale of 0 is valid glTF (a flat coat); 0 means "default" in mvr */
    }
    if (const tinygltf::Value *e = find("KHR_materials_sheen", ew)) {
        numbers(*e, "sheenColorFactor", d.sheen.color_factor, 3, ew);
        d.sheen.roughness_factor = float(number(*e, "sheenRoughnessFactor", 0.0));
        d.sheen.color_texture = texture_value(*e, "sheenColorTexture", ew);
        d.sheen.roughness_texture = texture_value(*e, "sheenRoughnessTexture", ew);
    }
    if (const tinygltf::Value *e = find("KHR_materials_transmission", ew)) {
        d.transmission.factor = float(number(*e, "transmissionFactor", 0.0));
        d.transmission.texture = texture_value(*e, "transmissionTexture", ew);
    }
    if (const tinygltf::Value *e = find("KHR_materials_volume", ew)) {
        d.volume.thickness_factor = float(number(*e, "thicknessFactor", 0.0));
        d.volume.thickness_texture = texture_value(*e, "thicknessTexture", ew);
        /* the extension's default is +infinity (no absorption), mvr's 0 */
        double distance = number(*e, "attenuationDistance", 0.0);
        d.volume.attenuation_distance = std::isfinite(distance) && distance > 0 ? float(distance) : 0.0f;
        numbers(*e, "attenuationColor", d.volume.attenuation_color, 3, ew);
    }
    if (const tinygltf::Value *e = find("KHR_materials_dispersion", ew))
        d.dispersion = float(number(*e, "dispersion", 0.0));
    if (const tinygltf::Value *e = find("KHR_materials_iridescence", ew)) {
        d.iridescence.factor = float(number(*e, "iridescenceFactor", 0.0));
        d.iridescence.texture = texture_value(*e, "iridescenceTexture", ew);
        d.iridescence.ior = float(number(*e, "iridescenceIor", 1.3));
        d.iridescence.thickness_minimum = float(number(*e, "iridescenceThicknessMinimum", 100.0));
        d.iridescence.thickness_maximum = float(number(*e, "iridescenceThicknessMaximum", 400.0));
        d.iridescence.thickness_texture = texture_value(*e, "iridescenceThicknessTexture", ew);
    }
    if (const tinygltf::Value *e = find("KHR_materials_anisotropy", ew)) {
        d.anisotropy.strength = float(number(*e, "anisotropyStrength", 0.0));
        d.anisotropy.rotation = float(number(*e, "anisotropyRotation", 0.0));
        d.anisotropy.texture = texture_value(*e, "anisotropyTexture", ew);
    }
    if (const tinygltf::Value *e = find("KHR_materials_pbrSpecularGlossiness", ew)) {
        /* the diffuse color takes the base color's place; metallic-roughness is ignored */
        d.spec_gloss.enabled = true;
        for (float &c : d.base_color_factor)
            c = 1.0f;
        numbers(*e, "diffuseFactor", d.base_color_factor, 4, ew);
        d.base_color = texture_value(*e, "diffuseTexture", ew);
        numbers(*e, "specularFactor", d.spec_gloss.specular_factor, 3, ew);
        d.spec_gloss.glossiness_factor = float(number(*e, "glossinessFactor", 1.0));
        d.spec_gloss.texture = texture_value(*e, "specularGlossinessTexture", ew);
        d.metallic_roughness = mvr_texture_ref{};
    }
}

}  // namespace mvr_gltf
