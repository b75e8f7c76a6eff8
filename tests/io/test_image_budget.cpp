// mvr_image's memory budget and its refusals of hostile headers, with small
// generated files (never a large allocation: the point is refusal first):
//  - a 121-byte .hdr declaring 16384x16384, a 64-channel 4096x4096 EXR
//    header (32 KB) and a 38-byte WebP declaring 16383x16383: mvr_image_read
//    refuses each under the default budget, naming the file, the declared
//    size and the budget, and the process never grows by gigabytes;
//  - a 16-bit interlaced PNG whose size fits the 8-bit charge but not its
//    real cost (16-bit native rows for the whole image) is refused by
//    mvr_image_decode and by a glTF load whose budget only the 8-bit charge
//    fits (the load's budget is never waived, not even for a missing image);
//  - the budget counts every stored channel: a small 64-channel EXR is
//    refused under a budget its 4-channel twin decodes within;
//  - a truncated JPEG is refused (never a grey texture), from memory, from a
//    file and in a glTF load; the whole file decodes;
//  - a corrupt PNG prints nothing to stderr (libpng's message is the error's).
// OpenImageIO is linked here only to write the small JPEG / EXR inputs.
#include <OpenImageIO/imageio.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "mvr/mvr_gltf.h"
#include "mvr/mvr_image.h"
#include "mvr_test.h"

namespace {

std::string out_path(const std::string &name)
{
    return std::string(MVR_IMAGE_BUDGET_OUT) + "/" + name;
}

bool write_bytes(const std::string &path, const std::vector<unsigned char> &b)
{
    FILE *f = std::fopen(path.c_str(), "wb");
    bool ok = f && std::fwrite(b.data(), 1, b.size(), f) == b.size();
    return f && std::fclose(f) == 0 && ok;
}

std::vector<unsigned char> read_bytes(const std::string &path)
{
    std::vector<unsigned char> b;
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f)
        return b;
    int c;
    while ((c = std::getc(f)) != EOF)
        b.push_back(static_cast<unsigned char>(c));
    std::fclose(f);
    return b;
}

void put(std::vector<unsigned char> &b, const void *p, size_t n)
{
    const auto *c = static_cast<const unsigned char *>(p);
    b.insert(b.end(), c, c + n);
}

void put_str(std::vector<unsigned char> &b, const std::string &s)
{
    put(b, s.data(), s.size());
}

