/* Skins and morph targets on the GPU. Both paths run deform.glsl's
 * mvr_deform on the same data:
 * - morph deltas: one RGBA32F texture per scene geometry (uploaded once);
 * - the frame's joint matrices and active weights: one RGBA32F texture,
 *   uploaded once per frame that moved them, whatever the view count;
 * - the vertex path: the mesh program deforms in its vertex stage, once per
 *   view and pass (llvmpipe loops views inside a multiview draw);
 * - the pre-skinning path: one transform feedback capture per deform per
 *   frame that moved, into a buffer every view and the shadow pass draw. */
#include <stdlib.h>
#include <string.h>

#include "errors.h"
#include "program.h"
#include "program_cache.h"
#include "renderer.h"
#include "skinning.h"

#define DATA_WIDTH (1u << MVR_DEFORM_WIDTH_LOG2)
/* the captured vertex: position (vec3), normal (vec3), tangent (vec4),
 * interleaved as program.c names the varyings */
#define PRESKIN_STRIDE 40

const char *mvr_skinning_path_name(mvr_skinning_path path)
{
    switch (path) {
    case MVR_SKINNING_PATH_AUTO: return "auto";
    case MVR_SKINNING_PATH_VERTEX: return "vertex";
    case MVR_SKINNING_PATH_PRESKIN: return "preskin";
    }
    return NULL;
}

static void release_buffers(mvr_renderer *r)
{
    mvr_skinning *k = &r->skinning;
    for (uint32_t i = 0; i < k->buffer_count; ++i) {
        mvr_state_forget_vao(&r->state, k->buffers[i].vao);
        mvr_gl_delete(r, MVR_GL_VERTEX_ARRAY, &k->buffers[i].vao);
        mvr_gl_delete(r, MVR_GL_BUFFER, &k->buffers[i].buffer);
    }
    k->buffer_count = 0;
    k->captured_key = 0;
}

void mvr_skinning_release(mvr_renderer *r)
{
    mvr_skinning *k = &r->skinning;
    release_buffers(r);
    free(k->buffers);
    k->buffers = NULL;
    k->buffer_cap = 0;
    mvr_gl_delete(r, MVR_GL_TEXTURE, &k->deltas);
    mvr_gl_delete(r, MVR_GL_TEXTURE, &k->data);
    mvr_state_forget_framebuffer(&r->state, k->capture_fbo);
    mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &k->capture_fbo);
    mvr_gl_delete(r, MVR_GL_RENDERBUFFER, &k->capture_color);
    k->deltas_geometry = 0;
    k->data_rows = 0;
}

static mvr_result capture_framebuffer(mvr_renderer *r)
{
    mvr_skinning *k = &r->skinning;
    const mvr_gl_api_table *gl = r->gl;
    if (!k->capture_fbo) {
        gl->GenRenderbuffers(1, &k->capture_color);
        gl->BindRenderbuffer(GL_RENDERBUFFER, k->capture_color);
        gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, 0, GL_R8, 1, 1);
        gl->GenFramebuffers(1, &k->capture_fbo);
        mvr_state_draw_framebuffer(&r->state, k->capture_fbo);
        gl->FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, k->capture_color);
        mvr_result res = mvr_gl_check_alloc(r, "pre-skinning framebuffer (1x1 R8)");
        if (res != MVR_OK)
            return res;
        if (gl->CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return mvr_gl_fail(r, MVR_ERROR_FRAMEBUFFER, "pre-skinning framebuffer (1x1 R8) is incomplete");
    }
    mvr_state_draw_framebuffer(&r->state, k->capture_fbo);
    return MVR_OK;
}

/* An RGBA32F texture of rows x DATA_WIDTH texels read with texelFetch:
 * nearest, one level (complete without mipmaps). */
