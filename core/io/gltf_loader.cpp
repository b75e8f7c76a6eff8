// mvr_gltf: tinygltf parses, this file validates and converts into an
// mvr_scene. No exception leaves it: every failure is an mvr_result with a
// message naming the glTF object.
#include <sys/stat.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "gltf_convert.hpp"
#include "gltf_files.hpp"
#include "gltf_internal.hpp"
#include "gltf_prepass.hpp"
#include "mvr/mvr_image.h"

extern "C" {
#include "core_util.h"
#include "scene_internal.h"
}

namespace mvr_gltf {

void context::warn(const std::string &msg)
{
    warnings++;
    if (logger.fn && (logger.level == MVR_LOG_DEFAULT || logger.level >= MVR_LOG_WARNING))
        logger.fn(MVR_LOG_WARNING, MVR_LOG_ID_GENERAL, ("mvr_gltf: " + msg).c_str(), logger.user_data);
}

void context::debug(const std::string &msg)
{
    mvr_log(&logger, MVR_LOG_DEBUG, MVR_LOG_ID_GENERAL, "mvr_gltf: %s", msg.c_str());
}

byte_span context::buffer(int index, const std::string &what)
{
    if (index < 0 || size_t(index) >= res.buffers.size())
        refuse(what + ": buffer " + std::to_string(index) + " does not exist (" + std::to_string(res.buffers.size()) +
               " buffers)");
    buffer_source &b = res.buffers[size_t(index)];
    if (b.loaded)
        return b.span;
    std::string w = "buffers[" + std::to_string(index) + "]";
    if (!b.has_uri && b.meshopt_fallback && !(res.glb && index == 0))
        refuse(w + " is EXT_meshopt_compression's fallback buffer and has no data; only bufferViews with that "
               "extension may use it (read by " + what + ")");
    if (!b.has_uri) {
        // glTF 2.0, 4.4.3.3: only buffers[0] may refer to the GLB's BIN chunk
        if (!res.glb)
            refuse(w + " has no uri (read by " + what + ")");
        if (index != 0)
            refuse(w + " has no uri: only buffers[0] may use the GLB's BIN chunk (read by " + what + ")");
        if (!res.bin)
            refuse(w + " refers to the GLB's BIN chunk, but the GLB has none");
        if (b.byte_length > res.bin_size)
            refuse(w + ".byteLength " + std::to_string(b.byte_length) + " is more than the BIN chunk's " +
                   std::to_string(res.bin_size) + " bytes");
        b.span = byte_span{res.bin, b.byte_length};
    } else {
        read_result r = files->read(b.uri, w + ".uri", true);
        if (r.data->bytes.size() < b.byte_length)
            refuse(w + ".uri " + quote(b.uri) + ": " + std::to_string(r.data->bytes.size()) +
                   " bytes, byteLength says " + std::to_string(b.byte_length));
        b.owner = r.data;
        b.span = byte_span{r.data->bytes.data(), b.byte_length};
        buffers_read += r.fresh ? 1 : 0;
    }
    b.loaded = true;
    return b.span;
}

using tinygltf::Model;

namespace {

// Extensions mvr implements (a required one outside this list is an error).
const std::set<std::string> implemented = {
    "EXT_meshopt_compression", "KHR_draco_mesh_compression",   // gltf_codecs.cpp
    "KHR_lights_punctual", "KHR_materials_unlit", "KHR_texture_transform", "KHR_materials_emissive_strength",
    "KHR_materials_ior", "KHR_materials_specular", "KHR_materials_clearcoat", "KHR_materials_sheen",
    "KHR_materials_pbrSpecularGlossiness", "KHR_materials_transmission", "KHR_materials_volume",
    "KHR_materials_dispersion", "KHR_materials_iridescence", "KHR_materials_anisotropy",
    "KHR_mesh_quantization", "KHR_materials_variants",
    "KHR_texture_basisu", "EXT_texture_webp"};   // gltf_materials.cpp: their source, else the fallback

// glTF 2.0, 3.12: a required extension mvr does not implement refuses the
// file, naming it; one that is only used is warned about once and left out
// (the file's fallback renders). Checked on the pre-pass's lists, before
// tinygltf parses: an unsupported extension's JSON never gets to fail first.
void check_extensions(context &cx)
{
    for (const auto &e : cx.res.extensions_required)
        if (!implemented.count(e))
            throw load_error(MVR_ERROR_UNSUPPORTED,
                             "the file requires extension " + quote(e) + ", which mvr does not implement");
    std::set<std::string> warned;
    for (const auto &e : cx.res.extensions_used) {
        if (e == "KHR_mesh_quantization")
            cx.quantization_declared = true;
        else if (!implemented.count(e) && warned.insert(e).second)
            cx.warn("extension " + quote(e) + " is used but not implemented; the file renders without it");
    }
}

void count_scene_warning(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    auto *cx = static_cast<context *>(user);
    if (level == MVR_LOG_WARNING)
        ++cx->warnings;
    mvr_log(&cx->logger, level, id, "%s", message);
}

// tinygltf's file access, never used (it is given no external URI): refused.
bool refuse_exists(const std::string &, void *)
{
    return false;
}
std::string refuse_expand(const std::string &, void *)
{
    return "";
}
bool refuse_read(std::vector<unsigned char> *, std::string *, const std::string &, void *)
{
    return false;
}
bool refuse_write(std::string *, const std::string &, const std::vector<unsigned char> &, void *)
{
    return false;
}

// tinygltf calls this for the one-byte placeholder each image became in
// the pre-pass: mvr decodes images itself, from the sources it took out.
bool ignore_placeholder(tinygltf::Image *, const int, std::string *, std::string *, int, int, const unsigned char *,
                        int, void *)
{
    return true;
}

// tinygltf's messages, shortened: they may quote names and URIs from the file.
std::string short_message(std::string m)
{
    while (!m.empty() && (m.back() == '\n' || m.back() == ' '))
        m.pop_back();
    std::string first = m.substr(0, m.find('\n'));
    std::string q = quote(first);
    return q.substr(1, q.size() - 2) + (first.size() < m.size() ? " (and more)" : "");
}

// ---- conversions ----

// Index list of a primitive in list form: strips, fans and loops converted.
// Lists are moved through, not copied (the budget counted them once).
std::vector<uint32_t> to_list(int mode, std::vector<uint32_t> in, mvr_primitive_mode *out_mode)
{
    std::vector<uint32_t> out;
    size_t n = in.size();
    switch (mode) {
    case TINYGLTF_MODE_POINTS: *out_mode = MVR_PRIMITIVE_POINTS; return in;
    case TINYGLTF_MODE_LINE: *out_mode = MVR_PRIMITIVE_LINES; in.resize(n / 2 * 2); return in;
    case TINYGLTF_MODE_LINE_STRIP:
    case TINYGLTF_MODE_LINE_LOOP:
        *out_mode = MVR_PRIMITIVE_LINES;
        for (size_t i = 0; i + 1 < n; ++i)
            out.insert(out.end(), {in[i], in[i + 1]});
        if (mode == TINYGLTF_MODE_LINE_LOOP && n > 2)
            out.insert(out.end(), {in[n - 1], in[0]});
        return out;
    case TINYGLTF_MODE_TRIANGLE_STRIP:
        *out_mode = MVR_PRIMITIVE_TRIANGLES;
        for (size_t i = 0; i + 2 < n; ++i) {
            /* every other triangle flipped to keep the winding (glTF 2.0, 3.7.2.1) */
            if (i % 2 == 0)
                out.insert(out.end(), {in[i], in[i + 1], in[i + 2]});
            else
                out.insert(out.end(), {in[i + 1], in[i], in[i + 2]});
        }
        return out;
    case TINYGLTF_MODE_TRIANGLE_FAN:
        *out_mode = MVR_PRIMITIVE_TRIANGLES;
        for (size_t i = 1; i + 1 < n; ++i)
            out.insert(out.end(), {in[0], in[i], in[i + 1]});
        return out;
    default:
        *out_mode = MVR_PRIMITIVE_TRIANGLES;
        in.resize(n / 3 * 3);
        return in;
    }
}

constexpr uint32_t FLOAT = ANY_FLOAT;
constexpr uint32_t I8 = 1u << 0, U8 = 1u << 1, I16 = 1u << 2, U16 = 1u << 3;

// ---- what rendering the scene will allocate, charged at load ----
// The renderer's uploads hold memory beyond the scene's copy (host memory on
// llvmpipe): charged as part of the scene, so a file whose render would
// exceed the budget is refused here, before anything is allocated for it.

// gl/skinning.c keeps each morph delta as one RGBA32F texel.
constexpr uint64_t morph_texel_bytes = 16;
// Reading targets holds the load's and the scene's copy (3 floats a texel each).
constexpr uint64_t morph_read_bytes = 2 * 3 * sizeof(float);

// Delta texels of primitive p's targets as core/scene.c lays them out
// (morph_texels): vertices x targets x the attributes some target moves
// (POSITION, NORMAL and TANGENT where the primitive has them; none at all
// still moves POSITION by zero). From the JSON alone: a target without
// data (no bufferView, sparse or not) counts for what it expands to.
uint64_t morph_texels(const tinygltf::Primitive &p, size_t vcount, bool has_normals, bool has_tangents,
                      const std::string &pw)
{
    bool moved[3] = {false, false, false};
    for (const auto &target : p.targets)
        for (const auto &a : target) {
            moved[0] = moved[0] || a.first == "POSITION";
            moved[1] = moved[1] || (a.first == "NORMAL" && has_normals);
            moved[2] = moved[2] || (a.first == "TANGENT" && has_tangents);
        }
    uint64_t attributes = uint64_t(moved[0]) + uint64_t(moved[1]) + uint64_t(moved[2]);
    return mul_checked(mul_checked(vcount, p.targets.size(), pw), attributes ? attributes : 1, pw);
}

}  // namespace

mvr_mesh_id converter::mesh(int index)
{
    auto found = meshes.find(index);
    if (found != meshes.end())
        return found->second;
    if (size_t(index) >= m.meshes.size())
        refuse("mesh " + std::to_string(index) + " does not exist (" + std::to_string(m.meshes.size()) + " meshes)");
    const tinygltf::Mesh &g = m.meshes[size_t(index)];
    std::string w = "meshes[" + std::to_string(index) + "]";
    mesh_facts facts;
    // glTF 2.0, 3.7.2.2: every primitive has the same number of morph targets
    if (!g.primitives.empty())
        facts.targets = uint32_t(g.primitives[0].targets.size());
    for (size_t k = 1; k < g.primitives.size(); ++k)
        if (g.primitives[k].targets.size() != facts.targets)
            refuse(w + ".primitives[" + std::to_string(k) + "] has " + std::to_string(g.primitives[k].targets.size()) +
                   " morph targets, primitives[0] has " + std::to_string(facts.targets) +
                   ": every primitive of a mesh must have as many");
    std::vector<float> weights = mesh_weights(g, w, facts.targets);
    std::vector<prim_data> data;
    for (size_t k = 0; k < g.primitives.size(); ++k) {
        const tinygltf::Primitive &p = g.primitives[k];
        std::string pw = w + ".primitives[" + std::to_string(k) + "]";
        if (p.mode < 0 || p.mode > TINYGLTF_MODE_TRIANGLE_FAN)
            refuse(pw + ": mode " + std::to_string(p.mode) + " is not a glTF primitive mode");
        auto attr = [&](const char *name) {
            auto it = p.attributes.find(name);
            return it == p.attributes.end() ? -1 : it->second;
        };
        int a_pos = attr("POSITION");
        if (a_pos < 0) {
            cx.warn(pw + " has no POSITION; skipped");
            continue;
        }
        prim_data d;
        d.source = k;
        d.variant_maps = variant_mappings(index, int(k), pw);
        // KHR_draco_mesh_compression: its accessors read the decoded mesh until the primitive is read
        draco_scope draco(cx, index, int(k), p, pw);
        // glTF 2.0 3.7.2.1 + KHR_mesh_quantization: the component types allowed per attribute
        uint32_t quant_pos = FLOAT | I8 | U8 | I16 | U16;
        d.pos = read_floats(cx, a_pos, 3, pw + ".attributes.POSITION", quant_pos);
        size_t vcount = d.pos.size() / 3;
        const tinygltf::Accessor &pa = m.accessors[size_t(a_pos)];
        if (pa.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !cx.quantization_declared)
            cx.warn(pw + ".attributes.POSITION is quantized but KHR_mesh_quantization is not in extensionsUsed");
        for (float v : d.pos)
            if (!std::isfinite(v))
                refuse(pw + ".attributes.POSITION: accessor " + std::to_string(a_pos) + " holds NaN or infinite values");
        cx.vertices = add_checked(cx.vertices, vcount, pw);
        if (cx.vertices > cx.limits.max_vertices)
            refuse(pw + ": more than " + std::to_string(cx.limits.max_vertices) +
                   " vertices in the file (mvr_gltf_options.max_vertices)");
        auto optional = [&](const char *name, int comps, uint32_t allowed, std::vector<float> &out) {
            int a = attr(name);
            if (a < 0)
                return;
            std::string aw = pw + ".attributes." + name;
            out = read_floats(cx, a, comps, aw, allowed);
            if (out.size() / size_t(comps) != vcount)
                refuse(aw + ": accessor " + std::to_string(a) + " has " + std::to_string(out.size() / size_t(comps)) +
                       " elements, POSITION has " + std::to_string(vcount));
        };
        optional("NORMAL", 3, FLOAT | I8 | I16, d.nrm);
        optional("TANGENT", 4, FLOAT | I8 | I16, d.tan);
        optional("TEXCOORD_0", 2, FLOAT | I8 | U8 | I16 | U16, d.uv0);
        optional("TEXCOORD_1", 2, FLOAT | I8 | U8 | I16 | U16, d.uv1);
        int a_col = attr("COLOR_0");
        if (a_col >= 0) {
            // COLOR_0 is VEC3 or VEC4 (a missing accessor is refused by read_floats)
            int comps = size_t(a_col) < m.accessors.size() && m.accessors[size_t(a_col)].type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
            std::vector<float> c;
            optional("COLOR_0", comps, FLOAT | U8 | U16, c);
            cx.mem.charge(vcount * 4 * sizeof(float), pw + ".attributes.COLOR_0 (as RGBA)");
            cx.mesh_bytes += vcount * 4 * sizeof(float);
            d.col.resize(vcount * 4, 1.0f);
            for (size_t v = 0; v < vcount; ++v)
                for (int ch = 0; ch < comps; ++ch)
                    d.col[v * 4 + size_t(ch)] = c[v * size_t(comps) + size_t(ch)];
        }
        skin_attributes(p, pw, vcount, d, facts);
        if (!p.targets.empty()) {
            uint64_t texels = morph_texels(p, vcount, !d.nrm.empty(), !d.tan.empty(), pw);
            uint64_t gpu = mul_checked(texels, morph_texel_bytes, pw);
            std::string what = pw + ".targets (" + std::to_string(p.targets.size()) + " targets of " +
                               std::to_string(vcount) + " vertices: " + std::to_string(texels) + " delta texels";
            { charged reading(cx.mem, add_checked(gpu, mul_checked(texels, morph_read_bytes, pw), pw),
                              what + ", read, with the scene's copy and the GPU's)"); }
            cx.mem.charge(gpu, what + ", RGBA32F for rendering)");   // held with the scene
        }
        morph_targets(p, pw, vcount, d);
        std::vector<uint32_t> idx;
        if (p.indices >= 0) {
            idx = read_indices(cx, p.indices, pw + ".indices");
            for (size_t i = 0; i < idx.size(); ++i)
                if (idx[i] >= vcount)
                    refuse(pw + ".indices: accessor " + std::to_string(p.indices) + " element " + std::to_string(i) +
                           " = " + std::to_string(idx[i]) + " is past the " + std::to_string(vcount) + " vertices");
        } else {
            cx.mem.charge(vcount * sizeof(uint32_t), pw + " (implicit indices)");
            cx.mesh_bytes += vcount * sizeof(uint32_t);
            idx.resize(vcount);
            for (size_t i = 0; i < vcount; ++i)
                idx[i] = uint32_t(i);
        }
        // strips and fans become lists (up to 3x the indices): charged first
        uint64_t listed = p.mode == TINYGLTF_MODE_TRIANGLE_STRIP || p.mode == TINYGLTF_MODE_TRIANGLE_FAN ? idx.size() * 3
                          : p.mode == TINYGLTF_MODE_LINE_STRIP || p.mode == TINYGLTF_MODE_LINE_LOOP ? idx.size() * 2
                                                                                                       : 0;
        cx.mem.charge(listed * sizeof(uint32_t), pw + " (strip / fan / loop as a list)");
        cx.mesh_bytes += listed * sizeof(uint32_t);
        d.idx = to_list(p.mode, std::move(idx), &d.mode);
        cx.indices = add_checked(cx.indices, d.idx.size(), pw);
        if (cx.indices > cx.limits.max_indices)
            refuse(pw + ": more than " + std::to_string(cx.limits.max_indices) +
                   " indices in the file (mvr_gltf_options.max_indices)");
        if (d.idx.empty()) {
            cx.warn(pw + " has too few vertices for its mode; skipped");
            continue;
        }
        d.material = p.material >= 0 ? material(p.material) : mvr_material_id{0};
        generated_tangents(p, pw, d);
        data.push_back(std::move(d));
    }
    mesh_info[index] = facts;
    mvr_mesh_id id = {0};
    if (data.empty()) {
        meshes[index] = id;
        return id;
    }
    std::vector<mvr_primitive_desc> prims(data.size());
    for (size_t k = 0; k < data.size(); ++k) {
        mvr_primitive_desc &pd = prims[k];
        std::memset(&pd, 0, sizeof pd);
        const prim_data &d = data[k];
        pd.vertex_count = uint32_t(d.pos.size() / 3);
        pd.positions = d.pos.data();
        pd.normals = d.nrm.empty() ? nullptr : d.nrm.data();
        pd.tangents = d.tan.empty() ? nullptr : d.tan.data();
        pd.texcoords0 = d.uv0.empty() ? nullptr : d.uv0.data();
        pd.texcoords1 = d.uv1.empty() ? nullptr : d.uv1.data();
        pd.colors = d.col.empty() ? nullptr : d.col.data();
        pd.index_count = uint32_t(d.idx.size());
        pd.indices32 = d.idx.data();
        pd.mode = d.mode;
        pd.material = d.material;
        pd.joints0 = d.joints0.empty() ? nullptr : d.joints0.data();
        pd.weights0 = d.weights0.empty() ? nullptr : d.weights0.data();
        pd.joints1 = d.joints1.empty() ? nullptr : d.joints1.data();
        pd.weights1 = d.weights1.empty() ? nullptr : d.weights1.data();
        pd.targets = d.target_descs.empty() ? nullptr : d.target_descs.data();
        pd.target_count = uint32_t(d.target_descs.size());
    }
    mvr_mesh_desc md;
    std::memset(&md, 0, sizeof md);
    md.primitives = prims.data();
    md.primitive_count = uint32_t(prims.size());
    md.name = g.name.c_str();
    md.weights = weights.empty() ? nullptr : weights.data();
    md.weight_count = uint32_t(weights.size());
    // the scene keeps a copy of what was read: charged while both exist
    cx.mem.charge(cx.mesh_bytes, w + " (the scene's copy)");
    check(mvr_scene_add_mesh(scene, &md, &id), w);
    for (size_t k = 0; k < data.size(); ++k)
        if (!data[k].variant_maps.empty())
            check(mvr_scene_set_primitive_variants(scene, id, uint32_t(k), data[k].variant_maps.data(),
                                                   uint32_t(data[k].variant_maps.size())),
                  w + ".primitives[" + std::to_string(data[k].source) + "].extensions.KHR_materials_variants");
    data.clear();
    cx.mem.release(cx.mesh_bytes);
    cx.mesh_bytes = 0;
    meshes[index] = id;
    return id;
}

// state: 0 unseen, 1 on the current path, 2 done. A node seen twice means a
// cycle or a shared child, both invalid (glTF 2.0, 3.5.3: nodes form a forest).
void converter::node(int index, mvr_node_id parent, std::vector<char> &state, uint32_t depth)
{
    std::string w = "nodes[" + std::to_string(index) + "]";
    if (index < 0 || size_t(index) >= m.nodes.size())
        refuse(w + " does not exist (" + std::to_string(m.nodes.size()) + " nodes)");
    if (state[size_t(index)] == 1)
        refuse(w + " is its own ancestor: the node graph has a cycle");
    if (state[size_t(index)] == 2)
        refuse(w + " has two parents (or is a root listed twice): nodes must form a tree");
    if (depth > 1024)
        refuse(w + ": the node hierarchy is deeper than 1024");
    state[size_t(index)] = 1;
    const tinygltf::Node &g = m.nodes[size_t(index)];
    mvr_node_desc d;
    std::memset(&d, 0, sizeof d);
    d.parent = parent;
    d.name = g.name.c_str();
    if (g.matrix.size() == 16) {
        d.use_matrix = true;
        for (int i = 0; i < 16; ++i)
            d.matrix[i] = g.matrix[size_t(i)];
    } else {
        if (!g.matrix.empty())
            refuse(w + ".matrix has " + std::to_string(g.matrix.size()) + " numbers, not 16");
        if ((!g.translation.empty() && g.translation.size() != 3) || (!g.rotation.empty() && g.rotation.size() != 4) ||
            (!g.scale.empty() && g.scale.size() != 3))
            refuse(w + ": translation / rotation / scale of the wrong length");
        for (size_t i = 0; i < g.translation.size(); ++i)
            d.translation[i] = g.translation[i];
        for (size_t i = 0; i < g.rotation.size(); ++i)
            d.rotation[i] = g.rotation[i];
        if (g.rotation.empty())
            d.rotation[3] = 1.0;
        for (size_t i = 0; i < 3; ++i)
            d.scale[i] = g.scale.empty() ? 1.0 : g.scale[i];
        if (!g.scale.empty() && g.scale[0] == 0 && g.scale[1] == 0 && g.scale[2] == 0) {
            /* (0,0,0) means "default" in mvr's desc; glTF's zero scale hides the node */
            d.scale[0] = 1e-30;
        }
    }
    if (g.mesh >= 0)
        d.mesh = mesh(g.mesh);
    if (g.camera >= 0) {
        auto found = cameras.find(g.camera);
        if (found == cameras.end() && bad_cameras.count(g.camera))
            refuse(w + " uses " + bad_cameras[g.camera]);
        if (found == cameras.end())
            refuse(w + ": camera " + std::to_string(g.camera) + " does not exist");
        d.camera = found->second;
    }
    auto lp = g.extensions.find("KHR_lights_punctual");
    if (lp != g.extensions.end()) {
        int li = int(number(lp->second, "light", -1));
        auto found = lights.find(li);
        if (found == lights.end() && bad_lights.count(li))
            refuse(w + " uses " + bad_lights[li]);
        if (found == lights.end())
            refuse(w + ".extensions.KHR_lights_punctual: light " + std::to_string(li) + " does not exist");
        d.light = found->second;
    }
    mvr_node_id id = {0};
    check(mvr_scene_add_node(scene, &d, &id), w);
    node_ids[size_t(index)] = id;
    node_weights(index, id);
    if (g.skin >= 0) {
        // the skin itself is converted once every node of the scene is in (skins())
        if (g.mesh < 0)
            cx.warn(w + " has a skin but no mesh; the skin is ignored");
        else if (d.mesh.id != 0)
            skinned.push_back({index, id});
    }
    for (int child : g.children)
        node(child, id, state, depth + 1);
    state[size_t(index)] = 2;
}

namespace {

void convert_cameras_and_lights(converter &cv)
{
    const Model &m = cv.m;
    for (size_t i = 0; i < m.cameras.size(); ++i) {
        const tinygltf::Camera &c = m.cameras[i];
        std::string w = "cameras[" + std::to_string(i) + "]";
        try {
        mvr_projection p;
        std::memset(&p, 0, sizeof p);
        auto bad = cv.cx.res.bad_cameras.find(int(i)); /* what the pre-pass found tinygltf could not parse */
        if (bad != cv.cx.res.bad_cameras.end())
            refuse(bad->second);
        if (c.type == "perspective") {
            p.type = MVR_PROJECTION_PERSPECTIVE;
            p.yfov = c.perspective.yfov;
            p.aspect = c.perspective.aspectRatio; /* 0 = the viewport's */
            p.znear = c.perspective.znear;
            p.zfar = c.perspective.zfar;          /* 0 = infinite */
            if (!(p.yfov > 0 && p.yfov < 3.14159) || !(p.znear > 0) || (p.zfar != 0 && !(p.zfar > p.znear)))
                refuse(w + ": perspective yfov / znear / zfar out of range");
        } else if (c.type == "orthographic") {
            p.type = MVR_PROJECTION_ORTHOGRAPHIC;
            p.xmag = std::fabs(c.orthographic.xmag);
            p.ymag = std::fabs(c.orthographic.ymag);
            p.znear = c.orthographic.znear > 0 ? c.orthographic.znear : 1e-4;
            p.zfar = c.orthographic.zfar;
            if (!(p.xmag > 0 && p.ymag > 0) || !(p.zfar > p.znear))
                refuse(w + ": orthographic xmag / ymag / znear / zfar out of range");
        } else {
            refuse(w + ": type " + quote(c.type) + " is not perspective or orthographic");
        }
        mvr_camera_id id = {0};
        cv.check(mvr_scene_add_camera(cv.scene, &p, &id), w);
        cv.cameras[int(i)] = id;
        } catch (const load_error &e) {
            cv.set_aside(e, cv.bad_cameras, int(i));
        }
    }
    for (size_t i = 0; i < m.lights.size(); ++i) {
        const tinygltf::Light &l = m.lights[i];
        std::string w = "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
        try {
        mvr_light_desc d;
        std::memset(&d, 0, sizeof d);
        if (l.type == "directional")
            d.type = MVR_LIGHT_DIRECTIONAL;
        else if (l.type == "point")
            d.type = MVR_LIGHT_POINT;
        else if (l.type == "spot")
            d.type = MVR_LIGHT_SPOT;
        else
            refuse(w + ": type " + quote(l.type) + " is not directional, point or spot");
        d.color[0] = d.color[1] = d.color[2] = 1.0f;
        for (size_t c = 0; c < 3 && c < l.color.size(); ++c)
            d.color[c] = float(l.color[c]);
        if (d.color[0] == 0 && d.color[1] == 0 && d.color[2] == 0)
            d.intensity = 0; /* black light: mvr's zero color means white */
        else
            d.intensity = float(l.intensity);
        d.range = float(l.range);
        d.inner_cone_angle = float(l.spot.innerConeAngle);
        d.outer_cone_angle = float(l.spot.outerConeAngle);
        mvr_light_id id = {0};
        cv.check(mvr_scene_add_light(cv.scene, &d, &id), w);
        cv.lights[int(i)] = id;
        } catch (const load_error &e) {
            cv.set_aside(e, cv.bad_lights, int(i));
        }
    }
}

mvr_result load(const unsigned char *bytes, size_t size, const std::string &base_dir, bool allow_files,
                const mvr_gltf_options *options, mvr_scene **out, mvr_gltf_info *info, mvr_error *error)
{
    mvr_gltf_options o;
    if (options)
        o = *options;
    else
        std::memset(&o, 0, sizeof o);
    context cx;
    cx.logger = o.logger;
    cx.strict = o.strict;
    cx.limits.max_file_bytes = o.max_file_bytes ? o.max_file_bytes : (uint64_t(1) << 30);
    cx.limits.max_vertices = o.max_vertices ? o.max_vertices : (uint64_t(16) << 20);
    cx.limits.max_indices = o.max_indices ? o.max_indices : (uint64_t(64) << 20);
    cx.limits.max_image_dimension = o.max_image_dimension ? o.max_image_dimension : 16384;
    cx.limits.max_nodes = o.max_nodes ? o.max_nodes : (1u << 20);
    cx.limits.max_images = o.max_images ? o.max_images : 4096;
    cx.mem.limit = o.memory_budget ? o.memory_budget : (uint64_t(2) << 30);
    file_resolver files(base_dir, allow_files, o.file_access, cx.limits.max_file_bytes, cx.mem);
    cx.files = &files;
    uint64_t json_estimate = 0;
    mvr_scene *scene = nullptr;
    try {
        if (size > cx.limits.max_file_bytes)
            refuse("the file is " + std::to_string(size) + " bytes, over the cap of " +
                   std::to_string(cx.limits.max_file_bytes) + " (mvr_gltf_options.max_file_bytes)");
        cx.mem.charge(size, "the file");
        json_text json = split_container(bytes, size, cx.res, cx);
        json_estimate = scan_json(json.data, json.size);
        cx.mem.charge(json_estimate, "the parsed JSON (estimated from its " + std::to_string(json.size) + " bytes)");
        Model model;
        {
            uint64_t model_size = 0;
            std::string rewritten = extract_resources(json, cx.res, &model_size);
            check_extensions(cx);
            cx.mem.charge(model_size, "tinygltf's model of the JSON");
            json_estimate += model_size;
            tinygltf::TinyGLTF loader;
            // tinygltf is handed no file to open: every resource is a data: placeholder
            loader.SetFsCallbacks(tinygltf::FsCallbacks{refuse_exists, refuse_expand, refuse_read, refuse_write, nullptr});
            loader.SetImageLoader(ignore_placeholder, nullptr);
            std::string err, warn;
            bool ok = loader.LoadASCIIFromString(&model, &err, &warn, rewritten.data(), unsigned(rewritten.size()), "");
            if (!ok)
                refuse(err.empty() ? "not a glTF file" : short_message(err));
            if (!warn.empty())
                cx.warn(short_message(warn));
            // tinygltf 2.7 drops an animation channel without target.node or
            // sampler (as KHR_animation_pointer's channels are) and says so only
            // in err: counted as ignored, warned once
            uint32_t dropped = 0;
            for (const char *lost : {"field is missing in animation.channels.target", "field is missing in animation channels"})
                for (size_t at = err.find(lost); at != std::string::npos; at = err.find(lost, at + 1))
                    ++dropped;
            if (dropped) {
                cx.channels_ignored += dropped;
                cx.warn(std::to_string(dropped) + " animation channel(s) without target.node or sampler (e.g. "
                        "KHR_animation_pointer's) are not implemented; ignored (channel indices in later messages "
                        "skip them)");
            }
            // accessors of a type glTF 2.0 does not define: no components
            // (accessor_at refuses them by name, any other reader by their count)
            for (const auto &u : cx.res.unknown_accessor_types)
                if (size_t(u.first) < model.accessors.size())
                    model.accessors[size_t(u.first)].type = -1;
            // undo the pre-pass's placeholder view: those accessors are zeros
            if (cx.res.placeholder_view) {
                for (int i : cx.res.viewless_accessors)
                    if (size_t(i) < model.accessors.size())
                        model.accessors[size_t(i)].bufferView = -1;
                model.bufferViews.pop_back();
                model.buffers.pop_back();
            }
        }
        cx.model = &model;
        // the scene's node records: a fixed cost each (see core/scene.c)
        cx.mem.charge(uint64_t(model.nodes.size()) * 512, std::to_string(model.nodes.size()) + " nodes");
        if (model.nodes.size() > cx.limits.max_nodes)
            refuse(std::to_string(model.nodes.size()) + " nodes, over the cap of " +
                   std::to_string(cx.limits.max_nodes) + " (mvr_gltf_options.max_nodes)");
        mvr_scene_desc sd;
        std::memset(&sd, 0, sizeof sd);
        // the scene's warnings (repaired values) count as the load's while it
        // runs; the scene keeps the caller's logger afterwards
        sd.logger.fn = count_scene_warning;
        sd.logger.level = MVR_LOG_DEBUG; /* all of it: the forwarder applies the caller's level */
        sd.logger.user_data = &cx;
        mvr_error serr;
        if (mvr_scene_create(&sd, &scene, &serr) != MVR_OK)
            throw load_error(serr.result, serr.message);
        converter cv{cx, scene, model};
        cv.variants();
        convert_cameras_and_lights(cv);
        // which scene: the option, the file's default, or the first
        int si = o.scene ? int(o.scene) - 1 : (model.defaultScene >= 0 ? model.defaultScene : 0);
        if (o.scene && size_t(si) >= model.scenes.size())
            refuse("scene " + std::to_string(o.scene) + " requested (1-based); the file has " +
                   std::to_string(model.scenes.size()));
        std::vector<char> state(model.nodes.size(), 0);
        cv.node_ids.assign(model.nodes.size(), mvr_node_id{0});
        if (!model.scenes.empty()) {
            if (size_t(si) >= model.scenes.size())
                refuse("the default scene " + std::to_string(si) + " does not exist");
            for (int root : model.scenes[size_t(si)].nodes)
                cv.node(root, mvr_node_id{0}, state, 0);
        } else {
            // no scenes: every node that is no one's child is a root
            std::vector<char> child(model.nodes.size(), 0);
            for (const auto &n : model.nodes)
                for (int c : n.children)
                    if (c >= 0 && size_t(c) < child.size())
                        child[size_t(c)] = 1;
            for (size_t i = 0; i < model.nodes.size(); ++i)
                if (!child[i])
                    cv.node(int(i), mvr_node_id{0}, state, 0);
        }
        cv.skins();
        cv.animations();
        uint32_t occlusion_packed = pack_textures(cx, scene);
        charge_texture_uploads(cx, scene, cv.images);
        scene->logger = o.logger;
        if (info) {
            info->warnings = cx.warnings;
            info->camera_nodes = mvr_scene_camera_node_count(scene);
            info->images_missing = cx.images_missing;
            info->images_decoded = cx.images_decoded;
            info->buffers_read = cx.buffers_read;
            info->memory_budget = cx.mem.limit;
            info->memory_peak = cx.mem.peak;
            info->json_bytes_estimate = json_estimate;
            info->animation_channels_ignored = cx.channels_ignored;
            info->images_occlusion_packed = occlusion_packed;
        }
        *out = scene;
        if (error) {
            error->result = MVR_OK;
            error->message[0] = '\0';
        }
        return MVR_OK;
    } catch (const load_error &e) {
        mvr_scene_destroy(scene);
        return mvr_error_set(error, e.result, "mvr_gltf: %s", e.what());
    } catch (const std::bad_alloc &) {
        mvr_scene_destroy(scene);
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_gltf: out of memory");
    } catch (const std::exception &e) {
        mvr_scene_destroy(scene);
        return mvr_error_set(error, MVR_ERROR_INVALID_ASSET, "mvr_gltf: %s", e.what());
    } catch (...) {
        mvr_scene_destroy(scene);
        return mvr_error_set(error, MVR_ERROR_INTERNAL, "mvr_gltf: unknown exception");
    }
}

}  // namespace
}  // namespace mvr_gltf

