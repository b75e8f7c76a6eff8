// io_hostile's PBR material extension files (matext_*): malformed
// extension JSON refused naming the material and the field, values out of
// range repaired (counted, warned), a well-formed file of every extension
// loading without a warning.
#ifndef MVR_TEST_HOSTILE_MATERIAL_EXT_HPP
#define MVR_TEST_HOSTILE_MATERIAL_EXT_HPP

#include "hostile_files.hpp"
#include "mvr_test.h"

namespace hostile {

// Writes the matext_* files into f.
void material_ext_files(files &f);

// The case (io_hostile runs it).
void material_extensions_are_checked(mvr_test_state *t);

}  // namespace hostile

#endif
