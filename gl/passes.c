/*
 * The frame: per-draw data written once into the uniform ring whatever the
 * number of views, then one framebuffer pass per chunk of views (multiview:
 * up to GL_MAX_VIEWS_OVR consecutive layers sharing a viewport) or per view
 * (loop), each drawing the opaque, alpha-masked and blended draws in order.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "environment.h"
#include "renderer_internal.h"

/* Views per uniform block (MVR_MAX_VIEWS of shaders/views.glsl); the
 * block's layout is MVR_VIEWS_* of core/frame.h. */
#define VIEWS_PER_BLOCK MVR_VIEWS_PER_BLOCK
#define VIEW_INFO_SIZE MVR_VIEW_INFO_SIZE /* one ivec4 of mvr_view_info: the view's light mask */
#define VIEW_BLOCK_SIZE MVR_VIEWS_BLOCK_SIZE

static GLsizeiptr align_up(GLsizeiptr v, GLsizeiptr a)
{
    return (v + a - 1) / a * a;
}

/* Exact sRGB encode (IEC 61966-2-1) for clear colors of UNORM targets. */
static float srgb_encode(float c)
{
    c = c < 0.0f ? 0.0f : c > 1.0f ? 1.0f : c;
    return c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

typedef struct frame_layout {
    GLintptr draws, lights;          /* in the ring's static region (re-sent only on change) */
    GLintptr views;                  /* in this frame's ring segment */
    GLsizeiptr lights_size;
    uint32_t view_blocks;
    GLintptr draw_materials;         /* per-draw baseline: a material block per draw */
    GLsizeiptr draw_material_stride;
    GLintptr *compact;               /* per chunk: its compacted blocks in this segment, or -1 */
    GLintptr shadow_views;           /* the shadow pass's view block: caster matrices */
    GLintptr shadow_block;           /* the receivers' mvr_shadows block */
} frame_layout;

/* Whether a draw (by position in the frame's list) is visible in any of the
 * views [first, first + count). */
static bool visible_in_views(const mvr_renderer *r, uint32_t first, uint32_t count, uint32_t draw)
{
    if (!r->culling)
        return true;
    for (uint32_t v = first; v < first + count; ++v)
        if (mvr_visible(&r->vis, v, draw))
            return true;
    return false;
}

/* Per-pass compaction. Instanced draws read consecutive blocks, so a draw
 * culled in the middle of a run splits it (city, 2 views: 2640 visible
 * draws took ~830 calls instead of ~73). Where a pass culled anything, the
 * blocks of its visible opaque and masked draws are copied, in draw order,
 * into this frame's segment; runs then skip culled draws. Blended draws are
 * never instanced and keep reading the static blocks. Returns the bytes
 * the chunk needs (0 = not compacted). */
static GLsizeiptr compact_size(const mvr_renderer *r, const mvr_view_chunk *ch)
{
    const mvr_frame *f = &r->frame;
    if (!r->culling || r->draw_capacity <= 1 || r->material_path == MVR_MATERIAL_PATH_PER_DRAW)
        return 0;
    uint32_t visible = 0, listed = 0;
    for (int k = 0; k < MVR_PASS_KIND_COUNT; ++k) {
        if (k == MVR_PASS_BLEND)
            continue;
        listed += f->pass_count[k];
        for (uint32_t i = 0; i < f->pass_count[k]; ++i)
            visible += visible_in_views(r, ch->base, ch->count, f->pass_first[k] + i);
    }
    if (visible == listed || visible < 2) /* nothing culled, or no run to keep */
        return 0;
    return (GLsizeiptr)visible * f->block_stride;
}

/* Writes the compacted blocks of every chunk that needs them (one upload). */
static mvr_result upload_compacted(mvr_renderer *r, const mvr_view_chunk *chunks, uint32_t chunk_count,
                                   frame_layout *lay, GLintptr at, GLsizeiptr bytes)
{
    const mvr_frame *f = &r->frame;
    if (bytes == 0)
        return MVR_OK;
    if ((size_t)bytes > r->compact_scratch_cap) {
        uint8_t *p = realloc(r->compact_scratch, (size_t)bytes);
        if (!p)
            return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "compacted blocks: out of memory");
        r->compact_scratch = p;
        r->compact_scratch_cap = (size_t)bytes;
    }
    size_t w = 0;
    for (uint32_t c = 0; c < chunk_count; ++c) {
        if (lay->compact[c] < 0)
            continue;
        lay->compact[c] = at + (GLintptr)w;
        for (int k = 0; k < MVR_PASS_KIND_COUNT; ++k) {
            if (k == MVR_PASS_BLEND)
                continue;
            for (uint32_t i = 0; i < f->pass_count[k]; ++i) {
                uint32_t pos = f->pass_first[k] + i;
                if (!visible_in_views(r, chunks[c].base, chunks[c].count, pos))
                    continue;
                memcpy(r->compact_scratch + w, f->draw_blocks + (size_t)f->draws[pos].block * f->block_stride,
                       f->block_stride);
                w += f->block_stride;
            }
        }
    }
    r->gl->BufferSubData(GL_UNIFORM_BUFFER, at, (GLsizeiptr)w, r->compact_scratch);
    r->stats.compacted_bytes += w;
    return MVR_OK;
}

/* Sends the per-draw blocks and lights into the ring's static region: only
 * when the frame was rebuilt (a transform, material, geometry or the origin
 * changed) or the ring was replaced. */