void put_le32(std::vector<unsigned char> &b, uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        b.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

void put_be32(std::vector<unsigned char> &b, uint32_t v)
{
    for (int i = 3; i >= 0; --i)
        b.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

// The most memory the process has held, in MiB.
long peak_mib()
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss / 1024;
}

bool says(const mvr_error &e, const char *part)
{
    return std::strstr(e.message, part) != nullptr;
}

// A Radiance header (Greg Ward, "Real Pixels", Graphics Gems II: the
// "#?RADIANCE" magic, FORMAT, a blank line, then "-Y height +X width"), the
// start of one run-length scanline and padding: 121 bytes.
std::vector<unsigned char> huge_hdr()
{
    std::vector<unsigned char> b;
    put_str(b, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16384 +X 16384\n");
    const unsigned char run[4] = {2, 2, 0x40, 0};
    put(b, run, 4);
    b.resize(121, 0x80);
    return b;
}

// An OpenEXR scanline file's header (openexr.com, "The OpenEXR File Layout":
// magic, version 2, attributes as name, type, size, value, a null byte, then
// one 64-bit offset per scanline for uncompressed data): 64 float channels of
// 4096x4096 declared, no pixels.
std::vector<unsigned char> wide_exr(int channels, int size)
{
    std::vector<unsigned char> b = {0x76, 0x2f, 0x31, 0x01};
    put_le32(b, 2);
    auto attr = [&](const char *name, const char *type, const std::vector<unsigned char> &v) {
        put(b, name, std::strlen(name) + 1);
        put(b, type, std::strlen(type) + 1);
        put_le32(b, uint32_t(v.size()));
        put(b, v.data(), v.size());
    };
    std::vector<unsigned char> chlist, box, one, zero8;
    for (int c = 0; c < channels; ++c) {
        char name[8];
        std::snprintf(name, sizeof name, "c%02d", c);
        put(chlist, name, std::strlen(name) + 1);
        put_le32(chlist, 2);                     // FLOAT
        put_le32(chlist, 0);                     // pLinear, reserved
        put_le32(chlist, 1);                     // xSampling
        put_le32(chlist, 1);                     // ySampling
    }
    chlist.push_back(0);
    for (uint32_t v : {0u, 0u, uint32_t(size - 1), uint32_t(size - 1)})
        put_le32(box, v);
    float f1 = 1.0f;
    put(one, &f1, 4);
    zero8.assign(8, 0);
    attr("channels", "chlist", chlist);
    attr("compression", "compression", {0});
    attr("dataWindow", "box2i", box);
    attr("displayWindow", "box2i", box);
    attr("lineOrder", "lineOrder", {0});
    attr("pixelAspectRatio", "float", one);
    attr("screenWindowCenter", "v2f", zero8);
    attr("screenWindowWidth", "float", one);
    b.push_back(0);
    b.resize(b.size() + 8 * size_t(size) + 64, 0);
    return b;
}

// A lossy WebP (RIFF "WEBP" with a "VP8 " chunk, RFC 9649 2.5; the VP8 key
// frame header of RFC 6386 9.1: frame tag, start code 9D 01 2A, 14-bit width
// and height) declaring 16383x16383, with nothing after the header: 38 bytes.
std::vector<unsigned char> huge_webp()
{
    std::vector<unsigned char> vp8 = {0x10, 0x02, 0x00, 0x9d, 0x01, 0x2a, 0xff, 0x3f, 0xff, 0x3f};
    vp8.resize(18, 0);
    std::vector<unsigned char> b;
    put_str(b, "RIFF");
    put_le32(b, uint32_t(4 + 8 + vp8.size()));
    put_str(b, "WEBPVP8 ");
    put_le32(b, uint32_t(vp8.size()));
    put(b, vp8.data(), vp8.size());
    return b;
}

uint32_t crc32_of(const unsigned char *p, size_t n)
{
    // ISO/IEC 15948 Annex D: CRC-32, polynomial 0xEDB88320 (reflected)
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

void png_chunk(std::vector<unsigned char> &b, const char *type, const std::vector<unsigned char> &data)
{
    put_be32(b, uint32_t(data.size()));
    size_t start = b.size();
    put(b, type, 4);
    put(b, data.data(), data.size());
    put_be32(b, crc32_of(b.data() + start, b.size() - start));
}

// A PNG header (ISO/IEC 15948 11.2.2) of 16-bit RGBA, Adam7-interlaced, with
// a token IDAT: whatever decodes it fails on the data, after allocating.
std::vector<unsigned char> png16_interlaced(uint32_t w, uint32_t h)
{
    std::vector<unsigned char> b = {137, 80, 78, 71, 13, 10, 26, 10}, ihdr;
    put_be32(ihdr, w);
    put_be32(ihdr, h);
    for (unsigned char v : {16, 6, 0, 0, 1})   // depth, RGBA, deflate, filter 0, Adam7
        ihdr.push_back(v);
    png_chunk(b, "IHDR", ihdr);
    png_chunk(b, "IDAT", {0x78, 0x9c, 0x63, 0x00, 0x00});
    png_chunk(b, "IEND", {});
    return b;
}

// A base64 data URI (RFC 4648 4) of the bytes.
std::string data_uri(const char *mime, const std::vector<unsigned char> &b)
{
    static const char *abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string s = std::string("data:") + mime + ";base64,";
    for (size_t i = 0; i < b.size(); i += 3) {
        uint32_t v = uint32_t(b[i]) << 16 | (i + 1 < b.size() ? uint32_t(b[i + 1]) << 8 : 0) |
                     (i + 2 < b.size() ? b[i + 2] : 0);
        s += abc[v >> 18 & 63];
        s += abc[v >> 12 & 63];
        s += i + 1 < b.size() ? abc[v >> 6 & 63] : '=';
        s += i + 2 < b.size() ? abc[v & 63] : '=';
    }
    return s;
}

// A one-triangle glTF whose material's base colour is the image.
std::string textured_gltf(const std::string &uri)
{
    const float tri[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};   // 3 positions, 3 UVs
    std::vector<unsigned char> buf(sizeof tri);
    std::memcpy(buf.data(), tri, sizeof tri);
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],
"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],
"textures":[{"source":0}],"images":[{"uri":")" +
           uri + R"("}],
"buffers":[{"byteLength":60,"uri":")" +
           data_uri("application/octet-stream", buf) + R"("}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}]})";
}

