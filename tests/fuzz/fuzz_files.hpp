// The files the glTF fuzz target's URIs can reach: a folder made once per
// process (options.base_dir), and seed files whose URIs point into it, out
// of it, and at what is not there.
#ifndef MVR_FUZZ_FILES_HPP
#define MVR_FUZZ_FILES_HPP

#include <string>
#include <vector>

namespace fuzz {

// Makes (once) and returns the fuzz target's base_dir: a fresh folder
// TMP/mvr-fuzz-XXXXXX/base holding
//   a.bin        a buffer: a textured quad's vertices and indices (seed_buffer)
//   img.png      a 16 x 16 PNG
//   img.jpg      a 16 x 16 JPEG
//   sub/b.bin    the same buffer
//   sub/x.png    the same PNG
// and, OUTSIDE it, in its parent: outside.bin (the same buffer) and
// outside.png. Removed when the process exits.
const std::string &base_dir();

// Writes the seeds (ext_*.gltf / .glb) into dir; returns their paths, and
// which of them must load, every URI naming a file inside base_dir.
struct seed { std::string path; bool inside; };
std::vector<seed> write_seeds(const std::string &dir);

}  // namespace fuzz

#endif
