#include <string.h>

#include "state_cache.h"

/* A value the GL never reports, so the first set after invalidation is sent. */
#define UNKNOWN_NAME 0xFFFFFFFFu
#define UNKNOWN_ENUM 0xFFFFFFFFu

void mvr_state_init(mvr_state_cache *s, const mvr_gl_api_table *gl, bool known)
{
    mvr_state_counters counters = s->counters;
    memset(s, 0, sizeof *s);
    s->counters = counters;
    s->gl = gl;
    if (!known) {
        mvr_state_invalidate(s);
        return;
    }
    s->known = true;
    /* GL's initial state (GLES 3.2 spec, state tables 21.x) */
    for (int i = 0; i < MVR_STATE_TEXTURE_UNITS; ++i)
        s->texture_targets[i] = GL_TEXTURE_2D;
    s->active_unit = 0;
    s->viewport[0] = s->viewport[1] = 0;
    s->viewport[2] = s->viewport[3] = -1; /* the drawable's size: unknown to us */
    s->depth_func = GL_LESS;
    s->depth_mask = GL_TRUE;
    s->cull_mode = GL_BACK;
    s->front_face = GL_CCW;
    for (int i = 0; i < 4; ++i)
        s->color_mask[i] = GL_TRUE;
    s->blend_src_rgb = s->blend_src_a = GL_ONE;
    s->blend_dst_rgb = s->blend_dst_a = GL_ZERO;
    s->clip_origin = GL_LOWER_LEFT_EXT;
    s->clip_depth = GL_NEGATIVE_ONE_TO_ONE_EXT;
}

void mvr_state_invalidate(mvr_state_cache *s)
{
    const mvr_gl_api_table *gl = s->gl;
    mvr_state_counters counters = s->counters;
    bool rebind = s->rebind_always;
    memset(s, 0xFF, sizeof *s);
    s->gl = gl;
    s->counters = counters;
    s->rebind_always = rebind;
    s->known = false;
    for (int i = 0; i < MVR_STATE_UBO_BINDINGS; ++i)
        s->ubo[i].size = -1;
    s->viewport[2] = s->viewport[3] = -1;
}

void mvr_state_program(mvr_state_cache *s, GLuint program)
{
    if (s->program == program)
        return;
    s->gl->UseProgram(program);
    s->program = program;
    s->counters.program_binds++;
}

void mvr_state_assume_program(mvr_state_cache *s, GLuint program)
{
    s->program = program;
    s->counters.program_binds++;
}

void mvr_state_vao(mvr_state_cache *s, GLuint vao)
{
    if (s->vao == vao)
        return;
    s->gl->BindVertexArray(vao);
    s->vao = vao;
}

void mvr_state_array_buffer(mvr_state_cache *s, GLuint buffer)
{
    if (s->array_buffer == buffer)
        return;
    s->gl->BindBuffer(GL_ARRAY_BUFFER, buffer);
    s->array_buffer = buffer;
}

void mvr_state_draw_framebuffer(mvr_state_cache *s, GLuint fbo)
{
    if (s->draw_fbo == fbo)
        return;
    s->gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    s->draw_fbo = fbo;
    s->counters.framebuffer_binds++;
}

void mvr_state_read_framebuffer(mvr_state_cache *s, GLuint fbo)
{
    if (s->read_fbo == fbo)
        return;
    s->gl->BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    s->read_fbo = fbo;
}

void mvr_state_ubo_range(mvr_state_cache *s, GLuint index, GLuint buffer, GLintptr offset,
                         GLsizeiptr size)
{
    mvr_ubo_binding *b = &s->ubo[index];
    if (b->buffer == buffer && b->offset == offset && b->size == size && !s->rebind_always)
        return;
    s->gl->BindBufferRange(GL_UNIFORM_BUFFER, index, buffer, offset, size);
    b->buffer = buffer;
    b->offset = offset;
    b->size = size;
    s->counters.ubo_range_binds++;
}

static void active_unit(mvr_state_cache *s, GLuint unit)
{
    if (s->active_unit == unit)
        return;
    s->gl->ActiveTexture(GL_TEXTURE0 + unit);
    s->active_unit = unit;
}

void mvr_state_texture(mvr_state_cache *s, GLuint unit, GLenum target, GLuint texture)
{
    if (s->textures[unit] == texture && s->texture_targets[unit] == target && !s->rebind_always)
        return;
    active_unit(s, unit);
    s->gl->BindTexture(target, texture);
    s->textures[unit] = texture;
    s->texture_targets[unit] = target;
    s->counters.texture_binds++;
}

void mvr_state_sampler(mvr_state_cache *s, GLuint unit, GLuint sampler)
{
    if (s->samplers[unit] == sampler)
        return;
    s->gl->BindSampler(unit, sampler);
    s->samplers[unit] = sampler;
}

void mvr_state_viewport(mvr_state_cache *s, GLint x, GLint y, GLsizei w, GLsizei h)
{
    if (s->viewport[0] == x && s->viewport[1] == y && s->viewport[2] == w && s->viewport[3] == h)
        return;
    s->gl->Viewport(x, y, w, h);
    s->viewport[0] = x;
    s->viewport[1] = y;
    s->viewport[2] = w;
    s->viewport[3] = h;
}

static void enable(mvr_state_cache *s, GLenum cap, bool *cached, bool on)
{
    /* an invalidated bool holds 0xFF, which is neither true nor false */
    unsigned char raw;
    memcpy(&raw, cached, 1);
    if (raw == (on ? 1u : 0u))
        return;
    if (on)
        s->gl->Enable(cap);
    else
        s->gl->Disable(cap);
    *cached = on;
}

