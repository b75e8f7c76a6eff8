// io: mvr against a peer. tests/data/peers holds this project's own test
// files (spheres of every roughness and metalness, Blender's export of a
// textured, normal-mapped model), two environments (a uniform radiance of 1
// and a procedural sky), and what the Khronos glTF Sample Renderer made of
// them (scripts/peers/render_khronos.sh, in headless Chromium on the same
// llvmpipe; manifest.json records how). Each reference is re-rendered here
// through the library as `mvr render` would (the file's camera, the
// environment as an equirectangular image, exposure 1, no tone mapping),
// with the rotation the manifest names, and compared on the interiors of
// what both drew (pixels whose 5 x 5 neighbourhood both renderers covered:
// silhouettes are anti-aliasing's business, not lighting's).
//
// Encodings: the Khronos renderer writes round(255 * pow(c, 1/2.2)), not the
// sRGB curve; mvr's linear float output is encoded the same way here, so the
// comparison is of the same function of radiance, and differences are in
// 1/255 steps of that encoding.
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mvr/mvr_gltf.h"
#include "mvr/mvr_image.h"
#include "mvr_test.h"

namespace {

struct comparison {
    double rmse = 0;      // in 1/255 steps
    double mean_abs = 0;  // the signed difference's magnitude: a bias shows here
    double mean_signed = 0;
    unsigned worst = 0;
    size_t pixels = 0;
};

// RGB bytes (rows top first) of mvr's render of one manifest entry.
std::vector<uint8_t> render_mvr(mvr_test_state *t, mvr_context *ctx, const nlohmann::json &entry,
                                const std::string &dir, uint32_t disable_features = 0, bool anisotropic = false)
{
    std::vector<uint8_t> out;
    std::string asset = dir + "/" + entry.at("asset").get<std::string>();
    std::string env_path = dir + "/" + entry.at("environment").get<std::string>();
    uint32_t w = entry.at("width").get<uint32_t>(), h = entry.at("height").get<uint32_t>();
    mvr_scene *scene = nullptr;
    mvr_error err;
    if (mvr_gltf_load_file(asset.c_str(), nullptr, &scene, nullptr, &err) != MVR_OK) {
        CHECK_MSG(t, false, "%s: %s", asset.c_str(), err.message);
        return out;
    }
    mvr_image_data env_image;
    std::memset(&env_image, 0, sizeof env_image);
    mvr_environment *env = nullptr;
    mvr_view_set *views = nullptr;
    mvr_renderer *renderer = nullptr;
    mvr_target *target = nullptr;
    bool ok = mvr_image_read(env_path.c_str(), MVR_PIXEL_F32, &env_image, &err) == MVR_OK;
    CHECK_MSG(t, ok, "%s: %s", env_path.c_str(), err.message);
    if (ok) {
        mvr_environment_desc ed;
        std::memset(&ed, 0, sizeof ed);
        ed.source = MVR_ENVIRONMENT_PIXELS;
        ed.pixels = static_cast<const float *>(env_image.pixels);
        ed.width = env_image.width;
        ed.height = env_image.height;
        ed.rotation = entry.at("env_rotation_mvr_deg").get<float>();
        ok = mvr_environment_create(&ed, &env, &err) == MVR_OK;
        CHECK_MSG(t, ok, "environment: %s", err.message);
    }
    if (ok) {
        mvr_node_id camera = mvr_scene_camera_node(scene, entry.at("camera_index").get<uint32_t>());
        ok = mvr_view_set_from_camera(scene, camera, 1, 0.0, &views, &err) == MVR_OK;
        CHECK_MSG(t, ok, "camera: %s", err.message);
    }
    if (ok) {
        mvr_renderer_desc rd;
        std::memset(&rd, 0, sizeof rd);
        rd.context = ctx;
        rd.overrides.disable_features = disable_features;
        rd.overrides.anisotropic = anisotropic ? MVR_OVERRIDE_ON : MVR_OVERRIDE_NONE;
        ok = mvr_renderer_create(&rd, &renderer, &err) == MVR_OK;
        CHECK_MSG(t, ok, "renderer: %s", err.message);
    }
    if (ok) {
        mvr_target_desc td;
        std::memset(&td, 0, sizeof td);
        td.width = w;
        td.height = h;
        td.color_format = MVR_COLOR_FORMAT_RGBA32F;
        td.anti_aliasing = MVR_ANTI_ALIASING_NONE; /* the comparisons' thresholds were set without AA */
        mvr_render_desc desc;
        std::memset(&desc, 0, sizeof desc);
        desc.clear_color[3] = 1.0f;
        desc.exposure = 1.0f;
        desc.environment = env;
        ok = mvr_target_create(renderer, &td, &target) == MVR_OK &&
             mvr_renderer_render(renderer, scene, views, target, &desc) == MVR_OK;
        CHECK_MSG(t, ok, "render: %s", mvr_renderer_last_error(renderer));
    }
    if (ok) {
        std::vector<float> px(static_cast<size_t>(w) * h * 4);
        ok = mvr_renderer_read_layer(renderer, target, 0, MVR_READBACK_RGBA32F, px.data(), px.size() * sizeof(float)) ==
             MVR_OK;
        CHECK_MSG(t, ok, "read back: %s", mvr_renderer_last_error(renderer));
        if (ok) {
            out.resize(static_cast<size_t>(w) * h * 3);
            for (uint32_t y = 0; y < h; ++y)      // GL rows are bottom-up
                for (uint32_t x = 0; x < w; ++x)
                    for (int c = 0; c < 3; ++c) {
                        double v = px[(static_cast<size_t>(h - 1 - y) * w + x) * 4 + c];
                        v = v < 0 ? 0 : v > 1 ? 1 : v;
                        out[(static_cast<size_t>(y) * w + x) * 3 + c] =
                            static_cast<uint8_t>(std::lround(255.0 * std::pow(v, 1.0 / 2.2)));
                    }
        }
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(renderer);
    mvr_view_set_destroy(views);
    mvr_environment_destroy(env);
    mvr_image_free(&env_image);
    mvr_scene_destroy(scene);
    return out;
}

// The mesh feature bit mvr_program_feature_name calls `name` (0: none).
uint32_t feature_bit(const char *name)
{
    for (uint32_t b = 1; b; b <<= 1) {
        const char *n = mvr_program_feature_name(b);
        if (n && std::strcmp(n, name) == 0)
            return b;
    }
    return 0;
}

bool covered(const uint8_t *p)
{
    return p[0] || p[1] || p[2];
}

comparison compare(const std::vector<uint8_t> &a, const std::vector<uint8_t> &b, uint32_t w, uint32_t h)
{
    comparison c;
    double sum2 = 0, sum = 0, sum_abs = 0;
    const int r = 2;
    for (uint32_t y = r; y + r < h; ++y)
        for (uint32_t x = r; x + r < w; ++x) {
            bool inside = true;
            for (int dy = -r; dy <= r && inside; ++dy)
                for (int dx = -r; dx <= r && inside; ++dx) {
                    size_t i = (static_cast<size_t>(y + dy) * w + (x + dx)) * 3;
                    inside = covered(&a[i]) && covered(&b[i]);
                }
            if (!inside)
                continue;
            size_t i = (static_cast<size_t>(y) * w + x) * 3;
            for (int k = 0; k < 3; ++k) {
                int d = static_cast<int>(a[i + k]) - static_cast<int>(b[i + k]);
                sum2 += static_cast<double>(d) * d;
                sum += d;
                sum_abs += std::abs(d);
                c.worst = std::max(c.worst, static_cast<unsigned>(std::abs(d)));
            }
            ++c.pixels;
        }
    double n = 3.0 * static_cast<double>(c.pixels ? c.pixels : 1);
    c.rmse = std::sqrt(sum2 / n);
    c.mean_signed = sum / n;
    c.mean_abs = sum_abs / n;
    return c;
}

void mvr_agrees_with_the_khronos_sample_renderer(mvr_test_state *t)
{
    const std::string dir = MVR_PEERS_DIR;
    std::ifstream in(dir + "/manifest.json");
    CHECK_MSG(t, in.good(), "%s/manifest.json missing", dir.c_str());
    if (!in.good())
        return;
    nlohmann::json manifest = nlohmann::json::parse(in);
    mvr_context *ctx = nullptr;
    mvr_context_desc cd;
    std::memset(&cd, 0, sizeof cd);
    mvr_error err;
    if (mvr_context_create(&cd, &ctx, &err) != MVR_OK) {
        CHECK_MSG(t, false, "context: %s", err.message);
        return;
    }
    // The stated bounds (RMSE in 1/255 steps of the gamma-2.2 encoding, on
    // interiors), from what was measured on llvmpipe (printed below):
    // - uniform environment: the target, 2/255. Under radiance 1 the
    //   renderers differ only in their DFG tables and multiple-scattering
    //   terms (diffuse is exact in both).
    // - the sky: 3.5/255. A sun of radiance 50 in a 4-degree disc: the
    //   prefiltered maps differ (Khronos: 256-texel cube, 1024 GGX samples,
    //   a Lambertian irradiance cube; mvr's defaults: 128-texel cube, 256
    //   samples with filtered importance sampling, spherical harmonics).
    //   Measured 2.64 (spheres) and 1.79 (textured); with 64 samples the
    //   spheres were at 4.35, with a 256-texel cube and 1024 samples 1.77.
    // - coated.gltf (KHR_materials_clearcoat, _ior, _specular factors): 0.06
    //   under the uniform environment, 2.07 under the sky; spec_gloss.gltf
    //   (KHR_materials_pbrSpecularGlossiness) 0.06 and 2.62.
    // - glass.gltf (KHR_materials_transmission, _volume, _dispersion): 3.0
    //   and 4.0. The mean difference is small (0.18 / 255 uniform) but the
    //   refracted bars have sharp edges, and there a sample one texel over
    //   changes a pixel entirely: the Khronos renderer refracts into a
    //   1024-wide copy of the scene, mvr into the view's own 256-wide colour
    //   (same footprint per roughness). Measured 2.50 and 3.18.
    // - films.gltf (KHR_materials_iridescence, _anisotropy, on a sphere with
    //   tangents): 0.01 and 2.96 under the general bounds.
    // - sheen.gltf (KHR_materials_sheen, Blender's export: factors, and a
    //   sheen color texture): 12 and 10, measured 11.02 and 9.12, mvr darker
    //   (mean -8.9 and -4.9). Two departures of the Sample Renderer 1.1.0,
    //   both measured by putting them into mvr's table (not committed):
    //   (a) it never uploads its sheen albedo table (loadEnvironment marks
    //   the texture initialized), so it samples an incomplete texture, 0: no
    //   albedo scaling of the base under the sheen, which the extension
    //   asks for and mvr does; (b) its Charlie LUT is not the integral of
    //   its own sheen lobe (D of alpha = roughness where its lights use
    //   roughness^2, and Charlie-sampled half vectors weighted as if
    //   uniform): 30-50% above it. With E = 0 and its estimator in mvr's
    //   table, the RMSE is 0.29 (uniform) and 7.06 (sky: its Charlie chain of
    //   64 samples and no filtered importance sampling shows the sun as a
    //   spot and the horizon as a line on the sphere).
    // - principled.gltf (Blender's export of Principled BSDF materials:
    //   clearcoat and clearcoat roughness textures, specular colour, ior,
    //   emissive strength with an emission texture, transmission and volume
    //   in front of a textured backdrop): 0.24 and 1.82 under the general
    //   bounds (its backdrop is smooth, so the refraction has no sharp edges).
    unsigned compared = 0;
    for (const auto &entry : manifest.at("images")) {
        std::string file = entry.at("file").get<std::string>();
        std::string env = entry.at("environment").get<std::string>();
        uint32_t w = entry.at("width").get<uint32_t>(), h = entry.at("height").get<uint32_t>();
        CHECK_MSG(t, entry.at("encoding").get<std::string>() == "gamma2.2" &&
                         entry.at("tone_mapping").get<std::string>() == "none" && !entry.at("env_mirror").get<bool>(),
                  "%s: settings this test does not reproduce", file.c_str());
        mvr_image_data ref;
        std::memset(&ref, 0, sizeof ref);
        if (mvr_image_read((dir + "/" + file).c_str(), MVR_PIXEL_U8, &ref, &err) != MVR_OK) {
            CHECK_MSG(t, false, "%s: %s", file.c_str(), err.message);
            continue;
        }
        std::vector<uint8_t> theirs(static_cast<size_t>(w) * h * 3);
        bool size_ok = ref.width == w && ref.height == h;
        CHECK_MSG(t, size_ok, "%s is %ux%u, the manifest says %ux%u", file.c_str(), ref.width, ref.height, w, h);
        for (size_t i = 0; size_ok && i < static_cast<size_t>(w) * h; ++i)
            for (int c = 0; c < 3; ++c)
                theirs[i * 3 + c] = static_cast<const uint8_t *>(ref.pixels)[i * 4 + c];
        mvr_image_free(&ref);
        std::vector<uint8_t> ours = size_ok ? render_mvr(t, ctx, entry, dir) : std::vector<uint8_t>();
        if (ours.empty())
            continue;
        comparison c = compare(ours, theirs, w, h);
        // MVR_PEERS_OUT=DIR: mvr's render of each reference, as mvr_<reference>.png (to look at)
        if (const char *out_dir = std::getenv("MVR_PEERS_OUT")) {
            std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4, 255);
            for (size_t i = 0; i < static_cast<size_t>(w) * h; ++i)
                for (int k = 0; k < 3; ++k)
                    rgba[i * 4 + k] = ours[i * 3 + k];
            mvr_image_view view = {w, h, MVR_PIXEL_U8, false, rgba.data()};
            std::string path = std::string(out_dir) + "/mvr_" + file;
            CHECK_MSG(t, mvr_image_write(path.c_str(), &view, &err) == MVR_OK, "%s: %s", path.c_str(), err.message);
        }
        std::string asset = entry.at("asset").get<std::string>();
        double bound = env == "uniform.hdr" ? 2.0 : 3.5;
        if (asset == "glass.gltf")
            bound = env == "uniform.hdr" ? 3.0 : 4.0;
        else if (asset == "sheen.gltf")
            bound = env == "uniform.hdr" ? 12.0 : 10.0;
        std::printf("  %-28s RMSE %.2f, mean |d| %.2f, mean d %+.2f, worst %u (1/255) over %zu pixels (bound %.1f)\n",
                    file.c_str(), c.rmse, c.mean_abs, c.mean_signed, c.worst, c.pixels, bound);
        CHECK_MSG(t, c.pixels > 5000, "%s: only %zu interior pixels", file.c_str(), c.pixels);
        CHECK_MSG(t, c.rmse <= bound, "%s: RMSE %.2f / 255 over the bound %.1f", file.c_str(), c.rmse, bound);
        if (asset == "textured.gltf") {
            // Blender's normal-mapped export. The Khronos renderer samples its
            // mipmapped textures with 16x anisotropic filtering; mvr does with
            // overrides.anisotropic on (not its default: docs/peers.md), and
            // then agrees better on creases and rims (measured uniform / sky:
            // 0.64 / 1.57 with it, 1.30 / 1.79 trilinear)
            std::vector<uint8_t> af = render_mvr(t, ctx, entry, dir, 0, true);
            comparison ca = af.empty() ? comparison{} : compare(af, theirs, w, h);
            std::printf("  %-28s anisotropic: RMSE %.2f, mean d %+.2f\n", "", ca.rmse, ca.mean_signed);
            const double tight = env == "uniform.hdr" ? 1.0 : 1.7;
            CHECK_MSG(t, !af.empty() && ca.rmse <= tight, "%s, anisotropic: RMSE %.2f / 255 over %.1f", file.c_str(),
                      ca.rmse, tight);
            // the same file without TANGENT: glTF asks for MikkTSpace tangents,
            // which the Khronos renderer computes and mvr's loader generates
            // (measured 1.43 / 1.86; 2.00 / 2.32 with the per-pixel frame from
            // screen-space derivatives mvr used before; 1.30 / 1.79 with the
            // file's own tangents)
            nlohmann::json bare_entry = entry;
            bare_entry["asset"] = "textured_no_tangents.gltf";
            std::vector<uint8_t> bare = render_mvr(t, ctx, bare_entry, dir);
            comparison nt = bare.empty() ? comparison{} : compare(bare, theirs, w, h);
            std::printf("  %-28s without TANGENT: RMSE %.2f, mean d %+.2f\n", "", nt.rmse, nt.mean_signed);
            const double nt_bound = env == "uniform.hdr" ? 1.6 : 2.0;
            CHECK_MSG(t, !bare.empty() && nt.rmse <= nt_bound, "%s without TANGENT: RMSE %.2f / 255 over %.1f",
                      file.c_str(), nt.rmse, nt_bound);
        }
        if (asset == "sheen.gltf") {
            // the sheen brings mvr nearer the reference than no sheen does
            // (measured 40.56 and 26.83 without it: 0.27 and 0.34 of that with it)
            std::vector<uint8_t> bare = render_mvr(t, ctx, entry, dir, feature_bit("SHEEN"));
            comparison off = compare(bare, theirs, w, h);
            std::printf("  %-28s without the sheen: RMSE %.2f, mean d %+.2f\n", "", off.rmse, off.mean_signed);
            CHECK_MSG(t, c.rmse < 0.5 * off.rmse, "%s: RMSE %.2f with the sheen, %.2f without", file.c_str(), c.rmse,
                      off.rmse);
        }
        if (asset == "principled.gltf") {
            // each extension that can be turned off brings mvr nearer the
            // reference (measured without: clearcoat 3.26 / 2.74, specular
            // and ior 5.83 / 4.93, transmission and volume 67.1 / 50.9)
            for (const char *name : {"CLEARCOAT", "SPECULAR", "TRANSMISSION"}) {
                std::vector<uint8_t> bare = render_mvr(t, ctx, entry, dir, feature_bit(name));
                comparison off = compare(bare, theirs, w, h);
                std::printf("  %-28s without %s: RMSE %.2f, mean d %+.2f\n", "", name, off.rmse, off.mean_signed);
                CHECK_MSG(t, c.rmse < off.rmse, "%s: RMSE %.2f with %s, %.2f without", file.c_str(), c.rmse, name,
                          off.rmse);
            }
        }
        ++compared;
    }
    CHECK_MSG(t, compared >= 4, "%u references compared", compared);
    mvr_context_destroy(ctx);
}

}  // namespace

MVR_TEST_MAIN(TEST(mvr_agrees_with_the_khronos_sample_renderer))
