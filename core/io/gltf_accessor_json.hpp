// The accessor and bufferView members tinygltf 2.7 reads wrongly, checked on
// the JSON itself before it parses (gltf_accessors.cpp; the pre-pass calls it).
#ifndef MVR_GLTF_ACCESSOR_JSON_HPP
#define MVR_GLTF_ACCESSOR_JSON_HPP

#include <nlohmann/json.hpp>

namespace mvr_gltf {

// Refuses, naming the object, a byteOffset or byteStride that is not an
// integer >= 0 (tinygltf reads a negative one as 0), and a sparse member
// that tinygltf narrows to int (a bufferView, byteOffset or componentType
// past INT32_MAX, a count of 2^32 + 1 read as 1) or a sparse count not in
// 1..the accessor's count.
void check_accessor_json(const nlohmann::json &doc);

}  // namespace mvr_gltf

#endif
