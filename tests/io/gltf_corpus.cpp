// The glTF test corpus: files covering every feature the loader supports,
// and files broken in every way the loader must refuse. Written fresh by the
// tests (no third-party models).
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "gltf_gen.hpp"
#include "mvr/mvr.h"

namespace gen {

static const int BYTE = 5120, UBYTE = 5121, SHORT = 5122, USHORT = 5123, UINT = 5125, FLOAT = 5126;

// A unit quad facing +Z: positions, normals, uvs, indices; returns the primitive JSON.
static std::string quad_primitive(builder &b, float cx, float cy, int material, bool uv1 = false)
{
    std::vector<float> pos = {cx - 0.4f, cy - 0.4f, 0, cx + 0.4f, cy - 0.4f, 0, cx + 0.4f, cy + 0.4f, 0, cx - 0.4f, cy + 0.4f, 0};
    std::vector<float> nrm = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    // one statement each: the operands of + are not sequenced, and the
    // broken files rely on this order (POSITION 0, NORMAL 1, TEXCOORD_0 2, indices 3)
    int a_pos = b.floats(pos, "VEC3");
    int a_nrm = b.floats(nrm, "VEC3");
    int a_uv = b.floats(uv, "VEC2");
    std::string attrs = "\"POSITION\":" + std::to_string(a_pos) + ",\"NORMAL\":" + std::to_string(a_nrm) +
                        ",\"TEXCOORD_0\":" + std::to_string(a_uv);
    if (uv1) {
        // set 1 flipped: not a copy of set 0, which the loader would fold into set 0
        std::vector<float> flipped = {0, 0, 1, 0, 1, 1, 0, 1};
        int a_uv1 = b.floats(flipped, "VEC2");
        attrs += ",\"TEXCOORD_1\":" + std::to_string(a_uv1);
    }
    int a_idx = b.indices16({0, 1, 2, 0, 2, 3});
    std::string p = "{\"attributes\":{" + attrs + "},\"indices\":" + std::to_string(a_idx);
    if (material >= 0)
        p += ",\"material\":" + std::to_string(material);
    return p + "}";
}

static void one_mesh_scene(builder &b, const std::vector<std::string> &primitives)
{
    std::string prims = "[";
    for (size_t i = 0; i < primitives.size(); ++i)
        prims += (i ? "," : "") + primitives[i];
    b.add(b.meshes, "{\"primitives\":" + prims + "]}");
    b.add(b.nodes, "{\"mesh\":0}");
    b.add(b.scenes, "{\"nodes\":[0]}");
}

static int light_scene(builder &b)
{
    b.add(b.lights, "{\"type\":\"directional\",\"intensity\":2.0}");
    b.ext_used.push_back("KHR_lights_punctual");
    return b.add(b.nodes, "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}},\"rotation\":[-0.3,0.2,0,0.93]}");
}

static void textured(builder &b, const std::vector<uint8_t> &png, const std::vector<uint8_t> &jpg, container c,
                     const std::string &dir, const std::string &name)
{
    std::string png_source, jpg_source;
    if (c == container::external_bin) {
        write_file(dir + "/" + name + "_checker.png", png.data(), png.size());
        write_file(dir + "/" + name + "_checker.jpg", jpg.data(), jpg.size());
        png_source = "{\"uri\":\"" + name + "_checker.png\"}";
        jpg_source = "{\"uri\":\"" + name + "_checker.jpg\"}";
    } else if (c == container::data_uri) {
        png_source = "{\"uri\":\"data:image/png;base64," + base64(png.data(), png.size()) + "\"}";
        jpg_source = "{\"uri\":\"data:image/jpeg;base64," + base64(jpg.data(), jpg.size()) + "\"}";
    } else {
        png_source = "{\"bufferView\":" + std::to_string(b.view(png.data(), png.size())) + ",\"mimeType\":\"image/png\"}";
        jpg_source = "{\"bufferView\":" + std::to_string(b.view(jpg.data(), jpg.size())) + ",\"mimeType\":\"image/jpeg\"}";
    }
    b.add(b.images, png_source);
    b.add(b.images, jpg_source);
    b.add(b.samplers, "{\"magFilter\":9728,\"minFilter\":9728,\"wrapS\":33071,\"wrapT\":33071}");
    b.add(b.textures, "{\"source\":0,\"sampler\":0}");
    b.add(b.textures, "{\"source\":1}");
    b.add(b.materials, "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},\"metallicFactor\":0}}");
    b.add(b.materials, "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":1},\"metallicFactor\":0}}");
    one_mesh_scene(b, {quad_primitive(b, -0.5f, 0, 0), quad_primitive(b, 0.5f, 0, 1)});
    int light = light_scene(b);
    b.scenes[0] = "{\"nodes\":[0," + std::to_string(light) + "]}";
}

