// Fuzz target of the glTF loader (libFuzzer): any bytes, as .gltf or .glb
// from memory, must load or fail with an error; never crash, hang, or
// allocate past the caps. Small caps keep each run fast.
#include <cstddef>
#include <cstdint>

#include "mvr/mvr_gltf.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    mvr_gltf_options o = {};
    o.max_file_bytes = 1u << 20;
    o.max_vertices = 1u << 16;
    o.max_indices = 1u << 18;
    o.max_image_dimension = 256;
    o.max_nodes = 4096;
    mvr_scene *scene = nullptr;
    mvr_error error;
    if (size > 0)
        mvr_gltf_load_memory(data, size, &o, &scene, nullptr, &error);
    mvr_scene_destroy(scene);
    return 0;
}
