/* A fingerprint of a scene's content (scene_hash.h). */
#include "scene_hash.h"

#include "program_binary_file.h" /* mvr_fnv1a64 */
#include "scene_internal.h"

static uint64_t mix_u32(uint64_t h, uint32_t v)
{
    return mvr_fnv1a64(h, &v, sizeof v);
}

uint64_t mvr_scene_content_hash(const mvr_scene *s)
{
    uint64_t h = MVR_FNV1A64_INIT;
    const uint32_t counts[] = {s->image_count, s->material_count, s->primitive_count, s->mesh_count, s->node_count,
                               s->light_count,  s->camera_count,  s->skin_count,      s->animation_count};
    h = mvr_fnv1a64(h, counts, sizeof counts);
    for (uint32_t i = 0; i < s->image_count; ++i) {
        const scene_image *img = &s->images[i];
        h = mix_u32(mix_u32(mix_u32(h, img->width), img->height), (uint32_t)img->format);
        h = mvr_fnv1a64(h, &img->hash, sizeof img->hash);
    }
    /* the placement: nodes (their rest pose and what they draw; the demos
     * share one box mesh between scenes) */
    for (uint32_t i = 0; i < s->node_count; ++i) {
        const scene_node *n = &s->nodes[i];
        const uint32_t refs[5] = {n->parent, n->mesh, n->light, n->skin, (uint32_t)n->use_matrix};
        h = mvr_fnv1a64(h, refs, sizeof refs);
        const double pose[10] = {n->rest_translation.x, n->rest_translation.y, n->rest_translation.z,
                                 n->rest_scale.x,       n->rest_scale.y,       n->rest_scale.z,
                                 n->rest_rotation.x,    n->rest_rotation.y,    n->rest_rotation.z,
                                 n->rest_rotation.w};
        h = mvr_fnv1a64(h, n->use_matrix ? (const void *)&n->matrix : (const void *)pose,
                        n->use_matrix ? sizeof n->matrix : sizeof pose);
    }
    /* the materials' factors and modes (field by field: no padding bytes) */
    for (uint32_t i = 0; i < s->material_count; ++i) {
        const mvr_material_desc *m = &s->materials[i].desc;
        h = mvr_fnv1a64(h, m->base_color_factor, sizeof m->base_color_factor);
        const float f[3] = {m->metallic_factor, m->roughness_factor, m->alpha_cutoff};
        h = mvr_fnv1a64(h, f, sizeof f);
        h = mix_u32(mix_u32(mix_u32(h, (uint32_t)m->alpha_mode), m->double_sided), m->unlit);
    }
    for (uint32_t i = 0; i < s->primitive_count; ++i) {
        const scene_primitive *p = &s->primitives[i];
        h = mix_u32(mix_u32(mix_u32(h, p->vertex_count), p->index_count), p->material);
        h = mix_u32(h, (uint32_t)p->mode);
        if (p->positions)
            h = mvr_fnv1a64(h, p->positions, (size_t)p->vertex_count * 3 * sizeof(float));
        if (p->indices)
            h = mvr_fnv1a64(h, p->indices, (size_t)p->index_count * sizeof(uint32_t));
    }
    return h;
}