static std::string component_types(builder &b, const std::string &dir)
{
    // positions int16 normalized, normals int8 normalized, interleaved with a
    // stride of 12; uvs uint16 normalized; COLOR_0 uint8 normalized VEC3;
    // uint8 indices in one primitive, uint32 in the other (KHR_mesh_quantization)
    struct vtx { int16_t p[3]; int16_t pad; int8_t n[3]; int8_t pad2; };
    static_assert(sizeof(vtx) == 12, "interleaved vertex");
    vtx v[4] = {{{-32767, -32767, 0}, 0, {0, 0, 127}, 0}, {{32767, -32767, 0}, 0, {0, 0, 127}, 0},
                {{32767, 32767, 0}, 0, {0, 0, 127}, 0}, {{-32767, 32767, 0}, 0, {0, 0, 127}, 0}};
    int iv = b.view(v, sizeof v, 12);
    int pos = b.accessor(iv, 0, SHORT, 4, "VEC3", true);
    int nrm = b.accessor(iv, 8, BYTE, 4, "VEC3", true);
    uint16_t uv[8] = {0, 65535, 65535, 65535, 65535, 0, 0, 0};
    int uvs = b.accessor(b.view(uv, sizeof uv), 0, USHORT, 4, "VEC2", true);
    uint8_t col[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 0};
    int cols = b.accessor(b.view(col, sizeof col), 0, UBYTE, 4, "VEC3", true);
    uint8_t i8[3] = {0, 1, 2};
    uint32_t i32[3] = {0, 2, 3};
    int idx8 = b.accessor(b.view(i8, sizeof i8), 0, UBYTE, 3, "SCALAR");
    int idx32 = b.accessor(b.view(i32, sizeof i32), 0, UINT, 3, "SCALAR");
    std::string attrs = "{\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm) +
                        ",\"TEXCOORD_0\":" + std::to_string(uvs) + ",\"COLOR_0\":" + std::to_string(cols) + "}";
    b.add(b.materials, "{\"pbrMetallicRoughness\":{\"metallicFactor\":0}}");
    b.add(b.meshes, "{\"primitives\":[{\"attributes\":" + attrs + ",\"indices\":" + std::to_string(idx8) +
                        ",\"material\":0},{\"attributes\":" + attrs + ",\"indices\":" + std::to_string(idx32) +
                        ",\"material\":0}]}");
    b.add(b.nodes, "{\"mesh\":0,\"scale\":[0.8,0.8,0.8]}");
    b.scenes.push_back("{\"nodes\":[0," + std::to_string(light_scene(b)) + "]}");
    b.ext_used.push_back("KHR_mesh_quantization");
    b.ext_required.push_back("KHR_mesh_quantization");
    return b.write(dir, "component_types", container::external_bin);
}

static std::string sparse(builder &b, const std::string &dir)
{
    // vertex 2 of the quad moved to y = 1.5 by a sparse substitution; a second
    // triangle whose positions are only sparse values (no bufferView)
    std::vector<float> base = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0};
    int bv = b.view(base.data(), base.size() * 4);
    uint16_t which[1] = {2};
    float moved[3] = {0.5f, 1.5f, 0.0f};
    int iv = b.view(which, sizeof which), vv = b.view(moved, sizeof moved);
    std::string sp = ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" + std::to_string(iv) +
                     ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(vv) + "}}";
    int pos = b.accessor(bv, 0, FLOAT, 4, "VEC3", false, sp + ",\"min\":[-0.5,-0.5,0],\"max\":[0.5,0.5,0]");
    uint8_t all[3] = {0, 1, 2};
    float tri[9] = {-1.0f, -1.0f, 0.1f, -0.6f, -1.0f, 0.1f, -0.8f, -0.6f, 0.1f};
    int iv2 = b.view(all, sizeof all), vv2 = b.view(tri, sizeof tri);
    std::string sp2 = ",\"sparse\":{\"count\":3,\"indices\":{\"bufferView\":" + std::to_string(iv2) +
                      ",\"componentType\":5121},\"values\":{\"bufferView\":" + std::to_string(vv2) + "}}";
    int pos2 = b.accessor(-1, 0, FLOAT, 3, "VEC3", false, sp2);
    b.add(b.meshes, "{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"indices\":" +
                        std::to_string(b.indices16({0, 1, 2, 0, 2, 3})) + "},{\"attributes\":{\"POSITION\":" +
                        std::to_string(pos2) + "}}]}");
    b.add(b.nodes, "{\"mesh\":0}");
    b.scenes.push_back("{\"nodes\":[0]}");
    return b.write(dir, "sparse", container::data_uri);
}