static mvr_result upload_static(mvr_renderer *r)
{
    const mvr_gl_api_table *gl = r->gl;
    mvr_frame *f = &r->frame;
    GLsizeiptr align = (GLsizeiptr)r->ubo_alignment;
    if (r->material_path == MVR_MATERIAL_PATH_PER_DRAW)
        for (uint32_t i = 0; i < f->draw_count; ++i) {
            int32_t zero = 0; /* per-draw baseline: each draw reads element 0 of its own range */
            memcpy(f->draw_blocks + (size_t)i * f->block_stride + MVR_DRAW_INFO_OFFSET, &zero, sizeof zero);
        }
    GLsizeiptr draw_bytes = (GLsizeiptr)f->draw_count * f->block_stride;
    uint32_t light_count = f->light_counts[0] + f->light_counts[1] + f->light_counts[2];
    GLsizeiptr lights_size = (GLsizeiptr)light_count * MVR_LIGHT_BLOCK_SIZE;
    GLsizeiptr rel_lights = align_up(draw_bytes, align);
    bool reallocated = false;
    mvr_result res = mvr_ring_reserve_static(r, align_up(rel_lights + lights_size, align) + align, &reallocated);
    if (res != MVR_OK)
        return res;
    gl->BindBuffer(GL_UNIFORM_BUFFER, r->ring.buffer);
    if (draw_bytes)
        gl->BufferSubData(GL_UNIFORM_BUFFER, 0, draw_bytes, f->draw_blocks);
    if (lights_size)
        gl->BufferSubData(GL_UNIFORM_BUFFER, rel_lights, lights_size, f->light_blocks);
    r->upload_bytes += (uint64_t)draw_bytes + (uint64_t)lights_size;
    return MVR_OK;
}

static mvr_result upload_frame(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t,
                               const mvr_view_chunk *chunks, uint32_t chunk_count, frame_layout *lay,
                               bool static_current)
{
    const mvr_gl_api_table *gl = r->gl;
    const mvr_frame *f = &r->frame;
    GLsizeiptr align = (GLsizeiptr)r->ubo_alignment;
    GLsizeiptr draw_bytes = (GLsizeiptr)f->draw_count * f->block_stride;
    uint32_t light_count = f->light_counts[0] + f->light_counts[1] + f->light_counts[2];
    lay->lights_size = (GLsizeiptr)light_count * MVR_LIGHT_BLOCK_SIZE;
    lay->draws = 0;
    lay->lights = align_up(draw_bytes, align);
    lay->view_blocks = (views->count + VIEWS_PER_BLOCK - 1) / VIEWS_PER_BLOCK;
    GLsizeiptr view_block_stride = align_up(VIEW_BLOCK_SIZE, align);
    GLsizeiptr total = view_block_stride * lay->view_blocks;
    /* the per-draw baseline: each draw's material in its own range, sent every
     * frame as such a renderer would (plus a tail: a bound range covers the
     * whole declared block) */
    bool per_draw = r->material_path == MVR_MATERIAL_PATH_PER_DRAW;
    GLsizeiptr table_bytes = (GLsizeiptr)r->material_capacity * MVR_MATERIAL_BLOCK_SIZE;
    lay->draw_material_stride = align_up(MVR_MATERIAL_BLOCK_SIZE, align);
    GLsizeiptr rel_materials = align_up(total, align);
    if (per_draw)
        total = rel_materials + lay->draw_material_stride * (GLsizeiptr)f->draw_count + table_bytes;
    GLsizeiptr rel_compact = align_up(total, align), compact_bytes = 0;
    for (uint32_t c = 0; c < chunk_count; ++c) {
        GLsizeiptr n = compact_size(r, &chunks[c]);
        lay->compact[c] = n ? 0 : -1;
        compact_bytes += n;
    }
    if (compact_bytes) /* and a tail: an instanced draw's range covers a whole block array */
        total = rel_compact + compact_bytes + (GLsizeiptr)r->draw_capacity * r->draw_stride;
    const mvr_shadow_plan *plan = &r->shadows.plan;
    GLsizeiptr rel_shadow_views = align_up(total, align);
    GLsizeiptr rel_shadow_block = align_up(rel_shadow_views + (GLsizeiptr)VIEW_BLOCK_SIZE, align);
    if (plan->layer_count)
        total = rel_shadow_block + (GLsizeiptr)MVR_SHADOW_BLOCK_SIZE;
    mvr_result res = static_current ? MVR_OK : upload_static(r);
    if (res != MVR_OK)
        return res;
    bool reallocated = false;
    res = mvr_ring_begin_frame(r, total, &reallocated);
    if (res == MVR_OK && reallocated) /* a new buffer: its static region is empty */
        res = upload_static(r);
    if (res != MVR_OK)
        return res;
    r->frame_key.valid = true;
    GLintptr seg = r->ring.static_size + (GLintptr)r->ring.current * r->ring.segment_size;
    lay->views = seg;
    lay->draw_materials = seg + rel_materials;
    lay->shadow_views = seg + rel_shadow_views;
    lay->shadow_block = seg + rel_shadow_block;
    if (plan->layer_count) {
        /* the casters' matrices, as views of the shadow pass; the receivers' block */
        float casters[MVR_SHADOW_MAX_LAYERS][16];
        for (uint32_t k = 0; k < plan->layer_count; ++k) {
            mvr_mat4f m = mvr_dmat4_to_float(&plan->layers[k].view_proj);
            memcpy(casters[k], m.m, sizeof casters[k]);
        }
        gl->BufferSubData(GL_UNIFORM_BUFFER, lay->shadow_views + (GLintptr)MVR_VIEWS_VIEW_PROJ_OFFSET,
                          (GLsizeiptr)plan->layer_count * MVR_VIEW_MATRIX_SIZE, casters);
        uint8_t block[MVR_SHADOW_BLOCK_SIZE];
        mvr_shadow_block_pack(plan, &r->shadows.settings, r->reversed_z, block);
        gl->BufferSubData(GL_UNIFORM_BUFFER, lay->shadow_block, (GLsizeiptr)sizeof block, block);
        r->upload_bytes += (uint64_t)plan->layer_count * MVR_VIEW_MATRIX_SIZE + sizeof block;
    }
    if (per_draw && f->draw_count) {
        uint8_t *mats = calloc((size_t)lay->draw_material_stride, f->draw_count);
        if (!mats)
            return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "per-draw materials: out of memory");
        for (uint32_t i = 0; i < f->draw_count; ++i) {
            const mvr_draw *d = &f->draws[i];
            mvr_material_pack(mvr_scene_material(r->gpu.scene, d->material), NULL,
                              mats + (size_t)d->block * (size_t)lay->draw_material_stride);
        }
        gl->BufferSubData(GL_UNIFORM_BUFFER, lay->draw_materials,
                          lay->draw_material_stride * (GLsizeiptr)f->draw_count, mats);
        r->upload_bytes += (uint64_t)lay->draw_material_stride * f->draw_count;
        free(mats);
    }
    /* per view: its matrix and eye position, relative to the set's origin */
    float matrices[VIEWS_PER_BLOCK][16];
    float eyes[VIEWS_PER_BLOCK][4];
    int32_t infos[VIEWS_PER_BLOCK][4];
    float view_matrices[VIEWS_PER_BLOCK][16]; /* extra outputs only */
    bool outputs = t->shader_outputs != 0;
    for (uint32_t b = 0; b < lay->view_blocks; ++b) {
        uint32_t first = b * VIEWS_PER_BLOCK;
        uint32_t n = views->count - first < VIEWS_PER_BLOCK ? views->count - first : VIEWS_PER_BLOCK;
        for (uint32_t k = 0; k < n; ++k) {
            const mvr_view_desc *v = &views->views[first + k];
            mvr_viewport vp = mvr_view_viewport(v, t->desc.width, t->desc.height);
            mvr_view_gpu_matrices(v, views->origin, vp, r->reversed_z, matrices[k], eyes[k]);
            if (outputs)
                mvr_view_gpu_view_matrix(v, views->origin, view_matrices[k]);
            uint32_t mask = mvr_view_light_mask(f, v);
            memset(infos[k], 0, sizeof infos[k]);
            memcpy(&infos[k][0], &mask, sizeof mask);
        }
        GLintptr at = lay->views + (GLintptr)b * view_block_stride;
        gl->BufferSubData(GL_UNIFORM_BUFFER, at + (GLintptr)MVR_VIEWS_VIEW_PROJ_OFFSET,
                          (GLsizeiptr)n * MVR_VIEW_MATRIX_SIZE, matrices);
        gl->BufferSubData(GL_UNIFORM_BUFFER, at + (GLintptr)MVR_VIEWS_EYE_POSITION_OFFSET,
                          (GLsizeiptr)n * MVR_VIEW_EYE_SIZE, eyes);
        gl->BufferSubData(GL_UNIFORM_BUFFER, at + (GLintptr)MVR_VIEWS_VIEW_INFO_OFFSET,
                          (GLsizeiptr)n * VIEW_INFO_SIZE, infos);
        r->view_upload_bytes += (uint64_t)n * (MVR_VIEW_MATRIX_SIZE + MVR_VIEW_EYE_SIZE + VIEW_INFO_SIZE);
        if (outputs) {
            gl->BufferSubData(GL_UNIFORM_BUFFER, at + (GLintptr)MVR_VIEWS_VIEW_MATRIX_OFFSET,
                              (GLsizeiptr)n * MVR_VIEW_MATRIX_SIZE, view_matrices);
            r->view_upload_bytes += (uint64_t)n * MVR_VIEW_MATRIX_SIZE;
        }
    }
    return upload_compacted(r, chunks, chunk_count, lay, seg + rel_compact, compact_bytes);
}

