/* The frame's uniform data: per-draw blocks and lights in the ring's
 * static region (re-sent only on change), then per frame the view blocks,
 * shadow blocks, the per-draw baseline's materials and the compacted blocks
 * of culled passes in one ring segment. */
#include <stdlib.h>
#include <string.h>

#include "draw_list.h"
#include "errors.h"
#include "frame_upload.h"
#include "renderer.h"
#include "ring.h"
#include "targets.h"

/* Views per uniform block (MVR_MAX_VIEWS of shaders/views.glsl); the
 * block's layout is MVR_VIEWS_* of core/frame.h. */
#define VIEWS_PER_BLOCK MVR_VIEWS_PER_BLOCK
#define VIEW_INFO_SIZE MVR_VIEW_INFO_SIZE /* one ivec4 of mvr_view_info: the view's light mask */
#define VIEW_BLOCK_SIZE MVR_VIEWS_BLOCK_SIZE
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
            visible += mvr_draw_visible(r, ch->base, ch->count, f->pass_first[k] + i);
    }
    if (visible == listed || visible < 2) /* nothing culled, or no run to keep */
        return 0;
    return (GLsizeiptr)visible * f->block_stride;
}

/* Writes the compacted blocks of every chunk that needs them (one upload). */
static mvr_result upload_compacted(mvr_renderer *r, const mvr_view_chunk *chunks, uint32_t chunk_count,
                                   mvr_frame_layout *lay, GLintptr at, GLsizeiptr bytes)
{
    const mvr_frame *f = &r->frame;
    if (bytes == 0)
        return MVR_OK;
    if ((size_t)bytes > r->compact_scratch_cap) {
        uint8_t *p = realloc(r->compact_scratch, (size_t)bytes);
        if (!p)
            return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "compacted blocks: out of memory");
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
                if (!mvr_draw_visible(r, chunks[c].base, chunks[c].count, pos))
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
    GLsizeiptr rel_lights = mvr_align_up(draw_bytes, align);
    bool reallocated = false;
    mvr_result res = mvr_ring_reserve_static(r, mvr_align_up(rel_lights + lights_size, align) + align, &reallocated);
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

mvr_result mvr_frame_upload(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t,
                            const mvr_view_chunk *chunks, uint32_t chunk_count, mvr_frame_layout *lay,
                            bool static_current)
{
    const mvr_gl_api_table *gl = r->gl;
    const mvr_frame *f = &r->frame;
    GLsizeiptr align = (GLsizeiptr)r->ubo_alignment;
    GLsizeiptr draw_bytes = (GLsizeiptr)f->draw_count * f->block_stride;
    uint32_t light_count = f->light_counts[0] + f->light_counts[1] + f->light_counts[2];
    lay->lights_size = (GLsizeiptr)light_count * MVR_LIGHT_BLOCK_SIZE;
    lay->draws = 0;
    lay->lights = mvr_align_up(draw_bytes, align);
    lay->view_blocks = (views->count + VIEWS_PER_BLOCK - 1) / VIEWS_PER_BLOCK;
    GLsizeiptr view_block_stride = mvr_align_up(VIEW_BLOCK_SIZE, align);
    GLsizeiptr total = view_block_stride * lay->view_blocks;
    /* the per-draw baseline: each draw's material in its own range, sent every
     * frame as such a renderer would (plus a tail: a bound range covers the
     * whole declared block) */
    bool per_draw = r->material_path == MVR_MATERIAL_PATH_PER_DRAW;
    GLsizeiptr table_bytes = (GLsizeiptr)r->material_capacity * MVR_MATERIAL_BLOCK_SIZE;
    lay->draw_material_stride = mvr_align_up(MVR_MATERIAL_BLOCK_SIZE, align);
    GLsizeiptr rel_materials = mvr_align_up(total, align);
    if (per_draw)
        total = rel_materials + lay->draw_material_stride * (GLsizeiptr)f->draw_count + table_bytes;
    GLsizeiptr rel_compact = mvr_align_up(total, align), compact_bytes = 0;
    for (uint32_t c = 0; c < chunk_count; ++c) {
        GLsizeiptr n = compact_size(r, &chunks[c]);
        lay->compact[c] = n ? 0 : -1;
        compact_bytes += n;
    }
    if (compact_bytes) /* and a tail: an instanced draw's range covers a whole block array */
        total = rel_compact + compact_bytes + (GLsizeiptr)r->draw_capacity * r->draw_stride;
    const mvr_shadow_plan *plan = &r->shadows.plan;
    GLsizeiptr rel_shadow_views = mvr_align_up(total, align);
    GLsizeiptr rel_shadow_block = mvr_align_up(rel_shadow_views + (GLsizeiptr)VIEW_BLOCK_SIZE, align);
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
            return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "per-draw materials: out of memory");
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
