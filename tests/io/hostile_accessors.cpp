// io_hostile's accessor files and their case (see hostile_accessors.hpp).
// One quad whose POSITION accessor (accessor 0, bufferView 0) carries a
// sparse substitution moving vertices 1 and 2 to x = 3 (glTF 2.0, 3.6.2.3);
// each file breaks one member of it.
#include "hostile_accessors.hpp"

#include <cstdint>
#include <functional>
#include <string>

#include "hostile_check.hpp"
#include "hostile_docs.hpp"

namespace hostile {

namespace {

struct sparse_quad {
    doc d;
    int indices_view = -1, values_view = -1;
};

// The quad with sparse indices i0, i1 (u16) and values x = 3.
sparse_quad make_sparse_quad(uint16_t i0, uint16_t i1)
{
    sparse_quad q;
    std::vector<uint8_t> bin;
    std::string prim = quad(q.d, bin, 0, 0, 0, 0.5f, -1);
    const uint16_t idx[2] = {i0, i1};
    const float values[6] = {3, -0.5f, 0, 3, 0.5f, 0};
    q.indices_view = put_view(q.d, bin, 0, idx, sizeof idx);
    q.values_view = put_view(q.d, bin, 0, values, sizeof values);
    q.d.accessors[0].pop_back();   // '}'
    q.d.accessors[0] += ",\"sparse\":{\"count\":2,\"indices\":{\"bufferView\":" + std::to_string(q.indices_view) +
                        ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(q.values_view) + "}}}";
    one_mesh(q.d, {prim});
    q.d.buffers.push_back(data_buffer(bin));
    return q;
}

}  // namespace

void accessor_files(files &f)
{
    const std::string A = "acc_";
    f.text(A + "sparse_valid.gltf", make_sparse_quad(1, 2).d.json(),
           "a quad whose POSITION moves vertices 1, 2 to x = 3 by sparse substitution", "loads, bounds reach x = 3");
    auto variant = [&](const std::string &name, const std::string &what, const std::string &naming,
                       const std::function<void(sparse_quad &)> &change, uint16_t i0 = 1, uint16_t i1 = 2) {
        sparse_quad q = make_sparse_quad(i0, i1);
        change(q);
        f.text(A + name, q.d.json(), what, "refused naming " + naming, naming);
    };
    auto none = [](sparse_quad &) {};
    auto sparse_member = [](const std::string &from, const std::string &to) {
        return [from, to](sparse_quad &q) { q.d.accessors[0] = replace_all(q.d.accessors[0], from, to); };
    };
    // glTF 2.0, accessor.sparse.indices: "strictly increasing"
    variant("sparse_decreasing.gltf", "sparse indices 2, 1",
            "accessor 0.sparse.indices[1] = 1 is not greater than indices[0] = 2", none, 2, 1);
    variant("sparse_repeated.gltf", "sparse indices 1, 1",
            "accessor 0.sparse.indices[1] = 1 is not greater than indices[0] = 1", none, 1, 1);
    // negative offsets and strides: the schema's minimum is 0
    variant("offset_negative.gltf", "accessor 0 byteOffset -12", "accessors[0].byteOffset is '-12'",
            [](sparse_quad &q) {
                q.d.accessors[0] = replace_all(q.d.accessors[0], "\"bufferView\":0,", "\"bufferView\":0,\"byteOffset\":-12,");
            });
    variant("view_offset_negative.gltf", "bufferView 0 byteOffset -4", "bufferViews[0].byteOffset is '-4'",
            [](sparse_quad &q) { q.d.buffer_views[0] = replace_all(q.d.buffer_views[0], "\"byteOffset\":0", "\"byteOffset\":-4"); });
    variant("view_stride_negative.gltf", "bufferView 0 byteStride -12", "bufferViews[0].byteStride is '-12'",
            [](sparse_quad &q) { q.d.buffer_views[0].insert(1, "\"byteStride\":-12,"); });
    variant("sparse_indices_offset_negative.gltf", "sparse indices byteOffset -2",
            "accessors[0].sparse.indices.byteOffset is '-2'", sparse_member("\"componentType\":5123}", "\"componentType\":5123,\"byteOffset\":-2}"));
    variant("sparse_values_offset_negative.gltf", "sparse values byteOffset -12",
            "accessors[0].sparse.values.byteOffset is '-12'", [](sparse_quad &q) {
                std::string v = "\"values\":{\"bufferView\":" + std::to_string(q.values_view);
                q.d.accessors[0] = replace_all(q.d.accessors[0], v, v + ",\"byteOffset\":-12");
            });
    // what tinygltf narrows to int: 2^31 wraps negative, 2^32 + 1 to 1, 2^32 to 0
    variant("sparse_count_2p31.gltf", "sparse count 2147483648 (4 vertices)",
            "accessors[0].sparse.count is '2147483648', not an integer in 1..4", sparse_member("\"count\":2,", "\"count\":2147483648,"));
    variant("sparse_count_2p32_plus_1.gltf", "sparse count 4294967297 (tinygltf reads 1)",
            "accessors[0].sparse.count is '4294967297'", sparse_member("\"count\":2,", "\"count\":4294967297,"));
    variant("sparse_count_5.gltf", "sparse count 5 (4 vertices)", "accessors[0].sparse.count is '5', not an integer in 1..4",
            sparse_member("\"count\":2,", "\"count\":5,"));
    variant("sparse_indices_offset_2p32.gltf", "sparse indices byteOffset 4294967296 (tinygltf reads 0)",
            "accessors[0].sparse.indices.byteOffset is '4294967296'",
            sparse_member("\"componentType\":5123}", "\"componentType\":5123,\"byteOffset\":4294967296}"));
    variant("view_index_2p32.gltf", "accessor 0 bufferView 4294967296 (tinygltf reads 0)",
            "accessors[0].bufferView is '4294967296'", sparse_member("{\"bufferView\":0,", "{\"bufferView\":4294967296,"));
}

void accessor_offsets_and_sparse_are_checked(mvr_test_state *t)
{
    const files &f = F();
    outcome ok = load(t, f.path("acc_sparse_valid.gltf"), defaults());
    CHECK_MSG(t, ok.r == MVR_OK, "acc_sparse_valid: %s", ok.msg.c_str());
    if (ok.scene) {
        mvr_scene_info info;
        mvr_scene_get_info(ok.scene, &info);
        CHECK_MSG(t, info.bounds_max[0] == 3.0 && info.bounds_min[0] == -0.5,
                  "acc_sparse_valid: x in %g..%g, expected -0.5..3 (the sparse values applied)", info.bounds_min[0],
                  info.bounds_max[0]);
    }
    size_t refused = check_refusals(t, f, "acc_");
    CHECK_MSG(t, refused == 12, "%zu acc_* files to be refused, expected 12", refused);
    // no count prints wrapped
    outcome w = load(t, f.path("acc_sparse_count_2p31.gltf"), defaults());
    CHECK_MSG(t, !has(w.msg, "-2147483648"), "acc_sparse_count_2p31: %s", w.msg.c_str());
}

}  // namespace hostile
