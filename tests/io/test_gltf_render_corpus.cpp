// io: every file of the glTF test corpus (tests/io/gltf_corpus.cpp) and every
// input the fuzzer once crashed on (tests/fuzz/regressions) goes through the
// loader AND the renderer, so the sanitizer build sees real files reach every
// stage of a frame, empty scenes included.
//
// Asserted, for each feature file: it loads with MVR_OK; three frames render
// with MVR_OK (the default view path into a float target with every light
// casting shadows; the loop path with auto-exposure and tone mapping, lit by
// the neutral studio environment too; an anti-aliased half-float frame with
// per-view transparency order); no pixel
// of any is NaN or infinite; something is drawn (stats) and pixels other
// than the clear colour land in the image. For each file with nothing to
// draw: the same, except that no draw is made (where the scene holds no
// primitive) and the image is the clear colour, exactly (one colour
// everywhere after tone mapping). Broken files and regression inputs load or
// fail cleanly (no scene, a message); those that load render without NaN.
#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "gltf_gen.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

#define W 64
#define H 48
#define VIEWS 2

// exact in half floats too: the aa frame's clear colour reads back unchanged
static const float CLEAR[4] = {0.0625f, 0.0625f, 0.125f, 1.0f};

static std::string base_name(const std::string &p)
{
    return p.substr(p.find_last_of('/') + 1);
}

static gen::corpus &corpus()
{
    static gen::corpus c = [] {
        std::string d = MVR_GLTF_RENDER_CORPUS_DIR;
        mkdir(d.c_str(), 0777);
        return gen::write_corpus(d);
    }();
    return c;
}

static mvr_context *context(mvr_test_state *t)
{
    static mvr_context *ctx = nullptr;
    static bool tried = false;
    if (!tried) {
        tried = true;
        mvr_error err;
        if (mvr_context_create(nullptr, &ctx, &err) != MVR_OK) {
            ctx = nullptr;
            std::printf("  no GL context: %s\n", err.message);
        }
    }
    CHECK_MSG(t, ctx != nullptr, "no GL context");
    return ctx;
}

struct frame {
    bool ok = false;
    uint32_t draws = 0;
    std::vector<float> px; // VIEWS layers of W x H RGBA floats
};

// What one rendered frame holds: non-finite values, pixels that are not the
// clear colour, pixels that differ from the frame's first.
struct census {
    size_t non_finite = 0, not_clear = 0, not_uniform = 0;
};

static census count(const std::vector<float> &px)
{
    census c;
    for (size_t i = 0; i + 3 < px.size(); i += 4) {
        bool finite = true, clear = true, same = true;
        for (int k = 0; k < 4; ++k) {
            finite = finite && std::isfinite(px[i + size_t(k)]);
            clear = clear && px[i + size_t(k)] == CLEAR[k];
            same = same && px[i + size_t(k)] == px[size_t(k)];
        }
        c.non_finite += !finite;
        c.not_clear += !clear;
        c.not_uniform += !same;
    }
    return c;
}

enum class style {
    plain,  // default view path, float target, linear exposure, every light casts shadows
    post,   // loop path, auto-exposure and the PBR Neutral tone mapper (an HDR frame and its post pass),
            // lit by the neutral studio environment too (image-based lighting on every material)
    aa      // default view path, half-float target, anti-aliasing (auto), per-view transparency order
};
static const char *style_name(style st)
{
    return st == style::plain ? "plain" : st == style::post ? "post" : "aa";
}