static std::string modes(builder &b, const std::string &dir)
{
    // strip (4 -> 2 triangles), fan (5 -> 3), lines, line loop, line strip,
    // points, non-indexed triangles, side by side
    std::vector<std::string> prims;
    const int mode_list[7] = {5, 6, 1, 2, 3, 0, 4};
    for (int k = 0; k < 7; ++k) {
        float x = -1.5f + 0.5f * float(k);
        std::vector<float> pos = {x - 0.2f, -0.2f, 0, x + 0.2f, -0.2f, 0, x - 0.2f, 0.2f, 0, x + 0.2f, 0.2f, 0, x, 0.35f, 0};
        int n = mode_list[k] == 6 ? 5 : mode_list[k] == 4 ? 3 : 4;
        pos.resize(size_t(n) * 3);
        int a = b.floats(pos, "VEC3");
        std::string p = "{\"attributes\":{\"POSITION\":" + std::to_string(a) + "},\"mode\":" + std::to_string(mode_list[k]);
        if (mode_list[k] != 4) {
            std::vector<uint16_t> idx;
            for (int i = 0; i < n; ++i)
                idx.push_back(uint16_t(i));
            p += ",\"indices\":" + std::to_string(b.indices16(idx));
        }
        prims.push_back(p + ",\"material\":0}");
    }
    b.add(b.materials, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.6,0.2,1]},\"extensions\":{\"KHR_materials_unlit\":{}}}");
    b.ext_used.push_back("KHR_materials_unlit");
    one_mesh_scene(b, prims);
    return b.write(dir, "modes", container::external_bin);
}

static std::string materials(builder &b, const std::string &dir)
{
    auto png = checker_image("png", 32, 200, 120, 40);
    auto half = checker_image("png", 16, 128, 128, 255, 128);
    b.add(b.images, "{\"uri\":\"data:image/png;base64," + base64(png.data(), png.size()) + "\"}");
    b.add(b.images, "{\"uri\":\"data:image/png;base64," + base64(half.data(), half.size()) + "\"}");
    b.add(b.textures, "{\"source\":0}");
    b.add(b.textures, "{\"source\":1}");
    const char *mats[] = {
        "{\"pbrMetallicRoughness\":{\"metallicRoughnessTexture\":{\"index\":0},\"metallicFactor\":1,\"roughnessFactor\":0.5}}",
        "{\"normalTexture\":{\"index\":1,\"scale\":0.5},\"pbrMetallicRoughness\":{\"metallicFactor\":0}}",
        "{\"occlusionTexture\":{\"index\":0,\"strength\":0.5,\"texCoord\":1},\"pbrMetallicRoughness\":{\"metallicFactor\":0}}",
        "{\"emissiveTexture\":{\"index\":0},\"emissiveFactor\":[1,1,1],\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":3}}}",
        "{\"alphaMode\":\"MASK\",\"alphaCutoff\":0.3,\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":1}}}",
        "{\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.8,0.2,0.4]}}",
        "{\"doubleSided\":true,\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.2,0.8,1]}}",
        "{\"extensions\":{\"KHR_materials_unlit\":{}},\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}",
        "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0,\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.5,0],\"rotation\":0.4,\"scale\":[2,2]}}}}}",
    };
    std::vector<std::string> prims;
    for (int k = 0; k < 9; ++k) {
        b.add(b.materials, mats[k]);
        prims.push_back(quad_primitive(b, -1.0f + float(k % 3), 1.0f - float(k / 3), k, k == 2));
    }
    b.ext_used = {"KHR_materials_emissive_strength", "KHR_materials_unlit", "KHR_texture_transform"};
    one_mesh_scene(b, prims);
    b.scenes[0] = "{\"nodes\":[0," + std::to_string(light_scene(b)) + "]}";
    return b.write(dir, "materials", container::external_bin);
}

