#include <stdlib.h>
#include <string.h>

#include "batch_plan.h"
#include "shader_gen.h"

bool mvr_sampler_uses_mipmaps(const mvr_sampler_desc *s)
{
    switch (s->min_filter) {
    case MVR_FILTER_NEAREST:
    case MVR_FILTER_LINEAR:
        return false;
    case MVR_FILTER_DEFAULT:
    case MVR_FILTER_NEAREST_MIPMAP_NEAREST:
    case MVR_FILTER_LINEAR_MIPMAP_NEAREST:
    case MVR_FILTER_NEAREST_MIPMAP_LINEAR:
    case MVR_FILTER_LINEAR_MIPMAP_LINEAR:
        return true;
    }
    return true;
}

/* Defaults resolved, so equal GL state compares equal. */
static mvr_sampler_desc normalized(mvr_sampler_desc s)
{
    if (s.mag_filter == MVR_FILTER_DEFAULT)
        s.mag_filter = MVR_FILTER_LINEAR;
    if (s.min_filter == MVR_FILTER_DEFAULT)
        s.min_filter = MVR_FILTER_LINEAR_MIPMAP_LINEAR;
    if (s.wrap_s == MVR_WRAP_DEFAULT)
        s.wrap_s = MVR_WRAP_REPEAT;
    if (s.wrap_t == MVR_WRAP_DEFAULT)
        s.wrap_t = MVR_WRAP_REPEAT;
    return s;
}

uint32_t mvr_mip_levels(uint32_t w, uint32_t h)
{
    uint32_t n = 1, m = w > h ? w : h;
    while (m > 1) {
        m >>= 1;
        n++;
    }
    return n;
}

static bool note(mvr_batch_plan *p, const char *fmt, ...) MVR_PRINTF(2, 3);
static bool note(mvr_batch_plan *p, const char *fmt, ...)
{
    if (!mvr_array_grow((void **)&p->notes, &p->note_cap, p->note_count, sizeof *p->notes))
        return false;
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    mvr_str_vformat(buf, sizeof buf, fmt, ap);
    va_end(ap);
    size_t len = strlen(buf) + 1;
    p->notes[p->note_count] = malloc(len);
    if (!p->notes[p->note_count])
        return false;
    memcpy(p->notes[p->note_count++], buf, len);
    return true;
}

void mvr_role_neutral(uint32_t role, uint8_t out[4])
{
    out[0] = out[1] = out[2] = out[3] = 255;
    if (role == MVR_ROLE_NORMAL || role == MVR_ROLE_CLEARCOAT_NORMAL)
        out[0] = out[1] = 128;
    else if (role == MVR_ROLE_ANISOTROPY)
        out[1] = 128;
}

uint32_t mvr_image_group_levels(const scene_image *img, const mvr_sampler_desc *smp)
{
    if (!mvr_sampler_uses_mipmaps(smp))
        return 1;
    return img->format == MVR_IMAGE_FORMAT_RGBA8 ? mvr_mip_levels(img->width, img->height) : img->levels;
}

static bool same_key(const mvr_texture_group *g, uint32_t role, uint32_t w, uint32_t h, mvr_image_format format,
                     bool srgb, uint32_t levels, const mvr_sampler_desc *s)
{
    return g->role == role && g->width == w && g->height == h && g->format == format && g->srgb == srgb &&
           g->levels == levels && g->sampler.mag_filter == s->mag_filter && g->sampler.min_filter == s->min_filter &&
           g->sampler.wrap_s == s->wrap_s && g->sampler.wrap_t == s->wrap_t;
}

/* Identical stored bytes (pixels, or blocks of every level) in one format. */
static bool same_pixels(const scene_image *a, const scene_image *b)
{
    return a->hash == b->hash && a->format == b->format && a->levels == b->levels && a->width == b->width &&
           a->height == b->height && a->bytes == b->bytes &&
           memcmp(mvr_scene_image_bytes(a), mvr_scene_image_bytes(b), a->bytes) == 0;
}

