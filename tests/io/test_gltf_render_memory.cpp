// io_gltf_render_memory: what rendering a scene will allocate is charged to
// the load's memory budget at load, before anything is allocated for it:
// - morph targets, as the RGBA32F delta texels gl/skinning.c uploads
//   (vertices x targets x attributes x 16 bytes), counted from the JSON, so
//   sparse targets without data are charged for what they expand to: a file
//   of a few KB whose targets expand to gigabytes is refused at once, with
//   a message naming the targets and the budget, and the process's peak RSS
//   stays small (it used to load, holding 1.5 GB, and ask for 2.7 GB more
//   when rendered);
// - block-compressed images as decoded for upload (width x height x 4 per
//   level, what Mesa holds for ASTC it cannot sample): a few KB of
//   Zstandard-compressed ASTC that decodes to 64 MiB is charged 64 MiB.
#include <sys/resource.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "gltf_gen.hpp"
#include "hostile_ktx2.hpp"
#include "mvr/mvr_gltf.h"
#include "mvr_test.h"

namespace {

const uint64_t MiB = 1u << 20;

long max_rss_kb()
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

struct loaded {
    mvr_result r = MVR_ERROR_INTERNAL;
    std::string msg;
    mvr_scene *scene = nullptr;
    mvr_gltf_info info = {};
    long rss_growth_kb = 0;
    loaded(const std::string &json, uint64_t budget)
    {
        mvr_gltf_options o;
        std::memset(&o, 0, sizeof o);
        o.memory_budget = budget;
        mvr_error err = {};
        long rss0 = max_rss_kb();
        r = mvr_gltf_load_memory(json.data(), json.size(), &o, &scene, &info, &err);
        rss_growth_kb = max_rss_kb() - rss0;
        msg = r == MVR_OK ? "" : err.message;
    }
    loaded(const loaded &) = delete;
    loaded &operator=(const loaded &) = delete;
    ~loaded() { mvr_scene_destroy(scene); }
    bool has(const char *part) const { return msg.find(part) != std::string::npos; }
};

std::string data_uri(const std::vector<uint8_t> &b, const char *mime = "application/octet-stream")
{
    return std::string("data:") + mime + ";base64," + gen::base64(b.data(), b.size());
}

// `vertices` points, all at the origin (POSITION without a bufferView), and
// `targets` morph targets that all name one sparse POSITION accessor without
// a bufferView: one delta (1, 0, 0) at vertex 0, the rest zeros.
std::string sparse_morph_file(uint32_t vertices, uint32_t targets)
{
    std::vector<uint8_t> bin(16, 0);
    const float delta[3] = {1, 0, 0};
    std::memcpy(bin.data() + 4, delta, sizeof delta);   // index 0 (uint32) at 0, the delta at 4
    std::string v = std::to_string(vertices), list;
    for (uint32_t t = 0; t < targets; ++t)
        list += std::string(t ? "," : "") + "{\"POSITION\":1}";
    return "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":16,\"uri\":\"" + data_uri(bin) +
           "\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":4},{\"buffer\":0,\"byteOffset\":4,\"byteLength\":12}],"
           "\"accessors\":[{\"componentType\":5126,\"count\":" + v + ",\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[0,0,0]},"
           "{\"componentType\":5126,\"count\":" + v + ",\"type\":\"VEC3\",\"sparse\":{\"count\":1,\"indices\":"
           "{\"bufferView\":0,\"componentType\":5125},\"values\":{\"bufferView\":1}}}],"
           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"mode\":0,\"targets\":[" + list +
           "]}]}],\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}";
}

void sparse_morph_targets_charged_for_their_expansion(mvr_test_state *t)
{
    // 1 M vertices x 64 targets: 64 M delta texels, 1 GiB on the GPU; 2 GiB
    // with the copies reading them holds. Refused before they are read.
    std::string file = sparse_morph_file(1u << 20, 64);
    CHECK_MSG(t, file.size() < 4096, "the file is %zu bytes", file.size());
    {
        loaded l(file, 0);
        CHECK_MSG(t, l.r == MVR_ERROR_OUT_OF_MEMORY && l.has("meshes[0].primitives[0].targets") &&
                         l.has("memory_budget") && l.has("2048.0 MiB"),
                  "64 sparse targets of 1 M vertices: %s %s", mvr_result_name(l.r), l.msg.c_str());
        CHECK(t, l.scene == nullptr);
        CHECK_MSG(t, l.rss_growth_kb < 64 * 1024, "peak RSS grew by %ld KB", l.rss_growth_kb);
    }
    // a tighter budget refuses fewer targets: 8 targets of 256 k vertices
    // are 2 M texels, 32 MiB on the GPU (the reading alone fit 64 MiB before)
    {
        loaded l(sparse_morph_file(1u << 18, 8), 64 * MiB);
        CHECK_MSG(t, l.r == MVR_ERROR_OUT_OF_MEMORY && l.has("meshes[0].primitives[0].targets") &&
                         l.has("memory_budget"),
                  "8 sparse targets of 256 k vertices, 64 MiB: %s %s", mvr_result_name(l.r), l.msg.c_str());
        CHECK_MSG(t, l.rss_growth_kb < 64 * 1024, "peak RSS grew by %ld KB", l.rss_growth_kb);
    }
    // one target of 1 M vertices loads; its 16 MiB of GPU deltas are in the peak
    {
        loaded l(sparse_morph_file(1u << 20, 1), 0);
        CHECK_MSG(t, l.r == MVR_OK, "one sparse target: %s", l.msg.c_str());
        CHECK_MSG(t, l.info.memory_peak >= (1u << 20) * uint64_t(16 + 24), "peak %llu",
                  (unsigned long long)l.info.memory_peak);
        if (l.scene) {
            mvr_scene_info si;
            mvr_scene_get_info(l.scene, &si);
            CHECK_EQ_INT(t, si.morph_targets, 1);
        }
        // and just under that peak it is refused, naming the mesh
        loaded under(sparse_morph_file(1u << 20, 1), l.info.memory_peak - 1);
        CHECK_MSG(t, under.r == MVR_ERROR_OUT_OF_MEMORY && under.has("meshes[0]") && under.has("memory_budget"),
                  "one sparse target under its peak: %s %s", mvr_result_name(under.r), under.msg.c_str());
    }
}

// A triangle textured by a 4096 x 4096 ASTC 4x4 KTX2 (16 MiB of blocks,
// Zstandard-compressed to a few KB of filler) as a data URI.
std::string astc_file()
{
    hostile::ktx2_desc k = hostile::ktx2_gpu("astc", 4096, 4096, 1);
    hostile::ktx2_zstd(k);
    std::vector<uint8_t> ktx = hostile::ktx2_file(k);
    std::vector<uint8_t> bin(36 + 24, 0);
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, uv[6] = {0, 0, 1, 0, 0, 1};
    std::memcpy(bin.data(), pos, sizeof pos);
    std::memcpy(bin.data() + 36, uv, sizeof uv);
    return "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_texture_basisu\"],"
           "\"buffers\":[{\"byteLength\":60,\"uri\":\"" + data_uri(bin) + "\"}],"
           "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":24}],"
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],"
           "\"max\":[1,1,0]},{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}],"
           "\"images\":[{\"uri\":\"" + data_uri(ktx, "image/ktx2") + "\",\"mimeType\":\"image/ktx2\"}],"
           "\"textures\":[{\"extensions\":{\"KHR_texture_basisu\":{\"source\":0}}}],"
           "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},\"material\":0}]}],"
           "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}";
}