static mvr_result make_data_texture(mvr_renderer *r, GLuint *tex, uint32_t rows, const float *data, const char *what)
{
    const mvr_gl_api_table *gl = r->gl;
    if (rows > (uint32_t)r->ctx->caps.limits.max_texture_size)
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED,
                           "%s: %u rows of %u texels exceed GL_MAX_TEXTURE_SIZE %d", what, rows, DATA_WIDTH,
                           r->ctx->caps.limits.max_texture_size);
    mvr_gl_delete(r, MVR_GL_TEXTURE, tex);
    gl->GenTextures(1, tex);
    mvr_state_texture(&r->state, MVR_UNIT_ANIM_DATA, GL_TEXTURE_2D, *tex);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, (GLsizei)DATA_WIDTH, (GLsizei)rows);
    mvr_result res = mvr_gl_check_alloc(r, "%s (%u x %u RGBA32F)", what, DATA_WIDTH, rows);
    if (res == MVR_OK && data)
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, (GLsizei)DATA_WIDTH, (GLsizei)rows, GL_RGBA, GL_FLOAT, data);
    if (res != MVR_OK)
        mvr_gl_delete(r, MVR_GL_TEXTURE, tex);
    return res;
}

mvr_result mvr_skinning_sync_scene(mvr_renderer *r, const mvr_scene *s)
{
    mvr_skinning *k = &r->skinning;
    /* the captured buffers' vertex arrays name the old vertex buffers */
    release_buffers(r);
    mvr_gl_delete(r, MVR_GL_TEXTURE, &k->deltas);
    k->deltas_geometry = 0;
    if (s->morph_texels == 0)
        return MVR_OK;
    /* deform.glsl indexes texels with a 32-bit int */
    if (s->morph_texels > (uint64_t)INT32_MAX - DATA_WIDTH)
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED, "morph targets: %llu delta texels are more than mvr indexes",
                           (unsigned long long)s->morph_texels);
    uint32_t rows = (uint32_t)((s->morph_texels + DATA_WIDTH - 1) / DATA_WIDTH);
    /* the GL's limit before the staging copy: a texture the GL cannot hold
     * is refused without allocating its bytes first */
    if (rows > (uint32_t)r->ctx->caps.limits.max_texture_size)
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED,
                           "morph target deltas: %u rows of %u texels exceed GL_MAX_TEXTURE_SIZE %d", rows,
                           DATA_WIDTH, r->ctx->caps.limits.max_texture_size);
    size_t floats = (size_t)rows * DATA_WIDTH * 4;
    float *data = calloc(floats, sizeof *data);
    if (!data)
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "morph targets: out of memory (%zu floats)", floats);
    for (uint32_t i = 0; i < s->primitive_count; ++i) {
        const scene_primitive *p = &s->primitives[i];
        if (!p->target_count)
            continue;
        const float *attr[3] = {p->target_positions, p->target_normals, p->target_tangents};
        size_t per_target = (size_t)p->vertex_count * 3;
        for (uint32_t t = 0; t < p->target_count; ++t)
            for (uint32_t a = 0; a < 3; ++a) {
                uint32_t slot = (p->morph_slots >> (2 * a)) & 3u;
                if (slot == 3)
                    continue;
                const float *src = attr[a] + t * per_target;
                float *dst = data + (p->morph_base + ((uint64_t)t * p->morph_attributes + slot) * p->vertex_count) * 4;
                for (uint32_t v = 0; v < p->vertex_count; ++v)
                    memcpy(dst + (size_t)v * 4, src + (size_t)v * 3, 3 * sizeof(float));
            }
    }
    mvr_result res = make_data_texture(r, &k->deltas, rows, data, "morph target deltas");
    free(data);
    if (res != MVR_OK)
        return res;
    r->upload_bytes += (uint64_t)floats * sizeof(float);
    k->deltas_geometry = s->geometry_version;
    return MVR_OK;
}

mvr_skinning_path mvr_skinning_rule(uint32_t views)
{
    /* pre-skinning does the work once for every view and the shadow pass,
     * the vertex path once per view on drivers that loop views in a
     * multiview draw; one view without shadows gains nothing from a capture
     * pass (docs/benchmarks.md) */
    return views > 1 ? MVR_SKINNING_PATH_PRESKIN : MVR_SKINNING_PATH_VERTEX;
}

mvr_skinning_path mvr_skinning_choose(const mvr_renderer *r, const mvr_scene *s, uint32_t views)
{
    (void)s;
    if (r->skinning.requested != MVR_SKINNING_PATH_AUTO)
        return r->skinning.requested;
    /* auto: what the tuner runs this frame (gl/tuning.c), else the rule */
    return r->skinning.tuned != MVR_SKINNING_PATH_AUTO ? r->skinning.tuned : mvr_skinning_rule(views);
}

