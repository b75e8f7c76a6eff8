// The loader's pre-pass: GLB framing, JSON bounds, and the resources taken
// out of the JSON before tinygltf parses it (gltf_prepass.cpp).
#ifndef MVR_GLTF_PREPASS_HPP
#define MVR_GLTF_PREPASS_HPP

#include "gltf_files.hpp"
#include "gltf_internal.hpp"

namespace mvr_gltf {

struct json_text {
    const unsigned char *data;
    size_t size;
};

// A GLB is checked and split (its BIN chunk goes to res.bin); anything else
// is taken as the JSON itself.
json_text split_container(const unsigned char *bytes, size_t size, resources &res, context &cx);

// Refuses JSON nested deeper than 64 levels; returns an upper bound of the
// heap the parsed JSON takes (nlohmann's tree and tinygltf's model).
uint64_t scan_json(const unsigned char *p, size_t n);

// Takes every buffer's and image's source out of the JSON into res and
// returns the JSON tinygltf parses (those replaced by one-byte placeholders);
// model_size: what tinygltf's model objects will take.
std::string extract_resources(const json_text &text, resources &res, uint64_t *model_size);

}  // namespace mvr_gltf

#endif
