#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "frame.h"
#include "material.h"

uint32_t mvr_draw_features(const scene_primitive *p, const mvr_material_desc *m)
{
    uint32_t f = 0;
    if (p->normals)
        f |= MVR_FEATURE_NORMALS;
    if (p->colors)
        f |= MVR_FEATURE_COLOR0;
    /* the extensions' code only where a material departs from glTF's core model */
    uint32_t extensions = mvr_material_extension_features(m);
    f |= extensions;
    for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
        if (!mvr_material_samples_role(m, role))
            continue;
        /* A texture whose coordinate set the primitive lacks cannot be
         * sampled (a core role is then not sampled; an extension's role
         * reads texture coordinate 0 or (0, 0): glTF forbids the case) */
        const mvr_texture_ref *t = mvr_material_role(m, role);
        const float *uv = t->texcoord == 1 ? p->uv1 : p->uv0;
        if (!uv)
            continue;
        f |= (role < MVR_CORE_ROLE_COUNT ? mvr_role_feature(role) : 0u) |
             (t->texcoord == 1 ? MVR_FEATURE_UV1 : MVR_FEATURE_UV0);
        if (t->transform.enabled)
            f |= MVR_FEATURE_TEXTURE_TRANSFORM;
    }
    if ((f & (MVR_FEATURE_NORMAL_TEX | MVR_FEATURE_ANISOTROPY)) && p->tangents && p->normals)
        f |= MVR_FEATURE_TANGENTS;
    if ((f & MVR_FEATURE_CLEARCOAT) && mvr_material_samples_role(m, MVR_ROLE_CLEARCOAT_NORMAL) && p->tangents &&
        p->normals)
        f |= MVR_FEATURE_TANGENTS;
    if (m->alpha_mode == MVR_ALPHA_MASK)
        f |= MVR_FEATURE_ALPHA_MASK;
    else if (m->alpha_mode == MVR_ALPHA_BLEND)
        f |= MVR_FEATURE_ALPHA_BLEND;
    if (m->double_sided)
        f |= MVR_FEATURE_DOUBLE_SIDED;
    if (m->unlit) {
        /* unlit reads no normal, tangent or lighting texture, and no extension */
        f |= MVR_FEATURE_UNLIT;
        f &= ~(uint32_t)(MVR_FEATURE_NORMALS | MVR_FEATURE_TANGENTS | MVR_FEATURE_NORMAL_TEX |
                         MVR_FEATURE_METAL_ROUGH_TEX | MVR_FEATURE_OCCLUSION_TEX | MVR_FEATURE_EMISSIVE_TEX |
                         extensions);
    }
    return f;
}

static void put_f(uint8_t *dst, const float *v, size_t n)
{
    memcpy(dst, v, n * sizeof(float));
}

static void put_i(uint8_t *dst, const int32_t *v, size_t n)
{
    memcpy(dst, v, n * sizeof(int32_t));
}

static bool reserve_draws(mvr_frame *f, uint32_t count)
{
    if (count <= f->draw_cap)
        return true;
    size_t bytes;
    if (!mvr_size_mul(count, sizeof *f->draws, &bytes))
        return false;
    mvr_draw *d = realloc(f->draws, bytes);
    if (!d)
        return false;
    f->draws = d;
    f->draw_cap = count;
    return true;
}

/* The blended pass back to front. Opaque and masked draws: fewest state
 * changes first (program (features), textures (group_key), the material
 * table's page), then, where by_primitive, the draws of one primitive together (the order
 * of many small draws, which instancing merges into one call per run), then
 * nearest first across materials, which cost nothing to switch (the draw
 * block names the material), so early depth rejects what nearer draws hide
 * (the boxes of scripts/peers/make_boxes.py at 1280x960: 1.73 shaded
 * fragments a covered pixel grouped by material, 1.13 front to back; 34 ->
 * 21-27 ms a frame; docs/benchmarks.md). */
