/* The scene's own storage, shared by core (frame prep) and the GL backend
 * (uploads). Arrays are indexed by id - 1. */
#ifndef MVR_SCENE_INTERNAL_H
#define MVR_SCENE_INTERNAL_H

#include "core_util.h"
#include "mvr_math.h"

#define MVR_NO_INDEX UINT32_MAX

typedef struct scene_image {
    uint32_t width, height;
    uint8_t *rgba;
    uint64_t hash;               /* of the pixels: identical images can share GPU storage */
    char name[64];
} scene_image;

typedef struct scene_material {
    mvr_material_desc desc;      /* name pointer cleared; defaults resolved */
    char name[64];
} scene_material;

typedef struct scene_primitive {
    uint32_t vertex_count;
    float *positions, *normals, *tangents, *uv0, *uv1, *colors;
    uint32_t index_count;
    uint32_t *indices;           /* widened to 32 bits; NULL when not indexed */
    bool small_indices;          /* every index fits 16 bits: uploaded as 16-bit */
    mvr_primitive_mode mode;
    uint32_t material;           /* index; MVR_NO_INDEX = default material */
    mvr_dvec3 bounds_min, bounds_max; /* local */
} scene_primitive;

typedef struct scene_mesh {
    uint32_t first_primitive, primitive_count;
    char name[64];
} scene_mesh;

typedef struct scene_node {
    uint32_t parent;             /* index or MVR_NO_INDEX; parents come first */
    bool use_matrix;
    mvr_dvec3 translation, scale;
    mvr_dquat rotation;
    mvr_dmat4 matrix;
    uint32_t mesh, light, camera; /* indices or MVR_NO_INDEX */
    char name[64];
} scene_node;

struct mvr_scene {
    mvr_logger logger;
    char last_error[MVR_ERROR_MESSAGE_SIZE];
    scene_image *images;
    uint32_t image_count, image_cap;
    scene_material *materials;
    uint32_t material_count, material_cap;
    scene_primitive *primitives;
    uint32_t primitive_count, primitive_cap;
    scene_mesh *meshes;
    uint32_t mesh_count, mesh_cap;
    scene_node *nodes;
    uint32_t node_count, node_cap;
    mvr_light_desc *lights;
    uint32_t light_count, light_cap;
    mvr_projection *cameras;
    uint32_t camera_count, camera_cap;
    float ambient[3];
    /* Change counters: a renderer re-uploads what moved on since it looked. */
    uint64_t geometry_version;   /* meshes, images */
    uint64_t material_version;
    uint64_t transform_version;  /* node transforms, lights, ambient */
    /* Tells scenes apart for a renderer's cache even when a new scene is
     * allocated where a destroyed one was. */
    uint64_t serial;
    uint32_t sanitized;          /* degenerate values repaired on the way in (logged) */
};

uint64_t mvr_scene_serial(const mvr_scene *scene);

/* The resolved default material (glTF's defaults). */
const mvr_material_desc *mvr_scene_material(const mvr_scene *scene, uint32_t index);

/* World matrices of every node (double), in node order. */
void mvr_scene_world_matrices(const mvr_scene *scene, mvr_dmat4 *out);

#endif
