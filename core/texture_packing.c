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
 * (tests/gl/test_materials.c, occlusion_packing_gives_the_same_pixels). */
#include <string.h>

#include "material.h"
#include "scene_internal.h"

/* Whether every primitive that draws with material `material` (as its own,
 * selected or a variant's) has a second texture coordinate set equal to its
 * first, and at least one does. Exporters write such copies (DamagedHelmet's
 * TEXCOORD_1 is TEXCOORD_0's accessor). */
static bool texcoord1_repeats_texcoord0(const mvr_scene *s, uint32_t material)
{
    uint32_t users = 0;
    for (uint32_t i = 0; i < s->primitive_count; ++i) {
        const scene_primitive *p = &s->primitives[i];
        bool uses = p->material == material || p->own_material == material;
        for (uint32_t k = 0; k < p->variant_map_count && !uses; ++k)
            uses = p->variant_maps[k].material == material;
        if (!uses)
            continue;
        if (!p->uv0 || !p->uv1 ||
            (p->uv0 != p->uv1 && memcmp(p->uv0, p->uv1, (size_t)p->vertex_count * 2 * sizeof(float)) != 0))
            return false;
        users++;
    }
    return users > 0;
}

uint32_t mvr_scene_fold_texcoords(mvr_scene *s)
{
    if (!s)
        return 0;
    uint32_t folded = 0;
    for (uint32_t i = 0; i < s->material_count; ++i) {
        mvr_material_desc *m = &s->materials[i].desc;
        bool reads_texcoord1 = false;
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
            const mvr_texture_ref *t = mvr_material_role(m, role);
            reads_texcoord1 |= t->image.id && t->texcoord == 1;
        }
        if (!reads_texcoord1 || !texcoord1_repeats_texcoord0(s, i))
            continue;
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
            mvr_texture_ref *t = (mvr_texture_ref *)mvr_material_role(m, role);
            if (t->texcoord == 1)
                t->texcoord = 0;
        }
        s->material_version++;
        folded++;
    }
    return folded;
}

/* The occlusion image that image `mr` (index) can take into its red channel:
 * its id, or 0 where it cannot. Every reference to `mr` must be a
 * metallic-roughness one (nothing else reads its red channel), and every
 * material sampling it must have no occlusion texture or the same occlusion
 * image, fetched alike, the same size, in RGBA8. */
static uint32_t occlusion_for(const mvr_scene *s, uint32_t mr)
{
    const scene_image *target = &s->images[mr];
    if (target->format != MVR_IMAGE_FORMAT_RGBA8 || !target->rgba)
        return 0;
    uint32_t ao = 0;
    for (uint32_t i = 0; i < s->material_count; ++i) {
        const mvr_material_desc *m = &s->materials[i].desc;
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role)
            if (role != MVR_ROLE_METAL_ROUGH && mvr_material_role(m, role)->image.id == mr + 1)
                return 0;
        if (m->metallic_roughness.image.id != mr + 1 || !m->occlusion.image.id)
            continue;
        /* the occlusion fetched as the metallic-roughness texture is, once
         * its image is the same */
        mvr_texture_ref moved = m->occlusion;
        moved.image = m->metallic_roughness.image;
        if (!mvr_texture_refs_fetch_alike(&moved, &m->metallic_roughness) || m->spec_gloss.enabled)
            return 0;
        uint32_t id = m->occlusion.image.id;
        if (ao && id != ao)
            return 0;
        ao = id;
    }
    if (!ao || ao > s->image_count)
        return 0;
    const scene_image *src = &s->images[ao - 1];
    if (src->format != MVR_IMAGE_FORMAT_RGBA8 || !src->rgba || src->width != target->width ||
        src->height != target->height)
        return 0;
    return ao;
}

uint32_t mvr_scene_pack_occlusion(mvr_scene *s)
{
    if (!s)
        return 0;
    uint32_t packed = 0;
    for (uint32_t mr = 0; mr < s->image_count; ++mr) {
        uint32_t ao = occlusion_for(s, mr);
        if (!ao)
            continue;
        scene_image *target = &s->images[mr];
        const uint8_t *from = s->images[ao - 1].rgba;
        size_t texels = (size_t)target->width * target->height; /* <= 16384^2: add_image checked */
        for (size_t k = 0; k < texels; ++k)
            target->rgba[4 * k] = from[4 * k];
        mvr_scene_image_rehash(target);
        for (uint32_t i = 0; i < s->material_count; ++i) {
            mvr_material_desc *m = &s->materials[i].desc;
            if (m->metallic_roughness.image.id == mr + 1 && m->occlusion.image.id == ao)
                m->occlusion.image = m->metallic_roughness.image;
        }
        s->geometry_version++;
        s->material_version++;
        packed++;
    }
    return packed;
}
