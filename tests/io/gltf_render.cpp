#include "gltf_render.hpp"

namespace gltf_render {

std::vector<uint8_t> two_layers(mvr_test_state *t, mvr_context *ctx, mvr_scene *scene, mvr_view_path path,
                                const char *what, const char *program_cache_dir)
{
    const int W = frame_width, H = frame_height;
    mvr_framing_desc fd = {MVR_LAYOUT_STEREO, 2, 0.2, double(W) / H, 0, 0.0, 0.0};
    mvr_view_set *views = nullptr;
    mvr_error err;
    std::vector<uint8_t> out;
    if (mvr_view_set_frame_scene(scene, &fd, &views, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s: framing: %s", what, err.message);
        return out;
    }
    mvr_renderer_desc rd = {};
    rd.context = ctx;
    rd.view_path = path;
    rd.program_cache_dir = program_cache_dir;
    mvr_renderer *r = nullptr;
    mvr_target *target = nullptr;
    mvr_target_desc td = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    mvr_render_desc desc = {{0.05f, 0.05f, 0.08f, 1.0f}, 1.0f, MVR_TONE_MAP_NONE};
    bool ok = mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
              mvr_renderer_render(r, scene, views, target, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "%s: render (%s path): %s", what, mvr_view_path_name(path),
              r ? mvr_renderer_last_error(r) : err.message);
    if (ok) {
        out.resize(size_t(W) * H * 4 * 2);
        for (uint32_t k = 0; k < 2; ++k) {
            bool read = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, &out[size_t(k) * W * H * 4],
                                                size_t(W) * H * 4) == MVR_OK;
            CHECK_MSG(t, read, "%s: readback of layer %u: %s", what, k, mvr_renderer_last_error(r));
        }
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(views);
    return out;
}

}  // namespace gltf_render
