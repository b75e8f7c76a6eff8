// glTF materials, textures and images into the scene (glTF 2.0, 3.8 - 3.9):
// samplers, KHR_texture_transform, images decoded once from bytes mvr read
// (PNG, JPEG, WebP through mvr_image; KTX2 through ktx2.cpp), textures'
// extension sources (KHR_texture_basisu, EXT_texture_webp) with their
// fallbacks, and images that cannot be had left out with a warning.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "gltf_convert.hpp"
#include "gltf_files.hpp"
#include "gltf_image_ahead.hpp"
#include "ktx2.hpp"
#include "mvr/mvr_image.h"

extern "C" {
#include "core_util.h"
#include "scene_internal.h"
#include "material.h"
}

namespace mvr_gltf {

namespace {

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

}  // namespace

double number(const tinygltf::Value &v, const char *key, double fallback)
{
    if (!v.IsObject() || !v.Has(key))
        return fallback;
    const tinygltf::Value &n = v.Get(key);
    return n.IsNumber() ? n.GetNumberAsDouble() : fallback;
}

mvr_image_id converter::image(int index, const std::string &what, const std::string &fallback)
{
    auto found = images.find(index);
    if (found != images.end() && found->second.id != 0)
        return found->second;
    if (index < 0 || size_t(index) >= cx.res.images.size())
        refuse(what + ": image " + std::to_string(index) + " does not exist");
    auto failed = failed_images.find(index);
    if (found == images.end()) {
        if (!ahead_tried) {
            ahead_tried = true;
            ahead = decode_images_ahead(cx, m);
        }
        std::string iname = "images[" + std::to_string(index) + "]";
        try {
            mvr_image_id id = decode_image(size_t(index), iname);
            images[index] = id;
            return id;
        } catch (const load_error &e) {
            if (e.result == MVR_ERROR_OUT_OF_MEMORY)
                throw;   // the budget is never waived
            images[index] = mvr_image_id{0};
            failed = failed_images.emplace(index, image_failure{e.result, e.what(), false, false}).first;
        }
    }
    // Left out. A payload mvr cannot decode (MVR_ERROR_UNSUPPORTED: Basis
    // Universal, GPU block formats, WebP without a reader) beside a fallback
    // is what the fallback is for: noted (info), not a warning, not missing,
    // not an error when strict. Anything else (missing, broken) is warned
    // once per image and counted, or an error when strict.
    image_failure &f = failed->second;
    if (!fallback.empty() && f.result == MVR_ERROR_UNSUPPORTED) {
        if (!f.noted) {
            f.noted = true;
            mvr_log(&cx.logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL, "mvr_gltf: %s; %s falls back to %s",
                    f.message.c_str(), what.c_str(), fallback.c_str());
        }
        return mvr_image_id{0};
    }
    if (cx.strict)
        throw load_error(f.result, f.message);
    if (!f.warned) {
        f.warned = true;
        ++cx.images_missing;
        cx.warn(f.message + (fallback.empty() ? "; left out, its textures take their defaults"
                                              : "; left out, " + what + " falls back to " + fallback));
    }
    return mvr_image_id{0};
}

namespace {

// A KTX2 container's level 0 (ktx2.hpp) as an image: what the loader
// needs to charge the budget before decoding, and the decoding itself.
struct ktx2_image {
    const unsigned char *bytes;
    size_t size;
    mvr_ktx2::info info;
};

ktx2_image parse_ktx2(const unsigned char *bytes, uint64_t size, const std::string &mime, const std::string &iname)
{
    ktx2_image k{bytes, size_t(size), {}};
    bool declared = mime == "image/ktx2";
    if (!mvr_ktx2::is_ktx2(bytes, size_t(size)))
        refuse(iname + ": mimeType " + quote(mime) + " but the bytes are not a KTX2 file");
    if (!mime.empty() && !declared)
        refuse(iname + ": mimeType " + quote(mime) + " but the bytes are KTX2 (image/ktx2)");
    std::string why;
    if (mvr_ktx2::parse(bytes, size_t(size), &k.info, &why) != mvr_ktx2::status::ok)
        refuse(iname + ": " + why);
    std::string reason = mvr_ktx2::unsupported_reason(k.info);
    if (!reason.empty())
        throw load_error(MVR_ERROR_UNSUPPORTED, iname + ": KTX2 " + reason);
    return k;
}

}  // namespace

mvr_image_id converter::decode_image(size_t index, const std::string &iname)
{
    const image_source &src = cx.res.images[index];
    const unsigned char *bytes = nullptr;
    uint64_t size = 0;
    read_result file;
    std::string key;
    if (src.buffer_view >= 0) {
        uint64_t stride = 0;
        bytes = view_bytes(cx, src.buffer_view, &size, &stride, iname);
        key = "bufferView:" + std::to_string(src.buffer_view);
    } else if (src.has_uri) {
        file = cx.files->read(src.uri, iname + ".uri", false);
        bytes = file.data->bytes.data();
        size = file.data->bytes.size();
        key = file.key;
    } else {
        refuse(iname + " has neither a uri nor a bufferView");
    }
    auto same = decoded.find(key);
    if (!key.empty() && same != decoded.end())
        return same->second;
    if (size == 0)
        refuse(iname + ": no image data");
    const std::string &mime = !src.mime_type.empty() ? src.mime_type : file.media_type;
    // The decoder comes from the bytes (and must agree with the mimeType):
    // KTX2 here (ktx2.cpp), PNG / JPEG / WebP through mvr_image.
    bool ktx2 = mvr_ktx2::is_ktx2(bytes, size_t(size)) || mime == "image/ktx2";
    ktx2_image k{};
    mvr_image_header h;
    mvr_error err;
    uint64_t raw = 0;   // what decoding holds besides the RGBA8 result
    if (ktx2) {
        k = parse_ktx2(bytes, size, mime, iname);
        h.width = k.info.width;
        h.height = k.info.height;
        h.channels = k.info.components;
        raw = mvr_ktx2::scratch_bytes(k.info);
        if (mvr_ktx2::block_format(k.info) != MVR_IMAGE_FORMAT_RGBA8)
            return add_blocks(k.bytes, k.size, k.info, index, iname, key);
    } else {
        mvr_result r = mvr_image_probe(bytes, size_t(size), mime.c_str(), &h, &err);
        if (r != MVR_OK)
            throw load_error(r == MVR_ERROR_UNSUPPORTED ? r : MVR_ERROR_INVALID_ASSET, iname + ": " + err.message);
    }
    if (h.width > cx.limits.max_image_dimension || h.height > cx.limits.max_image_dimension)
        refuse(iname + ": " + std::to_string(h.width) + "x" + std::to_string(h.height) + " is over the cap of " +
               std::to_string(cx.limits.max_image_dimension) + " (mvr_gltf_options.max_image_dimension)");
    if (decoded.size() >= cx.limits.max_images)
        refuse(iname + ": more than " + std::to_string(cx.limits.max_images) +
               " images (mvr_gltf_options.max_images)");
    // Decoding holds the inflated KTX2 level and the RGBA8 result, or what
    // mvr_image_decode_cost says PNG / JPEG / WebP decoding holds (the result
    // and the decoder's own copies: 16-bit rows, OpenImageIO's buffers);
    // adding it to the scene, the result and the scene's copy; then the copy
    // stays. The larger of the two phases is charged before anything is
    // allocated, and the decoder is held to the same figure.
    uint64_t rgba = uint64_t(h.width) * h.height * 4;
    uint64_t decode_cost = rgba + raw;
    if (!ktx2 && mvr_image_decode_cost(bytes, size_t(size), mime.c_str(), &decode_cost, &err) != MVR_OK)
        throw load_error(err.result == MVR_ERROR_UNSUPPORTED ? err.result : MVR_ERROR_INVALID_ASSET,
                         iname + ": " + err.message);
    uint64_t charge = std::max(decode_cost, 2 * rgba);
    mvr_image_id id = {0};
    {
        // decoded ahead (the same call, on another thread): taken, and its
        // hold released, before the decoding is charged as it always is
        std::unique_ptr<mvr_image_data, void (*)(mvr_image_data *)> early(new mvr_image_data(), [](mvr_image_data *p) {
            mvr_image_free(p);
            delete p;
        });
        bool have = !ktx2 && take_ahead(ahead.get(), key, bytes, size, charge, early.get());
        charged decoding(cx.mem, charge,
                         iname + " (" + std::to_string(h.width) + "x" + std::to_string(h.height) + ", decoding)");
        mvr_image_data pixels;
        std::memset(&pixels, 0, sizeof pixels);
        if (have) {
            pixels = *early;
            std::memset(early.get(), 0, sizeof *early);
        } else if (ktx2) {
            // Whether the image is sRGB comes from its role (base colour and
            // emissive are sRGB-encoded, glTF 2.0, 3.9.2), as for PNG / JPEG:
            // the KTX2 format's _SRGB / _UNORM (k.info.srgb) is informational.
            pixels.pixels = std::malloc(size_t(rgba));
            if (!pixels.pixels)
                throw load_error(MVR_ERROR_OUT_OF_MEMORY, iname + ": out of memory decoding KTX2");
            pixels.width = h.width;
            pixels.height = h.height;
            pixels.type = MVR_PIXEL_U8;
            std::string why;
            mvr_ktx2::status st = mvr_ktx2::decode(k.bytes, k.size, k.info, static_cast<unsigned char *>(pixels.pixels), &why);
            if (st != mvr_ktx2::status::ok) {
                mvr_image_free(&pixels);
                throw load_error(st == mvr_ktx2::status::out_of_memory ? MVR_ERROR_OUT_OF_MEMORY
                                 : st == mvr_ktx2::status::unsupported ? MVR_ERROR_UNSUPPORTED
                                                                       : MVR_ERROR_INVALID_ASSET,
                                 iname + ": " + why);
            }
        } else if (mvr_image_decode_within(bytes, size_t(size), mime.c_str(), cx.limits.max_image_dimension, charge,
                                           &pixels, &err) != MVR_OK) {
            throw load_error(err.result == MVR_ERROR_OUT_OF_MEMORY || err.result == MVR_ERROR_UNSUPPORTED
                                 ? err.result
                                 : MVR_ERROR_INVALID_ASSET,
                             iname + ": " + err.message);
        }
        const std::string &name = m.images.size() > index ? m.images[index].name : std::string();
        mvr_image_desc d;
        std::memset(&d, 0, sizeof d);
        d.width = pixels.width;
        d.height = pixels.height;
        d.rgba8 = static_cast<const uint8_t *>(pixels.pixels);
        d.name = name.c_str();
        mvr_result added = mvr_scene_add_image(scene, &d, &id);
        mvr_image_free(&pixels);
        check(added, iname);
    }
    cx.mem.charge(rgba, iname + " (the scene's copy)"); /* within what was just released */
    ++cx.images_decoded;
    if (!key.empty())
        decoded[key] = id;
    return id;
}

// A KTX2 file of a GPU block format mvr keeps (ETC2, EAC, ASTC LDR): its
// levels into the scene as they are, never decoded to RGBA8. Whether the
// GL can sample them is the renderer's to say (the scene is GL-free).
mvr_image_id converter::add_blocks(const unsigned char *bytes, size_t size, const mvr_ktx2::info &info, size_t index,
                                   const std::string &iname, const std::string &key)
{
    struct {
        const unsigned char *bytes;
        size_t size;
        const mvr_ktx2::info &info;
    } k{bytes, size, info};
    if (k.info.width > cx.limits.max_image_dimension || k.info.height > cx.limits.max_image_dimension)
        refuse(iname + ": " + std::to_string(k.info.width) + "x" + std::to_string(k.info.height) +
               " is over the cap of " + std::to_string(cx.limits.max_image_dimension) +
               " (mvr_gltf_options.max_image_dimension)");
    if (decoded.size() >= cx.limits.max_images)
        refuse(iname + ": more than " + std::to_string(cx.limits.max_images) + " images (mvr_gltf_options.max_images)");
    mvr_image_format format = mvr_ktx2::block_format(k.info);
    uint32_t levels = mvr_ktx2::block_levels(k.info);
    uint64_t blocks = 0;   // the levels' sizes, checked by the parser against the format's block arithmetic
    for (uint32_t lv = 0; lv < levels; ++lv)
        blocks += k.info.levels[lv].uncompressed;
    std::string dims = std::to_string(k.info.width) + "x" + std::to_string(k.info.height) + " " +
                       mvr_image_format_name(format) + ", " + std::to_string(levels) + " levels";
    mvr_image_id id = {0};
    {
        // reading holds the inflated levels (Zstandard) and the scene's copy
        charged reading(cx.mem, mvr_ktx2::scratch_bytes(k.info) + blocks, iname + " (" + dims + ", reading)");
        std::vector<mvr_image_level> lv;
        std::vector<std::vector<unsigned char>> storage;
        std::string why;
        mvr_ktx2::status st = mvr_ktx2::read_blocks(k.bytes, k.size, k.info, &lv, &storage, &why);
        if (st != mvr_ktx2::status::ok)
            throw load_error(st == mvr_ktx2::status::out_of_memory ? MVR_ERROR_OUT_OF_MEMORY
                             : st == mvr_ktx2::status::unsupported ? MVR_ERROR_UNSUPPORTED
                                                                   : MVR_ERROR_INVALID_ASSET,
                             iname + ": " + why);
        const std::string &name = m.images.size() > index ? m.images[index].name : std::string();
        mvr_image_desc d;
        std::memset(&d, 0, sizeof d);
        d.width = k.info.width;
        d.height = k.info.height;
        d.name = name.c_str();
        d.format = format;
        d.level_count = uint32_t(lv.size());
        for (size_t i = 0; i < lv.size() && i < MVR_IMAGE_MAX_LEVELS; ++i)
            d.levels[i] = lv[i];
        check(mvr_scene_add_image(scene, &d, &id), iname);
    }
    cx.mem.charge(blocks, iname + " (the scene's copy)"); /* within what was just released */
    ++cx.images_decoded;
    block_transfer[id.id] = k.info.dfd_transfer;
    if (!key.empty())
        decoded[key] = id;
    return id;
}

mvr_texture_ref converter::texture(const tinygltf::TextureInfo &info, const std::string &what)
{
    return texture_ref(info.index, info.texCoord, info.extensions, what);
}

mvr_texture_ref converter::texture_ref(int index, int texcoord, const tinygltf::ExtensionMap &ext, const std::string &what)
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
    // The texture's images in the order mvr tries them: the extensions'
    // (EXT_texture_webp, KHR_texture_basisu: WebP or KTX2, decoded like any
    // image), then `source`, their fallback (the extensions' specifications:
    // a client that cannot use the extension's image uses `source`).
    struct candidate {
        int image;
        std::string via;
    };
    std::vector<candidate> sources;
    for (const char *e : {"EXT_texture_webp", "KHR_texture_basisu"}) {
        auto it = t.extensions.find(e);
        if (it == t.extensions.end())
            continue;
        std::string via = tname + ".extensions." + e + ".source";
        const tinygltf::Value &v = it->second;
        if (!v.IsObject() || !v.Has("source") || !v.Get("source").IsNumber())
            refuse(via + " is missing or not a number");
        double s = v.Get("source").GetNumberAsDouble();
        if (!(s >= 0 && s <= double(INT32_MAX)) || s != std::floor(s))
            refuse(via + " is not a valid image index");
        sources.push_back({int(s), via});
    }
    if (t.source >= 0)
        sources.push_back({t.source, tname + ".source"});
    if (sources.empty()) {
        cx.warn(tname + " has no source image; " + what + " is left untextured");
        return ref;
    }
    for (size_t i = 0; i < sources.size() && ref.image.id == 0; ++i) {
        std::string fallback;
        if (i + 1 < sources.size())
            fallback = "images[" + std::to_string(sources[i + 1].image) + "] (" + sources[i + 1].via + ")";
        ref.image = image(sources[i].image, sources[i].via, fallback);
    }
    if (ref.image.id == 0) {
        missing_texture = true;
        return ref;
    }
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

void converter::note_transfer(const mvr_material_desc &d, const std::string &w)
{
    const uint8_t TRANSFER_SRGB = 2;   // Khronos Data Format 1.3, 5.8
    for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
        const mvr_texture_ref *t = mvr_material_role(&d, role);
        auto it = block_transfer.find(t->image.id);
        if (t->image.id == 0 || it == block_transfer.end())
            continue;
        bool file_srgb = it->second == TRANSFER_SRGB, role_srgb = mvr_role_is_srgb(role);
        if (file_srgb != role_srgb)
            mvr_log(&cx.logger, MVR_LOG_DEBUG, MVR_LOG_ID_GENERAL,
                    "mvr_gltf: %s: the %s texture's KTX2 says %s; the role's %s transfer is used", w.c_str(),
                    mvr_role_name(role), file_srgb ? "sRGB" : "linear", role_srgb ? "sRGB" : "linear");
    }
}