static int compare_draws(const mvr_draw *a, const mvr_draw *b, bool by_primitive)
{
    if (a->pass != b->pass)
        return a->pass < b->pass ? -1 : 1;
    if (a->pass == MVR_PASS_BLEND) {
        /* back to front */
        if (a->depth != b->depth)
            return a->depth > b->depth ? -1 : 1;
        return a->block < b->block ? -1 : (a->block > b->block);
    }
    if (a->features != b->features)
        return a->features < b->features ? -1 : 1;
    if (a->group_key != b->group_key)
        return a->group_key < b->group_key ? -1 : 1;
    if (a->material_page != b->material_page)
        return a->material_page < b->material_page ? -1 : 1;
    if (by_primitive && a->primitive != b->primitive)
        return a->primitive < b->primitive ? -1 : 1;
    if (a->depth != b->depth)
        return a->depth < b->depth ? -1 : 1;
    if (a->material != b->material)
        return a->material < b->material ? -1 : 1;
    return a->block < b->block ? -1 : (a->block > b->block);
}

static int compare_draws_front_to_back(const void *a, const void *b)
{
    return compare_draws(a, b, false);
}

static int compare_draws_by_primitive(const void *a, const void *b)
{
    return compare_draws(a, b, true);
}

/* The calls the opaque and masked draws take in this order where nothing is
 * culled: a run of one primitive that binds the same is one instanced call
 * (gl/draw_list.c instance_run; deformed draws each their own). */
static uint32_t opaque_calls(const mvr_draw *d, uint32_t n)
{
    uint32_t calls = 0;
    for (uint32_t i = 0; i < n; ++i) {
        if (d[i].pass == MVR_PASS_BLEND)
            continue;
        const mvr_draw *p = i ? &d[i - 1] : NULL;
        bool same = p && p->pass == d[i].pass && mvr_draws_bind_alike(p, &d[i]) && p->deform == MVR_NO_INDEX &&
                    d[i].deform == MVR_NO_INDEX;
        calls += !same;
    }
    return calls;
}

/* More calls front to back than this, and more than twice as many, keep
 * the draws of a primitive together: instancing's saving then outweighs
 * the overdraw front to back would save (the city demo: 73 calls grouped,
 * 2,558 front to back). */
#define MVR_FRONT_TO_BACK_EXTRA_CALLS 64u

static void sort_draws(mvr_draw *d, uint32_t n)
{
    /* a scene with nothing to draw has no draw array: qsort's base must
     * not be NULL, even for zero elements */
    if (n < 2)
        return;
    qsort(d, n, sizeof *d, compare_draws_front_to_back);
    uint32_t front_to_back = opaque_calls(d, n);
    /* at most 64 calls cannot be 64 more than grouping takes: one sort */
    if (front_to_back <= MVR_FRONT_TO_BACK_EXTRA_CALLS)
        return;
    qsort(d, n, sizeof *d, compare_draws_by_primitive);
    uint32_t grouped = opaque_calls(d, n);
    if (front_to_back <= grouped + MVR_FRONT_TO_BACK_EXTRA_CALLS || front_to_back <= 2u * grouped)
        qsort(d, n, sizeof *d, compare_draws_front_to_back);
}

/* A skinned draw's joint matrices are already world and relative to the
 * origin: its model is the identity (exactly, so both skinning paths agree). */
static void pack_draw_block(uint8_t *dst, const mvr_dmat4 *world, mvr_dvec3 origin, uint32_t material,
                           const mvr_deform *deform, const uint32_t ids[4])
{
    bool skinned = deform && deform->joint_base >= 0;
    mvr_dmat4 identity = mvr_dmat4_identity();
    mvr_mat4f model = skinned ? mvr_dmat4_to_float(&identity) : mvr_dmat4_relative_to(world, origin);
    mvr_dmat4 nm = skinned ? identity : mvr_dmat4_normal_matrix(world);
    mvr_mat4f normal = mvr_dmat4_to_float(&nm);
    put_f(dst + MVR_DRAW_MODEL_OFFSET, model.m, 16);
    put_f(dst + MVR_DRAW_NORMAL_MATRIX_OFFSET, normal.m, 12);
    memcpy(dst + MVR_DRAW_IDS_OFFSET, ids, 4 * sizeof *ids);
    int32_t info[4] = {(int32_t)material, deform ? deform->joint_base : -1, deform ? deform->morph_base : -1,
                       deform ? deform->delta_base : -1};
    put_i(dst + MVR_DRAW_INFO_OFFSET, info, 4);
}

