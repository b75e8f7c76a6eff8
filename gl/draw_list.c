/* The draw lists of a pass: per draw its program, per-draw block range,
 * material range and textures, consecutive draws instanced; blended draws
 * back to front (per view where the views' orders diverge). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw_list.h"
#include "environment_gl.h"
#include "program_cache.h"
#include "renderer.h"
#include "skinning.h"
#include "targets.h"
#include "transmission.h"

bool mvr_draw_visible(const mvr_renderer *r, uint32_t first, uint32_t count, uint32_t draw)
{
    if (!r->culling)
        return true;
    for (uint32_t v = first; v < first + count; ++v)
        if (mvr_visible(&r->vis, v, draw))
            return true;
    return false;
}

static bool visible_in_pass(const mvr_renderer *r, const mvr_pass_context *pc, uint32_t draw)
{
    return mvr_draw_visible(r, pc->first_view, pc->views, draw);
}

typedef struct blend_key {
    double distance;
    uint32_t position;           /* in the blend list */
} blend_key;

/* back to front; equal distances keep the shared order */
static int compare_blend_keys(const void *pa, const void *pb)
{
    const blend_key *a = pa, *b = pb;
    if (a->distance != b->distance)
        return a->distance > b->distance ? -1 : 1;
    return a->position < b->position ? -1 : (a->position > b->position);
}

/* A view's eye relative to the view set's origin. */
static mvr_dvec3 view_eye(const mvr_view_set *vs, uint32_t view)
{
    const mvr_view_desc *v = &vs->views[view];
    return mvr_dvec3_sub(mvr_dvec3_make(v->position[0], v->position[1], v->position[2]), vs->origin);
}

static double blend_distance(const mvr_draw *d, mvr_dvec3 eye)
{
    return mvr_dvec3_length(mvr_dvec3_sub(mvr_dvec3_make(d->center[0], d->center[1], d->center[2]), eye));
}

/* Whether any view of the pass needs another order than the centroid
 * order: some pair of consecutive blended draws (both drawn in the pass)
 * that the view sees front to back. The centroid order is then not sorted
 * by that view's distances, so its exact order differs. */
bool mvr_blend_orders_diverge(const mvr_renderer *r, const mvr_pass_context *pc)
{
    const mvr_frame *f = &r->frame;
    for (uint32_t v = pc->first_view; v < pc->first_view + pc->views; ++v) {
        mvr_dvec3 eye = view_eye(pc->view_set, v);
        double prev = INFINITY;
        for (uint32_t i = 0; i < f->pass_count[MVR_PASS_BLEND]; ++i) {
            uint32_t pos = f->pass_first[MVR_PASS_BLEND] + i;
            if (!visible_in_pass(r, pc, pos))
                continue;
            double d = blend_distance(&f->draws[pos], eye);
            if (d > prev)
                return true;
            prev = d;
        }
    }
    return false;
}

/* Per-view transparency order: the blend list sorted by distance from the
 * pass's one view (relative to the origin, in double, as the centroid
 * order is from the origin). Returns NULL when the centroid order applies. */
static const blend_key *per_view_blend_order(mvr_renderer *r, const mvr_pass_context *pc)
{
    const mvr_frame *f = &r->frame;
    uint32_t n = f->pass_count[MVR_PASS_BLEND];
    if (r->blend_policy == MVR_TRANSPARENCY_ORDER_CENTROID || pc->views != 1 || n < 2)
        return NULL;
    if (n > r->blend_order_cap) {
        void *p = realloc(r->blend_order, (size_t)n * sizeof(blend_key));
        if (!p)
            return NULL; /* out of memory: the shared order still draws */
        r->blend_order = p;
        r->blend_order_cap = n;
    }
    blend_key *keys = r->blend_order;
    mvr_dvec3 eye = view_eye(pc->view_set, pc->first_view);
    for (uint32_t i = 0; i < n; ++i) {
        keys[i].distance = blend_distance(&f->draws[f->pass_first[MVR_PASS_BLEND] + i], eye);
        keys[i].position = i;
    }
    qsort(keys, n, sizeof *keys, compare_blend_keys);
    return keys;
}


/* The features overrides.force_inert_features adds to a draw's key: each compiles
 * code in that cannot change this draw's pixels. A disabled texture
 * transform is the identity (exact: x * 1 + y * -0 + 0); UV sets only feed
 * sampling a draw's material selects by its own bits; a missing COLOR_0
 * reads the generic attribute, set to (1, 1, 1, 1) (exact); tangents only
 * matter with a normal map; the array bit without textures only renames
 * sampler macros. Normals, alpha modes, double-sidedness and unlit change
 * shading, so they are never forced. */
