/* What the renderer has uploaded of a scene (gl/gpu_scene.c, gl/gpu_geometry.c). */
#ifndef MVR_GPU_SCENE_H
#define MVR_GPU_SCENE_H

#include "batch_plan.h"
#include "context_internal.h"
#include "frame.h"

/* GPU copy of one scene primitive. */
#define MVR_VERTEX_ATTRIBUTES 10 /* locations of mesh.vert.glsl and deform.glsl */
typedef struct mvr_gpu_primitive {
    GLuint vao, vbo, ibo;
    uint32_t attributes;         /* bit per location present in vbo */
    GLintptr attribute_offset[MVR_VERTEX_ATTRIBUTES];
    GLenum mode, index_type;
    GLsizei count;
} mvr_gpu_primitive;

typedef struct mvr_gpu_texture {
    uint32_t image;              /* scene image index; MVR_NO_INDEX - role: a role's 1 x 1 neutral texture */
    bool srgb;
    GLuint texture;
} mvr_gpu_texture;

typedef struct mvr_gpu_sampler {
    mvr_sampler_desc desc;
    GLuint sampler;
} mvr_gpu_sampler;

/* Per-material texture bindings (the per-material path: one 2D texture per image). */
typedef struct mvr_gpu_material {
    GLuint textures[MVR_ROLE_COUNT]; /* 0 = role unused */
    GLuint samplers[MVR_ROLE_COUNT];
} mvr_gpu_material;

/* What the renderer has uploaded of one scene. `scene` is an identity (with
 * its serial: a new scene at a freed one's address has another serial),
 * dereferenced only during the render that passed it in: a scene may be
 * destroyed between renders. */
typedef struct mvr_gpu_scene {
    const mvr_scene *scene;
    uint64_t scene_serial;
    uint64_t geometry_version, material_version;
    mvr_gpu_primitive *primitives;
    uint32_t primitive_count;
    mvr_gpu_texture *textures;
    uint32_t texture_count, texture_cap;
    mvr_gpu_sampler *samplers;
    uint32_t sampler_count, sampler_cap;
    mvr_gpu_material *materials; /* scene materials + the default one (per-material paths) */
    /* Two representations of the materials: [1] the array path's (texture
     * arrays, blocks with layer indices), [0] the per-material paths' (2D
     * textures, blocks without). The frame's is uploaded when first needed;
     * both stay resident only while auto's tuner measures them. */
    bool resident[2];
    GLuint material_ubos[2];
    bool arrays;                 /* this frame draws with the array path's */
    mvr_batch_plan plan;         /* array path: texture groups and material slots */
    GLuint *group_textures;      /* one GL_TEXTURE_2D_ARRAY per plan group */
    GLuint *group_samplers;
    uint32_t material_count;
    GLuint material_ubo;         /* this frame's: material_ubos[arrays] */
    uint32_t material_pages;
    GLsizeiptr material_page_stride; /* bytes between pages (aligned) */
    /* images stored smaller than the scene's (too large for the GL): one
     * flag per scene image, and how many are set */
    uint8_t *downscaled;
    uint32_t downscaled_cap, downscaled_count;
    /* the same for images held block-compressed, and for images whose
     * format the GL cannot sample (drawn with their roles' neutral values) */
    uint8_t *compressed, *unsampleable;
    uint32_t compressed_cap, compressed_count, unsampleable_cap, unsampleable_count;
} mvr_gpu_scene;

/* gpu_scene.c: uploads what changed in the scene (geometry, textures,
 * materials) and the representation of the materials this frame's material
 * path draws with; keep_both: the other stays resident (auto's tuner is
 * measuring both), else it is released. */
mvr_result mvr_gpu_scene_sync(mvr_renderer *r, const mvr_scene *scene, bool keep_both);
void mvr_gpu_scene_release(mvr_renderer *r);

/* gpu_geometry.c: every primitive of the scene uploaded (after
 * mvr_gpu_primitives_release), and their GL objects deleted. */
mvr_result mvr_gpu_primitives_upload(mvr_renderer *r, const mvr_scene *scene);
void mvr_gpu_primitives_release(mvr_renderer *r);

#endif
