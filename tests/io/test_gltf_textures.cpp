// io_gltf_textures: textures beyond PNG / JPEG (issue 20, item 4) at the
// loader: KTX2 containers (tests/io/hostile_ktx2.cpp writes them field by
// field) declared through KHR_texture_basisu or as a plain source, by
// mimeType or by signature; EXT_texture_webp; and the payloads mvr cannot
// decode (GPU block formats other than ETC2 / EAC / ASTC, which
// io_gltf_blocks tests, and Basis Universal) falling back to the texture's
// `source`, or to the role's default with one warning naming the image.
//
// Every scene is one unlit quad whose base colour texture is an 8 x 8 image of
// four 4 x 4 quadrants of known colours, sampled NEAREST, rendered into two
// stereo views (tests/io/gltf_render.cpp). A decoded KTX2 / WebP image must
// render the same bytes as the PNG of the same pixels, and the quadrants'
// colours must be in the picture.
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "gltf_gen.hpp"
#include "gltf_render.hpp"
#include "hostile_docs.hpp"
#include "hostile_ktx2.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

#ifndef MVR_GLTF_TEXTURES_DIR
#error "MVR_GLTF_TEXTURES_DIR (where the test writes its files) must be defined"
#endif

namespace {

using namespace hostile;

const uint32_t S = 8;   // image size
// quadrants: top-left, top-right, bottom-left, bottom-right (RGBA)
const uint8_t quadrant[4][4] = {{200, 30, 40, 255}, {20, 180, 60, 255}, {30, 50, 220, 255}, {240, 240, 240, 255}};

std::string dir()
{
    static std::string d = [] {
        std::string p = MVR_GLTF_TEXTURES_DIR;
        mkdir(p.c_str(), 0777);
        mkdir((p + "/programs").c_str(), 0777);
        return p;
    }();
    return d;
}

// The test image (rows top first), optionally with each texel mapped (R8, RG8 keep fewer channels).
std::vector<uint8_t> checker()
{
    std::vector<uint8_t> px(size_t(S) * S * 4);
    for (uint32_t y = 0; y < S; ++y)
        for (uint32_t x = 0; x < S; ++x) {
            const uint8_t *c = quadrant[(y >= S / 2 ? 2 : 0) + (x >= S / 2 ? 1 : 0)];
            std::memcpy(&px[(size_t(y) * S + x) * 4], c, 4);
        }
    return px;
}

// What a KTX2 of vk_format holds of px, as RGBA8 (R8: r,0,0,1; R8G8: r,g,0,1).
std::vector<uint8_t> as_format(std::vector<uint8_t> px, uint32_t vk)
{
    for (size_t i = 0; i < px.size(); i += 4) {
        if (vk == VK_R8_UNORM)
            px[i + 1] = 0;
        if (vk == VK_R8_UNORM || vk == VK_R8G8_UNORM)
            px[i + 2] = 0;
        if (vk == VK_R8_UNORM || vk == VK_R8G8_UNORM || vk == VK_R8G8B8_UNORM || vk == VK_R8G8B8_SRGB ||
            vk == VK_B8G8R8_UNORM)
            px[i + 3] = 255;
    }
    return px;
}

// RGBA8 pixels encoded by OpenImageIO ("png", or "webp": lossy in OpenImageIO 2.4).
std::vector<uint8_t> encode(const char *format, const std::vector<uint8_t> &px, uint32_t w, uint32_t h)
{
    using namespace OIIO;
    std::string path = Filesystem::unique_path(dir() + "/tmp-%%%%%%%%." + format);
    auto o = ImageOutput::create(path);
    ImageSpec spec(int(w), int(h), 4, TypeDesc::UINT8);
    if (!o || !o->open(path, spec) || !o->write_image(TypeDesc::UINT8, px.data()) || !o->close())
        return {};
    std::vector<uint8_t> bytes = gen::read_file(path);
    Filesystem::remove(path);
    return bytes;
}

// Decodes an encoded image with OpenImageIO into RGBA8 (to make the PNG twin of a lossy WebP).
std::vector<uint8_t> decode(const std::vector<uint8_t> &bytes, const char *format)
{
    using namespace OIIO;
    std::string path = Filesystem::unique_path(dir() + "/tmp-%%%%%%%%." + format);
    gen::write_file(path, bytes.data(), bytes.size());
    std::vector<uint8_t> px(size_t(S) * S * 4, 255);
    auto in = ImageInput::open(path);
    bool ok = in && in->spec().width == int(S) && in->spec().height == int(S) &&
              in->read_image(0, 0, 0, std::min(in->spec().nchannels, 4), TypeDesc::UINT8, px.data(), 4);
    Filesystem::remove(path);
    return ok ? px : std::vector<uint8_t>();
}

bool oiio_reads_webp()
{
    std::string list = std::string(OIIO::get_string_attribute("input_format_list"));
    return ("," + list + ",").find(",webp,") != std::string::npos;
}

// ------------------------------------------------------------ scenes

struct scene_spec {
    std::vector<std::string> images;   // each image's JSON
    std::string texture;               // textures[0]'s JSON, without "sampler" ("" = untextured)
    int materials = 1;                 // quads (each its own material, all using textures[0])
    std::vector<std::string> used, required;
};

std::string write_scene(const std::string &name, const scene_spec &s)
{
    doc d;
    std::vector<uint8_t> bin;
    for (const auto &i : s.images)
        d.add(d.images, i);
    int tex = -1;
    if (!s.texture.empty()) {
        d.add(d.samplers, "{\"magFilter\":9728,\"minFilter\":9728}");
        std::string t = s.texture;
        t.insert(1, "\"sampler\":0,");
        tex = d.add(d.textures, t);
    }
    std::vector<std::string> prims;
    for (int m = 0; m < s.materials; ++m)
        prims.push_back(quad(d, bin, 0, float(m) * 1.2f, 0, 0.5f, unlit(d, tex)));
    one_mesh(d, prims);
    d.buffers.insert(d.buffers.begin(), data_buffer(bin));
    for (const auto &e : s.used)
        d.use(e);
    for (const auto &e : s.required)
        d.ext_required.push_back(e);
    std::string path = dir() + "/" + name + ".gltf";
    write_text(path, d.json());
    return path;
}

std::string file_image(const std::string &name, const std::vector<uint8_t> &bytes, const char *mime = nullptr)
{
    write_bytes(dir() + "/" + name, bytes.data(), bytes.size());
    std::string j = "{\"uri\":\"" + name + "\"";
    if (mime)
        j += std::string(",\"mimeType\":\"") + mime + "\"";
    return j + "}";
}

std::string data_image(const std::vector<uint8_t> &bytes, const char *mime)
{
    return std::string("{\"uri\":\"data:") + mime + ";base64," + gen::base64(bytes.data(), bytes.size()) + "\"}";
}

const char *basisu = "KHR_texture_basisu", *webp = "EXT_texture_webp";

// textures[0] = the extension's source only (required), or the extension's
// source with `source` as its fallback (used).
scene_spec ext_only(const char *ext, const std::string &image)
{
    return {{image}, std::string("{\"extensions\":{\"") + ext + "\":{\"source\":0}}}", 1, {ext}, {ext}};
}
scene_spec ext_with_fallback(const char *ext, const std::string &image, const std::string &fallback)
{
    return {{image, fallback}, std::string("{\"source\":1,\"extensions\":{\"") + ext + "\":{\"source\":0}}}", 1, {ext}, {}};
}
scene_spec plain(const std::string &image)
{
    return {{image}, "{\"source\":0}", 1, {}, {}};
}

// ------------------------------------------------------------ load and render

struct loaded {
    mvr_result r = MVR_OK;
    std::string msg;
    mvr_scene *scene = nullptr;
    mvr_gltf_info info = {};
    std::vector<std::string> warnings, infos;
    loaded() = default;
    loaded(const loaded &) = delete;
    loaded &operator=(const loaded &) = delete;
    ~loaded() { mvr_scene_destroy(scene); }
    bool warned(const std::string &a, const std::string &b = "") const
    {
        for (const auto &w : warnings)
            if (w.find(a) != std::string::npos && w.find(b) != std::string::npos)
                return true;
        return false;
    }
    bool noted(const std::string &a, const std::string &b = "") const
    {
        for (const auto &w : infos)
            if (w.find(a) != std::string::npos && w.find(b) != std::string::npos)
                return true;
        return false;
    }
};

void collect(mvr_log_level level, mvr_log_id, const char *message, void *user)
{
    auto *l = static_cast<loaded *>(user);
    if (level == MVR_LOG_WARNING)
        l->warnings.push_back(message);
    else if (level == MVR_LOG_INFO)
        l->infos.push_back(message);
}

void load(const std::string &path, loaded *out, bool strict = false)
{
    mvr_gltf_options o;
    std::memset(&o, 0, sizeof o);
    o.strict = strict;
    o.logger.fn = collect;
    o.logger.user_data = out;
    o.logger.level = MVR_LOG_INFO;
    mvr_error err;
    std::memset(&err, 0, sizeof err);
    out->r = mvr_gltf_load_file(path.c_str(), &o, &out->scene, &out->info, &err);
    out->msg = out->r == MVR_OK ? "" : err.message;
    std::string name = path.substr(path.find_last_of('/') + 1);
    std::printf("  %-40s %-22s decoded %u missing %u warnings %u %s\n", name.c_str(), mvr_result_name(out->r),
                out->info.images_decoded, out->info.images_missing, out->info.warnings,
                out->r != MVR_OK ? out->msg.c_str() : out->warnings.empty() ? "" : out->warnings[0].c_str());
}

mvr_context *g_ctx = nullptr;

mvr_context *context(mvr_test_state *t)
{
    static bool tried = false;
    if (!tried) {
        tried = true;
        mvr_error err;
        if (mvr_context_create(nullptr, &g_ctx, &err) != MVR_OK) {
            std::printf("  no GL context: %s\n", err.message);
            g_ctx = nullptr;
        }
    }
    (void)t;
    return g_ctx;
}

std::vector<uint8_t> render(mvr_test_state *t, const loaded &l, const std::string &what)
{
    mvr_context *ctx = context(t);
    if (!ctx || !l.scene)
        return {};
    std::string cache = dir() + "/programs";
    return gltf_render::two_layers(t, ctx, l.scene, MVR_VIEW_PATH_AUTO, what.c_str(), cache.c_str());
}

// Pixels of the frame within 3 of colour c (RGB).
size_t count_colour(const std::vector<uint8_t> &px, const uint8_t *c)
{
    size_t n = 0;
    for (size_t i = 0; i + 3 < px.size(); i += 4) {
        bool near = true;
        for (int k = 0; k < 3; ++k)
            near = near && std::abs(int(px[i + size_t(k)]) - int(c[k])) <= 3;
        n += near;
    }
    return n;
}

// The reference frames: the PNG of the given pixels, and the untextured quad.
std::vector<uint8_t> png_frame(mvr_test_state *t, const std::vector<uint8_t> &px, const std::string &name)
{
    loaded l;
    load(write_scene(name, plain(file_image(name + ".png", encode("png", px, S, S)))), &l);
    CHECK_MSG(t, l.r == MVR_OK && l.info.images_decoded == 1 && l.warnings.empty(), "%s: %s", name.c_str(),
              l.msg.c_str());
    return render(t, l, name);
}

const std::vector<uint8_t> &untextured_frame(mvr_test_state *t, int materials = 1)
{
    static std::vector<uint8_t> frames[3];
    if (frames[materials].empty()) {
        scene_spec s;
        s.materials = materials;
        loaded l;
        load(write_scene("untextured_" + std::to_string(materials), s), &l);
        frames[materials] = render(t, l, "untextured");
    }
    return frames[materials];
}

// A load of a file whose texture must decode and render as `reference`
// (the PNG frame of the same pixels): no warning, one image decoded.
// pixels: the image's, whose quadrants' colours must be in the frame
// (empty for lossy WebP, whose texels vary inside a quadrant: the frame
// must then differ from the untextured quad's).
void renders_like(mvr_test_state *t, const std::string &path, const std::vector<uint8_t> &reference,
                  const std::vector<uint8_t> &pixels, uint32_t decoded = 1)
{
    std::string name = path.substr(path.find_last_of('/') + 1);
    loaded l;
    load(path, &l);
    CHECK_MSG(t, l.r == MVR_OK, "%s: %s", name.c_str(), l.msg.c_str());
    if (l.r != MVR_OK)
        return;
    CHECK_MSG(t, l.warnings.empty(), "%s: warned: %s", name.c_str(), l.warnings[0].c_str());
    CHECK_MSG(t, l.info.images_decoded == decoded && l.info.images_missing == 0, "%s: decoded %u, missing %u",
              name.c_str(), l.info.images_decoded, l.info.images_missing);
    std::vector<uint8_t> px = render(t, l, name);
    if (px.empty() || reference.empty())
        return;
    CHECK_MSG(t, px == reference, "%s: the frame differs from the PNG's", name.c_str());
    CHECK_MSG(t, px != untextured_frame(t), "%s: the frame is the untextured quad's", name.c_str());
    for (int q = 0; q < 4 && !pixels.empty(); ++q) {
        const uint8_t *c = &pixels[((q / 2) * (S / 2) * S + (q % 2) * (S / 2)) * 4];
        size_t n = count_colour(px, c);
        CHECK_MSG(t, n > 100, "%s: %zu pixels of quadrant %d's colour (%u, %u, %u)", name.c_str(), n, q, c[0], c[1],
                  c[2]);
    }
}

bool have_gl(mvr_test_state *t)
{
    return context(t) != nullptr;
}

// ------------------------------------------------------------ cases

// Uncompressed 8-bit KTX2 in every format mvr decodes, with one level, a
// full chain (whose smaller levels are magenta: only level 0 is used) and
// levelCount 0, through KHR_texture_basisu (required, no fallback).
void ktx2_uncompressed_renders_like_png(mvr_test_state *t)
{
    if (!have_gl(t))
        SKIP(t, "no GL context");
    const uint32_t formats[] = {VK_R8G8B8A8_SRGB, VK_R8G8B8A8_UNORM, VK_B8G8R8A8_SRGB, VK_R8G8B8_SRGB,
                                VK_R8G8B8_UNORM,  VK_B8G8R8_UNORM,   VK_R8G8_UNORM,    VK_R8_UNORM};
    for (uint32_t vk : formats) {
        std::vector<uint8_t> px = as_format(checker(), vk);
        std::string f = "vk" + std::to_string(vk);
        std::vector<uint8_t> ref = png_frame(t, px, "png_" + f);
        for (uint32_t levels : {1u, 4u, 0u}) {
            std::string n = "ktx2_" + f + "_levels" + std::to_string(levels);
            std::vector<uint8_t> k = ktx2_file(ktx2_from_rgba(checker(), S, S, vk, levels));
            renders_like(t, write_scene(n, ext_only(basisu, file_image(n + ".ktx2", k, "image/ktx2"))), ref, px);
        }
    }
}

// One RGBA8 KTX2 declared every way: plain `source` with mimeType, plain
// without (by signature: a file, a bufferView), a data: URI, with and
// without KHR_texture_basisu in extensionsUsed.
void ktx2_declared_every_way(mvr_test_state *t)
{
    if (!have_gl(t))
        SKIP(t, "no GL context");
    std::vector<uint8_t> px = checker();
    std::vector<uint8_t> ref = png_frame(t, px, "png_rgba");
    std::vector<uint8_t> k = ktx2_file(ktx2_from_rgba(px, S, S, VK_R8G8B8A8_SRGB, 4));
    renders_like(t, write_scene("ktx2_plain_mime", plain(file_image("plain.ktx2", k, "image/ktx2"))), ref, px);
    renders_like(t, write_scene("ktx2_plain_signature", plain(file_image("plain_sig.bin", k))), ref, px);
    renders_like(t, write_scene("ktx2_data_uri", plain(data_image(k, "image/ktx2"))), ref, px);
    // a bufferView (GLB-style: the image's bytes in buffer 0)
    {
        doc d;
        std::vector<uint8_t> bin;
        int v = put_view(d, bin, 0, k.data(), k.size());
        d.add(d.images, "{\"bufferView\":" + std::to_string(v) + ",\"mimeType\":\"image/ktx2\"}");
        d.add(d.samplers, "{\"magFilter\":9728,\"minFilter\":9728}");
        int tex = d.add(d.textures, "{\"sampler\":0,\"extensions\":{\"KHR_texture_basisu\":{\"source\":0}}}");
        one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, unlit(d, tex))});
        d.buffers.insert(d.buffers.begin(), data_buffer(bin));
        d.use(basisu);
        d.ext_required.push_back(basisu);
        std::string path = dir() + "/ktx2_buffer_view.gltf";
        write_text(path, d.json());
        renders_like(t, path, ref, px);
    }
    // the same image as two uses: decoded once
    scene_spec two = ext_only(basisu, file_image("twice.ktx2", k));
    two.materials = 2;
    loaded l;
    load(write_scene("ktx2_two_materials", two), &l);
    CHECK_MSG(t, l.r == MVR_OK && l.info.images_decoded == 1 && l.warnings.empty(), "two materials: %s, decoded %u",
              l.msg.c_str(), l.info.images_decoded);
}

