// Fuzz target of the glTF loader (libFuzzer): any bytes, as .gltf or .glb
// from memory, must load or fail with an error; never crash, hang, or
// allocate past the caps. Small caps keep each run fast.
//
// External URIs resolve against a folder made once per process
// (fuzz_files.hpp: a buffer, a PNG, a JPEG, a subfolder, and files outside
// the folder named like them), so fuzzed URIs such as "a.bin", "sub/x.png",
// "../outside.bin" or "%2e%2e/outside.bin" reach the loader's resolver and
// file reads. The seeds (fuzz_replay) and the dictionary (gltf.dict) name
// those files.
#include <cstddef>
#include <cstdint>

#include "fuzz_files.hpp"
#include "fuzz_gltf.hpp"

mvr_result fuzz_gltf_load(const uint8_t *data, size_t size, mvr_gltf_info *info)
{
    mvr_gltf_options o = {};
    o.base_dir = fuzz::base_dir().c_str();
    o.max_file_bytes = 1u << 20;
    o.max_vertices = 1u << 16;
    o.max_indices = 1u << 18;
    o.max_image_dimension = 256;
    o.max_nodes = 4096;
    mvr_scene *scene = nullptr;
    mvr_error error;
    mvr_result r = mvr_gltf_load_memory(data, size, &o, &scene, info, &error);
    mvr_scene_destroy(scene);
    return r;
}

extern "C" int LLVMFuzzerInitialize(int *, char ***)
{
    fuzz::base_dir(); // made before the first input, not during it
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 0)
        fuzz_gltf_load(data, size);
    return 0;
}