/* The layer of an image in a group, added if new (identical pixels share one). */
static bool layer_of(mvr_texture_group *g, const mvr_scene *s, uint32_t image, uint32_t *out)
{
    const scene_image *img = &s->images[image];
    for (uint32_t k = 0; k < g->layer_count; ++k) {
        uint32_t other = g->layer_images[k];
        if (other == image || (other != MVR_NO_INDEX && same_pixels(&s->images[other], img))) {
            *out = k;
            return true;
        }
    }
    if (!mvr_array_grow((void **)&g->layer_images, &g->layer_cap, g->layer_count, sizeof *g->layer_images))
        return false;
    g->layer_images[g->layer_count] = image;
    *out = g->layer_count++;
    return true;
}

/* The neutral layer of a group, added if it has none. */
static bool neutral_of(mvr_texture_group *g, uint32_t *out)
{
    if (g->neutral_layer == MVR_NO_INDEX) {
        if (!mvr_array_grow((void **)&g->layer_images, &g->layer_cap, g->layer_count, sizeof *g->layer_images))
            return false;
        g->neutral_layer = g->layer_count;
        g->layer_images[g->layer_count++] = MVR_NO_INDEX;
    }
    *out = g->neutral_layer;
    return true;
}

static mvr_texture_group *new_group(mvr_batch_plan *p, uint32_t role, uint32_t w, uint32_t h, mvr_image_format format,
                                    bool srgb, uint32_t levels, const mvr_sampler_desc *smp)
{
    if (!mvr_array_grow((void **)&p->groups, &p->group_cap, p->group_count, sizeof *p->groups))
        return NULL;
    mvr_texture_group *g = &p->groups[p->group_count++];
    memset(g, 0, sizeof *g);
    g->role = role;
    g->width = w;
    g->height = h;
    g->format = format;
    g->srgb = srgb;
    g->levels = levels;
    g->sampler = *smp;
    g->neutral_layer = MVR_NO_INDEX;
    return g;
}

/* Why an image starts a new group, relative to the role's first group. */
static void explain(mvr_batch_plan *p, const mvr_texture_group *first, uint32_t role, uint32_t image,
                    uint32_t material, uint32_t w, uint32_t h, mvr_image_format format, bool srgb, uint32_t levels,
                    const mvr_sampler_desc *s, bool full)
{
    if (full)
        note(p, "%s image %u (material %u): group %u is full (GL_MAX_ARRAY_TEXTURE_LAYERS)", mvr_role_name(role),
             image, material, (unsigned)(first - p->groups));
    else if (first->width != w || first->height != h)
        note(p, "%s image %u (material %u): size %ux%u differs from group %u (%ux%u)", mvr_role_name(role), image,
             material, w, h, (unsigned)(first - p->groups), first->width, first->height);
    else if (first->format != format)
        note(p, "%s image %u (material %u): format %s differs from group %u (%s)", mvr_role_name(role), image,
             material, mvr_image_format_name(format), (unsigned)(first - p->groups),
             mvr_image_format_name(first->format));
    else if (first->srgb != srgb)
        note(p, "%s image %u (material %u): format differs from group %u", mvr_role_name(role), image, material,
             (unsigned)(first - p->groups));
    else if (first->levels != levels)
        note(p, "%s image %u (material %u): mip count %u differs from group %u (%u)", mvr_role_name(role), image,
             material, levels, (unsigned)(first - p->groups), first->levels);
    else
        note(p, "%s image %u (material %u): sampler (filters %d/%d, wrap %d/%d) differs from group %u",
             mvr_role_name(role), image, material, (int)s->mag_filter, (int)s->min_filter, (int)s->wrap_s,
             (int)s->wrap_t, (unsigned)(first - p->groups));
}

static int compare_groups(const void *pa, const void *pb)
{
    const mvr_material_slots *a = *(const mvr_material_slots *const *)pa, *b = *(const mvr_material_slots *const *)pb;
    int c = memcmp(a->group, b->group, sizeof a->group);
    return c ? c : (a < b ? -1 : a > b);
}