void mvr_state_depth(mvr_state_cache *s, bool test, GLenum func, GLboolean mask)
{
    enable(s, GL_DEPTH_TEST, &s->depth_test, test);
    if (s->depth_func != func) {
        s->gl->DepthFunc(func);
        s->depth_func = func;
    }
    if (s->depth_mask != mask) {
        s->gl->DepthMask(mask);
        s->depth_mask = mask;
    }
}

void mvr_state_cull(mvr_state_cache *s, bool enabled, GLenum front_face)
{
    enable(s, GL_CULL_FACE, &s->cull_face, enabled);
    if (s->cull_mode != GL_BACK) {
        s->gl->CullFace(GL_BACK);
        s->cull_mode = GL_BACK;
    }
    if (s->front_face != front_face) {
        s->gl->FrontFace(front_face);
        s->front_face = front_face;
    }
}

void mvr_state_blend(mvr_state_cache *s, bool enabled, GLenum src_rgb, GLenum dst_rgb,
                     GLenum src_a, GLenum dst_a)
{
    enable(s, GL_BLEND, &s->blend, enabled);
    if (!enabled)
        return;
    if (s->blend_src_rgb != src_rgb || s->blend_dst_rgb != dst_rgb || s->blend_src_a != src_a ||
        s->blend_dst_a != dst_a) {
        s->gl->BlendFuncSeparate(src_rgb, dst_rgb, src_a, dst_a);
        s->blend_src_rgb = src_rgb;
        s->blend_dst_rgb = dst_rgb;
        s->blend_src_a = src_a;
        s->blend_dst_a = dst_a;
    }
}

void mvr_state_color_mask(mvr_state_cache *s, bool all)
{
    GLboolean v = all ? GL_TRUE : GL_FALSE;
    if (s->color_mask[0] == v && s->color_mask[1] == v && s->color_mask[2] == v && s->color_mask[3] == v)
        return;
    s->gl->ColorMask(v, v, v, v);
    for (int i = 0; i < 4; ++i)
        s->color_mask[i] = v;
}

void mvr_state_scissor_test(mvr_state_cache *s, bool enabled)
{
    enable(s, GL_SCISSOR_TEST, &s->scissor_test, enabled);
}

void mvr_state_rasterizer_discard(mvr_state_cache *s, bool enabled)
{
    enable(s, GL_RASTERIZER_DISCARD, &s->rasterizer_discard, enabled);
}

#ifndef GL_FRAMEBUFFER_SRGB
#define GL_FRAMEBUFFER_SRGB 0x8DB9 /* desktop GL 3.0 / ARB_framebuffer_sRGB */
#endif

void mvr_state_framebuffer_srgb(mvr_state_cache *s, bool enabled)
{
    enable(s, GL_FRAMEBUFFER_SRGB, &s->framebuffer_srgb, enabled);
}

void mvr_state_clip_control(mvr_state_cache *s, GLenum origin, GLenum depth)
{
    if (s->clip_origin == origin && s->clip_depth == depth)
        return;
    s->gl->ClipControl(origin, depth);
    s->clip_origin = origin;
    s->clip_depth = depth;
}

void mvr_state_forget_texture(mvr_state_cache *s, GLuint texture)
{
    for (int i = 0; i < MVR_STATE_TEXTURE_UNITS; ++i)
        if (s->textures[i] == texture)
            s->textures[i] = 0;
}

void mvr_state_forget_textures(mvr_state_cache *s)
{
    for (int i = 0; i < MVR_STATE_TEXTURE_UNITS; ++i)
        s->textures[i] = UNKNOWN_NAME;
}

void mvr_state_forget_buffer(mvr_state_cache *s, GLuint buffer)
{
    for (int i = 0; i < MVR_STATE_UBO_BINDINGS; ++i)
        if (s->ubo[i].buffer == buffer)
            s->ubo[i].buffer = 0; /* GL unbinds the name; the range stays unknown */
    if (s->array_buffer == buffer)
        s->array_buffer = 0;
}

void mvr_state_forget_framebuffer(mvr_state_cache *s, GLuint fbo)
{
    if (s->draw_fbo == fbo)
        s->draw_fbo = 0;
    if (s->read_fbo == fbo)
        s->read_fbo = 0;
}

void mvr_state_forget_program(mvr_state_cache *s, GLuint program)
{
    if (s->program == program)
        s->program = UNKNOWN_NAME; /* a deleted current program stays in use until replaced */
}

void mvr_state_forget_vao(mvr_state_cache *s, GLuint vao)
{
    if (s->vao == vao)
        s->vao = 0;
}

void mvr_state_forget_sampler(mvr_state_cache *s, GLuint sampler)
{
    for (int i = 0; i < MVR_STATE_TEXTURE_UNITS; ++i)
        if (s->samplers[i] == sampler)
            s->samplers[i] = 0;
}

void mvr_state_polygon_offset(mvr_state_cache *s, bool enabled, GLfloat factor, GLfloat units)
{
    enable(s, GL_POLYGON_OFFSET_FILL, &s->polygon_offset_fill, enabled);
    /* an invalidated float is NaN: never equal, so the first call sends */
    if (!enabled || (s->polygon_offset_factor == factor && s->polygon_offset_units == units))
        return;
    s->gl->PolygonOffset(factor, units);
    s->polygon_offset_factor = factor;
    s->polygon_offset_units = units;
}