// Zstandard supercompression (scheme 2), every level compressed; also a
// level of two frames with a skippable frame between them.
void ktx2_zstd_renders_like_png(mvr_test_state *t)
{
    if (!have_gl(t))
        SKIP(t, "no GL context");
    for (uint32_t vk : {VK_R8G8B8A8_SRGB, VK_R8G8B8_SRGB, VK_R8_UNORM}) {
        std::vector<uint8_t> px = as_format(checker(), vk);
        std::string f = "vk" + std::to_string(vk);
        std::vector<uint8_t> ref = png_frame(t, px, "png_zstd_" + f);
        for (uint32_t levels : {1u, 4u}) {
            ktx2_desc d = ktx2_from_rgba(checker(), S, S, vk, levels);
            ktx2_zstd(d);
            std::string n = "ktx2_zstd_" + f + "_levels" + std::to_string(levels);
            renders_like(t, write_scene(n, ext_only(basisu, file_image(n + ".ktx2", ktx2_file(d)))), ref, px);
        }
    }
    // two frames + a skippable frame (magic 0x184D2A50, 4 bytes of content)
    std::vector<uint8_t> px = checker();
    ktx2_desc a = ktx2_from_rgba(px, S, S, VK_R8G8B8A8_SRGB, 1), b = a;
    std::vector<uint8_t> raw = a.levels[0];
    a.levels[0].assign(raw.begin(), raw.begin() + long(raw.size() / 2));
    b.levels[0].assign(raw.begin() + long(raw.size() / 2), raw.end());
    ktx2_zstd(a);
    ktx2_zstd(b);
    std::vector<uint8_t> level = a.levels[0];
    const uint8_t skippable[12] = {0x50, 0x2A, 0x4D, 0x18, 4, 0, 0, 0, 1, 2, 3, 4};
    level.insert(level.end(), skippable, skippable + 12);
    level.insert(level.end(), b.levels[0].begin(), b.levels[0].end());
    a.levels[0] = level;
    a.uncompressed[0] = raw.size();
    renders_like(t, write_scene("ktx2_zstd_frames", ext_only(basisu, file_image("frames.ktx2", ktx2_file(a)))),
                 png_frame(t, px, "png_frames"), px);
}