struct load_result {
    mvr_result r = MVR_OK;
    mvr_gltf_info info = {};
    mvr_error err = {};
    std::vector<std::string> warnings;
};

void on_log(mvr_log_level level, mvr_log_id, const char *message, void *user)
{
    if (level <= MVR_LOG_WARNING)
        static_cast<load_result *>(user)->warnings.push_back(message);
}

load_result load(const std::string &json, uint64_t budget)
{
    load_result out;
    mvr_gltf_options o;
    std::memset(&o, 0, sizeof o);
    o.memory_budget = budget;
    o.logger.fn = on_log;
    o.logger.user_data = &out;
    mvr_scene *scene = nullptr;
    out.r = mvr_gltf_load_memory(json.data(), json.size(), &o, &scene, &out.info, &out.err);
    mvr_scene_destroy(scene);
    return out;
}

// A small image written by OpenImageIO; empty on failure.
std::vector<unsigned char> oiio_file(const std::string &name, int w, int h, int channels, OIIO::TypeDesc type,
                                     const char *attribute = nullptr, int value = 0)
{
    std::string path = out_path(name);
    auto out = OIIO::ImageOutput::create(path);
    OIIO::ImageSpec spec(w, h, channels, type);
    if (attribute)
        spec.attribute(attribute, value);
    std::vector<float> pixels(size_t(w) * size_t(h) * size_t(channels));
    for (size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = float((i * 37) % 101) / 100.0f;   // texture, so the JPEG has entropy-coded data
    if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !out->close())
        return {};
    return read_bytes(path);
}

}  // namespace

static void hostile_headers_refused_before_allocating(mvr_test_state *t)
{
    struct file {
        const char *name;
        std::vector<unsigned char> bytes;
        const char *declared;
    } files[] = {
        {"huge.hdr", huge_hdr(), "16384x16384, 3 channel(s)"},
        {"wide.exr", wide_exr(64, 4096), "4096x4096, 64 channel(s) of 4 byte(s)"},
        {"huge.webp", huge_webp(), "16383x16383"},
    };
    CHECK(t, files[0].bytes.size() == 121);
    for (const file &f : files) {
        std::string path = out_path(f.name);
        CHECK(t, write_bytes(path, f.bytes));
        mvr_image_data img = {};
        mvr_error e = {};
        mvr_result r = mvr_image_read(path.c_str(), MVR_PIXEL_F32, &img, &e);
        CHECK_MSG(t, r == MVR_ERROR_OUT_OF_MEMORY, "%s: %d %s", f.name, r, e.message);
        CHECK_MSG(t, says(e, path.c_str()) && says(e, f.declared) && says(e, "memory budget of 2048.0 MiB"),
                  "%s: %s", f.name, e.message);
        CHECK(t, img.pixels == nullptr);
        // the same through the explicit budget, and under a smaller one
        r = mvr_image_read_within(path.c_str(), MVR_PIXEL_U8, 64u << 20, &img, &e);
        CHECK_MSG(t, r == MVR_ERROR_OUT_OF_MEMORY && says(e, "memory budget of 64.0 MiB"), "%s: %s", f.name, e.message);
    }
    // refused before anything was allocated: each would have needed gigabytes
    CHECK_MSG(t, peak_mib() < 1024, "the process peaked at %ld MiB", peak_mib());
}