void compressed_images_charged_as_decoded(mvr_test_state *t)
{
    std::string file = astc_file();
    CHECK_MSG(t, file.size() < 64 * 1024, "the file is %zu bytes", file.size());
    const uint64_t decoded = 4096ull * 4096 * 4, blocks = 4096ull * 4096;
    loaded l(file, 0);
    CHECK_MSG(t, l.r == MVR_OK && l.info.images_decoded == 1, "ASTC 4096^2: %s %s (%u decoded)", mvr_result_name(l.r),
              l.msg.c_str(), l.info.images_decoded);
    // held together at the end: the scene's blocks and the decoded texels
    CHECK_MSG(t, l.info.memory_peak >= decoded + blocks, "peak %.1f MiB, expected >= %.1f",
              double(l.info.memory_peak) / MiB, double(decoded + blocks) / MiB);
    // a budget that holds the blocks but not their decoding refuses the image by name
    loaded small(file, 72 * MiB);
    CHECK_MSG(t, small.r == MVR_ERROR_OUT_OF_MEMORY && small.has("images[0]") && small.has("decoded to RGBA8") &&
                     small.has("memory_budget"),
              "ASTC 4096^2 in 72 MiB: %s %s", mvr_result_name(small.r), small.msg.c_str());
}

}  // namespace

MVR_TEST_MAIN(TEST(sparse_morph_targets_charged_for_their_expansion), TEST(compressed_images_charged_as_decoded))