/* ---- skins and morph targets */

static bool grow_buffer(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return true;
    size_t n = *cap ? *cap : 64, bytes;
    while (n < need)
        n *= 2;
    if (!mvr_size_mul(n, elem, &bytes))
        return false;
    void *q = realloc(*p, bytes);
    if (!q)
        return false;
    *p = q;
    *cap = n;
    return true;
}

static bool deform_texels(mvr_frame *f, uint32_t count, float **out)
{
    *out = NULL;
    if (count == 0)
        return true;
    size_t need = ((size_t)f->deform_texels + count) * 4;
    if (!grow_buffer((void **)&f->deform_data, &f->deform_data_cap, need, sizeof(float)))
        return false;
    *out = f->deform_data + (size_t)f->deform_texels * 4;
    memset(*out, 0, (size_t)count * 4 * sizeof(float));
    f->deform_texels += count;
    return true;
}

/* Joint matrices of every skin a drawn node uses: in double (joint_world,
 * for bounds) and, relative to the origin and narrowed, into the texels. */
static bool pose_skins(mvr_frame *f, const mvr_scene *s, mvr_dvec3 origin)
{
    size_t cap = f->skin_first_cap;
    if (!grow_buffer((void **)&f->skin_first, &cap, s->skin_count ? s->skin_count : 1, sizeof *f->skin_first))
        return false;
    f->skin_first_cap = (uint32_t)cap;
    for (uint32_t i = 0; i < s->skin_count; ++i)
        f->skin_first[i] = MVR_NO_INDEX;
    uint32_t total = 0;
    for (uint32_t i = 0; i < s->node_count; ++i) {
        const scene_node *n = &s->nodes[i];
        if (n->skin == MVR_NO_INDEX || n->mesh == MVR_NO_INDEX || f->skin_first[n->skin] != MVR_NO_INDEX)
            continue;
        f->skin_first[n->skin] = total;
        total += s->skins[n->skin].joint_count;
    }
    cap = f->joint_world_cap;
    if (!grow_buffer((void **)&f->joint_world, &cap, total ? total : 1, sizeof *f->joint_world))
        return false;
    f->joint_world_cap = (uint32_t)cap;
    float *texels;
    if (!deform_texels(f, total * MVR_DEFORM_TEXELS_PER_JOINT, &texels))
        return false;
    f->joints = total;
    for (uint32_t k = 0; k < s->skin_count; ++k) {
        if (f->skin_first[k] == MVR_NO_INDEX)
            continue;
        mvr_dmat4 *joints = f->joint_world + f->skin_first[k];
        mvr_scene_skin_matrices(s, k, f->world, joints);
        for (uint32_t j = 0; j < s->skins[k].joint_count; ++j) {
            float *t = texels + ((size_t)f->skin_first[k] + j) * MVR_DEFORM_TEXELS_PER_JOINT * 4;
            mvr_mat4f m = mvr_dmat4_relative_to(&joints[j], origin);
            mvr_dmat4 nd = mvr_dmat4_normal_matrix(&joints[j]);
            mvr_mat4f nm = mvr_dmat4_to_float(&nd);
            memcpy(t, m.m, 16 * sizeof(float));
            for (int c = 0; c < 3; ++c) /* the normal matrix's 3x3 columns */
                memcpy(t + 16 + c * 4, nm.m + c * 4, 3 * sizeof(float));
        }
    }
    return true;
}

/* The deform of one (node, primitive), its morph header and active
 * weights written: only targets with a non-zero weight cost work. */
