/*
 * mvr_gltf: glTF 2.0 (.gltf with external files or data URIs, .glb) into an
 * mvr_scene, through tinygltf behind a C ABI. Every index, offset, stride,
 * count and reference is checked against the real buffer sizes before it is
 * read; a bad file fails with a message naming the object, e.g.
 * "meshes[3].primitives[0].attributes.NORMAL: accessor 12 reads past the end
 * of bufferView 4". Nothing in a file can crash the loader or make it
 * allocate without bound: the caps below say how much it accepts.
 *
 * Supported: scenes, node hierarchy (TRS and matrix), every primitive mode
 * (strips, fans and loops converted), accessors of every component type,
 * normalized or not, with strides, sparse accessors, missing indices,
 * KHR_mesh_quantization; metallic-roughness materials with all texture roles,
 * samplers, TEXCOORD_0/1; perspective and orthographic cameras;
 * KHR_lights_punctual, KHR_materials_unlit, KHR_texture_transform,
 * KHR_materials_emissive_strength. Skins and morph targets draw the bind pose
 * (with a warning). A required extension outside this list is an error that
 * names it; an unknown optional one is a warning.
 */
#ifndef MVR_GLTF_H
#define MVR_GLTF_H

#include "mvr/mvr.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mvr_gltf_options {
    /* 0 = the file's default scene (or its first); k > 0 = scenes[k - 1] */
    uint32_t scene;
    /* Where a file loaded from memory finds external buffers and images;
     * NULL = external URIs are refused (data URIs and GLB chunks still work). */
    const char *base_dir;
    /* Caps; 0 = the default in brackets. */
    uint64_t max_file_bytes;        /* any file read, the glTF and each external one [1 GiB] */
    uint64_t max_vertices;          /* summed over all primitives [64 M] */
    uint64_t max_indices;           /* summed over all primitives [256 M] */
    uint32_t max_image_dimension;   /* width or height of a texture [16384] */
    uint32_t max_nodes;             /* [1 M] */
    mvr_logger logger;              /* warnings (skins, unknown optional extensions, ...) */
} mvr_gltf_options;

typedef struct mvr_gltf_info {
    uint32_t warnings;              /* how many warnings went to the logger */
    uint32_t camera_nodes;          /* nodes with a camera, in node order (mvr_scene_camera_node) */
} mvr_gltf_info;

/* Loads a .gltf or .glb file (by content, not by name). info is optional. */
mvr_result mvr_gltf_load_file(const char *path, const mvr_gltf_options *options, mvr_scene **out_scene,
                              mvr_gltf_info *info, mvr_error *out_error);

/* Loads from memory: GLB if it starts with the GLB magic, else glTF JSON. */
mvr_result mvr_gltf_load_memory(const void *data, size_t size, const mvr_gltf_options *options,
                                mvr_scene **out_scene, mvr_gltf_info *info, mvr_error *out_error);

#ifdef __cplusplus
}
#endif
#endif
