// io_hostile's files (see hostile_files.hpp), made of the pieces in
// hostile_docs.cpp.
#include "hostile_files.hpp"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "hostile_codecs.hpp"
#include "hostile_docs.hpp"
#include "hostile_ktx2.hpp"
#include "hostile_variants.hpp"
#include "hostile_material_ext.hpp"

namespace hostile {

using gen::json_string;

// ------------------------------------------------------------ the files

std::string spelling::uri(const char *outside, const char *inside) const
{
    return replace_all(replace_all(pattern, "@", outside), "#", inside);
}

void files::text(const std::string &name, const std::string &content, const std::string &what,
                 const std::string &expect, const std::string &refused_naming)
{
    write_text(path(name), content);
    list.push_back({name, what, expect, refused_naming});
}

void files::bytes(const std::string &name, const std::vector<uint8_t> &b, const std::string &what,
                  const std::string &expect)
{
    write_bytes(path(name), b.data(), b.size());
    list.push_back({name, what, expect, ""});
}

static void relink(const std::string &target, const std::string &link)
{
    unlink(link.c_str());
    if (symlink(target.c_str(), link.c_str()) != 0)
        throw std::runtime_error("cannot create symlink " + link);
}

static void sparse_file(const std::string &path, uint64_t size)
{
    int fd = open(path.c_str(), O_CREAT | O_WRONLY | O_TRUNC, 0644);
    if (fd < 0 || ftruncate(fd, off_t(size)) != 0) {
        if (fd >= 0)
            close(fd);
        throw std::runtime_error("cannot create sparse " + path);
    }
    close(fd);
}

static std::vector<uint8_t> float_colours(float r, float g, float b, size_t pad_to)
{
    std::vector<uint8_t> out(pad_to, 0);
    float c[16];
    for (int i = 0; i < 4; ++i)
        c[i * 4 + 0] = r, c[i * 4 + 1] = g, c[i * 4 + 2] = b, c[i * 4 + 3] = 1;
    std::memcpy(out.data(), c, sizeof c);
    return out;
}

// Skins, morph targets and animations: anim_doc (valid) and each way of
// breaking it, refused naming the object; the unknown-path files load.
static void anim_files(files &f)
{
    anim_parts a;
    f.text("anim_valid.gltf", anim_doc(&a).json(), "a skinned, morphed, animated quad (tests/io/hostile_docs.hpp)",
           "loads: 1 skin, 2 joints, 2 morph targets, 1 animation");
    auto variant = [&](const std::string &name, const std::string &what, const std::string &naming,
                       const std::function<void(doc &)> &change) {
        doc d = anim_doc();
        change(d);
        f.text(name, d.json(), what, "refused naming " + naming, naming);
    };
    const std::string A = "anim_";
    auto S = [](int i) { return std::to_string(i); };
    auto channel = [](int sampler, int node, const char *path) {
        return "{\"sampler\":" + std::to_string(sampler) + ",\"target\":{\"node\":" + std::to_string(node) +
               ",\"path\":\"" + path + "\"}}";
    };
    // skins
    variant(A + "joint_past_skin.gltf", "JOINTS_0 names joint 1, skin 0 has one joint", "JOINTS_0 names joint 1",
            [](doc &d) { d.skins[0] = replace_all(d.skins[0], "[1,2]", "[1]"); });
    variant(A + "skin_joint_missing.gltf", "skin 0's joints[1] is node 99 (3 nodes)", "skins[0].joints[1]: node 99 does not exist",
            [](doc &d) { d.skins[0] = replace_all(d.skins[0], "[1,2]", "[1,99]"); });
    variant(A + "skin_joint_negative.gltf", "skin 0's joints[0] is node -1", "skins[0].joints[0]: node -1 does not exist",
            [](doc &d) { d.skins[0] = replace_all(d.skins[0], "[1,2]", "[-1,2]"); });
    variant(A + "skin_joint_outside_scene.gltf", "skin 0's joints[1] is node 3, in no scene",
            "skins[0].joints[1]: node 3 is not in the loaded scene", [](doc &d) {
                d.add(d.nodes, "{}");
                d.skins[0] = replace_all(d.skins[0], "[1,2]", "[1,3]");
            });
    variant(A + "skin_joint_twice.gltf", "skin 0 lists node 2 twice", "skins[0].joints[1]: node 2 is listed twice",
            [](doc &d) { d.skins[0] = replace_all(d.skins[0], "[1,2]", "[2,2]"); });
    variant(A + "skin_missing.gltf", "node 0's skin is 4 (1 skin)", "nodes[0].skin: skin 4 does not exist",
            [](doc &d) { d.nodes[0] = replace_all(d.nodes[0], "\"skin\":0", "\"skin\":4"); });
    variant(A + "ibm_short.gltf", "inverseBindMatrices: 1 matrix for 2 joints",
            "skins[0].inverseBindMatrices: accessor " + S(a.ibm) + " has 1 matrices",
            [&](doc &d) { d.accessors[size_t(a.ibm)] = replace_all(d.accessors[size_t(a.ibm)], "\"count\":2", "\"count\":1"); });
    variant(A + "ibm_mat3.gltf", "inverseBindMatrices of type MAT3", "skins[0].inverseBindMatrices: accessor " + S(a.ibm),
            [&](doc &d) { d.accessors[size_t(a.ibm)] = replace_all(d.accessors[size_t(a.ibm)], "MAT4", "MAT3"); });
    variant(A + "ibm_ushort.gltf", "inverseBindMatrices of componentType UNSIGNED_SHORT",
            "skins[0].inverseBindMatrices: accessor " + S(a.ibm) + " has componentType 5123",
            [&](doc &d) { d.accessors[size_t(a.ibm)] = replace_all(d.accessors[size_t(a.ibm)], "5126", "5123"); });
    variant(A + "skin_joints_70000.gltf", "a skin of 70000 joints", "skins[0] has 70000 joints", [](doc &d) {
        std::string j = "[1";
        for (int i = 1; i < 70000; ++i)
            j += ",2";
        d.skins[0] = replace_all(d.skins[0], "[1,2]", j + "]");
    });
    // values no float may hold: an accessor in a second buffer replaces one of anim_doc's
    auto bad_values = [&](const std::string &name, const std::string &what, const std::string &naming, int accessor,
                          const std::vector<float> &v, const char *type) {
        variant(name, what, naming, [&](doc &d) {
            std::vector<uint8_t> bin2;
            int view = put_view(d, bin2, 1, v.data(), v.size() * sizeof(float));
            std::string t = type;
            size_t comps = t == "MAT4" ? 16 : t == "VEC4" ? 4 : t == "VEC3" ? 3 : 1;
            int q = put_accessor(d, view, FLOAT, (long long)(v.size() / comps), type);
            d.buffers.push_back(data_buffer(bin2));
            std::string from = ":" + S(accessor), to = ":" + S(q);
            d.skins[0] = replace_all(d.skins[0], "\"inverseBindMatrices\"" + from + ",", "\"inverseBindMatrices\"" + to + ",");
            d.meshes[0] = replace_all(d.meshes[0], from + "}", to + "}");
            d.meshes[0] = replace_all(d.meshes[0], from + ",", to + ",");
            d.animations[0] = replace_all(d.animations[0], "\"output\"" + from + ",", "\"output\"" + to + ",");
            d.animations[0] = replace_all(d.animations[0], "\"output\"" + from + "}", "\"output\"" + to + "}");
        });
    };
    const float nan = std::nanf(""), inf = HUGE_VALF;
    std::vector<float> ibm(32, 0.0f);
    ibm[0] = ibm[5] = ibm[10] = ibm[15] = ibm[16] = ibm[21] = ibm[26] = 1;
    ibm[31] = nan;
    bad_values(A + "ibm_nan.gltf", "inverseBindMatrices with a NaN", "skins[0].inverseBindMatrices: accessor " +
               S(int(anim_doc().accessors.size())) + " holds NaN or infinite values", a.ibm, ibm, "MAT4");
    bad_values(A + "target_inf.gltf", "targets[1].POSITION with an infinity",
               "meshes[0].primitives[0].targets[1].POSITION: accessor " + S(int(anim_doc().accessors.size())) +
                   " holds NaN or infinite values",
               a.target1, {0, 0, 0, inf, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3");
    bad_values(A + "translation_nan.gltf", "translation output with a NaN",
               "animations[0].samplers[0].output: accessor " + S(int(anim_doc().accessors.size())) +
                   " holds NaN or infinite values",
               a.translations, {0, 0, 0, nan, 0, 0, 0, 0, 0}, "VEC3");
    bad_values(A + "weights_negative.gltf", "WEIGHTS_0 (float) with a weight of -1",
               "meshes[0].primitives[0].attributes.WEIGHTS_0: accessor " + S(int(anim_doc().accessors.size())) +
                   " element 2 has a negative, NaN or infinite weight",
               a.weights, {1, 0, 0, 0, 1, 0, 0, 0, -1, 2, 0, 0, 1, 0, 0, 0}, "VEC4");
    // skinning attributes
    variant(A + "joints_without_weights.gltf", "JOINTS_0 without WEIGHTS_0",
            "meshes[0].primitives[0].attributes.JOINTS_0 without WEIGHTS_0",
            [&](doc &d) { d.meshes[0] = replace_all(d.meshes[0], ",\"WEIGHTS_0\":" + S(a.weights), ""); });
    variant(A + "weights_without_joints.gltf", "WEIGHTS_0 without JOINTS_0",
            "meshes[0].primitives[0].attributes.WEIGHTS_0 without JOINTS_0",
            [&](doc &d) { d.meshes[0] = replace_all(d.meshes[0], ",\"JOINTS_0\":" + S(a.joints), ""); });
    variant(A + "joints1_without_joints0.gltf", "JOINTS_1 / WEIGHTS_1 only",
            "meshes[0].primitives[0].attributes.JOINTS_1 without JOINTS_0", [](doc &d) {
                d.meshes[0] = replace_all(replace_all(d.meshes[0], "JOINTS_0", "JOINTS_1"), "WEIGHTS_0", "WEIGHTS_1");
            });
    variant(A + "weights_not_normalized.gltf", "WEIGHTS_0 of UNSIGNED_BYTE, not normalized",
            "attributes.WEIGHTS_0: accessor " + S(a.weights) + " has integer componentType 5121 but is not normalized",
            [&](doc &d) { d.accessors[size_t(a.weights)] = replace_all(d.accessors[size_t(a.weights)], ",\"normalized\":true", ""); });
    variant(A + "joints_normalized.gltf", "JOINTS_0 of normalized UNSIGNED_BYTE",
            "attributes.JOINTS_0: accessor " + S(a.weights) + " is normalized",
            [&](doc &d) { d.meshes[0] = replace_all(d.meshes[0], "\"JOINTS_0\":" + S(a.joints), "\"JOINTS_0\":" + S(a.weights)); });
    variant(A + "joints_float.gltf", "JOINTS_0 of FLOAT (no bufferView)",
            "attributes.JOINTS_0: accessor " + S(int(anim_doc().accessors.size())) + " has componentType 5126", [&](doc &d) {
                int z = d.add(d.accessors, "{\"componentType\":5126,\"count\":4,\"type\":\"VEC4\"}");
                d.meshes[0] = replace_all(d.meshes[0], "\"JOINTS_0\":" + S(a.joints), "\"JOINTS_0\":" + S(z));
            });
    variant(A + "joints_short_count.gltf", "JOINTS_0 of 3 elements, POSITION of 4",
            "attributes.JOINTS_0: accessor " + S(a.joints) + " has 3 elements, POSITION has 4",
            [&](doc &d) { d.accessors[size_t(a.joints)] = replace_all(d.accessors[size_t(a.joints)], "\"count\":4", "\"count\":3"); });
    // morph targets and weights
    variant(A + "targets_mismatch.gltf", "primitive 1 has 1 morph target, primitive 0 has 2",
            "meshes[0].primitives[1] has 1 morph targets, primitives[0] has 2", [&](doc &d) {
                std::string one = replace_all(a.primitive, ",{\"POSITION\":" + S(a.target1) + "}", "");
                d.meshes[0] = replace_all(d.meshes[0], a.primitive + "]", a.primitive + "," + one + "]");
            });
    variant(A + "mesh_weights_length.gltf", "mesh.weights [0.5] for 2 targets",
            "meshes[0].weights has 1 values, the mesh has 2 morph targets",
            [](doc &d) { d.meshes[0] = replace_all(d.meshes[0], "[0.5,0.25]", "[0.5]"); });
    variant(A + "node_weights_length.gltf", "node.weights [1,0,0] for 2 targets", "nodes[0].weights has 3 values",
            [](doc &d) { d.nodes[0] = replace_all(d.nodes[0], "[1,0]", "[1,0,0]"); });
    variant(A + "target_short_count.gltf", "targets[1].POSITION of 2 elements, POSITION of 4",
            "meshes[0].primitives[0].targets[1].POSITION: accessor " + S(a.target1) + " has 2 elements",
            [&](doc &d) { d.accessors[size_t(a.target1)] = replace_all(d.accessors[size_t(a.target1)], "\"count\":4", "\"count\":2"); });
    variant(A + "target_vec2.gltf", "targets[0].POSITION of type VEC2", "targets[0].POSITION: accessor " + S(a.target0),
            [&](doc &d) { d.accessors[size_t(a.target0)] = replace_all(d.accessors[size_t(a.target0)], "VEC3", "VEC2"); });
    // samplers
    variant(A + "times_not_increasing.gltf", "sampler 0's input: 3 keys at 0 s (an accessor of zeros)",
            "animations[0].samplers[0].input: accessor", [](doc &d) {
                int z = d.add(d.accessors, "{\"componentType\":5126,\"count\":3,\"type\":\"SCALAR\"}");
                d.animations[0] = replace_all(d.animations[0], "{\"input\":", "{\"input\":" + std::to_string(z) + ",\"x\":");
            });
    variant(A + "output_count.gltf", "sampler 0's output: 2 values for 3 keys",
            "animations[0].samplers[0].output: accessor " + S(a.translations) + " has 2 elements; 3 keys of LINEAR translation",
            [&](doc &d) {
                d.accessors[size_t(a.translations)] = replace_all(d.accessors[size_t(a.translations)], "\"count\":3", "\"count\":2");
            });
    variant(A + "cubic_output_count.gltf", "sampler 0 CUBICSPLINE with 3 values for 3 keys (9 needed)",
            "animations[0].samplers[0].output: accessor " + S(a.translations) + " has 3 elements; 3 keys of CUBICSPLINE translation",
            [](doc &d) { d.animations[0] = replace_all(d.animations[0], "\"LINEAR\"", "\"CUBICSPLINE\""); });
    variant(A + "weights_output_count.gltf", "sampler 2 (weights, 2 targets): 5 values for 3 keys",
            "animations[0].samplers[2].output: accessor " + S(a.morph_weights) + " has 5 elements; 3 keys of STEP weights",
            [&](doc &d) {
                d.accessors[size_t(a.morph_weights)] = replace_all(d.accessors[size_t(a.morph_weights)], "\"count\":6", "\"count\":5");
            });
    variant(A + "interpolation_unknown.gltf", "sampler 0 interpolation SMOOTH",
            "animations[0].samplers[0].interpolation 'SMOOTH' is not LINEAR, STEP or CUBICSPLINE",
            [](doc &d) { d.animations[0] = replace_all(d.animations[0], "\"LINEAR\"", "\"SMOOTH\""); });
    variant(A + "rotation_not_normalized.gltf", "rotation output of SHORT, not normalized",
            "animations[0].samplers[1].output: accessor " + S(a.rotations) + " has integer componentType 5122 but is not normalized",
            [&](doc &d) { d.accessors[size_t(a.rotations)] = replace_all(d.accessors[size_t(a.rotations)], ",\"normalized\":true", ""); });
    variant(A + "translation_short.gltf", "translation output of VEC3 normalized SHORT (FLOAT only)",
            "animations[0].samplers[0].output: accessor " + S(int(anim_doc().accessors.size())) + " has componentType 5122",
            [&](doc &d) {
                int q = d.add(d.accessors, replace_all(d.accessors[size_t(a.rotations)], "VEC4", "VEC3"));
                d.animations[0] = replace_all(d.animations[0], "\"output\":" + S(a.translations), "\"output\":" + S(q));
            });
    variant(A + "translation_vec4.gltf", "translation output of VEC4 FLOAT",
            "animations[0].samplers[0].output: accessor " + S(a.translations) + " has 4 components per element, 3 expected",
            [&](doc &d) {
                d.accessors[size_t(a.translations)] = replace_all(d.accessors[size_t(a.translations)], "VEC3", "VEC4");
            });
    variant(A + "sampler_shared.gltf", "sampler 0 read by a translation and a rotation channel",
            "animations[0].samplers[0] is read by animations[0].channels[0]", [&](doc &d) {
                d.animations[0] = replace_all(d.animations[0], channel(1, 2, "rotation"), channel(0, 2, "rotation"));
            });
    variant(A + "times_huge_count.gltf", "sampler 0's input: 2000000000 keys, no bufferView",
            "animations[0].samplers[0].input: accessor", [](doc &d) {
                int z = d.add(d.accessors, "{\"componentType\":5126,\"count\":2000000000,\"type\":\"SCALAR\"}");
                d.animations[0] = replace_all(d.animations[0], "{\"input\":", "{\"input\":" + std::to_string(z) + ",\"x\":");
            });
    variant(A + "input_missing.gltf", "sampler 0's input is accessor 999", "animations[0].samplers[0].input: accessor 999 does not exist",
            [](doc &d) { d.animations[0] = replace_all(d.animations[0], "{\"input\":", "{\"input\":999,\"x\":"); });
    // channels
    variant(A + "channel_node_missing.gltf", "channel 0 targets node 42 (3 nodes)",
            "animations[0].channels[0].target.node: node 42 does not exist", [&](doc &d) {
                d.animations[0] = replace_all(d.animations[0], channel(0, 1, "translation"), channel(0, 42, "translation"));
            });
    variant(A + "channel_sampler_missing.gltf", "channel 1 reads sampler 9 (3 samplers)",
            "animations[0].channels[1].sampler: sampler 9 does not exist", [&](doc &d) {
                d.animations[0] = replace_all(d.animations[0], channel(1, 2, "rotation"), channel(9, 2, "rotation"));
            });
    variant(A + "weights_no_mesh.gltf", "channel 2 animates the weights of node 1 (no mesh)",
            "animations[0].channels[2]: animates the weights of node 1, which has no mesh", [&](doc &d) {
                d.animations[0] = replace_all(d.animations[0], channel(2, 0, "weights"), channel(2, 1, "weights"));
            });
    // unknown paths: warned once each, the channels left out; the file loads
    {
        doc d = anim_doc();
        d.animations[0] = replace_all(d.animations[0], "]}", "," + channel(0, 2, "pointer") + "," +
                                                                channel(0, 1, "pointer") + "," + channel(0, 2, "color") + "]}");
        f.text(A + "unknown_paths.gltf", d.json(), "channels 3..5 on paths pointer, pointer, color",
               "loads; one warning per path; 3 channels ignored");
        doc e = anim_doc();
        e.animations[0] = replace_all(e.animations[0], "]}", ",{\"sampler\":0,\"target\":{\"path\":\"pointer\"}}]}");
        e.use("KHR_animation_pointer");
        f.text(A + "pointer_without_node.gltf", e.json(), "a KHR_animation_pointer channel (no target.node)",
               "loads; warned; 1 channel ignored");
    }
}

// KTX2 containers (core/io/ktx2.cpp): a valid one, and each field of the
// header, the index, the DFD, the key/value data and the levels made to lie
// (offsets and lengths past the end or wrapping around 2^64, counts, sizes
// that do not match the format, Zstandard frames that inflate to other
// sizes, a decompression bomb); and valid shapes mvr does not decode.
static void ktx2_files(files &f)
{
    std::vector<uint8_t> px(8 * 8 * 4);
    for (size_t i = 0; i < px.size(); i += 4)
        px[i] = 250, px[i + 1] = 140, px[i + 2] = 20, px[i + 3] = 255;   // orange
    const ktx2_desc base = ktx2_from_rgba(px, 8, 8, VK_R8G8B8A8_SRGB, 4);
    const std::vector<uint8_t> valid = ktx2_file(base);
    auto put = [&](const std::string &name, const std::vector<uint8_t> &bytes, const std::string &what,
                   const std::string &expect) {
        write_bytes(f.asset + "/" + name + ".ktx2", bytes.data(), bytes.size());
        f.text(name + ".gltf", textured_doc("{\"uri\":\"" + name + ".ktx2\",\"mimeType\":\"image/ktx2\"}").json(),
               what, expect);
    };
    const std::string left_out = "loads, images[0] left out with a warning; strict: refused naming images[0]";
    auto edited = [&](const std::string &name, const std::string &what,
                      const std::function<void(std::vector<uint8_t> &)> &edit) {
        std::vector<uint8_t> b = valid;
        edit(b);
        put(name, b, what, left_out);
    };
    auto dfd_of = [](const std::vector<uint8_t> &b) { return size_t(b[KTX2_DFD_OFFSET]) | size_t(b[KTX2_DFD_OFFSET + 1]) << 8; };
    put("ktx2_valid", valid, "an 8x8 orange RGBA8 KTX2 with 4 levels", "loads, decoded, orange");
    put("ktx2_short_header", std::vector<uint8_t>(valid.begin(), valid.begin() + 40), "the first 40 bytes of a KTX2",
        left_out);
    edited("ktx2_level_past_end", "level 0's byteLength reaches past the end", [](std::vector<uint8_t> &b) {
        put_le64(b, ktx2_level_entry(0) + 8, b.size());
        put_le64(b, ktx2_level_entry(0) + 16, b.size());
    });
    edited("ktx2_level_offset_wraps", "level 0 at offset 2^64 - 16, 256 bytes (the sum wraps)",
           [](std::vector<uint8_t> &b) { put_le64(b, ktx2_level_entry(0), ~uint64_t(0) - 15); });
    edited("ktx2_level_count_huge", "levelCount 0xFFFFFFFF",
           [](std::vector<uint8_t> &b) { put_le32(b, KTX2_LEVEL_COUNT, 0xFFFFFFFFu); });
    put("ktx2_level_index_past_end", std::vector<uint8_t>(valid.begin(), valid.begin() + 100),
        "levelCount 4, the file ends inside the level index", left_out);
    edited("ktx2_dfd_outside", "dfdByteOffset 0xFFFFFFF0",
           [](std::vector<uint8_t> &b) { put_le32(b, KTX2_DFD_OFFSET, 0xFFFFFFF0u); });
    edited("ktx2_dfd_total_mismatch", "dfdTotalSize differs from dfdByteLength",
           [&](std::vector<uint8_t> &b) { put_le32(b, dfd_of(b), 0x7FFFFFFFu); });
    edited("ktx2_dfd_block_too_big", "the descriptor block's size runs past the DFD",
           [&](std::vector<uint8_t> &b) { put_le32(b, dfd_of(b) + 8, 2u | 0xFFFCu << 16); });
    {
        ktx2_desc k = base;
        k.orientation = "rd";
        std::vector<uint8_t> b = ktx2_file(k);
        size_t kvd = size_t(b[KTX2_KVD_OFFSET]) | size_t(b[KTX2_KVD_OFFSET + 1]) << 8;
        std::vector<uint8_t> runaway = b, no_nul = b;
        put_le32(runaway, kvd, 0xFFFFFFF0u);
        for (size_t i = kvd + 4; i < kvd + 4 + 18; ++i)
            no_nul[i] = 'K';
        put("ktx2_kvd_runaway", runaway, "a key/value pair of 0xFFFFFFF0 bytes", left_out);
        put("ktx2_kvd_no_nul", no_nul, "a key without its NUL", left_out);
    }
    edited("ktx2_sgd_outside", "supercompression global data at 2^63", [](std::vector<uint8_t> &b) {
        put_le64(b, 64, uint64_t(1) << 63);
        put_le64(b, 72, 16);
    });
    edited("ktx2_level_size_lie", "level 0 holds 16 bytes for 8x8 RGBA8 (256)", [](std::vector<uint8_t> &b) {
        put_le64(b, ktx2_level_entry(0) + 8, 16);
        put_le64(b, ktx2_level_entry(0) + 16, 16);
    });
    edited("ktx2_faces_3", "faceCount 3", [](std::vector<uint8_t> &b) { put_le32(b, 36, 3); });
    edited("ktx2_height0_depth", "pixelHeight 0 with pixelDepth 5", [](std::vector<uint8_t> &b) {
        put_le32(b, 24, 0);
        put_le32(b, 28, 5);
    });
    edited("ktx2_width0", "pixelWidth 0", [](std::vector<uint8_t> &b) { put_le32(b, 20, 0); });
    edited("ktx2_basislz_rgba8", "BasisLZ supercompression of VK_FORMAT_R8G8B8A8_SRGB",
           [](std::vector<uint8_t> &b) { put_le32(b, 44, 1); });
    {
        // 100000 x 100000 RGBA8 whose level index claims the 40 GB it would take
        ktx2_desc k = base;
        k.width = k.height = 100000;
        k.level_count = 1;
        k.levels.resize(1);
        std::vector<uint8_t> b = ktx2_file(k);
        put_le64(b, ktx2_level_entry(0) + 8, uint64_t(100000) * 100000 * 4);
        put_le64(b, ktx2_level_entry(0) + 16, uint64_t(100000) * 100000 * 4);
        put("ktx2_dims_huge", b, "100000x100000 RGBA8, level 0 claims 40 GB", left_out);
    }
    // Zstandard: frames of other sizes, garbage, a bomb
    auto zstd_level = [&](size_t raw_bytes, uint32_t w, uint32_t h, uint64_t claim) {
        ktx2_desc k = base;
        k.width = w;
        k.height = h;
        k.level_count = 1;
        k.levels.assign(1, std::vector<uint8_t>(raw_bytes, 7));
        ktx2_zstd(k);
        k.uncompressed[0] = claim;
        return ktx2_file(k);
    };
    put("ktx2_zstd_short", zstd_level(100, 8, 8, 256), "8x8 RGBA8 whose Zstandard level inflates to 100 of 256 bytes",
        left_out);
    put("ktx2_zstd_long", zstd_level(4096, 8, 8, 256), "8x8 RGBA8 whose Zstandard level inflates to 4096 of 256 bytes",
        left_out);
    {
        ktx2_desc k = base;
        k.level_count = 1;
        k.levels.assign(1, std::vector<uint8_t>(300));
        for (size_t i = 0; i < 300; ++i)
            k.levels[0][i] = uint8_t(i * 37 + 11);
        k.supercompression = 2;
        k.uncompressed = {256};
        put("ktx2_zstd_garbage", ktx2_file(k), "8x8 RGBA8, a Zstandard level of 300 bytes that are no frame", left_out);
    }
    put("ktx2_zstd_bomb_16k", zstd_level(1024, 16384, 16384, uint64_t(16384) * 16384 * 4),
        "16384x16384 RGBA8 (1 GiB) in a Zstandard frame that inflates to 1 KB",
        "OUT_OF_MEMORY naming images[0] (64 MiB and default budgets), never allocated");
    put("ktx2_zstd_over_cap", zstd_level(1024, 20000, 20000, uint64_t(20000) * 20000 * 4),
        "20000x20000 RGBA8 (over max_image_dimension) in a small Zstandard frame", left_out);
    // valid containers of shapes and formats mvr does not decode: left out as unsupported
    auto shape = [&](const std::string &name, const std::string &what, const std::function<void(ktx2_desc &)> &edit,
                     size_t level_bytes) {
        ktx2_desc k = base;
        k.level_count = 1;
        k.levels.assign(1, std::vector<uint8_t>(level_bytes, 9));
        edit(k);
        put(name, ktx2_file(k), what, left_out);
    };
    shape("ktx2_cubemap", "a valid cubemap", [](ktx2_desc &k) { k.faces = 6; }, 8 * 8 * 4 * 6);
    shape("ktx2_3d", "a valid 3D texture (depth 2)", [](ktx2_desc &k) { k.depth = 2; }, 8 * 8 * 4 * 2);
    shape("ktx2_array", "a valid array texture of 3 layers", [](ktx2_desc &k) { k.layers = 3; }, 8 * 8 * 4 * 3);
    shape("ktx2_rgba16f", "VK_FORMAT_R16G16B16A16_SFLOAT",
          [](ktx2_desc &k) { k.vk_format = VK_R16G16B16A16_SFLOAT, k.type_size = 2, k.texel_bytes = 8; }, 8 * 8 * 8);

    // GPU block payloads mvr keeps as blocks (ETC2, ASTC), each made to lie
    const ktx2_desc etc2 = ktx2_gpu("etc2", 8, 8, 4);   // 8x8 ETC2 RGBA8: 64, 16, 16, 16 bytes
    const std::vector<uint8_t> etc2_valid = ktx2_file(etc2);
    put("ktx2_etc2_truncated", std::vector<uint8_t>(etc2_valid.begin(), etc2_valid.end() - 10),
        "an 8x8 ETC2 KTX2 with 4 levels, its last 10 bytes (of level 0) cut", left_out);
    {
        std::vector<uint8_t> b = etc2_valid;   // level 1 (4x4: one 16-byte block) says 8
        put_le64(b, ktx2_level_entry(1) + 8, 8);
        put_le64(b, ktx2_level_entry(1) + 16, 8);
        put("ktx2_etc2_level_size_lie", b, "8x8 ETC2 whose level 1 holds 8 bytes (one block is 16)", left_out);
    }
    {
        std::vector<uint8_t> b = etc2_valid;   // 65536 x 65536: 4 GiB of blocks claimed
        put_le32(b, 20, 65536);
        put_le32(b, 24, 65536);
        put_le32(b, KTX2_LEVEL_COUNT, 1);
        put_le64(b, ktx2_level_entry(0) + 8, uint64_t(16384) * 16384 * 16);
        put_le64(b, ktx2_level_entry(0) + 16, uint64_t(16384) * 16384 * 16);
        put("ktx2_etc2_dims_huge", b, "65536x65536 ETC2, level 0 claims its 4 GiB", left_out);
    }
    {
        std::vector<uint8_t> b = etc2_valid;
        put_le32(b, KTX2_LEVEL_COUNT, 5);
        put("ktx2_etc2_levels_beyond_log2", b, "8x8 ETC2 with levelCount 5 (log2(8) + 1 = 4)", left_out);
    }
    {
        ktx2_desc k = etc2;   // Zstandard level 2 inflates to 8 of its 16 bytes
        k.levels[2].resize(8);
        ktx2_zstd(k);
        k.uncompressed[2] = 16;
        put("ktx2_etc2_zstd_short", ktx2_file(k), "8x8 ETC2, Zstandard level 2 inflates to 8 of 16 bytes", left_out);
    }
    {
        ktx2_desc k = etc2;
        k.orientation = "ru";
        put("ktx2_etc2_bottom_up", ktx2_file(k), "8x8 ETC2 stored bottom row first (KTXorientation ru)", left_out);
    }
    {
        ktx2_desc k = ktx2_gpu("astc", 8, 8, 1);   // sized for 4x4 blocks (4 blocks), declared 6x6 (also 4 blocks)...
        k.vk_format = 165;                         // VK_FORMAT_ASTC_6x6_UNORM_BLOCK
        k.levels[0].resize(16 * 3);                // ... so 3 blocks is a lie
        put("ktx2_astc_6x6_size_lie", ktx2_file(k), "8x8 ASTC 6x6 whose level 0 holds 3 blocks (it needs 4)", left_out);
    }
}

files write_all(const std::string &root_in)
{
    files f;
    mkdirs(root_in);
    char real[PATH_MAX];
    if (!realpath(root_in.c_str(), real))
        throw std::runtime_error("realpath " + root_in);
    f.root = real;
    f.asset = f.root + "/asset";
    mkdirs(f.asset + "/sub");
    mkdirs(f.root + "/cwd");
    mkdirs(f.root + "/shared_textures");
    const std::string &R = f.root;
    const std::string REFUSE_BUF = "refused: INVALID_ASSET naming buffers[1].uri";
    const std::string DEGRADE_IMG = "loads, images[0] left out (warning), no outside pixel";

    // outside the asset folder: distinctive colours and sizes
    std::vector<uint8_t> magenta = solid_image("png", 16, 16, 255, 0, 255);
    magenta.resize(OUTSIDE_PNG_SIZE, 0); // bytes after IEND: decoders ignore them
    write_bytes(R + "/outside.png", magenta.data(), magenta.size());
    std::vector<uint8_t> outside_bin = float_colours(1, 0, 1, OUTSIDE_BIN_SIZE);
    write_bytes(R + "/outside.bin", outside_bin.data(), outside_bin.size());
    // inside: the prefixes of the NUL spellings
    std::vector<uint8_t> white = solid_image("png", 16, 16, 255, 255, 255);
    write_bytes(f.asset + "/inside.png", white.data(), white.size());
    std::vector<uint8_t> inside_bin = float_colours(1, 1, 1, OUTSIDE_BIN_SIZE);
    write_bytes(f.asset + "/inside.bin", inside_bin.data(), inside_bin.size());
    relink(R + "/outside.png", f.asset + "/link_outside.png");
    relink(R + "/outside.bin", f.asset + "/link_outside.bin");
    relink("..", f.asset + "/link_up");
    relink(R, f.asset + "/link_root");
    relink(R + "/no_such_outside.bin", f.asset + "/link_dangling.bin");
    relink(R + "/no_such_outside.png", f.asset + "/link_dangling.png");
    // only in the current directory of the test (it chdirs there)
    write_bytes(R + "/cwd/only_in_cwd.png", magenta.data(), magenta.size());
    write_bytes(R + "/cwd/only_in_cwd.bin", outside_bin.data(), outside_bin.size());
    // a texture library beside the asset folder (file_access.allowed_root)
    std::vector<uint8_t> cyan = solid_image("png", 16, 16, 0, 200, 255);
    write_bytes(R + "/shared_textures/a.png", cyan.data(), cyan.size());

    f.spellings = {
        {"dotdot", "../@", false},
        {"sub_dotdot", "sub/../../@", false},
        {"pct_dots", "%2e%2e/@", false},
        {"pct_all_upper", "%2E%2E%2F@", false},
        {"pct_slash", "..%2f@", false},
        {"backslash", "..\\@", true},
        {"pct_backslash", "..%5c@", true},
        {"dot_dotdot", "./../@", false},
        {"sub_pct_dots", "sub/%2e%2e/%2e%2e/@", false},
        {"double_pct", "%252e%252e/@", true},
        {"abs_real", R + "/@", false},
        {"abs_pct", "%2F" + R.substr(1) + "/@", false},
        {"etc_passwd", "/etc/passwd", false},
        {"abs_fake", "/abs/path/to/outside/file", false},
        {"file_url", "file://" + R + "/@", false},
        {"file_rel", "file:../@", false},
        {"http", "http://127.0.0.1:1/@", false},
        {"drive", "C:/@", false},
        {"unc", "//host/@", false},
        {"nul_pct", "#%00/../../@", false},
        {"nul_raw", std::string("#") + '\0' + "/../../@", false},
        {"symlink_file", "link_@", false},
        {"symlink_dir_rel", "link_up/@", false},
        {"symlink_dir_abs", "link_root/@", false},
        {"tilde", "~/../@", true}, // "~" is a folder name: back inside, no such file
    };
    struct stat sb;
    uint64_t passwd_size = stat("/etc/passwd", &sb) == 0 ? uint64_t(sb.st_size) : 64;
    for (const spelling &s : f.spellings) {
        std::string bin_uri = s.uri("outside.bin", "inside.bin");
        uint64_t len = s.label == "etc_passwd" ? passwd_size : OUTSIDE_BIN_SIZE;
        f.text("trav_buf_" + s.label + ".gltf", colour_doc(bin_uri, len).json(),
               "buffer 1 (COLOR_0) uri " + s.label, s.may_be_missing ? "refused (INVALID_ASSET or IO) naming buffers[1].uri" : REFUSE_BUF);
        std::string img_uri = s.uri("outside.png", "inside.png");
        f.text("trav_img_" + s.label + ".gltf", textured_doc("{\"uri\":" + json_string(img_uri) + "}").json(),
               "image 0 uri " + s.label, DEGRADE_IMG);
    }
    // a declared byteLength that disagrees with the outside file's size
    f.text("trav_buf_dotdot_length.gltf", colour_doc("../outside.bin", 64).json(),
           "buffer 1 ../outside.bin, byteLength 64 (the file has 30012)", REFUSE_BUF + ", no size in the message");
    // the same refusals where the outside file does not exist: the messages must not differ (no existence oracle)
    f.text("trav_buf_dotdot_nonexistent.gltf", colour_doc("../no_such_outside.bin", OUTSIDE_BIN_SIZE).json(),
           "buffer 1 ../no_such_outside.bin (no such file outside)", REFUSE_BUF + ", as for an existing file");
    f.text("trav_buf_symlink_dangling.gltf", colour_doc("link_dangling.bin", OUTSIDE_BIN_SIZE).json(),
           "buffer 1 a symlink to a missing file outside", REFUSE_BUF + ", as for an existing target");
    f.text("trav_img_dotdot_nonexistent.gltf", textured_doc("{\"uri\":\"../no_such_outside.png\"}").json(),
           "image 0 ../no_such_outside.png", DEGRADE_IMG + ", as for an existing file");
    f.text("trav_img_symlink_dangling.gltf", textured_doc("{\"uri\":\"link_dangling.png\"}").json(),
           "image 0 a symlink to a missing file outside", DEGRADE_IMG + ", as for an existing target");
    // positive controls: the same bytes inside the folder do reach the pixels (the magenta detector works)
    write_bytes(f.asset + "/magenta_inside.png", magenta.data(), magenta.size());
    write_bytes(f.asset + "/magenta_inside.bin", outside_bin.data(), outside_bin.size());
    f.text("control_magenta_image.gltf", textured_doc("{\"uri\":\"magenta_inside.png\"}").json(),
           "control: the outside PNG's bytes inside the folder", "loads, draws magenta");
    f.text("control_magenta_buffer.gltf", colour_doc("magenta_inside.bin", OUTSIDE_BIN_SIZE).json(),
           "control: the outside .bin's bytes inside the folder", "loads, draws magenta");
    f.text("reference.gltf", textured_doc("", false).json(), "the untextured quad (reference)", "loads");
    f.text("cwd_buf.gltf", colour_doc("only_in_cwd.bin", OUTSIDE_BIN_SIZE).json(),
           "buffer 1 uri names a file only in the current directory", "refused (IO) naming buffers[1].uri");
    f.text("cwd_img.gltf", textured_doc("{\"uri\":\"only_in_cwd.png\"}").json(),
           "image 0 uri names a file only in the current directory", DEGRADE_IMG);

    // ---- spoofed images
    std::vector<uint8_t> orange_jpg = solid_image("jpg", 16, 16, 255, 128, 0);
    std::vector<uint8_t> orange_png = solid_image("png", 16, 16, 255, 128, 0);
    write_bytes(f.asset + "/jpeg_named.png", orange_jpg.data(), orange_jpg.size());
    f.text("spoof_jpeg_as_png.gltf", textured_doc("{\"uri\":\"jpeg_named.png\"}").json(),
           "JPEG bytes in a file named .png, no mimeType", "loads, decoded as JPEG (by signature)");
    f.text("spoof_jpeg_mime_png.gltf", textured_doc("{\"uri\":\"jpeg_named.png\",\"mimeType\":\"image/png\"}").json(),
           "JPEG bytes, mimeType image/png", "loads, images[0] left out (mimeType disagrees)");
    {
        std::vector<uint8_t> bin;
        doc d;
        int v = put_view(d, bin, 0, orange_jpg.data(), orange_jpg.size());
        d.add(d.images, "{\"bufferView\":" + std::to_string(v) + ",\"mimeType\":\"image/png\"}");
        d.add(d.textures, "{\"source\":0}");
        one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, unlit(d, 0))});
        while (bin.size() % 4)
            bin.push_back(0);
        d.buffers.push_back("{\"byteLength\":" + std::to_string(bin.size()) + "}");
        f.bytes("spoof_glb_jpeg_mime_png.glb", glb({json_chunk(d.json()), chunk{BIN_CHUNK, bin}}),
                "GLB bufferView image: JPEG bytes, mimeType image/png", "loads, images[0] left out");
    }
    f.text("spoof_data_uri_png_jpeg.gltf",
           textured_doc("{\"uri\":\"data:image/png;base64," + gen::base64(orange_jpg.data(), orange_jpg.size()) + "\"}").json(),
           "data:image/png URI holding JPEG bytes", "safe either way (informational)");
    write_text(f.asset + "/text.png", "This is not a PNG, it is a text file pretending to be one.\n");
    f.text("spoof_text_png.gltf", textured_doc("{\"uri\":\"text.png\"}").json(), "a text file named .png",
           "loads, images[0] left out");
    {
        std::vector<uint8_t> mp4 = {0, 0, 0, 0x18, 'f', 't', 'y', 'p', 'i', 's', 'o', 'm', 0, 0, 2, 0,
                                    'i', 's', 'o', 'm', 'i', 's', 'o', '2', 0, 0, 0x10, 0, 'm', 'd', 'a', 't'};
        std::vector<uint8_t> avi = {'R', 'I', 'F', 'F', 0, 0x10, 0, 0, 'A', 'V', 'I', ' ', 'L', 'I', 'S', 'T'};
        uint32_t seed = 7;
        for (int i = 0; i < 4096; ++i) {
            seed = seed * 1664525u + 1013904223u;
            mp4.push_back(uint8_t(seed >> 24));
            avi.push_back(uint8_t(seed >> 16));
        }
        write_bytes(f.asset + "/movie.mp4", mp4.data(), mp4.size());
        write_bytes(f.asset + "/movie.avi", avi.data(), avi.size());
        write_bytes(f.asset + "/movie_named.png", mp4.data(), mp4.size());
    }
    f.text("spoof_mp4.gltf", textured_doc("{\"uri\":\"movie.mp4\"}").json(), "an MP4 (ftyp box, random data) as image",
           "loads, images[0] left out, no video decoder");
    f.text("spoof_avi.gltf", textured_doc("{\"uri\":\"movie.avi\"}").json(), "an AVI (RIFF header, random data) as image",
           "loads, images[0] left out, no video decoder");
    f.text("spoof_mp4_mime_video.gltf", textured_doc("{\"uri\":\"movie.mp4\",\"mimeType\":\"video/mp4\"}").json(),
           "an MP4 with mimeType video/mp4", "loads, images[0] left out");
    f.text("spoof_mp4_named_png.gltf", textured_doc("{\"uri\":\"movie_named.png\"}").json(), "MP4 bytes named .png",
           "loads, images[0] left out");