static bool add_deform(mvr_frame *f, const mvr_scene *s, uint32_t node, uint32_t prim, uint32_t *out)
{
    const scene_node *n = &s->nodes[node];
    const scene_primitive *p = &s->primitives[prim];
    bool skinned = mvr_scene_draw_skinned(s, n, p);
    const float *w = p->target_count ? mvr_scene_node_weights(s, n) : NULL;
    *out = MVR_NO_INDEX;
    if (!skinned && !p->target_count)
        return true;
    size_t cap = f->deform_cap;
    if (!grow_buffer((void **)&f->deforms, &cap, (size_t)f->deform_count + 1, sizeof *f->deforms))
        return false;
    f->deform_cap = (uint32_t)cap;
    mvr_deform *d = &f->deforms[f->deform_count];
    memset(d, 0, sizeof *d);
    d->node = node;
    d->primitive = prim;
    d->joint_base = skinned ? (int32_t)(f->skin_first[n->skin] * MVR_DEFORM_TEXELS_PER_JOINT) : -1;
    d->morph_base = -1;
    d->delta_base = p->target_count ? (int32_t)p->morph_base : -1;
    if (skinned)
        d->features |= MVR_FEATURE_SKIN | (p->influence_sets > 1 ? MVR_FEATURE_SKIN8 : 0u);
    if (p->target_count) {
        d->features |= MVR_FEATURE_MORPH;
        uint32_t active = 0;
        for (uint32_t t = 0; w && t < p->target_count; ++t)
            active += w[t] != 0.0f;
        float *texels;
        d->morph_base = (int32_t)f->deform_texels;
        if (!deform_texels(f, 1 + (active + 1) / 2, &texels))
            return false;
        texels[0] = (float)active;
        texels[1] = (float)p->vertex_count;
        texels[2] = (float)p->morph_attributes;
        texels[3] = (float)p->morph_slots;
        uint32_t k = 0;
        for (uint32_t t = 0; w && t < p->target_count; ++t)
            if (w[t] != 0.0f) {
                texels[4 + 2 * k] = (float)t;
                texels[4 + 2 * k + 1] = w[t];
                k++;
            }
        d->active_targets = active;
        f->morph_active += active;
    }
    if (p->normals)
        d->features |= MVR_FEATURE_NORMALS;
    if (p->tangents)
        d->features |= MVR_FEATURE_TANGENTS;
    *out = f->deform_count++;
    return true;
}