mvr_material_id converter::material(int index)
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
    missing_texture = false;
    d.emissive = texture(g.emissiveTexture, w + ".emissiveTexture");
    if (missing_texture)
        d.emissive_factor[0] = d.emissive_factor[1] = d.emissive_factor[2] = 0.0f; /* no emission without its map */
    if (g.alphaMode == "MASK")
        d.alpha_mode = MVR_ALPHA_MASK;
    else if (g.alphaMode == "BLEND")
        d.alpha_mode = MVR_ALPHA_BLEND;
    else if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty())
        refuse(w + ": alphaMode " + quote(g.alphaMode) + " is not OPAQUE, MASK or BLEND");
    d.alpha_cutoff = float(g.alphaCutoff);
    if (d.alpha_cutoff == 0.0f)
        d.alpha_cutoff = 1e-7f; /* a cutoff of 0 is valid glTF; 0 means "default" in mvr */
    d.double_sided = g.doubleSided;
    d.unlit = g.extensions.count("KHR_materials_unlit") > 0;
    auto es = g.extensions.find("KHR_materials_emissive_strength");
    if (es != g.extensions.end()) {
        d.emissive_strength = float(number(es->second, "emissiveStrength", 1.0));
        if (d.emissive_strength == 0.0f)
            for (float &e : d.emissive_factor)
                e = 0.0f; /* the extension's strength 0 turns emission off; 0 means "default" in mvr */
    }
    pbr_extensions(g, w, d);
    note_transfer(d, w);
    d.name = g.name.c_str();
    mvr_material_id id = {0};
    check(mvr_scene_add_material(scene, &d, &id), w);
    materials[index] = id;
    return id;
}

