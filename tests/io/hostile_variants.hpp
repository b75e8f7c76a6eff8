// io_hostile's material variant files (KHR_materials_variants) and their
// case: a valid file whose selections render their colours, and each way of
// breaking the root's variants or a primitive's mappings, refused naming
// the object (see hostile_variants.cpp).
#ifndef MVR_HOSTILE_VARIANTS_HPP
#define MVR_HOSTILE_VARIANTS_HPP

#include "hostile_files.hpp"
#include "mvr_test.h"

namespace hostile {

// Writes the variants_* files into f.
void variant_files(files &f);

// The case (io_hostile runs it).
void material_variants_are_checked(mvr_test_state *t);

}  // namespace hostile

#endif
