#include "fuzz_files.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "gltf_gen.hpp"

namespace fuzz {

// A textured quad: the buffer's bytes, and its JSON with the buffer's and
// the image's URIs to fill in.
struct quad {
    std::vector<uint8_t> bin;
    std::string json; // "@BUFFER@" and "@IMAGE@" stand for the URIs
};

static gen::builder quad_builder()
{
    gen::builder b;
    int pos = b.floats({-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0}, "VEC3");
    int nrm = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    int uv = b.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
    int idx = b.indices16({0, 1, 2, 0, 2, 3});
    b.add(b.meshes, "{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" +
                        std::to_string(nrm) + ",\"TEXCOORD_0\":" + std::to_string(uv) +
                        "},\"indices\":" + std::to_string(idx) + ",\"material\":0}]}");
    b.add(b.materials, "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},\"metallicFactor\":0}}");
    b.add(b.textures, "{\"source\":0,\"sampler\":0}");
    b.add(b.samplers, "{\"magFilter\":9728,\"minFilter\":9986,\"wrapS\":10497,\"wrapT\":33648}");
    b.add(b.images, "{\"uri\":\"@IMAGE@\"}");
    b.add(b.nodes, "{\"mesh\":0}");
    b.add(b.scenes, "{\"nodes\":[0]}");
    b.buffer_uri_override = "@BUFFER@";
    return b;
}

static const quad &the_quad()
{
    static const quad q = [] {
        gen::builder b = quad_builder();
        return quad{b.bin, b.json(gen::container::external_bin, "")};
    }();
    return q;
}

static std::string with_uris(std::string json, const std::string &buffer, const std::string &image)
{
    json.replace(json.find("@BUFFER@"), 8, buffer);
    json.replace(json.find("@IMAGE@"), 7, image);
    return json;
}

static std::vector<std::string> made; // files, then folders, removed at exit

static void remove_made()
{
    for (auto it = made.rbegin(); it != made.rend(); ++it)
        std::remove(it->c_str());
}

static void put(const std::string &path, const std::vector<uint8_t> &bytes)
{
    gen::write_file(path, bytes.data(), bytes.size());
    made.push_back(path);
}

static void folder(const std::string &path)
{
    if (mkdir(path.c_str(), 0700) != 0)
        throw std::runtime_error("fuzz: cannot make " + path);
    made.push_back(path);
}

const std::string &base_dir()
{
    static const std::string base = [] {
        const char *tmp = std::getenv("TMPDIR");
        std::string root = std::string(tmp && *tmp ? tmp : "/tmp") + "/mvr-fuzz-XXXXXX";
        if (!mkdtemp(&root[0]))
            throw std::runtime_error("fuzz: cannot make a folder under " + root);
        made.push_back(root);
        std::atexit(remove_made);
        std::string b = root + "/base";
        folder(b);
        folder(b + "/sub");
        std::vector<uint8_t> png = gen::checker_image("png", 16, 200, 60, 30);
        std::vector<uint8_t> jpg = gen::checker_image("jpg", 16, 30, 60, 200);
        put(b + "/a.bin", the_quad().bin);
        put(b + "/img.png", png);
        put(b + "/img.jpg", jpg);
        put(b + "/sub/b.bin", the_quad().bin);
        put(b + "/sub/x.png", png);
        put(root + "/outside.bin", the_quad().bin); // what a confined loader never reads
        put(root + "/outside.png", png);
        return b;
    }();
    return base;
}

std::vector<seed> write_seeds(const std::string &dir)
{
    std::vector<seed> seeds;
    auto json = [&](const char *name, const char *buffer, const char *image, bool inside) {
        std::string j = with_uris(the_quad().json, buffer, image);
        std::string path = dir + "/" + name + ".gltf";
        gen::write_file(path, j.data(), j.size());
        seeds.push_back({path, inside});
    };
    json("ext_inside", "a.bin", "img.png", true);
    json("ext_inside_jpeg", "a.bin", "img.jpg", true);
    json("ext_sub", "sub/b.bin", "sub/x.png", true);
    json("ext_dot", "./a.bin", "sub/../img.png", false);
    json("ext_outside", "../outside.bin", "../outside.png", false);
    json("ext_outside_encoded", "%2e%2e/outside.bin", "%2E%2E/outside.png", false);
    json("ext_outside_via_sub", "sub/../../outside.bin", "sub/%2e%2e/%2e%2e/outside.png", false);
    json("ext_outside_backslash", "..\\\\outside.bin", "sub\\\\x.png", false);
    json("ext_schemes", "file:a.bin", "http://127.0.0.1/img.png", false);
    json("ext_missing", "no.bin", "sub/no.png", false);
    {   // a GLB: the buffer in its BIN chunk, the image outside it
        gen::builder b = quad_builder();
        b.buffer_uri_override.clear();
        b.images[0] = "{\"uri\":\"img.png\"}";
        seeds.push_back({b.write(dir, "ext_glb_image", gen::container::glb), true});
    }
    return seeds;
}

}  // namespace fuzz
