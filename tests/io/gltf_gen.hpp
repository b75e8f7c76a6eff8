// A small glTF writer for the tests: builds the JSON and the binary buffer
// by hand, so broken files can be made exactly as broken as wanted.
#ifndef MVR_GLTF_GEN_HPP
#define MVR_GLTF_GEN_HPP

#include <cstdint>
#include <string>
#include <vector>

namespace gen {

enum class container { external_bin, data_uri, glb };

// A document's top-level lists, each entry the JSON of one object (lights:
// KHR_lights_punctual's; ext_*: extension names, unquoted). builder and the
// tests that assemble documents of their own (io_hostile) serialise them
// through json_members(), in one order.
struct doc_lists {
    std::vector<std::string> buffer_views, accessors, meshes, materials, textures, images, samplers, nodes,
        scenes, cameras, lights, ext_used, ext_required, skins, animations;
    int add(std::vector<std::string> &list, const std::string &json); // returns the index
};

// The members after "buffers", each only when its list is non-empty:
// ,"bufferViews":[...] ... ,"scenes":[...], ,"scene":default_scene (with
// scenes), "skins", "animations", the KHR_lights_punctual lights,
// "extensionsUsed" and "extensionsRequired" (the names as JSON strings).
std::string json_members(const doc_lists &d, int default_scene);
std::string json_array(const std::vector<std::string> &items); // [a,b,...]
std::string json_string(const std::string &s);                 // quoted, with " \ and controls escaped

struct builder : doc_lists {
    std::vector<uint8_t> bin;
    int default_scene = 0;
    std::string buffer_uri_override;   // e.g. "missing.bin"
    long long buffer_length_delta = 0; // lie about the buffer's length

    // Appends bytes (4-aligned) as a bufferView; returns its index.
    int view(const void *data, size_t n, int stride = 0);
    int accessor(int view, size_t offset, int component_type, long long count, const char *type,
                 bool normalized = false, const std::string &extra = "");
    int floats(const std::vector<float> &v, const char *type);          // view + float accessor
    int indices16(const std::vector<uint16_t> &v);
    std::string json(container c, const std::string &bin_name) const;
    // Writes name.gltf (+ name.bin) or name.glb into dir; returns the path.
    std::string write(const std::string &dir, const std::string &name, container c) const;
};

std::string base64(const uint8_t *p, size_t n);
// A size x size RGBA checker encoded as PNG or JPEG ("png" / "jpg"), through OpenImageIO.
std::vector<uint8_t> checker_image(const char *format, int size, uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255);
// A size x size image of one RGBA colour, encoded like checker_image.
std::vector<uint8_t> solid_image(const char *format, int size, uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255);
void write_file(const std::string &path, const void *data, size_t n);
std::vector<uint8_t> read_file(const std::string &path);

// Writes every feature file and every broken file into dir; returns their paths.
struct corpus {
    std::vector<std::string> features;
    struct broken { std::string path; int expected_result; std::string message_part; };
    std::vector<broken> broken_files;
    // Files that load with MVR_OK and put nothing in the image: an empty
    // scene, nodes without meshes, a camera or a light alone, zero scale
    std::vector<std::string> nothing_to_draw;
};
corpus write_corpus(const std::string &dir);

}  // namespace gen

#endif
