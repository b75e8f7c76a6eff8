// mvr_gltf: tinygltf parses, this file validates and converts into an
// mvr_scene. No exception leaves it: every failure is an mvr_result with a
// message naming the glTF object.
#include <sys/stat.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "gltf_internal.hpp"
#include "mvr/mvr_image.h"

extern "C" {
#include "core_util.h"
}

namespace mvr_gltf {

void context::warn(const std::string &msg)
{
    warnings++;
    if (logger.fn && (logger.level == MVR_LOG_DEFAULT || logger.level >= MVR_LOG_WARNING))
        logger.fn(MVR_LOG_WARNING, MVR_LOG_ID_GENERAL, ("mvr_gltf: " + msg).c_str(), logger.user_data);
}

namespace {

using tinygltf::Model;

// Extensions mvr implements (a required one outside this list is an error).
const std::set<std::string> implemented = {
    "KHR_lights_punctual", "KHR_materials_unlit", "KHR_texture_transform", "KHR_materials_emissive_strength",
    "KHR_mesh_quantization"};

// ---- file access for tinygltf: bounded reads, no ~ expansion ----

struct fs_state {
    uint64_t max_bytes;
    bool allow_files;
    std::string error;
};

bool fs_exists(const std::string &path, void *user)
{
    auto *st = static_cast<fs_state *>(user);
    if (!st->allow_files) {
        if (st->error.empty())
            st->error = "external file '" + path + "' refused: loaded from memory without a base_dir";
        return false;
    }
    struct stat sb;
    return stat(path.c_str(), &sb) == 0 && S_ISREG(sb.st_mode);
}

std::string fs_expand(const std::string &path, void *)
{
    return path; // no home-directory or environment expansion of names from a file
}

bool fs_read(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *user)
{
    auto *st = static_cast<fs_state *>(user);
    if (!st->allow_files) {
        if (err)
            *err += "external file '" + path + "' refused: loaded from memory without a base_dir\n";
        return false;
    }
    struct stat sb;
    if (stat(path.c_str(), &sb) != 0 || !S_ISREG(sb.st_mode)) {
        if (err)
            *err += "cannot open '" + path + "'\n";
        return false;
    }
    if (uint64_t(sb.st_size) > st->max_bytes) {
        st->error = "'" + path + "' is " + std::to_string(sb.st_size) + " bytes, over the cap of " +
                    std::to_string(st->max_bytes) + " (mvr_gltf_options.max_file_bytes)";
        if (err)
            *err += st->error + "\n";
        return false;
    }
    std::ifstream f(path, std::ios::binary);
    out->resize(size_t(sb.st_size));
    if (!f.read(reinterpret_cast<char *>(out->data()), std::streamsize(sb.st_size))) {
        if (err)
            *err += "cannot read '" + path + "'\n";
        return false;
    }
    return true;
}

bool fs_write(std::string *, const std::string &, const std::vector<unsigned char> &, void *)
{
    return false; // the loader never writes
}

// Images are kept encoded (mvr_image decodes them with OpenImageIO). For an
// image in a buffer view, tinygltf 2.7 computes bytes and size from the view
// without checking them against the buffer (found by the fuzzer): the view is
// checked here, against the model tinygltf is filling (user = the Model),
// before a byte is read.
bool keep_encoded(tinygltf::Image *image, const int index, std::string *err, std::string *, int, int,
                  const unsigned char *bytes, int size, void *user)
{
    if (size <= 0 || !bytes)
        return false;
    if (image->bufferView >= 0) {
        const auto *model = static_cast<const tinygltf::Model *>(user);
        std::string what = "images[" + std::to_string(index) + "]: bufferView " + std::to_string(image->bufferView);
        if (size_t(image->bufferView) >= model->bufferViews.size()) {
            if (err)
                *err += what + " does not exist\n";
            return false;
        }
        const auto &v = model->bufferViews[size_t(image->bufferView)];
        if (v.buffer < 0 || size_t(v.buffer) >= model->buffers.size()) {
            if (err)
                *err += what + " names a missing buffer\n";
            return false;
        }
        const auto &data = model->buffers[size_t(v.buffer)].data;
        uint64_t end = uint64_t(v.byteOffset) + uint64_t(v.byteLength);
        if (end > data.size() || uint64_t(size) > v.byteLength || end < v.byteOffset ||
            bytes < data.data() || bytes + size > data.data() + data.size()) {
            if (err)
                *err += what + " reads past the end of buffer " + std::to_string(v.buffer) + "\n";
            return false;
        }
    }
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

// JSON nesting deeper than this is refused before parsing: parsers and
// destructors recurse on nesting, and a glTF never needs more than ~10 levels.
constexpr int max_json_depth = 64;

void check_json_depth(const unsigned char *p, size_t n)
{
    int depth = 0;
    bool in_string = false;
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
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

// The JSON chunk of a GLB (12-byte header, then chunks of length + type).
void check_glb(const unsigned char *p, size_t n)
{
    if (n < 20)
        refuse("GLB is " + std::to_string(n) + " bytes: too short for a header and a JSON chunk");
    uint32_t version, length, chunk_length, chunk_type;
    std::memcpy(&version, p + 4, 4);
    std::memcpy(&length, p + 8, 4);
    std::memcpy(&chunk_length, p + 12, 4);
    std::memcpy(&chunk_type, p + 16, 4);
    if (version != 2)
        refuse("GLB version " + std::to_string(version) + " (2 is supported)");
    if (length > n)
        refuse("GLB header says " + std::to_string(length) + " bytes, the file has " + std::to_string(n) +
               " (truncated?)");
    if (chunk_type != 0x4E4F534Au || uint64_t(chunk_length) + 20 > length)
        refuse("GLB's first chunk is not a JSON chunk inside the file");
    check_json_depth(p + 20, chunk_length);
}

// ---- conversions ----

mvr_filter filter_of(int gl, bool min)
{
    switch (gl) {
    case TINYGLTF_TEXTURE_FILTER_NEAREST: return MVR_FILTER_NEAREST;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: return MVR_FILTER_LINEAR;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: return min ? MVR_FILTER_NEAREST_MIPMAP_NEAREST : MVR_FILTER_NEAREST;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: return min ? MVR_FILTER_LINEAR_MIPMAP_NEAREST : MVR_FILTER_LINEAR;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: return min ? MVR_FILTER_NEAREST_MIPMAP_LINEAR : MVR_FILTER_NEAREST;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: return min ? MVR_FILTER_LINEAR_MIPMAP_LINEAR : MVR_FILTER_LINEAR;
    default: return MVR_FILTER_DEFAULT;
    }
}

mvr_wrap wrap_of(int gl)
{
    switch (gl) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return MVR_WRAP_CLAMP_TO_EDGE;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return MVR_WRAP_MIRRORED_REPEAT;
    default: return MVR_WRAP_REPEAT;
    }
}

double number(const tinygltf::Value &v, const char *key, double fallback)
{
    if (!v.IsObject() || !v.Has(key))
        return fallback;
    const tinygltf::Value &n = v.Get(key);
    return n.IsNumber() ? n.GetNumberAsDouble() : fallback;
}

struct converter {
    context &cx;
    mvr_scene *scene;
    const Model &m;
    std::map<int, mvr_image_id> images;      // glTF image -> scene image
    std::map<int, mvr_material_id> materials;
    std::map<int, mvr_mesh_id> meshes;
    std::map<int, mvr_camera_id> cameras;
    std::map<int, mvr_light_id> lights;
    bool warned_skin = false, warned_morph = false;

    void check(mvr_result r, const std::string &what)
    {
        if (r != MVR_OK)
            throw load_error(r == MVR_ERROR_INVALID_ARGUMENT ? MVR_ERROR_INVALID_ASSET : r,
                             what + ": " + mvr_scene_last_error(scene));
    }

    mvr_image_id image(int index, const std::string &what)
    {
        auto found = images.find(index);
        if (found != images.end())
            return found->second;
        if (index < 0 || size_t(index) >= m.images.size())
            refuse(what + ": image " + std::to_string(index) + " does not exist");
        const tinygltf::Image &img = m.images[size_t(index)];
        std::string iname = "images[" + std::to_string(index) + "]";
        std::vector<unsigned char> bytes = img.image;
        if (img.bufferView >= 0) {
            // an image in a buffer view: bounds checked like any accessor
            if (size_t(img.bufferView) >= m.bufferViews.size())
                refuse(iname + ": bufferView " + std::to_string(img.bufferView) + " does not exist");
            const auto &v = m.bufferViews[size_t(img.bufferView)];
            if (v.buffer < 0 || size_t(v.buffer) >= m.buffers.size())
                refuse(iname + ": bufferView " + std::to_string(img.bufferView) + " names a missing buffer");
            const auto &data = m.buffers[size_t(v.buffer)].data;
            if (add_checked(v.byteOffset, v.byteLength, iname) > data.size())
                refuse(iname + ": bufferView " + std::to_string(img.bufferView) + " reads past the end of buffer " +
                       std::to_string(v.buffer));
            if (bytes.empty())
                bytes.assign(data.begin() + long(v.byteOffset), data.begin() + long(v.byteOffset + v.byteLength));
        }
        if (bytes.empty())
            refuse(iname + ": no image data (missing file or bufferView)");
        mvr_image_data decoded;
        mvr_error err;
        const char *hint = !img.mimeType.empty() ? img.mimeType.c_str() : img.uri.c_str();
        if (mvr_image_decode(bytes.data(), bytes.size(), hint, cx.limits.max_image_dimension, &decoded, &err) !=
            MVR_OK)
            throw load_error(err.result == MVR_ERROR_OUT_OF_MEMORY ? err.result : MVR_ERROR_INVALID_ASSET,
                             iname + (img.uri.empty() ? "" : " (" + (img.uri.size() > 64 ? img.uri.substr(0, 64) + "..." : img.uri) + ")") +
                                 ": " + err.message);
        mvr_image_desc d = {decoded.width, decoded.height, static_cast<const uint8_t *>(decoded.pixels),
                            img.name.c_str()};
        mvr_image_id id = {0};
        mvr_result r = mvr_scene_add_image(scene, &d, &id);
        mvr_image_free(&decoded);
        check(r, iname);
        images[index] = id;
        return id;
    }

    mvr_texture_ref texture(const tinygltf::TextureInfo &info, const std::string &what)
    {
        return texture_ref(info.index, info.texCoord, info.extensions, what);
    }

    mvr_texture_ref texture_ref(int index, int texcoord, const tinygltf::ExtensionMap &ext, const std::string &what)
    {
        mvr_texture_ref ref;
        std::memset(&ref, 0, sizeof ref);
        if (index < 0)
            return ref;
        if (size_t(index) >= m.textures.size())
            refuse(what + ": texture " + std::to_string(index) + " does not exist (" +
                   std::to_string(m.textures.size()) + " textures)");
        const tinygltf::Texture &t = m.textures[size_t(index)];
        std::string tname = "textures[" + std::to_string(index) + "]";
        if (t.source < 0) {
            cx.warn(tname + " has no source image (or only an extension's); " + what + " is left untextured");
            return ref;
        }
        ref.image = image(t.source, tname);
        if (t.sampler >= 0) {
            if (size_t(t.sampler) >= m.samplers.size())
                refuse(tname + ": sampler " + std::to_string(t.sampler) + " does not exist");
            const tinygltf::Sampler &s = m.samplers[size_t(t.sampler)];
            ref.sampler.mag_filter = filter_of(s.magFilter, false);
            ref.sampler.min_filter = filter_of(s.minFilter, true);
            ref.sampler.wrap_s = wrap_of(s.wrapS);
            ref.sampler.wrap_t = wrap_of(s.wrapT);
        }
        ref.texcoord = uint32_t(texcoord);
        auto tt = ext.find("KHR_texture_transform");
        if (tt != ext.end()) {
            const tinygltf::Value &v = tt->second;
            ref.transform.enabled = true;
            if (v.Has("offset") && v.Get("offset").IsArray() && v.Get("offset").ArrayLen() == 2) {
                ref.transform.offset[0] = float(v.Get("offset").Get(0).GetNumberAsDouble());
                ref.transform.offset[1] = float(v.Get("offset").Get(1).GetNumberAsDouble());
            }
            ref.transform.rotation = float(number(v, "rotation", 0.0));
            ref.transform.scale[0] = ref.transform.scale[1] = 1.0f;
            if (v.Has("scale") && v.Get("scale").IsArray() && v.Get("scale").ArrayLen() == 2) {
                ref.transform.scale[0] = float(v.Get("scale").Get(0).GetNumberAsDouble());
                ref.transform.scale[1] = float(v.Get("scale").Get(1).GetNumberAsDouble());
            }
            if (v.Has("texCoord"))
                ref.texcoord = uint32_t(number(v, "texCoord", texcoord)); /* overrides, per the extension */
        }
        if (ref.texcoord > 1) {
            cx.warn(what + " uses TEXCOORD_" + std::to_string(ref.texcoord) + "; mvr reads sets 0 and 1, so it is left untextured");
            std::memset(&ref, 0, sizeof ref);
        }
        return ref;
    }

    mvr_material_id material(int index)
    {
        auto found = materials.find(index);
        if (found != materials.end())
            return found->second;
        if (size_t(index) >= m.materials.size())
            refuse("material " + std::to_string(index) + " does not exist (" + std::to_string(m.materials.size()) +
                   " materials)");
        const tinygltf::Material &g = m.materials[size_t(index)];
        std::string w = "materials[" + std::to_string(index) + "]";
        mvr_material_desc d = mvr_material_defaults();
        const auto &pbr = g.pbrMetallicRoughness;
        for (size_t c = 0; c < 4 && c < pbr.baseColorFactor.size(); ++c)
            d.base_color_factor[c] = float(pbr.baseColorFactor[c]);
        d.metallic_factor = float(pbr.metallicFactor);
        d.roughness_factor = float(pbr.roughnessFactor);
        for (size_t c = 0; c < 3 && c < g.emissiveFactor.size(); ++c)
            d.emissive_factor[c] = float(g.emissiveFactor[c]);
        d.base_color = texture(pbr.baseColorTexture, w + ".pbrMetallicRoughness.baseColorTexture");
        d.metallic_roughness = texture(pbr.metallicRoughnessTexture, w + ".pbrMetallicRoughness.metallicRoughnessTexture");
        d.normal = texture_ref(g.normalTexture.index, g.normalTexture.texCoord, g.normalTexture.extensions,
                               w + ".normalTexture");
        d.normal_scale = float(g.normalTexture.scale);
        d.occlusion = texture_ref(g.occlusionTexture.index, g.occlusionTexture.texCoord,
                                  g.occlusionTexture.extensions, w + ".occlusionTexture");
        d.occlusion_strength = float(g.occlusionTexture.strength);
        d.emissive = texture(g.emissiveTexture, w + ".emissiveTexture");
        if (g.alphaMode == "MASK")
            d.alpha_mode = MVR_ALPHA_MASK;
        else if (g.alphaMode == "BLEND")
            d.alpha_mode = MVR_ALPHA_BLEND;
        else if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty())
            refuse(w + ": alphaMode '" + g.alphaMode + "' is not OPAQUE, MASK or BLEND");
        d.alpha_cutoff = float(g.alphaCutoff);
        if (d.alpha_cutoff == 0.0f)
            d.alpha_cutoff = 1e-7f; /* a cutoff of 0 is valid glTF; 0 means "default" in mvr */
        d.double_sided = g.doubleSided;
        d.unlit = g.extensions.count("KHR_materials_unlit") > 0;
        auto es = g.extensions.find("KHR_materials_emissive_strength");
        if (es != g.extensions.end())
            d.emissive_strength = float(number(es->second, "emissiveStrength", 1.0));
        if (d.emissive_strength == 0.0f)
            for (float &e : d.emissive_factor)
                e = 0.0f; /* strength 0 turns emission off; 0 means "default" in mvr */
        d.name = g.name.c_str();
        mvr_material_id id = {0};
        check(mvr_scene_add_material(scene, &d, &id), w);
        materials[index] = id;
        return id;
    }

    mvr_mesh_id mesh(int index);
    void node(int index, mvr_node_id parent, std::vector<char> &state, uint32_t depth);
};

// Index list of a primitive in list form: strips, fans and loops converted.
std::vector<uint32_t> to_list(int mode, const std::vector<uint32_t> &in, mvr_primitive_mode *out_mode)
{
    std::vector<uint32_t> out;
    size_t n = in.size();
    switch (mode) {
    case TINYGLTF_MODE_POINTS: *out_mode = MVR_PRIMITIVE_POINTS; return in;
    case TINYGLTF_MODE_LINE: *out_mode = MVR_PRIMITIVE_LINES; out = in; out.resize(n / 2 * 2); return out;
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
        out = in;
        out.resize(n / 3 * 3);
        return out;
    }
}

constexpr uint32_t FLOAT = ANY_FLOAT;
constexpr uint32_t I8 = 1u << 0, U8 = 1u << 1, I16 = 1u << 2, U16 = 1u << 3;

mvr_mesh_id converter::mesh(int index)
{
    auto found = meshes.find(index);
    if (found != meshes.end())
        return found->second;
    if (size_t(index) >= m.meshes.size())
        refuse("mesh " + std::to_string(index) + " does not exist (" + std::to_string(m.meshes.size()) + " meshes)");
    const tinygltf::Mesh &g = m.meshes[size_t(index)];
    std::string w = "meshes[" + std::to_string(index) + "]";
    struct prim_data {
        std::vector<float> pos, nrm, tan, uv0, uv1, col;
        std::vector<uint32_t> idx;
        mvr_primitive_mode mode;
        mvr_material_id material;
    };
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
        if (!p.targets.empty() && !warned_morph) {
            cx.warn(pw + " has morph targets: mvr draws the base mesh (weights 0)");
            warned_morph = true;
        }
        prim_data d;
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
            d.col.resize(vcount * 4, 1.0f);
            for (size_t v = 0; v < vcount; ++v)
                for (int ch = 0; ch < comps; ++ch)
                    d.col[v * 4 + size_t(ch)] = c[v * size_t(comps) + size_t(ch)];
        }
        if (attr("JOINTS_0") >= 0 && !warned_skin) {
            cx.warn(pw + " is skinned: mvr draws the bind pose");
            warned_skin = true;
        }
        std::vector<uint32_t> idx;
        if (p.indices >= 0) {
            idx = read_indices(cx, p.indices, pw + ".indices");
            for (size_t i = 0; i < idx.size(); ++i)
                if (idx[i] >= vcount)
                    refuse(pw + ".indices: accessor " + std::to_string(p.indices) + " element " + std::to_string(i) +
                           " = " + std::to_string(idx[i]) + " is past the " + std::to_string(vcount) + " vertices");
        } else {
            idx.resize(vcount);
            for (size_t i = 0; i < vcount; ++i)
                idx[i] = uint32_t(i);
        }
        d.idx = to_list(p.mode, idx, &d.mode);
        cx.indices = add_checked(cx.indices, d.idx.size(), pw);
        if (cx.indices > cx.limits.max_indices)
            refuse(pw + ": more than " + std::to_string(cx.limits.max_indices) +
                   " indices in the file (mvr_gltf_options.max_indices)");
        if (d.idx.empty()) {
            cx.warn(pw + " has too few vertices for its mode; skipped");
            continue;
        }
        d.material = p.material >= 0 ? material(p.material) : mvr_material_id{0};
        data.push_back(std::move(d));
    }
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
    }
    mvr_mesh_desc md = {prims.data(), uint32_t(prims.size()), g.name.c_str()};
    check(mvr_scene_add_mesh(scene, &md, &id), w);
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
    if (g.skin >= 0 && !warned_skin) {
        cx.warn(w + " is skinned: mvr draws the bind pose");
        warned_skin = true;
    }
    if (g.camera >= 0) {
        auto found = cameras.find(g.camera);
        if (found == cameras.end())
            refuse(w + ": camera " + std::to_string(g.camera) + " does not exist");
        d.camera = found->second;
    }
    auto lp = g.extensions.find("KHR_lights_punctual");
    if (lp != g.extensions.end()) {
        int li = int(number(lp->second, "light", -1));
        auto found = lights.find(li);
        if (found == lights.end())
            refuse(w + ".extensions.KHR_lights_punctual: light " + std::to_string(li) + " does not exist");
        d.light = found->second;
    }
    mvr_node_id id = {0};
    check(mvr_scene_add_node(scene, &d, &id), w);
    for (int child : g.children)
        node(child, id, state, depth + 1);
    state[size_t(index)] = 2;
}

