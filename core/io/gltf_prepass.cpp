// Before tinygltf sees a byte: the GLB container is checked and split, the
// JSON's nesting and size are bounded, and every buffer's and image's source
// (uri, bufferView, mimeType) is taken out of the JSON. tinygltf then parses
// a JSON whose buffers and images are one-byte data: placeholders: it never
// opens a file, never decodes a resource, and never reads the BIN chunk
// (tinygltf 2.7 bounds that chunk without its 8-byte header, an 8-byte heap
// over-read, and binds every uri-less buffer to it).
#include <cmath>
#include <cstdint>
#include <cstring>

#include <nlohmann/json.hpp>

#include "gltf_accessor_json.hpp"
#include "gltf_prepass.hpp"

namespace mvr_gltf {

// JSON nesting deeper than this is refused before parsing: parsers and
// destructors recurse on nesting, and a glTF never needs more than ~10 levels.
constexpr int max_json_depth = 64;

// Heap bytes per JSON value while it is parsed: a parsed tree's node and
// tinygltf's copy of extras / extensions (tinygltf::Value, 152 bytes), which
// live together at the peak. Measured as the rise of VmHWM over a load: 208
// bytes per value for 2 M numbers in an extras array, 118 per empty object;
// an upper bound, so the budget refuses before a parser allocates.
// tinygltf's model objects are counted apart, by their real sizes
// (model_bytes below): 500 k empty materials are 2 MB of JSON and 1.1 GB of
// tinygltf::Material.
constexpr uint64_t json_bytes_per_value = 256;

uint64_t scan_json(const unsigned char *p, size_t n)
{
    int depth = 0;
    bool in_string = false;
    uint64_t values = 1;
    for (size_t i = 0; i < n; ++i) {
        unsigned char c = p[i];
        if (in_string) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > max_json_depth)
                refuse("JSON nests deeper than " + std::to_string(max_json_depth) + " levels");
            ++values;
        } else if (c == ']' || c == '}') {
            --depth;
        } else if (c == ',' || c == ':') {
            ++values;
        }
    }
    // each value costs its node; its text (strings, keys) is held about twice
    return values * json_bytes_per_value + 2 * uint64_t(n);
}

static uint32_t u32_at(const unsigned char *p)
{
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v; /* GLB is little-endian, like every platform mvr builds for */
}

// glTF 2.0, 4.4 (GLB): a 12-byte header (magic, version 2, length), then
// chunks of (length, type, data), each starting and ending on a 4-byte
// boundary; the first chunk is JSON, an optional BIN chunk follows it;
// chunks of other types are ignored.
json_text split_container(const unsigned char *bytes, size_t size, resources &res, context &cx)
{
    json_text out{bytes, size};
    res.glb = size >= 4 && std::memcmp(bytes, "glTF", 4) == 0;
    if (!res.glb)
        return out;
    if (size < 20)
        refuse("GLB is " + std::to_string(size) + " bytes: too short for a header and a JSON chunk");
    uint32_t version = u32_at(bytes + 4), length = u32_at(bytes + 8);
    if (version != 2)
        refuse("GLB version " + std::to_string(version) + " (2 is supported)");
    if (length > size)
        refuse("GLB header says " + std::to_string(length) + " bytes, the file has " + std::to_string(size) +
               " (truncated?)");
    if (length < size)
        cx.warn("GLB header says " + std::to_string(length) + " bytes, the file has " + std::to_string(size) +
                "; the rest is ignored");
    if (length % 4 != 0)
        refuse("GLB length " + std::to_string(length) + " is not a multiple of 4");
    uint64_t at = 12;
    int chunk = 0;
    bool have_json = false;
    while (at < length) {
        std::string cname = "GLB chunk " + std::to_string(chunk);
        if (length - at < 8)
            refuse(cname + " at byte " + std::to_string(at) + ": its 8-byte header runs past the GLB's end");
        uint32_t clen = u32_at(bytes + at), ctype = u32_at(bytes + at + 4);
        uint64_t data_at = at + 8;
        if (uint64_t(clen) > length - data_at)
            refuse(cname + " (" + std::to_string(clen) + " bytes at byte " + std::to_string(data_at) +
                   ") runs past the GLB's end (" + std::to_string(length) + " bytes)");
        if (clen % 4 != 0)
            refuse(cname + " length " + std::to_string(clen) + " is not a multiple of 4 (chunks are 4-byte aligned)");
        if (chunk == 0) {
            if (ctype != 0x4E4F534Au)
                refuse("GLB's first chunk is not a JSON chunk");
            out = json_text{bytes + data_at, size_t(clen)};
            have_json = true;
        } else if (ctype == 0x4E4F534Au) {
            refuse(cname + " is a second JSON chunk");
        } else if (ctype == 0x004E4942u) {
            if (chunk != 1)
                refuse(cname + " is a BIN chunk; only the chunk after the JSON chunk may be one");
            res.bin = bytes + data_at;
            res.bin_size = clen;
        }
        at = data_at + clen;
        ++chunk;
    }
    if (!have_json)
        refuse("GLB has no JSON chunk");
    return out;
}

