// io: compressed geometry. tests/data/codecs holds three encodings of one
// model, tests/data/peers/textured.gltf (Blender's Suzanne: 3372 vertices,
// 3936 triangles, UVs, normals, tangents, a base colour and a normal map),
// made by the real tools (scripts/make_codec_assets.sh, README.md there):
//   meshopt_float.glb  gltfpack -cc -noq: EXT_meshopt_compression of the float
//                      data (lossless; gltfpack reorders vertices and triangles)
//   meshopt.glb        gltfpack -cc: KHR_mesh_quantization (14-bit positions,
//                      12-bit UVs, 8-bit normals and tangents) compressed with
//                      EXT_meshopt_compression, normals and tangents through its
//                      OCTAHEDRAL filter; the fallback buffer has no data
//   draco.glb          draco_transcoder: KHR_draco_mesh_compression with Draco's
//                      defaults (11-bit positions, 10-bit UVs, 8-bit normals and
//                      tangents); the accessors have no bufferView
// Each is loaded and rendered from the plain file's camera (two stereo views,
// the sky environment of tests/data/peers) and compared with the plain file's
// render on the interiors of what both drew (pixels whose 5 x 5
// neighbourhood both covered: a silhouette moved by a quantized position
// flips whole pixels, which is coverage, not shading). Bounds (1/255 steps of
// the sRGB8 target), from what was measured on llvmpipe (printed below; two
// 256 x 256 views, ~26900 interior pixels):
//   meshopt_float  worst 1, RMSE 0.05 (measured 0.012, 13 pixels of 131072
//                  differ by one step): the same floats; gltfpack's reordered
//                  triangles meet the rasterizer's interpolation in another
//                  vertex order
//   meshopt        RMSE 1.0 (measured 0.72, worst 95): quantization. Normals
//                  and tangents in 8 bits (octahedral) shade as a fine noise;
//                  14-bit positions and 12-bit UVs move edges (the ears and
//                  brows over the head, the base colour's hard checker edges)
//                  by a fraction of a pixel, which flips a few pixels along
//                  them by the full contrast
//   draco          RMSE 3.0 (measured 2.43, worst 148): Draco's defaults.
//                  Mostly its 11-bit positions (1/2048 of the 2.65-unit box)
//                  moving those edges: the same file with 16-bit positions
//                  measured 1.05, with 16 bits for every attribute 0.48
// and the scene bounds agree within each encoding's position quantization.
// MVR_CODECS_OUT=DIR keeps the renders (DIR/plain_0.png, DIR/draco_1.png, ...).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mvr/mvr_gltf.h"
#include "mvr/mvr_image.h"
#include "mvr_test.h"