// KTXorientation: "rd" (the default) and "ru" with the rows stored bottom first.
void ktx2_orientation(mvr_test_state *t)
{
    if (!have_gl(t))
        SKIP(t, "no GL context");
    std::vector<uint8_t> px = checker();
    std::vector<uint8_t> ref = png_frame(t, px, "png_orientation");
    ktx2_desc rd = ktx2_from_rgba(px, S, S, VK_R8G8B8A8_SRGB, 1);
    rd.orientation = "rd";
    renders_like(t, write_scene("ktx2_rd", ext_only(basisu, file_image("rd.ktx2", ktx2_file(rd)))), ref, px);
    std::vector<uint8_t> flipped(px.size());
    for (uint32_t y = 0; y < S; ++y)
        std::memcpy(&flipped[size_t(y) * S * 4], &px[size_t(S - 1 - y) * S * 4], size_t(S) * 4);
    ktx2_desc ru = ktx2_from_rgba(flipped, S, S, VK_R8G8B8A8_SRGB, 1);
    ru.orientation = "ru";
    renders_like(t, write_scene("ktx2_ru", ext_only(basisu, file_image("ru.ktx2", ktx2_file(ru)))), ref, px);
}

// Payloads mvr parses but does not decode: GPU block formats it does not
// upload (BC7; ETC2, EAC and ASTC are uploaded as blocks, io_gltf_blocks)
// and Basis Universal (ETC1S / BasisLZ, UASTC, UASTC + zstd).
// With a PNG fallback the fallback renders, silently (an info message);
// without one the quad is untextured, with exactly one warning naming the
// image and the format (one per image, however many materials use it), and
// strict refuses the file naming the image.
void gpu_and_basis_payloads_fall_back(mvr_test_state *t)
{
    if (!have_gl(t))
        SKIP(t, "no GL context");
    std::vector<uint8_t> px = checker();
    std::vector<uint8_t> png = encode("png", px, S, S);
    std::vector<uint8_t> ref = png_frame(t, px, "png_fallback");
    struct kind {
        const char *name, *format;   // format: a part of the warning
    } kinds[] = {{"bc7", "BC7_UNORM"}, {"etc1s", "ETC1S"}, {"uastc", "UASTC"}, {"uastc_zstd", "UASTC"}};
    for (const kind &k : kinds) {
        std::string n = std::string("gpu_") + k.name;
        std::vector<uint8_t> file = ktx2_file(ktx2_gpu(k.name, S, S, 4));
        std::string image = file_image(n + ".ktx2", file, "image/ktx2");
        std::string fb = file_image(n + "_fallback.png", png, "image/png");
        // with the fallback
        std::string with = write_scene(n + "_fallback", ext_with_fallback(basisu, image, fb));
        renders_like(t, with, ref, px);
        {
            loaded l;
            load(with, &l);
            CHECK_MSG(t, l.noted("images[0]", k.format) && l.noted("falls back to images[1]"),
                      "%s: no info message naming images[0], %s and the fallback", n.c_str(), k.format);
            loaded s;
            load(with, &s, true);
            CHECK_MSG(t, s.r == MVR_OK && s.info.images_decoded == 1, "%s strict: %s", n.c_str(), s.msg.c_str());
        }
        // without: the default, one warning
        for (int materials : {1, 2}) {
            scene_spec spec = ext_only(basisu, image);
            spec.materials = materials;
            std::string without = write_scene(n + "_alone_" + std::to_string(materials), spec);
            loaded l;
            load(without, &l);
            CHECK_MSG(t, l.r == MVR_OK, "%s alone: %s", n.c_str(), l.msg.c_str());
            if (l.r != MVR_OK)
                continue;
            CHECK_MSG(t, l.warnings.size() == 1 && l.warned("images[0]", k.format),
                      "%s alone (%d materials): %zu warnings, the first: %s", n.c_str(), materials, l.warnings.size(),
                      l.warnings.empty() ? "" : l.warnings[0].c_str());
            CHECK_MSG(t, l.info.images_missing == 1 && l.info.images_decoded == 0, "%s alone: missing %u, decoded %u",
                      n.c_str(), l.info.images_missing, l.info.images_decoded);
            std::vector<uint8_t> frame = render(t, l, n);
            CHECK_MSG(t, !frame.empty() && frame == untextured_frame(t, materials),
                      "%s alone: the frame is not the untextured quad's", n.c_str());
            if (materials == 1) {
                loaded s;
                load(without, &s, true);
                CHECK_MSG(t, s.r == MVR_ERROR_UNSUPPORTED && s.msg.find("images[0]") != std::string::npos,
                          "%s alone strict: %s %s", n.c_str(), mvr_result_name(s.r), s.msg.c_str());
            }
        }
    }
}