static mvr_result upload_data(mvr_renderer *r)
{
    mvr_skinning *k = &r->skinning;
    const mvr_frame *f = &r->frame;
    uint32_t rows = (f->deform_texels + DATA_WIDTH - 1) / DATA_WIDTH;
    if (rows > k->data_rows || !k->data) {
        uint32_t grown = k->data_rows ? k->data_rows : 1;
        while (grown < rows)
            grown *= 2;
        mvr_result res = make_data_texture(r, &k->data, grown, NULL, "joint matrices and morph weights");
        if (res != MVR_OK)
            return res;
        k->data_rows = grown;
    }
    mvr_state_texture(&r->state, MVR_UNIT_ANIM_DATA, GL_TEXTURE_2D, k->data);
    /* whole rows, except the last: only the texels the frame holds */
    uint32_t full = f->deform_texels / DATA_WIDTH, rest = f->deform_texels % DATA_WIDTH;
    if (full)
        r->gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, (GLsizei)DATA_WIDTH, (GLsizei)full, GL_RGBA, GL_FLOAT,
                             f->deform_data);
    if (rest)
        r->gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, (GLint)full, (GLsizei)rest, 1, GL_RGBA, GL_FLOAT,
                             f->deform_data + (size_t)full * DATA_WIDTH * 4);
    uint64_t bytes = (uint64_t)f->deform_texels * 16u;
    r->stats.animation_upload_bytes += bytes;
    r->upload_bytes += bytes;
    return MVR_OK;
}

/* The buffer and vertex array a deform's captured vertices are drawn with:
 * the capture for locations 0-2, the primitive's own buffer for the rest. */
static mvr_result preskin_buffer(mvr_renderer *r, uint32_t index, const mvr_deform *d)
{
    mvr_skinning *k = &r->skinning;
    const mvr_gl_api_table *gl = r->gl;
    if (index >= k->buffer_cap) {
        uint32_t cap = k->buffer_cap ? k->buffer_cap * 2 : 8;
        while (cap <= index)
            cap *= 2;
        mvr_preskin_buffer *p = realloc(k->buffers, cap * sizeof *p);
        if (!p)
            return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "pre-skinning: out of memory");
        k->buffers = p;
        k->buffer_cap = cap;
    }
    while (k->buffer_count <= index) {
        memset(&k->buffers[k->buffer_count], 0, sizeof k->buffers[0]);
        k->buffers[k->buffer_count++].primitive = MVR_NO_INDEX;
    }
    mvr_preskin_buffer *b = &k->buffers[index];
    const mvr_gpu_primitive *gp = &r->gpu.primitives[d->primitive];
    uint32_t vertices = r->gpu.scene->primitives[d->primitive].vertex_count;
    if (b->vao && b->primitive == d->primitive && b->vertices == vertices)
        return MVR_OK;
    mvr_state_forget_vao(&r->state, b->vao);
    mvr_gl_delete(r, MVR_GL_VERTEX_ARRAY, &b->vao);
    mvr_gl_delete(r, MVR_GL_BUFFER, &b->buffer);
    gl->GenBuffers(1, &b->buffer);
    mvr_state_array_buffer(&r->state, b->buffer);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)vertices * PRESKIN_STRIDE, NULL, GL_DYNAMIC_COPY);
    mvr_result res = mvr_gl_check_alloc(r, "pre-skinned vertices of primitive %u (%u vertices)", d->primitive,
                                        vertices);
    if (res != MVR_OK)
        return res;
    gl->GenVertexArrays(1, &b->vao);
    mvr_state_vao(&r->state, b->vao);
    static const GLint sizes[3] = {3, 3, 4};
    static const GLintptr offsets[3] = {0, 12, 24};
    for (GLuint loc = 0; loc < 3; ++loc) {
        if (!(gp->attributes & (1u << loc)))
            continue;
        gl->EnableVertexAttribArray(loc);
        gl->VertexAttribPointer(loc, sizes[loc], GL_FLOAT, GL_FALSE, PRESKIN_STRIDE,
                                (const void *)(uintptr_t)offsets[loc]);
    }
    static const GLint rest_sizes[3] = {2, 2, 4}; /* uv0, uv1, color0 at locations 3-5 */
    mvr_state_array_buffer(&r->state, gp->vbo);
    for (GLuint loc = 3; loc < 6; ++loc) {
        if (!(gp->attributes & (1u << loc)))
            continue;
        gl->EnableVertexAttribArray(loc);
        gl->VertexAttribPointer(loc, rest_sizes[loc - 3], GL_FLOAT, GL_FALSE, 0,
                                (const void *)(uintptr_t)gp->attribute_offset[loc]);
    }
    if (gp->ibo)
        gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, gp->ibo); /* VAO state */
    mvr_state_vao(&r->state, 0);
    b->primitive = d->primitive;
    b->vertices = vertices;
    return MVR_OK;
}