static uint32_t inert_features(const mvr_renderer *r, uint32_t features)
{
    uint32_t f = MVR_FEATURE_TEXTURE_TRANSFORM | MVR_FEATURE_UV0 | MVR_FEATURE_UV1 | MVR_FEATURE_COLOR0;
    if (!(features & MVR_FEATURE_NORMAL_TEX))
        f |= MVR_FEATURE_TANGENTS;
    if (r->gpu.arrays)
        f |= MVR_FEATURE_MATERIAL_ARRAYS;
    return f;
}

/* What the outputs-only pass keeps of a blended draw's features: its
 * geometry, normals and alpha; nothing that lights. */
#define OUTPUTS_ONLY_FEATURES                                                                                         \
    (MVR_FEATURE_NORMALS | MVR_FEATURE_UV0 | MVR_FEATURE_UV1 | MVR_FEATURE_COLOR0 | MVR_FEATURE_BASE_COLOR_TEX |       \
     MVR_FEATURE_TEXTURE_TRANSFORM | MVR_FEATURE_ALPHA_BLEND | MVR_FEATURE_DOUBLE_SIDED | MVR_FEATURE_MATERIAL_ARRAYS | \
     MVR_DEFORM_FEATURES)

static mvr_result bind_program(mvr_pass_context *pc, uint32_t features)
{
    mvr_renderer *r = pc->r;
    mvr_program_entry *e = pc->last_program;
    if (!e || pc->last_features != features) {
        const mvr_frame *f = &r->frame;
        uint32_t all = features | pc->output_features | (r->force_inert_features ? inert_features(r, features) : 0u);
        if (pc->outputs_only)
            all = features & OUTPUTS_ONLY_FEATURES;
        mvr_shader_variant v = mvr_mesh_variant(r, all, pc->num_views);
        v.outputs = (uint8_t)(pc->shader_outputs | (pc->outputs_only ? MVR_SHADER_OUT_ONLY : 0u));
        if (!pc->outputs_only) {
            v.directional_lights = (uint8_t)f->light_counts[0];
            v.point_lights = (uint8_t)f->light_counts[1];
            v.spot_lights = (uint8_t)f->light_counts[2];
        }
        mvr_result res = mvr_program_cache_get(r, &v, &e);
        if (res != MVR_OK)
            return res;
        pc->last_program = e;
        pc->last_features = features;
    }
    mvr_state_program(&r->state, e->program);
    const mvr_gl_api_table *gl = r->gl;
    if (pc->outputs_only && e->output_alpha_cutoff != pc->output_alpha_cutoff) {
        gl->Uniform1f(e->loc_output_alpha_cutoff, pc->output_alpha_cutoff);
        e->output_alpha_cutoff = pc->output_alpha_cutoff;
    }
    if (e->view_base != pc->view_base) {
        gl->Uniform1i(e->loc_view_base, pc->view_base);
        e->view_base = pc->view_base;
    }
    mvr_transmission_set_uniforms(r, e);
    if (e->frame_serial != r->frame_serial) {
        gl->Uniform3fv(e->loc_ambient, 1, pc->scene->ambient);
        gl->Uniform1f(e->loc_exposure, pc->mesh_exposure);
        if (e->variant.features & MVR_FEATURE_IBL)
            mvr_environment_set_uniforms(r, e, pc->desc->environment, pc->desc->environment_samples);
        e->frame_serial = r->frame_serial;
    }
    return MVR_OK;
}

/* Instancing: how many visible draws from position i of a pass list form
 * one instanced draw (*instances), and how many list positions that spans
 * (the return value). The draws' blocks must be consecutive: the frame
 * stores blocks in draw order, so without compaction the draws must follow
 * each other and all be visible; in a compacted pass culled draws between
 * them are skipped. They share what a draw binds: primitive, program
 * features, winding, and the material table page and textures (group_key:
 * the texture-array groups, or a textured material itself; draws without
 * textures share it whatever their material, which the draw block names).
 * Instances are drawn in order, as the separate draws would be, so pixels do
 * not change. Blended draws stay single: their order is the sort's
 * back-to-front. */