// EXT_texture_webp through OpenImageIO's WebP reader: the WebP (lossy, as
// OpenImageIO 2.4 writes it) renders like the PNG of its own decoded pixels,
// through the extension (required; or with a PNG fallback of other colours
// that must not be used) and as a plain source with mimeType image/webp.
// A lit quad whose material keeps occlusion (read by TEXCOORD_1) apart from
// metallic-roughness, as DamagedHelmet does: where TEXCOORD_1 is
// TEXCOORD_0's accessor the loader reads set 0 and packs the occlusion into
// the metallic-roughness image's red channel (core/texture_packing.c; the
// pixels: gl_texture_packing); where TEXCOORD_1 holds other values it
// leaves both alone.
void separate_occlusion_is_packed_at_load(mvr_test_state *t)
{
    std::vector<uint8_t> mr = checker(), ao = checker();
    for (size_t i = 0; i < ao.size(); i += 4)
        ao[i] = uint8_t(255 - ao[i]);
    for (int same_uv = 1; same_uv >= 0; --same_uv) {
        doc d;
        std::vector<uint8_t> bin;
        d.add(d.images, file_image("mr.png", encode("png", mr, S, S)));
        d.add(d.images, file_image("ao.png", encode("png", ao, S, S)));
        d.add(d.samplers, "{}");
        d.add(d.textures, "{\"sampler\":0,\"source\":0}");
        d.add(d.textures, "{\"sampler\":0,\"source\":1}");
        int mat = d.add(d.materials, "{\"pbrMetallicRoughness\":{\"metallicRoughnessTexture\":{\"index\":0}},"
                                     "\"occlusionTexture\":{\"index\":1,\"texCoord\":1}}");
        // quad() adds position, normal and uv accessors in that order
        int uv1 = int(d.accessors.size()) + 2;
        if (!same_uv) {
            float other[8] = {0, 0.5f, 0.5f, 0.5f, 0.5f, 0, 0, 0};
            uv1 = put_accessor(d, put_view(d, bin, 0, other, sizeof other), 5126, 4, "VEC2");
        }
        one_mesh(d, {quad(d, bin, 0, 0, 0, 0.5f, mat, ",\"TEXCOORD_1\":" + std::to_string(uv1))});
        d.buffers.insert(d.buffers.begin(), data_buffer(bin));
        std::string name = same_uv ? "occlusion_apart_same_uv" : "occlusion_apart_other_uv";
        std::string path = dir() + "/" + name + ".gltf";
        write_text(path, d.json());
        loaded l;
        load(path, &l);
        CHECK_MSG(t, l.r == MVR_OK && l.info.images_decoded == 2, "%s: %s", name.c_str(), l.msg.c_str());
        CHECK_MSG(t, l.info.images_occlusion_packed == uint32_t(same_uv), "%s: %u images packed", name.c_str(),
                  l.info.images_occlusion_packed);
        if (have_gl(t))
            CHECK_MSG(t, !render(t, l, name).empty(), "%s: no frame", name.c_str());
    }
}