// Emission without KHR_materials_emissive_strength (glTF 2.0, 3.9.4: the
// factor alone), and the extension's strength 0 turning it off; no light.
static std::string emission(builder &b, const std::string &dir)
{
    b.add(b.materials, "{\"emissiveFactor\":[1,0.5,0.25],\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]}}");
    b.add(b.materials, "{\"emissiveFactor\":[1,0.5,0.25],\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},"
                       "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":0}}}");
    b.ext_used = {"KHR_materials_emissive_strength"};
    one_mesh_scene(b, {quad_primitive(b, -0.5f, 0, 0), quad_primitive(b, 0.5f, 0, 1)});
    return b.write(dir, "emission", container::external_bin);
}

// Normal maps on the back faces of a double-sided material: four quads with
// one normal map tilting the front's normal toward its tangent (+u), with
// and without TANGENT, at x = -1.5 / -0.5 facing the camera (+z) and, turned
// 180 degrees about Y, at +0.5 / +1.5 showing their back faces. A back face
// takes the front's whole tangent frame negated (the Khronos Sample Viewer's
// rule: its relief is the front's seen from behind), so with the light
// coming from (+1, 0, +1) all four shade alike.
static std::string double_sided_normals(builder &b, const std::string &dir)
{
    auto png = solid_image("png", 4, 217, 128, 217); /* (0.70, 0, 0.70) in tangent space */
    b.add(b.images, "{\"uri\":\"data:image/png;base64," + base64(png.data(), png.size()) + "\"}");
    b.add(b.textures, "{\"source\":0}");
    b.add(b.materials, "{\"doubleSided\":true,\"normalTexture\":{\"index\":0},"
                       "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.8,0.8,1],\"metallicFactor\":0,"
                       "\"roughnessFactor\":1}}");
    auto with_tangents = [&](std::string p) {
        int a_tan = b.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4");
        return p.replace(p.find("{\"attributes\":{") + 15, 0, "\"TANGENT\":" + std::to_string(a_tan) + ",");
    };
    std::string tangent_quad = with_tangents(quad_primitive(b, -1.5f, 0, 0));
    std::string derived_quad = quad_primitive(b, -0.5f, 0, 0);
    std::string quads = "[" + tangent_quad + "," + derived_quad + "]";
    b.add(b.meshes, "{\"primitives\":" + quads + "}");
    /* turned about Y, x maps to -x: the derived-tangent quad lands at +0.5, the other at +1.5 */
    b.add(b.nodes, "{\"mesh\":0}");
    b.add(b.nodes, "{\"mesh\":0,\"rotation\":[0,1,0,0]}");
    int light = b.add(b.lights, "{\"type\":\"directional\",\"intensity\":2}");
    /* rotated 45 degrees about Y: the light travels along -(1, 0, 1) */
    b.add(b.nodes, "{\"rotation\":[0,0.3826834,0,0.9238795],\"extensions\":{\"KHR_lights_punctual\":{\"light\":" +
                       std::to_string(light) + "}}}");
    b.add(b.scenes, "{\"nodes\":[0,1,2]}");
    b.ext_used = {"KHR_lights_punctual"};
    return b.write(dir, "double_sided_normals", container::external_bin);
}

static std::string scene_graph(builder &b, const std::string &dir)
{
    b.add(b.materials, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.3,0.6,0.9,1],\"metallicFactor\":0}}");
    b.add(b.meshes, "{\"primitives\":[" + quad_primitive(b, 0, 0, 0) + "]}");
    b.add(b.cameras, "{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1}}");
    b.add(b.cameras, "{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":2,\"ymag\":2,\"znear\":0.1,\"zfar\":50}}");
    b.add(b.lights, "{\"type\":\"directional\",\"intensity\":1.5}");
    b.add(b.lights, "{\"type\":\"point\",\"intensity\":8,\"range\":20,\"color\":[1,0.8,0.6]}");
    b.add(b.lights, "{\"type\":\"spot\",\"intensity\":30,\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.5}}");
    b.ext_used.push_back("KHR_lights_punctual");
    // 0: parent by matrix (translate x +0.5); 1: child by TRS; 2, 3: cameras; 4-6: lights
    b.add(b.nodes, "{\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0.5,0,0,1],\"children\":[1]}");
    b.add(b.nodes, "{\"mesh\":0,\"translation\":[-0.5,0,0],\"rotation\":[0,0.2588,0,0.9659],\"scale\":[1,1.5,1]}");
    b.add(b.nodes, "{\"camera\":0,\"translation\":[0,0,3]}");
    b.add(b.nodes, "{\"camera\":1,\"translation\":[0,0,4]}");
    b.add(b.nodes, "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}},\"rotation\":[-0.38,0,0,0.92]}");
    b.add(b.nodes, "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}},\"translation\":[0,1,1.5]}");
    b.add(b.nodes, "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}},\"translation\":[0,0,2]}");
    b.scenes.push_back("{\"nodes\":[4]}");                   // scene 0: a light only
    b.scenes.push_back("{\"nodes\":[0,2,3,4,5,6]}");         // scene 1: the default
    b.default_scene = 1;
    return b.write(dir, "scene_graph", container::glb);
}