static void png16_interlaced_charged_at_16_bits(mvr_test_state *t)
{
    // 16384 x 14000: the 8-bit charge (RGBA8 + RGBA8) is 1750 MiB, within
    // 2 GiB; the real cost adds 8 bytes a pixel of native rows: 2625 MiB
    const uint32_t w = 16384, h = 14000;
    std::vector<unsigned char> png = png16_interlaced(w, h);
    uint64_t cost = 0;
    mvr_error e = {};
    CHECK_MSG(t, mvr_image_decode_cost(png.data(), png.size(), "image/png", &cost, &e) == MVR_OK, "%s", e.message);
    uint64_t px = uint64_t(w) * h;
    CHECK_MSG(t, cost == px * 4 + px * 8 + uint64_t(h) * sizeof(void *), "cost %llu", (unsigned long long)cost);
    mvr_image_data img = {};
    mvr_result r = mvr_image_decode(png.data(), png.size(), "image/png", 0, &img, &e);
    CHECK_MSG(t, r == MVR_ERROR_OUT_OF_MEMORY && says(e, "16384x14000, 4 channel(s) of 2 byte(s)") &&
                     says(e, "memory budget of 2048.0 MiB"),
              "%d %s", r, e.message);
    CHECK(t, img.pixels == nullptr);
    // in a glTF load of budget 80 MiB: 4096 x 2048 is charged 64 MiB at 8
    // bits (fits) but holds 96 MiB at 16 (refused, the budget is never waived)
    load_result l = load(textured_gltf(data_uri("image/png", png16_interlaced(4096, 2048))), 80u << 20);
    CHECK_MSG(t, l.r == MVR_ERROR_OUT_OF_MEMORY && says(l.err, "images[0]") && says(l.err, "memory budget"), "%d %s",
              l.r, l.err.message);
    CHECK_MSG(t, peak_mib() < 1024, "the process peaked at %ld MiB", peak_mib());
}

static void every_channel_counts(mvr_test_state *t)
{
    std::vector<unsigned char> wide = oiio_file("wide64.exr", 32, 32, 64, OIIO::TypeDesc::FLOAT);
    std::vector<unsigned char> rgba = oiio_file("rgba4.exr", 32, 32, 4, OIIO::TypeDesc::FLOAT);
    CHECK(t, !wide.empty() && !rgba.empty());
    // 32 x 32 x 4 x 4 bytes, twice (as read, and RGBA): 32 KiB; 64 channels
    // as read add 240 KiB more
    const uint64_t budget = 128u << 10;
    mvr_image_data img = {};
    mvr_error e = {};
    mvr_result r = mvr_image_read_within(out_path("rgba4.exr").c_str(), MVR_PIXEL_F32, budget, &img, &e);
    CHECK_MSG(t, r == MVR_OK && img.width == 32, "%s", e.message);
    mvr_image_free(&img);
    r = mvr_image_read_within(out_path("wide64.exr").c_str(), MVR_PIXEL_F32, budget, &img, &e);
    CHECK_MSG(t, r == MVR_ERROR_OUT_OF_MEMORY && says(e, "64 channel(s)"), "%d %s", r, e.message);
    r = mvr_image_read_within(out_path("wide64.exr").c_str(), MVR_PIXEL_F32, 1u << 20, &img, &e);
    CHECK_MSG(t, r == MVR_OK, "%s", e.message);
    mvr_image_free(&img);
}

