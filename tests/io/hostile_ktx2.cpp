// KTX 2.0 files for the tests (see hostile_ktx2.hpp).
#include "hostile_ktx2.hpp"

#include <zstd.h>

#include <stdexcept>

namespace hostile {

void put_le32(std::vector<uint8_t> &b, size_t at, uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        b[at + size_t(i)] = uint8_t(v >> (8 * i));
}

void put_le64(std::vector<uint8_t> &b, size_t at, uint64_t v)
{
    for (int i = 0; i < 8; ++i)
        b[at + size_t(i)] = uint8_t(v >> (8 * i));
}

uint64_t get_le64(const std::vector<uint8_t> &b, size_t at)
{
    uint64_t v = 0;
    for (int i = 7; i >= 0; --i)
        v = v << 8 | b[at + size_t(i)];
    return v;
}

static void align(std::vector<uint8_t> &b, size_t to)
{
    while (to > 1 && b.size() % to)
        b.push_back(0);
}

static size_t lcm4(size_t n)
{
    size_t m = n ? n : 1;
    while (m % 4)
        m += n ? n : 1;
    return m;
}

std::vector<uint8_t> ktx2_file(const ktx2_desc &k)
{
    static const uint8_t id[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
    size_t nlev = k.levels.size();
    std::vector<uint8_t> b(80 + 24 * nlev, 0);
    std::copy(id, id + 12, b.begin());
    const uint32_t head[9] = {k.vk_format, k.type_size, k.width, k.height, k.depth, k.layers, k.faces,
                              k.level_count, k.supercompression};
    for (int i = 0; i < 9; ++i)
        put_le32(b, 12 + 4 * size_t(i), head[i]);
    // data format descriptor: dfdTotalSize, one basic block (Khronos Data Format 1.3, 5)
    size_t dfd = b.size();
    uint32_t block = 24 + 16 * k.channels;
    b.resize(dfd + 4 + block, 0);
    put_le32(b, dfd, 4 + block);
    put_le32(b, dfd + 4, 0);                                   // vendor 0, descriptor type 0
    put_le32(b, dfd + 8, 2u | block << 16);                    // version 2, block size
    put_le32(b, dfd + 12, uint32_t(k.color_model) | 1u << 8 | uint32_t(k.transfer) << 16);   // primaries BT709
    put_le32(b, dfd + 16, uint32_t(k.block_width - 1) | uint32_t(k.block_height - 1) << 8);
    put_le32(b, dfd + 20, k.texel_bytes);                      // bytesPlane0
    static const uint8_t channel_ids[4] = {0, 1, 2, 15};       // R, G, B, A
    for (uint32_t c = 0; c < k.channels; ++c) {
        size_t s = dfd + 28 + 16 * size_t(c);
        put_le32(b, s, (c * 8) | 7u << 16 | uint32_t(channel_ids[c & 3]) << 24);
        put_le32(b, s + 12, 255);                              // sampleUpper
    }
    put_le32(b, KTX2_DFD_OFFSET, uint32_t(dfd));
    put_le32(b, KTX2_DFD_LENGTH, 4 + block);
    // key/value data
    if (!k.orientation.empty()) {
        size_t kvd = b.size();
        std::string kv = std::string("KTXorientation") + '\0' + k.orientation + '\0';
        std::vector<uint8_t> len(4);
        put_le32(len, 0, uint32_t(kv.size()));
        b.insert(b.end(), len.begin(), len.end());
        b.insert(b.end(), kv.begin(), kv.end());
        align(b, 4);
        put_le32(b, KTX2_KVD_OFFSET, uint32_t(kvd));
        put_le32(b, KTX2_KVD_LENGTH, uint32_t(b.size() - kvd));
    }
    if (!k.sgd.empty()) {
        align(b, 8);
        put_le64(b, 64, b.size());
        put_le64(b, 72, k.sgd.size());
        b.insert(b.end(), k.sgd.begin(), k.sgd.end());
    }
    // the levels, smallest first
    size_t alignment = k.supercompression == 0 ? lcm4(k.texel_bytes) : 1;
    for (size_t p = nlev; p-- > 0;) {
        align(b, alignment);
        size_t at = ktx2_level_entry(uint32_t(p));
        put_le64(b, at, b.size());
        put_le64(b, at + 8, k.levels[p].size());
        uint64_t raw = p < k.uncompressed.size() ? k.uncompressed[p] : k.levels[p].size();
        put_le64(b, at + 16, k.supercompression == 1 ? 0 : raw);
        b.insert(b.end(), k.levels[p].begin(), k.levels[p].end());
    }
    return b;
}

void ktx2_zstd(ktx2_desc &k)
{
    k.uncompressed.clear();
    for (auto &l : k.levels) {
        std::vector<uint8_t> z(ZSTD_compressBound(l.size()));
        size_t n = ZSTD_compress(z.data(), z.size(), l.data(), l.size(), 3);
        if (ZSTD_isError(n))
            throw std::runtime_error(std::string("ZSTD_compress: ") + ZSTD_getErrorName(n));
        z.resize(n);
        k.uncompressed.push_back(l.size());
        l = std::move(z);
    }
    k.supercompression = 2;
}

ktx2_desc ktx2_from_rgba(const std::vector<uint8_t> &px, uint32_t w, uint32_t h, uint32_t vk_format, uint32_t levels)
{
    ktx2_desc k;
    k.vk_format = vk_format;
    k.width = w;
    k.height = h;
    k.level_count = levels;
    int order[4] = {0, 1, 2, 3};
    uint32_t c = 4;
    bool srgb = false;
    switch (vk_format) {
    case VK_R8_UNORM: c = 1; break;
    case VK_R8G8_UNORM: c = 2; break;
    case VK_R8G8B8_SRGB: srgb = true; /* fall through */
    case VK_R8G8B8_UNORM: c = 3; break;
    case VK_B8G8R8_UNORM: c = 3; order[0] = 2; order[2] = 0; break;
    case VK_R8G8B8A8_SRGB: srgb = true; break;
    case VK_R8G8B8A8_UNORM: break;
    case VK_B8G8R8A8_SRGB: srgb = true; order[0] = 2; order[2] = 0; break;
    default: throw std::runtime_error("ktx2_from_rgba: not an 8-bit format of the tests");
    }
    k.transfer = srgb ? 2 : 1;
    k.texel_bytes = c;
    k.channels = c;
    uint32_t stored = levels ? levels : 1;
    for (uint32_t p = 0; p < stored; ++p) {
        uint32_t lw = w >> p ? w >> p : 1, lh = h >> p ? h >> p : 1;
        std::vector<uint8_t> l(size_t(lw) * lh * c);
        for (size_t i = 0; i < size_t(lw) * lh; ++i)
            for (uint32_t j = 0; j < c; ++j) {
                static const uint8_t magenta[4] = {255, 0, 255, 255};
                l[i * c + j] = p == 0 ? px[i * 4 + size_t(order[j])] : magenta[order[j]];
            }
        k.levels.push_back(std::move(l));
    }
    return k;
}

ktx2_desc ktx2_gpu(const std::string &kind, uint32_t w, uint32_t h, uint32_t levels)
{
    ktx2_desc k;
    k.width = w;
    k.height = h;
    k.level_count = levels;
    k.block_width = k.block_height = 4;
    k.channels = 1;
    k.texel_bytes = 16;
    if (kind == "etc2") {
        k.vk_format = VK_ETC2_R8G8B8A8_SRGB;
        k.color_model = 161;   // ETC2
    } else if (kind == "eac") {
        k.vk_format = VK_EAC_R11_UNORM;
        k.color_model = 161;
        k.texel_bytes = 8;
        k.transfer = 1;
    } else if (kind == "astc") {
        k.vk_format = VK_ASTC_4x4_SRGB;
        k.color_model = 162;   // ASTC
    } else if (kind == "bc7") {
        k.vk_format = VK_BC7_UNORM;
        k.color_model = 134;   // BC7
        k.transfer = 1;
    } else if (kind == "etc1s") {
        k.vk_format = 0;
        k.color_model = 163;
        k.supercompression = 1;
        k.texel_bytes = 8;
        k.sgd.assign(64, 0x5A);   // stands in for the codebooks (never read)
    } else if (kind == "uastc" || kind == "uastc_zstd") {
        k.vk_format = 0;
        k.color_model = 166;
    } else {
        throw std::runtime_error("ktx2_gpu: unknown kind " + kind);
    }
    uint32_t stored = levels ? levels : 1;
    for (uint32_t p = 0; p < stored; ++p) {
        uint32_t lw = w >> p ? w >> p : 1, lh = h >> p ? h >> p : 1;
        size_t blocks = size_t((lw + 3) / 4) * ((lh + 3) / 4);
        // BasisLZ: an opaque slice of any length; the others: whole blocks
        k.levels.push_back(std::vector<uint8_t>(kind == "etc1s" ? 24 : blocks * k.texel_bytes, uint8_t(0x40 + p)));
    }
    if (kind == "uastc_zstd")
        ktx2_zstd(k);
    return k;
}

}  // namespace hostile
