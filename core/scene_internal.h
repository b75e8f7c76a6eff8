/* The scene's own storage, shared by core (frame prep) and the GL backend
 * (uploads). Arrays are indexed by id - 1. */
#ifndef MVR_SCENE_INTERNAL_H
#define MVR_SCENE_INTERNAL_H

#include "core_util.h"
#include "mvr_math.h"
#include "mvr/mvr.h"

#define MVR_NO_INDEX UINT32_MAX

typedef struct scene_image {
    uint32_t width, height;
    uint8_t *rgba;               /* RGBA8 images; NULL for block formats */
    /* block formats: the levels back to back in `blocks`, level k at
     * blocks + level_offset[k], level_size[k] bytes (exact, validated) */
    mvr_image_format format;
    uint32_t levels;             /* RGBA8: 1 (mips are generated) */
    uint8_t *blocks;
    size_t level_offset[MVR_IMAGE_MAX_LEVELS], level_size[MVR_IMAGE_MAX_LEVELS];
    size_t bytes;                /* of rgba, or of every level's blocks */
    uint64_t hash;               /* of the pixels / blocks: identical images can share GPU storage */
    char name[64];
} scene_image;

/* The stored bytes of an image (rgba or blocks). */
static inline const uint8_t *mvr_scene_image_bytes(const scene_image *img)
{
    return img->format == MVR_IMAGE_FORMAT_RGBA8 ? img->rgba : img->blocks;
}

/* Sets img->hash from its bytes, size, format and levels (after its bytes change). */
void mvr_scene_image_rehash(scene_image *img);

/* Rewrites texture coordinate set 1 as set 0 in the texture refs of each
 * material whose primitives (every one drawing with it, at least one) hold
 * the same values in both sets: the same pixels for those primitives, without
 * the second set's varying (core/texture_packing.c; a primitive added later
 * with that material reads set 0 where it said 1). Returns how many
 * materials changed. */
uint32_t mvr_scene_fold_texcoords(mvr_scene *scene);

/* Moves each material's separate occlusion image into the red channel of
 * its metallic-roughness image where the pixels stay the same
 * (core/texture_packing.c); returns how many images took one. */
uint32_t mvr_scene_pack_occlusion(mvr_scene *scene);

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
    /* skinning: 0, 1 or 2 sets of 4 joints and weights per vertex, the
     * weights normalised over all sets; max_joint the largest joint index
     * with a non-zero weight (checked against the skin a node gives it) */
    uint32_t influence_sets;
    uint16_t *joints[2];
    float *weights[2];
    uint32_t max_joint;
    /* per joint index 0..max_joint: the bind-space box of the vertices it
     * moves (min > max: none), for posed bounds */
    mvr_dvec3 *joint_min, *joint_max;
    /* morph targets: target_count * vertex_count * 3 deltas per attribute
     * (NULL: no target moves it; zeros where one target lacks it), and per
     * target the largest |position delta| per axis (bounds) */
    uint32_t target_count;
    float *target_positions, *target_normals, *target_tangents;
    mvr_dvec3 *target_extent;
    /* where its deltas sit in the scene's morph delta texels (deform.glsl):
     * base + (target * morph_attributes + slot) * vertex_count + vertex;
     * slots: position | normal << 2 | tangent << 4, 3 = none */
    uint64_t morph_base;
    uint32_t morph_attributes, morph_slots;
    /* material variants (core/scene_variants.c): the material its desc gave
     * (material above is the selected variant's, else this one) and its
     * mappings, each variant at most once */
    uint32_t own_material;
    struct scene_variant_mapping *variant_maps;
    uint32_t variant_map_count;
} scene_primitive;

typedef struct scene_variant_mapping {
    uint32_t variant;
    uint32_t material;           /* index; MVR_NO_INDEX = default material */
} scene_variant_mapping;

typedef struct scene_mesh {
    uint32_t first_primitive, primitive_count;
    uint32_t target_count;       /* morph targets of every primitive (0: none) */
    float *weights;              /* target_count default weights (glTF mesh.weights) */
    char name[64];
} scene_mesh;

typedef struct scene_skin {
    uint32_t *joints;            /* node indices */
    mvr_dmat4 *inverse_bind;     /* per joint */
    uint32_t joint_count;
    uint32_t skeleton;           /* node index or MVR_NO_INDEX */
    char name[64];
} scene_skin;

typedef struct scene_anim_sampler {
    double *times, *values;
    uint32_t key_count, value_count;
    mvr_interpolation interpolation;
} scene_anim_sampler;

typedef struct scene_anim_channel {
    uint32_t sampler, node;
    mvr_animation_path path;
    uint32_t components;         /* 3, 4, 3 or the node's mesh's target count */
} scene_anim_channel;