static void pack_lights(mvr_frame *f, const mvr_scene *s, mvr_dvec3 origin)
{
    memset(f->light_counts, 0, sizeof f->light_counts);
    f->lights_dropped = 0;
    uint8_t blocks[3][MVR_SHADER_MAX_LIGHTS_PER_TYPE][MVR_LIGHT_BLOCK_SIZE];
    mvr_frame_light info[3][MVR_SHADER_MAX_LIGHTS_PER_TYPE];
    for (uint32_t i = 0; i < s->node_count; ++i) {
        const scene_node *n = &s->nodes[i];
        if (n->light == MVR_NO_INDEX)
            continue;
        const mvr_light_desc *l = &s->lights[n->light];
        uint32_t type = (uint32_t)l->type;
        if (f->light_counts[type] >= MVR_SHADER_MAX_LIGHTS_PER_TYPE) {
            f->lights_dropped++;
            continue;
        }
        uint8_t *b = blocks[type][f->light_counts[type]++];
        memset(b, 0, MVR_LIGHT_BLOCK_SIZE);
        mvr_dvec3 p = mvr_dvec3_sub(mvr_dmat4_transform_point(&f->world[i], mvr_dvec3_make(0, 0, 0)), origin);
        mvr_dvec3 d = mvr_dvec3_normalize(mvr_dmat4_transform_dir(&f->world[i], mvr_dvec3_make(0, 0, -1)),
                                          mvr_dvec3_make(0, 0, -1));
        mvr_frame_light *li = &info[type][f->light_counts[type] - 1];
        li->type = l->type;
        li->position = p;
        li->direction = d;
        li->range = l->range;
        li->outer_cone_angle = l->outer_cone_angle;
        li->cast_shadows = l->cast_shadows;
        li->layers = l->layers ? l->layers : 0xffffffffu;
        li->peak = (double)fmaxf(l->color[0], fmaxf(l->color[1], l->color[2])) * l->intensity;
        float position_range[4] = {(float)p.x, (float)p.y, (float)p.z, l->range};
        float direction[4] = {(float)d.x, (float)d.y, (float)d.z, 0.0f};
        float color[4] = {l->color[0] * l->intensity, l->color[1] * l->intensity, l->color[2] * l->intensity, 0.0f};
        put_f(b + MVR_LIGHT_POSITION_RANGE_OFFSET, position_range, 4);
        put_f(b + MVR_LIGHT_DIRECTION_OFFSET, direction, 4);
        put_f(b + MVR_LIGHT_COLOR_OFFSET, color, 4);
        if (l->type == MVR_LIGHT_SPOT) {
            /* KHR_lights_punctual: scale = 1 / max(0.001, cos(inner) - cos(outer)),
             * offset = -cos(outer) * scale; attenuation = clamp(cd * scale + offset)^2 */
            float co = cosf(l->outer_cone_angle), ci = cosf(l->inner_cone_angle);
            float scale = 1.0f / fmaxf(0.001f, ci - co);
            float spot[4] = {scale, -co * scale, 0.0f, 0.0f};
            put_f(b + MVR_LIGHT_SPOT_OFFSET, spot, 4);
        }
    }
    uint8_t *dst = f->light_blocks;
    mvr_frame_light *out = f->lights;
    for (int t = 0; t < 3; ++t)
        for (uint32_t k = 0; k < f->light_counts[t]; ++k, dst += MVR_LIGHT_BLOCK_SIZE)
            memcpy(dst, blocks[t][k], MVR_LIGHT_BLOCK_SIZE), *out++ = info[t][k];
}

