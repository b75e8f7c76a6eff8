/*
 * mvr_gltf: glTF 2.0 (.gltf with external files or data URIs, .glb) into an
 * mvr_scene, through tinygltf behind a C ABI. Every index, offset, stride,
 * count and reference is checked against the real buffer sizes before it is
 * read; a bad file fails with a message naming the object, e.g.
 * "meshes[3].primitives[0].attributes.NORMAL: accessor 12 reads past the end
 * of bufferView 4". Messages quote at most 80 characters of any value from
 * the file.
 *
 * Untrusted files are normal input:
 * - File access: every URI in the file (buffers, images) goes through one
 *   resolver. It percent-decodes the URI and reads it relative to the glTF's
 *   folder (or options.base_dir); it refuses absolute paths, any scheme but
 *   data:, ".." (or a symbolic link) that leaves the folder, and never
 *   searches the current directory. A caller can widen this, never narrow it
 *   by accident: file_access.allowed_root also admits files below another
 *   folder, file_access.read replaces file reads altogether. mvr reads every
 *   byte itself (tinygltf only parses the JSON); images are decoded from
 *   those bytes, the decoder chosen from their signature (checked against the
 *   declared mimeType), never from a name's extension. A message about a
 *   refused URI says nothing about files outside the folder.
 * - Memory: one budget per load (memory_budget, default 2 GiB) counts the
 *   file bytes, the parsed JSON (estimated from its token count before it is
 *   parsed), external and data-URI buffers, decoded image bytes (from the
 *   image header, before decoding) and the vertex and index data, each before
 *   it is allocated, and what rendering the scene will allocate (morph target
 *   deltas, 16 bytes per vertex, target and attribute, counted before any
 *   target is read; images as uploaded, block-compressed ones decoded to
 *   RGBA8); what exceeds it fails with MVR_ERROR_OUT_OF_MEMORY and a
 *   message naming the object. Only buffers and images the scene uses are
 *   read, each once (two images or buffers naming the same file share one
 *   read and one decode).
 * - GLB framing is checked by mvr: every chunk inside the file and 4-byte
 *   aligned, the JSON chunk first, the BIN chunk bound to buffer 0 only.
 * - Images that are missing or cannot be decoded degrade: their textures
 *   take the role's default (white, flat normal, no emission), a warning
 *   names them and info.images_missing counts them; options.strict makes
 *   them errors.
 *
 * Supported: scenes, node hierarchy (TRS and matrix), every primitive mode
 * (strips, fans and loops converted), accessors of every component type,
 * normalized or not, with strides, sparse accessors, accessors without a
 * bufferView (zeros), missing indices, KHR_mesh_quantization;
 * metallic-roughness materials with all texture roles, samplers,
 * TEXCOORD_0/1; perspective and orthographic cameras; KHR_lights_punctual,
 * KHR_materials_unlit, KHR_texture_transform, KHR_materials_emissive_strength,
 * KHR_materials_ior, KHR_materials_specular and KHR_materials_clearcoat (their
 * factors; their textures are warned about once and not sampled);
 * KHR_materials_variants (the variants, in file order, and each primitive's
 * mappings: mvr_scene_select_variant; a mapping naming a variant or material
 * that does not exist, or a variant twice in one primitive, is refused);
 * skins (JOINTS_0/1 + WEIGHTS_0/1: up to 8 influences per vertex, more sets
 * are ignored with a warning; the skins of the nodes in the loaded scene, each
 * joint a node of that scene), morph targets (POSITION / NORMAL / TANGENT
 * deltas; TEXCOORD / COLOR deltas are ignored with a warning), mesh and node
 * weights, and animations (every one in the file, in file order, with its
 * name; channels on translation / rotation / scale / weights; a channel whose
 * node is outside the loaded scene, or whose path is unknown, e.g.
 * KHR_animation_pointer's, is left out: see info.animation_channels_ignored).
 * A required
 * extension outside this list is an error that names it; an unknown optional
 * one is a warning. Cameras and lights no node uses are not checked beyond a
 * warning.
 */
#ifndef MVR_GLTF_H
#define MVR_GLTF_H

#include "mvr/mvr.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A caller's own reader for external URIs (like cgltf's file options). It
 * receives the URI percent-decoded, without query or fragment; data: URIs,
 * other schemes and absolute paths never reach it, but ".." does: confinement
 * is then the caller's. It returns at most max_bytes bytes in memory it
 * allocated; mvr hands them back to release. */
typedef mvr_result (*mvr_gltf_read_fn)(const char *uri, uint64_t max_bytes, void **out_data, size_t *out_size,
                                       void *user_data);
typedef void (*mvr_gltf_release_fn)(void *data, void *user_data);

typedef struct mvr_gltf_file_access {
    /* Files below this folder are admitted too (e.g. a texture library shared
     * by many assets); NULL = only the asset's own folder. */
    const char *allowed_root;
    mvr_gltf_read_fn read;          /* NULL = mvr reads files itself, confined as above */
    mvr_gltf_release_fn release;    /* frees what read returned; NULL = free() */
    void *user_data;
} mvr_gltf_file_access;

typedef struct mvr_gltf_options {
    /* 0 = the file's default scene (or its first); k > 0 = scenes[k - 1] */
    uint32_t scene;
    /* Where a file loaded from memory finds external buffers and images;
     * NULL = external URIs are refused (data URIs and GLB chunks still work)
     * unless file_access.read is set. For mvr_gltf_load_file: the file's own
     * folder when NULL. */
    const char *base_dir;
    /* Caps; 0 = the default in brackets. */
    uint64_t max_file_bytes;        /* any file read, the glTF and each external one [1 GiB] */
    uint64_t max_vertices;          /* summed over all primitives [16 M] */
    uint64_t max_indices;           /* summed over all primitives [64 M] */
    uint32_t max_image_dimension;   /* width or height of a texture [16384] */
    uint32_t max_nodes;             /* [1 M] */
    mvr_logger logger;              /* warnings (unknown optional extensions, ...) */
    /* Bytes the load may hold at once, by its own accounting (see above) [2 GiB]. */
    uint64_t memory_budget;
    uint32_t max_images;            /* images the scene uses [4096] */
    mvr_gltf_file_access file_access;
    /* Missing or undecodable images fail the load instead of degrading. */
    bool strict;
} mvr_gltf_options;

typedef struct mvr_gltf_info {
    uint32_t warnings;              /* how many warnings went to the logger */
    uint32_t camera_nodes;          /* nodes with a camera, in node order (mvr_scene_camera_node) */
    uint32_t images_missing;        /* images left out (missing or undecodable): textures take the role's default */
    uint32_t images_decoded;        /* images decoded (each once, however often it is referenced) */
    uint32_t buffers_read;          /* external and data-URI buffers read (unused ones are not) */
    uint64_t memory_budget;         /* the budget in force */
    uint64_t memory_peak;           /* the most bytes the load held at once, by its accounting */
    uint64_t json_bytes_estimate;   /* what the parsed JSON was counted as */
    /* animation channels left out: unknown target paths (KHR_animation_pointer's
     * "pointer" among them, warned once per path) and channels whose node is
     * outside the loaded scene */
    uint32_t animation_channels_ignored;
    /* metallic-roughness images that took their materials' separate occlusion
     * image into their unused red channel (the same pixels, a texture fetch
     * less a fragment; glTF 2.0 3.9.3 describes this packing) */
    uint32_t images_occlusion_packed;
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