/* Whether a deform changes its vertices this frame: skinned, or morphed by
 * a non-zero weight. One that does not draws its own vertices (the same
 * as a capture of them would be) and costs no capture. */
static bool needs_capture(const mvr_deform *d)
{
    return d->joint_base >= 0 || d->active_targets > 0;
}

/* One capture per deform: its vertices, deformed, into its buffer. */
mvr_result mvr_skinning_capture(mvr_renderer *r)
{
    const mvr_gl_api_table *gl = r->gl;
    const mvr_frame *f = &r->frame;
    mvr_result res = capture_framebuffer(r);
    if (res != MVR_OK)
        return res;
    mvr_state_rasterizer_discard(&r->state, true);
    for (uint32_t i = 0; i < f->deform_count && res == MVR_OK; ++i) {
        const mvr_deform *d = &f->deforms[i];
        if (!needs_capture(d))
            continue;
        res = preskin_buffer(r, i, d);
        if (res != MVR_OK)
            break;
        mvr_shader_variant v;
        memset(&v, 0, sizeof v);
        v.program = MVR_PROGRAM_PRESKIN;
        v.features = d->features & MVR_PRESKIN_FEATURES;
        mvr_program_entry *e;
        res = mvr_program_cache_get(r, &v, &e);
        if (res != MVR_OK)
            break;
        mvr_state_program(&r->state, e->program);
        GLint info[4] = {0, d->joint_base, d->morph_base, d->delta_base};
        if (e->loc_deform_info >= 0)
            gl->Uniform4iv(e->loc_deform_info, 1, info);
        mvr_state_vao(&r->state, r->gpu.primitives[d->primitive].vao);
        gl->BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, r->skinning.buffers[i].buffer);
        gl->BeginTransformFeedback(GL_POINTS);
        gl->DrawArrays(GL_POINTS, 0, (GLsizei)r->skinning.buffers[i].vertices);
        gl->EndTransformFeedback();
        r->stats.preskin_passes++;
    }
    gl->BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    mvr_state_rasterizer_discard(&r->state, false);
    mvr_state_vao(&r->state, 0);
    r->skinning.captured_key = res == MVR_OK ? 1 : 0;
    return res;
}

mvr_result mvr_skinning_frame(mvr_renderer *r, bool frame_changed)
{
    mvr_skinning *k = &r->skinning;
    const mvr_frame *f = &r->frame;
    r->stats.joints = f->joints;
    r->stats.morph_targets_active = f->morph_active;
    r->stats.skinning_path = f->deform_count ? k->path : MVR_SKINNING_PATH_AUTO;
    if (!f->deform_count)
        return MVR_OK;
    if (frame_changed || !k->data) {
        mvr_result res = upload_data(r);
        if (res != MVR_OK)
            return res;
    }
    /* vertex stages only (cheap to change on llvmpipe): bound once per frame */
    mvr_state_texture(&r->state, MVR_UNIT_ANIM_DATA, GL_TEXTURE_2D, k->data);
    mvr_state_sampler(&r->state, MVR_UNIT_ANIM_DATA, 0);
    mvr_state_texture(&r->state, MVR_UNIT_MORPH_DELTAS, GL_TEXTURE_2D, k->deltas);
    mvr_state_sampler(&r->state, MVR_UNIT_MORPH_DELTAS, 0);
    return MVR_OK;
}

GLuint mvr_skinning_vao(const mvr_renderer *r, const mvr_draw *d)
{
    const mvr_skinning *k = &r->skinning;
    if (k->path != MVR_SKINNING_PATH_PRESKIN || d->deform == MVR_NO_INDEX || d->deform >= k->buffer_count ||
        d->deform >= r->frame.deform_count || !needs_capture(&r->frame.deforms[d->deform]))
        return 0;
    return k->buffers[d->deform].vao;
}
