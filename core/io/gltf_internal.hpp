// Shared by the glTF loader's files: the load context and validated reads.
#ifndef MVR_GLTF_INTERNAL_HPP
#define MVR_GLTF_INTERNAL_HPP

#include <tiny_gltf.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mvr/mvr_gltf.h"

namespace mvr_gltf {

// A refusal with the result to return and a message naming the object.
struct load_error : std::runtime_error {
    mvr_result result;
    load_error(mvr_result r, const std::string &msg) : std::runtime_error(msg), result(r) {}
};

[[noreturn]] inline void refuse(const std::string &msg)
{
    throw load_error(MVR_ERROR_INVALID_ASSET, msg);
}

struct caps {
    uint64_t max_file_bytes, max_vertices, max_indices;
    uint32_t max_image_dimension, max_nodes;
};

struct context {
    const tinygltf::Model *model = nullptr;
    caps limits{};
    mvr_logger logger{};
    uint32_t warnings = 0;
    uint64_t vertices = 0, indices = 0;   // running totals against the caps
    bool quantization_declared = false;   // KHR_mesh_quantization in extensionsUsed
    void warn(const std::string &msg);
};

// Reads accessor `index` as floats, `components` per element (the accessor's
// type must have exactly that many). Normalized integers become [0, 1] or
// [-1, 1] (glTF 2.0 3.11), others convert as they are. Every offset, stride and
// count is checked first, sparse substitution included. `what` names the use
// for messages, e.g. "meshes[3].primitives[0].attributes.NORMAL".
std::vector<float> read_floats(context &cx, int index, int components, const std::string &what,
                               uint32_t allowed_component_types);

// Reads accessor `index` as unsigned indices (SCALAR of UNSIGNED_BYTE / SHORT / INT).
std::vector<uint32_t> read_indices(context &cx, int index, const std::string &what);

// Bit of a glTF component type in an allowed mask.
uint32_t component_bit(int component_type);
constexpr uint32_t ANY_FLOAT = 1u << 6;

// Overflow-checked 64-bit arithmetic: refuses with the message on overflow.
uint64_t mul_checked(uint64_t a, uint64_t b, const std::string &what);
uint64_t add_checked(uint64_t a, uint64_t b, const std::string &what);

}  // namespace mvr_gltf

#endif
