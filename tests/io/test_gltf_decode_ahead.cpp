// io_gltf_decode_ahead: images decoded in parallel (core/io/gltf_image_ahead.cpp)
// give the load that decoding one at a time gives. GLBs of several PNG and
// JPEG textures in bufferViews (two images sharing one view, one texture no
// material uses) load with MVR_DECODE_THREADS=1 (nothing ahead), 2 and 4:
//  - the same images in the same order, pixel for pixel, the same info;
//  - with three broken images among them (a JPEG cut short, refused before
//    decoding; a PNG with a corrupt IDAT and a JPEG naming an undefined
//    Huffman table, which fail while decoding, ahead too): the same warnings
//    in the same order (the loader's, not the images'), and with strict the
//    same first error;
//  - under a memory budget just above what the one-thread load needs: the
//    load still succeeds (images held ahead are dropped, then decoded in
//    order), and just below it the same refusal;
//  - the parallel path ran (the loader's debug note says so).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <sys/stat.h>

#include "gltf_gen.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

extern "C" {
#include "scene_internal.h"
}

#ifndef MVR_DECODE_AHEAD_DIR
#error "MVR_DECODE_AHEAD_DIR (where the test writes its files) must be defined"
#endif

namespace {

using gen::builder;

// A quad at (cx, 0) with material m.
std::string quad(builder &b, float cx, int m)
{
    std::vector<float> pos = {cx - 0.4f, -0.4f, 0, cx + 0.4f, -0.4f, 0, cx + 0.4f, 0.4f, 0, cx - 0.4f, 0.4f, 0};
    std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    int a_pos = b.floats(pos, "VEC3");
    int a_uv = b.floats(uv, "VEC2");
    int a_idx = b.indices16({0, 1, 2, 0, 2, 3});
    return "{\"attributes\":{\"POSITION\":" + std::to_string(a_pos) + ",\"TEXCOORD_0\":" + std::to_string(a_uv) +
           "},\"indices\":" + std::to_string(a_idx) + ",\"material\":" + std::to_string(m) + "}";
}

// The offset of the first `tag` (bytes) at or after `from`, or 0.
size_t find(const std::vector<uint8_t> &b, const char *tag, size_t n, size_t from = 0)
{
    for (size_t i = from; i + n <= b.size(); ++i)
        if (std::memcmp(b.data() + i, tag, n) == 0)
            return i;
    return 0;
}

// The images: PNG and JPEG of several sizes; `broken`: image 1 a JPEG cut
// short, image 2 a PNG whose IDAT data is corrupt (its CRC fails), image 4 a
// JPEG whose scan names Huffman table 3, which it does not define.
std::string write_glb(const std::string &name, bool broken)
{
    builder b;
    std::vector<std::vector<uint8_t>> enc = {
        gen::checker_image("png", 64, 200, 30, 30),  gen::checker_image("jpg", 48, 30, 200, 30),
        gen::checker_image("png", 33, 30, 30, 200),  gen::checker_image("jpg", 80, 200, 200, 30),
        gen::checker_image("jpg", 40, 90, 10, 160),  gen::checker_image("png", 24, 10, 160, 90),
    };
    if (broken) {
        enc[1].resize(enc[1].size() / 2);
        size_t idat = find(enc[2], "IDAT", 4);
        enc[2][idat + 6] ^= 0x55;
        size_t sos = find(enc[4], "\xFF\xDA", 2);
        enc[4][sos + 6] = 0x33;   // FF DA, length (2), Ns, Cs1, Td1Ta1
    }
    std::vector<int> views;
    for (size_t i = 0; i < enc.size(); ++i)
        views.push_back(b.view(enc[i].data(), enc[i].size()));
    const char *mime[] = {"image/png", "image/jpeg", "image/png", "image/jpeg", "image/jpeg", "image/png"};
    for (size_t i = 0; i < enc.size(); ++i)
        b.add(b.images, "{\"bufferView\":" + std::to_string(views[i]) + ",\"mimeType\":\"" + mime[i] + "\"}");
    // image 6 names image 0's bytes again: decoded once
    b.add(b.images, "{\"bufferView\":" + std::to_string(views[0]) + ",\"mimeType\":\"image/png\"}");
    std::string prims;
    for (int i = 0; i < 7; ++i) {
        b.add(b.textures, "{\"source\":" + std::to_string(i) + "}");
        // texture 5 (image 5) is in no material: decoded ahead maybe, never used
        int tex = i == 5 ? 6 : i;
        if (i == 6)
            break;
        b.add(b.materials, "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":" + std::to_string(tex) +
                               "}},\"emissiveTexture\":{\"index\":" + std::to_string((i + 2) % 5) + "}}");
        prims += (i ? "," : "") + quad(b, float(i), i);
    }
    b.add(b.meshes, "{\"primitives\":[" + prims + "]}");
    b.add(b.nodes, "{\"mesh\":0}");
    b.add(b.scenes, "{\"nodes\":[0]}");
    return b.write(MVR_DECODE_AHEAD_DIR, name, gen::container::glb);
}

struct outcome {
    mvr_result r = MVR_OK;
    std::string error;
    std::vector<std::string> warnings;
    bool ahead = false;     // the debug note of images decoded ahead
    bool dropped = false;   // and of those dropped for the budget
    mvr_gltf_info info{};
    std::vector<std::vector<uint8_t>> pixels;
    std::vector<uint32_t> sizes;
};

void on_log(mvr_log_level level, mvr_log_id, const char *msg, void *user)
{
    outcome *o = static_cast<outcome *>(user);
    if (level == MVR_LOG_WARNING)
        o->warnings.push_back(msg);
    if (level == MVR_LOG_DEBUG && std::strstr(msg, "decoded ahead"))
        o->ahead = true;
    if (level == MVR_LOG_DEBUG && std::strstr(msg, "dropped"))
        o->dropped = true;
}

outcome load(const std::string &path, const char *threads, bool strict, uint64_t budget = 0)
{
    setenv("MVR_DECODE_THREADS", threads, 1);
    outcome o;
    mvr_gltf_options opt = {};
    opt.logger.fn = on_log;
    opt.logger.level = MVR_LOG_DEBUG;
    opt.logger.user_data = &o;
    opt.strict = strict;
    opt.memory_budget = budget;
    mvr_scene *s = nullptr;
    mvr_error err = {};
    o.r = mvr_gltf_load_file(path.c_str(), &opt, &s, &o.info, &err);
    o.error = o.r == MVR_OK ? "" : err.message;
    if (s) {
        for (uint32_t i = 0; i < s->image_count; ++i) {
            const scene_image &img = s->images[i];
            o.sizes.push_back(img.width);
            o.sizes.push_back(img.height);
            o.pixels.emplace_back(img.rgba, img.rgba + size_t(img.width) * img.height * 4);
        }
        mvr_scene_destroy(s);
    }
    unsetenv("MVR_DECODE_THREADS");
    return o;
}

// b (threads) against a (one thread): everything but the peak and the note.
void same(mvr_test_state *t, const outcome &a, const outcome &b, const char *what)
{
    CHECK_MSG(t, a.r == b.r, "%s: result %d vs %d (%s)", what, int(a.r), int(b.r), b.error.c_str());
    CHECK_MSG(t, a.error == b.error, "%s: error '%s' vs '%s'", what, a.error.c_str(), b.error.c_str());
    CHECK_MSG(t, a.warnings == b.warnings, "%s: %zu vs %zu warnings (first: %s)", what, a.warnings.size(),
              b.warnings.size(), b.warnings.empty() ? "" : b.warnings[0].c_str());
    CHECK_MSG(t, a.info.images_decoded == b.info.images_decoded && a.info.images_missing == b.info.images_missing &&
                     a.info.warnings == b.info.warnings,
              "%s: decoded %u / %u, missing %u / %u", what, a.info.images_decoded, b.info.images_decoded,
              a.info.images_missing, b.info.images_missing);
    CHECK_MSG(t, a.sizes == b.sizes, "%s: image sizes differ", what);
    CHECK_MSG(t, a.pixels == b.pixels, "%s: pixels differ", what);
}

void same_load_on_any_threads(mvr_test_state *t)
{
    std::string path = write_glb("six_images", false);
    outcome one = load(path, "1", false);
    CHECK_MSG(t, one.r == MVR_OK, "%s", one.error.c_str());
    CHECK_MSG(t, !one.ahead, "one thread decoded ahead");
    CHECK_EQ_INT(t, one.info.images_decoded, 5);   // image 5 unused, image 6 is image 0's bytes
    CHECK_EQ_INT(t, one.pixels.size(), 5);
    for (const char *n : {"2", "4"}) {
        outcome par = load(path, n, false);
        CHECK_MSG(t, par.ahead, "%s threads: nothing decoded ahead", n);
        same(t, one, par, n);
        CHECK_MSG(t, par.info.memory_peak >= one.info.memory_peak, "%s threads: peak %llu under one thread's %llu", n,
                  (unsigned long long)par.info.memory_peak, (unsigned long long)one.info.memory_peak);
    }
}

void broken_images_reported_as_before(mvr_test_state *t)
{
    std::string path = write_glb("two_broken", true);
    for (int strict = 0; strict < 2; ++strict) {
        outcome one = load(path, "1", strict != 0);
        outcome par = load(path, "4", strict != 0);
        // material 0 needs images 0 and 2, material 1 images 1 and 3, material 2 images 2 and 4
        if (strict) {
            CHECK_MSG(t, one.r == MVR_ERROR_INVALID_ASSET && one.error.find("images[2]") != std::string::npos,
                      "strict: %s", one.error.c_str());
        } else {
            CHECK_MSG(t, one.r == MVR_OK && one.info.images_missing == 3, "missing %u: %s", one.info.images_missing,
                      one.error.c_str());
            const char *order[] = {"images[2]", "images[1]", "images[4]"};
            CHECK_MSG(t, one.warnings.size() == 3, "%zu warnings", one.warnings.size());
            for (size_t k = 0; k < 3 && k < one.warnings.size(); ++k)
                CHECK_MSG(t, one.warnings[k].find(order[k]) != std::string::npos, "warning %zu: %s", k,
                          one.warnings[k].c_str());
        }
        CHECK_MSG(t, par.ahead, "strict %d: nothing decoded ahead", strict);
        same(t, one, par, strict ? "strict" : "lenient");
    }
}

void budget_as_before(mvr_test_state *t)
{
    std::string path = write_glb("budget", false);
    outcome one = load(path, "1", false);
    CHECK_MSG(t, one.r == MVR_OK, "%s", one.error.c_str());
    uint64_t peak = one.info.memory_peak;
    // just enough for one image at a time: what is held ahead gives way
    outcome fits = load(path, "4", false, peak);
    same(t, one, fits, "budget = the one-thread peak");
    CHECK_MSG(t, fits.ahead && fits.dropped, "budget = the peak: decoded ahead %d, dropped %d", fits.ahead,
              fits.dropped);
    // one byte less: refused, with the same message, either way
    outcome one_short = load(path, "1", false, peak - 1);
    outcome par_short = load(path, "4", false, peak - 1);
    CHECK_MSG(t, one_short.r == MVR_ERROR_OUT_OF_MEMORY, "%s", one_short.error.c_str());
    same(t, one_short, par_short, "budget = the peak - 1");
}

}  // namespace

int main()
{
    mkdir(MVR_DECODE_AHEAD_DIR, 0755);
    static const mvr_test_case cases[] = {
        TEST(same_load_on_any_threads),
        TEST(broken_images_reported_as_before),
        TEST(budget_as_before),
    };
    return mvr_test_run(cases, sizeof cases / sizeof cases[0]);
}