mvr_result mvr_frame_build(mvr_frame *f, const mvr_scene *s, mvr_dvec3 origin, uint32_t stride,
                           uint32_t material_capacity, const mvr_batch_plan *plan, char *why, size_t why_size)
{
    if (material_capacity == 0) {
        mvr_str_copy(why, why_size, "material capacity 0");
        return MVR_ERROR_INTERNAL;
    }
    if (stride < MVR_DRAW_BLOCK_SIZE) {
        mvr_str_format(why, why_size, "draw block stride %u < %u", stride, MVR_DRAW_BLOCK_SIZE);
        return MVR_ERROR_INTERNAL;
    }
    if (s->node_count > f->world_cap) {
        mvr_dmat4 *w = realloc(f->world, (size_t)s->node_count * sizeof *w);
        if (!w) {
            mvr_str_copy(why, why_size, "out of memory (world matrices)");
            return MVR_ERROR_OUT_OF_MEMORY;
        }
        f->world = w;
        f->world_cap = s->node_count;
    }
    mvr_scene_world_matrices(s, f->world);
    f->deform_count = f->deform_texels = f->joints = f->morph_active = 0;
    if (!pose_skins(f, s, origin)) {
        mvr_str_copy(why, why_size, "out of memory (joint matrices)");
        return MVR_ERROR_OUT_OF_MEMORY;
    }

    uint32_t count = 0;
    for (uint32_t i = 0; i < s->node_count; ++i)
        if (s->nodes[i].mesh != MVR_NO_INDEX)
            count += s->meshes[s->nodes[i].mesh].primitive_count;
    size_t block_bytes;
    if (!reserve_draws(f, count) || !mvr_size_mul(count ? count : 1, stride, &block_bytes)) {
        mvr_str_copy(why, why_size, "out of memory (draw list)");
        return MVR_ERROR_OUT_OF_MEMORY;
    }
    if (block_bytes > f->draw_blocks_cap) {
        uint8_t *b = realloc(f->draw_blocks, block_bytes);
        if (!b) {
            mvr_str_copy(why, why_size, "out of memory (draw blocks)");
            return MVR_ERROR_OUT_OF_MEMORY;
        }
        f->draw_blocks = b;
        f->draw_blocks_cap = block_bytes;
    }
    f->block_stride = stride;
    f->draw_count = 0;
    f->transmissive_draws = 0;
    for (uint32_t i = 0; i < s->node_count; ++i) {
        const scene_node *n = &s->nodes[i];
        if (n->mesh == MVR_NO_INDEX)
            continue;
        const mvr_dmat4 *w = &f->world[i];
        bool mirrored = mvr_dmat4_det3(w) < 0.0;
        const scene_mesh *m = &s->meshes[n->mesh];
        for (uint32_t k = 0; k < m->primitive_count; ++k) {
            uint32_t pi = m->first_primitive + k;
            const scene_primitive *p = &s->primitives[pi];
            const mvr_material_desc *mat = mvr_scene_material(s, p->material);
            mvr_draw *d = &f->draws[f->draw_count];
            if (!add_deform(f, s, i, pi, &d->deform)) {
                mvr_str_copy(why, why_size, "out of memory (morph weights)");
                return MVR_ERROR_OUT_OF_MEMORY;
            }
            d->primitive = pi;
            d->material = p->material;
            d->features = mvr_draw_features(p, mat) & ~f->disabled_features;
            d->block = f->draw_count;
            d->node = i;
            /* transmissive surfaces sample what the opaque sub-passes
             * drew behind them: after those, back to front with the
             * blended ones (blending only where their alpha mode says) */
            d->pass = mat->alpha_mode == MVR_ALPHA_BLEND || (d->features & MVR_FEATURE_TRANSMISSION) ? MVR_PASS_BLEND
                      : mat->alpha_mode == MVR_ALPHA_MASK                                         ? MVR_PASS_MASK
                                                                                                   : MVR_PASS_OPAQUE;
            f->transmissive_draws += (d->features & MVR_FEATURE_TRANSMISSION) != 0;
            d->mirrored = mirrored;
            if (d->deform == MVR_NO_INDEX) {
                mvr_dvec3 center = mvr_dvec3_scale(mvr_dvec3_add(p->bounds_min, p->bounds_max), 0.5);
                mvr_dvec3 world_center = mvr_dvec3_sub(mvr_dmat4_transform_point(w, center), origin);
                d->depth = (float)mvr_dvec3_length(world_center);
                /* bounding sphere: the box's half diagonal scaled by the largest
                 * axis scale of the world matrix (conservative under shear too) */
                double half = 0.5 * mvr_dvec3_length(mvr_dvec3_sub(p->bounds_max, p->bounds_min));
                double sx = mvr_dvec3_length(mvr_dmat4_transform_dir(w, mvr_dvec3_make(1, 0, 0)));
                double sy = mvr_dvec3_length(mvr_dmat4_transform_dir(w, mvr_dvec3_make(0, 1, 0)));
                double sz = mvr_dvec3_length(mvr_dmat4_transform_dir(w, mvr_dvec3_make(0, 0, 1)));
                d->center[0] = world_center.x;
                d->center[1] = world_center.y;
                d->center[2] = world_center.z;
                d->radius = half * fmax(sx, fmax(sy, sz)) * (1.0 + 1e-6) + 1e-9;
            } else {
                /* posed: the skeleton's and the weights' bounds, never the
                 * bind pose's (a posed character is never culled while
                 * visible); the same box shadows fit */
                const mvr_deform *df = &f->deforms[d->deform];
                mvr_dvec3 lo, hi;
                mvr_scene_posed_bounds(s, n, p, w,
                                       df->joint_base >= 0 ? f->joint_world + f->skin_first[n->skin] : NULL, &lo,
                                       &hi);
                mvr_dvec3 c = mvr_dvec3_sub(mvr_dvec3_scale(mvr_dvec3_add(lo, hi), 0.5), origin);
                d->center[0] = c.x;
                d->center[1] = c.y;
                d->center[2] = c.z;
                d->depth = (float)mvr_dvec3_length(c);
                d->radius = 0.5 * mvr_dvec3_length(mvr_dvec3_sub(hi, lo)) * (1.0 + 1e-6) + 1e-9;
                if (df->joint_base >= 0) /* the skeleton decides the winding, not the node */
                    d->mirrored = mvr_dmat4_det3(f->joint_world + f->skin_first[n->skin]) < 0.0;
                if (!f->preskin)
                    d->features |= df->features & MVR_DEFORM_FEATURES;
            }
            /* material index: the default material sits after the scene's */
            uint32_t material_slot = p->material == MVR_NO_INDEX ? s->material_count : p->material;
            d->group_key = 0;
            if (plan) {
                uint32_t neutral = mvr_batch_plan_neutral_features(plan, material_slot);
                if (mat->unlit) /* unlit reads the base color only */
                    neutral &= MVR_FEATURE_BASE_COLOR_TEX;
                /* a white layer is white at any coordinates: reading the
                 * primitive's TEXCOORD_0 for it keeps the textured materials'
                 * program */
                if (neutral && p->uv0)
                    neutral |= MVR_FEATURE_UV0;
                d->features |= neutral;
                /* the array bit only where something is sampled: a draw
                 * without textures keeps the key (and program) it has on
                 * every material path */
                if ((d->features & MVR_TEXTURE_FEATURES) || plan->materials[material_slot].extension_textures)
                    d->features |= MVR_FEATURE_MATERIAL_ARRAYS;
                d->group_key = mvr_batch_plan_group_key(plan, material_slot);
            } else {
                /* per material: its own textures, where it samples any */
                for (uint32_t role = 0; role < MVR_ROLE_COUNT && !d->group_key; ++role)
                    if (mvr_material_samples_role(mat, role))
                        d->group_key = (uint64_t)material_slot + 1u;
            }
            d->material_page = material_slot / material_capacity;
            f->draw_count++;
        }
    }
    sort_draws(f->draws, f->draw_count);
    /* blocks in draw order: a run of consecutive draws reads consecutive
     * blocks, so it can be one instanced draw over one range */
    for (uint32_t i = 0; i < f->draw_count; ++i) {
        mvr_draw *d = &f->draws[i];
        uint32_t material_slot = d->material == MVR_NO_INDEX ? s->material_count : d->material;
        d->block = i;
        /* the extra outputs' IDs: mvr's ids (index + 1) */
        const scene_node *node = &s->nodes[d->node];
        uint32_t first = node->mesh < s->mesh_count ? s->meshes[node->mesh].first_primitive : d->primitive;
        uint32_t ids[4] = {d->node + 1u, node->mesh < s->mesh_count ? node->mesh + 1u : 0u,
                           d->material == MVR_NO_INDEX ? 0u : d->material + 1u, d->primitive - first + 1u};
        pack_draw_block(f->draw_blocks + (size_t)i * stride, &f->world[d->node], origin,
                        material_slot % material_capacity, d->deform != MVR_NO_INDEX ? &f->deforms[d->deform] : NULL,
                        ids);
    }
    memset(f->pass_first, 0, sizeof f->pass_first);
    memset(f->pass_count, 0, sizeof f->pass_count);
    for (uint32_t i = f->draw_count; i-- > 0;) {
        f->pass_first[f->draws[i].pass] = i;
        f->pass_count[f->draws[i].pass]++;
    }
    pack_lights(f, s, origin);
    return MVR_OK;
}

