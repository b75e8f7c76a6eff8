// The fuzz target's load, with its options (caps, base_dir), for the replay
// to check what the seeds give.
#ifndef MVR_FUZZ_GLTF_HPP
#define MVR_FUZZ_GLTF_HPP

#include <cstddef>
#include <cstdint>

#include "mvr/mvr_gltf.h"

// info: optional (the replay checks that nothing degraded to a warning)
mvr_result fuzz_gltf_load(const uint8_t *data, size_t size, mvr_gltf_info *info = nullptr);

#endif
