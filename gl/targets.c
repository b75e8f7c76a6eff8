/* Targets: a 2D texture array of N layers (color + depth). The color array is
 * mvr's own or the application's (an XR swapchain image); the depth array is
 * always mvr's. Framebuffers are made on first use per layer range and kept. */
#include <stdlib.h>
#include <string.h>

#include "renderer_internal.h"

static GLenum gl_color_format(mvr_color_format f)
{
    switch (f) {
    case MVR_COLOR_FORMAT_DEFAULT: return GL_SRGB8_ALPHA8;
    case MVR_COLOR_FORMAT_RGBA8: return GL_RGBA8;
    case MVR_COLOR_FORMAT_RGBA16F: return GL_RGBA16F;
    case MVR_COLOR_FORMAT_RGBA32F: return GL_RGBA32F;
    }
    return GL_SRGB8_ALPHA8;
}

/* The multisampled renderbuffers a view is drawn into before its resolve. */
static mvr_result make_msaa(mvr_target *t)
{
    mvr_renderer *r = t->renderer;
    const mvr_gl_api_table *gl = r->gl;
    GLint max = 0;
    /* the format's own limit (float formats may allow fewer than GL_MAX_SAMPLES) */
    gl->GetInternalformativ(GL_RENDERBUFFER, t->internal_format, GL_SAMPLES, 1, &max);
    if ((GLint)t->desc.samples > max)
        return mvr_renderer_fail(r, MVR_ERROR_UNSUPPORTED,
                                 "mvr_target_create: %u samples asked, %s allows at most %d on %s", t->desc.samples,
                                 mvr_color_format_name(t->desc.color_format), max, r->ctx->caps.renderer);
    GLsizei w = (GLsizei)t->desc.width, h = (GLsizei)t->desc.height, n = (GLsizei)t->desc.samples;
    gl->GenRenderbuffers(1, &t->msaa_color);
    gl->BindRenderbuffer(GL_RENDERBUFFER, t->msaa_color);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, n, t->internal_format, w, h);
    gl->GenRenderbuffers(1, &t->msaa_depth);
    gl->BindRenderbuffer(GL_RENDERBUFFER, t->msaa_depth);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_DEPTH_COMPONENT32F, w, h);
    gl->BindRenderbuffer(GL_RENDERBUFFER, 0);
    gl->GenFramebuffers(1, &t->msaa_fbo);
    mvr_state_draw_framebuffer(&r->state, t->msaa_fbo);
    gl->FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->msaa_color);
    gl->FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->msaa_depth);
    mvr_result res = mvr_gl_check(r->ctx, "multisampled framebuffer", true);
    if (res == MVR_OK)
        res = mvr_gl_check_framebuffer(r->ctx, GL_DRAW_FRAMEBUFFER, "multisampled framebuffer");
    if (res != MVR_OK)
        return mvr_renderer_fail(r, res, "mvr_target_create: %u samples: %s", t->desc.samples,
                                 mvr_context_last_error(r->ctx));
    return MVR_OK;
}

