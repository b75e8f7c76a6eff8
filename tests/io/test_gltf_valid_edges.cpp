// io_gltf_valid_edges: files the glTF 2.0 specification and its JSON schema
// allow, as in the Khronos glTF-Validator's test suite, that tinygltf 2.7
// refuses and the loader's pre-pass (core/io/gltf_prepass.cpp) now lets
// through; and, beside each, the same construct where it is really wrong,
// still refused with a message naming the object:
// - an accessor type the schema's anyOf admits as "any string" (VEC5) in an
//   accessor nobody reads; a primitive that reads it is refused;
// - integers written with a fraction of zero ("count": 3.0): JSON Schema's
//   "integer" is any number whose fractional part is zero; 3.5 is refused;
// - an animation sampler's input (its times) without a bufferView: zeros,
//   as any accessor without one (glTF 2.0, 3.6.2.1), sparse or not;
// - a buffer without uri in a .gltf: valid, with no data; a bufferView that
//   is read from it is refused.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "gltf_gen.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

namespace {

struct loaded {
    mvr_result r = MVR_ERROR_INTERNAL;
    std::string msg;
    mvr_scene *scene = nullptr;
    mvr_scene_info si = {};
    explicit loaded(const std::string &json)
    {
        mvr_error err = {};
        r = mvr_gltf_load_memory(json.data(), json.size(), nullptr, &scene, nullptr, &err);
        msg = r == MVR_OK ? "" : err.message;
        if (scene)
            mvr_scene_get_info(scene, &si);
    }
    loaded(const loaded &) = delete;
    loaded &operator=(const loaded &) = delete;
    ~loaded() { mvr_scene_destroy(scene); }
    bool has(const char *part) const { return msg.find(part) != std::string::npos; }
};

// One triangle's positions (x in 0..2, y in 0..1) and, after them, four
// floats an extra accessor may read: 40 + 16 bytes in a data URI.
std::string triangle_buffer()
{
    const float f[13] = {0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 1, 2, 3};
    std::vector<uint8_t> b(56, 0);
    std::memcpy(b.data(), f, sizeof f);
    return "{\"byteLength\":56,\"uri\":\"data:application/octet-stream;base64," + gen::base64(b.data(), b.size()) +
           "\"}";
}

// A document around one triangle: buffer 0 (more buffers after it),
// bufferView 0 its positions and bufferView 1 the four floats after them,
// accessor 0 the positions and `accessors` after it, a mesh whose primitive
// has `attributes` beside POSITION, one node, one scene; `extra` members last.
std::string doc(const std::string &accessors, const std::string &attributes = "", const std::string &buffers = "",
                const std::string &extra = "")
{
    return "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[" + triangle_buffer() + buffers +
           "],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":16}],"
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
           "\"min\":[0,0,0],\"max\":[2,1,0]}" +
           accessors + "],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0" + attributes +
           "}}]}],\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0" + extra + "}";
}

void loads_one_triangle(mvr_test_state *t, const loaded &l, const char *label)
{
    CHECK_MSG(t, l.r == MVR_OK, "%s: %s %s", label, mvr_result_name(l.r), l.msg.c_str());
    if (l.r != MVR_OK)
        return;
    CHECK_MSG(t, l.si.meshes == 1 && l.si.nodes == 1, "%s: %u meshes, %u nodes", label, l.si.meshes, l.si.nodes);
    CHECK_MSG(t, l.si.bounds_min[0] == 0 && l.si.bounds_max[0] == 2 && l.si.bounds_max[1] == 1,
              "%s: bounds x %g..%g y ..%g", label, l.si.bounds_min[0], l.si.bounds_max[0], l.si.bounds_max[1]);
}

void unknown_accessor_type(mvr_test_state *t)
{
    // unused: loads
    const std::string vec5 = ",{\"bufferView\":1,\"componentType\":5126,\"count\":1,\"type\":\"VEC5\"}";
    loaded unused(doc(vec5));
    loads_one_triangle(t, unused, "unused VEC5 accessor");
    // read as a primitive's attribute: refused, naming the accessor and its type
    loaded used(doc(vec5, ",\"TEXCOORD_0\":1"));
    CHECK_MSG(t, used.r == MVR_ERROR_INVALID_ASSET && used.has("accessor 1") && used.has("VEC5"), "used VEC5: %s %s",
              mvr_result_name(used.r), used.msg.c_str());
    CHECK(t, used.scene == nullptr);
}

void integers_written_as_floats(mvr_test_state *t)
{
    // every integer of the file with ".0": indices, counts, offsets, enums
    std::string d = "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[" + triangle_buffer() +
                    "],\"bufferViews\":[{\"buffer\":0.0,\"byteOffset\":0.0,\"byteLength\":36.0}],"
                    "\"accessors\":[{\"bufferView\":0.0,\"byteOffset\":0.0,\"componentType\":5126.0,\"count\":3.0,"
                    "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[2.0,1.0,0.0]}],"
                    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0.0},\"mode\":4.0}]}],"
                    "\"nodes\":[{\"mesh\":0.0}],\"scenes\":[{\"nodes\":[0.0]}],\"scene\":0.0}";
    // the buffer's byteLength too (mvr's own pre-pass read it as an integer)
    size_t at = d.find("\"byteLength\":56");
    d.replace(at, 15, "\"byteLength\":56.0");
    loaded l(d);
    loads_one_triangle(t, l, "integers as 3.0");
    // a fraction is not an integer: still refused
    std::string half = d;
    at = half.find("\"count\":3.0");
    half.replace(at, 11, "\"count\":3.5");
    loaded h(half);
    CHECK_MSG(t, h.r != MVR_OK && h.scene == nullptr, "count 3.5: %s", mvr_result_name(h.r));
}