namespace {

const char *placeholder_buffer = "data:application/octet-stream;base64,AA==";
const char *placeholder_image = "data:image/png;base64,AA==";

}  // namespace

// What tinygltf 2.7's camera parser would refuse (glTF 2.0, 5.12-5.14: the
// type's object with its required numbers); "" if nothing.
static std::string camera_problem(const nlohmann::json &c)
{
    if (!c.is_object())
        return "not an object";
    auto type = c.find("type");
    if (type == c.end() || !type->is_string())
        return "type is missing or not a string";
    std::string t = type->get<std::string>();
    if (t != "perspective" && t != "orthographic")
        return "type " + quote(t) + " is not perspective or orthographic";
    auto p = c.find(t);
    if (p == c.end() || !p->is_object())
        return t + " is missing or not an object";
    static const char *perspective[] = {"yfov", "znear"};
    static const char *orthographic[] = {"xmag", "ymag", "zfar", "znear"};
    const char **req = t == "perspective" ? perspective : orthographic;
    size_t n = t == "perspective" ? 2 : 4;
    for (size_t k = 0; k < n; ++k) {
        auto v = p->find(req[k]);
        if (v == p->end() || !v->is_number())
            return t + "." + req[k] + " is missing or not a number";
    }
    for (const char *opt : {"aspectRatio", "zfar"}) {
        auto v = p->find(opt);
        if (t == "perspective" && v != p->end() && !v->is_number())
            return t + "." + opt + " is not a number";
    }
    return "";
}

// What tinygltf's model will hold for the top-level arrays: count x sizeof.
static uint64_t model_bytes(const nlohmann::json &doc)
{
    auto count = [&](const char *key) -> uint64_t {
        auto it = doc.find(key);
        return it != doc.end() && it->is_array() ? it->size() : 0;
    };
    auto nested = [&](const char *key, const char *inner) -> uint64_t {
        uint64_t n = 0;
        auto it = doc.find(key);
        if (it != doc.end() && it->is_array())
            for (const auto &e : *it)
                if (e.is_object()) {
                    auto in = e.find(inner);
                    if (in != e.end() && in->is_array())
                        n += in->size();
                }
        return n;
    };
    using namespace tinygltf;
    return count("accessors") * sizeof(Accessor) + count("animations") * sizeof(Animation) +
           nested("animations", "channels") * sizeof(AnimationChannel) +
           nested("animations", "samplers") * sizeof(AnimationSampler) + count("buffers") * sizeof(Buffer) +
           count("bufferViews") * sizeof(BufferView) + count("cameras") * sizeof(Camera) +
           count("images") * sizeof(Image) + count("materials") * sizeof(Material) + count("meshes") * sizeof(Mesh) +
           nested("meshes", "primitives") * sizeof(Primitive) + count("nodes") * sizeof(Node) +
           count("samplers") * sizeof(Sampler) + count("scenes") * sizeof(Scene) + count("skins") * sizeof(Skin) +
           count("textures") * sizeof(Texture);
}

