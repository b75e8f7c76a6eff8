// The io tests' frame of a loaded scene (io_gltf, io_hostile): two stereo
// views, framed on the scene's bounds, rendered into a 2-layer RGBA8 target
// of frame_width x frame_height and read back.
#ifndef MVR_GLTF_RENDER_HPP
#define MVR_GLTF_RENDER_HPP

#include <cstdint>
#include <vector>

#include "mvr/mvr.h"
#include "mvr_test.h"

namespace gltf_render {

const int frame_width = 64, frame_height = 48;

// Both layers' RGBA8 bytes, layer 0 first; empty after a failed check whose
// message starts with `what` (framing, render on `path`, or a readback).
// program_cache_dir: the renderer's, or nullptr for none.
std::vector<uint8_t> two_layers(mvr_test_state *t, mvr_context *ctx, mvr_scene *scene, mvr_view_path path,
                                const char *what, const char *program_cache_dir = nullptr);

}  // namespace gltf_render

#endif
