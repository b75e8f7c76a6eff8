// Skinning attributes (JOINTS_n / WEIGHTS_n), morph targets, mesh and node
// weights, skins and animations (glTF 2.0, 3.7.2.1, 3.7.2.2, 3.7.3, 3.11)
// into the scene's mesh, skin, weights and animation calls. Like the rest of
// the loader: every count, index and reference from the file is checked
// before it is used, and a refusal names the glTF object.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

#include "gltf_convert.hpp"
#include "gltf_internal.hpp"

namespace mvr_gltf {

namespace {

constexpr uint32_t FLOAT = ANY_FLOAT;
constexpr uint32_t I8 = 1u << 0, U8 = 1u << 1, I16 = 1u << 2, U16 = 1u << 3;

std::string str(uint64_t v)
{
    return std::to_string(v);
}

std::string num(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
}

int attribute(const std::map<std::string, int> &attrs, const std::string &name)
{
    auto it = attrs.find(name);
    return it == attrs.end() ? -1 : it->second;
}

// The set number n of an attribute named prefix + n (digits only), or -1.
int set_number(const std::string &name, const std::string &prefix)
{
    if (name.compare(0, prefix.size(), prefix) != 0 || name.size() == prefix.size() || name.size() > prefix.size() + 6)
        return -1;
    int n = 0;
    for (size_t i = prefix.size(); i < name.size(); ++i) {
        if (name[i] < '0' || name[i] > '9')
            return -1;
        n = n * 10 + (name[i] - '0');
    }
    return n;
}

void all_finite(const std::vector<float> &v, int accessor, const std::string &what)
{
    for (float x : v)
        if (!std::isfinite(x))
            refuse(what + ": accessor " + std::to_string(accessor) + " holds NaN or infinite values");
}

std::string elements(const std::vector<float> &v, int comps, int accessor)
{
    return "accessor " + std::to_string(accessor) + " has " + str(v.size() / size_t(comps)) + " elements";
}

bool integer_type(context &cx, int accessor)
{
    return cx.model->accessors[size_t(accessor)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT;
}

}  // namespace

// ------------------------------------------------------------ primitives

void converter::skin_attributes(const tinygltf::Primitive &p, const std::string &pw, size_t vcount, prim_data &d,
                                mesh_facts &facts)
{
    // mvr takes two sets (8 influences per vertex): more are warned about once
    for (const auto &a : p.attributes) {
        int n = std::max(set_number(a.first, "JOINTS_"), set_number(a.first, "WEIGHTS_"));
        if (n >= 2 && !warned_joints2) {
            cx.warn(pw + ".attributes." + a.first + ": mvr uses up to 8 influences per vertex (JOINTS_0/1 and "
                    "WEIGHTS_0/1); further sets are ignored");
            warned_joints2 = true;
        }
    }
    for (int set = 0; set < 2; ++set) {
        std::string jn = "JOINTS_" + str(uint64_t(set)), wn = "WEIGHTS_" + str(uint64_t(set));
        int ja = attribute(p.attributes, jn), wa = attribute(p.attributes, wn);
        if (ja < 0 && wa < 0)
            continue;
        if (ja < 0)
            refuse(pw + ".attributes." + wn + " without " + jn);
        if (wa < 0)
            refuse(pw + ".attributes." + jn + " without " + wn);
        if (set == 1 && d.joints0.empty())
            refuse(pw + ".attributes.JOINTS_1 without JOINTS_0");
        std::string jw = pw + ".attributes." + jn, ww = pw + ".attributes." + wn;
        std::vector<uint16_t> joints = read_joints(cx, ja, jw);
        if (joints.size() / 4 != vcount)
            refuse(jw + ": accessor " + std::to_string(ja) + " has " + str(joints.size() / 4) + " elements, POSITION has " +
                   str(vcount));
        // glTF 2.0, 3.7.2.1: FLOAT, or normalized UNSIGNED_BYTE / UNSIGNED_SHORT
        std::vector<float> weights = read_floats(cx, wa, 4, ww, FLOAT | U8 | U16);
        require_normalized(cx, wa, ww);
        if (weights.size() / 4 != vcount)
            refuse(ww + ": " + elements(weights, 4, wa) + ", POSITION has " + str(vcount));
        for (size_t i = 0; i < weights.size(); ++i)
            if (!std::isfinite(weights[i]) || weights[i] < 0)
                refuse(ww + ": accessor " + std::to_string(wa) + " element " + str(i / 4) +
                       " has a negative, NaN or infinite weight");
        for (uint16_t j : joints)
            if (int(j) > facts.max_joint) {
                facts.max_joint = j;
                facts.joint_attr = jw;
            }
        (set == 0 ? d.joints0 : d.joints1) = std::move(joints);
        (set == 0 ? d.weights0 : d.weights1) = std::move(weights);
    }
}

void converter::morph_targets(const tinygltf::Primitive &p, const std::string &pw, size_t vcount, prim_data &d)
{
    if (p.targets.empty())
        return;
    bool moved[3] = {false, false, false};   // POSITION, NORMAL, TANGENT: some target moves it
    d.targets.resize(p.targets.size());
    for (size_t t = 0; t < p.targets.size(); ++t) {
        std::string tw = pw + ".targets[" + str(t) + "]";
        morph_data &md = d.targets[t];
        for (const auto &a : p.targets[t]) {
            std::string aw = tw + "." + a.first;
            int slot = a.first == "POSITION" ? 0 : a.first == "NORMAL" ? 1 : a.first == "TANGENT" ? 2 : -1;
            if (slot < 0) {
                if (!warned_target_attr) {
                    cx.warn(aw + ": morph target deltas of " + quote(a.first) +
                            " are not implemented (only POSITION, NORMAL, TANGENT); ignored");
                    warned_target_attr = true;
                }
                continue;
            }
            if ((slot == 1 && d.nrm.empty()) || (slot == 2 && d.tan.empty())) {
                if (!warned_target_dropped) {
                    cx.warn(aw + ": the primitive has no " + a.first + ", so there is nothing to move; deltas dropped");
                    warned_target_dropped = true;
                }
                continue;
            }
            // glTF 2.0, 3.7.2.2 and KHR_mesh_quantization: POSITION deltas FLOAT or
            // (normalized or not) BYTE / SHORT; NORMAL and TANGENT deltas FLOAT or
            // normalized BYTE / SHORT; all VEC3 (TANGENT deltas have no w)
            std::vector<float> &out = slot == 0 ? md.pos : slot == 1 ? md.nrm : md.tan;
            out = read_floats(cx, a.second, 3, aw, FLOAT | I8 | I16);
            if (slot != 0)
                require_normalized(cx, a.second, aw);
            if (integer_type(cx, a.second) && !cx.quantization_declared)
                cx.warn(aw + " is quantized but KHR_mesh_quantization is not in extensionsUsed");
            if (out.size() / 3 != vcount)
                refuse(aw + ": " + elements(out, 3, a.second) + ", POSITION has " + str(vcount));
            all_finite(out, a.second, aw);
            moved[slot] = true;
        }
    }
    // every target gives the same attributes (what the scene asks): one a
    // target leaves out while another moves it is zeros; targets that move
    // nothing at all move the positions by zero
    if (!moved[0] && !moved[1] && !moved[2])
        moved[0] = true;
    bool need_zeros = false;
    for (const morph_data &md : d.targets)
        need_zeros = need_zeros || (moved[0] && md.pos.empty()) || (moved[1] && md.nrm.empty()) ||
                     (moved[2] && md.tan.empty());
    if (need_zeros) {
        uint64_t bytes = mul_checked(vcount, 3 * sizeof(float), pw);
        cx.mem.charge(bytes, pw + ".targets (zero deltas)");
        cx.mesh_bytes += bytes;
        d.zeros.assign(vcount * 3, 0.0f);
    }
    // the descriptions point into d's vectors, whose buffers stay put when d is moved
    d.target_descs.resize(d.targets.size());
    for (size_t t = 0; t < d.targets.size(); ++t) {
        const morph_data &md = d.targets[t];
        mvr_morph_target_desc &td = d.target_descs[t];
        std::memset(&td, 0, sizeof td);
        auto pick = [&](bool wanted, const std::vector<float> &v) -> const float * {
            return !wanted ? nullptr : v.empty() ? d.zeros.data() : v.data();
        };
        td.positions = pick(moved[0], md.pos);
        td.normals = pick(moved[1], md.nrm);
        td.tangents = pick(moved[2], md.tan);
    }
}

std::vector<float> converter::mesh_weights(const tinygltf::Mesh &g, const std::string &w, uint32_t targets)
{
    std::vector<float> out;
    if (g.weights.empty())
        return out;
    if (g.weights.size() != targets)
        refuse(w + ".weights has " + str(g.weights.size()) + " values, the mesh has " + str(targets) +
               " morph targets");
    for (size_t i = 0; i < g.weights.size(); ++i) {
        if (!std::isfinite(g.weights[i]))
            refuse(w + ".weights[" + str(i) + "] is not a finite number");
        out.push_back(float(g.weights[i]));
    }
    return out;
}

// ------------------------------------------------------------ nodes

void converter::node_weights(int index, mvr_node_id id)
{
    const tinygltf::Node &g = m.nodes[size_t(index)];
    if (g.weights.empty())
        return;
    std::string w = "nodes[" + std::to_string(index) + "].weights";
    if (g.mesh < 0)
        refuse(w + ": the node has no mesh");
    auto facts = mesh_info.find(g.mesh);   // mesh() has read it
    uint32_t targets = facts == mesh_info.end() ? 0 : facts->second.targets;
    if (g.weights.size() != targets)
        refuse(w + " has " + str(g.weights.size()) + " values, mesh " + std::to_string(g.mesh) + " has " +
               str(targets) + " morph targets");
    std::vector<float> v;
    for (size_t i = 0; i < g.weights.size(); ++i) {
        if (!std::isfinite(g.weights[i]))
            refuse(w + "[" + str(i) + "] is not a finite number");
        v.push_back(float(g.weights[i]));
    }
    if (meshes[g.mesh].id == 0) {
        cx.debug(w + ": the node's mesh draws nothing; ignored");
        return;
    }
    check(mvr_scene_set_node_weights(scene, id, v.data(), uint32_t(v.size())), w);
}

// ------------------------------------------------------------ skins

namespace {

const uint32_t MAX_JOINTS = 65536;   // mvr_skin_desc.joint_count

// skins[si], converted once: joints (each a node of the loaded scene, once),
// inverse bind matrices (MAT4 FLOAT, at least one per joint, finite).
mvr_skin_id convert_skin(converter &cv, int si)
{
    auto found = cv.skin_ids.find(si);
    if (found != cv.skin_ids.end())
        return found->second;
    context &cx = cv.cx;
    const tinygltf::Skin &s = cv.m.skins[size_t(si)];
    std::string w = "skins[" + std::to_string(si) + "]";
    size_t n = s.joints.size();
    if (n == 0)
        refuse(w + ".joints is empty");
    if (n > MAX_JOINTS)
        refuse(w + " has " + str(n) + " joints; mvr takes at most " + str(MAX_JOINTS));
    std::vector<mvr_node_id> joints(n);
    std::vector<char> seen(cv.m.nodes.size(), 0);
    for (size_t k = 0; k < n; ++k) {
        int j = s.joints[k];
        std::string jw = w + ".joints[" + str(k) + "]";
        if (j < 0 || size_t(j) >= cv.m.nodes.size())
            refuse(jw + ": node " + std::to_string(j) + " does not exist (" + str(cv.m.nodes.size()) + " nodes)");
        if (cv.node_ids[size_t(j)].id == 0)
            refuse(jw + ": node " + std::to_string(j) + " is not in the loaded scene");
        if (seen[size_t(j)])
            refuse(jw + ": node " + std::to_string(j) + " is listed twice");
        seen[size_t(j)] = 1;
        joints[k] = cv.node_ids[size_t(j)];
    }
    scoped_reads reads(cx);
    std::vector<double> ibm;
    std::optional<charged> as_doubles;
    if (s.inverseBindMatrices >= 0) {
        std::string iw = w + ".inverseBindMatrices";
        std::vector<float> f = read_floats(cx, s.inverseBindMatrices, 16, iw, FLOAT);
        if (f.size() / 16 < n)
            refuse(iw + ": accessor " + std::to_string(s.inverseBindMatrices) + " has " + str(f.size() / 16) +
                   " matrices, the skin has " + str(n) + " joints");
        all_finite(f, s.inverseBindMatrices, iw);
        as_doubles.emplace(cx.mem, uint64_t(n) * 16 * sizeof(double), iw + " (as doubles)");
        ibm.assign(f.begin(), f.begin() + std::ptrdiff_t(n * 16));
    }
    mvr_skin_desc d;
    std::memset(&d, 0, sizeof d);
    d.joints = joints.data();
    d.joint_count = uint32_t(n);
    d.inverse_bind_matrices = ibm.empty() ? nullptr : ibm.data();
    if (s.skeleton >= 0) {
        if (size_t(s.skeleton) >= cv.m.nodes.size())
            refuse(w + ".skeleton: node " + std::to_string(s.skeleton) + " does not exist (" +
                   str(cv.m.nodes.size()) + " nodes)");
        d.skeleton = cv.node_ids[size_t(s.skeleton)];   // {0} outside the loaded scene: it is informative only
    }
    d.name = s.name.c_str();
    // the scene keeps the joints and their matrices (in double) while the load goes on
    cx.mem.charge(uint64_t(n) * (16 * sizeof(double) + sizeof(mvr_node_id)), w + " (the scene's copy)");
    mvr_skin_id id = {0};
    cv.check(mvr_scene_add_skin(cv.scene, &d, &id), w);
    cv.skin_ids[si] = id;
    cv.skin_joint_counts[si] = uint32_t(n);
    return id;
}

}  // namespace

// Skins are converted once every node of the loaded scene is in (joints may
// be anywhere in it), and only those a node of that scene uses.
void converter::skins()
{
    for (const auto &sn : skinned) {
        const tinygltf::Node &g = m.nodes[size_t(sn.first)];
        std::string nw = "nodes[" + std::to_string(sn.first) + "]";
        if (size_t(g.skin) >= m.skins.size())
            refuse(nw + ".skin: skin " + std::to_string(g.skin) + " does not exist (" + str(m.skins.size()) + " skins)");
        mvr_skin_id sid = convert_skin(*this, g.skin);
        uint32_t joints = skin_joint_counts[g.skin];
        const mesh_facts &f = mesh_info[g.mesh];
        if (f.max_joint >= 0 && uint32_t(f.max_joint) >= joints)
            refuse(nw + ": " + f.joint_attr + " names joint " + std::to_string(f.max_joint) + ", past the " +
                   str(joints) + " joints of skins[" + std::to_string(g.skin) + "]");
        check(mvr_scene_set_node_skin(scene, sn.second, sid), nw + ".skin");
    }
}

// ------------------------------------------------------------ animations

namespace {

struct sampler_need {
    uint32_t components = 0;       // per key value; 0: no kept channel reads the sampler
    int type = -1;                 // the output accessor's type
    mvr_animation_path path = MVR_ANIMATION_PATH_TRANSLATION;
    std::string by;                // the first channel reading it, for messages
};

const char *interpolation_name(mvr_interpolation i)
{
    return i == MVR_INTERPOLATION_STEP ? "STEP" : i == MVR_INTERPOLATION_CUBICSPLINE ? "CUBICSPLINE" : "LINEAR";
}

// animations[ai]. Its channels on nodes outside the loaded scene, and those
// on paths mvr does not implement, are left out (counted in
// cx.channels_ignored); samplers no kept channel reads are dropped, the
// others renumbered in file order. An animation left with no channel is
// still added, empty, so that animation indices are the file's.
void convert_animation(converter &cv, size_t ai)
{
    context &cx = cv.cx;
    const tinygltf::Animation &a = cv.m.animations[ai];
    std::string w = "animations[" + str(ai) + "]";
    std::vector<sampler_need> needs(a.samplers.size());
    std::vector<mvr_animation_channel_desc> channels;
    std::vector<int> channel_sampler;   // the file's sampler index of each kept channel
    for (size_t ci = 0; ci < a.channels.size(); ++ci) {
        const tinygltf::AnimationChannel &c = a.channels[ci];
        std::string cw = w + ".channels[" + str(ci) + "]";
        mvr_animation_path path;
        if (c.target_path == "translation")
            path = MVR_ANIMATION_PATH_TRANSLATION;
        else if (c.target_path == "rotation")
            path = MVR_ANIMATION_PATH_ROTATION;
        else if (c.target_path == "scale")
            path = MVR_ANIMATION_PATH_SCALE;
        else if (c.target_path == "weights")
            path = MVR_ANIMATION_PATH_WEIGHTS;
        else {
            ++cx.channels_ignored;
            if (cv.warned_paths.insert(c.target_path).second)
                cx.warn(cw + ": target path " + quote(c.target_path) +
                        (c.target_path == "pointer" ? " (KHR_animation_pointer)" : "") +
                        " is not implemented; channel ignored");
            continue;
        }
        if (c.sampler < 0 || size_t(c.sampler) >= a.samplers.size())
            refuse(cw + ".sampler: sampler " + std::to_string(c.sampler) + " does not exist (" +
                   str(a.samplers.size()) + " samplers in " + w + ")");
        if (c.target_node < 0 || size_t(c.target_node) >= cv.m.nodes.size())
            refuse(cw + ".target.node: node " + std::to_string(c.target_node) + " does not exist (" +
                   str(cv.m.nodes.size()) + " nodes)");
        mvr_node_id node = cv.node_ids[size_t(c.target_node)];
        if (node.id == 0) {
            ++cx.channels_ignored;
            cx.debug(cw + ": node " + std::to_string(c.target_node) + " is not in the loaded scene; channel ignored");
            continue;
        }
        uint32_t comps = path == MVR_ANIMATION_PATH_ROTATION ? 4 : 3;
        int type = path == MVR_ANIMATION_PATH_ROTATION ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
        if (path == MVR_ANIMATION_PATH_WEIGHTS) {
            const tinygltf::Node &n = cv.m.nodes[size_t(c.target_node)];
            std::string nn = "node " + std::to_string(c.target_node);
            if (n.mesh < 0)
                refuse(cw + ": animates the weights of " + nn + ", which has no mesh");
            auto f = cv.mesh_info.find(n.mesh);
            comps = f == cv.mesh_info.end() ? 0 : f->second.targets;
            if (comps == 0)
                refuse(cw + ": animates the weights of " + nn + ", whose mesh " + std::to_string(n.mesh) +
                       " has no morph targets");
            auto drawn = cv.meshes.find(n.mesh);
            if (drawn == cv.meshes.end() || drawn->second.id == 0) {
                ++cx.channels_ignored;
                cx.debug(cw + ": " + nn + "'s mesh draws nothing; channel ignored");
                continue;
            }
            type = TINYGLTF_TYPE_SCALAR;
        }
        sampler_need &nd = needs[size_t(c.sampler)];
        if (nd.components && (nd.components != comps || nd.type != type))
            refuse(w + ".samplers[" + std::to_string(c.sampler) + "] is read by " + nd.by + " (" +
                   mvr_animation_path_name(nd.path) + ", " + str(nd.components) + " values a key) and by " + cw +
                   " (" + mvr_animation_path_name(path) + ", " + str(comps) + " values a key)");
        if (!nd.components) {
            nd.components = comps;
            nd.type = type;
            nd.path = path;
            nd.by = cw;
        }
        mvr_animation_channel_desc cd;
        std::memset(&cd, 0, sizeof cd);
        cd.node = node;
        cd.path = path;
        channels.push_back(cd);
        channel_sampler.push_back(c.sampler);
    }
    // every sampler's interpolation is checked, read or not
    std::vector<mvr_interpolation> interp(a.samplers.size());
    for (size_t j = 0; j < a.samplers.size(); ++j) {
        const std::string &s = a.samplers[j].interpolation;
        if (s == "LINEAR")
            interp[j] = MVR_INTERPOLATION_LINEAR;
        else if (s == "STEP")
            interp[j] = MVR_INTERPOLATION_STEP;
        else if (s == "CUBICSPLINE")
            interp[j] = MVR_INTERPOLATION_CUBICSPLINE;
        else
            refuse(w + ".samplers[" + str(j) + "].interpolation " + quote(s) + " is not LINEAR, STEP or CUBICSPLINE");
    }
    scoped_reads reads(cx);
    std::vector<int> renumbered(a.samplers.size(), -1);
    std::vector<std::vector<float>> times, values;
    std::vector<mvr_animation_sampler_desc> samplers;
    uint64_t copy_bytes = 0;
    for (size_t j = 0; j < a.samplers.size(); ++j) {
        const sampler_need &nd = needs[j];
        if (!nd.components)
            continue;
        const tinygltf::AnimationSampler &s = a.samplers[j];
        std::string sw = w + ".samplers[" + str(j) + "]";
        std::vector<float> t = read_floats(cx, s.input, 1, sw + ".input", FLOAT);
        all_finite(t, s.input, sw + ".input");
        // times without a bufferView (nor sparse values) are all 0 (glTF 2.0,
        // 3.6.2.1), which the schema allows; at every time >= 0 such a sampler
        // gives its last key (3.11: clamped past the last key), so that key
        // alone is kept
        size_t keep_from = 0;
        const tinygltf::Accessor &ta = cx.model->accessors[size_t(s.input)];
        if (t.size() > 1 && ta.bufferView < 0 && !ta.sparse.isSparse &&
            std::all_of(t.begin(), t.end(), [](float x) { return x == 0.0f; })) {
            keep_from = t.size() - 1;
            cx.debug(sw + ".input: accessor " + std::to_string(s.input) + " has no bufferView (every key at 0 s): the last "
                     "key alone is kept");
            t.erase(t.begin(), t.begin() + std::ptrdiff_t(keep_from));
        }
        for (size_t k = 1; k < t.size(); ++k)
            if (!(t[k] > t[k - 1]))
                refuse(sw + ".input: accessor " + std::to_string(s.input) + " key " + str(k) + " (" + num(t[k]) +
                       " s) is not after key " + str(k - 1) + " (" + num(t[k - 1]) +
                       " s): times must increase strictly");
        // glTF 2.0, 3.11: translation and scale FLOAT; rotation and weights
        // FLOAT or normalized BYTE / UNSIGNED_BYTE / SHORT / UNSIGNED_SHORT
        bool quantizable = nd.path == MVR_ANIMATION_PATH_ROTATION || nd.path == MVR_ANIMATION_PATH_WEIGHTS;
        int type_comps = nd.type == TINYGLTF_TYPE_VEC4 ? 4 : nd.type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
        std::string ow = sw + ".output";
        std::vector<float> v = read_floats(cx, s.output, type_comps, ow, quantizable ? FLOAT | I8 | U8 | I16 | U16 : FLOAT);
        if (quantizable)
            require_normalized(cx, s.output, ow);
        uint64_t per_key = uint64_t(nd.components) * (interp[j] == MVR_INTERPOLATION_CUBICSPLINE ? 3 : 1);
        uint64_t want = mul_checked(t.size() + keep_from, per_key, sw);
        if (v.size() != want)
            refuse(ow + ": accessor " + std::to_string(s.output) + " has " + str(v.size() / size_t(type_comps)) +
                   " elements; " + str(t.size() + keep_from) + " keys of " + interpolation_name(interp[j]) + " " +
                   mvr_animation_path_name(nd.path) + " (read by " + nd.by + ") need " + str(want / uint64_t(type_comps)));
        all_finite(v, s.output, ow);
        v.erase(v.begin(), v.begin() + std::ptrdiff_t(keep_from * per_key));
        if (t.size() > UINT32_MAX || v.size() > UINT32_MAX)
            refuse(sw + ": too many keys");
        copy_bytes = add_checked(copy_bytes, (t.size() + v.size()) * sizeof(float), sw);
        renumbered[j] = int(samplers.size());
        mvr_animation_sampler_desc sd;
        std::memset(&sd, 0, sizeof sd);
        sd.key_count = uint32_t(t.size());
        sd.value_count = uint32_t(v.size());
        sd.interpolation = interp[j];
        samplers.push_back(sd);
        times.push_back(std::move(t));
        values.push_back(std::move(v));
    }
    for (size_t j = 0; j < samplers.size(); ++j) {
        samplers[j].times = times[j].data();
        samplers[j].values = values[j].data();
    }
    for (size_t k = 0; k < channels.size(); ++k)
        channels[k].sampler = uint32_t(renumbered[size_t(channel_sampler[k])]);
    mvr_animation_desc d;
    std::memset(&d, 0, sizeof d);
    d.samplers = samplers.empty() ? nullptr : samplers.data();
    d.sampler_count = uint32_t(samplers.size());
    d.channels = channels.empty() ? nullptr : channels.data();
    d.channel_count = uint32_t(channels.size());
    d.name = a.name.c_str();
    // the scene keeps a copy while the load goes on
    cx.mem.charge(add_checked(copy_bytes, channels.size() * sizeof(mvr_animation_channel_desc), w),
                  w + " (the scene's copy)");
    uint32_t index = 0;
    cv.check(mvr_scene_add_animation(cv.scene, &d, &index), w);
}

}  // namespace

void converter::animations()
{
    for (size_t i = 0; i < m.animations.size(); ++i)
        convert_animation(*this, i);
}

}  // namespace mvr_gltf