void convert_cameras_and_lights(converter &cv)
{
    const Model &m = cv.m;
    for (size_t i = 0; i < m.cameras.size(); ++i) {
        const tinygltf::Camera &c = m.cameras[i];
        std::string w = "cameras[" + std::to_string(i) + "]";
        mvr_projection p;
        std::memset(&p, 0, sizeof p);
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
            refuse(w + ": type '" + c.type + "' is not perspective or orthographic");
        }
        mvr_camera_id id = {0};
        cv.check(mvr_scene_add_camera(cv.scene, &p, &id), w);
        cv.cameras[int(i)] = id;
    }
    for (size_t i = 0; i < m.lights.size(); ++i) {
        const tinygltf::Light &l = m.lights[i];
        std::string w = "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
        mvr_light_desc d;
        std::memset(&d, 0, sizeof d);
        if (l.type == "directional")
            d.type = MVR_LIGHT_DIRECTIONAL;
        else if (l.type == "point")
            d.type = MVR_LIGHT_POINT;
        else if (l.type == "spot")
            d.type = MVR_LIGHT_SPOT;
        else
            refuse(w + ": type '" + l.type + "' is not directional, point or spot");
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
    cx.limits.max_file_bytes = o.max_file_bytes ? o.max_file_bytes : (uint64_t(1) << 30);
    cx.limits.max_vertices = o.max_vertices ? o.max_vertices : (uint64_t(16) << 20);
    cx.limits.max_indices = o.max_indices ? o.max_indices : (uint64_t(64) << 20);
    cx.limits.max_image_dimension = o.max_image_dimension ? o.max_image_dimension : 16384;
    cx.limits.max_nodes = o.max_nodes ? o.max_nodes : (1u << 20);
    mvr_scene *scene = nullptr;
    try {
        if (size > cx.limits.max_file_bytes)
            refuse("the file is " + std::to_string(size) + " bytes, over the cap of " +
                   std::to_string(cx.limits.max_file_bytes) + " (mvr_gltf_options.max_file_bytes)");
        bool glb = size >= 4 && std::memcmp(bytes, "glTF", 4) == 0;
        if (glb)
            check_glb(bytes, size);
        else
            check_json_depth(bytes, size);
        tinygltf::TinyGLTF loader;
        fs_state fs{cx.limits.max_file_bytes, allow_files, ""};
        loader.SetFsCallbacks(tinygltf::FsCallbacks{fs_exists, fs_expand, fs_read, fs_write, &fs});
        Model model;
        loader.SetImageLoader(keep_encoded, &model);
        std::string err, warn;
        bool ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes, unsigned(size), base_dir)
                      : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char *>(bytes),
                                                   unsigned(size), base_dir);
        if (!fs.error.empty())
            refuse(fs.error);
        if (!ok) {
            while (!err.empty() && (err.back() == '\n' || err.back() == ' '))
                err.pop_back();
            refuse(err.empty() ? "not a glTF file" : err);
        }
        if (!warn.empty())
            cx.warn(warn);
        cx.model = &model;
        for (const auto &e : model.extensionsRequired)
            if (!implemented.count(e))
                throw load_error(MVR_ERROR_UNSUPPORTED,
                                 "the file requires extension " + e + ", which mvr does not implement");
        for (const auto &e : model.extensionsUsed) {
            if (e == "KHR_mesh_quantization")
                cx.quantization_declared = true;
            else if (!implemented.count(e))
                cx.warn("extension " + e + " is used but not implemented; the file renders without it");
        }
        if (model.nodes.size() > cx.limits.max_nodes)
            refuse(std::to_string(model.nodes.size()) + " nodes, over the cap of " +
                   std::to_string(cx.limits.max_nodes) + " (mvr_gltf_options.max_nodes)");
        mvr_scene_desc sd;
        std::memset(&sd, 0, sizeof sd);
        sd.logger = o.logger;
        mvr_error serr;
        if (mvr_scene_create(&sd, &scene, &serr) != MVR_OK)
            throw load_error(serr.result, serr.message);
        converter cv{cx, scene, model, {}, {}, {}, {}, {}, false, false};
        convert_cameras_and_lights(cv);
        // which scene: the option, the file's default, or the first
        int si = o.scene ? int(o.scene) - 1 : (model.defaultScene >= 0 ? model.defaultScene : 0);
        if (o.scene && size_t(si) >= model.scenes.size())
            refuse("scene " + std::to_string(o.scene) + " requested (1-based); the file has " +
                   std::to_string(model.scenes.size()));
        std::vector<char> state(model.nodes.size(), 0);
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
        if (info) {
            info->warnings = cx.warnings;
            info->camera_nodes = mvr_scene_camera_node_count(scene);
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
        std::string base = slash == std::string::npos ? "." : p.substr(0, slash);
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
