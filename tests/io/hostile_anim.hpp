// io_hostile's skin, morph target and animation files (anim_*) and their
// case: anim_doc (tests/io/hostile_docs.hpp), a valid skinned, morphed,
// animated quad, each way of breaking it, refused naming the object, and
// channels with paths mvr does not implement, which load with a warning.
#ifndef MVR_HOSTILE_ANIM_HPP
#define MVR_HOSTILE_ANIM_HPP

#include "hostile_files.hpp"
#include "mvr_test.h"

namespace hostile {

// Writes the anim_* files into f.
void anim_files(files &f);

// The case (io_hostile runs it).
void skins_morphs_and_animations_are_checked(mvr_test_state *t);

}  // namespace hostile

#endif