void webp_renders_like_png(mvr_test_state *t)
{
    if (!have_gl(t))
        SKIP(t, "no GL context");
    std::vector<uint8_t> w = encode("webp", checker(), S, S);
    if (w.empty())
        SKIP(t, "this OpenImageIO writes no WebP");
    std::vector<uint8_t> other(size_t(S) * S * 4, 90);
    std::string fb = file_image("webp_fallback.png", encode("png", other, S, S), "image/png");
    if (!oiio_reads_webp()) {
        // no reader: the fallback renders, and a WebP alone degrades with a warning
        std::vector<uint8_t> ref = png_frame(t, other, "png_webp_fallback");
        renders_like(t, write_scene("webp_no_reader", ext_with_fallback(webp, file_image("c.webp", w), fb)), ref, other);
        return;
    }
    std::vector<uint8_t> px = decode(w, "webp");
    CHECK(t, !px.empty());
    if (px.empty())
        return;
    std::vector<uint8_t> ref = png_frame(t, px, "png_webp_twin");
    std::string image = file_image("checker.webp", w, "image/webp");
    renders_like(t, write_scene("webp_ext", ext_only(webp, image)), ref, {});
    renders_like(t, write_scene("webp_ext_fallback", ext_with_fallback(webp, image, fb)), ref, {});
    renders_like(t, write_scene("webp_plain", plain(image)), ref, {});
    renders_like(t, write_scene("webp_plain_signature", plain(file_image("checker_sig.bin", w))), ref, {});
}