// ---- KHR_materials_variants ----

void converter::variants()
{
    const variants_source &v = cx.res.variants;
    const std::string w = "extensions.KHR_materials_variants";
    if (!v.problem.empty())
        refuse(w + (v.problem.rfind("variants", 0) == 0 ? "." : " ") + v.problem);
    // the scene's copies of the names: charged like the rest of the scene
    uint64_t bytes = 0;
    for (const auto &name : v.names)
        bytes += name.size() + 1 + 32;
    cx.mem.charge(bytes, w + ".variants (" + std::to_string(v.names.size()) + " names)");
    for (size_t i = 0; i < v.names.size(); ++i)
        check(mvr_scene_add_variant(scene, v.names[i].c_str(), nullptr), w + ".variants[" + std::to_string(i) + "]");
}

std::vector<mvr_variant_mapping> converter::variant_mappings(int mesh, int prim, const std::string &pw)
{
    std::vector<mvr_variant_mapping> out;
    auto found = cx.res.variant_primitives.find({mesh, prim});
    if (found == cx.res.variant_primitives.end())
        return out;
    const primitive_variants_source &src = found->second;
    const std::string w = pw + ".extensions.KHR_materials_variants";
    if (!src.problem.empty())
        refuse(w + (src.problem.rfind("mappings", 0) == 0 ? "." : " ") + src.problem);
    const uint32_t count = mvr_scene_variant_count(scene);
    // glTF: a variant names at most one material per primitive
    std::map<int64_t, size_t> mapped_by;
    for (size_t j = 0; j < src.mappings.size(); ++j) {
        const variant_mapping_source &ms = src.mappings[j];
        std::string mw = w + ".mappings[" + std::to_string(j) + "]";
        if (size_t(ms.material) >= m.materials.size())
            refuse(mw + ".material: material " + std::to_string(ms.material) + " does not exist (" +
                   std::to_string(m.materials.size()) + " materials)");
        for (size_t n = 0; n < ms.variants.size(); ++n) {
            int64_t v = ms.variants[n];
            std::string vw = mw + ".variants[" + std::to_string(n) + "]";
            if (v >= int64_t(count))
                refuse(vw + ": variant " + std::to_string(v) + " does not exist (" + std::to_string(count) +
                       " variants in extensions.KHR_materials_variants)");
            auto seen = mapped_by.find(v);
            if (seen != mapped_by.end())
                refuse(vw + ": variant " + std::to_string(v) + " is mapped already by mappings[" +
                       std::to_string(seen->second) + "] (a variant maps at most one material per primitive)");
            mapped_by[v] = j;
        }
        mvr_material_id mat = material(int(ms.material));
        for (int64_t v : ms.variants)
            out.push_back(mvr_variant_mapping{uint32_t(v), mat});
    }
    return out;
}

