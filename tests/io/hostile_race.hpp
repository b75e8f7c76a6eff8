// io_hostile's race against the resolver (issue 31): a file inside the asset
// folder swapped, while the glTF is loaded again and again, between a real
// file and a symbolic link to a file outside the folder.
#ifndef MVR_HOSTILE_RACE_HPP
#define MVR_HOSTILE_RACE_HPP

#include "mvr_test.h"

namespace hostile {

// Loads the race glTF race_loads() times while a thread swaps its buffer;
// no load may return the outside file's bytes.
void symlink_swaps_never_read_outside(mvr_test_state *t);

// Symbolic links that stay inside the folder resolve; those that leave it
// are refused unless allowed_root admits their target.
void symlinks_inside_the_folder_still_resolve(mvr_test_state *t);

// 20000, or MVR_HOSTILE_RACE_LOADS (1..10^7) for longer hunts.
long race_loads();

}  // namespace hostile

#endif
