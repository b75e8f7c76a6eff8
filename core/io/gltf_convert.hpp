// The converter from tinygltf's model into an mvr_scene, shared by the
// loader's files: gltf_loader.cpp (meshes, nodes, cameras, lights, the load),
// gltf_materials.cpp (materials, textures, images) and gltf_animation.cpp
// (skinning attributes, morph targets, skins, node weights, animations).
#ifndef MVR_GLTF_CONVERT_HPP
#define MVR_GLTF_CONVERT_HPP

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "gltf_internal.hpp"

namespace mvr_ktx2 {
struct info;
}

namespace mvr_gltf {

struct image_ahead;   // gltf_image_ahead.hpp

// A number member of a JSON value from tinygltf (fallback when absent).
double number(const tinygltf::Value &v, const char *key, double fallback);

// One morph target's deltas as read (empty: the target has none of that attribute).
struct morph_data {
    std::vector<float> pos, nrm, tan;
};

// A primitive as read, before it becomes an mvr_primitive_desc.
struct prim_data {
    std::vector<float> pos, nrm, tan, uv0, uv1, col;
    std::vector<uint32_t> idx;
    mvr_primitive_mode mode = MVR_PRIMITIVE_TRIANGLES;
    mvr_material_id material = {0};
    std::vector<uint16_t> joints0, joints1;   // 4 per vertex each
    std::vector<float> weights0, weights1;
    std::vector<morph_data> targets;
    std::vector<float> zeros;                 // deltas of targets lacking an attribute other targets move
    std::vector<mvr_morph_target_desc> target_descs;
    size_t source = 0;                        // its index in the glTF mesh's primitives
    std::vector<mvr_variant_mapping> variant_maps;   // KHR_materials_variants
};

// What the rest of the load needs to know about a glTF mesh once read.
struct mesh_facts {
    uint32_t targets = 0;          // morph targets (every primitive has as many)
    int max_joint = -1;            // the largest joint index its JOINTS_n name (-1: none)
    std::string joint_attr;        // the attribute naming it, for messages
};

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
    std::map<int, mesh_facts> mesh_info;     // every glTF mesh mesh() was asked for
    std::vector<mvr_node_id> node_ids;       // glTF node -> scene node ({0}: not in the loaded scene)
    std::vector<std::pair<int, mvr_node_id>> skinned;   // nodes with a skin and something to draw
    std::map<int, mvr_skin_id> skin_ids;
    std::map<int, uint32_t> skin_joint_counts;
    bool warned_joints2 = false, warned_target_attr = false, warned_target_dropped = false;
    std::set<std::string> warned_paths;      // unknown animation paths, each warned once
    bool missing_texture = false;   // set when a texture's image was left out
    struct image_failure {
        mvr_result result;
        std::string message;
        bool warned, noted;   // warned (no fallback) / noted (fallback used), each once
    };
    std::map<int, image_failure> failed_images;   // images left out, and why
    std::map<uint32_t, uint8_t> block_transfer;   // scene image of GPU blocks -> its KTX2 DFD transfer function
    // images decoded in parallel when the first image is needed (null: none)
    std::shared_ptr<image_ahead> ahead;
    bool ahead_tried = false;
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
    // with a warning, once per image (id 0: its textures take the role's
    // default, or the fallback) unless strict; the budget is never waived.
    // fallback: the image tried next ("" = none), for messages; an image
    // mvr cannot decode (MVR_ERROR_UNSUPPORTED) with a fallback is no warning.
    mvr_image_id image(int index, const std::string &what, const std::string &fallback = std::string());
    mvr_texture_ref texture(const tinygltf::TextureInfo &info, const std::string &what);
    mvr_texture_ref texture_ref(int index, int texcoord, const tinygltf::ExtensionMap &ext, const std::string &what);
    mvr_material_id material(int index);
    // gltf_material_ext.cpp: the PBR extensions of material g (w names it) into d
    void pbr_extensions(const tinygltf::Material &g, const std::string &w, mvr_material_desc &d);
    // a textureInfo inside an extension's JSON (ext.key; absent: no texture);
    // scale: a normalTextureInfo's scale where wanted
    mvr_texture_ref texture_value(const tinygltf::Value &ext, const char *key, const std::string &what,
                                  float *scale = nullptr);
    // KHR_materials_variants: the root's variants into the scene (before
    // any mesh); a primitive's mappings, checked (each variant exists and is
    // mapped once, each material exists), their materials converted.
    void variants();
    std::vector<mvr_variant_mapping> variant_mappings(int mesh, int prim, const std::string &pw);
    mvr_mesh_id mesh(int index);
    void node(int index, mvr_node_id parent, std::vector<char> &state, uint32_t depth);

    // gltf_tangents.cpp
    // Tangents for d where p has a normal map, NORMAL and the map's TEXCOORD
    // but no TANGENT (glTF 2.0 3.7.2.1: MikkTSpace), else nothing.
    void generated_tangents(const tinygltf::Primitive &p, const std::string &pw, prim_data &d);

    // gltf_animation.cpp
    // JOINTS_n / WEIGHTS_n of primitive p (vcount vertices) into d; facts
    // records the largest joint index.
    void skin_attributes(const tinygltf::Primitive &p, const std::string &pw, size_t vcount, prim_data &d,
                         mesh_facts &facts);
    // p's morph targets into d (and d.target_descs, pointing into d).
    void morph_targets(const tinygltf::Primitive &p, const std::string &pw, size_t vcount, prim_data &d);
    // mesh.weights, checked against its target count (empty: none given).
    std::vector<float> mesh_weights(const tinygltf::Mesh &g, const std::string &w, uint32_t targets);
    // node.weights of the node just added as `id`.
    void node_weights(int index, mvr_node_id id);
    // After every node of the scene is added: the skins nodes use, then
    // every animation.
    void skins();
    void animations();

private:
    mvr_image_id decode_image(size_t index, const std::string &iname);
    mvr_image_id add_blocks(const unsigned char *bytes, size_t size, const mvr_ktx2::info &info, size_t index,
                            const std::string &iname, const std::string &key);
    // a debug note where a KTX2 of GPU blocks says sRGB (or linear) and the
    // role it is used in says otherwise (the role decides)
    void note_transfer(const mvr_material_desc &d, const std::string &w);
};

}  // namespace mvr_gltf

#endif
