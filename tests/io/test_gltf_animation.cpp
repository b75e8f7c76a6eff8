// io_gltf_animation: skins, morph targets and animations from glTF files
// this test writes itself (tests/io/gltf_gen.*): what loads, what the scene
// then holds (skins, joints, targets, animations with their names and
// ranges), that a channel drives its node (through camera nodes, whose world
// pose mvr_scene_camera_view gives), what is warned about once, and that
// the samplers' keys are charged to the load's memory budget. The refusals
// of broken files: io_hostile (tests/io/hostile_files.cpp, anim_*).
#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "gltf_gen.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

namespace {

const int UBYTE = 5121, SHORT = 5122, USHORT = 5123, FLOAT = 5126;

std::string dir()
{
    std::string d = MVR_GLTF_ANIMATION_DIR;
    mkdir(d.c_str(), 0777);
    return d;
}

struct logged {
    std::vector<std::string> warnings;
    size_t count(const std::string &part) const
    {
        size_t n = 0;
        for (const auto &w : warnings)
            n += w.find(part) != std::string::npos;
        return n;
    }
};

void on_log(mvr_log_level level, mvr_log_id, const char *message, void *user)
{
    if (level == MVR_LOG_WARNING)
        static_cast<logged *>(user)->warnings.push_back(message);
}

struct loaded {
    mvr_result r = MVR_ERROR_INTERNAL;
    std::string msg;
    mvr_scene *scene = nullptr;
    mvr_gltf_info info = {};
    logged log;
    mvr_scene_info si = {};
    loaded() = default;
    loaded(const loaded &) = delete;
    loaded &operator=(const loaded &) = delete;
    ~loaded() { mvr_scene_destroy(scene); }
};

// Loads path; the scene's info when it loads.
void load(loaded &l, const std::string &path, uint32_t scene = 0, uint64_t budget = 0)
{
    mvr_gltf_options o;
    std::memset(&o, 0, sizeof o);
    o.logger.fn = on_log;
    o.logger.user_data = &l.log;
    o.logger.level = MVR_LOG_DEBUG;
    o.scene = scene;
    o.memory_budget = budget;
    mvr_error err;
    l.r = mvr_gltf_load_file(path.c_str(), &o, &l.scene, &l.info, &err);
    l.msg = l.r == MVR_OK ? "" : err.message;
    if (l.scene)
        mvr_scene_get_info(l.scene, &l.si);
}

template <typename T>
int put(gen::builder &b, const std::vector<T> &v, int ctype, long long count, const char *type, bool normalized = false,
        const std::string &extra = "")
{
    return b.accessor(b.view(v.data(), v.size() * sizeof(T)), 0, ctype, count, type, normalized, extra);
}

std::string S(int i)
{
    return std::to_string(i);
}

// A quad (4 vertices, 2 triangles) facing +z; its primitive's JSON with
// `extra` attributes and members (targets) appended.
std::string quad(gen::builder &b, const std::string &extra_attributes = "", const std::string &extra_members = "",
                 bool normals = false)
{
    int pos = b.floats({-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0}, "VEC3");
    int idx = b.indices16({0, 1, 2, 0, 2, 3});
    std::string n = normals ? ",\"NORMAL\":" + S(b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")) : "";
    return "{\"attributes\":{\"POSITION\":" + S(pos) + n + extra_attributes + "},\"indices\":" + S(idx) +
           extra_members + "}";
}

// ---- (a) SimpleSkin: a strip of 4 quads up y, 2 joints (node 1 the root,
// node 2 its child at y = 1), joints and weights as (normalized) bytes
std::string simple_skin(gen::container c, const std::string &name)
{
    gen::builder b;
    std::vector<float> pos;
    std::vector<uint16_t> idx;
    std::vector<uint8_t> joints, weights;
    for (int r = 0; r < 5; ++r) {
        for (float x : {-0.5f, 0.5f}) {
            pos.insert(pos.end(), {x, 0.5f * float(r), 0});
            joints.insert(joints.end(), {0, 1, 0, 0});
            uint8_t w1 = uint8_t(r * 255 / 4);
            weights.insert(weights.end(), {uint8_t(255 - w1), w1, 0, 0});
        }
        if (r < 4) {
            uint16_t k = uint16_t(2 * r);
            idx.insert(idx.end(), {k, uint16_t(k + 1), uint16_t(k + 3), k, uint16_t(k + 3), uint16_t(k + 2)});
        }
    }
    int ap = b.floats(pos, "VEC3");
    int ai = b.indices16(idx);
    int aj = put(b, joints, UBYTE, 10, "VEC4");
    int aw = put(b, weights, UBYTE, 10, "VEC4", true);
    std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
    int aibm = put(b, ibm, FLOAT, 2, "MAT4");
    b.add(b.meshes, "{\"primitives\":[{\"attributes\":{\"POSITION\":" + S(ap) + ",\"JOINTS_0\":" + S(aj) +
                        ",\"WEIGHTS_0\":" + S(aw) + "},\"indices\":" + S(ai) + "}]}");
    b.add(b.nodes, "{\"mesh\":0,\"skin\":0}");
    b.add(b.nodes, "{\"children\":[2]}");
    b.add(b.nodes, "{\"translation\":[0,1,0]}");
    b.add(b.scenes, "{\"nodes\":[0,1]}");
    b.add(b.skins, "{\"inverseBindMatrices\":" + S(aibm) + ",\"joints\":[1,2]}");
    // SimpleSkin's animation: joint 1 bends about z and back
    std::vector<float> times = {0, 1, 2};
    std::vector<float> rot = {0, 0, 0, 1, 0, 0, 0.3826834f, 0.9238795f, 0, 0, 0, 1};
    int at = put(b, times, FLOAT, 3, "SCALAR", false, ",\"min\":[0],\"max\":[2]");
    int ar = put(b, rot, FLOAT, 3, "VEC4");
    b.add(b.animations, "{\"samplers\":[{\"input\":" + S(at) + ",\"output\":" + S(ar) +
                            "}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":2,\"path\":\"rotation\"}}]}");
    return b.write(dir(), name, c);
}

void skins_load(mvr_test_state *t)
{
    const struct {
        gen::container c;
        const char *name;
    } files[] = {{gen::container::data_uri, "simple_skin"}, {gen::container::glb, "simple_skin_glb"},
                 {gen::container::external_bin, "simple_skin_bin"}};
    for (const auto &f : files) {
        loaded l;
        load(l, simple_skin(f.c, f.name));
        CHECK_MSG(t, l.r == MVR_OK, "%s: %s", f.name, l.msg.c_str());
        if (!l.scene)
            continue;
        CHECK_EQ_INT(t, l.si.skins, 1);
        CHECK_EQ_INT(t, l.si.joints, 2);
        CHECK_EQ_INT(t, l.si.nodes, 3);
        CHECK_EQ_INT(t, l.si.animations, 1);
        CHECK_EQ_INT(t, l.si.morph_targets, 0);
        CHECK_MSG(t, l.info.warnings == 0 && l.log.warnings.empty(), "%s: %u warnings, first: %s", f.name,
                  l.info.warnings, l.log.warnings.empty() ? "" : l.log.warnings[0].c_str());
        mvr_animation_info ai;
        CHECK(t, mvr_scene_get_animation_info(l.scene, 0, &ai) == MVR_OK);
        CHECK(t, ai.start == 0 && ai.end == 2 && ai.channels == 1 && ai.samplers == 1 && ai.name &&
                     std::strcmp(ai.name, "") == 0);
        CHECK(t, mvr_scene_apply_animation(l.scene, 0, 1.0, MVR_ANIMATION_CLAMP) == MVR_OK);
    }
}

// Two sets of influences load; a third is warned about once and ignored; a
// node with a skin whose mesh has no joints draws as usual.
void influence_sets(mvr_test_state *t)
{
    gen::builder b;
    std::vector<uint16_t> j(16, 0);
    std::vector<float> w0 = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    std::vector<float> wz(16, 0.0f);
    int aj = put(b, j, USHORT, 4, "VEC4");
    int aw = b.floats(w0, "VEC4");
    int az = b.floats(wz, "VEC4");
    std::string sets = ",\"JOINTS_0\":" + S(aj) + ",\"WEIGHTS_0\":" + S(aw) + ",\"JOINTS_1\":" + S(aj) +
                       ",\"WEIGHTS_1\":" + S(az) + ",\"JOINTS_2\":" + S(aj) + ",\"WEIGHTS_2\":" + S(az) +
                       ",\"JOINTS_3\":" + S(aj) + ",\"WEIGHTS_3\":" + S(az);
    b.add(b.meshes, "{\"primitives\":[" + quad(b, sets) + "]}");
    b.add(b.meshes, "{\"primitives\":[" + quad(b) + "]}");
    b.add(b.nodes, "{\"mesh\":0,\"skin\":0}");
    b.add(b.nodes, "{}");
    b.add(b.nodes, "{\"mesh\":1,\"skin\":0,\"translation\":[2,0,0]}");
    b.add(b.scenes, "{\"nodes\":[0,1,2]}");
    b.add(b.skins, "{\"joints\":[1]}");   // no inverseBindMatrices: identities
    loaded l;
    load(l, b.write(dir(), "influence_sets", gen::container::data_uri));
    CHECK_MSG(t, l.r == MVR_OK, "%s", l.msg.c_str());
    CHECK_EQ_INT(t, l.si.skins, 1);
    CHECK_EQ_INT(t, l.si.joints, 1);
    CHECK_EQ_INT(t, l.log.warnings.size(), 1);
    CHECK_MSG(t, l.log.count("8 influences") == 1 && l.log.count("JOINTS_2") == 1, "%s",
              l.log.warnings.empty() ? "(no warning)" : l.log.warnings[0].c_str());
}

// ---- (b) SimpleMorph: a quad with two POSITION targets, mesh.weights [0.5, 0.25]
void morph_targets_load(mvr_test_state *t)
{
    std::vector<float> up = {0, 0, 0, 0, 0, 0, 0, 0.5f, 0, 0, 0.5f, 0};
    std::vector<float> right = {0, 0, 0, 0.5f, 0, 0, 0.5f, 0, 0, 0, 0, 0};
    {
        gen::builder b;
        int t0 = b.floats(up, "VEC3"), t1 = b.floats(right, "VEC3");
        std::string targets = ",\"targets\":[{\"POSITION\":" + S(t0) + "},{\"POSITION\":" + S(t1) + "}]";
        b.add(b.meshes, "{\"primitives\":[" + quad(b, "", targets) + "],\"weights\":[0.5,0.25]}");
        b.add(b.nodes, "{\"mesh\":0}");
        b.add(b.nodes, "{\"mesh\":0,\"weights\":[1,0],\"translation\":[2,0,0]}");
        b.add(b.scenes, "{\"nodes\":[0,1]}");
        loaded l;
        load(l, b.write(dir(), "simple_morph", gen::container::glb));
        CHECK_MSG(t, l.r == MVR_OK, "simple_morph: %s", l.msg.c_str());
        CHECK_EQ_INT(t, l.si.morph_targets, 2);
        CHECK_EQ_INT(t, l.si.meshes, 1);
        CHECK_EQ_INT(t, l.info.warnings, 0);
    }
    {   // two primitives of two targets each (4 in all); normals moved by one
        // target only (the other's are zeros); a quantized target (normalized
        // shorts, KHR_mesh_quantization)
        gen::builder b;
        int t0 = b.floats(up, "VEC3"), t1 = b.floats(right, "VEC3");
        int n0 = b.floats({0, 0, 0, 0, 0, 0, 0.1f, 0, 0, 0.1f, 0, 0}, "VEC3");
        std::vector<int16_t> q = {0, 0, 0, 0, 0, 0, 0, 16384, 0, 0, 16384, 0};
        int tq = put(b, q, SHORT, 4, "VEC3", true);
        std::string p0 = quad(b, "", ",\"targets\":[{\"POSITION\":" + S(t0) + ",\"NORMAL\":" + S(n0) +
                                         "},{\"POSITION\":" + S(t1) + "}]", true);
        std::string p1 = quad(b, "", ",\"targets\":[{\"POSITION\":" + S(tq) + "},{\"POSITION\":" + S(t1) + "}]");
        b.add(b.meshes, "{\"primitives\":[" + p0 + "," + p1 + "]}");
        b.add(b.nodes, "{\"mesh\":0}");
        b.add(b.scenes, "{\"nodes\":[0]}");
        b.ext_used.push_back("KHR_mesh_quantization");
        b.ext_required.push_back("KHR_mesh_quantization");
        loaded l;
        load(l, b.write(dir(), "morph_two_primitives", gen::container::data_uri));
        CHECK_MSG(t, l.r == MVR_OK, "morph_two_primitives: %s", l.msg.c_str());
        CHECK_EQ_INT(t, l.si.morph_targets, 4);
        CHECK_EQ_INT(t, l.si.primitives, 2);
        CHECK_MSG(t, l.info.warnings == 0, "%u warnings, first: %s", l.info.warnings,
                  l.log.warnings.empty() ? "" : l.log.warnings[0].c_str());
    }
    {   // TEXCOORD_0 deltas (not implemented) in both targets: one warning;
        // NORMAL deltas on a primitive without normals: dropped, one warning
        gen::builder b;
        int t0 = b.floats(up, "VEC3"), t1 = b.floats(right, "VEC3");
        int uv = b.floats({0, 0, 0.1f, 0, 0.1f, 0.1f, 0, 0.1f}, "VEC2");
        std::string targets = ",\"targets\":[{\"POSITION\":" + S(t0) + ",\"TEXCOORD_0\":" + S(uv) + ",\"NORMAL\":" +
                              S(t1) + "},{\"POSITION\":" + S(t1) + ",\"TEXCOORD_0\":" + S(uv) + ",\"NORMAL\":" + S(t0) +
                              "}]";
        b.add(b.meshes, "{\"primitives\":[" + quad(b, "", targets) + "]}");
        b.add(b.nodes, "{\"mesh\":0}");
        b.add(b.scenes, "{\"nodes\":[0]}");
        loaded l;
        load(l, b.write(dir(), "morph_ignored_deltas", gen::container::data_uri));
        CHECK_MSG(t, l.r == MVR_OK, "morph_ignored_deltas: %s", l.msg.c_str());
        CHECK_EQ_INT(t, l.si.morph_targets, 2);
        CHECK_EQ_INT(t, l.log.warnings.size(), 2);
        CHECK_EQ_INT(t, l.log.count("'TEXCOORD_0' are not implemented"), 1);
        CHECK_EQ_INT(t, l.log.count("has no NORMAL"), 1);
    }
}

// ---- (c) an animation: translation LINEAR (float), rotation CUBICSPLINE
// (normalized shorts), weights STEP; cameras on the animated nodes show
// their world pose
std::string walk_file(const std::string &name)
{
    gen::builder b;
    std::vector<float> up = {0, 0, 0, 0, 0, 0, 0, 0.5f, 0, 0, 0.5f, 0};
    int t0 = b.floats(up, "VEC3"), t1 = b.floats(up, "VEC3");
    b.add(b.meshes, "{\"primitives\":[" +
                        quad(b, "", ",\"targets\":[{\"POSITION\":" + S(t0) + "},{\"POSITION\":" + S(t1) + "}]") +
                        "],\"weights\":[0,0]}");
    b.add(b.cameras, "{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1}}");
    b.add(b.nodes, "{\"camera\":0,\"translation\":[0,0,10]}");            // 0: moved by translation
    b.add(b.nodes, "{\"camera\":0,\"translation\":[0,0,5]}");             // 1: turned by rotation
    b.add(b.nodes, "{\"mesh\":0}");                                       // 2: morphed by weights
    b.add(b.scenes, "{\"nodes\":[0,1,2]}");
    int tt = b.floats({0, 1, 2}, "SCALAR");
    int tv = b.floats({0, 0, 0, 2, 0, 0, 2, 4, 0}, "VEC3");
    int rt = b.floats({0.5f, 1.5f, 3}, "SCALAR");
    // per key: in-tangent, value, out-tangent; tangents 0, values: identity,
    // 90 degrees about y, 180 degrees about y
    std::vector<int16_t> rv = {0, 0, 0, 0, 0, 0, 0, 32767, 0, 0, 0, 0,
                               0, 0, 0, 0, 0, 23170, 0, 23170, 0, 0, 0, 0,
                               0, 0, 0, 0, 0, 32767, 0, 0, 0, 0, 0, 0};
    int rq = put(b, rv, SHORT, 9, "VEC4", true);
    int wt = b.floats({0.25f, 1}, "SCALAR");
    int wv = b.floats({1, 0, 0, 1}, "SCALAR");
    b.add(b.animations,
          "{\"name\":\"walk\",\"samplers\":[{\"input\":" + S(tt) + ",\"output\":" + S(tv) + ",\"interpolation\":\"LINEAR\"},"
          "{\"input\":" + S(rt) + ",\"output\":" + S(rq) + ",\"interpolation\":\"CUBICSPLINE\"},"
          "{\"input\":" + S(wt) + ",\"output\":" + S(wv) + ",\"interpolation\":\"STEP\"}],"
          "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}},"
          "{\"sampler\":1,\"target\":{\"node\":1,\"path\":\"rotation\"}},"
          "{\"sampler\":2,\"target\":{\"node\":2,\"path\":\"weights\"}}]}");
    return b.write(dir(), name, gen::container::external_bin);
}

bool near3(const double *a, double x, double y, double z)
{
    return std::fabs(a[0] - x) < 1e-5 && std::fabs(a[1] - y) < 1e-5 && std::fabs(a[2] - z) < 1e-5;
}

void animations_load_and_drive_nodes(mvr_test_state *t)
{
    loaded l;
    load(l, walk_file("walk"));
    CHECK_MSG(t, l.r == MVR_OK, "walk: %s", l.msg.c_str());
    if (!l.scene)
        return;
    CHECK_EQ_INT(t, l.info.warnings, 0);
    CHECK_EQ_INT(t, l.info.animation_channels_ignored, 0);
    CHECK_EQ_INT(t, mvr_scene_animation_count(l.scene), 1);
    CHECK_EQ_INT(t, l.si.animations, 1);
    mvr_animation_info ai;
    CHECK(t, mvr_scene_get_animation_info(l.scene, 0, &ai) == MVR_OK);
    CHECK_MSG(t, ai.name && std::strcmp(ai.name, "walk") == 0, "name %s", ai.name ? ai.name : "(null)");
    CHECK_MSG(t, ai.start == 0 && ai.end == 3, "start %g end %g", ai.start, ai.end);
    CHECK(t, ai.channels == 3 && ai.samplers == 3);
    uint32_t found = 99;
    CHECK(t, mvr_scene_find_animation(l.scene, "walk", &found) == MVR_OK && found == 0);

    mvr_node_id mover = mvr_scene_camera_node(l.scene, 0), turner = mvr_scene_camera_node(l.scene, 1);
    mvr_view_desc v;
    auto pose = [&](mvr_node_id n) {
        std::memset(&v, 0, sizeof v);
        return mvr_scene_camera_view(l.scene, n, &v) == MVR_OK;
    };
    CHECK(t, pose(mover) && near3(v.position, 0, 0, 10));
    CHECK(t, mvr_scene_apply_animation(l.scene, 0, 0.5, MVR_ANIMATION_CLAMP) == MVR_OK);
    CHECK_MSG(t, pose(mover) && near3(v.position, 1, 0, 0), "t 0.5: %g %g %g", v.position[0], v.position[1], v.position[2]);
    CHECK(t, mvr_scene_apply_animation(l.scene, 0, 1.5, MVR_ANIMATION_CLAMP) == MVR_OK);
    CHECK_MSG(t, pose(mover) && near3(v.position, 2, 2, 0), "t 1.5: %g %g %g", v.position[0], v.position[1], v.position[2]);
    // at a key of the CUBICSPLINE sampler: its value, dequantized (23170 / 32767) and normalised
    CHECK(t, pose(turner));
    double s = std::sqrt(0.5);
    CHECK_MSG(t, std::fabs(std::fabs(v.orientation[1]) - s) < 1e-4 && std::fabs(std::fabs(v.orientation[3]) - s) < 1e-4 &&
                     std::fabs(v.orientation[0]) < 1e-6 && std::fabs(v.orientation[2]) < 1e-6,
              "t 1.5 orientation %g %g %g %g", v.orientation[0], v.orientation[1], v.orientation[2], v.orientation[3]);
    CHECK(t, near3(v.position, 0, 0, 5));
    CHECK(t, mvr_scene_apply_animation(l.scene, 0, 10, MVR_ANIMATION_CLAMP) == MVR_OK);
    CHECK(t, pose(mover) && near3(v.position, 2, 4, 0));
    mvr_scene_reset_pose(l.scene);
    CHECK(t, pose(mover) && near3(v.position, 0, 0, 10));
}

// A channel on a node outside the loaded scene is left out without a
// warning; an animation left with no channel keeps its index.
void channels_outside_the_scene(mvr_test_state *t)
{
    gen::builder b;
    b.add(b.meshes, "{\"primitives\":[" + quad(b) + "]}");
    b.add(b.nodes, "{\"mesh\":0}");
    b.add(b.nodes, "{\"mesh\":0}");
    b.add(b.scenes, "{\"nodes\":[0]}");
    b.add(b.scenes, "{\"nodes\":[1]}");
    int tt = b.floats({0, 1}, "SCALAR");
    int tv = b.floats({0, 0, 0, 1, 0, 0}, "VEC3");
    std::string sampler = "\"samplers\":[{\"input\":" + S(tt) + ",\"output\":" + S(tv) + "}]";
    b.add(b.animations, "{\"name\":\"other\"," + sampler + ",\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"translation\"}}]}");
    b.add(b.animations, "{\"name\":\"mine\"," + sampler + ",\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}},"
                        "{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"scale\"}}]}");
    std::string path = b.write(dir(), "two_scenes", gen::container::data_uri);
    for (uint32_t sc : {1u, 2u}) {
        loaded l;
        load(l, path, sc);
        CHECK_MSG(t, l.r == MVR_OK, "scene %u: %s", sc, l.msg.c_str());
        if (!l.scene)
            continue;
        CHECK_EQ_INT(t, l.info.warnings, 0);
        CHECK_EQ_INT(t, l.info.animation_channels_ignored, sc == 1 ? 2 : 1);
        CHECK_EQ_INT(t, mvr_scene_animation_count(l.scene), 2);
        mvr_animation_info a0, a1;
        CHECK(t, mvr_scene_get_animation_info(l.scene, 0, &a0) == MVR_OK && std::strcmp(a0.name, "other") == 0);
        CHECK(t, mvr_scene_get_animation_info(l.scene, 1, &a1) == MVR_OK && std::strcmp(a1.name, "mine") == 0);
        CHECK_EQ_INT(t, a0.channels, sc == 1 ? 0 : 1);
        CHECK_EQ_INT(t, a1.channels, 1);
    }
}

// The samplers' keys count against the load's memory budget.
void keys_are_charged(mvr_test_state *t)
{
    const size_t keys = 200000;
    gen::builder b;
    b.add(b.meshes, "{\"primitives\":[" + quad(b) + "]}");
    b.add(b.nodes, "{\"mesh\":0}");
    b.add(b.scenes, "{\"nodes\":[0]}");
    std::vector<float> times(keys), values(keys * 3);
    for (size_t k = 0; k < keys; ++k) {
        times[k] = float(k) / 64.0f;
        values[k * 3] = float(k % 7);
    }
    int tt = b.floats(times, "SCALAR"), tv = b.floats(values, "VEC3");
    b.add(b.animations, "{\"samplers\":[{\"input\":" + S(tt) + ",\"output\":" + S(tv) +
                            "}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}]}");
    std::string path = b.write(dir(), "many_keys", gen::container::external_bin);
    const uint64_t key_bytes = keys * 4 * sizeof(float);
    loaded l;
    load(l, path);
    CHECK_MSG(t, l.r == MVR_OK, "%s", l.msg.c_str());
    // the buffer, the keys as read and the scene's copy of them, all held at once
    CHECK_MSG(t, l.info.memory_peak >= 3 * key_bytes, "peak %llu", (unsigned long long)l.info.memory_peak);
    loaded small;
    load(small, path, 0, l.info.memory_peak - 1);
    CHECK_MSG(t, small.r == MVR_ERROR_OUT_OF_MEMORY && small.msg.find("animations[0]") != std::string::npos, "%s: %s",
              mvr_result_name(small.r), small.msg.c_str());
}

}  // namespace

MVR_TEST_MAIN(TEST(skins_load), TEST(influence_sets), TEST(morph_targets_load), TEST(animations_load_and_drive_nodes),
              TEST(channels_outside_the_scene), TEST(keys_are_charged))
