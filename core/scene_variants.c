/* Material variants (KHR_materials_variants): named variants, per primitive
 * a mapping from variants to materials, and the selected variant, which
 * sets each mapped primitive's material. A change of any primitive's
 * material moves the scene's material version, so a renderer rebuilds its
 * draws; nothing else is sent again. */
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

void mvr_scene_free_variants(mvr_scene *s)
{
    for (uint32_t i = 0; i < s->variant_count; ++i)
        free(s->variant_names[i]);
    free(s->variant_names);
    s->variant_names = NULL;
    s->variant_count = s->variant_cap = 0;
}

mvr_result mvr_scene_add_variant(mvr_scene *s, const char *name, uint32_t *out_index)
{
    if (!s || !name)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_variant: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    /* the index must stay apart from MVR_VARIANT_DEFAULT */
    if (s->variant_count >= MVR_VARIANT_DEFAULT - 1)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_variant(%.64s): too many variants", name);
    size_t len = strlen(name);
    char *copy = malloc(len + 1);
    if (!copy || !GROW(s, variant_names, variant_count, variant_cap)) {
        free(copy);
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_variant(%.64s): out of memory", name);
    }
    memcpy(copy, name, len + 1);
    s->variant_names[s->variant_count] = copy;
    if (out_index)
        *out_index = s->variant_count;
    s->variant_count++;
    return MVR_OK;
}

uint32_t mvr_scene_variant_count(const mvr_scene *s)
{
    return s ? s->variant_count : 0;
}

const char *mvr_scene_variant_name(const mvr_scene *s, uint32_t index)
{
    return s && index < s->variant_count ? s->variant_names[index] : NULL;
}

mvr_result mvr_scene_find_variant(const mvr_scene *s, const char *name, uint32_t *out_index)
{
    if (!s || !name || !out_index)
        return s ? mvr_scene_fail((mvr_scene *)s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_find_variant: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    for (uint32_t i = 0; i < s->variant_count; ++i)
        if (strcmp(s->variant_names[i], name) == 0) {
            *out_index = i;
            return MVR_OK;
        }
    char names[256] = "";
    for (uint32_t i = 0; i < s->variant_count; ++i) {
        size_t used = strlen(names);
        mvr_str_format(names + used, sizeof names - used, "%s'%.64s'", i ? ", " : "", s->variant_names[i]);
    }
    return mvr_scene_fail((mvr_scene *)s, MVR_ERROR_INVALID_ARGUMENT, "no variant named '%.64s' (%u variants%s%s)",
                          name, s->variant_count, s->variant_count ? ": " : "", names);
}

/* Sets p's material for the selected variant; true when it changed. */
static bool apply_variant(const mvr_scene *s, scene_primitive *p)
{
    uint32_t material = p->own_material;
    if (s->selected_variant != MVR_VARIANT_DEFAULT)
        for (uint32_t i = 0; i < p->variant_map_count; ++i)
            if (p->variant_maps[i].variant == s->selected_variant) {
                material = p->variant_maps[i].material;
                break;
            }
    bool changed = p->material != material;
    p->material = material;
    return changed;
}

mvr_result mvr_scene_set_primitive_variants(mvr_scene *s, mvr_mesh_id mesh, uint32_t primitive,
                                            const mvr_variant_mapping *mappings, uint32_t count)
{
    if (!s || (count && !mappings))
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_set_primitive_variants: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    if (mesh.id == 0 || mesh.id > s->mesh_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_set_primitive_variants: mesh %u out of range (%u meshes)", mesh.id,
                              s->mesh_count);
    const scene_mesh *m = &s->meshes[mesh.id - 1];
    if (primitive >= m->primitive_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_set_primitive_variants(%s): primitive %u out of range (%u primitives)",
                              m->name, primitive, m->primitive_count);
    for (uint32_t i = 0; i < count; ++i) {
        if (mappings[i].variant >= s->variant_count)
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_scene_set_primitive_variants(%s): primitive %u, mapping %u names variant %u; "
                                  "the scene has %u",
                                  m->name, primitive, i, mappings[i].variant, s->variant_count);
        if (mappings[i].material.id > s->material_count)
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_scene_set_primitive_variants(%s): primitive %u, mapping %u names material %u; "
                                  "the scene has %u",
                                  m->name, primitive, i, mappings[i].material.id, s->material_count);
        for (uint32_t j = 0; j < i; ++j)
            if (mappings[j].variant == mappings[i].variant)
                return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                      "mvr_scene_set_primitive_variants(%s): primitive %u, mappings %u and %u both "
                                      "name variant %u (each variant at most once per primitive)",
                                      m->name, primitive, j, i, mappings[i].variant);
    }
    scene_variant_mapping *maps = NULL;
    if (count) {
        maps = malloc((size_t)count * sizeof *maps);
        if (!maps)
            return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY,
                                  "mvr_scene_set_primitive_variants(%s): out of memory (%u mappings)", m->name, count);
        for (uint32_t i = 0; i < count; ++i) {
            maps[i].variant = mappings[i].variant;
            maps[i].material = mappings[i].material.id ? mappings[i].material.id - 1 : MVR_NO_INDEX;
        }
    }
    scene_primitive *p = &s->primitives[m->first_primitive + primitive];
    free(p->variant_maps);
    p->variant_maps = maps;
    p->variant_map_count = count;
    if (apply_variant(s, p))
        s->material_version++;
    return MVR_OK;
}

mvr_result mvr_scene_select_variant(mvr_scene *s, uint32_t index)
{
    if (!s)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (index != MVR_VARIANT_DEFAULT && index >= s->variant_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_select_variant: variant %u out of range (%u variants)", index,
                              s->variant_count);
    if (index == s->selected_variant)
        return MVR_OK;
    s->selected_variant = index;
    bool changed = false;
    for (uint32_t i = 0; i < s->primitive_count; ++i)
        if (s->primitives[i].variant_map_count || s->primitives[i].material != s->primitives[i].own_material)
            changed |= apply_variant(s, &s->primitives[i]);
    if (changed)
        s->material_version++;
    return MVR_OK;
}

uint32_t mvr_scene_selected_variant(const mvr_scene *s)
{
    return s ? s->selected_variant : MVR_VARIANT_DEFAULT;
}