typedef struct scene_animation {
    scene_anim_sampler *samplers;
    uint32_t sampler_count;
    scene_anim_channel *channels;
    uint32_t channel_count;
    double start, end;
    char name[64];
} scene_animation;

typedef struct scene_node {
    uint32_t parent;             /* index or MVR_NO_INDEX; parents come first */
    bool use_matrix;
    mvr_dvec3 translation, scale;
    mvr_dquat rotation;
    mvr_dmat4 matrix;
    uint32_t mesh, light, camera; /* indices or MVR_NO_INDEX */
    uint32_t skin;               /* index or MVR_NO_INDEX */
    float *weights;              /* the mesh's target count; NULL = the mesh's defaults */
    /* the rest pose (mvr_scene_reset_pose): what add_node, set_node_transform
     * and set_node_weights last gave; animations never change it */
    float *rest_weights;
    mvr_dvec3 rest_translation, rest_scale;
    mvr_dquat rest_rotation;
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
    scene_skin *skins;
    uint32_t skin_count, skin_cap;
    scene_animation *animations;
    uint32_t animation_count, animation_cap;
    char **variant_names;        /* material variants, names heap-allocated */
    uint32_t variant_count, variant_cap;
    uint32_t selected_variant;   /* MVR_VARIANT_DEFAULT: none */
    uint64_t morph_texels;       /* delta texels of every primitive's targets */
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

/* Records a failure of a scene call (its message, logged) and returns r. */
mvr_result mvr_scene_fail(mvr_scene *scene, mvr_result r, const char *fmt, ...) MVR_PRINTF(3, 4);
/* Every one of n floats is finite. */
bool mvr_finite_floats(const float *v, size_t n);

/* Grows the array scene->field (count used, cap allocated) by one slot. */
#define GROW(s, field, count, cap) mvr_array_grow((void **)&(s)->field, &(s)->cap, (s)->count, sizeof *(s)->field)

/* The resolved default material (glTF's defaults). */
const mvr_material_desc *mvr_scene_material(const mvr_scene *scene, uint32_t index);

/* World matrices of every node (double), in node order. */
void mvr_scene_world_matrices(const mvr_scene *scene, mvr_dmat4 *out);

/* ---- skins and morph targets (core/scene_animation.c) */

/* Copies, checks and normalises a primitive's joints, weights and morph
 * targets into p (its vertex attributes already copied); frees nothing on
 * failure (the caller frees the primitive). */
mvr_result mvr_scene_primitive_deformers(mvr_scene *scene, scene_primitive *p, const mvr_primitive_desc *d,
                                         const char *mesh, uint32_t k);
void mvr_scene_free_deformers(scene_primitive *p);
void mvr_scene_free_skins_and_animations(mvr_scene *scene);

/* ---- material variants (core/scene_variants.c) */

void mvr_scene_free_variants(mvr_scene *scene);

/* Whether a node's draws are skinned: it has a skin and its primitive
 * joints (else the node's transform places the bind pose, as glTF asks). */
static inline bool mvr_scene_draw_skinned(const mvr_scene *s, const scene_node *n, const scene_primitive *p)
{
    (void)s;
    return n->skin != MVR_NO_INDEX && p->influence_sets > 0;
}

/* The weights a node's mesh is drawn with (target_count of them; NULL when
 * the mesh has no targets). */
const float *mvr_scene_node_weights(const mvr_scene *scene, const scene_node *node);

/* Joint matrices of a skin, world(joint) * inverse bind, in double. */
void mvr_scene_skin_matrices(const mvr_scene *scene, uint32_t skin, const mvr_dmat4 *world, mvr_dmat4 *out);

/* The CPU reference of deform.glsl, in double: the world positions of a
 * primitive's vertices as a node draws it now (morphed by its weights,
 * skinned by its skin, else placed by the node), out[3 * vertex_count].
 * Tests compare the GPU's paths with it. False when out of memory. */
bool mvr_scene_posed_positions(const mvr_scene *scene, uint32_t node, uint32_t primitive, double *out);
/* The same for normals (the primitive has them; else false): morphed by
 * the weights' deltas, then through the weighted sum of the joints' normal
 * matrices (else the node's), left unnormalised as deform.glsl leaves them. */
bool mvr_scene_posed_normals(const mvr_scene *scene, uint32_t node, uint32_t primitive, double *out);

/* World-space box of one primitive as node draws it this frame: posed by
 * its skin (joint_matrices: that skin's, from mvr_scene_skin_matrices) and
 * its morph weights; conservative. */
void mvr_scene_posed_bounds(const mvr_scene *scene, const scene_node *node, const scene_primitive *p,
                            const mvr_dmat4 *world, const mvr_dmat4 *joint_matrices, mvr_dvec3 *lo,
                            mvr_dvec3 *hi);

#endif