// An integer member in lo..hi: its value, or -1 with *problem set (absent
// and optional: fallback).
static int64_t integer_member(const nlohmann::json &o, const char *key, int64_t lo, int64_t hi, bool required,
                              int64_t fallback, std::string *problem)
{
    auto it = o.find(key);
    if (it == o.end()) {
        if (required && problem->empty())
            *problem = std::string(key) + " is missing";
        return fallback;
    }
    // (nlohmann reads a non-negative integer as unsigned, a negative one as signed)
    bool ok = it->is_number_integer() &&
              (it->is_number_unsigned() ? it->get<uint64_t>() <= uint64_t(hi) && it->get<uint64_t>() >= uint64_t(lo)
                                        : it->get<int64_t>() <= hi && it->get<int64_t>() >= lo);
    if (!ok) {
        if (problem->empty())
            *problem = std::string(key) + " is not an integer in " + std::to_string(lo) + ".." + std::to_string(hi);
        return -1;
    }
    return it->is_number_unsigned() ? int64_t(it->get<uint64_t>()) : it->get<int64_t>();
}

// extensionsRequired and extensionsUsed (their strings; the loader checks
// them before tinygltf parses, so an unsupported extension is named even
// where its JSON would make tinygltf fail).
static void extension_lists(const nlohmann::json &doc, resources &res)
{
    for (auto list : {std::make_pair("extensionsRequired", &res.extensions_required),
                      std::make_pair("extensionsUsed", &res.extensions_used)}) {
        auto it = doc.find(list.first);
        if (it == doc.end() || !it->is_array())
            continue;
        for (const auto &e : *it)
            if (e.is_string())
                list.second->push_back(e.get<std::string>());
    }
}

// bufferViews[i].extensions.EXT_meshopt_compression, read here (tinygltf
// narrows its integers to int); its problems are reported when the view is read.
static void compressed_views(const nlohmann::json &doc, resources &res)
{
    auto views = doc.find("bufferViews");
    if (views == doc.end() || !views->is_array())
        return;
    const int64_t max = INT64_MAX / 2;
    for (size_t i = 0; i < views->size() && i <= size_t(INT32_MAX); ++i) {
        const nlohmann::json &v = (*views)[i];
        if (!v.is_object())
            continue;
        auto ext = v.find("extensions");
        if (ext == v.end() || !ext->is_object())
            continue;
        auto mo = ext->find("EXT_meshopt_compression");
        if (mo == ext->end())
            continue;
        meshopt_source &m = res.meshopt_views[int(i)];
        if (!mo->is_object()) {
            m.problem = "not an object";
            continue;
        }
        m.buffer = integer_member(*mo, "buffer", 0, INT32_MAX, true, -1, &m.problem);
        m.byte_offset = integer_member(*mo, "byteOffset", 0, max, false, 0, &m.problem);
        m.byte_length = integer_member(*mo, "byteLength", 1, max, true, 0, &m.problem);
        m.byte_stride = integer_member(*mo, "byteStride", 1, max, true, 0, &m.problem);
        m.count = integer_member(*mo, "count", 1, max, true, 0, &m.problem);
        auto mode = mo->find("mode");
        if (mode == mo->end() || !mode->is_string()) {
            if (m.problem.empty())
                m.problem = "mode is missing or not a string";
        } else {
            m.mode = mode->get<std::string>();
        }
        auto filter = mo->find("filter");
        if (filter != mo->end()) {
            if (filter->is_string())
                m.filter = filter->get<std::string>();
            else if (m.problem.empty())
                m.problem = "filter is not a string";
        }
    }
}

// Calls fn(i, k, value) for each meshes[i].primitives[k].extensions.<name>
// (meshes, primitives and extensions that are not objects are the parser's
// to refuse).
template <typename F> static void each_primitive_extension(const nlohmann::json &doc, const char *name, F fn)
{
    auto meshes = doc.find("meshes");
    if (meshes == doc.end() || !meshes->is_array())
        return;
    for (size_t i = 0; i < meshes->size() && i <= size_t(INT32_MAX); ++i) {
        const nlohmann::json &mesh = (*meshes)[i];
        auto prims = mesh.is_object() ? mesh.find("primitives") : mesh.end();
        if (!mesh.is_object() || prims == mesh.end() || !prims->is_array())
            continue;
        for (size_t k = 0; k < prims->size() && k <= size_t(INT32_MAX); ++k) {
            const nlohmann::json &p = (*prims)[k];
            auto ext = p.is_object() ? p.find("extensions") : p.end();
            if (!p.is_object() || ext == p.end() || !ext->is_object())
                continue;
            auto found = ext->find(name);
            if (found != ext->end())
                fn(int(i), int(k), *found);
        }
    }
}