// Light values as Blender's glTF exporter writes them for a modest scene
// (KHR_lights_punctual units: a sun of 2049 lux, a point light of 27,000
// candela), with a camera: a white image at exposure 1.
static std::string physical_lights(builder &b, const std::string &dir)
{
    b.add(b.materials, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.6,0.6,0.6,1],\"metallicFactor\":0,"
                       "\"roughnessFactor\":0.6}}");
    b.add(b.materials, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.25,0.1,1],\"metallicFactor\":0,"
                       "\"roughnessFactor\":0.4}}");
    b.add(b.meshes, "{\"primitives\":[" + quad_primitive(b, 0, 0, 0) + "]}");
    b.add(b.meshes, "{\"primitives\":[" + quad_primitive(b, 0, 0, 1) + "]}");
    b.add(b.cameras, "{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.7,\"znear\":0.1,\"zfar\":100}}");
    b.add(b.lights, "{\"type\":\"directional\",\"intensity\":2049,\"color\":[1,0.96,0.9],\"name\":\"Sun\"}");
    b.add(b.lights, "{\"type\":\"point\",\"intensity\":27000,\"color\":[1,0.85,0.7],\"name\":\"Point\"}");
    b.ext_used.push_back("KHR_lights_punctual");
    b.add(b.nodes, "{\"mesh\":0,\"rotation\":[-0.7071068,0,0,0.7071068],\"scale\":[12,12,12]}");
    b.add(b.nodes, "{\"mesh\":1,\"translation\":[-1,0.5,0],\"scale\":[1.2,1.2,1.2]}");
    b.add(b.nodes, "{\"mesh\":1,\"translation\":[1,0.5,-1],\"rotation\":[0,0.38,0,0.92],\"scale\":[1.2,1.2,1.2]}");
    b.add(b.nodes, "{\"camera\":0,\"translation\":[0,1.6,5],\"rotation\":[-0.1,0,0,0.995]}");
    b.add(b.nodes, "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}},\"rotation\":[-0.42,0.22,0.1,0.87]}");
    b.add(b.nodes, "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}},\"translation\":[0.5,3,2]}");
    b.scenes.push_back("{\"nodes\":[0,1,2,3,4,5]}");
    return b.write(dir, "physical_lights", container::data_uri);
}

