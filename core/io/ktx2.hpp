// KTX 2.0 containers (Khronos, "KTX File Format Specification", version 2.0)
// read by mvr itself: the header, the level index, the Data Format
// Descriptor's basic block and the key/value data, every offset, length,
// count and level size checked against the bytes before anything is read.
// What mvr decodes: level 0 of the uncompressed 8-bit formats
// (VK_FORMAT_R8 / R8G8 / R8G8B8 / B8G8R8 / R8G8B8A8 / B8G8R8A8, _UNORM or
// _SRGB), with no supercompression or Zstandard, into RGBA8. What mvr keeps
// as GPU blocks (every level, uploaded without decoding): ETC2 RGB8 / RGB8A1
// / RGBA8, EAC R11 / RG11 unsigned and ASTC LDR, with no supercompression or
// Zstandard (read_blocks). Everything else (BCn, signed EAC, ASTC HDR, Basis
// Universal, other formats, ZLIB) is parsed and named, not decoded:
// decode() / unsupported_reason() say why.
#ifndef MVR_KTX2_HPP
#define MVR_KTX2_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mvr/mvr.h"

namespace mvr_ktx2 {

// The 12-byte identifier «KTX 20»\r\n\x1A\n (spec, 3.1).
bool is_ktx2(const unsigned char *p, size_t n);

enum class payload {
    uncompressed8,   // an 8-bit uncompressed format mvr decodes
    block,           // a GPU block format (BCn, ETC2/EAC, ASTC): uploadable as is, not decoded here
    basis_etc1s,     // BasisLZ / ETC1S (supercompression 1)
    basis_uastc,     // UASTC (VK_FORMAT_UNDEFINED with a UASTC DFD)
    other            // any other format
};

enum supercompression : uint32_t { SC_NONE = 0, SC_BASISLZ = 1, SC_ZSTD = 2, SC_ZLIB = 3 };

struct level {
    uint64_t offset, length, uncompressed;   // as the level index says, checked against the file
};

struct info {
    uint32_t vk_format = 0, type_size = 0;
    uint32_t width = 0, height = 0;
    uint32_t level_count = 0;       // as declared (0: base level only, mips to be generated)
    uint32_t depth = 0;             // pixelDepth (0: not a 3D texture)
    uint32_t layers = 1;            // max(1, layerCount); only layer 0 is used
    uint32_t faces = 1;             // 6: a cubemap
    bool one_dimensional = false;   // pixelHeight 0 (height is then 1)
    uint32_t supercompression = 0;
    payload kind = payload::other;
    std::string format;             // "VK_FORMAT_R8G8B8A8_SRGB", "BasisLZ/ETC1S", "VK_FORMAT 1000054000", ...
    uint32_t components = 0;        // uncompressed8: 1..4 bytes per texel
    bool bgr = false;               // uncompressed8: stored B, G, R(, A)
    bool srgb = false;              // the format (or the DFD's transfer function) says sRGB: informational
    uint32_t block_width = 1, block_height = 1, block_bytes = 0;   // block formats (1 x 1 and texel size otherwise)
    uint8_t dfd_color_model = 0, dfd_transfer = 0;
    bool flip_x = false, flip_y = false;   // KTXorientation other than "rd" (right, down: rows top first)
    std::vector<level> levels;      // max(1, level_count) entries, level 0 (the largest) first
};

enum class status { ok, invalid, unsupported, out_of_memory };

// Parses and validates the container in p[0, n). invalid: the bytes break
// the format (message in *why); unsupported is never returned here (a valid
// file of any format parses, see kind).
status parse(const unsigned char *p, size_t n, info *out, std::string *why);

// Why a parsed file is neither decoded by decode() nor read by
// read_blocks(), or "" when it is one of the two.
std::string unsupported_reason(const info &in);

// The mvr_image_format a block-compressed file is kept in (MVR_IMAGE_FORMAT_RGBA8:
// not one mvr keeps as blocks; decode() or nothing).
mvr_image_format block_format(const info &in);

// The levels read_blocks() gives: max(1, levelCount) (levelCount 0 asks for
// generated mips, which blocks cannot have: the base level alone is kept).
uint32_t block_levels(const info &in);

// Reads every level of a file block_format() keeps (layer 0, face 0: the
// only one unsupported_reason lets through): levels[k] points into p for
// uncompressed data, or into storage[k] (inflated to exactly the level
// index's uncompressedByteLength) for Zstandard. invalid: a Zstandard level
// that does not inflate to its size; out_of_memory.
status read_blocks(const unsigned char *p, size_t n, const info &in, std::vector<mvr_image_level> *levels,
                   std::vector<std::vector<unsigned char>> *storage, std::string *why);

// Bytes decode() (or read_blocks()) holds besides its output while it runs
// (the inflated level(s) for Zstandard; 0 otherwise).
uint64_t scratch_bytes(const info &in);

// Decodes level 0 (layer 0) of a parsed file into rgba (width * height * 4
// bytes, rows top first as glTF samples them). unsupported: see
// unsupported_reason; invalid: the level's data is broken (a Zstandard
// frame that does not inflate to the level's size).
status decode(const unsigned char *p, size_t n, const info &in, unsigned char *rgba, std::string *why);

}  // namespace mvr_ktx2

#endif