// meshes[i].primitives[k].extensions.KHR_draco_mesh_compression, read here
// like the views'; problems are reported when the primitive is read.
static void draco_primitives(const nlohmann::json &doc, resources &res)
{
    each_primitive_extension(doc, "KHR_draco_mesh_compression", [&](int i, int k, const nlohmann::json &dr) {
        draco_source &d = res.draco_primitives[{i, k}];
        if (!dr.is_object()) {
            d.problem = "not an object";
            return;
        }
        d.buffer_view = integer_member(dr, "bufferView", 0, INT32_MAX, true, -1, &d.problem);
        auto attrs = dr.find("attributes");
        if (attrs == dr.end() || !attrs->is_object()) {
            if (d.problem.empty())
                d.problem = "attributes is missing or not an object";
            return;
        }
        for (auto a = attrs->begin(); a != attrs->end(); ++a) {
            std::string why;
            int64_t id = integer_member(*attrs, a.key().c_str(), 0, UINT32_MAX, true, -1, &why);
            if (!why.empty() && d.problem.empty())
                d.problem = "attributes." + key_name(a.key()) + " is not an integer in 0.." + std::to_string(UINT32_MAX);
            d.attributes.push_back({a.key(), id});
        }
    });
}

// extensions.KHR_materials_variants (the variants' names) and each
// primitive's extensions.KHR_materials_variants (its mappings), read here
// like the views'; problems are reported when the root or the primitive is read.
static void material_variants(const nlohmann::json &doc, resources &res)
{
    auto ext = doc.find("extensions");
    auto root = ext != doc.end() && ext->is_object() ? ext->find("KHR_materials_variants") : doc.end();
    if (ext != doc.end() && ext->is_object() && root != ext->end()) {
        variants_source &v = res.variants;
        v.present = true;
        auto list = root->is_object() ? root->find("variants") : root->end();
        if (!root->is_object())
            v.problem = "is not an object";
        else if (list == root->end() || !list->is_array())
            v.problem = "variants is missing or not an array";
        for (size_t i = 0; v.problem.empty() && i < list->size(); ++i) {
            const nlohmann::json &e = (*list)[i];
            auto name = e.is_object() ? e.find("name") : e.end();
            if (!e.is_object() || name == e.end() || !name->is_string())
                v.problem = "variants[" + std::to_string(i) + "]" +
                            (e.is_object() ? ".name is missing or not a string" : " is not an object");
            else
                v.names.push_back(name->get<std::string>());
        }
    }
    each_primitive_extension(doc, "KHR_materials_variants", [&](int i, int k, const nlohmann::json &mv) {
        primitive_variants_source &d = res.variant_primitives[{i, k}];
        auto maps = mv.is_object() ? mv.find("mappings") : mv.end();
        if (!mv.is_object()) {
            d.problem = "is not an object";
            return;
        }
        if (maps == mv.end() || !maps->is_array()) {
            d.problem = "mappings is missing or not an array";
            return;
        }
        for (size_t j = 0; j < maps->size() && d.problem.empty(); ++j) {
            const nlohmann::json &m = (*maps)[j];
            std::string mw = "mappings[" + std::to_string(j) + "]";
            if (!m.is_object()) {
                d.problem = mw + " is not an object";
                break;
            }
            variant_mapping_source ms;
            std::string why;
            ms.material = integer_member(m, "material", 0, INT32_MAX, true, -1, &why);
            if (!why.empty()) {
                d.problem = mw + "." + why;
                break;
            }
            auto vars = m.find("variants");
            if (vars == m.end() || !vars->is_array()) {
                d.problem = mw + ".variants is missing or not an array";
                break;
            }
            for (size_t n = 0; n < vars->size(); ++n) {
                const nlohmann::json &x = (*vars)[n];
                bool ok = x.is_number_unsigned() && x.get<uint64_t>() <= uint64_t(INT32_MAX);
                if (!ok) {
                    d.problem = mw + ".variants[" + std::to_string(n) + "] is not an integer in 0.." +
                                std::to_string(INT32_MAX);
                    break;
                }
                ms.variants.push_back(int64_t(x.get<uint64_t>()));
            }
            d.mappings.push_back(std::move(ms));
        }
    });
}

