// io_hostile's KTX2 container files and their case (see hostile_ktx2_files.hpp).
#include "hostile_ktx2_files.hpp"

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "hostile_check.hpp"
#include "hostile_docs.hpp"
#include "hostile_ktx2.hpp"

namespace hostile {

// KTX2 containers (core/io/ktx2.cpp): a valid one, and each field of the
// header, the index, the DFD, the key/value data and the levels made to lie
// (offsets and lengths past the end or wrapping around 2^64, counts, sizes
// that do not match the format, Zstandard frames that inflate to other
// sizes, a decompression bomb); and valid shapes mvr does not decode.
void ktx2_files(files &f)
{
    std::vector<uint8_t> px(8 * 8 * 4);
    for (size_t i = 0; i < px.size(); i += 4)
        px[i] = 250, px[i + 1] = 140, px[i + 2] = 20, px[i + 3] = 255;   // orange
    const ktx2_desc base = ktx2_from_rgba(px, 8, 8, VK_R8G8B8A8_SRGB, 4);
    const std::vector<uint8_t> valid = ktx2_file(base);
    auto put = [&](const std::string &name, const std::vector<uint8_t> &bytes, const std::string &what,
                   const std::string &expect) {
        write_bytes(f.asset + "/" + name + ".ktx2", bytes.data(), bytes.size());
        f.text(name + ".gltf", textured_doc("{\"uri\":\"" + name + ".ktx2\",\"mimeType\":\"image/ktx2\"}").json(),
               what, expect);
    };
    const std::string left_out = "loads, images[0] left out with a warning; strict: refused naming images[0]";
    auto edited = [&](const std::string &name, const std::string &what,
                      const std::function<void(std::vector<uint8_t> &)> &edit) {
        std::vector<uint8_t> b = valid;
        edit(b);
        put(name, b, what, left_out);
    };
    auto dfd_of = [](const std::vector<uint8_t> &b) { return size_t(b[KTX2_DFD_OFFSET]) | size_t(b[KTX2_DFD_OFFSET + 1]) << 8; };
    put("ktx2_valid", valid, "an 8x8 orange RGBA8 KTX2 with 4 levels", "loads, decoded, orange");
    put("ktx2_short_header", std::vector<uint8_t>(valid.begin(), valid.begin() + 40), "the first 40 bytes of a KTX2",
        left_out);
    edited("ktx2_level_past_end", "level 0's byteLength reaches past the end", [](std::vector<uint8_t> &b) {
        put_le64(b, ktx2_level_entry(0) + 8, b.size());
        put_le64(b, ktx2_level_entry(0) + 16, b.size());
    });
    edited("ktx2_level_offset_wraps", "level 0 at offset 2^64 - 16, 256 bytes (the sum wraps)",
           [](std::vector<uint8_t> &b) { put_le64(b, ktx2_level_entry(0), ~uint64_t(0) - 15); });
    edited("ktx2_level_count_huge", "levelCount 0xFFFFFFFF",
           [](std::vector<uint8_t> &b) { put_le32(b, KTX2_LEVEL_COUNT, 0xFFFFFFFFu); });
    put("ktx2_level_index_past_end", std::vector<uint8_t>(valid.begin(), valid.begin() + 100),
        "levelCount 4, the file ends inside the level index", left_out);
    edited("ktx2_dfd_outside", "dfdByteOffset 0xFFFFFFF0",
           [](std::vector<uint8_t> &b) { put_le32(b, KTX2_DFD_OFFSET, 0xFFFFFFF0u); });
    edited("ktx2_dfd_total_mismatch", "dfdTotalSize differs from dfdByteLength",
           [&](std::vector<uint8_t> &b) { put_le32(b, dfd_of(b), 0x7FFFFFFFu); });
    edited("ktx2_dfd_block_too_big", "the descriptor block's size runs past the DFD",
           [&](std::vector<uint8_t> &b) { put_le32(b, dfd_of(b) + 8, 2u | 0xFFFCu << 16); });
    {
        ktx2_desc k = base;
        k.orientation = "rd";
        std::vector<uint8_t> b = ktx2_file(k);
        size_t kvd = size_t(b[KTX2_KVD_OFFSET]) | size_t(b[KTX2_KVD_OFFSET + 1]) << 8;
        std::vector<uint8_t> runaway = b, no_nul = b;
        put_le32(runaway, kvd, 0xFFFFFFF0u);
        for (size_t i = kvd + 4; i < kvd + 4 + 18; ++i)
            no_nul[i] = 'K';
        put("ktx2_kvd_runaway", runaway, "a key/value pair of 0xFFFFFFF0 bytes", left_out);
        put("ktx2_kvd_no_nul", no_nul, "a key without its NUL", left_out);
    }
    edited("ktx2_sgd_outside", "supercompression global data at 2^63", [](std::vector<uint8_t> &b) {
        put_le64(b, 64, uint64_t(1) << 63);
        put_le64(b, 72, 16);
    });
    edited("ktx2_level_size_lie", "level 0 holds 16 bytes for 8x8 RGBA8 (256)", [](std::vector<uint8_t> &b) {
        put_le64(b, ktx2_level_entry(0) + 8, 16);
        put_le64(b, ktx2_level_entry(0) + 16, 16);
    });
    edited("ktx2_faces_3", "faceCount 3", [](std::vector<uint8_t> &b) { put_le32(b, 36, 3); });
    edited("ktx2_height0_depth", "pixelHeight 0 with pixelDepth 5", [](std::vector<uint8_t> &b) {
        put_le32(b, 24, 0);
        put_le32(b, 28, 5);
    });
    edited("ktx2_width0", "pixelWidth 0", [](std::vector<uint8_t> &b) { put_le32(b, 20, 0); });
    edited("ktx2_basislz_rgba8", "BasisLZ supercompression of VK_FORMAT_R8G8B8A8_SRGB",
           [](std::vector<uint8_t> &b) { put_le32(b, 44, 1); });
    {
        // 100000 x 100000 RGBA8 whose level index claims the 40 GB it would take
        ktx2_desc k = base;
        k.width = k.height = 100000;
        k.level_count = 1;
        k.levels.resize(1);
        std::vector<uint8_t> b = ktx2_file(k);
        put_le64(b, ktx2_level_entry(0) + 8, uint64_t(100000) * 100000 * 4);
        put_le64(b, ktx2_level_entry(0) + 16, uint64_t(100000) * 100000 * 4);
        put("ktx2_dims_huge", b, "100000x100000 RGBA8, level 0 claims 40 GB", left_out);
    }
    // Zstandard: frames of other sizes, garbage, a bomb
    auto zstd_level = [&](size_t raw_bytes, uint32_t w, uint32_t h, uint64_t claim) {
        ktx2_desc k = base;
        k.width = w;
        k.height = h;
        k.level_count = 1;
        k.levels.assign(1, std::vector<uint8_t>(raw_bytes, 7));
        ktx2_zstd(k);
        k.uncompressed[0] = claim;
        return ktx2_file(k);
    };
    put("ktx2_zstd_short", zstd_level(100, 8, 8, 256), "8x8 RGBA8 whose Zstandard level inflates to 100 of 256 bytes",
        left_out);
    put("ktx2_zstd_long", zstd_level(4096, 8, 8, 256), "8x8 RGBA8 whose Zstandard level inflates to 4096 of 256 bytes",
        left_out);
    {
        ktx2_desc k = base;
        k.level_count = 1;
        k.levels.assign(1, std::vector<uint8_t>(300));
        for (size_t i = 0; i < 300; ++i)
            k.levels[0][i] = uint8_t(i * 37 + 11);
        k.supercompression = 2;
        k.uncompressed = {256};
        put("ktx2_zstd_garbage", ktx2_file(k), "8x8 RGBA8, a Zstandard level of 300 bytes that are no frame", left_out);
    }
    put("ktx2_zstd_bomb_16k", zstd_level(1024, 16384, 16384, uint64_t(16384) * 16384 * 4),
        "16384x16384 RGBA8 (1 GiB) in a Zstandard frame that inflates to 1 KB",
        "OUT_OF_MEMORY naming images[0] (64 MiB and default budgets), never allocated");
    put("ktx2_zstd_over_cap", zstd_level(1024, 20000, 20000, uint64_t(20000) * 20000 * 4),
        "20000x20000 RGBA8 (over max_image_dimension) in a small Zstandard frame", left_out);
    // valid containers of shapes and formats mvr does not decode: left out as unsupported
    auto shape = [&](const std::string &name, const std::string &what, const std::function<void(ktx2_desc &)> &edit,
                     size_t level_bytes) {
        ktx2_desc k = base;
        k.level_count = 1;
        k.levels.assign(1, std::vector<uint8_t>(level_bytes, 9));
        edit(k);
        put(name, ktx2_file(k), what, left_out);
    };
    shape("ktx2_cubemap", "a valid cubemap", [](ktx2_desc &k) { k.faces = 6; }, 8 * 8 * 4 * 6);
    shape("ktx2_3d", "a valid 3D texture (depth 2)", [](ktx2_desc &k) { k.depth = 2; }, 8 * 8 * 4 * 2);
    shape("ktx2_array", "a valid array texture of 3 layers", [](ktx2_desc &k) { k.layers = 3; }, 8 * 8 * 4 * 3);
    shape("ktx2_rgba16f", "VK_FORMAT_R16G16B16A16_SFLOAT",
          [](ktx2_desc &k) { k.vk_format = VK_R16G16B16A16_SFLOAT, k.type_size = 2, k.texel_bytes = 8; }, 8 * 8 * 8);

    // GPU block payloads mvr keeps as blocks (ETC2, ASTC), each made to lie
    const ktx2_desc etc2 = ktx2_gpu("etc2", 8, 8, 4);   // 8x8 ETC2 RGBA8: 64, 16, 16, 16 bytes
    const std::vector<uint8_t> etc2_valid = ktx2_file(etc2);
    put("ktx2_etc2_truncated", std::vector<uint8_t>(etc2_valid.begin(), etc2_valid.end() - 10),
        "an 8x8 ETC2 KTX2 with 4 levels, its last 10 bytes (of level 0) cut", left_out);
    {
        std::vector<uint8_t> b = etc2_valid;   // level 1 (4x4: one 16-byte block) says 8
        put_le64(b, ktx2_level_entry(1) + 8, 8);
        put_le64(b, ktx2_level_entry(1) + 16, 8);
        put("ktx2_etc2_level_size_lie", b, "8x8 ETC2 whose level 1 holds 8 bytes (one block is 16)", left_out);
    }
    {
        std::vector<uint8_t> b = etc2_valid;   // 65536 x 65536: 4 GiB of blocks claimed
        put_le32(b, 20, 65536);
        put_le32(b, 24, 65536);
        put_le32(b, KTX2_LEVEL_COUNT, 1);
        put_le64(b, ktx2_level_entry(0) + 8, uint64_t(16384) * 16384 * 16);
        put_le64(b, ktx2_level_entry(0) + 16, uint64_t(16384) * 16384 * 16);
        put("ktx2_etc2_dims_huge", b, "65536x65536 ETC2, level 0 claims its 4 GiB", left_out);
    }
    {
        std::vector<uint8_t> b = etc2_valid;
        put_le32(b, KTX2_LEVEL_COUNT, 5);
        put("ktx2_etc2_levels_beyond_log2", b, "8x8 ETC2 with levelCount 5 (log2(8) + 1 = 4)", left_out);
    }
    {
        ktx2_desc k = etc2;   // Zstandard level 2 inflates to 8 of its 16 bytes
        k.levels[2].resize(8);
        ktx2_zstd(k);
        k.uncompressed[2] = 16;
        put("ktx2_etc2_zstd_short", ktx2_file(k), "8x8 ETC2, Zstandard level 2 inflates to 8 of 16 bytes", left_out);
    }
    {
        ktx2_desc k = etc2;
        k.orientation = "ru";
        put("ktx2_etc2_bottom_up", ktx2_file(k), "8x8 ETC2 stored bottom row first (KTXorientation ru)", left_out);
    }
    {
        ktx2_desc k = ktx2_gpu("astc", 8, 8, 1);   // sized for 4x4 blocks (4 blocks), declared 6x6 (also 4 blocks)...
        k.vk_format = 165;                         // VK_FORMAT_ASTC_6x6_UNORM_BLOCK
        k.levels[0].resize(16 * 3);                // ... so 3 blocks is a lie
        put("ktx2_astc_6x6_size_lie", ktx2_file(k), "8x8 ASTC 6x6 whose level 0 holds 3 blocks (it needs 4)", left_out);
    }
}

// KTX2 containers (the ktx2_* files above): every lie in
// the header, index, DFD, key/value data or levels leaves the image out
// (a warning naming images[0], the untextured picture) and is refused when
// strict; nothing is read out of bounds (the sanitizer build) and nothing
// large is allocated before the budget allows it.
void ktx2_containers_are_checked(mvr_test_state *t)
{
    const files &f = F();
    {
        outcome o = load(t, f.path("ktx2_valid.gltf"), defaults());
        CHECK_MSG(t, o.r == MVR_OK && o.info.images_decoded == 1 && o.warnings.empty(), "ktx2_valid: %s, decoded %u",
                  o.msg.c_str(), o.info.images_decoded);
        size_t orange = count_pixels(render(t, o.scene, "ktx2_valid"),
                                     [](const uint8_t *p) { return p[0] > 240 && p[1] > 120 && p[1] < 160 && p[2] < 40; });
        CHECK_MSG(t, orange > 200, "ktx2_valid: %zu orange pixels", orange);
    }
    const char *left_out[] = {
        "ktx2_short_header.gltf",    "ktx2_level_past_end.gltf",  "ktx2_level_offset_wraps.gltf",
        "ktx2_level_count_huge.gltf", "ktx2_level_index_past_end.gltf", "ktx2_dfd_outside.gltf",
        "ktx2_dfd_total_mismatch.gltf", "ktx2_dfd_block_too_big.gltf", "ktx2_kvd_runaway.gltf",
        "ktx2_kvd_no_nul.gltf",      "ktx2_sgd_outside.gltf",     "ktx2_level_size_lie.gltf",
        "ktx2_faces_3.gltf",         "ktx2_height0_depth.gltf",   "ktx2_width0.gltf",
        "ktx2_basislz_rgba8.gltf",   "ktx2_dims_huge.gltf",       "ktx2_zstd_short.gltf",
        "ktx2_zstd_long.gltf",       "ktx2_zstd_garbage.gltf",    "ktx2_zstd_over_cap.gltf",
        "ktx2_cubemap.gltf",         "ktx2_3d.gltf",              "ktx2_array.gltf",
        "ktx2_rgba16f.gltf",         "ktx2_etc2_truncated.gltf",  "ktx2_etc2_level_size_lie.gltf",
        "ktx2_etc2_dims_huge.gltf",  "ktx2_etc2_levels_beyond_log2.gltf", "ktx2_etc2_zstd_short.gltf",
        "ktx2_etc2_bottom_up.gltf",  "ktx2_astc_6x6_size_lie.gltf"};
    for (const char *n : left_out) {
        outcome o = load(t, f.path(n), defaults());
        left_out_and_clean(t, o, n);
        CHECK_MSG(t, o.ms < 2000, "%s: %.0f ms", n, o.ms);
        CHECK_MSG(t, o.rss_growth_kb < 64 * 1024, "%s: peak RSS grew by %ld KB", n, o.rss_growth_kb);
        outcome s = load(t, f.path(n), strict(), (std::string(n) + " strict").c_str());
        CHECK_MSG(t, (s.r == MVR_ERROR_INVALID_ASSET || s.r == MVR_ERROR_UNSUPPORTED) && has(s.msg, "images[0]"),
                  "%s strict: %s %s", n, mvr_result_name(s.r), s.msg.c_str());
    }
    // the bomb: 1 GiB declared, a frame of 1 KB; refused before the level is inflated
    for (uint64_t b : {64 * MiB, uint64_t(0)}) {
        for (bool st : {false, true}) {
            mvr_gltf_options o = b ? budget(b) : defaults();
            o.strict = st;
            std::string label = std::string("ktx2_zstd_bomb_16k") + (b ? " 64M" : " default") + (st ? " strict" : "");
            outcome r = load(t, f.path("ktx2_zstd_bomb_16k.gltf"), o, label.c_str());
            CHECK_MSG(t, r.r == MVR_ERROR_OUT_OF_MEMORY && has(r.msg, "memory_budget") && has(r.msg, "images[0]"),
                      "%s: %s %s", label.c_str(), mvr_result_name(r.r), r.msg.c_str());
            CHECK_MSG(t, r.rss_growth_kb < 200 * 1024, "%s: peak RSS grew by %ld KB", label.c_str(), r.rss_growth_kb);
        }
    }
}

}  // namespace hostile
