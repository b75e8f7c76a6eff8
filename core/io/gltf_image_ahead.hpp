// Images decoded ahead, on all cores: the PNG / JPEG images a glTF's textures
// name, decoded in parallel the first time the loader needs an image, then
// handed to converter::decode_image one by one in the loader's own order, so
// the scene, its image ids, the messages and which image fails first are
// those of decoding one at a time (a decode that fails ahead is simply done
// again in order, where its error is reported as before).
//
// Memory: what the pool decodes at once is charged to the load's budget
// before it starts; the results then held are charged until taken, and
// dropped (decoded again in order) when any other charge would otherwise go
// over the budget, so no load is refused that decoding in order would take.
//
// MVR_DECODE_THREADS=N (1..64) sets the threads (1: nothing is decoded
// ahead, the loader decodes each image when it needs it); the default is the
// online CPUs, at most 8.
#ifndef MVR_GLTF_IMAGE_AHEAD_HPP
#define MVR_GLTF_IMAGE_AHEAD_HPP

#include <memory>
#include <string>

#include "gltf_internal.hpp"
#include "mvr/mvr_image.h"

namespace mvr_gltf {

struct image_ahead;

// Decodes ahead what can be, or returns null (one thread, fewer than two
// images, nothing within the budget). Bytes are taken only from bufferViews
// whose buffer is already in memory (read, or the GLB's BIN chunk): nothing
// is read from a file here that the loader would read later.
std::shared_ptr<image_ahead> decode_images_ahead(context &cx, const tinygltf::Model &m);

// The pixels decoded ahead for `key` (converter::decode_image's key) from
// these bytes, with the budget `charge` the loader gives the decoder: true
// with *out filled and their hold released (the caller owns them now);
// false where there are none (the caller decodes).
bool take_ahead(image_ahead *ahead, const std::string &key, const unsigned char *bytes, uint64_t size,
                uint64_t charge, mvr_image_data *out);

}  // namespace mvr_gltf

#endif