// Broken or mismatched images degrade to the default with a warning naming
// them (or, beside a fallback, to the fallback with the warning); strict
// refuses. A texture with both extensions tries WebP, then KTX2, then source.
void broken_images_degrade(mvr_test_state *t)
{
    if (!have_gl(t))
        SKIP(t, "no GL context");
    std::vector<uint8_t> px = checker();
    std::vector<uint8_t> png = encode("png", px, S, S);
    std::vector<uint8_t> ref = png_frame(t, px, "png_broken");
    std::vector<uint8_t> k = ktx2_file(ktx2_from_rgba(px, S, S, VK_R8G8B8A8_SRGB, 1));
    std::vector<uint8_t> cut(k.begin(), k.begin() + long(k.size() - 10));
    struct broken {
        const char *name;
        std::string image, part;
    } cases[] = {
        {"mime_ktx2_png_bytes", file_image("png_as_ktx2.ktx2", png, "image/ktx2"), "not a KTX2 file"},
        {"mime_png_ktx2_bytes", file_image("ktx2_as_png.png", k, "image/png"), "the bytes are KTX2"},
        {"ktx2_truncated", file_image("truncated.ktx2", cut, "image/ktx2"), "KTX2 level 0"},
    };
    for (const broken &b : cases) {
        std::string n = b.name;
        {
            loaded l;
            load(write_scene(n, plain(b.image)), &l);
            CHECK_MSG(t, l.r == MVR_OK && l.warnings.size() == 1 && l.warned("images[0]", b.part) &&
                             l.info.images_missing == 1,
                      "%s: %s, %zu warnings (%s)", n.c_str(), l.msg.c_str(), l.warnings.size(),
                      l.warnings.empty() ? "" : l.warnings[0].c_str());
            std::vector<uint8_t> frame = render(t, l, n);
            CHECK_MSG(t, !frame.empty() && frame == untextured_frame(t), "%s: not the untextured quad", n.c_str());
            loaded s;
            load(write_scene(n, plain(b.image)), &s, true);
            CHECK_MSG(t, s.r == MVR_ERROR_INVALID_ASSET && s.msg.find("images[0]") != std::string::npos,
                      "%s strict: %s %s", n.c_str(), mvr_result_name(s.r), s.msg.c_str());
        }
        // beside a fallback: the fallback renders, the broken image is warned about
        loaded l;
        load(write_scene(n + "_fallback", ext_with_fallback(basisu, b.image, file_image(n + ".png", png))), &l);
        CHECK_MSG(t, l.r == MVR_OK && l.warnings.size() == 1 && l.warned("images[0]", "falls back to images[1]") &&
                         l.info.images_decoded == 1,
                  "%s with a fallback: %s, %zu warnings (%s)", n.c_str(), l.msg.c_str(), l.warnings.size(),
                  l.warnings.empty() ? "" : l.warnings[0].c_str());
        std::vector<uint8_t> frame = render(t, l, n);
        CHECK_MSG(t, !frame.empty() && frame == ref, "%s with a fallback: not the fallback's frame", n.c_str());
    }
    // both extensions: WebP first, then KTX2, then source
    if (oiio_reads_webp()) {
        std::vector<uint8_t> w = encode("webp", checker(), S, S);
        std::vector<uint8_t> wpx = decode(w, "webp");
        std::vector<uint8_t> wref = png_frame(t, wpx, "png_both_webp");
        scene_spec both = {{file_image("both.webp", w), file_image("both.ktx2", k), file_image("both.png", png)},
                           "{\"source\":2,\"extensions\":{\"EXT_texture_webp\":{\"source\":0},"
                           "\"KHR_texture_basisu\":{\"source\":1}}}",
                           1, {webp, basisu}, {}};
        renders_like(t, write_scene("both_extensions", both), wref, {});
    }
    // a texture whose extension names no valid image index is refused
    for (const char *bad : {"{\"source\":-1}", "{\"source\":1.5}", "{}", "{\"source\":7}"}) {
        scene_spec s = {{file_image("ok.png", png)}, std::string("{\"extensions\":{\"KHR_texture_basisu\":") + bad + "}}",
                        1, {basisu}, {}};
        loaded l;
        load(write_scene("bad_source", s), &l);
        CHECK_MSG(t, l.r == MVR_ERROR_INVALID_ASSET && l.msg.find("textures[0]") != std::string::npos,
                  "KHR_texture_basisu %s: %s %s", bad, mvr_result_name(l.r), l.msg.c_str());
    }
}

}  // namespace

int main()
{
    static const mvr_test_case cases[] = {
        {"ktx2_uncompressed_renders_like_png", ktx2_uncompressed_renders_like_png},
        {"ktx2_declared_every_way", ktx2_declared_every_way},
        {"ktx2_zstd_renders_like_png", ktx2_zstd_renders_like_png},
        {"ktx2_orientation", ktx2_orientation},
        {"gpu_and_basis_payloads_fall_back", gpu_and_basis_payloads_fall_back},
        {"webp_renders_like_png", webp_renders_like_png},
        {"broken_images_degrade", broken_images_degrade},
        {"separate_occlusion_is_packed_at_load", separate_occlusion_is_packed_at_load},
    };
    int rc = mvr_test_run(cases, sizeof cases / sizeof cases[0]);
    mvr_context_destroy(g_ctx);
    return rc;
}
