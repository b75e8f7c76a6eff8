// io_gltf_blocks: KTX2 textures of GPU block formats (issue 20, item 4)
// uploaded without decompression, mips included: ETC2 (the committed files
// of scripts/make_ktx2_assets.py, tests/data/codecs/etc2*.ktx2, and files
// the test writes with the same one-colour-per-block encoding), ASTC LDR
// (void-extent blocks: one constant colour each), and formats the GL cannot
// sample (forced with mvr_renderer_overrides.disable_image_formats) drawn
// with the role's neutral value and a warning naming the image.
//
// Every colour the blocks hold is exactly representable (the script's
// header says why), so a block texture must render the bytes of its PNG
// twin: the allowed difference is 1/255 per channel (measured on llvmpipe:
// 0). Frames are two stereo views of 64 x 48 (an unlit quad), rendered on
// both material paths (texture arrays, per-material 2D textures) and both
// view paths (multiview, loop), which must agree byte for byte.
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gltf_gen.hpp"
#include "gltf_render.hpp"
#include "hostile_docs.hpp"
#include "hostile_ktx2.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

#ifndef MVR_GLTF_BLOCKS_DIR
#error "MVR_GLTF_BLOCKS_DIR (where the test writes its files) must be defined"
#endif
#ifndef MVR_CODECS_DIR
#error "MVR_CODECS_DIR (tests/data/codecs) must be defined"
#endif

namespace {

using namespace hostile;

const uint32_t S = 16;   // the ETC2 images' size
// 5-bit colours of level 0's quadrants (top-left, top-right, bottom-left,
// bottom-right) and of levels 1..4, as scripts/make_ktx2_assets.py has them
const uint8_t quadrant5[4][3] = {{25, 4, 5}, {3, 22, 7}, {4, 6, 27}, {29, 29, 29}};
const uint8_t level5[5][3] = {{0, 0, 0}, {31, 0, 31}, {0, 31, 31}, {31, 31, 0}, {12, 12, 12}};

// What an ETC1-compatible differential block of 5-bit c decodes to (modifier +2).
uint8_t dec5(uint8_t v)
{
    return uint8_t(std::min(255, (v << 3 | v >> 2) + 2));
}

// An ETC2_RGBA8 block: a constant EAC alpha block, then a one-colour ETC2 block.
void put_block(std::vector<uint8_t> &out, const uint8_t *c5, uint8_t alpha)
{
    uint32_t hi = uint32_t(c5[0]) << 27 | uint32_t(c5[1]) << 19 | uint32_t(c5[2]) << 11 | 1u << 1;
    const uint8_t b[16] = {alpha, 0, 0, 0, 0, 0, 0, 0, uint8_t(hi >> 24), uint8_t(hi >> 16), uint8_t(hi >> 8),
                           uint8_t(hi), 0, 0, 0, 0};
    out.insert(out.end(), b, b + 16);
}

// The ETC2 image as a KTX2 of VK_FORMAT_ETC2_R8G8B8A8_SRGB with `levels`
// levels (0: the header says 0, level 0 stored).
ktx2_desc etc2(uint32_t levels)
{
    ktx2_desc k = ktx2_gpu("etc2", S, S, levels);
    for (uint32_t lv = 0; lv < k.levels.size(); ++lv) {
        uint32_t n = std::max(1u, (S >> lv) / 4);
        std::vector<uint8_t> b;
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x)
                put_block(b, lv ? level5[lv] : quadrant5[(y * 4 >= S / 2 ? 2 : 0) + (x * 4 >= S / 2 ? 1 : 0)], 255);
        k.levels[lv] = b;
    }
    return k;
}