static frame render(mvr_test_state *t, mvr_context *ctx, mvr_scene *scene, style st, const std::string &what)
{
    frame out;
    mvr_error err;
    mvr_framing_desc fd = {MVR_LAYOUT_STEREO, VIEWS, 0.2, double(W) / H, 0, 0.0, 0.0};
    mvr_view_set *views = nullptr;
    if (mvr_view_set_frame_scene(scene, &fd, &views, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s: framing: %s", what.c_str(), err.message);
        return out;
    }
    mvr_renderer_desc rd = {};
    rd.context = ctx;
    rd.view_path = st == style::post ? MVR_VIEW_PATH_LOOP : MVR_VIEW_PATH_AUTO;
    if (st == style::aa)
        rd.transparency_order = MVR_TRANSPARENCY_ORDER_PER_VIEW;
    mvr_target_desc td = {};
    td.width = W;
    td.height = H;
    td.layers = VIEWS;
    td.color_format = st == style::aa ? MVR_COLOR_FORMAT_RGBA16F : MVR_COLOR_FORMAT_RGBA32F;
    if (st == style::aa)
        td.anti_aliasing = MVR_ANTI_ALIASING_AUTO;
    mvr_render_desc desc = {};
    std::memcpy(desc.clear_color, CLEAR, sizeof CLEAR);
    if (st == style::plain) {
        desc.shadows.mode = MVR_SHADOWS_ALL;
        desc.shadows.map_size = 256;
    } else if (st == style::post) {
        desc.exposure_mode = MVR_EXPOSURE_AUTO;
        desc.tone_map = MVR_TONE_MAP_KHR_PBR_NEUTRAL;
    }
    mvr_environment *env = nullptr;
    if (st == style::post) {
        bool made = mvr_environment_create(nullptr, &env, &err) == MVR_OK;
        CHECK_MSG(t, made, "%s: environment: %s", what.c_str(), err.message);
        desc.environment = env;
    }
    mvr_renderer *r = nullptr;
    mvr_target *target = nullptr;
    bool ok = mvr_renderer_create(&rd, &r, &err) == MVR_OK;
    CHECK_MSG(t, ok, "%s: renderer: %s", what.c_str(), err.message);
    if (ok) {
        ok = mvr_target_create(r, &td, &target) == MVR_OK;
        CHECK_MSG(t, ok, "%s: target: %s", what.c_str(), mvr_renderer_last_error(r));
    }
    if (ok) {
        mvr_result res = mvr_renderer_render(r, scene, views, target, &desc);
        ok = res == MVR_OK;
        CHECK_MSG(t, ok, "%s: render: %s: %s", what.c_str(), mvr_result_name(res), mvr_renderer_last_error(r));
    }
    if (ok) {
        mvr_frame_stats stats;
        mvr_renderer_get_stats(r, &stats);
        out.draws = stats.draws;
        out.px.resize(size_t(W) * H * 4 * VIEWS);
        for (uint32_t k = 0; ok && k < VIEWS; ++k) {
            ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA32F, &out.px[size_t(k) * W * H * 4],
                                         size_t(W) * H * 4 * sizeof(float)) == MVR_OK;
            CHECK_MSG(t, ok, "%s: readback of layer %u: %s", what.c_str(), k, mvr_renderer_last_error(r));
        }
    }
    out.ok = ok;
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_environment_destroy(env);
    mvr_view_set_destroy(views);
    return out;
}

static mvr_scene *load(mvr_test_state *t, const std::string &path)
{
    mvr_scene *s = nullptr;
    mvr_error err;
    mvr_result r = mvr_gltf_load_file(path.c_str(), nullptr, &s, nullptr, &err);
    CHECK_MSG(t, r == MVR_OK && s, "%s: %s: %s", base_name(path).c_str(), mvr_result_name(r), err.message);
    return r == MVR_OK ? s : nullptr;
}

// Renders a loaded file in both styles and checks the frames against what
// the file should give: something drawn, nothing, or no expectation but
// finite pixels (fuzz inputs).
enum expect { nothing = 0, something = 1, anything = -1 };

static void load_and_render(mvr_test_state *t, mvr_context *ctx, const std::string &path, expect e, mvr_scene *scene)
{
    std::string name = base_name(path);
    for (style st : {style::plain, style::post, style::aa}) {
        std::string what = name + " (" + style_name(st) + ")";
        frame f = render(t, ctx, scene, st, what);
        if (!f.ok)
            continue;
        census c = count(f.px);
        std::printf("  %-26s %-6s %3u draws, %5zu of %d pixels not clear, %zu not finite\n", name.c_str(),
                    style_name(st), f.draws, c.not_clear, W * H * VIEWS, c.non_finite);
        CHECK_MSG(t, c.non_finite == 0, "%s: %zu pixels are NaN or infinite", what.c_str(), c.non_finite);
        if (e == something) {
            CHECK_MSG(t, f.draws > 0, "%s: nothing drawn", what.c_str());
            // the plain and aa frames store the clear colour exactly (it is
            // exact in half floats too); the post one maps it to some other
            // colour, the same everywhere
            size_t marked = st == style::post ? c.not_uniform : c.not_clear;
            CHECK_MSG(t, marked > 0, "%s: the image is only background", what.c_str());
        } else if (e == nothing) {
            // no draw at all where the scene holds no primitive (a zero-scale
            // node's primitive is drawn, and covers no pixel)
            mvr_scene_info info;
            mvr_scene_get_info(scene, &info);
            CHECK_MSG(t, info.primitives > 0 || f.draws == 0, "%s: %u draws of no primitive", what.c_str(), f.draws);
            if (st != style::post)
                CHECK_MSG(t, c.not_clear == 0, "%s: %zu pixels are not the clear colour", what.c_str(), c.not_clear);
            CHECK_MSG(t, c.not_uniform == 0, "%s: %zu pixels differ from the first", what.c_str(), c.not_uniform);
        }
    }
}

