/*
 * The one GL state cache: every state change the renderer makes goes through
 * it, so redundant calls are dropped and binds are counted for the stats. Its
 * defaults are GL's own initial state. The application, or another renderer
 * on the same context, may change anything between frames, so the renderer
 * invalidates the cache (every entry unknown) at the start of each call that
 * touches GL.
 */
#ifndef MVR_STATE_CACHE_H
#define MVR_STATE_CACHE_H

#include "gl_api.h"

#define MVR_STATE_UBO_BINDINGS 5
#define MVR_STATE_TEXTURE_UNITS 27 /* program.h: the highest unit + 1 */

typedef struct mvr_state_counters {
    uint32_t program_binds;
    uint32_t texture_binds;
    uint32_t ubo_range_binds;
    uint32_t framebuffer_binds;
} mvr_state_counters;

typedef struct mvr_ubo_binding {
    GLuint buffer;
    GLintptr offset;
    GLsizeiptr size;
} mvr_ubo_binding;

typedef struct mvr_state_cache {
    const mvr_gl_api_table *gl;
    bool known;                  /* false: every entry must be re-sent */
    GLuint program, vao, draw_fbo, read_fbo, array_buffer;
    mvr_ubo_binding ubo[MVR_STATE_UBO_BINDINGS];
    GLuint active_unit;
    GLuint textures[MVR_STATE_TEXTURE_UNITS];
    GLenum texture_targets[MVR_STATE_TEXTURE_UNITS];
    GLuint samplers[MVR_STATE_TEXTURE_UNITS];
    GLint viewport[4];
    bool depth_test, cull_face, blend, scissor_test;
    bool rasterizer_discard;     /* the pre-skinning capture only */
    bool polygon_offset_fill;
    GLfloat polygon_offset_factor, polygon_offset_units;
    bool framebuffer_srgb;       /* desktop GL only (GLES always encodes into sRGB formats) */
    GLenum depth_func, cull_mode, front_face;
    GLboolean depth_mask;
    GLboolean color_mask[4];
    GLenum blend_src_rgb, blend_dst_rgb, blend_src_a, blend_dst_a;
    GLenum clip_origin, clip_depth;
    mvr_state_counters counters;
    /* Benchmark baseline (MVR_MATERIAL_PATH_PER_DRAW): texture and uniform
     * range binds are sent even when nothing changed, as a renderer without
     * state tracking would. */
    bool rebind_always;
} mvr_state_cache;

/* GL's initial state (known = true), or all unknown (known = false). */
void mvr_state_init(mvr_state_cache *s, const mvr_gl_api_table *gl, bool known);
void mvr_state_invalidate(mvr_state_cache *s);

void mvr_state_program(mvr_state_cache *s, GLuint program);
/* Records a program made current outside the cache (by the program builder). */
void mvr_state_assume_program(mvr_state_cache *s, GLuint program);
void mvr_state_vao(mvr_state_cache *s, GLuint vao);
void mvr_state_array_buffer(mvr_state_cache *s, GLuint buffer);
void mvr_state_draw_framebuffer(mvr_state_cache *s, GLuint fbo);
void mvr_state_read_framebuffer(mvr_state_cache *s, GLuint fbo);
void mvr_state_ubo_range(mvr_state_cache *s, GLuint index, GLuint buffer, GLintptr offset,
                         GLsizeiptr size);
void mvr_state_texture(mvr_state_cache *s, GLuint unit, GLenum target, GLuint texture);
void mvr_state_sampler(mvr_state_cache *s, GLuint unit, GLuint sampler);
void mvr_state_viewport(mvr_state_cache *s, GLint x, GLint y, GLsizei w, GLsizei h);
void mvr_state_depth(mvr_state_cache *s, bool test, GLenum func, GLboolean mask);
void mvr_state_cull(mvr_state_cache *s, bool enabled, GLenum front_face);
void mvr_state_blend(mvr_state_cache *s, bool enabled, GLenum src_rgb, GLenum dst_rgb,
                     GLenum src_a, GLenum dst_a);
void mvr_state_color_mask(mvr_state_cache *s, bool all);
void mvr_state_scissor_test(mvr_state_cache *s, bool enabled);
void mvr_state_rasterizer_discard(mvr_state_cache *s, bool enabled);
/* GL_POLYGON_OFFSET_FILL and glPolygonOffset (values kept while disabled). */
void mvr_state_polygon_offset(mvr_state_cache *s, bool enabled, GLfloat factor, GLfloat units);
/* Desktop GL: sRGB encoding (and linear blending) for writes to sRGB
 * formats, which GLES always does; off by default there. Never call on GLES. */
void mvr_state_framebuffer_srgb(mvr_state_cache *s, bool enabled);
/* Needs a ClipControl entry point; callers check the caps first. */
void mvr_state_clip_control(mvr_state_cache *s, GLenum origin, GLenum depth);

/* Forgets a deleted object wherever the cache holds it (GL unbinds it too). */
void mvr_state_forget_texture(mvr_state_cache *s, GLuint texture);
/* Forgets every texture binding: the next bind of each unit is sent. */
void mvr_state_forget_textures(mvr_state_cache *s);
void mvr_state_forget_buffer(mvr_state_cache *s, GLuint buffer);
void mvr_state_forget_framebuffer(mvr_state_cache *s, GLuint fbo);
void mvr_state_forget_program(mvr_state_cache *s, GLuint program);
void mvr_state_forget_vao(mvr_state_cache *s, GLuint vao);
/* GL unbinds a deleted sampler from every unit; a GL that hands its name out
 * again (NVIDIA's does at once) would otherwise see the bind skipped. */
void mvr_state_forget_sampler(mvr_state_cache *s, GLuint sampler);

#endif