// An ASTC LDR void-extent block: every texel the colour c (8-bit, stored as c * 257).
void put_void_extent(std::vector<uint8_t> &out, const uint8_t *c)
{
    const uint8_t head[8] = {0xFC, 0xFD, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
    out.insert(out.end(), head, head + 8);
    for (int k = 0; k < 4; ++k) {
        uint16_t v = uint16_t(c[k] * 257);
        out.push_back(uint8_t(v));
        out.push_back(uint8_t(v >> 8));
    }
}

// An ASTC KTX2 (vk_format, bw x bh blocks) of w x h with two levels: level 0 colour c0, level 1 c1.
ktx2_desc astc(uint32_t vk, uint32_t bw, uint32_t bh, uint32_t w, uint32_t h, const uint8_t *c0, const uint8_t *c1)
{
    ktx2_desc k = ktx2_gpu("astc", w, h, 2);
    k.vk_format = vk;
    k.block_width = uint8_t(bw);
    k.block_height = uint8_t(bh);
    for (uint32_t lv = 0; lv < 2; ++lv) {
        uint32_t lw = std::max(1u, w >> lv), lh = std::max(1u, h >> lv);
        std::vector<uint8_t> b;
        for (uint32_t i = 0; i < ((lw + bw - 1) / bw) * ((lh + bh - 1) / bh); ++i)
            put_void_extent(b, lv ? c1 : c0);
        k.levels[lv] = b;
    }
    return k;
}

std::string dir()
{
    static std::string d = [] {
        std::string p = MVR_GLTF_BLOCKS_DIR;
        mkdir(p.c_str(), 0777);
        return p;
    }();
    return d;
}

std::string codecs(const std::string &name)
{
    return std::string(MVR_CODECS_DIR) + "/" + name;
}

std::string file_image(const std::string &name, const std::vector<uint8_t> &bytes, const char *mime = "image/ktx2")
{
    write_bytes(dir() + "/" + name, bytes.data(), bytes.size());
    std::string j = "{\"uri\":\"" + name + "\"";
    if (mime)
        j += std::string(",\"mimeType\":\"") + mime + "\"";
    return j + "}";
}

const char *NEAREST = "{\"magFilter\":9728,\"minFilter\":9728}";
const char *MIPMAPPED = "{\"magFilter\":9728,\"minFilter\":9984}";   // NEAREST_MIPMAP_NEAREST

// Quads in a row, quad i textured by images[i] (one material and texture
// each; "" = untextured), sampled by `sampler`; uv scale > 1 through
// KHR_texture_transform (a minified texture: the mips are read).
std::string write_scene(const std::string &name, const std::vector<std::string> &images, const char *sampler,
                        float uv_scale = 1)
{
    doc d;
    std::vector<uint8_t> bin;
    d.add(d.samplers, sampler);
    d.use("KHR_materials_unlit");
    if (uv_scale != 1)
        d.use("KHR_texture_transform");
    std::vector<std::string> prims;
    float x0 = -0.6f * float(images.size() - 1);
    for (size_t i = 0; i < images.size(); ++i) {
        std::string pbr = "\"metallicFactor\":0";
        if (!images[i].empty()) {
            int img = d.add(d.images, images[i]);
            int tex = d.add(d.textures, "{\"sampler\":0,\"source\":" + std::to_string(img) + "}");
            std::string info = "{\"index\":" + std::to_string(tex);
            if (uv_scale != 1) {
                char s[96];
                std::snprintf(s, sizeof s, ",\"extensions\":{\"KHR_texture_transform\":{\"scale\":[%g,%g]}}",
                              double(uv_scale), double(uv_scale));
                info += s;
            }
            pbr += ",\"baseColorTexture\":" + info + "}";
        }
        int m = d.add(d.materials, "{\"pbrMetallicRoughness\":{" + pbr + "},\"extensions\":{\"KHR_materials_unlit\":{}}}");
        prims.push_back(quad(d, bin, 0, x0 + 1.2f * float(i), 0, 0.5f, m));
    }
    one_mesh(d, prims);
    d.buffers.insert(d.buffers.begin(), data_buffer(bin));
    std::string path = dir() + "/" + name + ".gltf";
    write_text(path, d.json());
    return path;
}

// ------------------------------------------------------------ load and render

struct messages {
    std::vector<std::string> warnings;
    bool warned(const std::string &a, const std::string &b = "", const std::string &c = "") const
    {
        for (const auto &w : warnings)
            if (w.find(a) != std::string::npos && w.find(b) != std::string::npos && w.find(c) != std::string::npos)
                return true;
        return false;
    }
};

void collect(mvr_log_level level, mvr_log_id, const char *message, void *user)
{
    if (level == MVR_LOG_WARNING)
        static_cast<messages *>(user)->warnings.push_back(message);
}

struct loaded {
    mvr_result r = MVR_OK;
    std::string msg;
    mvr_scene *scene = nullptr;
    mvr_gltf_info info = {};
    messages log;
    loaded() = default;
    loaded(const loaded &) = delete;
    loaded &operator=(const loaded &) = delete;
    ~loaded() { mvr_scene_destroy(scene); }
};

void load(mvr_test_state *t, const std::string &path, loaded *out)
{
    mvr_gltf_options o;
    std::memset(&o, 0, sizeof o);
    o.logger.fn = collect;
    o.logger.user_data = &out->log;
    mvr_error err;
    std::memset(&err, 0, sizeof err);
    out->r = mvr_gltf_load_file(path.c_str(), &o, &out->scene, &out->info, &err);
    out->msg = out->r == MVR_OK ? "" : err.message;
    std::string name = path.substr(path.find_last_of('/') + 1);
    CHECK_MSG(t, out->r == MVR_OK && out->log.warnings.empty() && out->info.images_missing == 0,
              "%s: %s %s, %zu warnings %s", name.c_str(), mvr_result_name(out->r), out->msg.c_str(),
              out->log.warnings.size(), out->log.warnings.empty() ? "" : out->log.warnings[0].c_str());
}

mvr_context *g_ctx = nullptr;

mvr_context *context()
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
    return g_ctx;
}