static void feature_files_load_and_render(mvr_test_state *t)
{
    mvr_context *ctx = context(t);
    if (!ctx)
        return;
    unsigned n = 0;
    for (const std::string &path : corpus().features) {
        if (mvr_scene *s = load(t, path)) {
            load_and_render(t, ctx, path, something, s);
            mvr_scene_destroy(s);
            ++n;
        }
    }
    std::printf("  %u feature files loaded and rendered\n", n);
    CHECK(t, corpus().features.size() >= 12);
}

static void files_with_nothing_to_draw_render_the_clear_colour(mvr_test_state *t)
{
    mvr_context *ctx = context(t);
    if (!ctx)
        return;
    unsigned n = 0;
    for (const std::string &path : corpus().nothing_to_draw) {
        if (mvr_scene *s = load(t, path)) {
            load_and_render(t, ctx, path, nothing, s);
            mvr_scene_destroy(s);
            ++n;
        }
    }
    std::printf("  %u files with nothing to draw loaded and rendered\n", n);
    CHECK(t, corpus().nothing_to_draw.size() >= 6);
}

// The broken files' exact results are io_gltf's to check; here: each fails
// cleanly (no scene, a message) or, where the loader repairs it, renders.
static void broken_files_fail_cleanly_or_render(mvr_test_state *t)
{
    mvr_context *ctx = context(t);
    unsigned refused = 0;
    for (const auto &b : corpus().broken_files) {
        mvr_scene *s = reinterpret_cast<mvr_scene *>(&s);
        mvr_error err;
        mvr_result r = mvr_gltf_load_file(b.path.c_str(), nullptr, &s, nullptr, &err);
        if (r != MVR_OK) {
            CHECK_MSG(t, s == nullptr && err.message[0], "%s: a failed load leaves a scene or no message",
                      base_name(b.path).c_str());
            ++refused;
            continue;
        }
        if (ctx)
            load_and_render(t, ctx, b.path, anything, s);
        mvr_scene_destroy(s);
    }
    std::printf("  %zu broken files: %u refused, the others rendered\n", corpus().broken_files.size(), refused);
}

static void fuzz_regressions_load_and_render(mvr_test_state *t)
{
    std::string dir = MVR_FUZZ_REGRESSIONS_DIR;
    std::vector<std::string> files;
    if (DIR *d = opendir(dir.c_str())) {
        while (dirent *e = readdir(d)) {
            std::string path = dir + "/" + e->d_name;
            struct stat sb;
            if (e->d_name[0] != '.' && stat(path.c_str(), &sb) == 0 && S_ISREG(sb.st_mode))
                files.push_back(path);
        }
        closedir(d);
    }
    std::sort(files.begin(), files.end());
    CHECK_MSG(t, !files.empty(), "no regression inputs in %s", dir.c_str());
    mvr_context *ctx = files.empty() ? nullptr : context(t);
    unsigned loaded = 0;
    for (const std::string &path : files) {
        mvr_scene *s = reinterpret_cast<mvr_scene *>(&s);
        mvr_error err;
        mvr_result r = mvr_gltf_load_file(path.c_str(), nullptr, &s, nullptr, &err);
        std::printf("  %-26s %s%s%s\n", base_name(path).c_str(), mvr_result_name(r), r ? ": " : "", r ? err.message : "");
        if (r != MVR_OK) {
            CHECK_MSG(t, s == nullptr && err.message[0], "%s: a failed load leaves a scene or no message",
                      base_name(path).c_str());
            continue;
        }
        ++loaded;
        if (ctx)
            load_and_render(t, ctx, path, anything, s);
        mvr_scene_destroy(s);
    }
    std::printf("  %zu regression inputs, %u loaded and rendered\n", files.size(), loaded);
}

static void release_context(mvr_test_state *t)
{
    mvr_context *ctx = context(t);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(feature_files_load_and_render), TEST(files_with_nothing_to_draw_render_the_clear_colour),
              TEST(broken_files_fail_cleanly_or_render), TEST(fuzz_regressions_load_and_render), TEST(release_context))