static std::string skin_morph(builder &b, const std::string &dir)
{
    std::string quad = quad_primitive(b, 0, 0, -1);
    std::vector<uint8_t> joints(16, 0);
    std::vector<float> weights = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    int j = b.accessor(b.view(joints.data(), joints.size()), 0, UBYTE, 4, "VEC4");
    int w = b.floats(weights, "VEC4");
    std::vector<float> delta(12, 0.1f);
    int t = b.floats(delta, "VEC3");
    quad.insert(quad.find("},\"indices\""), ",\"JOINTS_0\":" + std::to_string(j) + ",\"WEIGHTS_0\":" + std::to_string(w));
    quad.insert(quad.size() - 1, ",\"targets\":[{\"POSITION\":" + std::to_string(t) + "}]");
    b.add(b.meshes, "{\"primitives\":[" + quad + "],\"weights\":[0.5]}");
    float ibm[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    int ib = b.accessor(b.view(ibm, sizeof ibm), 0, FLOAT, 1, "MAT4");
    b.add(b.nodes, "{\"mesh\":0,\"skin\":0}");
    b.add(b.nodes, "{}");
    b.scenes.push_back("{\"nodes\":[0,1]}");
    std::string json_skin = "{\"joints\":[1],\"inverseBindMatrices\":" + std::to_string(ib) + "}";
    std::string path = b.write(dir, "skin_morph", container::data_uri);
    // add "skins" by hand (the builder has no list for it)
    std::vector<uint8_t> text = read_file(path);
    std::string s(text.begin(), text.end());
    s.insert(s.size() - 1, ",\"skins\":[" + json_skin + "]");
    write_file(path, s.data(), s.size());
    return path;
}

static std::string optional_ext(builder &b, const std::string &dir)
{
    one_mesh_scene(b, {quad_primitive(b, 0, 0, -1)});
    b.ext_used.push_back("EXT_mvr_unknown_optional");
    return b.write(dir, "optional_ext", container::external_bin);
}

// ---- broken files ----

static builder broken_base()
{
    builder b;
    one_mesh_scene(b, {quad_primitive(b, 0, 0, -1)});
    return b;
}

// Replaces the first occurrence of from with to in a written file.
static void patch(const std::string &path, const std::string &from, const std::string &to)
{
    std::vector<uint8_t> bytes = read_file(path);
    std::string s(bytes.begin(), bytes.end());
    size_t at = s.find(from);
    if (at == std::string::npos)
        throw std::runtime_error("patch: '" + from + "' not in " + path);
    s.replace(at, from.size(), to);
    write_file(path, s.data(), s.size());
}

// ---- files with little or nothing to draw: the renderer's empty paths ----

// Only LINES and POINTS, no triangle: a 9 x 9 grid of lines and a point in
// every cell, unlit.
static std::string lines_points(builder &b, const std::string &dir)
{
    std::vector<float> lines, points;
    for (int k = 0; k <= 8; ++k) {
        float v = -1.0f + 0.25f * float(k);
        lines.insert(lines.end(), {-1.0f, v, 0, 1.0f, v, 0, v, -1.0f, 0, v, 1.0f, 0});
        for (int j = 0; k < 8 && j < 8; ++j)
            points.insert(points.end(), {v + 0.125f, -0.875f + 0.25f * float(j), 0});
    }
    int a_lines = b.floats(lines, "VEC3");
    int a_points = b.floats(points, "VEC3");
    b.add(b.materials, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.9,0.4,1]},\"extensions\":{\"KHR_materials_unlit\":{}}}");
    b.ext_used.push_back("KHR_materials_unlit");
    one_mesh_scene(b, {"{\"attributes\":{\"POSITION\":" + std::to_string(a_lines) + "},\"mode\":1,\"material\":0}",
                       "{\"attributes\":{\"POSITION\":" + std::to_string(a_points) + "},\"mode\":0,\"material\":0}"});
    return b.write(dir, "lines_points", container::data_uri);
}

// A lit quad on a node scaled to nothing along one or all axes: a singular
// model matrix (no inverse-transpose for the normals).
static std::string scaled_quad(builder &b, const std::string &dir, const char *name, const char *scale)
{
    b.add(b.meshes, "{\"primitives\":[" + quad_primitive(b, 0, 0, -1) + "]}");
    b.add(b.nodes, std::string("{\"mesh\":0,\"scale\":") + scale + "}");
    b.scenes.push_back("{\"nodes\":[0," + std::to_string(light_scene(b)) + "]}");
    return b.write(dir, name, container::data_uri);
}

static void nothing_to_draw(corpus &c, const std::string &dir)
{
    {   builder b; // a scene with no nodes
        b.scenes.push_back("{}");
        c.nothing_to_draw.push_back(b.write(dir, "empty_scene", container::data_uri)); }
    {   builder b; // no scenes, no nodes: the asset alone
        c.nothing_to_draw.push_back(b.write(dir, "asset_only", container::data_uri)); }
    {   builder b; // a node tree (TRS and matrix) without a mesh, in a GLB with no BIN chunk
        b.add(b.nodes, "{\"children\":[1,2],\"translation\":[1,2,3]}");
        b.add(b.nodes, "{\"rotation\":[0,0.7071068,0,0.7071068],\"scale\":[2,2,2]}");
        b.add(b.nodes, "{\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,5,0,0,1],\"children\":[3]}");
        b.add(b.nodes, "{}");
        b.scenes.push_back("{\"nodes\":[0]}");
        c.nothing_to_draw.push_back(b.write(dir, "nodes_no_mesh", container::glb)); }
    {   builder b; // a camera alone
        b.add(b.cameras, "{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1}}");
        b.add(b.nodes, "{\"camera\":0,\"translation\":[0,0,3]}");
        b.scenes.push_back("{\"nodes\":[0]}");
        c.nothing_to_draw.push_back(b.write(dir, "camera_only", container::data_uri)); }
    {   builder b; // a light alone
        int light = light_scene(b);
        b.scenes.push_back("{\"nodes\":[" + std::to_string(light) + "]}");
        c.nothing_to_draw.push_back(b.write(dir, "light_only", container::data_uri)); }
    {   builder b; // a mesh no node uses
        b.add(b.meshes, "{\"primitives\":[" + quad_primitive(b, 0, 0, -1) + "]}");
        b.add(b.nodes, "{\"translation\":[0,1,0]}");
        b.scenes.push_back("{\"nodes\":[0]}");
        c.nothing_to_draw.push_back(b.write(dir, "unreferenced_mesh", container::external_bin)); }
    {   builder b; // every triangle collapses to a point
        c.nothing_to_draw.push_back(scaled_quad(b, dir, "zero_scale", "[0,0,0]")); }
}