struct frame {
    std::vector<uint8_t> px;   // both layers, RGBA8
    mvr_frame_stats stats = {};
    messages log;              // the renderer's warnings
};

struct paths {
    mvr_material_path material;
    mvr_view_path view;
};
const paths every_path[] = {{MVR_MATERIAL_PATH_ARRAYS, MVR_VIEW_PATH_MULTIVIEW},
                            {MVR_MATERIAL_PATH_ARRAYS, MVR_VIEW_PATH_LOOP},
                            {MVR_MATERIAL_PATH_PER_MATERIAL, MVR_VIEW_PATH_MULTIVIEW},
                            {MVR_MATERIAL_PATH_PER_MATERIAL, MVR_VIEW_PATH_LOOP}};

// gltf_render::two_layers with the paths, the renderer's warnings, its stats
// and overrides.disable_image_formats.
frame render(mvr_test_state *t, mvr_scene *scene, const std::string &what, paths p = every_path[0],
             uint32_t disable_formats = 0)
{
    frame out;
    mvr_context *ctx = context();
    if (!ctx || !scene)
        return out;
    const int W = gltf_render::frame_width, H = gltf_render::frame_height;
    mvr_framing_desc fd = {MVR_LAYOUT_STEREO, 2, 0.2, double(W) / H, 0, 0.0, 0.0};
    // the level, sphere-fitted view these checks were sized for (the mip
    // level a minified quad reads depends on its size on screen)
    fd.level = true;
    fd.fit_sphere = true;
    mvr_view_set *views = nullptr;
    mvr_error err;
    if (mvr_view_set_frame_scene(scene, &fd, &views, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s: framing: %s", what.c_str(), err.message);
        return out;
    }
    mvr_renderer_desc rd = {};
    rd.context = ctx;
    rd.view_path = p.view;
    rd.material_path = p.material;
    rd.logger.fn = collect;
    rd.logger.user_data = &out.log;
    rd.overrides.disable_image_formats = disable_formats;
    mvr_renderer *r = nullptr;
    mvr_target *target = nullptr;
    mvr_target_desc td = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_DEFAULT, 0};
    mvr_render_desc desc = {{0.05f, 0.05f, 0.08f, 1.0f}, 1.0f, MVR_TONE_MAP_NONE};
    bool ok = mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
              mvr_renderer_render(r, scene, views, target, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "%s: render (%s, %s): %s", what.c_str(), mvr_material_path_name(p.material),
              mvr_view_path_name(p.view), r ? mvr_renderer_last_error(r) : err.message);
    if (ok) {
        mvr_renderer_get_stats(r, &out.stats);
        out.px.resize(size_t(W) * H * 4 * 2);
        for (uint32_t k = 0; k < 2; ++k)
            CHECK(t, mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, &out.px[size_t(k) * W * H * 4],
                                             size_t(W) * H * 4) == MVR_OK);
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(views);
    return out;
}