    // ---- image bombs
    std::vector<uint8_t> bomb = png_bomb(16384, 16384);
    write_bytes(f.asset + "/bomb_16k.png", bomb.data(), bomb.size());
    f.text("bomb_png_16k.gltf", textured_doc("{\"uri\":\"bomb_16k.png\"}").json(),
           "a PNG of a few hundred bytes whose IHDR says 16384 x 16384 (1 GiB RGBA)",
           "with memory_budget 64 MiB: OUT_OF_MEMORY naming images[0], memory_budget");
    f.text("bomb_png_16k_data_uri.gltf",
           textured_doc("{\"uri\":\"data:image/png;base64," + gen::base64(bomb.data(), bomb.size()) + "\"}").json(),
           "the same PNG bomb in a data URI", "with memory_budget 64 MiB: OUT_OF_MEMORY naming images[0]");
    std::vector<uint8_t> bomb_huge = png_bomb(100000, 100000);
    write_bytes(f.asset + "/bomb_100k.png", bomb_huge.data(), bomb_huge.size());
    f.text("bomb_png_100k.gltf", textured_doc("{\"uri\":\"bomb_100k.png\"}").json(),
           "a PNG whose IHDR says 100000 x 100000 (40 GB RGBA)", "refused or left out, naming images[0]; no allocation");
    std::vector<uint8_t> jbomb = jpeg_bomb(16000, 16000);
    write_bytes(f.asset + "/bomb_16k.jpg", jbomb.data(), jbomb.size());
    f.text("bomb_jpeg_16k.gltf", textured_doc("{\"uri\":\"bomb_16k.jpg\"}").json(),
           "a JPEG whose SOF says 16000 x 16000", "with memory_budget 64 MiB: OUT_OF_MEMORY naming images[0]");
    {
        std::vector<uint8_t> glbbin;
        doc d = glb_doc(glbbin, &bomb);
        f.bytes("bomb_png_16k.glb", glb({json_chunk(d.json()), chunk{BIN_CHUNK, glbbin}}),
                "the PNG bomb in a GLB bufferView", "with memory_budget 64 MiB: OUT_OF_MEMORY naming images[0]");
    }

