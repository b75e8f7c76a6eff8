// io: the glTF loader on a corpus the test writes itself. Every feature file
// loads and renders, with byte-identical multiview and loop paths; every
// broken file fails with the expected result and a message naming the object.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <sys/stat.h>

#include "gltf_gen.hpp"
#include "gltf_render.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

extern "C" {
#include "scene_internal.h"
}

#define W 64
#define H 48

static std::string corpus_dir()
{
    std::string d = MVR_GLTF_CORPUS_DIR;
    mkdir(d.c_str(), 0777);
    return d;
}

static gen::corpus &corpus()
{
    static gen::corpus c = gen::write_corpus(corpus_dir());
    return c;
}

static std::string base_name(const std::string &p)
{
    return p.substr(p.find_last_of('/') + 1);
}

struct warn_count {
    int warnings = 0;
    std::string last;
};

static void count_warnings(mvr_log_level level, mvr_log_id, const char *message, void *user)
{
    auto *w = static_cast<warn_count *>(user);
    if (level == MVR_LOG_WARNING) {
        w->warnings++;
        w->last = message;
    }
}

static mvr_scene *load(mvr_test_state *t, const std::string &path, mvr_gltf_info *info, warn_count *warns = nullptr)
{
    mvr_gltf_options o = {};
    if (warns) {
        o.logger.fn = count_warnings;
        o.logger.user_data = warns;
    }
    mvr_scene *s = nullptr;
    mvr_error err;
    mvr_result r = mvr_gltf_load_file(path.c_str(), &o, &s, info, &err);
    CHECK_MSG(t, r == MVR_OK, "%s: %s", base_name(path).c_str(), err.message);
    return s;
}

static size_t non_background(const std::vector<uint8_t> &px)
{
    size_t n = 0;
    for (size_t i = 0; i + 3 < px.size(); i += 4)
        n += px[i] != px[0] || px[i + 1] != px[1] || px[i + 2] != px[2];
    return n;
}

