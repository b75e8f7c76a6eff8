// io_hostile's PBR material extension files (see hostile_material_ext.hpp).
#include "hostile_material_ext.hpp"

#include <cstring>

#include "hostile_check.hpp"
#include "hostile_docs.hpp"

namespace hostile {

namespace {

const char *const EXTENSIONS[] = {"KHR_materials_ior",       "KHR_materials_specular",     "KHR_materials_clearcoat",
                                  "KHR_materials_sheen",     "KHR_materials_transmission", "KHR_materials_volume",
                                  "KHR_materials_dispersion", "KHR_materials_iridescence", "KHR_materials_anisotropy"};

// Every extension, well formed, each texture texture 0 (a 2 x 2 PNG).
std::string valid_extensions()
{
    const std::string T = R"({"index":0})";
    return std::string(R"("KHR_materials_ior":{"ior":1.4},)") +
           R"("KHR_materials_specular":{"specularFactor":0.5,"specularTexture":)" + T +
           R"(,"specularColorFactor":[1,0.5,0.5],"specularColorTexture":)" + T + "}," +
           R"("KHR_materials_clearcoat":{"clearcoatFactor":1,"clearcoatTexture":)" + T +
           R"(,"clearcoatRoughnessFactor":0.2,"clearcoatRoughnessTexture":)" + T +
           R"(,"clearcoatNormalTexture":{"index":0,"scale":0.5}},)" +
           R"("KHR_materials_sheen":{"sheenColorFactor":[0.5,0.4,0.3],"sheenColorTexture":)" + T +
           R"(,"sheenRoughnessFactor":0.4,"sheenRoughnessTexture":)" + T + "}," +
           R"("KHR_materials_transmission":{"transmissionFactor":0.8,"transmissionTexture":)" + T + "}," +
           R"("KHR_materials_volume":{"thicknessFactor":0.2,"thicknessTexture":)" + T +
           R"(,"attenuationDistance":2,"attenuationColor":[1,0.8,0.6]},)" +
           R"("KHR_materials_dispersion":{"dispersion":1},)" +
           R"("KHR_materials_iridescence":{"iridescenceFactor":1,"iridescenceTexture":)" + T +
           R"(,"iridescenceThicknessTexture":)" + T + "}," +
           R"("KHR_materials_anisotropy":{"anisotropyStrength":0.5,"anisotropyRotation":1,"anisotropyTexture":)" + T +
           "}";
}

// One lit, textured quad whose material 0 carries `extensions` (the members
// of its "extensions" object).
doc ext_doc(const std::string &extensions)
{
    std::vector<uint8_t> png = solid_image("png", 2, 2, 200, 150, 100);
    doc d = textured_doc("{\"uri\":\"data:image/png;base64," + gen::base64(png.data(), png.size()) + "\"}");
    d.materials[0] = R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0},"metallicFactor":0},)"
                     R"("extensions":{)" + extensions + "}}";
    d.ext_used.clear();
    for (const char *e : EXTENSIONS)
        d.use(e);
    return d;
}

}  // namespace

void material_ext_files(files &f)
{
    const std::string M = "matext_";
    f.text(M + "valid.gltf", ext_doc(valid_extensions()).json(), "every PBR extension, each with its textures",
           "loads without a warning");
    f.text(M + "out_of_range.gltf",
           ext_doc(R"("KHR_materials_transmission":{"transmissionFactor":5},)"
                   R"("KHR_materials_sheen":{"sheenColorFactor":[-1,0.5,2]})")
               .json(),
           "transmissionFactor 5, sheenColorFactor [-1, 0.5, 2]", "loads; the factors clamped, one warning");
    auto refused = [&](const std::string &name, const std::string &what, const std::string &naming,
                       const std::string &extensions) {
        f.text(M + name, ext_doc(extensions).json(), what, "refused naming " + naming, naming);
    };
    const std::string W = "materials[0].extensions.";
    refused("ext_not_object.gltf", "KHR_materials_sheen is an array", W + "KHR_materials_sheen is not an object",
            R"("KHR_materials_sheen":[1])");
    refused("color_length.gltf", "sheenColorFactor has two numbers",
            W + "KHR_materials_sheen.sheenColorFactor is not an array of 3 numbers",
            R"("KHR_materials_sheen":{"sheenColorFactor":[1,0]})");
    refused("color_string.gltf", "attenuationColor[1] is a string",
            W + "KHR_materials_volume.attenuationColor[1] is not a number",
            R"("KHR_materials_volume":{"attenuationColor":[1,"a",1]})");
    refused("texture_no_index.gltf", "clearcoatTexture is {}",
            W + "KHR_materials_clearcoat.clearcoatTexture.index is missing or not a valid index",
            R"("KHR_materials_clearcoat":{"clearcoatFactor":1,"clearcoatTexture":{}})");
    refused("texture_index_negative.gltf", "transmissionTexture.index is -1",
            W + "KHR_materials_transmission.transmissionTexture.index is missing or not a valid index",
            R"("KHR_materials_transmission":{"transmissionFactor":1,"transmissionTexture":{"index":-1}})");
    refused("texture_index_missing.gltf", "iridescenceTexture.index is 7 (one texture)",
            W + "KHR_materials_iridescence.iridescenceTexture: texture 7 does not exist",
            R"("KHR_materials_iridescence":{"iridescenceFactor":1,"iridescenceTexture":{"index":7}})");
    refused("texture_texcoord.gltf", "anisotropyTexture.texCoord is 0.5",
            W + "KHR_materials_anisotropy.anisotropyTexture.texCoord is not a valid set index",
            R"("KHR_materials_anisotropy":{"anisotropyStrength":1,"anisotropyTexture":{"index":0,"texCoord":0.5}})");
    refused("texture_not_object.gltf", "sheenRoughnessTexture is 0",
            W + "KHR_materials_sheen.sheenRoughnessTexture is not an object",
            R"("KHR_materials_sheen":{"sheenColorFactor":[1,1,1],"sheenRoughnessTexture":0})");
    refused("diffuse_length.gltf", "pbrSpecularGlossiness diffuseFactor has three numbers",
            W + "KHR_materials_pbrSpecularGlossiness.diffuseFactor is not an array of 4 numbers",
            R"("KHR_materials_pbrSpecularGlossiness":{"diffuseFactor":[1,1,1]})");
}

// Every broken file refused naming the material and the field; the valid
// one loads silently; out-of-range factors load, repaired, with a warning.
void material_extensions_are_checked(mvr_test_state *t)
{
    const files &f = F();
    size_t refused = check_refusals(t, f, "matext_");
    CHECK_MSG(t, refused >= 9, "%zu matext_* files refused", refused);
    outcome v = load(t, f.path("matext_valid.gltf"), defaults());
    CHECK_MSG(t, v.r == MVR_OK && v.warnings.empty(), "matext_valid: %s %s", v.msg.c_str(),
              v.warnings.empty() ? "" : v.warnings[0].c_str());
    if (v.scene)
        CHECK(t, !render(t, v.scene, "matext_valid").empty());
    outcome r = load(t, f.path("matext_out_of_range.gltf"), defaults());
    CHECK_MSG(t, r.r == MVR_OK && r.warnings.size() == 1 && r.warned("out of range"), "matext_out_of_range: %s, %zu warnings",
              r.msg.c_str(), r.warnings.size());
}

}  // namespace hostile