static uint32_t instance_run(const mvr_pass_context *pc, mvr_pass_kind kind, uint32_t i, uint32_t *instances)
{
    const mvr_renderer *r = pc->r;
    const mvr_frame *f = &r->frame;
    *instances = 1;
    if (r->draw_capacity <= 1 || kind == MVR_PASS_BLEND)
        return 1;
    const mvr_draw *a = &f->draws[f->pass_first[kind] + i];
    bool compacted = pc->compact >= 0;
    uint32_t n = 1, span = 1;
    while (n < r->draw_capacity && i + span < f->pass_count[kind]) {
        uint32_t pos = f->pass_first[kind] + i + span;
        if (!visible_in_pass(r, pc, pos)) {
            if (!compacted)
                break;
            span++;
            continue;
        }
        const mvr_draw *b = &f->draws[pos];
        /* a pre-skinned draw has its own captured vertices: never instanced */
        bool same = mvr_draws_bind_alike(a, b) && !mvr_skinning_vao(r, a) && !mvr_skinning_vao(r, b);
        if (!same)
            break;
        n++;
        span++;
    }
    *instances = n;
    return span;
}

void mvr_bind_draw_textures(mvr_renderer *r, const mvr_draw *d, uint32_t features, uint8_t *groups_used,
                            uint32_t *groups_used_count)
{
    const mvr_gpu_scene *g = &r->gpu;
    mvr_state_cache *st = &r->state;
    uint32_t slot = d->material == MVR_NO_INDEX ? g->material_count - 1 : d->material;
    if (g->arrays) {
        /* one array per role and group: binds change only at group boundaries */
        const mvr_material_slots *ms = &g->plan.materials[slot];
        for (uint32_t k = 0; k < MVR_ROLE_COUNT; ++k) {
            if (!(features & mvr_role_feature(k)) || ms->group[k] == MVR_NO_GROUP)
                continue;
            uint16_t grp = ms->group[k];
            GLuint unit = (GLuint)mvr_role_unit(k);
            mvr_state_texture(st, unit, GL_TEXTURE_2D_ARRAY, g->group_textures[grp]);
            mvr_state_sampler(st, unit, g->group_samplers[grp]);
            if (groups_used && !groups_used[grp]) {
                groups_used[grp] = 1;
                (*groups_used_count)++;
            }
        }
    } else {
        const mvr_gpu_material *m = &g->materials[slot];
        for (uint32_t k = 0; k < MVR_ROLE_COUNT; ++k) {
            /* an extension's role without a texture is not sampled (its bit in the block is clear) */
            if (!(features & mvr_role_feature(k)) || (k >= MVR_CORE_ROLE_COUNT && !m->textures[k]))
                continue;
            GLuint unit = (GLuint)mvr_role_unit(k);
            mvr_state_texture(st, unit, GL_TEXTURE_2D, m->textures[k]);
            mvr_state_sampler(st, unit, m->samplers[k]);
        }
    }
}

void mvr_submit_draw(mvr_renderer *r, const mvr_draw *d, uint32_t instances)
{
    const mvr_gl_api_table *gl = r->gl;
    bool double_sided = (d->features & MVR_FEATURE_DOUBLE_SIDED) != 0;
    mvr_state_cull(&r->state, !double_sided, d->mirrored ? GL_CW : GL_CCW);
    const mvr_gpu_primitive *p = &r->gpu.primitives[d->primitive];
    GLuint captured = mvr_skinning_vao(r, d);
    mvr_state_vao(&r->state, captured ? captured : p->vao);
    if (instances > 1) {
        if (p->ibo)
            gl->DrawElementsInstanced(p->mode, p->count, p->index_type, NULL, (GLsizei)instances);
        else
            gl->DrawArraysInstanced(p->mode, 0, p->count, (GLsizei)instances);
    } else if (p->ibo) {
        gl->DrawElements(p->mode, p->count, p->index_type, NULL);
    } else {
        gl->DrawArrays(p->mode, 0, p->count);
    }
}

_Static_assert(MVR_PASS_KIND_COUNT == 3, "mvr_frame_stats.sub_passes has one entry per pass kind");