// The largest per-channel difference of two frames (256: sizes differ).
int max_diff(const std::vector<uint8_t> &a, const std::vector<uint8_t> &b)
{
    if (a.size() != b.size() || a.empty())
        return 256;
    int m = 0;
    for (size_t i = 0; i < a.size(); ++i)
        m = std::max(m, std::abs(int(a[i]) - int(b[i])));
    return m;
}

// Pixels within 2 of colour c (RGB).
size_t count_colour(const std::vector<uint8_t> &px, const uint8_t *c)
{
    size_t n = 0;
    for (size_t i = 0; i + 3 < px.size(); i += 4)
        n += std::abs(int(px[i]) - int(c[0])) <= 2 && std::abs(int(px[i + 1]) - int(c[1])) <= 2 &&
             std::abs(int(px[i + 2]) - int(c[2])) <= 2;
    return n;
}

std::vector<uint8_t> decoded(const uint8_t *c5)
{
    return {dec5(c5[0]), dec5(c5[1]), dec5(c5[2]), 255};
}

// Renders a loaded scene on every path: the frames must be the same bytes;
// returns the first. compressed: the images the stats must report as held
// block-compressed.
frame render_every_path(mvr_test_state *t, const loaded &l, const std::string &what, uint32_t compressed)
{
    frame first;
    for (const paths &p : every_path) {
        frame f = render(t, l.scene, what, p);
        std::string label = what + " (" + mvr_material_path_name(p.material) + ", " + mvr_view_path_name(p.view) + ")";
        CHECK_MSG(t, f.stats.images_compressed == compressed && f.stats.images_unsampleable == 0,
                  "%s: images_compressed %u (want %u), images_unsampleable %u", label.c_str(),
                  f.stats.images_compressed, compressed, f.stats.images_unsampleable);
        CHECK_MSG(t, f.log.warnings.empty(), "%s: warned: %s", label.c_str(),
                  f.log.warnings.empty() ? "" : f.log.warnings[0].c_str());
        if (first.px.empty())
            first = f;
        else
            CHECK_MSG(t, f.px == first.px, "%s: differs from the first path's frame (max %d)", label.c_str(),
                      max_diff(f.px, first.px));
    }
    return first;
}

// ------------------------------------------------------------ cases