/* Numbers the distinct group tuples, in the order of the tuples (so draws
 * sorted by the number bind arrays in a stable order). */
static mvr_result number_group_sets(mvr_batch_plan *p)
{
    mvr_material_slots **order = malloc(p->material_count * sizeof *order);
    if (!order)
        return MVR_ERROR_OUT_OF_MEMORY;
    for (uint32_t m = 0; m < p->material_count; ++m)
        order[m] = &p->materials[m];
    qsort(order, p->material_count, sizeof *order, compare_groups);
    uint32_t set = 0;
    for (uint32_t k = 0; k < p->material_count; ++k) {
        if (k && memcmp(order[k]->group, order[k - 1]->group, sizeof order[k]->group) != 0)
            set++;
        order[k]->group_set = set;
    }
    free(order);
    return MVR_OK;
}

mvr_result mvr_batch_plan_build(mvr_batch_plan *p, const mvr_scene *s, uint32_t max_layers)
{
    return mvr_batch_plan_build_for(p, s, max_layers, UINT32_MAX);
}

mvr_result mvr_batch_plan_build_for(mvr_batch_plan *p, const mvr_scene *s, uint32_t max_layers, uint32_t sampleable)
{
    mvr_batch_plan_free(p);
    if (max_layers < 2)
        max_layers = 2;
    sampleable |= 1u << MVR_IMAGE_FORMAT_RGBA8;
    p->material_count = s->material_count + 1;
    p->materials = malloc(p->material_count * sizeof *p->materials);
    if (!p->materials)
        return MVR_ERROR_OUT_OF_MEMORY;
    for (uint32_t m = 0; m < p->material_count; ++m)
    {
        for (uint32_t r = 0; r < MVR_ROLE_COUNT; ++r)
            p->materials[m].group[r] = p->materials[m].layer[r] = MVR_NO_GROUP;
        p->materials[m].extension_textures = false;
    }

    for (uint32_t m = 0; m < s->material_count; ++m) {
        const mvr_material_desc *md = &s->materials[m].desc;
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
            if (!mvr_material_samples_role(md, role))
                continue;
            const mvr_texture_ref *t = mvr_material_role(md, role);
            uint32_t image = t->image.id - 1;
            const scene_image *img = &s->images[image];
            mvr_sampler_desc smp = normalized(t->sampler);
            bool srgb = mvr_role_is_srgb(role);
            /* A format the GL cannot sample: the role's neutral value, the
             * neutral layer of a 1 x 1 RGBA8 group (the renderer warns,
             * naming the image; here a note). */
            bool neutral = !(sampleable & (1u << img->format));
            uint32_t w = neutral ? 1 : img->width, h = neutral ? 1 : img->height;
            mvr_image_format format = neutral ? MVR_IMAGE_FORMAT_RGBA8 : img->format;
            uint32_t levels = neutral ? 1 : mvr_image_group_levels(img, &smp);
            if (neutral)
                note(p, "%s image %u (material %u): format %s cannot be sampled by this GL: the role's neutral value",
                     mvr_role_name(role), image, m, mvr_image_format_name(img->format));
            mvr_texture_group *first = NULL, *fit = NULL;
            bool full = false;
            for (uint32_t g = 0; g < p->group_count; ++g) {
                mvr_texture_group *grp = &p->groups[g];
                if (grp->role != role)
                    continue;
                if (!first)
                    first = grp;
                if (same_key(grp, role, w, h, format, srgb, levels, &smp)) {
                    /* room, or the image is already a layer */
                    bool present = neutral && grp->neutral_layer != MVR_NO_INDEX;
                    for (uint32_t k = 0; k < grp->layer_count && !present; ++k)
                        present = !neutral && grp->layer_images[k] == image;
                    if (present || grp->layer_count < max_layers) {
                        fit = grp;
                        break;
                    }
                    full = true;
                }
            }
            if (!fit) {
                if (first && !neutral)
                    explain(p, first, role, image, m, w, h, format, srgb, levels, &smp, full);
                fit = new_group(p, role, w, h, format, srgb, levels, &smp);
                if (!fit)
                    return MVR_ERROR_OUT_OF_MEMORY;
            }
            uint32_t layer = 0;
            if (!(neutral ? neutral_of(fit, &layer) : layer_of(fit, s, image, &layer)))
                return MVR_ERROR_OUT_OF_MEMORY;
            p->materials[m].group[role] = (uint16_t)(fit - p->groups);
            p->materials[m].layer[role] = (uint16_t)layer;
            if (role >= MVR_CORE_ROLE_COUNT)
                p->materials[m].extension_textures = true;
        }
    }

    /* A material without a texture in a role that other materials sample
     * reads a white layer of the role's first RGBA8 group (a block-compressed
     * group has no neutral layer: a 1 x 1 RGBA8 group of its own is made
     * when the role has only those): one program and no bind for both
     * kinds. White is exact for base color, metallic-roughness, occlusion
     * and emissive (the factor times 1.0); a "flat" normal texel (128, 128,
     * 255) is not exactly (0, 0, 1), so normal maps keep their own variant.
     * The extensions' roles need no white layer: their shader code samples
     * only where the material's block says it has a texture. */
    for (uint32_t role = 0; role < MVR_CORE_ROLE_COUNT; ++role) {
        if (role == MVR_ROLE_NORMAL)
            continue;
        mvr_texture_group *first = NULL;
        bool any = false, any_rgba8 = false;
        for (uint32_t g = 0; g < p->group_count && !first; ++g) {
            if (p->groups[g].role != role)
                continue;
            any = true;
            if (p->groups[g].format != MVR_IMAGE_FORMAT_RGBA8)
                continue;
            any_rgba8 = true;
            if (p->groups[g].layer_count < max_layers)
                first = &p->groups[g];
        }
        if (!any || (!first && any_rgba8)) /* every RGBA8 group full: as before, no neutral layer */
            continue;
        for (uint32_t m = 0; m < p->material_count; ++m) {
            if (p->materials[m].group[role] != MVR_NO_GROUP)
                continue;
            if (!first) {
                mvr_sampler_desc smp;
                memset(&smp, 0, sizeof smp);
                smp = normalized(smp);
                first = new_group(p, role, 1, 1, MVR_IMAGE_FORMAT_RGBA8, mvr_role_is_srgb(role), 1, &smp);
                if (!first)
                    return MVR_ERROR_OUT_OF_MEMORY;
            }
            uint32_t layer = 0;
            if (!neutral_of(first, &layer))
                return MVR_ERROR_OUT_OF_MEMORY;
            p->materials[m].group[role] = (uint16_t)(first - p->groups);
            p->materials[m].layer[role] = (uint16_t)layer;
        }
    }
    return number_group_sets(p);
}

void mvr_batch_plan_free(mvr_batch_plan *p)
{
    for (uint32_t g = 0; g < p->group_count; ++g)
        free(p->groups[g].layer_images);
    for (uint32_t n = 0; n < p->note_count; ++n)
        free(p->notes[n]);
    free(p->groups);
    free(p->materials);
    free(p->notes);
    memset(p, 0, sizeof *p);
}

uint32_t mvr_batch_plan_neutral_features(const mvr_batch_plan *p, uint32_t slot)
{
    uint32_t f = 0;
    if (slot >= p->material_count)
        return 0;
    for (uint32_t r = 0; r < MVR_CORE_ROLE_COUNT; ++r) {
        uint16_t g = p->materials[slot].group[r];
        if (g != MVR_NO_GROUP && p->groups[g].neutral_layer == p->materials[slot].layer[r])
            f |= mvr_role_feature(r);
    }
    return f;
}

uint64_t mvr_batch_plan_group_key(const mvr_batch_plan *p, uint32_t slot)
{
    return slot < p->material_count ? p->materials[slot].group_set : 0;
}