mvr_result mvr_target_create(mvr_renderer *r, const mvr_target_desc *d, mvr_target **out)
{
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (!d || !out)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_target_create: NULL argument");
    *out = NULL;
    const mvr_caps *c = &r->ctx->caps;
    mvr_target_desc desc = *d;
    if (desc.layers == 0)
        desc.layers = 1;
    if (!mvr_color_format_name(desc.color_format))
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_target_create: unknown color format %d",
                                 (int)desc.color_format);
    if (desc.width == 0 || desc.height == 0 || desc.width > (uint32_t)c->limits.max_texture_size ||
        desc.height > (uint32_t)c->limits.max_texture_size)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_target_create: size %ux%u not within 1..%d", desc.width, desc.height,
                                 c->limits.max_texture_size);
    uint64_t last_layer = (uint64_t)desc.external_base_layer + desc.layers;
    if (last_layer > (uint64_t)c->limits.max_array_texture_layers)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_target_create: layers up to %llu exceed GL_MAX_ARRAY_TEXTURE_LAYERS %d",
                                 (unsigned long long)last_layer, c->limits.max_array_texture_layers);
    if ((desc.color_format == MVR_COLOR_FORMAT_RGBA16F && !c->ext.ext_color_buffer_half_float) ||
        (desc.color_format == MVR_COLOR_FORMAT_RGBA32F && !c->ext.ext_color_buffer_float))
        return mvr_renderer_fail(r, MVR_ERROR_UNSUPPORTED, "mvr_target_create: %s is not renderable on %s",
                                 mvr_color_format_name(desc.color_format), c->renderer);
    if (desc.supersample > 4 || (desc.supersample > 1 && desc.samples > 1))
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_target_create: supersample %u (1..4, and not with samples)", desc.supersample);
    uint32_t factor = desc.supersample > 1 ? desc.supersample : 1;
    if ((uint64_t)desc.width * factor > (uint64_t)c->limits.max_texture_size ||
        (uint64_t)desc.height * factor > (uint64_t)c->limits.max_texture_size)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_target_create: %ux%u supersampled %u times exceeds GL_MAX_TEXTURE_SIZE %d",
                                 desc.width, desc.height, factor, c->limits.max_texture_size);
    GLenum ss_format = desc.color_format == MVR_COLOR_FORMAT_RGBA32F || !c->ext.ext_color_buffer_half_float
                           ? GL_RGBA32F : GL_RGBA16F;
    if (factor > 1 && ss_format == GL_RGBA32F && !c->ext.ext_color_buffer_float)
        return mvr_renderer_fail(r, MVR_ERROR_UNSUPPORTED,
                                 "mvr_target_create: supersampling needs a renderable float format on %s", c->renderer);
    if (desc.samples > 1 && desc.samples > (uint32_t)c->limits.max_samples)
        return mvr_renderer_fail(r, MVR_ERROR_UNSUPPORTED, "mvr_target_create: %u samples; GL_MAX_SAMPLES is %d",
                                 desc.samples, c->limits.max_samples);
    if (!desc.external_color_texture && (desc.external_level || desc.external_base_layer))
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_target_create: external_level / external_base_layer need an external texture");
    mvr_target *t = calloc(1, sizeof *t);
    if (!t)
        return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "mvr_target_create: out of memory");
    t->renderer = r;
    t->desc = desc;
    mvr_state_invalidate(&r->state);
    t->internal_format = gl_color_format(desc.color_format);
    const mvr_gl_api_table *gl = r->gl;
    if (desc.external_color_texture) {
        t->color = desc.external_color_texture;
    } else {
        gl->GenTextures(1, &t->color);
        mvr_state_texture(&r->state, 0, GL_TEXTURE_2D_ARRAY, t->color);
        gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, t->internal_format, (GLsizei)desc.width,
                         (GLsizei)desc.height, (GLsizei)desc.layers);
        t->owns_color = true;
    }
    if (factor > 1) {
        /* linear float samples: the resolve averages light, then encodes */
        t->ss_format = ss_format;
        gl->GenTextures(1, &t->ss_color);
        mvr_state_texture(&r->state, 0, GL_TEXTURE_2D_ARRAY, t->ss_color);
        gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, ss_format, (GLsizei)(desc.width * factor),
                         (GLsizei)(desc.height * factor), (GLsizei)desc.layers);
    }
    /* depth: 32-bit float (reversed-Z keeps its precision with distance) */
    gl->GenTextures(1, &t->depth);
    mvr_state_texture(&r->state, 0, GL_TEXTURE_2D_ARRAY, t->depth);
    gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_DEPTH_COMPONENT32F, (GLsizei)(desc.width * factor),
                     (GLsizei)(desc.height * factor), (GLsizei)desc.layers);
    if (mvr_gl_check(r->ctx, "mvr_target_create", true) != MVR_OK) {
        mvr_result res = mvr_renderer_fail(r, MVR_ERROR_GL, "%s (external texture %u: a %s 2D array of at "
                                           "least %ux%u and %llu layers?)",
                                           mvr_context_last_error(r->ctx), desc.external_color_texture,
                                           mvr_color_format_name(desc.color_format), desc.width,
                                           desc.height, (unsigned long long)last_layer);
        mvr_target_destroy(t);
        return res;
    }
    /* an application texture of the wrong kind shows up as an incomplete FBO */
    GLuint fbo = 0;
    mvr_result res = mvr_target_framebuffer(t, 0, 0, &fbo);
    if (res == MVR_OK && desc.samples > 1)
        res = make_msaa(t);
    if (res != MVR_OK) {
        mvr_target_destroy(t);
        return res;
    }
    *out = t;
    return MVR_OK;
}