void mvr_frame_free(mvr_frame *f)
{
    free(f->draws);
    free(f->draw_blocks);
    free(f->world);
    free(f->deforms);
    free(f->deform_data);
    free(f->joint_world);
    free(f->skin_first);
    memset(f, 0, sizeof *f);
}

void mvr_frustum_planes(const mvr_dmat4 *vp, bool reversed, mvr_frustum *out)
{
    double (*planes)[4] = out->planes;
    /* row i of a column-major matrix: m[i], m[4 + i], m[8 + i], m[12 + i] */
    double row[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            row[i][j] = vp->m[j * 4 + i];
    for (int j = 0; j < 4; ++j) {
        planes[0][j] = row[3][j] + row[0][j]; /* left:   x >= -w */
        planes[1][j] = row[3][j] - row[0][j]; /* right:  x <= w */
        planes[2][j] = row[3][j] + row[1][j]; /* bottom: y >= -w */
        planes[3][j] = row[3][j] - row[1][j]; /* top:    y <= w */
        planes[4][j] = reversed ? row[2][j] : row[3][j] + row[2][j]; /* z >= 0 (reversed) or z >= -w */
        planes[5][j] = row[3][j] - row[2][j]; /* z <= w */
    }
    for (int k = 0; k < 6; ++k) {
        double n = sqrt(planes[k][0] * planes[k][0] + planes[k][1] * planes[k][1] + planes[k][2] * planes[k][2]);
        if (!(n > 1e-300)) {
            /* no plane here (reversed-Z's infinite far: z = near > 0 always) */
            planes[k][0] = planes[k][1] = planes[k][2] = planes[k][3] = 0.0;
            continue;
        }
        for (int j = 0; j < 4; ++j)
            planes[k][j] /= n;
    }
}

bool mvr_sphere_in_frustum(const mvr_frustum *f, const double c[3], double r)
{
    for (int k = 0; k < 6; ++k) {
        const double *p = f->planes[k];
        if (p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0)
            continue;
        if (p[0] * c[0] + p[1] * c[1] + p[2] * c[2] + p[3] < -r)
            return false;
    }
    return true;
}

mvr_result mvr_visibility_compute(mvr_visibility *vis, const mvr_frame *f, const mvr_view_set *views,
                                  uint32_t width, uint32_t height, bool reversed)
{
    uint32_t words = (f->draw_count + 63) / 64;
    size_t need;
    if (!mvr_size_mul(words ? words : 1, views->count, &need))
        return MVR_ERROR_OUT_OF_MEMORY;
    if (need > vis->cap_words) {
        uint64_t *b = realloc(vis->bits, need * sizeof *b);
        if (!b)
            return MVR_ERROR_OUT_OF_MEMORY;
        vis->bits = b;
        vis->cap_words = need;
    }
    if (views->count > vis->culled_cap) {
        uint32_t *c = realloc(vis->culled, views->count * sizeof *c);
        if (!c)
            return MVR_ERROR_OUT_OF_MEMORY;
        vis->culled = c;
        vis->culled_cap = views->count;
    }
    vis->views = views->count;
    vis->words = words ? words : 1;
    memset(vis->bits, 0, need * sizeof *vis->bits);
    for (uint32_t v = 0; v < views->count; ++v) {
        const mvr_view_desc *vd = &views->views[v];
        mvr_viewport vp = mvr_view_viewport(vd, width, height);
        /* the matrix the GPU gets, in double */
        mvr_dmat4 m = mvr_view_relative_view_proj(vd, views->origin, vp, reversed);
        mvr_frustum frustum;
        mvr_frustum_planes(&m, reversed, &frustum);
        uint64_t *row = vis->bits + (size_t)v * vis->words;
        uint32_t culled = 0;
        for (uint32_t i = 0; i < f->draw_count; ++i) {
            const mvr_draw *d = &f->draws[i];
            if (mvr_sphere_in_frustum(&frustum, d->center, d->radius))
                row[i / 64] |= (uint64_t)1 << (i % 64);
            else
                culled++;
        }
        vis->culled[v] = culled;
    }
    return MVR_OK;
}

void mvr_visibility_free(mvr_visibility *vis)
{
    free(vis->bits);
    free(vis->culled);
    memset(vis, 0, sizeof *vis);
}