mvr_result mvr_draw_list(mvr_pass_context *pc, mvr_pass_kind kind)
{
    mvr_renderer *r = pc->r;
    const mvr_frame *f = &r->frame;
    const mvr_gpu_scene *g = &r->gpu;
    mvr_state_cache *st = &r->state;
    GLenum depth_func = r->reversed_z ? GL_GREATER : GL_LESS;
    /* pass skipping: a list with nothing visible in this pass sets no state
     * (no transparent draws, no blend sub-pass) */
    uint32_t first_visible = f->pass_count[kind];
    for (uint32_t i = 0; i < f->pass_count[kind] && first_visible == f->pass_count[kind]; ++i)
        if (visible_in_pass(r, pc, f->pass_first[kind] + i))
            first_visible = i;
    if (first_visible == f->pass_count[kind])
        return MVR_OK;
    if (!pc->outputs_only)
        r->stats.sub_passes[kind]++;
    if (pc->outputs_only) {
        /* the front-most surface above the cutoff: depth written; a
         * transmissive surface meets its own depth (<= / >=) */
        mvr_state_depth(st, true, r->reversed_z ? GL_GEQUAL : GL_LEQUAL, GL_TRUE);
        mvr_state_blend(st, false, GL_ONE, GL_ZERO, GL_ONE, GL_ZERO);
    } else if (kind == MVR_PASS_BLEND) {
        /* glTF BLEND: non-premultiplied "over"; blended surfaces do not write depth */
        mvr_state_depth(st, true, depth_func, GL_FALSE);
        mvr_state_blend(st, true, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        /* their outputs come from the outputs-only pass (an ID is not blended) */
        mvr_target_draw_buffers(pc->target, MVR_DRAW_COLOR);
    } else {
        mvr_state_depth(st, true, depth_func, GL_TRUE);
        mvr_state_blend(st, false, GL_ONE, GL_ZERO, GL_ONE, GL_ZERO);
    }
    /* the draw block's declared size: a bound range must cover it */
    GLsizeiptr draw_range = r->draw_capacity > 1 ? (GLsizeiptr)r->draw_capacity * r->draw_stride
                                                 : (GLsizeiptr)MVR_DRAW_BLOCK_SIZE;
    const blend_key *order = kind == MVR_PASS_BLEND ? per_view_blend_order(r, pc) : NULL;
    for (uint32_t i = order ? 0 : first_visible; i < f->pass_count[kind]; ++i) {
        uint32_t pos = f->pass_first[kind] + (order ? order[i].position : i);
        const mvr_draw *d = &f->draws[pos];
        if (!visible_in_pass(r, pc, pos))
            continue;
        if (kind == MVR_PASS_BLEND && !pc->outputs_only) {
            /* a transmissive surface not blended by its alpha mode writes
             * depth, opaque, in the back-to-front order */
            bool blended = (d->features & MVR_FEATURE_ALPHA_BLEND) != 0;
            mvr_state_depth(st, true, depth_func, blended ? GL_FALSE : GL_TRUE);
            mvr_state_blend(st, blended, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        }
        uint32_t instances;
        uint32_t span = instance_run(pc, kind, i, &instances);
        mvr_result res = bind_program(pc, d->features);
        if (res != MVR_OK)
            return res;
        GLintptr block_at = pc->lay->draws + (GLintptr)d->block * f->block_stride;
        if (pc->compact >= 0 && kind != MVR_PASS_BLEND) {
            block_at = pc->compact + (GLintptr)pc->compact_next * f->block_stride;
            pc->compact_next += instances;
        }
        mvr_state_ubo_range(st, MVR_BLOCK_DRAW, r->ring.buffer, block_at, draw_range);
        if (r->material_path == MVR_MATERIAL_PATH_PER_DRAW) /* baseline: a fragment-visible range per draw */
            mvr_state_ubo_range(st, MVR_BLOCK_MATERIALS, r->ring.buffer,
                                pc->lay->draw_materials + (GLintptr)d->block * pc->lay->draw_material_stride,
                                (GLsizeiptr)r->material_capacity * MVR_MATERIAL_BLOCK_SIZE);
        else
            mvr_state_ubo_range(st, MVR_BLOCK_MATERIALS, g->material_ubo,
                                (GLintptr)d->material_page * g->material_page_stride,
                                (GLsizeiptr)r->material_capacity * MVR_MATERIAL_BLOCK_SIZE);
        mvr_bind_draw_textures(r, d, pc->outputs_only ? d->features & OUTPUTS_ONLY_FEATURES : d->features,
                               pc->groups_used, &pc->groups_used_count);
        mvr_submit_draw(r, d, instances);
        r->stats.instanced_draw_calls += instances > 1;
        r->stats.draws += instances;
        r->stats.draw_calls++;
        i += span - 1;
    }
    if (kind == MVR_PASS_BLEND && !pc->outputs_only)
        mvr_target_draw_buffers(pc->target, MVR_DRAW_ALL);
    return MVR_OK;
}