// The committed ETC2 files (no supercompression, Zstandard; the glTF as
// committed, and the KTX2 declared every way) render like the PNG twin:
// within 1/255, the quadrants' colours in the picture, uploaded compressed
// (images_compressed; the PNG's 0), the same bytes on every path.
void etc2_renders_like_png(mvr_test_state *t)
{
    if (!context())
        SKIP(t, "no GL context");
    loaded png;
    load(t, write_scene("etc2_png", {file_image("etc2.png", gen::read_file(codecs("etc2.png")), "image/png")}, NEAREST),
         &png);
    frame ref = render_every_path(t, png, "etc2 png twin", 0);
    CHECK(t, !ref.px.empty());
    std::vector<uint8_t> ktx = gen::read_file(codecs("etc2.ktx2")), zstd = gen::read_file(codecs("etc2_zstd.ktx2"));
    CHECK(t, !ktx.empty() && !zstd.empty());
    struct variant {
        std::string name, path;
    } variants[] = {
        {"etc2.gltf (committed)", codecs("etc2.gltf")},
        {"etc2 mimeType", write_scene("etc2_mime", {file_image("etc2.ktx2", ktx)}, NEAREST)},
        {"etc2 signature", write_scene("etc2_sig", {file_image("etc2_sig.bin", ktx, nullptr)}, NEAREST)},
        {"etc2 zstd", write_scene("etc2_zstd", {file_image("etc2_zstd.ktx2", zstd)}, NEAREST)},
    };
    for (const variant &v : variants) {
        loaded l;
        load(t, v.path, &l);
        CHECK_MSG(t, l.info.images_decoded == 1, "%s: %u images", v.name.c_str(), l.info.images_decoded);
        frame f = render_every_path(t, l, v.name, 1);
        int d = max_diff(f.px, ref.px);
        std::printf("  %-24s max difference from the PNG twin: %d\n", v.name.c_str(), d);
        CHECK_MSG(t, d <= 1, "%s: differs from the PNG twin by %d/255", v.name.c_str(), d);
        for (int q = 0; q < 4; ++q) {
            std::vector<uint8_t> c = decoded(quadrant5[q]);
            size_t n = count_colour(f.px, c.data());
            CHECK_MSG(t, n > 100, "%s: %zu pixels of quadrant %d's colour", v.name.c_str(), n, q);
        }
    }
}

// The mips come from the file: a minified quad (uv scale 8, NEAREST_MIPMAP_NEAREST)
// shows the colours of levels > 0, which level 0 lacks; with 2 levels only
// level 1's (GL_TEXTURE_MAX_LEVEL 1); with levelCount 0 (base level only) only
// level 0's. Zstandard levels render the same bytes; every path agrees.
void etc2_mips_come_from_the_file(mvr_test_state *t)
{
    if (!context())
        SKIP(t, "no GL context");
    auto count_levels = [](const std::vector<uint8_t> &px, int from, int to) {
        size_t n = 0;
        for (int lv = from; lv <= to; ++lv) {
            std::vector<uint8_t> c = decoded(lv ? level5[lv] : quadrant5[0]);
            if (lv == 0)
                for (int q = 0; q < 4; ++q) {
                    c = decoded(quadrant5[q]);
                    n += count_colour(px, c.data());
                }
            else
                n += count_colour(px, c.data());
        }
        return n;
    };
    struct variant {
        const char *name;
        uint32_t levels;
        bool zstd;
        int lo, hi;   // the levels whose colours may show
    } variants[] = {{"etc2_mips_full", 5, false, 1, 4}, {"etc2_mips_full_zstd", 5, true, 1, 4},
                    {"etc2_mips_two", 2, false, 1, 1},  {"etc2_mips_base_only", 0, false, 0, 0}};
    std::vector<uint8_t> full;
    for (const variant &v : variants) {
        ktx2_desc k = etc2(v.levels);
        if (v.zstd)
            ktx2_zstd(k);
        loaded l;
        load(t, write_scene(v.name, {file_image(std::string(v.name) + ".ktx2", ktx2_file(k))}, MIPMAPPED, 8.0f), &l);
        frame f = render_every_path(t, l, v.name, 1);
        size_t inside = count_levels(f.px, v.lo, v.hi);
        size_t outside = count_levels(f.px, 0, 4) - inside;
        std::printf("  %-24s pixels of levels %d..%d: %zu, of the others: %zu\n", v.name, v.lo, v.hi, inside, outside);
        CHECK_MSG(t, inside > 500 && outside == 0, "%s: %zu pixels of levels %d..%d, %zu of other levels", v.name,
                  inside, v.lo, v.hi, outside);
        if (v.levels == 5 && !v.zstd)
            full = f.px;
        else if (v.levels == 5)
            CHECK_MSG(t, f.px == full, "%s: differs from the uncompressed file's frame", v.name);
    }
}