// The PBR extensions of materials[i].extensions, checked on the JSON itself
// where the parser would lose what is wrong: tinygltf drops an extension
// whose value is not an object, and a member whose value is an empty
// object, so a malformed one would vanish instead of being refused (the
// rest, values and indices, gltf_material_ext.cpp checks with the same
// messages).
static void material_extension_shapes(const nlohmann::json &doc)
{
    static const char *const pbr[] = {"KHR_materials_ior", "KHR_materials_specular", "KHR_materials_clearcoat",
                                      "KHR_materials_sheen", "KHR_materials_transmission", "KHR_materials_volume",
                                      "KHR_materials_dispersion", "KHR_materials_iridescence",
                                      "KHR_materials_anisotropy", "KHR_materials_pbrSpecularGlossiness"};
    auto materials = doc.find("materials");
    if (materials == doc.end() || !materials->is_array())
        return;
    for (size_t i = 0; i < materials->size(); ++i) {
        const nlohmann::json &m = (*materials)[i];
        auto ext = m.is_object() ? m.find("extensions") : m.end();
        if (!m.is_object() || ext == m.end() || !ext->is_object())
            continue;
        for (const char *name : pbr) {
            auto e = ext->find(name);
            if (e == ext->end())
                continue;
            std::string w = "materials[" + std::to_string(i) + "].extensions." + name;
            if (!e->is_object())
                refuse(w + " is not an object");
            for (auto member = e->begin(); member != e->end(); ++member) {
                const std::string &key = member.key();
                if (key.size() < 7 || key.compare(key.size() - 7, 7, "Texture") != 0)
                    continue;
                if (!member->is_object())
                    refuse(w + "." + key_name(key) + " is not an object");
                auto index = member->find("index");
                if (index == member->end() || !index->is_number_unsigned() || index->get<uint64_t>() > INT32_MAX)
                    refuse(w + "." + key_name(key) + ".index is missing or not a valid index");
            }
        }
    }
}

// Numbers with a zero fraction become integers (3.0 -> 3), everywhere but
// in extras (the application's own data, passed on as written). JSON Schema,
// which glTF 2.0's schema is written in, counts any number with a zero
// fractional part as an "integer" (draft 2020-12, Validation 6.1.1), so
// "count": 3.0 is valid; tinygltf 2.7 and the checks below take only JSON
// integers. A number field is unchanged by this: JSON has one number type.
// Only magnitudes below 2^53 (exact in a double) are rewritten.
static void integral_numbers(nlohmann::json &v, int depth)
{
    if (v.is_number_float()) {
        double d = v.get<double>();
        if (std::fabs(d) < 9007199254740992.0 && d == std::trunc(d))
            v = d < 0 ? nlohmann::json(int64_t(d)) : nlohmann::json(uint64_t(d));
        return;
    }
    if (depth >= max_json_depth) /* scan_json bounded the nesting already */
        return;
    if (v.is_array()) {
        for (auto &e : v)
            integral_numbers(e, depth + 1);
    } else if (v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it)
            if (it.key() != "extras")
                integral_numbers(it.value(), depth + 1);
    }
}