typedef struct pass_context {
    mvr_renderer *r;
    const mvr_scene *scene;
    const frame_layout *lay;
    const mvr_render_desc *desc;
    uint32_t output_features;
    uint32_t shader_outputs;     /* the target's extra outputs (MVR_SHADER_OUT_*, 0 = none) */
    bool outputs_only;           /* the blended draws' outputs pass */
    float output_alpha_cutoff;
    uint32_t num_views;          /* 0 on the loop path */
    int32_t view_base;           /* within the bound view block */
    uint32_t last_features;      /* program lookup cache */
    mvr_program_entry *last_program;
    uint8_t *groups_used;        /* array path: groups sampled in this pass */
    uint32_t groups_used_count;
    uint32_t first_view, views;  /* the pass's views: a draw visible in any is drawn */
    float mesh_exposure;         /* the linear exposure, or an HDR frame's pre-exposure */
    GLintptr compact;            /* the pass's compacted blocks, or -1 */
    uint32_t compact_next;       /* next compacted block to draw */
    const mvr_view_set *view_set;
    mvr_target *target;
} pass_context;

static bool visible_in_pass(const mvr_renderer *r, const pass_context *pc, uint32_t draw)
{
    return visible_in_views(r, pc->first_view, pc->views, draw);
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
static bool blend_orders_diverge(const mvr_renderer *r, const pass_context *pc)
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
static const blend_key *per_view_blend_order(mvr_renderer *r, const pass_context *pc)
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

static mvr_result bind_program(pass_context *pc, uint32_t features)
{
    mvr_renderer *r = pc->r;
    mvr_program_entry *e = pc->last_program;
    if (!e || pc->last_features != features) {
        const mvr_frame *f = &r->frame;
        uint32_t all = features | pc->output_features | (r->force_inert_features ? inert_features(r, features) : 0u);
        if (pc->outputs_only)
            all = features & OUTPUTS_ONLY_FEATURES;
        mvr_shader_variant v = mvr_renderer_mesh_variant(r, all, pc->num_views);
        v.outputs = (uint8_t)(pc->shader_outputs | (pc->outputs_only ? MVR_SHADER_OUT_ONLY : 0u));
        if (!pc->outputs_only) {
            v.directional_lights = (uint8_t)f->light_counts[0];
            v.point_lights = (uint8_t)f->light_counts[1];
            v.spot_lights = (uint8_t)f->light_counts[2];
        }
        mvr_result res = mvr_renderer_program(r, &v, &e);
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
 * features, winding, and the material table page and textures (the
 * texture-array group on the array path, the material itself otherwise).
 * Instances are drawn in order, as the separate draws would be, so pixels do
 * not change. Blended draws stay single: their order is the sort's
 * back-to-front. */
static uint32_t instance_run(const pass_context *pc, mvr_pass_kind kind, uint32_t i, uint32_t *instances)
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
        bool same = b->primitive == a->primitive && !mvr_skinning_vao(r, a) && !mvr_skinning_vao(r, b) &&
                    b->features == a->features && b->mirrored == a->mirrored &&
                    b->material_page == a->material_page &&
                    (r->gpu.arrays ? b->group_key == a->group_key : b->material == a->material);
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

static mvr_result draw_list(pass_context *pc, mvr_pass_kind kind)
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

/* ------------------------------------------------------------------ the frame
 * mvr_renderer_draw_frame prepares the frame's CPU data, builds its plan
 * (core/frame_plan.c) and executes the records in order, one function per
 * record kind. */

/* The executor's state: the frame's layout and constants, and the chunk
 * whose view pass is running. */
typedef struct frame_exec {
    mvr_renderer *r;
    const mvr_view_set *views;
    mvr_target *t;
    const mvr_render_desc *desc;
    const mvr_frame_plan *plan;
    bool static_current;         /* the frame's static blocks are uploaded already */
    bool ring_begun;             /* this frame's ring segment is in use */
    frame_layout lay;
    pass_context pc;
    double pre_exposure;
    float clear[4], clear_depth;
    GLsizeiptr view_block_stride;
    uint32_t light_total;
    /* the current chunk */
    GLuint fbo, msaa_fbo;        /* its layers' framebuffer; the multisampled one views draw into */
    GLuint draw_fbo;             /* the one its sub-passes draw into */
    bool split;                  /* its blended draws go per view */
    uint32_t block;              /* its view block */
    mvr_state_counters before;
    uint32_t draws_before;
} frame_exec;

/* The per-draw baseline re-binds textures and uniform ranges every draw. */
static void st_rebind_setup(mvr_renderer *r)
{
    r->state.rebind_always = r->material_path == MVR_MATERIAL_PATH_PER_DRAW;
}

/* The frame's CPU data: draw list and blocks (rebuilt only when what they
 * depend on changed: *same says they did not), visibility, shadow layers. */
static mvr_result prepare_frame(mvr_renderer *r, const mvr_scene *scene, const mvr_view_set *views,
                                const mvr_target *t, const mvr_render_desc *desc, bool *same)
{
    char why[256] = "";
    uint32_t stride = (uint32_t)align_up(MVR_DRAW_BLOCK_SIZE, (GLsizeiptr)r->ubo_alignment);
    /* dirty tracking: the same scene state seen from the same origin reuses
     * the frame and its uploaded blocks (a static scene sends only views) */
    /* where skinning runs decides the draws' programs: a change rebuilds */
    r->skinning.path = mvr_skinning_choose(r, scene, views->count);
    bool preskin = r->skinning.path == MVR_SKINNING_PATH_PRESKIN;
    *same = r->frame_key.valid && r->frame.preskin == preskin && r->frame_key.arrays == r->gpu.arrays &&
            r->frame_key.scene_serial == mvr_scene_serial(scene) &&
            r->frame_key.geometry_version == scene->geometry_version &&
            r->frame_key.material_version == scene->material_version &&
            r->frame_key.transform_version == scene->transform_version &&
            r->frame_key.origin.x == views->origin.x && r->frame_key.origin.y == views->origin.y &&
            r->frame_key.origin.z == views->origin.z;
    mvr_result res = MVR_OK;
    if (!*same) {
        r->frame_key.valid = false;
        r->frame.preskin = preskin;
        res = mvr_frame_build(&r->frame, scene, views->origin, stride, r->material_capacity,
                              r->gpu.arrays ? &r->gpu.plan : NULL, why, sizeof why);
        if (res != MVR_OK)
            return mvr_renderer_fail(r, res, "frame: %s", why);
        r->frame_key.scene_serial = mvr_scene_serial(scene);
        r->frame_key.arrays = r->gpu.arrays;
        r->frame_key.geometry_version = scene->geometry_version;
        r->frame_key.material_version = scene->material_version;
        r->frame_key.transform_version = scene->transform_version;
        r->frame_key.origin = views->origin;
    }
    if (r->frame.lights_dropped)
        mvr_log(&r->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                "mvr: %u lights beyond %d of one type are not drawn", r->frame.lights_dropped,
                MVR_SHADER_MAX_LIGHTS_PER_TYPE);
    if (r->culling) {
        res = mvr_visibility_compute(&r->vis, &r->frame, views, t->desc.width, t->desc.height, r->reversed_z);
        if (res != MVR_OK)
            return mvr_renderer_fail(r, res, "culling: out of memory");
        for (uint32_t v = 0; v < views->count; ++v)
            if (!views->views[v].disabled)
                r->stats.culled += r->vis.culled[v];
    }
    mvr_shadows_plan(r, views, t, desc);
    return MVR_OK;
}

/* The plan of this frame (r->plan) from its state, and the scratch its
 * executor needs (grown, never per frame). */
static mvr_result build_plan(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t,
                             const mvr_render_desc *desc, mvr_view_path path, bool same)
{
    mvr_frame_plan_input in;
    memset(&in, 0, sizeof in);
    in.views = views;
    in.width = t->desc.width;
    in.height = t->desc.height;
    in.samples = t->desc.samples;
    in.factor = mvr_target_factor(t);
    in.supersampled = t->ss_color != 0;
    in.unorm8 = t->internal_format == GL_RGBA8;
    in.post = mvr_post_needed(desc);
    in.max_views = (uint32_t)r->ctx->caps.limits.max_views_ovr;
    in.msaa_multiview = t->msaa_multiview;
    in.path = path;
    in.blend_policy = r->blend_policy;
    in.background = desc->background != MVR_BACKGROUND_COLOR;
    in.outputs = t->shader_outputs != 0;
    in.environment = desc->environment != NULL;
    /* KHR_materials_sheen: its maps only for a frame that draws it */
    r->sheen_frame = false;
    for (uint32_t i = 0; i < r->frame.draw_count && !r->sheen_frame; ++i)
        r->sheen_frame = (r->frame.draws[i].features & MVR_FEATURE_SHEEN) != 0;
    in.environment_new = mvr_environment_stale(r, desc->environment, r->sheen_frame);
    in.shadow_layers = r->shadows.plan.layer_count;
    in.deforms = r->frame.deform_count;
    in.preskin = r->skinning.path == MVR_SKINNING_PATH_PRESKIN;
    in.deforms_moved = !same || r->skinning.captured_key == 0;
    for (int k = 0; k < MVR_PASS_KIND_COUNT; ++k)
        in.draws[k] = r->frame.pass_count[k];
    in.transmissive = r->frame.transmissive_draws;
    mvr_frame_plan *plan = &r->plan;
    bool ok = mvr_frame_plan_build(plan, &in) == MVR_OK;
    if (ok && plan->chunk_count > r->chunk_compact_cap) {
        GLintptr *p = realloc(r->chunk_compact, plan->chunk_count * sizeof *p);
        ok = p != NULL;
        if (ok) {
            r->chunk_compact = p;
            r->chunk_compact_cap = plan->chunk_count;
        }
    }
    uint32_t groups = r->gpu.arrays ? r->gpu.plan.group_count + 1 : 0;
    if (ok && groups > r->groups_used_cap) {
        uint8_t *p = realloc(r->groups_used, groups);
        ok = p != NULL;
        if (ok) {
            r->groups_used = p;
            r->groups_used_cap = groups;
        }
    }
    if (!ok) {
        plan->count = plan->chunk_count = 0;
        return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "render: out of memory");
    }
    r->stats.anti_aliasing = t->anti_aliasing;
    r->stats.msaa_multiview = plan->msaa_multiview;
    r->path_ran = plan->path;
    return MVR_OK;
}

static mvr_result exec_env_prefilter(frame_exec *fx)
{
    return mvr_environment_sync(fx->r, fx->desc->environment, fx->r->sheen_frame);
}

/* The frame's state for the mesh passes: GL state, output features, clear values. */
static void setup_frame_state(frame_exec *fx)
{
    mvr_renderer *r = fx->r;
    const mvr_render_desc *desc = fx->desc;
    pass_context *pc = &fx->pc;
    pc->r = r;
    pc->lay = &fx->lay;
    pc->desc = desc;
    pc->groups_used = r->gpu.arrays ? r->groups_used : NULL;
    pc->view_set = fx->views;
    pc->target = fx->t;
    pc->shader_outputs = fx->t->shader_outputs;
    if ((pc->shader_outputs & MVR_SHADER_OUT_NORMAL) && desc->normal_space == MVR_NORMAL_SPACE_CAMERA)
        pc->shader_outputs |= MVR_SHADER_OUT_NORMAL_CAMERA;
    pc->output_alpha_cutoff = desc->output_alpha_cutoff > 0.0f ? desc->output_alpha_cutoff : 0.5f;
    r->stats.outputs = fx->t->desc.outputs;
    st_rebind_setup(r);
    if (fx->plan->encode_in_mesh) /* a supersampled target draws linear floats; its resolve encodes */
        pc->output_features |= MVR_FEATURE_SRGB_OUTPUT;
    pc->mesh_exposure = (float)fx->pre_exposure;
    if (r->shadows.plan.layer_count)
        pc->output_features |= MVR_FEATURE_SHADOWS;
    if (r->shadows.plan.masked)
        pc->output_features |= MVR_FEATURE_LIGHT_MASKS;
    /* image-based lighting: the environment, prefiltered before the view
     * passes, is read by every lit draw of every pass */
    if (desc->environment)
        pc->output_features |= MVR_FEATURE_IBL | (desc->environment_samples ? MVR_FEATURE_IBL_REFERENCE : 0u);
    mvr_state_cache *st = &r->state;
    if (r->force_inert_features) /* what a forced COLOR_0 reads where a primitive has none */
        r->gl->VertexAttrib4f(5, 1.0f, 1.0f, 1.0f, 1.0f);
    if (r->reversed_z)
        mvr_state_clip_control(st, GL_LOWER_LEFT_EXT, GL_ZERO_TO_ONE_EXT);
    else if (r->gl->ClipControl && r->ctx->caps.ext.ext_clip_control)
        mvr_state_clip_control(st, GL_LOWER_LEFT_EXT, GL_NEGATIVE_ONE_TO_ONE_EXT);
    mvr_state_scissor_test(st, false);
    /* desktop GL encodes writes to sRGB formats only when asked (GLES always
     * does): without it an sRGB target stores linear values, darker, and
     * blends them unconverted */
    if (r->ctx->caps.api == MVR_GL_API_DESKTOP)
        mvr_state_framebuffer_srgb(st, true);
    memcpy(fx->clear, desc->clear_color, sizeof fx->clear);
    if (fx->plan->encode_in_mesh)
        for (int c = 0; c < 3; ++c)
            fx->clear[c] = srgb_encode(fx->clear[c]);
    if (fx->plan->post) /* scene-referred in an HDR frame: exposed and tone mapped as the rest */
        for (int c = 0; c < 3; ++c)
            fx->clear[c] = (float)(fx->clear[c] * fx->pre_exposure);
    fx->clear_depth = r->reversed_z ? 0.0f : 1.0f;
    fx->view_block_stride = align_up(VIEW_BLOCK_SIZE, (GLsizeiptr)r->ubo_alignment);
    fx->light_total = r->frame.light_counts[0] + r->frame.light_counts[1] + r->frame.light_counts[2];
}

/* The HDR frame's array, the exposure, and the frame's uniform data. */
static mvr_result exec_upload(frame_exec *fx)
{
    mvr_renderer *r = fx->r;
    mvr_target *t = fx->t;
    const mvr_render_desc *desc = fx->desc;
    const mvr_frame_plan *plan = fx->plan;
    /* an HDR frame (tone mapping, physical exposure, dithering): views draw
     * into a half-float array, the post pass writes the layers */
    t->hdr_frame = plan->hdr_frame;
    if (plan->post) {
        mvr_result hr = mvr_target_ensure_hdr(t);
        if (hr != MVR_OK)
            return hr;
    }
    fx->pre_exposure = plan->post ? mvr_post_pre_exposure(r, t, desc) : (double)desc->exposure;
    r->stats.exposure_mode = desc->exposure_mode;
    r->stats.tone_mapper = desc->tone_map;
    r->stats.exposure_ev100 = log2(1.0 / (1.2 * fx->pre_exposure));
    fx->lay.compact = r->chunk_compact;
    mvr_result res = upload_frame(r, fx->views, t, plan->chunks, plan->chunk_count, &fx->lay, fx->static_current);
    if (res != MVR_OK)
        return res;
    fx->ring_begun = true;
    /* skins and morphs: joints and weights once for every view; on the
     * pre-skinning path the capture, before the shadow and view passes */
    res = mvr_skinning_frame(r, !fx->static_current);
    if (res != MVR_OK)
        return res;
    if (r->sheen_frame) {
        res = mvr_sheen_lut_sync(r);
        if (res != MVR_OK)
            return res;
    }
    setup_frame_state(fx);
    return MVR_OK;
}

/* view-independent: the shadow maps, once, before any view */
static mvr_result exec_shadow_maps(frame_exec *fx)
{
    return mvr_shadows_draw(fx->r, fx->lay.shadow_views, fx->lay.draws);
}

/* A chunk's view pass: its framebuffer and viewport, the clear, the
 * bindings every sub-pass shares, and whether its blended draws split. */
static mvr_result exec_view_pass(frame_exec *fx, const mvr_plan_record *rec)
{
    mvr_renderer *r = fx->r;
    mvr_target *t = fx->t;
    mvr_state_cache *st = &r->state;
    const mvr_view_chunk *ch = &fx->plan->chunks[rec->chunk];
    bool mv_pass = rec->multiview, msaa = rec->msaa, mv_msaa = msaa && mv_pass;
    GLuint draw_fbo = 0;
    mvr_result res = mvr_target_framebuffer(t, ch->base, mv_pass ? ch->count : 0, &fx->fbo);
    /* multisampled: the multiview chunk's own framebuffer, or one view's renderbuffers */
    fx->msaa_fbo = t->hdr_frame ? t->msaa_hdr_fbo : t->msaa_fbo;
    draw_fbo = msaa ? fx->msaa_fbo : fx->fbo;
    if (res == MVR_OK && mv_msaa)
        res = mvr_target_msaa_framebuffer(t, ch->base, ch->count, &draw_fbo);
    if (res != MVR_OK)
        return res;
    mvr_state_draw_framebuffer(st, draw_fbo);
    fx->draw_fbo = draw_fbo;
    /* views are drawn factor times the layer size on supersampled targets */
    uint32_t factor = fx->plan->factor;
    GLint vx = ch->viewport.x * (GLint)factor, vy = ch->viewport.y * (GLint)factor;
    GLsizei vw = (GLsizei)(ch->viewport.width * factor), vh = (GLsizei)(ch->viewport.height * factor);
    mvr_state_viewport(st, vx, vy, vw, vh);
    /* clear only the view's viewport: other views may share the layer */
    bool partial = ch->viewport.x != 0 || ch->viewport.y != 0 || ch->viewport.width != t->desc.width ||
                   ch->viewport.height != t->desc.height;
    if (partial) {
        mvr_state_scissor_test(st, true);
        r->gl->Scissor(vx, vy, vw, vh);
    }
    mvr_state_color_mask(st, true);
    mvr_state_depth(st, true, r->reversed_z ? GL_GREATER : GL_LESS, GL_TRUE);
    r->gl->ClearBufferfv(GL_COLOR, 0, fx->clear);
    r->gl->ClearBufferfv(GL_DEPTH, 0, &fx->clear_depth);
    /* extra outputs: 0 where nothing is drawn (draw buffer k + 1 is attachment k + 1) */
    static const GLfloat zero_f[4] = {0, 0, 0, 0};
    static const GLuint zero_u[4] = {0, 0, 0, 0};
    for (uint32_t k = 0; k < MVR_TARGET_OUTPUT_ARRAYS; ++k) {
        if (!t->output_arrays[k])
            continue;
        if (k == MVR_TARGET_OUTPUT_IDS)
            r->gl->ClearBufferuiv(GL_COLOR, (GLint)(k + 1), zero_u);
        else
            r->gl->ClearBufferfv(GL_COLOR, (GLint)(k + 1), zero_f);
    }
    if (partial)
        mvr_state_scissor_test(st, false);

    /* each pass binds what it samples (a few binds), so its stats stand
     * alone: texture_binds = groups used (arrays) or material changes */
    pass_context *pc = &fx->pc;
    mvr_state_forget_textures(st);
    fx->before = st->counters;
    fx->draws_before = r->stats.draws;
    if (pc->groups_used)
        memset(pc->groups_used, 0, r->gpu.plan.group_count + 1);
    pc->groups_used_count = 0;
    fx->block = ch->base / VIEWS_PER_BLOCK;
    mvr_state_ubo_range(st, MVR_BLOCK_VIEWS, r->ring.buffer,
                        fx->lay.views + (GLintptr)fx->block * fx->view_block_stride, VIEW_BLOCK_SIZE);
    if (fx->light_total)
        mvr_state_ubo_range(st, MVR_BLOCK_LIGHTS, r->ring.buffer, fx->lay.lights, fx->lay.lights_size);
    mvr_shadows_bind(r, fx->lay.shadow_block);
    if (fx->desc->environment)
        mvr_environment_bind(r, fx->desc->environment_samples > 0);
    if (r->sheen_frame)
        mvr_sheen_bind(r, fx->desc->environment != NULL);
    pc->num_views = mv_pass ? ch->count : 0;
    pc->first_view = ch->base;
    pc->views = ch->count;
    pc->view_base = (int32_t)(ch->base - fx->block * VIEWS_PER_BLOCK);
    pc->compact = fx->lay.compact[rec->chunk];
    pc->compact_next = 0;
    pc->last_program = NULL;
    /* blended draws: per view where the views' orders diverge (auto) or always (per_view) */
    fx->split = false;
    if (rec->blend != MVR_PLAN_BLEND_SHARED) {
        bool diverged = blend_orders_diverge(r, pc);
        r->stats.blend_diverged_chunks += diverged;
        fx->split = diverged || rec->blend == MVR_PLAN_BLEND_SPLIT;
    }
    return MVR_OK;
}

/* the background after the opaque and masked geometry, before the blended:
 * only uncovered pixels pass its depth test, and what is transparent blends
 * over it */
static mvr_result exec_background(frame_exec *fx)
{
    /* the background writes colour alone: no extra output is left undefined */
    mvr_target_draw_buffers(fx->t, MVR_DRAW_COLOR);
    mvr_result res = mvr_environment_draw_background(fx->r, fx->desc, fx->pc.num_views, fx->pc.view_base,
                                                     fx->plan->encode_in_mesh, fx->pc.mesh_exposure);
    mvr_target_draw_buffers(fx->t, MVR_DRAW_ALL);
    return res;
}

/* The extra outputs of a chunk's blended draws (after every colour pass,
 * so nothing the colour reads, such as an HDR frame's metered depth, sees
 * its depth writes): the chunk's framebuffer again, outputs alone. */
static mvr_result exec_outputs_blend(frame_exec *fx, const mvr_plan_record *rec)
{
    mvr_renderer *r = fx->r;
    mvr_state_cache *st = &r->state;
    const mvr_view_chunk *ch = &fx->plan->chunks[rec->chunk];
    GLuint fbo = 0;
    mvr_result res = mvr_target_framebuffer(fx->t, ch->base, rec->multiview ? ch->count : 0, &fbo);
    if (res != MVR_OK)
        return res;
    mvr_state_draw_framebuffer(st, fbo);
    mvr_state_viewport(st, ch->viewport.x, ch->viewport.y, (GLsizei)ch->viewport.width, (GLsizei)ch->viewport.height);
    mvr_state_scissor_test(st, false);
    mvr_state_color_mask(st, true);
    uint32_t block = ch->base / VIEWS_PER_BLOCK;
    mvr_state_ubo_range(st, MVR_BLOCK_VIEWS, r->ring.buffer,
                        fx->lay.views + (GLintptr)block * fx->view_block_stride, VIEW_BLOCK_SIZE);
    pass_context *pc = &fx->pc;
    pc->num_views = rec->multiview ? ch->count : 0;
    pc->first_view = ch->base;
    pc->views = ch->count;
    pc->view_base = (int32_t)(ch->base - block * VIEWS_PER_BLOCK);
    pc->compact = -1;
    pc->last_program = NULL;
    pc->outputs_only = true;
    mvr_target_draw_buffers(fx->t, MVR_DRAW_OUTPUTS);
    res = draw_list(pc, MVR_PASS_BLEND);
    mvr_target_draw_buffers(fx->t, MVR_DRAW_ALL);
    pc->outputs_only = false;
    pc->last_program = NULL;
    r->stats.output_blend_passes++;
    return res;
}

/* A view's own blend pass, into its layer and depth: after the multiview
 * pass, as a loop pass would draw it. */
static mvr_result exec_blend_view(frame_exec *fx, const mvr_plan_record *rec)
{
    mvr_renderer *r = fx->r;
    GLuint layer_fbo = 0;
    mvr_result res = mvr_target_framebuffer(fx->t, rec->first_view, 0, &layer_fbo);
    if (res != MVR_OK)
        return res;
    mvr_state_draw_framebuffer(&r->state, layer_fbo);
    pass_context *pc = &fx->pc;
    pc->num_views = 0;
    pc->first_view = rec->first_view;
    pc->views = 1;
    pc->view_base = (int32_t)(rec->first_view - fx->block * VIEWS_PER_BLOCK);
    pc->last_program = NULL; /* the loop variant of each program */
    res = draw_list(pc, MVR_PASS_BLEND);
    r->stats.blend_fallback_passes++;
    return res;
}

/* Resolves each view's samples into its layer (same rectangle): from the
 * view's renderbuffers, or layer by layer from the multisampled array
 * (never read from a multiview framebuffer). */
static mvr_result exec_msaa_resolve(frame_exec *fx, const mvr_plan_record *rec)
{
    mvr_renderer *r = fx->r;
    mvr_state_cache *st = &r->state;
    const mvr_viewport *vp = &fx->plan->chunks[rec->chunk].viewport;
    GLint x1 = vp->x + (GLint)vp->width, y1 = vp->y + (GLint)vp->height;
    mvr_state_scissor_test(st, false);
    for (uint32_t v = rec->first_view; v < rec->first_view + rec->views; ++v) {
        GLuint read_fbo = fx->msaa_fbo, out_fbo = fx->fbo;
        if (rec->msaa) {
            mvr_result res = mvr_target_msaa_framebuffer(fx->t, v, 0, &read_fbo);
            if (res == MVR_OK)
                res = mvr_target_framebuffer(fx->t, v, 0, &out_fbo);
            if (res != MVR_OK)
                return res;
        }
        mvr_state_read_framebuffer(st, read_fbo);
        mvr_state_draw_framebuffer(st, out_fbo);
        /* an HDR frame's metering reads depth: resolve it too */
        GLbitfield bits = GL_COLOR_BUFFER_BIT | (rec->depth ? GL_DEPTH_BUFFER_BIT : 0u);
        r->gl->BlitFramebuffer(vp->x, vp->y, x1, y1, vp->x, vp->y, x1, y1, bits, GL_NEAREST);
        r->stats.resolves++;
    }
    return MVR_OK;
}

/* The chunk's pass is done: its stats. */
static void end_chunk(frame_exec *fx, const mvr_plan_record *rec)
{
    mvr_renderer *r = fx->r;
    const mvr_view_chunk *ch = &fx->plan->chunks[rec->chunk];
    const mvr_state_cache *st = &r->state;
    bool mv_pass = fx->plan->multiview && ch->count > 1;
    r->stats.passes++;
    r->stats.multiview_passes += mv_pass;
    r->stats.views += ch->count;
    if (r->pass_stats_count < MVR_MAX_PASS_STATS) {
        mvr_pass_stats *ps = &r->pass_stats[r->pass_stats_count++];
        ps->first_view = ch->base;
        ps->views = ch->count;
        ps->multiview = mv_pass;
        ps->draws = r->stats.draws - fx->draws_before;
        ps->program_binds = st->counters.program_binds - fx->before.program_binds;
        ps->texture_binds = st->counters.texture_binds - fx->before.texture_binds;
        ps->ubo_range_binds = st->counters.ubo_range_binds - fx->before.ubo_range_binds;
        ps->texture_groups = fx->pc.groups_used_count;
    }
}

/* the supersampling resolve: the mean of each pixel's samples, encoded */
static mvr_result exec_supersample_resolve(frame_exec *fx)
{
    mvr_target *t = fx->t;
    return mvr_full_screen_passes(fx->r, t, t->ss_color, fx->plan->chunks, fx->plan->chunk_count,
                                  fx->plan->multiview,
                                  MVR_FEATURE_DOWNSAMPLE | (t->internal_format == GL_RGBA8 ? MVR_FEATURE_SRGB_ENCODE : 0u),
                                  NULL, false, &fx->r->stats.resolves);
}

static mvr_result exec_post(frame_exec *fx)
{
    return mvr_post_run(fx->r, fx->t, fx->views, fx->desc, fx->plan->chunks, fx->plan->chunk_count,
                        fx->plan->multiview, fx->pre_exposure);
}

static bool record_runs(const frame_exec *fx, const mvr_plan_record *rec)
{
    switch (rec->when) {
    case MVR_PLAN_RUN:
        return true;
    case MVR_PLAN_IF_ORDERS_AGREE:
        return !fx->split;
    case MVR_PLAN_IF_ORDERS_DIVERGE:
        return fx->split;
    default:
        return false;
    }
}

static mvr_result exec_record(frame_exec *fx, const mvr_plan_record *rec)
{
    switch (rec->kind) {
    case MVR_PLAN_ENV_PREFILTER:
        return exec_env_prefilter(fx);
    case MVR_PLAN_UPLOAD:
        return exec_upload(fx);
    case MVR_PLAN_PRESKIN:
        return mvr_skinning_capture(fx->r);
    case MVR_PLAN_SHADOW_MAPS:
        return exec_shadow_maps(fx);
    case MVR_PLAN_VIEW_PASS:
        return exec_view_pass(fx, rec);
    case MVR_PLAN_OPAQUE:
        return draw_list(&fx->pc, MVR_PASS_OPAQUE);
    case MVR_PLAN_MASK:
        return draw_list(&fx->pc, MVR_PASS_MASK);
    case MVR_PLAN_BACKGROUND:
        return exec_background(fx);
    case MVR_PLAN_TRANSMISSION:
        return mvr_transmission_copy(fx->r, fx->t, fx->plan, rec, (int32_t)(fx->block * VIEWS_PER_BLOCK), fx->msaa_fbo,
                                     fx->draw_fbo);
    case MVR_PLAN_BLEND:
        return draw_list(&fx->pc, MVR_PASS_BLEND);
    case MVR_PLAN_BLEND_VIEW:
        return exec_blend_view(fx, rec);
    case MVR_PLAN_MSAA_RESOLVE:
        return exec_msaa_resolve(fx, rec);
    case MVR_PLAN_SUPERSAMPLE_RESOLVE:
        return exec_supersample_resolve(fx);
    case MVR_PLAN_POST:
        return exec_post(fx);
    case MVR_PLAN_OUTPUTS_BLEND:
        return exec_outputs_blend(fx, rec);
    default:
        return MVR_OK;
    }
}

mvr_result mvr_renderer_draw_frame(mvr_renderer *r, const mvr_scene *scene, const mvr_view_set *views,
                                   mvr_target *t, const mvr_render_desc *desc, mvr_view_path path)
{
    r->plan.count = r->plan.chunk_count = 0;
    bool same = false;
    mvr_result res = prepare_frame(r, scene, views, t, desc, &same);
    if (res == MVR_OK)
        res = build_plan(r, views, t, desc, path, same);
    if (res != MVR_OK)
        return res;
    frame_exec fx;
    memset(&fx, 0, sizeof fx);
    fx.r = r;
    fx.views = views;
    fx.t = t;
    fx.desc = desc;
    fx.plan = &r->plan;
    fx.static_current = same;
    fx.pc.scene = scene;
    for (uint32_t i = 0; i < r->plan.count && res == MVR_OK; ++i) {
        const mvr_plan_record *rec = &r->plan.records[i];
        if (record_runs(&fx, rec))
            res = exec_record(&fx, rec);
        if (res == MVR_OK && rec->ends_chunk)
            end_chunk(&fx, rec);
    }
    if (fx.ring_begun) {
        r->state.rebind_always = false;
        mvr_ring_end_frame(r);
    }
    return res;
}