// The GPU-side bytes of one scene image: RGBA8 with its mip chain (the
// renderer generates mips), or a block-compressed image's levels decoded to
// RGBA8, width x height x 4 each (what a GL without the format, Mesa's
// llvmpipe among them for ASTC and ETC2, holds after decoding it at upload).
static uint64_t texture_upload_bytes(const scene_image &img)
{
    uint64_t total = 0, w = img.width, h = img.height;
    bool blocks = img.format != MVR_IMAGE_FORMAT_RGBA8;
    for (uint32_t level = 0;; ++level) {
        if (blocks && level >= img.levels)
            break;
        total += w * h * 4;
        if (!blocks && w == 1 && h == 1)
            break;
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
    return total;
}

void charge_texture_uploads(context &cx, const mvr_scene *scene, const std::map<int, mvr_image_id> &images)
{
    std::map<uint32_t, int> source;   // scene image id -> glTF image
    for (const auto &gi : images)
        if (gi.second.id != 0)
            source.emplace(gi.second.id, gi.first);
    // what no material samples is never uploaded (an occlusion image packed
    // into its metallic-roughness image, pack_textures)
    std::vector<char> sampled(scene->image_count, 0);
    for (uint32_t m = 0; m < scene->material_count; ++m)
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
            uint32_t id = mvr_material_role(&scene->materials[m].desc, role)->image.id;
            if (id && id <= scene->image_count)
                sampled[id - 1] = 1;
        }
    for (uint32_t i = 0; i < scene->image_count; ++i) {
        if (!sampled[i])
            continue;
        const scene_image &img = scene->images[i];
        auto from = source.find(i + 1);
        std::string name = from != source.end() ? "images[" + std::to_string(from->second) + "]"
                                                : "image " + std::to_string(i + 1);
        bool blocks = img.format != MVR_IMAGE_FORMAT_RGBA8;
        std::string dims = std::to_string(img.width) + "x" + std::to_string(img.height);
        cx.mem.charge(texture_upload_bytes(img),
                      name + " (" + dims + (blocks ? std::string(" ") + mvr_image_format_name(img.format) + ", " +
                                                         std::to_string(img.levels) + " levels, decoded to RGBA8"
                                                   : std::string(" RGBA8 with its mips")) +
                          ") uploaded for rendering");
    }
}

uint32_t pack_textures(context &cx, mvr_scene *scene)
{
    uint32_t texcoords_folded = mvr_scene_fold_texcoords(scene);
    uint32_t occlusion_packed = mvr_scene_pack_occlusion(scene);
    if (texcoords_folded || occlusion_packed)
        mvr_log(&cx.logger, MVR_LOG_DEBUG, MVR_LOG_ID_GENERAL,
                "mvr_gltf: %u material(s) read texture coordinates 0 where their primitives repeat them as 1; "
                "%u metallic-roughness image(s) took their material's occlusion image into their red channel "
                "(one texture fetch for both)",
                texcoords_folded, occlusion_packed);
    return occlusion_packed;
}

}  // namespace mvr_gltf