// Animations on node 0 whose times come from an accessor without a
// bufferView, as the glTF-Validator's animation/valid.gltf has them.
void times_without_a_buffer_view(mvr_test_state *t)
{
    // accessor 1: two times, no bufferView (both 0; min / max as the file
    // says them); accessor 2: two scales, no bufferView either (zeros)
    const std::string keys = ",{\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\",\"min\":[0],\"max\":[1]}"
                             ",{\"componentType\":5126,\"count\":2,\"type\":\"VEC3\"}";
    const std::string anim = ",\"animations\":[{\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":"
                             "\"scale\"}}],\"samplers\":[{\"input\":1,\"output\":2,\"interpolation\":\"LINEAR\"}]}]";
    loaded one(doc(keys, "", "", anim));
    loads_one_triangle(t, one, "two keys at time 0 without a bufferView");
    if (one.scene) {
        CHECK_MSG(t, mvr_scene_animation_count(one.scene) == 1, "%u animations", mvr_scene_animation_count(one.scene));
        mvr_animation_info ai = {};
        CHECK(t, mvr_scene_get_animation_info(one.scene, 0, &ai) == MVR_OK && ai.start == 0 && ai.end == 0 &&
                     ai.samplers == 1 && ai.channels == 1);
    }
    // the same two zero times read from a bufferView: not increasing, refused
    const std::string zeros_in_view = ",{\"bufferView\":1,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\"}"
                                      ",{\"componentType\":5126,\"count\":2,\"type\":\"VEC3\"}";
    std::string zv = doc(zeros_in_view, "", "", anim);
    // bufferView 1 starts with 0, 1: make it start with 0, 0 by reading from
    // the positions' first floats instead (bufferView 0: 0, 0, 0, ...)
    zv.replace(zv.find("\"bufferView\":1,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\""), 14,
               "\"bufferView\":0");
    loaded bad(zv);
    CHECK_MSG(t, bad.r == MVR_ERROR_INVALID_ASSET && bad.has("samplers[0].input") && bad.has("increase strictly"),
              "zero times in a bufferView: %s %s", mvr_result_name(bad.r), bad.msg.c_str());
    // two times without a bufferView made 0, 1 by a sparse substitution
    // (its index and value in buffer 1): the times as given
    std::vector<uint8_t> sparse(8, 0);
    const uint16_t index = 1;
    const float value = 1.0f;
    std::memcpy(sparse.data(), &index, 2);
    std::memcpy(sparse.data() + 4, &value, 4);
    std::string buf2 = ",{\"byteLength\":8,\"uri\":\"data:application/octet-stream;base64," +
                       gen::base64(sparse.data(), sparse.size()) + "\"}";
    std::string d = doc(",{\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\",\"min\":[0],\"max\":[1],"
                        "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":2,\"componentType\":5123},"
                        "\"values\":{\"bufferView\":3}}}"
                        ",{\"bufferView\":4,\"componentType\":5126,\"count\":2,\"type\":\"VEC3\"}",
                        "", buf2, anim);
    // views 2 and 3 (the sparse parts) and 4 (the six translation floats: 0, 0, 0, 2, 0, 0)
    size_t at = d.find("],\"accessors\"");
    d.insert(at, ",{\"buffer\":1,\"byteLength\":2},{\"buffer\":1,\"byteOffset\":4,\"byteLength\":4},"
                 "{\"buffer\":0,\"byteLength\":24}");
    loaded two(d);
    loads_one_triangle(t, two, "sparse times without a bufferView");
    if (two.scene) {
        CHECK_MSG(t, mvr_scene_animation_count(two.scene) == 1, "%u animations", mvr_scene_animation_count(two.scene));
        mvr_animation_info ai = {};
        CHECK(t, mvr_scene_get_animation_info(two.scene, 0, &ai) == MVR_OK && ai.end == 1.0);
    }
}

void buffer_without_uri(mvr_test_state *t)
{
    // unused: a buffer with no data, valid in a .gltf
    loaded unused(doc("", "", ",{\"byteLength\":16}"));
    loads_one_triangle(t, unused, "a buffer without uri, unused");
    // read: refused, naming the buffer
    std::string d = doc(",{\"bufferView\":2,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}",
                        ",\"TEXCOORD_0\":1", ",{\"byteLength\":24}");
    size_t at = d.find("],\"accessors\"");
    d.insert(at, ",{\"buffer\":1,\"byteLength\":24}");
    loaded used(d);
    CHECK_MSG(t, used.r == MVR_ERROR_INVALID_ASSET && used.has("buffers[1]") && used.has("no uri"),
              "a buffer without uri, read: %s %s", mvr_result_name(used.r), used.msg.c_str());
}

}  // namespace

MVR_TEST_MAIN(TEST(unknown_accessor_type), TEST(integers_written_as_floats), TEST(times_without_a_buffer_view),
              TEST(buffer_without_uri))
