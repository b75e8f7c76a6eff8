// KTX 2.0 files written field by field for the tests (io_gltf_textures, and
// io_hostile's ktx2_* files): the header, the level index, a basic data
// format descriptor, optional key/value data (KTXorientation), optional
// supercompression global data and the levels, smallest first, each aligned
// as the KTX File Format Specification 2.0 says (mipPadding). Any field can
// be set to a lie; nothing here checks what it writes.
#ifndef MVR_HOSTILE_KTX2_HPP
#define MVR_HOSTILE_KTX2_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hostile {

// VkFormat values the tests use
enum : uint32_t {
    VK_R8_UNORM = 9, VK_R8G8_UNORM = 16, VK_R8G8B8_UNORM = 23, VK_R8G8B8_SRGB = 29, VK_B8G8R8_UNORM = 30,
    VK_R8G8B8A8_UNORM = 37, VK_R8G8B8A8_SRGB = 43, VK_B8G8R8A8_SRGB = 50, VK_R16G16B16A16_SFLOAT = 97,
    VK_BC7_UNORM = 145, VK_ETC2_R8G8B8_UNORM = 147, VK_ETC2_R8G8B8A8_SRGB = 152, VK_EAC_R11_UNORM = 153,
    VK_ASTC_4x4_SRGB = 158, VK_ASTC_8x8_UNORM = 171
};

struct ktx2_desc {
    uint32_t vk_format = VK_R8G8B8A8_SRGB;
    uint32_t type_size = 1;
    uint32_t width = 0, height = 0, depth = 0, layers = 0, faces = 1;
    uint32_t level_count = 1;              // as the header says (0: base level only)
    uint32_t supercompression = 0;         // 0 none, 1 BasisLZ, 2 Zstandard
    uint8_t color_model = 1;               // DFD: 1 RGBSDA, 163 ETC1S, 166 UASTC
    uint8_t transfer = 2;                  // DFD: 1 linear, 2 sRGB
    uint8_t block_width = 1, block_height = 1;
    uint32_t texel_bytes = 4;              // DFD bytesPlane0; bytes per texel or block (mipPadding)
    uint32_t channels = 4;                 // DFD samples of 8 bits (R, G, B, A order; 0 = none)
    std::string orientation;               // KTXorientation ("" = no key/value data)
    std::vector<uint8_t> sgd;              // supercompression global data
    std::vector<std::vector<uint8_t>> levels;   // level 0 (the largest) first, as stored
    std::vector<uint64_t> uncompressed;    // uncompressedByteLength per level (empty: each level's size)
};

// The file's bytes.
std::vector<uint8_t> ktx2_file(const ktx2_desc &k);

// Zstandard-compresses every level (ZSTD_compress) and records the sizes
// they inflate to; k.supercompression becomes 2.
void ktx2_zstd(ktx2_desc &k);

// Offsets in a file ktx2_file wrote: header fields, and level p's entry.
const size_t KTX2_LEVEL_COUNT = 40, KTX2_DFD_OFFSET = 48, KTX2_DFD_LENGTH = 52, KTX2_KVD_OFFSET = 56,
             KTX2_KVD_LENGTH = 60;
inline size_t ktx2_level_entry(uint32_t p) { return 80 + 24 * size_t(p); }
void put_le32(std::vector<uint8_t> &b, size_t at, uint32_t v);
void put_le64(std::vector<uint8_t> &b, size_t at, uint64_t v);
uint64_t get_le64(const std::vector<uint8_t> &b, size_t at);

// An uncompressed 8-bit KTX2 of the RGBA pixels px (w x h, rows top first)
// in vk_format (one of the 8-bit formats above: the channels it keeps, in
// its order), with `levels` levels (0: the header says 0, one level stored);
// levels below 0 are filled with magenta (level 0 alone must be decoded).
ktx2_desc ktx2_from_rgba(const std::vector<uint8_t> &px, uint32_t w, uint32_t h, uint32_t vk_format,
                         uint32_t levels = 1);

// A block-compressed (or Basis) KTX2 of w x h whose levels are filler bytes
// of the right sizes: a valid container mvr parses but does not decode.
// kind: "etc2" (VK_ETC2_R8G8B8A8_SRGB), "eac" (VK_EAC_R11_UNORM), "astc"
// (VK_ASTC_4x4_SRGB), "bc7", "etc1s" (BasisLZ, VK_FORMAT_UNDEFINED), "uastc"
// (VK_FORMAT_UNDEFINED, UASTC DFD), "uastc_zstd".
ktx2_desc ktx2_gpu(const std::string &kind, uint32_t w, uint32_t h, uint32_t levels = 1);

}  // namespace hostile

#endif