    // ---- shared images and buffers
    std::vector<uint8_t> green = solid_image("png", 64, 64, 40, 220, 60);
    write_bytes(f.asset + "/shared.png", green.data(), green.size());
    write_bytes(f.asset + "/sub/shared_sub.png", green.data(), green.size());
    {
        doc d;
        std::vector<uint8_t> bin;
        std::vector<std::string> prims;
        for (int i = 0; i < 8; ++i) {
            d.add(d.images, "{\"uri\":\"shared.png\"}");
            d.add(d.textures, "{\"source\":" + std::to_string(i) + "}");
            prims.push_back(quad(d, bin, 0, -1.5f + float(i % 4), i < 4 ? -0.5f : 0.5f, 0.4f, unlit(d, i)));
        }
        one_mesh(d, prims);
        d.buffers.insert(d.buffers.begin(), data_buffer(bin));
        f.text("same_png_x8.gltf", d.json(), "8 images (8 textures, 8 materials) with uri shared.png",
               "loads, images_decoded == 1");
        // the same file spelled four ways
        const char *uris[4] = {"shared.png", "./shared.png", "shared%2Epng", "sub/../shared.png"};
        for (int i = 0; i < 4; ++i)
            d.images[size_t(i)] = std::string("{\"uri\":\"") + uris[i] + "\"}";
        for (int i = 4; i < 8; ++i)
            d.images[size_t(i)] = std::string("{\"uri\":\"") + uris[i - 4] + "\"}";
        f.text("same_png_spellings.gltf", d.json(), "8 images naming shared.png in four spellings",
               "loads, images_decoded == 1 (the same file)");
    }
    {
        // geometry split over 4 buffers that all name geom.bin
        doc d;
        std::vector<uint8_t> bin;
        std::string prim = quad(d, bin, 0, 0, 0, 0.5f, unlit(d, -1, 0.9f, 0.9f, 0.2f));
        // quad() put POSITION, NORMAL, TEXCOORD_0, indices in views 0..3: one buffer each
        for (int v = 0; v < 4; ++v)
            d.buffer_views[size_t(v)] =
                replace_all(d.buffer_views[size_t(v)], "\"buffer\":0", "\"buffer\":" + std::to_string(v));
        one_mesh(d, {prim});
        write_bytes(f.asset + "/geom.bin", bin.data(), bin.size());
        for (int b = 0; b < 4; ++b)
            d.buffers.push_back(uri_buffer("geom.bin", bin.size()));
        f.text("same_bin_x4.gltf", d.json(), "4 buffers with uri geom.bin, each read by a bufferView",
               "loads, buffers_read == 1");
    }

