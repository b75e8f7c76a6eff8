// io_hostile's KTX2 container files (ktx2_*, written with hostile_ktx2.hpp)
// and their case: a valid container, each field made to lie (left out with
// a warning, refused when strict), a decompression bomb (refused by the
// budget), and valid shapes mvr does not decode.
#ifndef MVR_HOSTILE_KTX2_FILES_HPP
#define MVR_HOSTILE_KTX2_FILES_HPP

#include "hostile_files.hpp"
#include "mvr_test.h"

namespace hostile {

// Writes the ktx2_* files into f.
void ktx2_files(files &f);

// The case (io_hostile runs it).
void ktx2_containers_are_checked(mvr_test_state *t);

}  // namespace hostile

#endif