extern "C" mvr_result mvr_gltf_load_memory(const void *data, size_t size, const mvr_gltf_options *options,
                                           mvr_scene **out_scene, mvr_gltf_info *info, mvr_error *error)
{
    if (!out_scene || !data || size == 0)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_gltf_load_memory: no data or out_scene");
    *out_scene = nullptr;
    const char *base = options ? options->base_dir : nullptr;
    return mvr_gltf::load(static_cast<const unsigned char *>(data), size, base ? base : "", base != nullptr, options,
                          out_scene, info, error);
}

extern "C" mvr_result mvr_gltf_load_file(const char *path, const mvr_gltf_options *options, mvr_scene **out_scene,
                                         mvr_gltf_info *info, mvr_error *error)
{
    if (!out_scene || !path)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_gltf_load_file: NULL argument");
    *out_scene = nullptr;
    try {
        uint64_t cap = options && options->max_file_bytes ? options->max_file_bytes : (uint64_t(1) << 30);
        struct stat sb;
        if (stat(path, &sb) != 0 || !S_ISREG(sb.st_mode))
            return mvr_error_set(error, MVR_ERROR_IO, "mvr_gltf_load_file: cannot open '%s'", path);
        if (uint64_t(sb.st_size) > cap)
            return mvr_error_set(error, MVR_ERROR_INVALID_ASSET,
                                 "mvr_gltf: '%s' is %lld bytes, over the cap of %llu (mvr_gltf_options.max_file_bytes)",
                                 path, (long long)sb.st_size, (unsigned long long)cap);
        if (sb.st_size == 0)
            return mvr_error_set(error, MVR_ERROR_INVALID_ASSET, "mvr_gltf: '%s' is empty", path);
        std::vector<unsigned char> bytes(size_t(sb.st_size));
        std::ifstream f(path, std::ios::binary);
        if (!f.read(reinterpret_cast<char *>(bytes.data()), std::streamsize(bytes.size())))
            return mvr_error_set(error, MVR_ERROR_IO, "mvr_gltf_load_file: cannot read '%s'", path);
        std::string p = path;
        size_t slash = p.find_last_of('/');
        std::string base = options && options->base_dir ? options->base_dir
                           : slash == std::string::npos ? "."
                           : slash == 0               ? "/"
                                                      : p.substr(0, slash);
        mvr_result r = mvr_gltf::load(bytes.data(), bytes.size(), base, true, options, out_scene, info, error);
        if (r != MVR_OK && error) {
            /* name the file in the message */
            std::string m = error->message;
            if (m.rfind("mvr_gltf: ", 0) == 0)
                m = "mvr_gltf: " + p + ": " + m.substr(10);
            std::snprintf(error->message, sizeof error->message, "%s", m.c_str());
        }
        return r;
    } catch (...) {
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_gltf_load_file: out of memory");
    }
}
