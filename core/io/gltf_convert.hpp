// The converter from tinygltf's model into an mvr_scene, shared by the
// loader's files: gltf_loader.cpp (meshes, nodes, cameras, lights, the load)
// and gltf_materials.cpp (materials, textures, images).
#ifndef MVR_GLTF_CONVERT_HPP
#define MVR_GLTF_CONVERT_HPP

#include <map>
#include <string>
#include <vector>

#include "gltf_internal.hpp"

namespace mvr_gltf {

// A number member of a JSON value from tinygltf (fallback when absent).
double number(const tinygltf::Value &v, const char *key, double fallback);

struct converter {
    converter(context &c, mvr_scene *s, const tinygltf::Model &model) : cx(c), scene(s), m(model) {}
    context &cx;
    mvr_scene *scene;
    const tinygltf::Model &m;
    std::map<int, mvr_image_id> images;      // glTF image -> scene image (0: left out)
    std::map<std::string, mvr_image_id> decoded;   // source (file, bufferView) -> scene image
    std::map<int, mvr_material_id> materials;
    std::map<int, mvr_mesh_id> meshes;
    std::map<int, mvr_camera_id> cameras;
    std::map<int, mvr_light_id> lights;
    bool warned_skin = false, warned_morph = false;
    bool missing_texture = false;   // set when a texture's image was left out
    // cameras and lights that failed their checks: an error only if a node uses them
    std::map<int, std::string> bad_cameras, bad_lights;

    void set_aside(const load_error &e, std::map<int, std::string> &bad, int index)
    {
        if (e.result == MVR_ERROR_OUT_OF_MEMORY)
            throw e;
        bad[index] = e.what();
        cx.warn(std::string(e.what()) + "; ignored unless a node uses it");
    }

    void check(mvr_result r, const std::string &what)
    {
        if (r != MVR_OK)
            throw load_error(r == MVR_ERROR_INVALID_ARGUMENT ? MVR_ERROR_INVALID_ASSET : r,
                             what + ": " + mvr_scene_last_error(scene));
    }

    // The scene image of images[index], decoded once (also when several
    // images name one file). A missing or undecodable image is left out
    // with a warning (id 0: its textures take the role's default) unless
    // strict; the budget is never waived.
    mvr_image_id image(int index, const std::string &what);
    mvr_texture_ref texture(const tinygltf::TextureInfo &info, const std::string &what);
    mvr_texture_ref texture_ref(int index, int texcoord, const tinygltf::ExtensionMap &ext, const std::string &what);
    mvr_material_id material(int index);
    mvr_mesh_id mesh(int index);
    void node(int index, mvr_node_id parent, std::vector<char> &state, uint32_t depth);

private:
    mvr_image_id decode_image(size_t index, const std::string &iname);
};

}  // namespace mvr_gltf

#endif
