/*
 * The batch plan (backend-free): per texture role, the scene's images grouped
 * by compatibility key (width, height, format: RGBA8 or a GPU block format,
 * sRGB or linear, mip count, sampler): block-compressed images never share
 * an array with RGBA8 ones or with another block format;
 * each group becomes one GL_TEXTURE_2D_ARRAY, one layer per distinct image.
 * A material records per role (group, layer), so a pass binds each group once
 * and draws pick their layers through the material table.
 */
#ifndef MVR_BATCH_PLAN_H
#define MVR_BATCH_PLAN_H

#include "material.h"
#include "scene_internal.h"

#define MVR_NO_GROUP UINT16_MAX

typedef struct mvr_texture_group {
    uint32_t role;
    uint32_t width, height;
    mvr_image_format format;     /* RGBA8, or the block format of every layer */
    bool srgb;
    /* RGBA8: 1, or the full mip chain (generated); block formats: 1, or the
     * levels the images hold (their files' own, maybe fewer than the chain) */
    uint32_t levels;
    mvr_sampler_desc sampler;    /* normalized (defaults resolved) */
    /* scene image per layer; MVR_NO_INDEX = the neutral layer (the role's
     * neutral value, mvr_role_neutral: RGBA8 groups only) */
    uint32_t *layer_images;
    uint32_t layer_count, layer_cap;
    uint32_t neutral_layer;      /* MVR_NO_INDEX until a material needs it */
} mvr_texture_group;

typedef struct mvr_material_slots {
    uint16_t group[MVR_ROLE_COUNT];   /* MVR_NO_GROUP: the role is not sampled */
    uint16_t layer[MVR_ROLE_COUNT];
    uint32_t group_set;               /* equal for materials with equal groups in every role */
    bool extension_textures;          /* an extension's role is sampled from an array */
} mvr_material_slots;

typedef struct mvr_batch_plan {
    mvr_texture_group *groups;
    uint32_t group_count, group_cap;
    mvr_material_slots *materials;    /* scene materials + the default one */
    uint32_t material_count;
    char **notes;                     /* why images could not join a group */
    uint32_t note_count, note_cap;
} mvr_batch_plan;

/* Builds the plan for a scene; max_layers = GL_MAX_ARRAY_TEXTURE_LAYERS;
 * every image format sampleable. */
mvr_result mvr_batch_plan_build(mvr_batch_plan *plan, const mvr_scene *scene, uint32_t max_layers);
/* The same for a GL that samples only the formats in `sampleable` (bits
 * 1u << mvr_image_format; RGBA8 always): a material's role whose image is
 * in another format reads the neutral layer of a 1 x 1 RGBA8 group (the
 * role's neutral value), with a note. */
mvr_result mvr_batch_plan_build_for(mvr_batch_plan *plan, const mvr_scene *scene, uint32_t max_layers,
                                    uint32_t sampleable);

/* The texel a role reads where it has no texture it can sample (RGBA8): white
 * (the factors alone), a flat normal (128, 128, 255) for the normal roles,
 * direction (1, 0) at full strength (255, 128, 255) for anisotropy. */
void mvr_role_neutral(uint32_t role, uint8_t out[4]);
void mvr_batch_plan_free(mvr_batch_plan *plan);

/* Feature bits of the roles a material reads from a neutral (white) layer on
 * the array path (roles it has no texture in; never the normal role). */
uint32_t mvr_batch_plan_neutral_features(const mvr_batch_plan *plan, uint32_t material_slot);

/* A sort key of a material's groups: equal keys bind the same arrays. */
uint64_t mvr_batch_plan_group_key(const mvr_batch_plan *plan, uint32_t material_slot);

/* The levels a group of an image holds: RGBA8: the full chain where the
 * sampler reads mips (generated), else 1; block formats: the image's own
 * levels where the sampler reads mips, else 1. */
uint32_t mvr_image_group_levels(const scene_image *img, const mvr_sampler_desc *sampler);

/* Levels of a full mip chain of a w x h image. */
uint32_t mvr_mip_levels(uint32_t w, uint32_t h);

/* Whether a sampler's minification filter reads mip levels. */
bool mvr_sampler_uses_mipmaps(const mvr_sampler_desc *s);

#endif