// Two files of the same blocks: one array (core_batch_plan checks that they
// share a layer), both counted as compressed; no RGBA8 group holds
// blocks, so the default material's white layer is a 1 x 1 RGBA8 group of
// its own (2 groups). An ETC2 image and an RGBA8 image of the same size
// never share an array (2 groups, the white layer in the RGBA8 one).
void etc2_groups(mvr_test_state *t)
{
    if (!context())
        SKIP(t, "no GL context");
    std::vector<uint8_t> ktx = gen::read_file(codecs("etc2.ktx2"));
    std::vector<uint8_t> png = gen::read_file(codecs("etc2.png"));
    {
        loaded l;
        load(t, write_scene("etc2_twice", {file_image("a.ktx2", ktx), file_image("b.ktx2", ktx)}, NEAREST), &l);
        frame f = render_every_path(t, l, "etc2 twice", 2);
        CHECK_MSG(t, f.stats.texture_groups == 2, "etc2 twice: %u texture groups", f.stats.texture_groups);
    }
    {
        loaded l;
        load(t, write_scene("etc2_and_png", {file_image("c.ktx2", ktx), file_image("c.png", png, "image/png")}, NEAREST),
             &l);
        frame f = render_every_path(t, l, "etc2 and png", 1);
        CHECK_MSG(t, f.stats.texture_groups == 2, "etc2 and png: %u texture groups", f.stats.texture_groups);
        CHECK(t, !f.px.empty());
    }
}

const uint32_t ETC2_FORMATS = 1u << MVR_IMAGE_FORMAT_ETC2_RGB8 | 1u << MVR_IMAGE_FORMAT_ETC2_RGB8_A1 |
                              1u << MVR_IMAGE_FORMAT_ETC2_RGBA8 | 1u << MVR_IMAGE_FORMAT_EAC_R11 |
                              1u << MVR_IMAGE_FORMAT_EAC_RG11;
const uint32_t ASTC_FORMATS = ((1u << (MVR_IMAGE_FORMAT_ASTC_12x12 + 1)) - 1) & ~((1u << MVR_IMAGE_FORMAT_ASTC_4x4) - 1);

// A format the GL cannot sample (forced): the frame does not fail; the
// warning names the image, its format and why; the stats count it; the
// texture reads the role's neutral value (white: the untextured quad's
// frame), on every path alike.
void unsampleable_formats_degrade(mvr_test_state *t)
{
    if (!context())
        SKIP(t, "no GL context");
    loaded plain;
    load(t, write_scene("untextured", {""}, NEAREST), &plain);
    frame white = render(t, plain.scene, "untextured");
    const uint8_t c[4] = {30, 200, 90, 255};
    struct variant {
        const char *name;
        std::string path;
        uint32_t disable;
        const char *format;
    } variants[] = {
        {"etc2", codecs("etc2.gltf"), ETC2_FORMATS, "etc2_rgba8"},
        {"astc", write_scene("astc_disabled", {file_image("astc_disabled.ktx2", ktx2_file(astc(158, 4, 4, 8, 8, c, c)))},
                             NEAREST),
         ASTC_FORMATS, "astc_4x4"},
    };
    for (const variant &v : variants) {
        loaded l;
        load(t, v.path, &l);
        for (const paths &p : every_path) {
            frame f = render(t, l.scene, v.name, p, v.disable);
            std::string label = std::string(v.name) + " (" + mvr_material_path_name(p.material) + ", " +
                                mvr_view_path_name(p.view) + ")";
            CHECK_MSG(t, f.stats.images_unsampleable == 1 && f.stats.images_compressed == 0,
                      "%s: images_unsampleable %u, images_compressed %u", label.c_str(), f.stats.images_unsampleable,
                      f.stats.images_compressed);
            CHECK_MSG(t, f.log.warnings.size() == 1 && f.log.warned("image 1", v.format, "neutral value"),
                      "%s: %zu warnings: %s", label.c_str(), f.log.warnings.size(),
                      f.log.warnings.empty() ? "" : f.log.warnings[0].c_str());
            CHECK_MSG(t, !f.px.empty() && f.px == white.px, "%s: not the untextured (white) quad", label.c_str());
        }
    }
}