// glTF 2.0's accessor types (5.1.10: the schema's anyOf also admits any
// other string, for types a later version may add).
static bool known_accessor_type(const std::string &t)
{
    for (const char *k : {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"})
        if (t == k)
            return true;
    return false;
}

std::string extract_resources(const json_text &text, resources &res, uint64_t *model_size)
{
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text.data, text.data + text.size);
    } catch (const nlohmann::json::exception &e) {
        refuse("the JSON does not parse: " + quote(e.what()));
    }
    if (!doc.is_object())
        refuse(std::string("the JSON is a ") + doc.type_name() + ", not an object");
    integral_numbers(doc, 0);
    *model_size = model_bytes(doc);
    check_accessor_json(doc);   // before tinygltf narrows or drops what it reads
    auto buffers = doc.find("buffers");
    if (buffers != doc.end()) {
        if (!buffers->is_array())
            refuse(std::string("buffers is a ") + buffers->type_name() + ", not an array");
        res.buffers.resize(buffers->size());
        for (size_t i = 0; i < buffers->size(); ++i) {
            std::string w = "buffers[" + std::to_string(i) + "]";
            nlohmann::json &b = (*buffers)[i];
            if (!b.is_object())
                refuse(w + " is not an object");
            buffer_source &src = res.buffers[i];
            auto len = b.find("byteLength");
            if (len == b.end() || !len->is_number_integer() || len->get<int64_t>() < 1)
                refuse(w + ".byteLength is missing or not an integer >= 1");
            src.byte_length = len->get<uint64_t>();
            auto uri = b.find("uri");
            if (uri != b.end()) {
                if (!uri->is_string())
                    refuse(w + ".uri is not a string");
                src.has_uri = true;
                src.uri = uri->get<std::string>();
            }
            auto ext = b.find("extensions");
            if (ext != b.end() && ext->is_object()) {
                auto mo = ext->find("EXT_meshopt_compression");
                if (mo != ext->end() && mo->is_object()) {
                    auto fb = mo->find("fallback");
                    src.meshopt_fallback = fb != mo->end() && fb->is_boolean() && fb->get<bool>();
                }
            }
            b["uri"] = placeholder_buffer;
            b["byteLength"] = 1;
        }
    }
    extension_lists(doc, res);
    compressed_views(doc, res);
    draco_primitives(doc, res);
    material_variants(doc, res);
    material_extension_shapes(doc);
    auto images = doc.find("images");
    if (images != doc.end()) {
        if (!images->is_array())
            refuse(std::string("images is a ") + images->type_name() + ", not an array");
        res.images.resize(images->size());
        for (size_t i = 0; i < images->size(); ++i) {
            std::string w = "images[" + std::to_string(i) + "]";
            nlohmann::json &im = (*images)[i];
            if (!im.is_object())
                refuse(w + " is not an object");
            image_source &src = res.images[i];
            auto uri = im.find("uri");
            if (uri != im.end()) {
                if (!uri->is_string())
                    refuse(w + ".uri is not a string");
                src.has_uri = true;
                src.uri = uri->get<std::string>();
            }
            auto view = im.find("bufferView");
            if (view != im.end()) {
                if (!view->is_number_integer() || view->get<int64_t>() < 0 || view->get<int64_t>() > INT32_MAX)
                    refuse(w + ".bufferView is not a valid index");
                src.buffer_view = int(view->get<int64_t>());
                im.erase("bufferView");
            }
            if (src.has_uri && src.buffer_view >= 0)
                refuse(w + " has both a uri and a bufferView");
            auto mime = im.find("mimeType");
            if (mime != im.end() && mime->is_string())
                src.mime_type = mime->get<std::string>();
            im["uri"] = placeholder_image;
        }
    }
    auto accessors = doc.find("accessors");
    if (accessors != doc.end() && accessors->is_array()) {
        for (size_t i = 0; i < accessors->size(); ++i) {
            nlohmann::json &a = (*accessors)[i];
            if (a.is_object() && a.find("bufferView") == a.end())
                res.viewless_accessors.push_back(int(i));
            // a type tinygltf 2.7 would refuse the whole file for: an error
            // only where the accessor is read (the loader marks it so)
            auto type = a.is_object() ? a.find("type") : a.end();
            if (a.is_object() && type != a.end() && type->is_string() && !known_accessor_type(type->get<std::string>())) {
                res.unknown_accessor_types[int(i)] = type->get<std::string>();
                *type = "SCALAR";
            }
        }
        if (!res.viewless_accessors.empty()) {
            nlohmann::json &views = doc["bufferViews"];
            nlohmann::json &bufs = doc["buffers"];
            if (!views.is_array())
                views = nlohmann::json::array();
            if (!bufs.is_array())
                bufs = nlohmann::json::array();
            bufs.push_back({{"byteLength", 1}, {"uri", placeholder_buffer}});
            views.push_back({{"buffer", bufs.size() - 1}, {"byteLength", 1}});
            for (int i : res.viewless_accessors)
                (*accessors)[size_t(i)]["bufferView"] = views.size() - 1;
            res.placeholder_view = true;
        }
    }
    auto cameras = doc.find("cameras");
    if (cameras != doc.end() && cameras->is_array()) {
        for (size_t i = 0; i < cameras->size(); ++i) {
            std::string why = camera_problem((*cameras)[i]);
            if (why.empty())
                continue;
            res.bad_cameras[int(i)] = "cameras[" + std::to_string(i) + "]: " + why;
            (*cameras)[i] = {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 1.0}}}};
        }
    }
    return doc.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace mvr_gltf