static void truncated_jpeg_refused(mvr_test_state *t)
{
    uint64_t costs[2] = {0, 0};
    for (int progressive = 0; progressive < 2; ++progressive) {
        std::string name = progressive ? "whole_progressive.jpg" : "whole.jpg";
        std::vector<unsigned char> jpg =
            oiio_file(name, 64, 64, 3, OIIO::TypeDesc::UINT8, "jpeg:progressive", progressive);
        CHECK(t, jpg.size() > 200);
        mvr_image_data img = {};
        mvr_error e = {};
        CHECK_MSG(t, mvr_image_decode(jpg.data(), jpg.size(), "image/jpeg", 0, &img, &e) == MVR_OK, "%s", e.message);
        mvr_image_free(&img);
        CHECK_MSG(t, mvr_image_decode_cost(jpg.data(), jpg.size(), "image/jpeg", &costs[progressive], &e) == MVR_OK,
                  "%s", e.message);
        std::vector<unsigned char> cut(jpg.begin(), jpg.begin() + long(jpg.size() * 2 / 3));
        mvr_result r = mvr_image_decode(cut.data(), cut.size(), "image/jpeg", 0, &img, &e);
        CHECK_MSG(t, r == MVR_ERROR_INVALID_ASSET && says(e, "truncated"), "%s: %d %s", name.c_str(), r, e.message);
        CHECK(t, img.pixels == nullptr);
        std::string path = out_path("cut_" + name);
        CHECK(t, write_bytes(path, cut));
        r = mvr_image_read(path.c_str(), MVR_PIXEL_U8, &img, &e);
        CHECK_MSG(t, r == MVR_ERROR_INVALID_ASSET && says(e, "truncated") && says(e, path.c_str()), "%d %s", r,
                  e.message);
        // in a load: the image is left out, warned (never a grey texture)
        load_result l = load(textured_gltf(data_uri("image/jpeg", cut)), 0);
        CHECK_MSG(t, l.r == MVR_OK && l.info.images_missing == 1, "%d %s", l.r, l.err.message);
        bool warned = false;
        for (const std::string &w : l.warnings)
            warned = warned || w.find("truncated") != std::string::npos;
        CHECK_MSG(t, warned, "no warning names the truncation (%zu warnings)", l.warnings.size());
    }
    // a progressive JPEG also holds its coefficients: 2 bytes a sample
    CHECK_MSG(t, costs[1] == costs[0] + 64 * 64 * 3 * 2, "baseline %llu, progressive %llu",
              (unsigned long long)costs[0], (unsigned long long)costs[1]);
}

// stderr into a file while fn runs; what was written there.
template <typename Fn>
std::string stderr_of(Fn fn)
{
    std::string path = out_path("stderr.txt");
    std::fflush(stderr);
    int saved = dup(2);
    FILE *f = std::fopen(path.c_str(), "w");
    if (saved < 0 || !f)
        return "(could not redirect stderr)";
    dup2(fileno(f), 2);
    fn();
    std::fflush(stderr);
    dup2(saved, 2);
    close(saved);
    std::fclose(f);
    std::vector<unsigned char> b = read_bytes(path);
    return std::string(b.begin(), b.end());
}

static void corrupt_png_prints_nothing(mvr_test_state *t)
{
    // a 1x1 grey PNG whose IDAT is not zlib: libpng refuses it
    std::vector<unsigned char> b = {137, 80, 78, 71, 13, 10, 26, 10}, ihdr;
    put_be32(ihdr, 1);
    put_be32(ihdr, 1);
    for (unsigned char v : {8, 0, 0, 0, 0})
        ihdr.push_back(v);
    png_chunk(b, "IHDR", ihdr);
    png_chunk(b, "IDAT", {0x12, 0x34, 0x56, 0x78});
    png_chunk(b, "IEND", {});
    mvr_error e = {};
    mvr_result r = MVR_OK;
    std::string printed = stderr_of([&] {
        mvr_image_data img = {};
        r = mvr_image_decode(b.data(), b.size(), "image/png", 0, &img, &e);
    });
    CHECK_MSG(t, r == MVR_ERROR_INVALID_ASSET, "%d %s", r, e.message);
    CHECK_MSG(t, printed.empty(), "printed to stderr: %s", printed.c_str());
}

int main()
{
    mkdir(MVR_IMAGE_BUDGET_OUT, 0755);
    static const mvr_test_case cases[] = {
        TEST(hostile_headers_refused_before_allocating), TEST(png16_interlaced_charged_at_16_bits),
        TEST(every_channel_counts), TEST(truncated_jpeg_refused), TEST(corrupt_png_prints_nothing),
    };
    return mvr_test_run(cases, sizeof cases / sizeof cases[0]);
}
