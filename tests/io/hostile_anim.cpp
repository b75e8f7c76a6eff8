// io_hostile's skin, morph target and animation files and their case (see
// hostile_anim.hpp).
#include "hostile_anim.hpp"

#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "hostile_check.hpp"
#include "hostile_docs.hpp"

namespace hostile {

// Skins, morph targets and animations: anim_doc (valid) and each way of
// breaking it, refused naming the object; the unknown-path files load.
void anim_files(files &f)
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
    // (zeros read from a bufferView: an accessor without one is all zeros,
    // which glTF allows, and keeps its last key: io_gltf_valid_edges)
    variant(A + "times_not_increasing.gltf", "sampler 0's input: 3 keys at 0 s (zeros in a bufferView)",
            "animations[0].samplers[0].input: accessor", [&](doc &d) {
                std::vector<uint8_t> bin2;
                const float zeros[3] = {0, 0, 0};
                int z = put_accessor(d, put_view(d, bin2, 1, zeros, sizeof zeros), FLOAT, 3, "SCALAR");
                d.buffers.push_back(data_buffer(bin2));
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

// Skins, morph targets and animations (anim_*, above): each
// broken file refused with a message naming the object; the valid one loads
// (and renders); unknown channel paths are warned about once each.
void skins_morphs_and_animations_are_checked(mvr_test_state *t)
{
    const files &f = F();
    size_t refused = check_refusals(t, f, "");
    CHECK_MSG(t, refused >= 30, "%zu anim_* files refused", refused);
    {
        outcome o = load(t, f.path("anim_valid.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.warnings.empty(), "anim_valid: %s %s", o.msg.c_str(),
                  o.warnings.empty() ? "" : o.warnings[0].c_str());
        if (o.scene) {
            mvr_scene_info si;
            mvr_scene_get_info(o.scene, &si);
            CHECK(t, si.skins == 1 && si.joints == 2 && si.morph_targets == 2 && si.animations == 1);
            mvr_animation_info ai;
            CHECK(t, mvr_scene_get_animation_info(o.scene, 0, &ai) == MVR_OK && std::strcmp(ai.name, "wave") == 0 &&
                         ai.start == 0 && ai.end == 1 && ai.channels == 3 && ai.samplers == 3);
            CHECK(t, mvr_scene_apply_animation(o.scene, 0, 0.75, MVR_ANIMATION_LOOP) == MVR_OK);
            std::vector<uint8_t> px = render(t, o.scene, "anim_valid");
            CHECK_MSG(t, px.empty() || drawn(px) > 50, "anim_valid: %zu pixels drawn", drawn(px));
        }
    }
    {
        outcome o = load(t, f.path("anim_unknown_paths.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "anim_unknown_paths: %s", o.msg.c_str());
        CHECK_EQ_INT(t, o.info.animation_channels_ignored, 3);
        size_t pointer = 0, colour = 0;
        for (const auto &w : o.warnings) {
            pointer += has(w, "target path 'pointer' (KHR_animation_pointer) is not implemented; channel ignored");
            colour += has(w, "target path 'color' is not implemented");
        }
        CHECK_MSG(t, pointer == 1 && colour == 1 && o.warnings.size() == 2, "%zu pointer, %zu color warnings of %zu",
                  pointer, colour, o.warnings.size());
        CHECK(t, o.warnings.empty() || has(o.warnings[0], "animations[0].channels[3]"));
        mvr_animation_info ai;
        CHECK(t, o.scene && mvr_scene_get_animation_info(o.scene, 0, &ai) == MVR_OK && ai.channels == 3);
    }
    {
        outcome o = load(t, f.path("anim_pointer_without_node.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK, "anim_pointer_without_node: %s", o.msg.c_str());
        CHECK_EQ_INT(t, o.info.animation_channels_ignored, 1);
        CHECK(t, o.warned("KHR_animation_pointer"));
    }
}

}  // namespace hostile
