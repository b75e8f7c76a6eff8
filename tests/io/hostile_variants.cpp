// io_hostile's material variant files (see hostile_variants.hpp).
#include "hostile_variants.hpp"

#include <cstring>
#include <functional>

#include "hostile_check.hpp"
#include "hostile_docs.hpp"

namespace hostile {

namespace {

const char *const VALID_ROOT = R"({"variants":[{"name":"red"},{"name":"blue"},{"name":"red"}]})";
// primitive 0: red in variants 0 and 2, blue in variant 1
const char *const VALID_MAPPINGS =
    R"({"mappings":[{"material":1,"variants":[0,2]},{"material":2,"variants":[1],"name":"blue paint"}]})";

// Two unlit quads side by side (x = -0.5 and 0.5), both white (material 0);
// materials 1 and 2 are red and blue. root: the root's
// extensions.KHR_materials_variants ("" = none); mappings0 / mappings1:
// primitive 0's / 1's ("" = none). KHR_materials_variants is used and required.
doc variants_doc(const std::string &root, const std::string &mappings0, const std::string &mappings1 = "")
{
    doc d;
    std::vector<uint8_t> bin;
    unlit(d, -1, 1, 1, 1);
    unlit(d, -1, 1, 0, 0);
    unlit(d, -1, 0, 0, 1);
    std::string p0 = quad(d, bin, 0, -0.5f, 0, 0.4f, 0), p1 = quad(d, bin, 0, 0.5f, 0, 0.4f, 0);
    if (!mappings0.empty())
        p0.insert(p0.size() - 1, ",\"extensions\":{\"KHR_materials_variants\":" + mappings0 + "}");
    if (!mappings1.empty())
        p1.insert(p1.size() - 1, ",\"extensions\":{\"KHR_materials_variants\":" + mappings1 + "}");
    one_mesh(d, {p0, p1});
    d.buffers.push_back(data_buffer(bin));
    if (!root.empty())
        d.extra = ",\"extensions\":{\"KHR_materials_variants\":" + root + "}";
    d.use("KHR_materials_variants");
    d.ext_required.push_back("KHR_materials_variants");
    return d;
}

size_t red(const std::vector<uint8_t> &px)
{
    return count_pixels(px, [](const uint8_t *p) { return p[0] > 200 && p[1] < 60 && p[2] < 60; });
}

size_t blue(const std::vector<uint8_t> &px)
{
    return count_pixels(px, [](const uint8_t *p) { return p[2] > 200 && p[0] < 60 && p[1] < 60; });
}

size_t white(const std::vector<uint8_t> &px)
{
    return count_pixels(px, [](const uint8_t *p) { return p[0] > 200 && p[1] > 200 && p[2] > 200; });
}

}  // namespace

void variant_files(files &f)
{
    const std::string V = "variants_";
    f.text(V + "valid.gltf", variants_doc(VALID_ROOT, VALID_MAPPINGS).json(),
           "two white quads, the left one red in variants 0 and 2 ('red', 'red'), blue in 1 ('blue')",
           "loads (required extension implemented); selections render red / blue / white");
    {
        // primitive 0 has no POSITION (skipped with a warning): the mapped
        // glTF primitive 1 is the scene's primitive 0
        doc d = variants_doc(VALID_ROOT, "", VALID_MAPPINGS);
        d.meshes[0] = replace_all(d.meshes[0], "{\"attributes\":{\"POSITION\":0,", "{\"attributes\":{");
        f.text(V + "after_skipped.gltf", d.json(), "primitive 0 without POSITION, primitive 1 mapped",
               "loads, one warning; 'red' turns the remaining quad red");
    }
    auto refused = [&](const std::string &name, const std::string &what, const std::string &naming,
                       const std::string &root, const std::string &mappings0, const std::string &mappings1 = "") {
        f.text(V + name, variants_doc(root, mappings0, mappings1).json(), what, "refused naming " + naming, naming);
    };
    const std::string R = "extensions.KHR_materials_variants";
    const std::string P0 = "meshes[0].primitives[0].extensions.KHR_materials_variants";
    // the root's variants
    refused("root_not_object.gltf", "the root extension is an array", R + " is not an object", "[1]", VALID_MAPPINGS);
    refused("root_no_variants.gltf", "the root extension has no variants", R + ".variants is missing or not an array",
            "{}", VALID_MAPPINGS);
    refused("root_variants_object.gltf", "variants is an object", R + ".variants is missing or not an array",
            R"({"variants":{"name":"red"}})", VALID_MAPPINGS);
    refused("variant_not_object.gltf", "variants[1] is 7", R + ".variants[1] is not an object",
            R"({"variants":[{"name":"red"},7]})", VALID_MAPPINGS);
    // tinygltf drops nulls from arrays: read as it is, the indices would shift
    refused("variant_null.gltf", "variants[0] is null (a parser that drops it shifts every index)",
            R + ".variants[0] is not an object", R"({"variants":[null,{"name":"blue"}]})", VALID_MAPPINGS);
    refused("variant_no_name.gltf", "variants[0] is {}", R + ".variants[0].name is missing or not a string",
            R"({"variants":[{},{"name":"blue"}]})", VALID_MAPPINGS);
    refused("variant_name_number.gltf", "variants[1].name is 5", R + ".variants[1].name is missing or not a string",
            R"({"variants":[{"name":"red"},{"name":5}]})", VALID_MAPPINGS);
    // a primitive's mappings
    refused("prim_not_object.gltf", "primitive 0's extension is true", P0 + " is not an object", VALID_ROOT, "true");
    refused("mappings_missing.gltf", "primitive 0's extension has no mappings", P0 + ".mappings is missing or not an array",
            VALID_ROOT, "{}");
    refused("mapping_not_object.gltf", "mappings[1] is a string", P0 + ".mappings[1] is not an object", VALID_ROOT,
            R"({"mappings":[{"material":1,"variants":[0]},"blue"]})");
    refused("mapping_no_material.gltf", "mappings[0] has no material", P0 + ".mappings[0].material is missing",
            VALID_ROOT, R"({"mappings":[{"variants":[0]}]})");
    refused("material_missing.gltf", "primitive 1's mappings[0].material is 99 (3 materials)",
            "meshes[0].primitives[1].extensions.KHR_materials_variants.mappings[0].material: material 99 does not "
            "exist (3 materials)",
            VALID_ROOT, VALID_MAPPINGS, R"({"mappings":[{"material":99,"variants":[0]}]})");
    refused("material_negative.gltf", "mappings[0].material is -1",
            P0 + ".mappings[0].material is not an integer in 0..2147483647", VALID_ROOT,
            R"({"mappings":[{"material":-1,"variants":[0]}]})");
    // 2^32 + 1: narrowed to int it would be material 1
    refused("material_wraps.gltf", "mappings[0].material is 4294967297 (1 when narrowed to 32 bits)",
            P0 + ".mappings[0].material is not an integer in 0..2147483647", VALID_ROOT,
            R"({"mappings":[{"material":4294967297,"variants":[0]}]})");
    refused("variants_not_array.gltf", "mappings[0].variants is 0", P0 + ".mappings[0].variants is missing or not an array",
            VALID_ROOT, R"({"mappings":[{"material":1,"variants":0}]})");
    refused("variant_missing.gltf", "mappings[1].variants[0] is 5 (3 variants)",
            P0 + ".mappings[1].variants[0]: variant 5 does not exist (3 variants", VALID_ROOT,
            R"({"mappings":[{"material":1,"variants":[0]},{"material":2,"variants":[5]}]})");
    refused("variant_negative.gltf", "mappings[0].variants[1] is -1",
            P0 + ".mappings[0].variants[1] is not an integer in 0..2147483647", VALID_ROOT,
            R"({"mappings":[{"material":1,"variants":[0,-1]}]})");
    refused("variant_fraction.gltf", "mappings[0].variants[0] is 0.5",
            P0 + ".mappings[0].variants[0] is not an integer in 0..2147483647", VALID_ROOT,
            R"({"mappings":[{"material":1,"variants":[0.5]}]})");
    // 2^32: narrowed to int it would be variant 0
    refused("variant_wraps.gltf", "mappings[0].variants[0] is 4294967296 (0 when narrowed to 32 bits)",
            P0 + ".mappings[0].variants[0] is not an integer in 0..2147483647", VALID_ROOT,
            R"({"mappings":[{"material":1,"variants":[4294967296]}]})");
    refused("variant_twice_in_mapping.gltf", "mappings[0].variants is [1, 1]",
            P0 + ".mappings[0].variants[1]: variant 1 is mapped already by mappings[0]", VALID_ROOT,
            R"({"mappings":[{"material":1,"variants":[1,1]}]})");
    refused("variant_in_two_mappings.gltf", "variant 0 in mappings[0] (red) and mappings[1] (blue)",
            P0 + ".mappings[1].variants[0]: variant 0 is mapped already by mappings[0]", VALID_ROOT,
            R"({"mappings":[{"material":1,"variants":[0]},{"material":2,"variants":[0]}]})");
    refused("no_root.gltf", "mappings without the root's variants", P0 + ".mappings[0].variants[0]: variant 0 does not "
            "exist (0 variants", "", VALID_MAPPINGS);
}

// Material variants (variants_* files): every broken file refused with a
// message naming the object; the valid one loads (the required extension
// implemented) and each selection draws its colour on the mapped quad only;
// a mapped primitive after a skipped one is still the one mapped.
void material_variants_are_checked(mvr_test_state *t)
{
    const files &f = F();
    size_t refused = check_refusals(t, f, "variants_");
    CHECK_MSG(t, refused >= 20, "%zu variants_* files refused", refused);
    {
        outcome o = load(t, f.path("variants_valid.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.warnings.empty(), "variants_valid: %s %s", o.msg.c_str(),
                  o.warnings.empty() ? "" : o.warnings[0].c_str());
        if (o.scene) {
            mvr_scene *s = o.scene;
            CHECK_EQ_INT(t, mvr_scene_variant_count(s), 3);
            uint32_t i = 9;
            CHECK(t, mvr_scene_find_variant(s, "red", &i) == MVR_OK && i == 0); /* the first of two 'red's */
            CHECK(t, mvr_scene_find_variant(s, "blue", &i) == MVR_OK && i == 1);
            std::vector<uint8_t> by_default = render(t, s, "variants_valid");
            CHECK(t, mvr_scene_select_variant(s, 0) == MVR_OK);
            std::vector<uint8_t> as_red = render(t, s, "variants_valid red");
            CHECK(t, mvr_scene_select_variant(s, 1) == MVR_OK);
            std::vector<uint8_t> as_blue = render(t, s, "variants_valid blue");
            CHECK(t, mvr_scene_select_variant(s, 2) == MVR_OK);
            std::vector<uint8_t> as_red2 = render(t, s, "variants_valid red (2)");
            CHECK(t, mvr_scene_select_variant(s, MVR_VARIANT_DEFAULT) == MVR_OK);
            std::vector<uint8_t> again = render(t, s, "variants_valid default again");
            if (!by_default.empty() && !as_red.empty() && !as_blue.empty()) {
                size_t w = white(by_default);
                CHECK_MSG(t, red(by_default) == 0 && blue(by_default) == 0 && w > 200,
                          "default: %zu red, %zu blue, %zu white pixels", red(by_default), blue(by_default), w);
                /* one quad turns red (or blue), the other stays white */
                CHECK_MSG(t, red(as_red) > 100 && blue(as_red) == 0 && white(as_red) > 100 && white(as_red) < w,
                          "red: %zu red, %zu blue, %zu white pixels", red(as_red), blue(as_red), white(as_red));
                CHECK_MSG(t, blue(as_blue) > 100 && red(as_blue) == 0 && white(as_blue) > 100,
                          "blue: %zu red, %zu blue, %zu white pixels", red(as_blue), blue(as_blue), white(as_blue));
                CHECK(t, as_red2 == as_red);
                CHECK(t, again == by_default);
            }
        }
    }
    {
        outcome o = load(t, f.path("variants_after_skipped.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.warnings.size() == 1 && o.warned("meshes[0].primitives[0] has no POSITION"),
                  "variants_after_skipped: %s, %zu warnings", o.msg.c_str(), o.warnings.size());
        if (o.scene) {
            std::vector<uint8_t> by_default = render(t, o.scene, "variants_after_skipped");
            CHECK(t, mvr_scene_select_variant(o.scene, 1) == MVR_OK);
            std::vector<uint8_t> as_blue = render(t, o.scene, "variants_after_skipped blue");
            CHECK_MSG(t, by_default.empty() || (blue(by_default) == 0 && white(by_default) > 100),
                      "default: %zu blue, %zu white", blue(by_default), white(by_default));
            CHECK_MSG(t, as_blue.empty() || (blue(as_blue) > 100 && white(as_blue) == 0),
                      "blue: %zu blue, %zu white", blue(as_blue), white(as_blue));
        }
    }
}

}  // namespace hostile