namespace {

const uint32_t W = 256, H = 256;

struct loaded {
    mvr_scene *scene = nullptr;
    mvr_gltf_info info = {};
    std::string error;
    ~loaded() { mvr_scene_destroy(scene); }
};

void load(const std::string &path, loaded *out)
{
    mvr_error err;
    std::memset(&err, 0, sizeof err);
    if (mvr_gltf_load_file(path.c_str(), nullptr, &out->scene, &out->info, &err) != MVR_OK)
        out->error = err.message;
}

struct comparison {
    double rmse = 0, mean_abs = 0;
    unsigned worst = 0;
    size_t pixels = 0;       // interior pixels compared
    size_t differing = 0;    // pixels that differ anywhere in the frame (silhouettes included)
};

// MVR_CODECS_OUT=DIR: each render's layers as DIR/NAME_K.png, to look at
void keep(const std::vector<uint8_t> &px, const std::string &name)
{
    const char *dir = std::getenv("MVR_CODECS_OUT");
    if (!dir || px.empty())
        return;
    for (uint32_t l = 0; l < 2; ++l) {
        mvr_image_view v = {W, H, MVR_PIXEL_U8, true, px.data() + size_t(l) * W * H * 4};
        mvr_error err;
        std::string path = std::string(dir) + "/" + name + "_" + std::to_string(l) + ".png";
        if (mvr_image_write(path.c_str(), &v, &err) != MVR_OK)
            std::printf("  (%s: %s)\n", path.c_str(), err.message);
    }
}

bool covered(const uint8_t *p)
{
    return p[0] || p[1] || p[2];
}

comparison compare(const std::vector<uint8_t> &a, const std::vector<uint8_t> &b, uint32_t layers)
{
    comparison c;
    double sum2 = 0, sum_abs = 0;
    const int r = 2;
    for (uint32_t l = 0; l < layers; ++l) {
        const uint8_t *pa = a.data() + size_t(l) * W * H * 4, *pb = b.data() + size_t(l) * W * H * 4;
        for (size_t i = 0; i < size_t(W) * H; ++i)
            c.differing += std::memcmp(pa + i * 4, pb + i * 4, 3) != 0;
        for (uint32_t y = r; y + r < H; ++y)
            for (uint32_t x = r; x + r < W; ++x) {
                bool inside = true;
                for (int dy = -r; dy <= r && inside; ++dy)
                    for (int dx = -r; dx <= r && inside; ++dx) {
                        size_t i = (size_t(y + dy) * W + size_t(x + dx)) * 4;
                        inside = covered(pa + i) && covered(pb + i);
                    }
                if (!inside)
                    continue;
                size_t i = (size_t(y) * W + x) * 4;
                for (int k = 0; k < 3; ++k) {
                    int d = int(pa[i + k]) - int(pb[i + k]);
                    sum2 += double(d) * d;
                    sum_abs += std::abs(d);
                    c.worst = std::max(c.worst, unsigned(std::abs(d)));
                }
                ++c.pixels;
            }
    }
    double n = 3.0 * double(c.pixels ? c.pixels : 1);
    c.rmse = std::sqrt(sum2 / n);
    c.mean_abs = sum_abs / n;
    return c;
}

void compressed_versions_render_like_the_plain_file(mvr_test_state *t)
{
    const std::string peers = MVR_PEERS_DIR, codecs = MVR_CODECS_DIR;
    loaded plain;
    load(peers + "/textured.gltf", &plain);
    CHECK_MSG(t, plain.scene, "textured.gltf: %s", plain.error.c_str());
    if (!plain.scene)
        return;
    struct encoding {
        const char *file;
        double rmse_bound;
        unsigned worst_bound;   // 0: not bounded
        double bounds_tolerance;
    };
    // positions: gltfpack's 14 bits and Draco's 11 bits over the model's 2.65-unit extent
    const encoding encodings[] = {
        {"meshopt_float.glb", 0.05, 1, 1e-6},
        {"meshopt.glb", 1.0, 0, 2.65 / 16383},
        {"draco.glb", 3.0, 0, 2.65 / 2047},
    };

    mvr_context *ctx = nullptr;
    mvr_context_desc cd;
    std::memset(&cd, 0, sizeof cd);
    mvr_error err;
    if (mvr_context_create(&cd, &ctx, &err) != MVR_OK) {
        if (mvr_test_in_ci())
            CHECK_MSG(t, false, "context: %s", err.message);
        else
            SKIP(t, "no GL context: %s", err.message);
        return;
    }
    mvr_image_data sky;
    std::memset(&sky, 0, sizeof sky);
    mvr_environment *env = nullptr;
    mvr_view_set *views = nullptr;
    mvr_renderer *renderer = nullptr;
    mvr_target *target = nullptr;
    bool ok = mvr_image_read((peers + "/sky.hdr").c_str(), MVR_PIXEL_F32, &sky, &err) == MVR_OK;
    CHECK_MSG(t, ok, "sky.hdr: %s", err.message);
    if (ok) {
        mvr_environment_desc ed;
        std::memset(&ed, 0, sizeof ed);
        ed.source = MVR_ENVIRONMENT_PIXELS;
        ed.pixels = static_cast<const float *>(sky.pixels);
        ed.width = sky.width;
        ed.height = sky.height;
        ok = mvr_environment_create(&ed, &env, &err) == MVR_OK;
        CHECK_MSG(t, ok, "environment: %s", err.message);
    }
    if (ok) {
        // every file renders from the plain file's camera (draco_transcoder drops cameras)
        ok = mvr_view_set_from_camera(plain.scene, mvr_scene_camera_node(plain.scene, 0), 2, 0.2, &views, &err) ==
             MVR_OK;
        CHECK_MSG(t, ok, "views: %s", err.message);
    }
    if (ok) {
        mvr_renderer_desc rd;
        std::memset(&rd, 0, sizeof rd);
        rd.context = ctx;
        mvr_target_desc td;
        std::memset(&td, 0, sizeof td);
        td.width = W;
        td.height = H;
        td.layers = 2;
        ok = mvr_renderer_create(&rd, &renderer, &err) == MVR_OK && mvr_target_create(renderer, &td, &target) == MVR_OK;
        CHECK_MSG(t, ok, "renderer: %s", renderer ? mvr_renderer_last_error(renderer) : err.message);
    }
    auto render = [&](mvr_scene *scene, const char *what) {
        std::vector<uint8_t> px;
        mvr_render_desc desc;
        std::memset(&desc, 0, sizeof desc);
        desc.clear_color[3] = 1.0f;
        desc.exposure = 1.0f;
        desc.environment = env;
        bool r = mvr_renderer_render(renderer, scene, views, target, &desc) == MVR_OK;
        CHECK_MSG(t, r, "%s: render: %s", what, mvr_renderer_last_error(renderer));
        if (!r)
            return px;
        px.resize(size_t(W) * H * 4 * 2);
        for (uint32_t l = 0; l < 2; ++l) {
            bool read = mvr_renderer_read_layer(renderer, target, l, MVR_READBACK_RGBA8, &px[size_t(l) * W * H * 4],
                                                size_t(W) * H * 4) == MVR_OK;
            CHECK_MSG(t, read, "%s: readback: %s", what, mvr_renderer_last_error(renderer));
        }
        return px;
    };
    std::vector<uint8_t> reference = ok ? render(plain.scene, "textured.gltf") : std::vector<uint8_t>();
    keep(reference, "plain");
    mvr_scene_info pi;
    mvr_scene_get_info(plain.scene, &pi);
    for (const encoding &e : encodings) {
        if (reference.empty())
            break;
        loaded c;
        load(codecs + "/" + e.file, &c);
        CHECK_MSG(t, c.scene, "%s: %s", e.file, c.error.c_str());
        if (!c.scene)
            continue;
        CHECK_MSG(t, c.info.warnings == 0 && c.info.images_decoded == 2, "%s: %u warnings, %u images", e.file,
                  c.info.warnings, c.info.images_decoded);
        mvr_scene_info ci;
        mvr_scene_get_info(c.scene, &ci);
        double worst_bound = 0;
        for (int k = 0; k < 3; ++k)
            worst_bound = std::max({worst_bound, std::fabs(ci.bounds_min[k] - pi.bounds_min[k]),
                                    std::fabs(ci.bounds_max[k] - pi.bounds_max[k])});
        CHECK_MSG(t, ci.primitives == 1 && worst_bound <= e.bounds_tolerance,
                  "%s: %u primitives, bounds off by %.3g (tolerance %.3g)", e.file, ci.primitives, worst_bound,
                  e.bounds_tolerance);
        std::vector<uint8_t> px = render(c.scene, e.file);
        if (px.empty())
            continue;
        keep(px, std::string(e.file).substr(0, std::strlen(e.file) - 4));
        comparison m = compare(reference, px, 2);
        std::printf("  %-18s RMSE %.3f, mean |d| %.3f, worst %u (1/255) over %zu interior pixels; %zu pixels differ "
                    "(of %u); bounds off by %.2g; peak %.1f MiB\n",
                    e.file, m.rmse, m.mean_abs, m.worst, m.pixels, m.differing, 2 * W * H, worst_bound,
                    double(c.info.memory_peak) / (1 << 20));
        CHECK_MSG(t, m.pixels > 20000, "%s: only %zu interior pixels", e.file, m.pixels);
        CHECK_MSG(t, m.rmse <= e.rmse_bound, "%s: RMSE %.3f over the bound %.2f", e.file, m.rmse, e.rmse_bound);
        CHECK_MSG(t, e.worst_bound == 0 || m.worst <= e.worst_bound, "%s: worst %u over %u", e.file, m.worst,
                  e.worst_bound);
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(renderer);
    mvr_view_set_destroy(views);
    mvr_environment_destroy(env);
    mvr_image_free(&sky);
    mvr_context_destroy(ctx);
}

}  // namespace

MVR_TEST_MAIN(TEST(compressed_versions_render_like_the_plain_file))
