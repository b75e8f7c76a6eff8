// io_hostile's accessor files (acc_*) and their case: negative byteOffsets
// and byteStrides (tinygltf reads them as 0), sparse indices that do not
// strictly increase, and sparse members tinygltf narrows to int.
#ifndef MVR_HOSTILE_ACCESSORS_HPP
#define MVR_HOSTILE_ACCESSORS_HPP

#include "hostile_files.hpp"
#include "mvr_test.h"

namespace hostile {

// Writes the acc_* files into f.
void accessor_files(files &f);

// The case (io_hostile runs it).
void accessor_offsets_and_sparse_are_checked(mvr_test_state *t);

}  // namespace hostile

#endif