corpus write_corpus(const std::string &dir)
{
    corpus c;
    auto png = checker_image("png", 32, 230, 80, 40);
    auto jpg = checker_image("jpg", 32, 40, 90, 220);
    { builder b; textured(b, png, jpg, container::external_bin, dir, "textured_external");
      c.features.push_back(b.write(dir, "textured_external", container::external_bin)); }
    { builder b; textured(b, png, jpg, container::data_uri, dir, "textured_data_uri");
      c.features.push_back(b.write(dir, "textured_data_uri", container::data_uri)); }
    std::string glb;
    { builder b; textured(b, png, jpg, container::glb, dir, "textured_glb");
      glb = b.write(dir, "textured", container::glb); c.features.push_back(glb); }
    { builder b; c.features.push_back(component_types(b, dir)); }
    { builder b; c.features.push_back(emission(b, dir)); }
    { builder b; c.features.push_back(double_sided_normals(b, dir)); }
    { builder b; c.features.push_back(sparse(b, dir)); }
    { builder b; c.features.push_back(modes(b, dir)); }
    { builder b; c.features.push_back(materials(b, dir)); }
    { builder b; c.features.push_back(scene_graph(b, dir)); }
    { builder b; c.features.push_back(skin_morph(b, dir)); }
    { builder b; c.features.push_back(optional_ext(b, dir)); }
    { builder b; c.features.push_back(physical_lights(b, dir)); }

    const int INVALID = MVR_ERROR_INVALID_ASSET, UNSUPPORTED = MVR_ERROR_UNSUPPORTED;
    auto broken = [&](const std::string &path, int result, const std::string &part) {
        c.broken_files.push_back({path, result, part});
    };
    {   // a GLB cut in half
        std::vector<uint8_t> bytes = read_file(glb);
        bytes.resize(bytes.size() / 2);
        write_file(dir + "/truncated.glb", bytes.data(), bytes.size());
        broken(dir + "/truncated.glb", INVALID, "truncated");
    }
    {   // GLB version 1
        std::vector<uint8_t> bytes = read_file(glb);
        bytes[4] = 1;
        write_file(dir + "/glb_version.glb", bytes.data(), bytes.size());
        broken(dir + "/glb_version.glb", INVALID, "GLB version 1");
    }
    {   builder b = broken_base();
        std::string p = b.write(dir, "accessor_past_view", container::data_uri);
        patch(p, "\"count\":4,\"type\":\"VEC3\"", "\"count\":40,\"type\":\"VEC3\"");
        broken(p, INVALID, "meshes[0].primitives[0].attributes.POSITION: accessor 0 reads past the end of bufferView 0"); }
    {   builder b = broken_base();
        std::string p = b.write(dir, "stride_overflow", container::data_uri);
        patch(p, "\"byteLength\":48}", "\"byteLength\":48,\"byteStride\":252}");
        patch(p, "\"count\":4,\"type\":\"VEC3\"", "\"count\":17000000,\"type\":\"VEC3\"");
        broken(p, INVALID, "exceeds the cap"); }
    {   builder b = broken_base();
        std::string p = b.write(dir, "absurd_count", container::data_uri);
        patch(p, "\"count\":4,\"type\":\"VEC3\"", "\"count\":4000000000,\"type\":\"VEC3\"");
        broken(p, INVALID, "attributes.POSITION"); }
    {   builder b = broken_base();
        b.nodes = {"{\"mesh\":0,\"children\":[1]}", "{\"children\":[0]}"};
        broken(b.write(dir, "cyclic_nodes", container::data_uri), INVALID, "cycle"); }
    {   builder b = broken_base();
        b.nodes = {"{\"mesh\":0,\"children\":[2]}", "{\"children\":[2]}", "{}"};
        b.scenes = {"{\"nodes\":[0,1]}"};
        broken(b.write(dir, "shared_child", container::data_uri), INVALID, "nodes[2] has two parents"); }
    {   builder b = broken_base();
        b.buffer_uri_override = "missing.bin";
        broken(b.write(dir, "missing_buffer", container::external_bin), MVR_ERROR_IO, "buffers[0].uri"); }
    {   builder b;
        std::vector<float> pos = {0, 0, 0, 1, NAN, 0, 0, 1, 0};
        int a = b.floats(pos, "VEC3");
        one_mesh_scene(b, {"{\"attributes\":{\"POSITION\":" + std::to_string(a) + "}}"});
        broken(b.write(dir, "nan_positions", container::data_uri), INVALID, "NaN"); }
    {   builder b = broken_base();
        b.ext_used = b.ext_required = {"EXT_mvr_does_not_exist"};
        broken(b.write(dir, "required_unknown", container::data_uri), UNSUPPORTED, "EXT_mvr_does_not_exist"); }
    {   builder b;
        std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
        int a = b.floats(pos, "VEC3");
        one_mesh_scene(b, {"{\"attributes\":{\"POSITION\":" + std::to_string(a) + "},\"indices\":" +
                           std::to_string(b.indices16({0, 1, 7})) + "}"});
        broken(b.write(dir, "bad_index", container::data_uri), INVALID, "= 7 is past the 4 vertices"); }
    {   builder b = broken_base();
        std::string p = b.write(dir, "view_past_buffer", container::data_uri);
        patch(p, "\"byteOffset\":0,\"byteLength\":48", "\"byteOffset\":100000,\"byteLength\":48");
        broken(p, INVALID, "bufferViews[0]"); }
    {   builder b = broken_base();
        std::string p = b.write(dir, "missing_accessor", container::data_uri);
        patch(p, "\"NORMAL\":1", "\"NORMAL\":99");
        broken(p, INVALID, "accessor 99 does not exist"); }
    {   builder b = broken_base();
        b.materials = {"{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":5}}}"};
        std::string p = b.write(dir, "bad_texture", container::data_uri);
        patch(p, "\"indices\":3}", "\"indices\":3,\"material\":0}");
        broken(p, INVALID, "texture 5 does not exist"); }
    {   builder b = broken_base();
        b.images = {"{\"uri\":\"data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAAB\"}"};
        b.textures = {"{\"source\":0}"};
        b.materials = {"{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}"};
        std::string p = b.write(dir, "bad_image", container::data_uri);
        patch(p, "\"indices\":3}", "\"indices\":3,\"material\":0}");
        broken(p, INVALID, "images[0]"); }
    {   builder b = broken_base();
        std::string p = b.write(dir, "bad_mode", container::data_uri);
        patch(p, "\"indices\":3}", "\"indices\":3,\"mode\":9}");
        broken(p, INVALID, "mode 9"); }
    {   builder b;
        std::vector<float> base = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        int bv = b.view(base.data(), base.size() * 4);
        uint16_t which[1] = {50};
        float moved[3] = {1, 1, 1};
        int iv = b.view(which, sizeof which), vv = b.view(moved, sizeof moved);
        int a = b.accessor(bv, 0, FLOAT, 3, "VEC3", false,
                           ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" + std::to_string(iv) +
                               ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(vv) + "}}");
        one_mesh_scene(b, {"{\"attributes\":{\"POSITION\":" + std::to_string(a) + "}}"});
        broken(b.write(dir, "sparse_index_oob", container::data_uri), INVALID, "sparse.indices[0] = 50"); }
    {   std::string deep(3000, '[');
        std::string s = "{\"asset\":{\"version\":\"2.0\"},\"extras\":" + deep + std::string(3000, ']') + "}";
        write_file(dir + "/deep_json.gltf", s.data(), s.size());
        broken(dir + "/deep_json.gltf", INVALID, "nests deeper"); }
    {   const char junk[] = "\x01\x02not json at all {{{";
        write_file(dir + "/not_json.gltf", junk, sizeof junk - 1);
        broken(dir + "/not_json.gltf", INVALID, "not_json.gltf"); }
    // drawn with lines and points only; a quad flattened to z = 0 by its node
    { builder b; c.features.push_back(lines_points(b, dir)); }
    { builder b; c.features.push_back(scaled_quad(b, dir, "flat_scale", "[1,1,0]")); }
    nothing_to_draw(c, dir);
    return c;
}

}  // namespace gen
