// io_hostile's compressed-geometry files (EXT_meshopt_compression,
// KHR_draco_mesh_compression) and extension messages: a valid quad encoded
// with meshoptimizer's own encoder, draco_transcoder's output of the codec
// test model, and each way of breaking them (truncated streams, lying counts and strides, missing Draco
// attributes, indices out of range), refused naming the object
// (tests/io/test_hostile.cpp, compressed_geometry_is_checked).
#ifndef MVR_HOSTILE_CODECS_HPP
#define MVR_HOSTILE_CODECS_HPP

#include <functional>

#include "hostile_docs.hpp"
#include "hostile_files.hpp"

namespace hostile {

// A unit quad (4 vertices, 2 triangles, unlit orange) whose POSITION
// (ATTRIBUTES, stride 12), NORMAL (VEC3 of normalized bytes, stride 4,
// filter OCTAHEDRAL) and indices (TRIANGLES, u16) are meshopt-compressed
// into buffer 0 (a data URI); their bufferViews lie in buffer 1, the
// fallback buffer without data. indices: the 6 indices to encode.
struct meshopt_parts {
    int position_view, normal_view, index_view, position, normal, indices;
    size_t position_bytes;   // the compressed POSITION stream's length
};
doc meshopt_doc(meshopt_parts *parts = nullptr, const std::vector<uint16_t> &indices = {0, 1, 2, 0, 2, 3});

// tests/data/codecs/draco.glb's Draco data (Suzanne, encoded by
// draco_transcoder: POSITION, NORMAL, TANGENT, TEXCOORD_0 and the triangles)
// in bufferView `view` of buffer 0 (a data URI), its accessors without
// bufferViews, drawn unlit blue. index_type: the indices accessor's
// componentType.
struct draco_parts {
    int view, position, normal, tangent, texcoord, indices;
    uint32_t points, triangles;
    uint32_t position_id, normal_id, tangent_id, texcoord_id;   // Draco unique ids
    size_t blob_bytes;
};
// patch: changes to the Draco data before it goes in.
doc draco_doc(draco_parts *parts = nullptr, int index_type = USHORT,
              const std::function<void(std::vector<uint8_t> &)> &patch = nullptr);

// Writes the codec_* and ext_* files into f.
void codec_files(files &f);

}  // namespace hostile

#endif