void mvr_target_destroy(mvr_target *t)
{
    if (!t)
        return;
    mvr_renderer *r = t->renderer;
    const mvr_gl_api_table *gl = r->gl;
    for (uint32_t i = 0; i < t->fbo_count; ++i) {
        mvr_state_forget_framebuffer(&r->state, t->fbos[i].fbo);
        gl->DeleteFramebuffers(1, &t->fbos[i].fbo);
    }
    free(t->fbos);
    if (t->owns_color) {
        mvr_state_forget_texture(&r->state, t->color);
        gl->DeleteTextures(1, &t->color);
    }
    mvr_state_forget_texture(&r->state, t->depth);
    gl->DeleteTextures(1, &t->depth);
    if (t->ss_color) {
        mvr_state_forget_texture(&r->state, t->ss_color);
        gl->DeleteTextures(1, &t->ss_color);
    }
    if (t->msaa_fbo) {
        mvr_state_forget_framebuffer(&r->state, t->msaa_fbo);
        gl->DeleteFramebuffers(1, &t->msaa_fbo);
    }
    gl->DeleteRenderbuffers(1, &t->msaa_color);
    gl->DeleteRenderbuffers(1, &t->msaa_depth);
    free(t);
}

uint32_t mvr_target_color_texture(const mvr_target *t)
{
    return t ? t->color : 0;
}

uint32_t mvr_target_factor(const mvr_target *t)
{
    return t->ss_color ? t->desc.supersample : 1;
}

static mvr_result target_framebuffer(mvr_target *t, uint32_t base, uint32_t count, bool output, GLuint *out);

mvr_result mvr_target_framebuffer(mvr_target *t, uint32_t base, uint32_t count, GLuint *out)
{
    return target_framebuffer(t, base, count, false, out);
}

mvr_result mvr_target_output_framebuffer(mvr_target *t, uint32_t base, uint32_t count, GLuint *out)
{
    /* without supersampling the color array views are drawn into is the output */
    return target_framebuffer(t, base, count, t->ss_color != 0, out);
}

static mvr_result target_framebuffer(mvr_target *t, uint32_t base, uint32_t count, bool output, GLuint *out)
{
    for (uint32_t i = 0; i < t->fbo_count; ++i) {
        if (t->fbos[i].base == base && t->fbos[i].count == count && t->fbos[i].output == output) {
            *out = t->fbos[i].fbo;
            return MVR_OK;
        }
    }
    mvr_renderer *r = t->renderer;
    if (t->fbo_count == t->fbo_cap) {
        uint32_t cap = t->fbo_cap ? t->fbo_cap * 2 : 8;
        mvr_fbo_entry *p = realloc(t->fbos, cap * sizeof *p);
        if (!p)
            return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "framebuffers: out of memory");
        t->fbos = p;
        t->fbo_cap = cap;
    }
    const mvr_gl_api_table *gl = r->gl;
    GLuint fbo = 0;
    gl->GenFramebuffers(1, &fbo);
    mvr_state_draw_framebuffer(&r->state, fbo);
    /* the real level and base layer: the application's array may be a level
     * or a slice of a larger texture; a supersampled target draws views into
     * its own array and writes the application's only in the resolve */
    bool into_color = output || !t->ss_color;
    GLuint color = into_color ? t->color : t->ss_color;
    GLint level = into_color ? (GLint)t->desc.external_level : 0;
    GLint layer = (GLint)((into_color ? t->desc.external_base_layer : 0) + base);
    if (count > 0) {
        gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, color, level, layer,
                                           (GLsizei)count);
        if (!output)
            gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, t->depth, 0,
                                               (GLint)base, (GLsizei)count);
    } else {
        gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, color, level, layer);
        if (!output)
            gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, t->depth, 0, (GLint)base);
    }
    t->fbos[t->fbo_count].base = base;
    t->fbos[t->fbo_count].output = output;
    t->fbos[t->fbo_count].count = count;
    t->fbos[t->fbo_count++].fbo = fbo;
    char where[96];
    mvr_str_format(where, sizeof where, "framebuffer for layers %u..%u%s", base, base + (count ? count : 1) - 1,
                   count ? " (multiview)" : "");
    mvr_result res = mvr_gl_check(r->ctx, where, true);
    if (res == MVR_OK)
        res = mvr_gl_check_framebuffer(r->ctx, GL_DRAW_FRAMEBUFFER, where);
    if (res != MVR_OK)
        return mvr_renderer_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    *out = fbo;
    return MVR_OK;
}