static void feature_files_render_alike_on_both_paths(mvr_test_state *t)
{
    mvr_context *ctx = nullptr;
    mvr_error err;
    if (mvr_context_create(nullptr, &ctx, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s", err.message);
        return;
    }
    bool multiview = mvr_context_caps(ctx)->ext.ovr_multiview2;
    for (const std::string &path : corpus().features) {
        std::string name = base_name(path);
        mvr_gltf_info info = {};
        mvr_scene *s = load(t, path, &info);
        if (!s)
            continue;
        std::vector<uint8_t> mv =
            gltf_render::two_layers(t, ctx, s, multiview ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP, name.c_str());
        std::vector<uint8_t> loop = gltf_render::two_layers(t, ctx, s, MVR_VIEW_PATH_LOOP, name.c_str());
        CHECK_MSG(t, !mv.empty() && mv == loop, "%s: multiview and loop layers differ", name.c_str());
        size_t drawn = non_background(mv);
        printf("  %-24s %zu of %d pixels drawn, %u warnings\n", name.c_str(), drawn,
               gltf_render::frame_width * gltf_render::frame_height * 2, info.warnings);
        CHECK_MSG(t, drawn > 50, "%s: almost nothing drawn (%zu pixels)", name.c_str(), drawn);
        mvr_scene_destroy(s);
    }
    CHECK(t, corpus().features.size() >= 10);
    mvr_context_destroy(ctx);
}

static const scene_primitive *prim(const mvr_scene *s, uint32_t i)
{
    return i < s->primitive_count ? &s->primitives[i] : nullptr;
}

static void features_convert_as_specified(mvr_test_state *t)
{
    const std::string d = corpus_dir();
    mvr_gltf_info info = {};
    mvr_scene_info si;
    if (mvr_scene *s = load(t, d + "/textured_external.gltf", &info)) {
        mvr_scene_get_info(s, &si);
        CHECK_EQ_INT(t, si.images, 2); /* PNG and JPEG decoded */
        CHECK_EQ_INT(t, s->images[0].width, 32);
        CHECK_EQ_INT(t, s->materials[0].desc.base_color.sampler.mag_filter, MVR_FILTER_NEAREST);
        CHECK_EQ_INT(t, s->materials[0].desc.base_color.sampler.wrap_s, MVR_WRAP_CLAMP_TO_EDGE);
        CHECK_EQ_INT(t, si.lights, 1);
        mvr_scene_destroy(s);
    }
    warn_count ct_warns;
    if (mvr_scene *s = load(t, d + "/component_types.gltf", &info, &ct_warns)) {
        mvr_scene_get_info(s, &si); /* int16 normalized * node scale 0.8 */
        CHECK_MSG(t, std::fabs(si.bounds_max[0] - 0.8) < 1e-6 && std::fabs(si.bounds_min[1] + 0.8) < 1e-6,
                  "bounds %g %g", si.bounds_max[0], si.bounds_min[1]);
        const scene_primitive *p = prim(s, 0);
        CHECK(t, p && p->colors && p->normals && p->uv0);
        if (p) {
            CHECK(t, p->colors[0] == 1.0f && p->colors[3] == 1.0f); /* VEC3 color, alpha 1 */
            CHECK(t, std::fabs(p->normals[2] - 1.0f) < 1e-6f);    /* int8 127 -> 1 */
            CHECK(t, std::fabs(p->uv0[1] - 1.0f) < 1e-6f);
        }
        /* the quantization extension is declared: the one warning is the
         * scene's, for the node's non-unit rotation */
        CHECK_EQ_INT(t, info.warnings, 1);
        CHECK_MSG(t, ct_warns.warnings == 1 && ct_warns.last.find("unit quaternion") != std::string::npos, "%s",
                  ct_warns.last.c_str());
        mvr_scene_destroy(s);
    }
    if (mvr_scene *s = load(t, d + "/sparse.gltf", &info)) {
        mvr_scene_get_info(s, &si);
        CHECK_MSG(t, std::fabs(si.bounds_max[1] - 1.5) < 1e-6, "sparse substitution: max y %g", si.bounds_max[1]);
        CHECK_MSG(t, std::fabs(si.bounds_min[0] + 1.0) < 1e-6, "sparse without bufferView: min x %g", si.bounds_min[0]);
        mvr_scene_destroy(s);
    }
    if (mvr_scene *s = load(t, d + "/modes.gltf", &info)) {
        /* strip 4 -> 2 triangles, fan 5 -> 3, lines 4, loop 4 -> 4 segments,
         * line strip 4 -> 3, points 4, non-indexed triangles 3 */
        const uint32_t expect[7] = {6, 9, 4, 8, 6, 4, 3};
        const mvr_primitive_mode modes[7] = {MVR_PRIMITIVE_TRIANGLES, MVR_PRIMITIVE_TRIANGLES, MVR_PRIMITIVE_LINES,
                                             MVR_PRIMITIVE_LINES,     MVR_PRIMITIVE_LINES,     MVR_PRIMITIVE_POINTS,
                                             MVR_PRIMITIVE_TRIANGLES};
        CHECK_EQ_INT(t, s->primitive_count, 7);
        for (uint32_t k = 0; k < 7 && k < s->primitive_count; ++k) {
            CHECK_MSG(t, s->primitives[k].index_count == expect[k], "mode %u: %u indices", k, s->primitives[k].index_count);
            CHECK_EQ_INT(t, s->primitives[k].mode, modes[k]);
        }
        /* the strip's second triangle keeps the winding: (2, 1, 3) */
        const uint32_t *si2 = s->primitives[0].indices;
        CHECK(t, si2[3] == 2 && si2[4] == 1 && si2[5] == 3);
        mvr_scene_destroy(s);
    }
    if (mvr_scene *s = load(t, d + "/materials.gltf", &info)) {
        CHECK_EQ_INT(t, s->material_count, 9);
        const mvr_material_desc *m = &s->materials[0].desc;
        CHECK(t, m->metallic_roughness.image.id != 0 && m->roughness_factor == 0.5f);
        CHECK(t, s->materials[1].desc.normal_scale == 0.5f);
        CHECK(t, s->materials[2].desc.occlusion_strength == 0.5f && s->materials[2].desc.occlusion.texcoord == 1);
        CHECK(t, s->materials[3].desc.emissive_strength == 3.0f);
        CHECK(t, s->materials[4].desc.alpha_mode == MVR_ALPHA_MASK && std::fabs(s->materials[4].desc.alpha_cutoff - 0.3f) < 1e-6f);
        CHECK(t, s->materials[5].desc.alpha_mode == MVR_ALPHA_BLEND);
        CHECK(t, s->materials[6].desc.double_sided);
        CHECK(t, s->materials[7].desc.unlit);
        const mvr_texture_transform *tt = &s->materials[8].desc.base_color.transform;
        CHECK(t, tt->enabled && tt->offset[0] == 0.5f && std::fabs(tt->rotation - 0.4f) < 1e-6f && tt->scale[1] == 2.0f);
        mvr_scene_destroy(s);
    }
    if (mvr_scene *s = load(t, d + "/scene_graph.glb", &info)) {
        CHECK_EQ_INT(t, info.camera_nodes, 2);
        CHECK_EQ_INT(t, s->light_count, 3);
        CHECK_EQ_INT(t, s->node_count, 7); /* the default scene (1): 6 roots' trees */
        mvr_scene_get_info(s, &si); /* parent x +0.5, child x -0.5: quad centered on 0 */
        CHECK_MSG(t, std::fabs(si.bounds_min[0] + si.bounds_max[0]) < 1e-3, "bounds x %g..%g", si.bounds_min[0],
                  si.bounds_max[0]);
        CHECK_MSG(t, std::fabs(si.bounds_max[1] - 0.6) < 1e-6, "scale y 1.5: max y %g", si.bounds_max[1]);
        mvr_view_desc v;
        CHECK(t, mvr_scene_camera_view(s, mvr_scene_camera_node(s, 0), &v) == MVR_OK);
        CHECK(t, v.position[2] == 3.0 && v.projection.type == MVR_PROJECTION_PERSPECTIVE && v.projection.zfar == 0.0);
        CHECK(t, mvr_scene_camera_view(s, mvr_scene_camera_node(s, 1), &v) == MVR_OK);
        CHECK(t, v.projection.type == MVR_PROJECTION_ORTHOGRAPHIC && v.projection.xmag == 2.0);
        mvr_scene_destroy(s);
    }
    {   /* scenes[0] on request: a light and nothing to draw */
        mvr_gltf_options o = {};
        o.scene = 1;
        mvr_scene *s = nullptr;
        mvr_error err;
        CHECK(t, mvr_gltf_load_file((d + "/scene_graph.glb").c_str(), &o, &s, nullptr, &err) == MVR_OK);
        if (s)
            CHECK(t, s->node_count == 1 && s->mesh_count == 0);
        mvr_scene_destroy(s);
        o.scene = 3;
        CHECK(t, mvr_gltf_load_file((d + "/scene_graph.glb").c_str(), &o, &s, nullptr, &err) == MVR_ERROR_INVALID_ASSET);
        CHECK(t, strstr(err.message, "scene 3 requested") != nullptr);
    }
    warn_count warns;
    if (mvr_scene *s = load(t, d + "/skin_morph.gltf", &info, &warns)) {
        // skins and morph targets load (tests/io/test_gltf_animation.cpp has more)
        CHECK_MSG(t, info.warnings == 0 && warns.warnings == 0, "%u warnings: %s", info.warnings, warns.last.c_str());
        mvr_scene_info si;
        mvr_scene_get_info(s, &si);
        CHECK(t, si.skins == 1 && si.joints == 1 && si.morph_targets == 1);
        mvr_scene_destroy(s);
    }
    warns = warn_count();
    if (mvr_scene *s = load(t, d + "/optional_ext.gltf", &info, &warns)) {
        CHECK(t, warns.warnings == 1 && warns.last.find("EXT_mvr_unknown_optional") != std::string::npos);
        mvr_scene_destroy(s);
    }
}

static void broken_files_are_refused_by_name(mvr_test_state *t)
{
    for (const auto &b : corpus().broken_files) {
        mvr_scene *s = reinterpret_cast<mvr_scene *>(&s);
        mvr_error err;
        // strict: an undecodable image is an error too (it degrades otherwise)
        mvr_gltf_options strict = {};
        strict.strict = true;
        mvr_result r = mvr_gltf_load_file(b.path.c_str(), &strict, &s, nullptr, &err);
        printf("  %-22s %s: %s\n", base_name(b.path).c_str(), mvr_result_name(r), err.message);
        CHECK_MSG(t, int(r) == b.expected_result, "%s: %s, expected %s", base_name(b.path).c_str(), mvr_result_name(r),
                  mvr_result_name(mvr_result(b.expected_result)));
        CHECK_MSG(t, std::string(err.message).find(b.message_part) != std::string::npos, "%s: message lacks '%s'",
                  base_name(b.path).c_str(), b.message_part.c_str());
        CHECK(t, s == nullptr);
    }
    CHECK(t, corpus().broken_files.size() >= 15);
    // without strict, the undecodable image is left out: the file loads
    // with a warning naming it, and the count says so
    mvr_gltf_info info = {};
    warn_count warns;
    if (mvr_scene *s = load(t, corpus_dir() + "/bad_image.gltf", &info, &warns)) {
        CHECK_MSG(t, info.images_missing == 1 && info.images_decoded == 0, "%u missing", info.images_missing);
        CHECK_MSG(t, warns.last.find("images[0]") != std::string::npos, "%s", warns.last.c_str());
        mvr_scene_destroy(s);
    }
}

static void memory_loads_and_caps(mvr_test_state *t)
{
    const std::string d = corpus_dir();
    std::vector<uint8_t> glb = gen::read_file(d + "/textured.glb");
    mvr_scene *s = nullptr;
    mvr_error err;
    CHECK_MSG(t, mvr_gltf_load_memory(glb.data(), glb.size(), nullptr, &s, nullptr, &err) == MVR_OK, "%s", err.message);
    mvr_scene_destroy(s);
    std::vector<uint8_t> ext = gen::read_file(d + "/textured_external.gltf");
    CHECK(t, mvr_gltf_load_memory(ext.data(), ext.size(), nullptr, &s, nullptr, &err) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(err.message, "base_dir") != nullptr, "%s", err.message);
    mvr_gltf_options o = {};
    o.base_dir = d.c_str();
    CHECK_MSG(t, mvr_gltf_load_memory(ext.data(), ext.size(), &o, &s, nullptr, &err) == MVR_OK, "%s", err.message);
    mvr_scene_destroy(s);
    o.max_vertices = 3;
    CHECK(t, mvr_gltf_load_memory(ext.data(), ext.size(), &o, &s, nullptr, &err) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(err.message, "max_vertices") != nullptr, "%s", err.message);
    o.max_vertices = 0;
    o.max_image_dimension = 16;
    mvr_gltf_info info = {};
    CHECK(t, mvr_gltf_load_memory(ext.data(), ext.size(), &o, &s, &info, &err) == MVR_OK);
    CHECK_MSG(t, info.images_missing == 2, "%u", info.images_missing); /* its PNG and its JPEG */
    mvr_scene_destroy(s);
    o.strict = true;
    CHECK(t, mvr_gltf_load_memory(ext.data(), ext.size(), &o, &s, nullptr, &err) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(err.message, "images[0]") != nullptr && strstr(err.message, "max_image_dimension"), "%s",
              err.message);
    o.strict = false;
    o.max_image_dimension = 0;
    o.max_file_bytes = 100;
    CHECK(t, mvr_gltf_load_file((d + "/textured.glb").c_str(), &o, &s, nullptr, &err) == MVR_ERROR_INVALID_ASSET);
    CHECK_MSG(t, strstr(err.message, "max_file_bytes") != nullptr, "%s", err.message);
    CHECK(t, mvr_gltf_load_file((d + "/no_such_file.gltf").c_str(), nullptr, &s, nullptr, &err) == MVR_ERROR_IO);
    CHECK(t, mvr_gltf_load_memory(nullptr, 0, nullptr, &s, nullptr, &err) == MVR_ERROR_INVALID_ARGUMENT);
}

// A file lit as Blender exports it (a 2049 lux sun, a 27,000 cd point
// light): at exposure 1 a white image; with what `mvr render` does by
// default for such lights (auto-exposure, Khronos PBR Neutral) a picture
// whose mean luminance is in a sane band with little clipped.
static void physical_lights_are_exposed_by_default(mvr_test_state *t)
{
    std::string path;
    for (const std::string &p : corpus().features)
        if (p.find("physical_lights") != std::string::npos)
            path = p;
    CHECK(t, !path.empty());
    mvr_gltf_info info;
    mvr_scene *scene = path.empty() ? nullptr : load(t, path, &info);
    mvr_context *ctx = nullptr;
    mvr_error err;
    if (!scene || mvr_context_create(nullptr, &ctx, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s", scene ? err.message : "load");
        mvr_scene_destroy(scene);
        return;
    }
    CHECK(t, mvr_scene_lights_physical(scene));
    mvr_view_desc view;
    CHECK(t, mvr_scene_camera_view(scene, mvr_scene_camera_node(scene, 0), &view) == MVR_OK);
    mvr_view_set_desc vsd = {1, &view, false, {0, 0, 0}};
    mvr_view_set *views = nullptr;
    CHECK(t, mvr_view_set_create(&vsd, &views, nullptr) == MVR_OK);
    mvr_renderer_desc rd = {};
    rd.context = ctx;
    mvr_renderer *r = nullptr;
    mvr_target *target = nullptr;
    mvr_target_desc td = {W, H, 1, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_DEFAULT, 0};
    bool ok = mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK;
    for (int k = 0; ok && k < 2; ++k) {
        mvr_render_desc desc = {};
        /* a pale sky: a display colour (never exposed), about 40% of the view */
        desc.clear_color[0] = 0.3f, desc.clear_color[1] = 0.45f, desc.clear_color[2] = 0.8f;
        desc.clear_color[3] = 1.0f;
        if (k == 1) {
            desc.exposure_mode = MVR_EXPOSURE_AUTO;
            desc.tone_map = MVR_TONE_MAP_KHR_PBR_NEUTRAL;
        }
        std::vector<uint8_t> px(size_t(W) * H * 4);
        ok = mvr_renderer_render(r, scene, views, target, &desc) == MVR_OK &&
             mvr_renderer_read_layer(r, target, 0, MVR_READBACK_RGBA8, px.data(), px.size()) == MVR_OK;
        CHECK_MSG(t, ok, "%s", mvr_renderer_last_error(r));
        double sum = 0;
        size_t clipped = 0;
        auto lin = [](uint8_t v) {
            double e = v / 255.0;
            return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
        };
        for (size_t i = 0; i < size_t(W) * H; ++i) {
            const uint8_t *p = &px[i * 4];
            sum += 0.2126 * lin(p[0]) + 0.7152 * lin(p[1]) + 0.0722 * lin(p[2]);
            clipped += p[0] >= 254 || p[1] >= 254 || p[2] >= 254;
        }
        double mean = sum / (double(W) * H), clip = double(clipped) / (double(W) * H);
        mvr_frame_stats st;
        mvr_renderer_get_stats(r, &st);
        std::printf("  %s: mean luminance %.3f, %.1f%% clipped, EV100 %.2f\n", k ? "auto + PBR Neutral" : "exposure 1",
                    mean, 100.0 * clip, st.exposure_ev100);
        if (k == 0) {
            CHECK_MSG(t, clip > 0.5, "exposure 1: only %.1f%% clipped", 100.0 * clip);
        } else {
            CHECK_MSG(t, mean >= 0.1 && mean <= 0.6 && clip <= 0.03, "auto: mean %.3f, %.1f%% clipped", mean,
                      100.0 * clip);
        }
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(views);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
}

// A corpus file loaded and rendered on the loop path (both layers' bytes);
// empty after a failed check.
static std::vector<uint8_t> render_corpus_file(mvr_test_state *t, const std::string &name)
{
    std::vector<uint8_t> px;
    mvr_scene *s = load(t, corpus_dir() + "/" + name, nullptr);
    if (!s)
        return px;
    mvr_context *ctx = nullptr;
    mvr_error err;
    if (mvr_context_create(nullptr, &ctx, &err) == MVR_OK)
        px = gltf_render::two_layers(t, ctx, s, MVR_VIEW_PATH_LOOP, name.c_str());
    else
        CHECK_MSG(t, 0, "%s", err.message);
    mvr_context_destroy(ctx);
    mvr_scene_destroy(s);
    return px;
}

// Emission needs no extension: an emissiveFactor alone glows (it used to be
// dropped unless KHR_materials_emissive_strength was present), and that
// extension's strength 0 turns it off. No light: the emissive quad shows
// its factor, sRGB-encoded (1, 0.5, 0.25 -> 255, 188, 137), the other black.
static void emission_needs_no_extension(mvr_test_state *t)
{
    mvr_scene *s = load(t, corpus_dir() + "/emission.gltf", nullptr);
    if (!s)
        return;
    const float *glow = s->materials[0].desc.emissive_factor, *off = s->materials[1].desc.emissive_factor;
    CHECK_MSG(t, glow[0] == 1.0f && glow[1] == 0.5f && glow[2] == 0.25f, "factor %g %g %g", glow[0], glow[1], glow[2]);
    CHECK(t, off[0] == 0.0f && off[1] == 0.0f && off[2] == 0.0f);
    mvr_scene_destroy(s);
    std::vector<uint8_t> px = render_corpus_file(t, "emission.gltf");
    size_t glowing = 0, dark = 0;
    for (size_t i = 0; i + 3 < px.size(); i += 4) {
        auto near = [&](int r, int g, int b) {
            return std::abs(px[i] - r) <= 3 && std::abs(px[i + 1] - g) <= 3 && std::abs(px[i + 2] - b) <= 3;
        };
        glowing += near(255, 188, 137);
        dark += near(0, 0, 0);
    }
    std::printf("  %zu pixels glow, %zu are black\n", glowing, dark);
    CHECK_MSG(t, glowing > 100 && dark > 100, "%zu glowing, %zu black pixels", glowing, dark);
}

// Normal maps on back faces (double_sided_normals.gltf): the quads showing
// their back faces shade like those showing their fronts, with and without
// tangents. Mirroring the frame (the old shader negated n and b, not t)
// turned the back faces' normals away from the light: dark.
static void back_faces_take_the_whole_tangent_frame(mvr_test_state *t)
{
    std::vector<uint8_t> px = render_corpus_file(t, "double_sided_normals.gltf");
    const int w = gltf_render::frame_width, y = gltf_render::frame_height / 2;
    // the quads along the middle row of layer 0, left to right: runs of
    // pixels unlike the background (the row's first pixel)
    std::vector<double> means;
    auto quad_pixel = [&](int x) {
        const uint8_t *p = &px[(size_t(y) * w + size_t(x)) * 4], *bg = &px[size_t(y) * w * 4];
        return std::abs(p[0] - bg[0]) + std::abs(p[1] - bg[1]) + std::abs(p[2] - bg[2]) > 12;
    };
    for (int x = 0; x < w && !px.empty();) {
        if (!quad_pixel(x)) {
            ++x;
            continue;
        }
        double sum = 0;
        int n = 0;
        for (; x < w && quad_pixel(x); ++x, ++n)
            sum += px[(size_t(y) * w + size_t(x)) * 4];
        if (n >= 3)
            means.push_back(sum / n);
    }
    std::printf("  %zu quads, mean red:", means.size());
    for (double m : means)
        std::printf(" %.1f", m);
    std::printf("\n");
    // tangents: quads 0 (front) and 3 (back); derived frames: 1 and 2
    CHECK_MSG(t, means.size() == 4, "%zu quads in the middle row, 4 expected", means.size());
    if (means.size() == 4) {
        CHECK_MSG(t, means[0] > 100 && means[1] > 100, "the fronts are not lit: %.1f %.1f", means[0], means[1]);
        CHECK_MSG(t, std::fabs(means[0] - means[3]) <= 8.0, "with tangents: front %.1f, back %.1f", means[0], means[3]);
        CHECK_MSG(t, std::fabs(means[1] - means[2]) <= 8.0, "derived tangents: front %.1f, back %.1f", means[1],
                  means[2]);
    }
}

MVR_TEST_MAIN(TEST(physical_lights_are_exposed_by_default), TEST(feature_files_render_alike_on_both_paths), TEST(features_convert_as_specified),
              TEST(broken_files_are_refused_by_name), TEST(memory_loads_and_caps), TEST(emission_needs_no_extension),
              TEST(back_faces_take_the_whole_tangent_frame))