    // ---- huge counts and files
    {
        doc d;
        int pos = put_accessor(d, -1, FLOAT, 16000000, "VEC3", ",\"min\":[0,0,0],\"max\":[0,0,0]");
        d.add(d.meshes, "{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}]}");
        d.add(d.nodes, "{\"mesh\":0}");
        d.add(d.scenes, "{\"nodes\":[0]}");
        f.text("zeros_16m_positions.gltf", d.json(), "POSITION: 16M VEC3 float, no bufferView (zeros, 192 MB)",
               "with memory_budget 64 MiB: OUT_OF_MEMORY, memory_budget");
        d.accessors[0] = replace_all(d.accessors[0], "16000000", "4000000");
        f.text("zeros_4m_positions.gltf", d.json(), "POSITION: 4M VEC3 float, no bufferView (zeros, 48 MB)",
               "loads; the accounting covers what the process took");
    }
    {
        doc d;
        std::vector<uint8_t> bin;
        int idx = put_accessor(d, -1, UINT, 16000000, "SCALAR");
        one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, -1, "", idx)});
        d.buffers.push_back(data_buffer(bin));
        f.text("zeros_16m_indices.gltf", d.json(), "indices: 16M u32, no bufferView (zeros, 64 MB)",
               "with memory_budget 64 MiB: OUT_OF_MEMORY, memory_budget");
    }
    sparse_file(f.asset + "/huge.bin", 3 * GiB);
    f.text("huge_sparse_bin.gltf", colour_doc("huge.bin", 3 * GiB).json(),
           "buffer 1: a 3 GiB sparse file, byteLength 3 GiB, read by COLOR_0",
           "refused before reading (max_file_bytes or memory_budget), naming buffers[1]");
    sparse_file(f.asset + "/big100m.bin", 100 * MiB);
    f.text("big_100m_bin.gltf", colour_doc("big100m.bin", 100 * MiB).json(),
           "buffer 1: a 100 MiB sparse file read by COLOR_0",
           "loads by default; memory_budget 64 MiB: OUT_OF_MEMORY naming buffers[1]");

    {
        // 1M JSON numbers (2 MB of text): the parsed JSON is counted before it is parsed
        doc d = textured_doc("", false);
        std::string zeros;
        zeros.reserve(2 * MiB + 16);
        for (int i = 0; i < 1000000; ++i)
            zeros += i ? ",0" : "0";
        d.extra = ",\"extras\":[" + zeros + "]";
        f.text("json_tokens_1m.gltf", d.json(), "1M numbers in extras (2 MB of JSON)",
               "loads by default; memory_budget 16 MiB: OUT_OF_MEMORY, memory_budget");
    }
    {
        // three real 2048x2048 PNGs in three files: 16 MiB each decoded; a
        // 72 MiB budget holds the decoding of one, not all three
        std::vector<uint8_t> big = solid_image("png", 2048, 2048, 200, 40, 40);
        std::vector<std::string> images;
        for (int i = 0; i < 3; ++i) {
            std::string name = "big2k_" + std::to_string(i) + ".png";
            write_bytes(f.asset + "/" + name, big.data(), big.size());
            images.push_back("{\"uri\":\"" + name + "\"}");
        }
        f.text("images_2k_x3.gltf", image_row_doc(images).json(),
               "three distinct 2048x2048 PNGs (16 MiB each decoded)",
               "loads by default; memory_budget 72 MiB: OUT_OF_MEMORY naming images[1] or [2] (the budget adds up)");
    }

    // ---- lying GLB chunks
    std::vector<uint8_t> bin;
    doc gd = glb_doc(bin, &orange_png);
    std::string gj = gd.json();
    f.bytes("glb_ok.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}}), "a valid GLB with its image in a bufferView",
            "loads, renders the image");
    {
        chunk c{BIN_CHUNK, bin};
        c.length_delta = 1000;
        f.bytes("glb_bin_past_end.glb", glb({json_chunk(gj), c}), "BIN chunk length 1000 past the file", "refused, GLB");
        c.length_delta = 8;
        f.bytes("glb_bin_counts_header.glb", glb({json_chunk(gj), c}), "BIN chunk length counts its own 8-byte header",
                "refused, GLB");
        chunk j = json_chunk(gj + " ");
        while (j.data.size() % 4 != 1)
            j.data.push_back(' ');
        j.pad = false;
        f.bytes("glb_json_unaligned.glb", glb({j, chunk{BIN_CHUNK, bin}}), "JSON chunk length 4k+1 (BIN unaligned)",
                "refused, GLB");
        f.bytes("glb_total_too_big.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}}, 100),
                "header total length 100 past the file", "refused, GLB");
        f.bytes("glb_total_too_small.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}}, -16),
                "header total length 16 short: BIN chunk ends past it", "refused, GLB");
        chunk huge = json_chunk(gj);
        huge.length_delta = 0xFFFFFFF0ll - (long long)((gj.size() + 3) / 4 * 4);
        f.bytes("glb_json_length_huge.glb", glb({huge, chunk{BIN_CHUNK, bin}}), "JSON chunk length 0xFFFFFFF0",
                "refused, GLB");
        std::vector<uint8_t> unknown(20, 0xAB);
        f.bytes("glb_unknown_chunk.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}, chunk{0x4B4E4B55u, unknown}}),
                "a chunk of unknown type after BIN", "loads (unknown chunks are ignored), renders");
        f.bytes("glb_two_bin.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, bin}, chunk{BIN_CHUNK, bin}}),
                "two BIN chunks", "refused, GLB");
        f.bytes("glb_bin_first.glb", glb({chunk{BIN_CHUNK, bin}, json_chunk(gj)}), "BIN chunk before JSON",
                "refused, GLB");
        f.bytes("glb_json_empty.glb", glb({json_chunk("")}), "JSON chunk of length 0", "refused");
        f.bytes("glb_header_only.glb", glb({}), "a 12-byte GLB header, no chunk", "refused, GLB");
    }
    {
        // buffer 1 uri-less too, read by COLOR_0
        doc d = gd;
        d.buffers.push_back("{\"byteLength\":64}");
        d.add(d.buffer_views, "{\"buffer\":1,\"byteOffset\":0,\"byteLength\":64}");
        int colour = put_accessor(d, int(d.buffer_views.size()) - 1, FLOAT, 4, "VEC4");
        d.meshes[0] = replace_all(d.meshes[0], "\"TEXCOORD_0\":", "\"COLOR_0\":" + std::to_string(colour) + ",\"TEXCOORD_0\":");
        f.bytes("glb_extra_uriless_buffer.glb", glb({json_chunk(d.json()), chunk{BIN_CHUNK, bin}}),
                "a second uri-less buffer, read by COLOR_0", "refused naming buffers[1]");
        f.bytes("glb_no_bin_chunk.glb", glb({json_chunk(gj)}), "buffer 0 uri-less and used, no BIN chunk",
                "refused naming buffers[0] (or GLB)");
        std::vector<uint8_t> short_bin(bin.begin(), bin.begin() + long(bin.size() / 2));
        f.bytes("glb_bin_shorter_than_buffer.glb", glb({json_chunk(gj), chunk{BIN_CHUNK, short_bin}}),
                "BIN chunk half of buffer 0's byteLength", "refused naming buffers[0] (or GLB)");
    }

    // ---- node graphs and nesting
    auto graph = [&](const std::string &name, const std::vector<std::string> &nodes, const std::string &scene,
                     const std::string &what, const std::string &expect) {
        doc d;
        std::vector<uint8_t> b;
        d.add(d.meshes, "{\"primitives\":[" + quad(d, b, 0, 0, 0, 0.5f, unlit(d, -1)) + "]}");
        d.buffers.push_back(data_buffer(b));
        d.nodes = nodes;
        if (!scene.empty())
            d.scenes = {scene};
        f.text(name, d.json(), what, expect);
    };
    graph("graph_cycle.gltf", {"{\"mesh\":0,\"children\":[1]}", "{\"children\":[0]}"}, "{\"nodes\":[0]}",
          "nodes 0 -> 1 -> 0", "refused naming nodes[");
    graph("graph_self_child.gltf", {"{\"mesh\":0,\"children\":[0]}"}, "{\"nodes\":[0]}", "node 0 its own child",
          "refused naming nodes[0]");
    graph("graph_child_twice.gltf", {"{\"mesh\":0,\"children\":[1,1]}", "{\"mesh\":0}"}, "{\"nodes\":[0]}",
          "node 1 listed twice in node 0's children", "refused naming nodes[1]");
    graph("graph_root_twice.gltf", {"{\"mesh\":0}"}, "{\"nodes\":[0,0]}", "node 0 twice in the scene's roots",
          "refused naming nodes[0]");
    graph("graph_cycle_unreachable.gltf", {"{\"mesh\":0}", "{\"children\":[2]}", "{\"children\":[1]}"},
          "{\"nodes\":[0]}", "a cycle 1 <-> 2 the scene does not reach", "loads or refused; no hang");
    graph("graph_cycle_no_scene.gltf", {"{\"mesh\":0,\"children\":[1]}", "{\"children\":[0]}"}, "",
          "no scenes, every node in a cycle (no root)", "loads or refused; no hang");
    {
        std::vector<std::string> chain;
        for (int i = 0; i < 1999; ++i)
            chain.push_back("{\"children\":[" + std::to_string(i + 1) + "],\"translation\":[0,0,0]}");
        chain.push_back("{\"mesh\":0}");
        graph("graph_chain_2000.gltf", chain, "{\"nodes\":[0]}", "a node chain 2000 deep",
              "loads and renders, or refused naming nodes[; no crash");
        chain.clear();
        for (int i = 0; i < 99999; ++i)
            chain.push_back("{\"children\":[" + std::to_string(i + 1) + "]}");
        chain.push_back("{\"mesh\":0}");
        graph("graph_chain_100k.gltf", chain, "{\"nodes\":[0]}", "a node chain 100000 deep",
              "loads or refused naming nodes[; no stack overflow");
    }
    {
        std::string deep = "{\"asset\":{\"version\":\"2.0\"},\"extras\":" + std::string(100000, '[') +
                           std::string(100000, ']') + "}";
        f.text("deep_json_100k.gltf", deep, "JSON arrays nested 100000 deep", "refused; no stack overflow");
        std::string deep_obj = "{\"asset\":{\"version\":\"2.0\"},\"extras\":";
        for (int i = 0; i < 100000; ++i)
            deep_obj += "{\"a\":";
        deep_obj += "0" + std::string(100000, '}') + "}";
        f.text("deep_json_objects_100k.gltf", deep_obj, "JSON objects nested 100000 deep", "refused; no stack overflow");
        f.bytes("deep_json_100k.glb", glb({json_chunk(deep)}), "the 100000-deep JSON in a GLB", "refused");
    }

    // ---- long strings
    f.long_value = letters(1536 * 1024, 12345);
    const std::string &L = f.long_value;
    f.text("long_buffer_uri.gltf", colour_doc(L + ".bin", 64).json(), "buffer 1 uri 1.5 MB long",
           "refused naming buffers[1].uri, message short");
    f.text("long_image_uri.gltf", textured_doc("{\"uri\":" + json_string(L + ".png") + "}").json(),
           "image 0 uri 1.5 MB long",
           "loads, images[0] left out, warning short");
    {
        doc d = textured_doc("", false);
        d.nodes[0] = "{\"mesh\":0,\"name\":" + json_string(L) + "}";
        d.meshes[0] = replace_all(d.meshes[0], "{\"primitives\"", "{\"name\":" + json_string(L) + ",\"primitives\"");
        f.text("long_names.gltf", d.json(), "node and mesh names 1.5 MB long", "loads");
        doc e = textured_doc("", false);
        e.ext_required = e.ext_used;
        e.ext_required.push_back(L);
        e.ext_used.push_back(L);
        f.text("long_ext_required.gltf", e.json(), "a required extension named by 1.5 MB", "UNSUPPORTED, message short");
        doc u = textured_doc("", false);
        u.ext_used.push_back(L);
        f.text("long_ext_used.gltf", u.json(), "an optional extension named by 1.5 MB", "loads, warning short");
        doc c = textured_doc("", false);
        c.cameras.push_back("{\"type\":" + json_string(L) + "}");
        f.text("long_camera_type_unused.gltf", c.json(), "an unused camera of type (1.5 MB)", "loads, warning short");
        c.nodes.push_back("{\"camera\":0}");
        c.scenes[0] = "{\"nodes\":[0,1]}";
        f.text("long_camera_type_used.gltf", c.json(), "a used camera of type (1.5 MB)", "refused naming cameras[0], short");
        doc m = textured_doc("{\"uri\":\"shared.png\",\"mimeType\":" + json_string(L) + "}");
        f.text("long_mime_type.gltf", m.json(), "image 0 mimeType 1.5 MB long", "left out or refused, message short");
    }
    f.long_b64_value = base64_letters(50 * 1024, 999);
    f.long_b64_value[25000] = '*'; // not a base64 character: malformed
    f.text("bad_data_uri_image_50k.gltf",
           textured_doc("{\"uri\":\"data:image/png;base64," + f.long_b64_value + "\"}").json(),
           "image 0: a malformed 50 KB base64 data URI", "loads, images[0] left out, warning short");
    f.text("bad_data_uri_buffer_50k.gltf",
           colour_doc("data:application/octet-stream;base64," + f.long_b64_value, 64).json(),
           "buffer 1: a malformed 50 KB base64 data URI", "refused naming buffers[1], message short");
    f.text("bad_data_uri_buffer_unpadded.gltf",
           colour_doc("data:application/octet-stream;base64," + base64_letters(50 * 1024 + 1, 998), 64).json(),
           "buffer 1: 50 KB of base64 whose length is 1 mod 4 (cannot be base64)", "informational");

    // ---- valid files the loader must accept
    {
        doc d = textured_doc("", false);
        d.buffers.push_back("{\"byteLength\":1024}");
        f.text("valid_unused_uriless_buffer.gltf", d.json(), ".gltf with a uri-less buffer nothing reads", "loads");
        doc h = textured_doc("", false);
        h.buffers.push_back("{\"byteLength\":64,\"uri\":\"http://127.0.0.1:1/x.bin\"}");
        f.text("valid_unused_http_buffer.gltf", h.json(), "an http:// buffer nothing reads", "loads, buffers_read == 1");
        doc r = textured_doc("", false);
        r.buffers.push_back("{\"byteLength\":" + std::to_string(OUTSIDE_BIN_SIZE) + ",\"uri\":\"../outside.bin\"}");
        f.text("valid_unused_outside_buffer.gltf", r.json(), "a ../ buffer nothing reads", "loads, buffers_read == 1");
    }
    {
        doc d;
        std::vector<uint8_t> b;
        int idx = put_accessor(d, -1, USHORT, 6, "SCALAR");
        one_mesh(d, {quad(d, b, 0, 0, 0, 0.5f, unlit(d, -1), "", idx)});
        d.buffers.push_back(data_buffer(b));
        f.text("valid_indices_without_view.gltf", d.json(), "indices accessor without bufferView (all 0)",
               "loads, draws nothing");
    }
    {
        doc d = textured_doc("", false, 0.2f, 0.6f, 0.9f);
        doc p = d;
        std::vector<uint8_t> b;
        doc q;
        quad(q, b, 0, 0, 0, 0.5f, -1);
        std::string enc;
        for (uint8_t c : b) {
            char x[4];
            if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '.')
                enc += char(c);
            else
                std::snprintf(x, sizeof x, "%%%02X", c), enc += x;
        }
        p.buffers[0] = "{\"byteLength\":" + std::to_string(b.size()) + ",\"uri\":\"data:application/octet-stream," + enc + "\"}";
        f.text("valid_base64_buffer.gltf", d.json(), "the quad, buffer as a base64 data URI", "loads");
        f.text("valid_plain_data_uri.gltf", p.json(), "the quad, buffer as a percent-encoded (non-base64) data URI",
               "loads, renders like the base64 one");
    }
    {
        doc d = textured_doc("", false);
        d.cameras.push_back("{\"type\":\"perspective\",\"perspective\":{\"yfov\":0,\"znear\":-1}}");
        d.lights.push_back("{\"type\":\"area\",\"intensity\":-5}");
        d.lights.push_back("{\"type\":\"point\",\"intensity\":-5,\"range\":-1}");
        d.use("KHR_lights_punctual");
        f.text("valid_unused_bad_camera_light.gltf", d.json(),
               "unused camera yfov 0 / znear -1, unused lights type area / intensity -5", "loads, warnings");
        d.nodes.push_back("{\"camera\":0}");
        d.scenes[0] = "{\"nodes\":[0,1]}";
        f.text("used_bad_camera.gltf", d.json(), "a node uses the camera with yfov 0", "refused naming cameras[0]");
    }
    f.text("valid_missing_texture.gltf", textured_doc("{\"uri\":\"not_there.png\"}", true, 0.9f, 0.3f, 0.2f).json(),
           "image 0 file missing, baseColorFactor red", "loads, images[0] left out, renders the factor");
    f.text("valid_missing_texture_reference.gltf", textured_doc("", false, 0.9f, 0.3f, 0.2f).json(),
           "the same without texture (reference)", "loads");
    {
        doc d;
        std::vector<uint8_t> b;
        d.add(d.images, "{\"uri\":\"shared.png\"}");
        d.add(d.textures, "{\"source\":0}");
        d.add(d.textures, "{\"source\":0}");
        int m0 = unlit(d, 0), m1 = unlit(d, 1, 0.5f, 0.5f, 1);
        one_mesh(d, {quad(d, b, 0, -0.5f, 0, 0.4f, m0), quad(d, b, 0, 0.5f, 0, 0.4f, m1)});
        d.buffers.insert(d.buffers.begin(), data_buffer(b));
        f.text("valid_shared_texture.gltf", d.json(), "two materials, two textures, one image",
               "loads, images_decoded == 1");
    }
    f.text("valid_inside_dotdot.gltf", textured_doc("{\"uri\":\"sub/../shared.png\"}").json(),
           "image uri sub/../shared.png (stays inside)", "loads, decoded");
    write_bytes(f.asset + "/my tex.png", orange_png.data(), orange_png.size());
    f.text("valid_percent_space.gltf", textured_doc("{\"uri\":\"my%20tex.png\"}").json(),
           "image uri my%20tex.png (file 'my tex.png')", "loads, decoded");
    f.text("widen_allowed_root.gltf", textured_doc("{\"uri\":\"../shared_textures/a.png\"}").json(),
           "image ../shared_textures/a.png", "left out by default; decoded with allowed_root = the parent");
    {
        doc d;
        std::vector<uint8_t> b;
        d.add(d.images, "{\"uri\":\"tex%20ture.png\"}");
        d.add(d.textures, "{\"source\":0}");
        std::string prim = quad(d, b, 0, 0, 0, 0.5f, unlit(d, 0));
        d.buffers.push_back(uri_buffer("geo%20data.bin", b.size()));
        one_mesh(d, {prim});
        f.text("widen_read_callback.gltf", d.json(), "buffer geo%20data.bin, image tex%20ture.png (neither on disk)",
               "fails by default; loads through file_access.read");
        write_bytes(f.asset + "/callback_geometry.bin", b.data(), b.size()); // what the callback serves
        // with file_access.read: absolute paths and schemes never reach it; query and fragment are cut
        std::vector<std::string> images;
        for (const char *uri : {"/abs/x.png", "http://127.0.0.1:1/x.png", "tex%20ture.png?v=2#f"})
            images.push_back("{\"uri\":" + json_string(uri) + "}");
        f.text("widen_read_callback_refused.gltf", image_row_doc(images).json(), "images /abs/x.png, http://..., tex%20ture.png?v=2#f",
               "file_access.read sees only 'tex ture.png'");
        doc e = textured_doc("{\"uri\":\"%2e%2e/x.png\"}");
        f.text("widen_read_callback_dotdot.gltf", e.json(), "image %2e%2e/x.png",
               "file_access.read receives ../x.png (confinement is the caller's)");
    }

    anim_files(f);
    codec_files(f);   // hostile_codecs.cpp: compressed geometry, extension messages
    variant_files(f); // hostile_variants.cpp: KHR_materials_variants
    material_ext_files(f); // hostile_material_ext.cpp: the PBR extensions
    ktx2_files(f);

    std::string index = "file\twhat\texpect\n";
    for (const auto &h : f.list)
        index += h.name + "\t" + h.what + "\t" + h.expect + "\n";
    write_text(R + "/index.tsv", index);
    return f;
}

int write_files_command(const char *dir)
{
    try {
        files f = write_all(dir);
        std::printf("io_hostile: %zu hostile files in %s (listed in %s/index.tsv)\n", f.list.size(), f.asset.c_str(),
                    f.root.c_str());
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "io_hostile: %s\n", e.what());
        return 1;
    }
}

}  // namespace hostile