// ASTC LDR where the GL has KHR_texture_compression_astc_ldr: void-extent
// blocks (one colour per level) of 4x4 (sRGB) and 6x6 (linear; 8x8 texels
// in 2 x 2 blocks, the last ones partly outside) render like the PNG of
// their colour (an RGBA8 twin), the mips (level 1's colour) read when minified. Without the
// extension the image degrades with the warning.
void astc_void_extent(mvr_test_state *t)
{
    mvr_context *ctx = context();
    if (!ctx)
        SKIP(t, "no GL context");
    bool has = mvr_context_caps(ctx)->ext.astc_ldr;
    std::printf("  KHR_texture_compression_astc_ldr: %s\n", has ? "yes" : "no");
    const uint8_t c0[4] = {200, 120, 40, 255}, c1[4] = {40, 90, 210, 255};
    struct variant {
        const char *name;
        uint32_t vk, bw, bh;
    } variants[] = {{"astc_4x4_srgb", 158, 4, 4}, {"astc_6x6_unorm", 165, 6, 6}};
    std::vector<uint8_t> px(8 * 8 * 4);
    for (size_t i = 0; i < px.size(); ++i)
        px[i] = c0[i % 4];
    // the twin: an uncompressed RGBA8 KTX2 of the same pixels (decoded to RGBA8 like a PNG)
    std::vector<uint8_t> png_bytes = ktx2_file(ktx2_from_rgba(px, 8, 8, VK_R8G8B8A8_SRGB, 1));
    loaded ref;
    load(t, write_scene("astc_ref", {file_image("astc_ref.ktx2", png_bytes)}, NEAREST), &ref);
    frame rf = render(t, ref.scene, "astc reference");
    for (const variant &v : variants) {
        ktx2_desc k = astc(v.vk, v.bw, v.bh, 8, 8, c0, c1);
        std::string image = file_image(std::string(v.name) + ".ktx2", ktx2_file(k));
        loaded l;
        load(t, write_scene(v.name, {image}, NEAREST), &l);
        if (!has) {
            frame f = render(t, l.scene, v.name);
            CHECK_MSG(t, f.stats.images_unsampleable == 1 && f.log.warned("image 1", "astc", "neutral value"),
                      "%s without the extension: unsampleable %u", v.name, f.stats.images_unsampleable);
            continue;
        }
        frame f = render_every_path(t, l, v.name, 1);
        int d = max_diff(f.px, rf.px);
        std::printf("  %-24s max difference from the RGBA8 twin: %d\n", v.name, d);
        CHECK_MSG(t, d <= 1, "%s: differs from its RGBA8 twin by %d/255", v.name, d);
        loaded m;
        load(t, write_scene(std::string(v.name) + "_minified", {image}, MIPMAPPED, 8.0f), &m);
        frame mf = render_every_path(t, m, std::string(v.name) + " minified", 1);
        size_t n1 = count_colour(mf.px, c1), n0 = count_colour(mf.px, c0);
        CHECK_MSG(t, n1 > 500 && n0 == 0, "%s minified: %zu pixels of level 1's colour, %zu of level 0's", v.name, n1,
                  n0);
    }
}

}  // namespace

int main()
{
    static const mvr_test_case cases[] = {
        {"etc2_renders_like_png", etc2_renders_like_png},
        {"etc2_mips_come_from_the_file", etc2_mips_come_from_the_file},
        {"etc2_groups", etc2_groups},
        {"unsampleable_formats_degrade", unsampleable_formats_degrade},
        {"astc_void_extent", astc_void_extent},
    };
    int rc = mvr_test_run(cases, sizeof cases / sizeof cases[0]);
    mvr_context_destroy(g_ctx);
    return rc;
}
