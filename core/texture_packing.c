/* Texture packing, at load: a material's second texture coordinate set
 * read as the first where every primitive drawing with it repeats the first
 * in the second (a varying less), and its separate occlusion image moved into the
 * unused red channel of its metallic-roughness image, so that the fragment
 * stage reads both from one fetch (mvr_material_occlusion_in_metal_rough).
 *
 * glTF 2.0 (3.9.3, 3.9.5) reads metalness from B and roughness from G of
 * the metallic-roughness texture and occlusion from R of the occlusion
 * texture, and names the packing of all three into one texture as the
 * intended use. Files that keep them apart (DamagedHelmet: two 2048x2048
 * JPEGs) cost llvmpipe a fifth of a textured material's fetches (about 5 of
 * 34 ms at 1280x960, docs/benchmarks.md). Filtering and mip generation work
 * per channel, so the packed texture's red channel filters to the occlusion
 * texture's red channel bit for bit: the pixels are the same
 * (tests/gl/test_texture_packing.c, packing_gives_the_same_pixels). */
#include <stdlib.h>
#include <string.h>

#include "material.h"
#include "scene_internal.h"

/* Whether a primitive's second texture coordinate set repeats its first. */
static bool texcoord1_repeats_texcoord0(const scene_primitive *p)
{
    return p->uv0 && p->uv1 &&
           (p->uv0 == p->uv1 || memcmp(p->uv0, p->uv1, (size_t)p->vertex_count * 2 * sizeof(float)) == 0);
}

/* Marks material `material` (an index, or MVR_NO_INDEX: the default
 * material, which has no textures) as drawn by a primitive that repeats its
 * first texture coordinate set in its second, or by one that does not. */
static void mark_user(uint32_t material, uint32_t count, bool repeats, uint8_t *users, uint8_t *other)
{
    if (material >= count)
        return;
    if (repeats)
        users[material] = 1;
    else
        other[material] = 1;
}

uint32_t mvr_scene_fold_texcoords(mvr_scene *s)
{
    if (!s || !s->material_count)
        return 0;
    /* per material: drawn by a primitive that repeats set 0 in set 1
     * (exporters write such copies: DamagedHelmet's TEXCOORD_1 is
     * TEXCOORD_0's accessor), and by one that does not; one pass over the
     * primitives, each as its own, selected or a variant's material */
    uint8_t *users = calloc(2 * (size_t)s->material_count, 1);
    if (!users)
        return 0; /* nothing folded: the same pixels, a varying more */
    uint8_t *other = users + s->material_count;
    for (uint32_t i = 0; i < s->primitive_count; ++i) {
        const scene_primitive *p = &s->primitives[i];
        bool repeats = texcoord1_repeats_texcoord0(p);
        mark_user(p->material, s->material_count, repeats, users, other);
        mark_user(p->own_material, s->material_count, repeats, users, other);
        for (uint32_t k = 0; k < p->variant_map_count; ++k)
            mark_user(p->variant_maps[k].material, s->material_count, repeats, users, other);
    }
    uint32_t folded = 0;
    for (uint32_t i = 0; i < s->material_count; ++i) {
        mvr_material_desc *m = &s->materials[i].desc;
        bool reads_texcoord1 = false;
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
            const mvr_texture_ref *t = mvr_material_role(m, role);
            reads_texcoord1 |= t->image.id && t->texcoord == 1;
        }
        if (!reads_texcoord1 || !users[i] || other[i])
            continue;
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
            mvr_texture_ref *t = (mvr_texture_ref *)mvr_material_role(m, role);
            if (t->texcoord == 1)
                t->texcoord = 0;
        }
        s->material_version++;
        folded++;
    }
    free(users);
    return folded;
}

/* What the materials ask of one image as a packing target. */
typedef struct packing_target {
    uint32_t occlusion;          /* the occlusion image id its materials pair it with (0: none yet) */
    bool refused;                /* read otherwise than as metallic-roughness, or paired unlike */
    bool packed;                 /* took the occlusion image's red channel */
} packing_target;

/* One pass over the materials: for each image, the occlusion image it can
 * take into its red channel. Every reference to it must be a
 * metallic-roughness one (nothing else reads its red channel), and every
 * material sampling it must have no occlusion texture or the same occlusion
 * image, fetched alike. An image some material reads as occlusion is never
 * a target, so no image is both a target and a source. */
static void find_targets(const mvr_scene *s, packing_target *targets)
{
    for (uint32_t i = 0; i < s->material_count; ++i) {
        const mvr_material_desc *m = &s->materials[i].desc;
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
            uint32_t id = mvr_material_role(m, role)->image.id;
            if (role != MVR_ROLE_METAL_ROUGH && id && id <= s->image_count)
                targets[id - 1].refused = true;
        }
        uint32_t mr = m->metallic_roughness.image.id, ao = m->occlusion.image.id;
        if (!mr || mr > s->image_count || !ao)
            continue;
        packing_target *t = &targets[mr - 1];
        /* the occlusion fetched as the metallic-roughness texture is, once
         * its image is the same */
        mvr_texture_ref moved = m->occlusion;
        moved.image = m->metallic_roughness.image;
        if (!mvr_texture_refs_fetch_alike(&moved, &m->metallic_roughness) || m->spec_gloss.enabled ||
            (t->occlusion && t->occlusion != ao))
            t->refused = true;
        t->occlusion = ao;
    }
}

/* Both RGBA8 and the same size. */
static bool packable(const scene_image *target, const scene_image *src)
{
    return target->format == MVR_IMAGE_FORMAT_RGBA8 && target->rgba && src->format == MVR_IMAGE_FORMAT_RGBA8 &&
           src->rgba && src->width == target->width && src->height == target->height;
}

uint32_t mvr_scene_pack_occlusion(mvr_scene *s)
{
    if (!s || !s->image_count)
        return 0;
    packing_target *targets = calloc(s->image_count, sizeof *targets);
    if (!targets)
        return 0; /* nothing packed: the same pixels, a fetch more */
    find_targets(s, targets);
    uint32_t packed = 0;
    for (uint32_t mr = 0; mr < s->image_count; ++mr) {
        uint32_t ao = targets[mr].occlusion;
        if (targets[mr].refused || !ao || ao > s->image_count || !packable(&s->images[mr], &s->images[ao - 1]))
            continue;
        scene_image *target = &s->images[mr];
        const uint8_t *from = s->images[ao - 1].rgba;
        size_t texels = (size_t)target->width * target->height; /* <= 16384^2: add_image checked */
        for (size_t k = 0; k < texels; ++k)
            target->rgba[4 * k] = from[4 * k];
        mvr_scene_image_rehash(target);
        targets[mr].packed = true;
        packed++;
    }
    /* the materials now read their occlusion from the packed image */
    for (uint32_t i = 0; packed && i < s->material_count; ++i) {
        mvr_material_desc *m = &s->materials[i].desc;
        uint32_t mr = m->metallic_roughness.image.id;
        if (mr && mr <= s->image_count && targets[mr - 1].packed && m->occlusion.image.id)
            m->occlusion.image = m->metallic_roughness.image;
    }
    if (packed) {
        s->geometry_version++;
        s->material_version++;
    }
    free(targets);
    return packed;
}
