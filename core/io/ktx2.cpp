// KTX 2.0 containers (see ktx2.hpp). Section numbers refer to the KTX File
// Format Specification 2.0; format numbers are VkFormat values (Vulkan 1.3,
// "Formats"). Every read is bounds-checked against n in 64-bit arithmetic
// that cannot overflow (offsets and lengths are at most 64-bit each; sums
// are checked).
#include "ktx2.hpp"

#include <zstd.h>

#include <cstring>
#include <memory>
#include <new>
#include <utility>

namespace mvr_ktx2 {

namespace {

const unsigned char identifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
const size_t header_bytes = 80;    // identifier, 9 UInt32, the index (4 UInt32 + 2 UInt64)
const size_t level_entry_bytes = 24;

uint32_t u32(const unsigned char *p)
{
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

uint64_t u64(const unsigned char *p)
{
    return uint64_t(u32(p)) | uint64_t(u32(p + 4)) << 32;
}

// [offset, offset + length) inside [0, n)?
bool inside(uint64_t offset, uint64_t length, size_t n)
{
    return offset <= n && length <= n - offset;
}

bool mul(uint64_t a, uint64_t b, uint64_t *out)
{
    return !__builtin_mul_overflow(a, b, out);
}

// The formats mvr names. Uncompressed 8-bit ones first (decoded), then the
// GPU block formats (texel block size from Vulkan's compatibility classes).
struct format_entry {
    uint32_t vk;
    const char *name;
    payload kind;
    uint8_t components, bw, bh, bytes;   // bytes: per texel (uncompressed) or per block
    bool bgr, srgb;
};

const format_entry formats[] = {
    {9, "VK_FORMAT_R8_UNORM", payload::uncompressed8, 1, 1, 1, 1, false, false},
    {15, "VK_FORMAT_R8_SRGB", payload::uncompressed8, 1, 1, 1, 1, false, true},
    {16, "VK_FORMAT_R8G8_UNORM", payload::uncompressed8, 2, 1, 1, 2, false, false},
    {22, "VK_FORMAT_R8G8_SRGB", payload::uncompressed8, 2, 1, 1, 2, false, true},
    {23, "VK_FORMAT_R8G8B8_UNORM", payload::uncompressed8, 3, 1, 1, 3, false, false},
    {29, "VK_FORMAT_R8G8B8_SRGB", payload::uncompressed8, 3, 1, 1, 3, false, true},
    {30, "VK_FORMAT_B8G8R8_UNORM", payload::uncompressed8, 3, 1, 1, 3, true, false},
    {36, "VK_FORMAT_B8G8R8_SRGB", payload::uncompressed8, 3, 1, 1, 3, true, true},
    {37, "VK_FORMAT_R8G8B8A8_UNORM", payload::uncompressed8, 4, 1, 1, 4, false, false},
    {43, "VK_FORMAT_R8G8B8A8_SRGB", payload::uncompressed8, 4, 1, 1, 4, false, true},
    {44, "VK_FORMAT_B8G8R8A8_UNORM", payload::uncompressed8, 4, 1, 1, 4, true, false},
    {50, "VK_FORMAT_B8G8R8A8_SRGB", payload::uncompressed8, 4, 1, 1, 4, true, true},
    // A8B8G8R8 packed into 32 bits little-endian: the bytes of R8G8B8A8 (spec, 3.2 note)
    {51, "VK_FORMAT_A8B8G8R8_UNORM_PACK32", payload::uncompressed8, 4, 1, 1, 4, false, false},
    {57, "VK_FORMAT_A8B8G8R8_SRGB_PACK32", payload::uncompressed8, 4, 1, 1, 4, false, true},
    {131, "VK_FORMAT_BC1_RGB_UNORM_BLOCK", payload::block, 0, 4, 4, 8, false, false},
    {132, "VK_FORMAT_BC1_RGB_SRGB_BLOCK", payload::block, 0, 4, 4, 8, false, true},
    {133, "VK_FORMAT_BC1_RGBA_UNORM_BLOCK", payload::block, 0, 4, 4, 8, false, false},
    {134, "VK_FORMAT_BC1_RGBA_SRGB_BLOCK", payload::block, 0, 4, 4, 8, false, true},
    {135, "VK_FORMAT_BC2_UNORM_BLOCK", payload::block, 0, 4, 4, 16, false, false},
    {136, "VK_FORMAT_BC2_SRGB_BLOCK", payload::block, 0, 4, 4, 16, false, true},
    {137, "VK_FORMAT_BC3_UNORM_BLOCK", payload::block, 0, 4, 4, 16, false, false},
    {138, "VK_FORMAT_BC3_SRGB_BLOCK", payload::block, 0, 4, 4, 16, false, true},
    {139, "VK_FORMAT_BC4_UNORM_BLOCK", payload::block, 0, 4, 4, 8, false, false},
    {140, "VK_FORMAT_BC4_SNORM_BLOCK", payload::block, 0, 4, 4, 8, false, false},
    {141, "VK_FORMAT_BC5_UNORM_BLOCK", payload::block, 0, 4, 4, 16, false, false},
    {142, "VK_FORMAT_BC5_SNORM_BLOCK", payload::block, 0, 4, 4, 16, false, false},
    {143, "VK_FORMAT_BC6H_UFLOAT_BLOCK", payload::block, 0, 4, 4, 16, false, false},
    {144, "VK_FORMAT_BC6H_SFLOAT_BLOCK", payload::block, 0, 4, 4, 16, false, false},
    {145, "VK_FORMAT_BC7_UNORM_BLOCK", payload::block, 0, 4, 4, 16, false, false},
    {146, "VK_FORMAT_BC7_SRGB_BLOCK", payload::block, 0, 4, 4, 16, false, true},
    {147, "VK_FORMAT_ETC2_R8G8B8_UNORM_BLOCK", payload::block, 0, 4, 4, 8, false, false},
    {148, "VK_FORMAT_ETC2_R8G8B8_SRGB_BLOCK", payload::block, 0, 4, 4, 8, false, true},
    {149, "VK_FORMAT_ETC2_R8G8B8A1_UNORM_BLOCK", payload::block, 0, 4, 4, 8, false, false},
    {150, "VK_FORMAT_ETC2_R8G8B8A1_SRGB_BLOCK", payload::block, 0, 4, 4, 8, false, true},
    {151, "VK_FORMAT_ETC2_R8G8B8A8_UNORM_BLOCK", payload::block, 0, 4, 4, 16, false, false},
    {152, "VK_FORMAT_ETC2_R8G8B8A8_SRGB_BLOCK", payload::block, 0, 4, 4, 16, false, true},
    {153, "VK_FORMAT_EAC_R11_UNORM_BLOCK", payload::block, 0, 4, 4, 8, false, false},
    {154, "VK_FORMAT_EAC_R11_SNORM_BLOCK", payload::block, 0, 4, 4, 8, false, false},
    {155, "VK_FORMAT_EAC_R11G11_UNORM_BLOCK", payload::block, 0, 4, 4, 16, false, false},
    {156, "VK_FORMAT_EAC_R11G11_SNORM_BLOCK", payload::block, 0, 4, 4, 16, false, false},
};

// ASTC: VkFormat 157 + 2 * i (UNORM) and + 1 (SRGB), and the HDR ones
// 1000066000 + i (SFLOAT, VK_EXT_texture_compression_astc_hdr), i in the
// order of these block sizes; every ASTC block is 16 bytes.
const uint8_t astc_blocks[14][2] = {{4, 4}, {5, 4},  {5, 5},  {6, 5},  {6, 6},   {8, 5},   {8, 6},
                                    {8, 8}, {10, 5}, {10, 6}, {10, 8}, {10, 10}, {12, 10}, {12, 12}};

bool describe_format(uint32_t vk, info *out)
{
    for (const format_entry &f : formats) {
        if (f.vk != vk)
            continue;
        out->format = f.name;
        out->kind = f.kind;
        out->components = f.components;
        out->block_width = f.bw;
        out->block_height = f.bh;
        out->block_bytes = f.bytes;
        out->bgr = f.bgr;
        out->srgb = f.srgb;
        return true;
    }
    int astc = -1;
    bool srgb = false, hdr = false;
    if (vk >= 157 && vk <= 184) {
        astc = int(vk - 157) / 2;
        srgb = (vk - 157) % 2 == 1;
    } else if (vk >= 1000066000u && vk <= 1000066013u) {
        astc = int(vk - 1000066000u);
        hdr = true;
    }
    if (astc < 0)
        return false;
    out->format = "VK_FORMAT_ASTC_" + std::to_string(astc_blocks[astc][0]) + "x" + std::to_string(astc_blocks[astc][1]) +
                  (hdr ? "_SFLOAT_BLOCK" : srgb ? "_SRGB_BLOCK" : "_UNORM_BLOCK");
    out->kind = payload::block;
    out->block_width = astc_blocks[astc][0];
    out->block_height = astc_blocks[astc][1];
    out->block_bytes = 16;
    out->srgb = srgb;
    return true;
}

// Data Format Descriptor colour models and transfer functions (Khronos Data Format 1.3, 5.6 / 5.8)
const uint8_t MODEL_ETC1S = 163, MODEL_UASTC = 166;
const uint8_t TRANSFER_SRGB = 2;

status bad(std::string *why, const std::string &msg)
{
    *why = msg;
    return status::invalid;
}

}  // namespace

bool is_ktx2(const unsigned char *p, size_t n)
{
    return n >= sizeof identifier && std::memcmp(p, identifier, sizeof identifier) == 0;
}

status parse(const unsigned char *p, size_t n, info *out, std::string *why)
{
    *out = info();
    if (!is_ktx2(p, n))
        return bad(why, "not a KTX2 file (no KTX 2.0 identifier)");
    if (n < header_bytes + level_entry_bytes)
        return bad(why, "KTX2 file of " + std::to_string(n) + " bytes is shorter than its header");
    info &in = *out;
    in.vk_format = u32(p + 12);
    in.type_size = u32(p + 16);
    in.width = u32(p + 20);
    in.height = u32(p + 24);
    uint32_t depth = u32(p + 28), layer_count = u32(p + 32), faces = u32(p + 36);
    in.depth = depth;
    in.faces = faces;
    in.level_count = u32(p + 40);
    in.supercompression = u32(p + 44);
    uint32_t dfd_offset = u32(p + 48), dfd_length = u32(p + 52), kvd_offset = u32(p + 56), kvd_length = u32(p + 60);
    uint64_t sgd_offset = u64(p + 64), sgd_length = u64(p + 72);

    // texture type (spec, 4.1): width > 0; height 0 only for 1D; faces 1, or 6 for a square cubemap
    if (in.width == 0)
        return bad(why, "KTX2 pixelWidth is 0");
    if (in.height == 0 && depth != 0)
        return bad(why, "KTX2 pixelHeight is 0 but pixelDepth is " + std::to_string(depth));
    if (faces != 1 && faces != 6)
        return bad(why, "KTX2 faceCount is " + std::to_string(faces) + " (1, or 6 for a cubemap)");
    if (faces == 6 && (in.width != in.height || depth != 0))
        return bad(why, "KTX2 cubemap faces are not square 2D images");
    in.layers = layer_count ? layer_count : 1;
    // levelCount <= floor(log2(max dimension)) + 1 (spec, 3.8): at most 32 levels
    uint64_t largest = in.width > in.height ? in.width : in.height;
    largest = largest > depth ? largest : depth;
    uint32_t max_levels = 1;
    while ((largest >> max_levels) != 0)
        ++max_levels;
    if (in.level_count > max_levels)
        return bad(why, "KTX2 levelCount " + std::to_string(in.level_count) + " is over the " +
                            std::to_string(max_levels) + " levels a " + std::to_string(largest) + "-texel image has");
    uint32_t num_levels = in.level_count ? in.level_count : 1;
    uint64_t index_end = header_bytes + uint64_t(num_levels) * level_entry_bytes;
    if (index_end > n)
        return bad(why, "KTX2 level index of " + std::to_string(num_levels) + " levels runs past the end of the " +
                            std::to_string(n) + " bytes");

    // Data Format Descriptor (spec, 3.10): dfdTotalSize, then the basic descriptor block
    if (dfd_length < 4 + 24 || !inside(dfd_offset, dfd_length, n))
        return bad(why, "KTX2 data format descriptor (offset " + std::to_string(dfd_offset) + ", " +
                            std::to_string(dfd_length) + " bytes) is missing, too short or outside the file");
    if (u32(p + dfd_offset) != dfd_length)
        return bad(why, "KTX2 dfdTotalSize " + std::to_string(u32(p + dfd_offset)) + " is not dfdByteLength " +
                            std::to_string(dfd_length));
    {
        const unsigned char *b = p + dfd_offset + 4;
        uint32_t w0 = u32(b), w1 = u32(b + 4);
        uint32_t vendor = w0 & 0x1FFFFu, type = w0 >> 17, block_size = w1 >> 16;
        if (vendor != 0 || type != 0 || block_size < 24 || block_size > dfd_length - 4)
            return bad(why, "KTX2 data format descriptor does not start with a basic descriptor block that fits in it");
        in.dfd_color_model = b[8];
        in.dfd_transfer = b[10];
    }

    // key/value data (spec, 3.11): pairs of length, key NUL value, padding to 4
    if (kvd_length > 0) {
        if (!inside(kvd_offset, kvd_length, n))
            return bad(why, "KTX2 key/value data (offset " + std::to_string(kvd_offset) + ", " +
                                std::to_string(kvd_length) + " bytes) is outside the file");
        uint64_t at = kvd_offset, end = uint64_t(kvd_offset) + kvd_length;
        while (at < end) {
            if (end - at < 4)
                return bad(why, "KTX2 key/value data ends inside a keyAndValueByteLength");
            uint32_t len = u32(p + at);
            if (len > end - at - 4)
                return bad(why, "KTX2 key/value pair at byte " + std::to_string(at) + " (" + std::to_string(len) +
                                    " bytes) runs past the key/value data");
            const unsigned char *kv = p + at + 4;
            const void *nul = std::memchr(kv, 0, len);
            if (!nul)
                return bad(why, "KTX2 key/value pair at byte " + std::to_string(at) + " has no NUL after its key");
            size_t key_len = size_t(static_cast<const unsigned char *>(nul) - kv);
            if (key_len == 14 && std::memcmp(kv, "KTXorientation", 14) == 0) {
                // "rd" (rows top first, texels left to right) unless it says otherwise
                size_t vlen = len - key_len - 1;
                const unsigned char *v = kv + key_len + 1;
                in.flip_x = vlen >= 1 && v[0] == 'l';
                in.flip_y = vlen >= 2 && v[1] == 'u';
            }
            at += 4 + ((uint64_t(len) + 3) & ~uint64_t(3));
        }
    }
    // supercompression global data (BasisLZ's codebooks): only bounds-checked, never read
    if (sgd_length > 0 && !inside(sgd_offset, sgd_length, n))
        return bad(why, "KTX2 supercompression global data (offset " + std::to_string(sgd_offset) + ", " +
                            std::to_string(sgd_length) + " bytes) is outside the file");

    // what the payload is
    bool known = describe_format(in.vk_format, &in);
    if (in.vk_format == 0) {
        if (in.supercompression == SC_BASISLZ || in.dfd_color_model == MODEL_ETC1S) {
            in.kind = payload::basis_etc1s;
            in.format = "Basis Universal ETC1S (BasisLZ)";
        } else if (in.dfd_color_model == MODEL_UASTC) {
            in.kind = payload::basis_uastc;
            in.format = "Basis Universal UASTC";
            in.block_width = in.block_height = 4;
            in.block_bytes = 16;
        } else {
            in.kind = payload::other;
            in.format = "VK_FORMAT_UNDEFINED (data format descriptor colour model " +
                        std::to_string(in.dfd_color_model) + ")";
        }
    } else if (!known) {
        in.kind = payload::other;
        in.format = "VK_FORMAT " + std::to_string(in.vk_format);
    }
    if (in.dfd_transfer == TRANSFER_SRGB)
        in.srgb = true;
    if (in.supercompression == SC_BASISLZ && in.kind != payload::basis_etc1s)
        return bad(why, "KTX2 BasisLZ supercompression of " + in.format + " (BasisLZ needs VK_FORMAT_UNDEFINED)");

    // the level index (spec, 3.9): every level inside the file, after the
    // index, of the size its format and dimensions give
    in.levels.resize(num_levels);
    bool sized = in.block_bytes != 0 && (in.supercompression == SC_NONE || in.supercompression == SC_ZSTD ||
                                         in.supercompression == SC_ZLIB);
    for (uint32_t lv = 0; lv < num_levels; ++lv) {
        const unsigned char *e = p + header_bytes + size_t(lv) * level_entry_bytes;
        level &l = in.levels[lv];
        l.offset = u64(e);
        l.length = u64(e + 8);
        l.uncompressed = u64(e + 16);
        std::string lw = "KTX2 level " + std::to_string(lv);
        if (l.length == 0 || !inside(l.offset, l.length, n) || l.offset < index_end)
            return bad(why, lw + " (offset " + std::to_string(l.offset) + ", " + std::to_string(l.length) +
                                " bytes) is empty, inside the header or past the end of the file (" +
                                std::to_string(n) + " bytes)");
        if (in.supercompression == SC_NONE && l.uncompressed != l.length)
            return bad(why, lw + ": byteLength " + std::to_string(l.length) + " but uncompressedByteLength " +
                                std::to_string(l.uncompressed) + " without supercompression");
        if (in.supercompression == SC_BASISLZ && l.uncompressed != 0)
            return bad(why, lw + ": uncompressedByteLength is not 0 under BasisLZ");
        if (!sized)
            continue;
        uint64_t w = in.width >> lv ? in.width >> lv : 1, h = in.height >> lv ? in.height >> lv : 1;
        uint64_t d = depth >> lv ? depth >> lv : 1;
        uint64_t bx = (w + in.block_width - 1) / in.block_width, by = (h + in.block_height - 1) / in.block_height;
        uint64_t expected = 0;
        if (!mul(bx, by, &expected) || !mul(expected, d, &expected) || !mul(expected, faces, &expected) ||
            !mul(expected, in.layers, &expected) || !mul(expected, in.block_bytes, &expected) ||
            l.uncompressed != expected)
            return bad(why, lw + " holds " + std::to_string(l.uncompressed) + " bytes (uncompressed); " + in.format +
                                " at " + std::to_string(w) + "x" + std::to_string(h) + " needs " +
                                (expected ? std::to_string(expected) : std::string("more than 2^64")));
    }
    if (in.height == 0) {
        in.one_dimensional = true;   // refused by unsupported_reason
        in.height = 1;
    }
    return status::ok;
}

std::string unsupported_reason(const info &in)
{
    switch (in.kind) {
    case payload::uncompressed8: break;
    case payload::block:
        if (block_format(in) == MVR_IMAGE_FORMAT_RGBA8)
            return in.format + " is a GPU block format mvr does not upload (it uploads ETC2, EAC R11 / RG11 unsigned "
                               "and ASTC LDR)";
        break;
    case payload::basis_etc1s:
    case payload::basis_uastc:
        return in.format + " needs a Basis Universal transcoder, which mvr does not have";
    case payload::other: return in.format + " is not a format mvr decodes (8-bit R, RG, RGB, BGR, RGBA, BGRA)";
    }
    const std::string only = ": mvr decodes 2D textures";
    if (in.depth != 0)
        return "3D texture (pixelDepth " + std::to_string(in.depth) + ")" + only;
    if (in.faces != 1)
        return "cubemap (faceCount " + std::to_string(in.faces) + ")" + only;
    if (in.one_dimensional)
        return "1D texture (pixelHeight 0)" + only;
    if (in.layers > 1)
        return "array texture of " + std::to_string(in.layers) + " layers" + only;
    if (in.supercompression == SC_ZLIB)
        return "ZLIB supercompression (scheme 3) is not decoded by mvr (none and Zstandard are)";
    if (in.supercompression != SC_NONE && in.supercompression != SC_ZSTD)
        return "supercompression scheme " + std::to_string(in.supercompression) + " is unknown to mvr";
    if (in.kind == payload::block && (in.flip_x || in.flip_y))
        return "block-compressed image stored " + std::string(in.flip_y ? "bottom row first" : "right to left") +
               " (KTXorientation): mvr uploads blocks as stored and cannot flip them";
    return "";
}

mvr_image_format block_format(const info &in)
{
    if (in.kind != payload::block)
        return MVR_IMAGE_FORMAT_RGBA8;
    switch (in.vk_format) {
    case 147: case 148: return MVR_IMAGE_FORMAT_ETC2_RGB8;
    case 149: case 150: return MVR_IMAGE_FORMAT_ETC2_RGB8_A1;
    case 151: case 152: return MVR_IMAGE_FORMAT_ETC2_RGBA8;
    case 153: return MVR_IMAGE_FORMAT_EAC_R11;
    case 155: return MVR_IMAGE_FORMAT_EAC_RG11;
    default: break;
    }
    // ASTC LDR: 157 + 2 * i (UNORM) and + 1 (SRGB), i in mvr_image_format's order
    if (in.vk_format >= 157 && in.vk_format <= 184)
        return mvr_image_format(int(MVR_IMAGE_FORMAT_ASTC_4x4) + int(in.vk_format - 157) / 2);
    return MVR_IMAGE_FORMAT_RGBA8;
}

uint32_t block_levels(const info &in)
{
    return in.level_count ? in.level_count : 1;
}

uint64_t scratch_bytes(const info &in)
{
    if (in.supercompression != SC_ZSTD || in.levels.empty())
        return 0;
    if (in.kind != payload::block)
        return in.levels[0].uncompressed;
    uint64_t sum = 0;   // each level is a checked product; a 2D chain's sum stays below 2^64 / 2
    for (uint32_t k = 0; k < block_levels(in) && k < in.levels.size(); ++k)
        sum += in.levels[k].uncompressed;
    return sum;
}

status read_blocks(const unsigned char *p, size_t n, const info &in, std::vector<mvr_image_level> *levels,
                   std::vector<std::vector<unsigned char>> *storage, std::string *why)
{
    std::string reason = unsupported_reason(in);
    if (reason.empty() && block_format(in) == MVR_IMAGE_FORMAT_RGBA8)
        reason = in.format + " is not a block format mvr keeps";
    if (!reason.empty()) {
        *why = reason;
        return status::unsupported;
    }
    uint32_t count = block_levels(in);
    levels->assign(count, mvr_image_level{nullptr, 0});
    storage->clear();
    try {
        storage->resize(count);
    } catch (const std::bad_alloc &) {
        *why = "out of memory reading KTX2 levels";
        return status::out_of_memory;
    }
    for (uint32_t k = 0; k < count; ++k) {
        const level &l = in.levels[k];
        std::string lw = "KTX2 level " + std::to_string(k);
        if (!inside(l.offset, l.length, n))
            return bad(why, lw + " is outside the file");
        if (in.supercompression == SC_NONE) {
            (*levels)[k] = mvr_image_level{p + l.offset, size_t(l.length)};
            continue;
        }
        // Zstandard: into a buffer of exactly uncompressedByteLength (the
        // block size parse() checked), which bounds what a hostile frame writes
        std::vector<unsigned char> &buf = (*storage)[k];
        try {
            buf.resize(size_t(l.uncompressed));
        } catch (const std::bad_alloc &) {
            *why = "out of memory inflating " + lw + " (" + std::to_string(l.uncompressed) + " bytes)";
            return status::out_of_memory;
        }
        size_t got = ZSTD_decompress(buf.data(), buf.size(), p + l.offset, size_t(l.length));
        if (ZSTD_isError(got))
            return bad(why, lw + "'s Zstandard data does not inflate (" + ZSTD_getErrorName(got) + ")");
        if (got != l.uncompressed)
            return bad(why, lw + "'s Zstandard data inflates to " + std::to_string(got) +
                                " bytes, the level index says " + std::to_string(l.uncompressed));
        (*levels)[k] = mvr_image_level{buf.data(), buf.size()};
    }
    return status::ok;
}

status decode(const unsigned char *p, size_t n, const info &in, unsigned char *rgba, std::string *why)
{
    std::string reason = unsupported_reason(in);
    if (reason.empty() && in.kind != payload::uncompressed8)
        reason = in.format + " is kept as GPU blocks, not decoded";
    if (!reason.empty()) {
        *why = reason;
        return status::unsupported;
    }
    const level &l = in.levels[0];
    if (!inside(l.offset, l.length, n))
        return bad(why, "KTX2 level 0 is outside the file");
    const unsigned char *src = p + l.offset;
    std::unique_ptr<unsigned char[]> inflated;
    if (in.supercompression == SC_ZSTD) {
        // one or more Zstandard frames (skippable ones skipped) that inflate
        // to exactly uncompressedByteLength (spec, 3.7.1.2); the output
        // buffer bounds what a hostile frame can write
        inflated.reset(new (std::nothrow) unsigned char[size_t(l.uncompressed)]);
        if (!inflated) {
            *why = "out of memory inflating KTX2 level 0 (" + std::to_string(l.uncompressed) + " bytes)";
            return status::out_of_memory;
        }
        size_t got = ZSTD_decompress(inflated.get(), size_t(l.uncompressed), src, size_t(l.length));
        if (ZSTD_isError(got))
            return bad(why, std::string("KTX2 level 0's Zstandard data does not inflate (") + ZSTD_getErrorName(got) +
                                ")");
        if (got != l.uncompressed)
            return bad(why, "KTX2 level 0's Zstandard data inflates to " + std::to_string(got) +
                                " bytes, the level index says " + std::to_string(l.uncompressed));
        src = inflated.get();
    }
    // layer 0, face 0: width * height texels of `components` bytes, rows
    // tightly packed (spec, 3.7); a size the level index was checked against
    const size_t w = in.width, h = in.height, c = in.components;
    for (size_t y = 0; y < h; ++y) {
        const unsigned char *row = src + (in.flip_y ? h - 1 - y : y) * w * c;
        unsigned char *o = rgba + y * w * 4;
        for (size_t x = 0; x < w; ++x, o += 4) {
            const unsigned char *t = row + (in.flip_x ? w - 1 - x : x) * c;
            // One and two channels are red and red-green, as a GPU samples
            // an R8 / R8G8 texture (missing colour channels 0, alpha 1), not
            // grey: KTX2 channels are not luminance.
            unsigned char r = t[0], g = c > 1 ? t[1] : 0, b = c > 2 ? t[2] : 0, a = c > 3 ? t[3] : 255;
            if (in.bgr)
                std::swap(r, b);
            o[0] = r;
            o[1] = g;
            o[2] = b;
            o[3] = a;
        }
    }
    return status::ok;
}

}  // namespace mvr_ktx2
