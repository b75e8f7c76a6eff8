/* Targets: a 2D texture array of N layers (color + depth). The color array is
 * mvr's own or the application's (an XR swapchain image); the depth array is
 * always mvr's. Framebuffers are made on first use per layer range and kept. */
#include <stdlib.h>
#include <string.h>

#include "errors.h"
#include "renderer.h"
#include "targets.h"

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
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED,
                           "mvr_target_create: %u samples asked, %s allows at most %d on %s", t->desc.samples,
                           mvr_color_format_name(t->desc.color_format), max, r->ctx->caps.renderer);
    GLsizei w = (GLsizei)t->desc.width, h = (GLsizei)t->desc.height, n = (GLsizei)t->desc.samples;
    gl->GenRenderbuffers(1, &t->msaa_color);
    gl->BindRenderbuffer(GL_RENDERBUFFER, t->msaa_color);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, n, t->internal_format, w, h);
    mvr_result res = mvr_gl_check_alloc(r, "mvr_target_create: multisampled color renderbuffer (%dx%d %s, %d "
                                        "samples)", w, h, mvr_color_format_name(t->desc.color_format), n);
    if (res != MVR_OK)
        return res;
    gl->GenRenderbuffers(1, &t->msaa_depth);
    gl->BindRenderbuffer(GL_RENDERBUFFER, t->msaa_depth);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_DEPTH_COMPONENT32F, w, h);
    gl->BindRenderbuffer(GL_RENDERBUFFER, 0);
    res = mvr_gl_check_alloc(r, "mvr_target_create: multisampled depth renderbuffer (%dx%d depth32f, %d samples)",
                             w, h, n);
    if (res != MVR_OK)
        return res;
    gl->GenFramebuffers(1, &t->msaa_fbo);
    mvr_state_draw_framebuffer(&r->state, t->msaa_fbo);
    gl->FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->msaa_color);
    gl->FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->msaa_depth);
    res = mvr_gl_check(r->ctx, "multisampled framebuffer", true);
    if (res == MVR_OK)
        res = mvr_gl_check_framebuffer(r->ctx, GL_DRAW_FRAMEBUFFER, "multisampled framebuffer");
    if (res != MVR_OK)
        return mvr_gl_fail(r, res, "mvr_target_create: %u samples: %s", t->desc.samples,
                           mvr_context_last_error(r->ctx));
    return MVR_OK;
}

const char *mvr_anti_aliasing_name(mvr_anti_aliasing aa)
{
    switch (aa) {
    case MVR_ANTI_ALIASING_DEFAULT: return "default";
    case MVR_ANTI_ALIASING_NONE: return "none";
    case MVR_ANTI_ALIASING_MSAA: return "msaa";
    case MVR_ANTI_ALIASING_SUPERSAMPLE: return "supersample";
    case MVR_ANTI_ALIASING_AUTO: return "auto";
    }
    return NULL;
}

/* The samples or supersample factor an anti-aliasing choice asks. */
static bool resolve_anti_aliasing(mvr_renderer *r, mvr_target_desc *d)
{
    const mvr_caps *c = &r->ctx->caps;
    mvr_anti_aliasing aa = d->anti_aliasing;
    /* the default: what samples or supersample ask (1: none), else the
     * AUTO method (mvr_target.h says why); none where extra outputs are
     * asked (an ID or a depth is not averaged: they stay exact, the colour
     * is not anti-aliased) */
    if (aa == MVR_ANTI_ALIASING_DEFAULT && d->samples == 0 && d->supersample == 0 && !d->outputs)
        aa = MVR_ANTI_ALIASING_AUTO;
    switch (aa) {
    case MVR_ANTI_ALIASING_DEFAULT:
        return true;
    case MVR_ANTI_ALIASING_NONE:
        d->samples = d->supersample = 0;
        return true;
    case MVR_ANTI_ALIASING_MSAA:
        d->supersample = 0;
        if (d->samples <= 1)
            d->samples = 4;
        return true;
    case MVR_ANTI_ALIASING_SUPERSAMPLE:
        d->samples = 0;
        if (d->supersample <= 1)
            d->supersample = 2;
        return true;
    case MVR_ANTI_ALIASING_AUTO: {
        /* 4x MSAA where the format takes it (multiview or per view: the
         * render picks), else 2x2 supersampling where a float target renders */
        GLint max = 0;
        r->gl->GetInternalformativ(GL_RENDERBUFFER, gl_color_format(d->color_format), GL_SAMPLES, 1, &max);
        d->samples = d->supersample = 0;
        if (max >= 4)
            d->samples = 4;
        else if (c->ext.ext_color_buffer_half_float || c->ext.ext_color_buffer_float)
            d->supersample = 2;
        return true;
    }
    }
    return false;
}

/* Multisampled multiview where the GL has it (and overrides.msaa_multiview is not off). */
static mvr_result make_msaa_multiview(mvr_target *t)
{
    mvr_renderer *r = t->renderer;
    const mvr_gl_api_table *gl = r->gl;
    const mvr_caps *c = &r->ctx->caps;
    if (r->msaa_multiview_off || !c->ext.ovr_multiview2 || t->desc.external_level != 0)
        return MVR_OK;
    if (c->ext.ovr_multiview_multisampled_render_to_texture && gl->FramebufferTextureMultisampleMultiviewOVR) {
        t->msaa_multiview = MVR_MSAA_MV_RENDER_TO_TEXTURE;
        return MVR_OK;
    }
    if (!c->ext.multiview_msaa_array)
        return MVR_OK;
    GLsizei w = (GLsizei)t->desc.width, h = (GLsizei)t->desc.height, n = (GLsizei)t->desc.samples;
    GLsizei layers = (GLsizei)t->desc.layers;
    gl->GenTextures(1, &t->msaa_array_color);
    mvr_state_texture(&r->state, 0, GL_TEXTURE_2D_MULTISAMPLE_ARRAY, t->msaa_array_color);
    gl->TexStorage3DMultisample(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, n, t->internal_format, w, h, layers, GL_TRUE);
    gl->GenTextures(1, &t->msaa_array_depth);
    mvr_state_texture(&r->state, 0, GL_TEXTURE_2D_MULTISAMPLE_ARRAY, t->msaa_array_depth);
    gl->TexStorage3DMultisample(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, n, GL_DEPTH_COMPONENT32F, w, h, layers, GL_TRUE);
    mvr_result res = mvr_gl_check(r->ctx, "multisampled arrays", true);
    if (res != MVR_OK) {
        /* the probe passed for RGBA8; this format (or this much memory) may
         * not: per view instead, with the renderbuffers made already */
        mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL,
                "mvr: no multisampled %s array here (%s): MSAA resolves view by view",
                mvr_color_format_name(t->desc.color_format), mvr_context_last_error(r->ctx));
        mvr_gl_delete(r, MVR_GL_TEXTURE, &t->msaa_array_color);
        mvr_gl_delete(r, MVR_GL_TEXTURE, &t->msaa_array_depth);
        return MVR_OK;
    }
    t->msaa_multiview = MVR_MSAA_MV_ARRAY;
    return MVR_OK;
}

/* A failure after mvr_gl_call_begin: recorded, and no GL error left behind. */
static mvr_result fail_create(mvr_renderer *r, mvr_result result, const char *fmt, ...) MVR_PRINTF(3, 4);
static mvr_result fail_create(mvr_renderer *r, mvr_result result, const char *fmt, ...)
{
    char message[MVR_ERROR_MESSAGE_SIZE];
    va_list ap;
    va_start(ap, fmt);
    mvr_str_vformat(message, sizeof message, fmt, ap);
    va_end(ap);
    return mvr_gl_call_end(r, "mvr_target_create", mvr_gl_fail(r, result, "%s", message));
}

/* One layered array of the target: storage checked, the failure naming it. */
static mvr_result make_array(mvr_target *t, GLuint *name, const char *what, GLenum format, const char *format_name,
                             uint32_t width, uint32_t height)
{
    mvr_renderer *r = t->renderer;
    const mvr_gl_api_table *gl = r->gl;
    gl->GenTextures(1, name);
    mvr_state_texture(&r->state, 0, GL_TEXTURE_2D_ARRAY, *name);
    gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, format, (GLsizei)width, (GLsizei)height, (GLsizei)t->desc.layers);
    double mib = (double)width * height * t->desc.layers *
                 (format == GL_RGBA32F || format == GL_RGBA32UI ? 16 : format == GL_RGBA16F ? 8 : 4) /
                 (1024.0 * 1024.0);
    return mvr_gl_check_alloc(r, "%s (%ux%u, %u layers, %s, %.1f %s)", what, width, height,
                              t->desc.layers, format_name, mib >= 1024.0 ? mib / 1024.0 : mib,
                              mib >= 1024.0 ? "GiB" : "MiB");
}

/* The color (unless the application's), supersampled and depth arrays. */
static mvr_result make_arrays(mvr_target *t, uint32_t factor, GLenum ss_format)
{
    const mvr_target_desc *desc = &t->desc;
    mvr_result res = MVR_OK;
    if (desc->external_color_texture) {
        t->color = desc->external_color_texture;
    } else {
        t->owns_color = true;
        res = make_array(t, &t->color, "mvr_target_create: color array", t->internal_format,
                         mvr_color_format_name(desc->color_format), desc->width, desc->height);
    }
    /* linear float samples: the resolve averages light, then encodes */
    if (res == MVR_OK && factor > 1) {
        t->ss_format = ss_format;
        res = make_array(t, &t->ss_color, "mvr_target_create: supersampled color array", ss_format,
                         ss_format == GL_RGBA32F ? "rgba32f" : "rgba16f", desc->width * factor, desc->height * factor);
    }
    /* depth: 32-bit float (reversed-Z keeps its precision with distance) */
    if (res == MVR_OK)
        res = make_array(t, &t->depth, "mvr_target_create: depth array", GL_DEPTH_COMPONENT32F, "depth32f",
                         desc->width * factor, desc->height * factor);
    /* extra outputs: full float (a depth in metres keeps 24 bits) and exact integers */
    static const struct { uint32_t bits, shader; GLenum format; const char *what, *name; } arrays[] = {
        {MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH) | MVR_OUTPUT_BIT(MVR_OUTPUT_DISTANCE) | MVR_OUTPUT_BIT(MVR_OUTPUT_COVERAGE),
         MVR_SHADER_OUT_GEOMETRY, GL_RGBA32F, "mvr_target_create: depth, distance and coverage array", "rgba32f"},
        {MVR_OUTPUT_BIT(MVR_OUTPUT_NORMAL), MVR_SHADER_OUT_NORMAL, GL_RGBA32F, "mvr_target_create: normal array",
         "rgba32f"},
        {MVR_OUTPUT_BIT(MVR_OUTPUT_IDS), MVR_SHADER_OUT_IDS, GL_RGBA32UI, "mvr_target_create: ID array", "rgba32ui"},
    };
    _Static_assert(MVR_ARRAY_COUNT(arrays) == MVR_TARGET_OUTPUT_ARRAYS, "one array per kind");
    for (uint32_t k = 0; k < MVR_TARGET_OUTPUT_ARRAYS && res == MVR_OK; ++k)
        if (desc->outputs & arrays[k].bits) {
            res = make_array(t, &t->output_arrays[k], arrays[k].what, arrays[k].format, arrays[k].name, desc->width,
                             desc->height);
            t->shader_outputs |= arrays[k].shader;
        }
    return res;
}

mvr_result mvr_target_create(mvr_renderer *r, const mvr_target_desc *d, mvr_target **out)
{
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (!d || !out)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_target_create: NULL argument");
    *out = NULL;
    if (!r->ctx)
        return mvr_gl_fail(r, MVR_ERROR_CONTEXT, "mvr_target_create: the renderer's context was destroyed");
    const mvr_caps *c = &r->ctx->caps;
    mvr_target_desc desc = *d;
    if (desc.layers == 0)
        desc.layers = 1;
    if (!mvr_anti_aliasing_name(desc.anti_aliasing))
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_target_create: unknown anti-aliasing %d",
                           (int)desc.anti_aliasing);
    if (!mvr_color_format_name(desc.color_format))
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_target_create: unknown color format %d",
                           (int)desc.color_format);
    if (desc.width == 0 || desc.height == 0 || desc.width > (uint32_t)c->limits.max_texture_size ||
        desc.height > (uint32_t)c->limits.max_texture_size)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_target_create: size %ux%u not within 1..%d", desc.width, desc.height,
                           c->limits.max_texture_size);
    uint64_t last_layer = (uint64_t)desc.external_base_layer + desc.layers;
    if (last_layer > (uint64_t)c->limits.max_array_texture_layers)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_target_create: layers up to %llu exceed GL_MAX_ARRAY_TEXTURE_LAYERS %d",
                           (unsigned long long)last_layer, c->limits.max_array_texture_layers);
    if ((desc.color_format == MVR_COLOR_FORMAT_RGBA16F && !c->ext.ext_color_buffer_half_float) ||
        (desc.color_format == MVR_COLOR_FORMAT_RGBA32F && !c->ext.ext_color_buffer_float))
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED, "mvr_target_create: %s is not renderable on %s",
                           mvr_color_format_name(desc.color_format), c->renderer);
    mvr_result res = mvr_gl_call_begin(r, "mvr_target_create");
    if (res != MVR_OK)
        return res;
    if (!mvr_color_format_name(desc.color_format) || !resolve_anti_aliasing(r, &desc))
        return fail_create(r, MVR_ERROR_INTERNAL, "mvr_target_create: anti-aliasing");
    if (desc.supersample > 4 || (desc.supersample > 1 && desc.samples > 1))
        return fail_create(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_target_create: supersample %u (1..4, and not with samples)", desc.supersample);
    uint32_t factor = desc.supersample > 1 ? desc.supersample : 1;
    if ((uint64_t)desc.width * factor > (uint64_t)c->limits.max_texture_size ||
        (uint64_t)desc.height * factor > (uint64_t)c->limits.max_texture_size)
        return fail_create(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_target_create: %ux%u supersampled %u times exceeds GL_MAX_TEXTURE_SIZE %d",
                           desc.width, desc.height, factor, c->limits.max_texture_size);
    GLenum ss_format = desc.color_format == MVR_COLOR_FORMAT_RGBA32F || !c->ext.ext_color_buffer_half_float
                           ? GL_RGBA32F : GL_RGBA16F;
    if (factor > 1 && ss_format == GL_RGBA32F && !c->ext.ext_color_buffer_float)
        return fail_create(r, MVR_ERROR_UNSUPPORTED,
                           "mvr_target_create: supersampling needs a renderable float format on %s", c->renderer);
    if (desc.samples > 1 && desc.samples > (uint32_t)c->limits.max_samples)
        return fail_create(r, MVR_ERROR_UNSUPPORTED, "mvr_target_create: %u samples; GL_MAX_SAMPLES is %d",
                           desc.samples, c->limits.max_samples);
    if (desc.outputs & ~((MVR_OUTPUT_BIT(MVR_OUTPUT_COUNT) - 1u) & ~MVR_OUTPUT_BIT(MVR_OUTPUT_COLOR)))
        return fail_create(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_target_create: unknown output bits 0x%x",
                           desc.outputs & ~((MVR_OUTPUT_BIT(MVR_OUTPUT_COUNT) - 1u) & ~MVR_OUTPUT_BIT(MVR_OUTPUT_COLOR)));
    if (desc.outputs && (desc.samples > 1 || desc.supersample > 1))
        return fail_create(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_target_create: extra outputs (depth, normals, IDs) need a target without "
                           "anti-aliasing: an ID or a depth is not averaged (%s)",
                           desc.samples > 1 ? "multisampled" : "supersampled");
    if ((desc.outputs & ~MVR_OUTPUT_BIT(MVR_OUTPUT_IDS)) && !c->ext.ext_color_buffer_float)
        return fail_create(r, MVR_ERROR_UNSUPPORTED,
                           "mvr_target_create: depth, distance, normal and coverage outputs need float colour "
                           "buffers (OpenGL ES 3.2 or EXT_color_buffer_float), which %s lacks", c->renderer);
    if (desc.outputs && c->limits.max_draw_buffers < 4)
        return fail_create(r, MVR_ERROR_UNSUPPORTED, "mvr_target_create: extra outputs need 4 draw buffers; %s has %d",
                           c->renderer, c->limits.max_draw_buffers);
    if (!desc.external_color_texture && (desc.external_level || desc.external_base_layer))
        return fail_create(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_target_create: external_level / external_base_layer need an external texture");
    mvr_target *t = calloc(1, sizeof *t);
    if (!t)
        return fail_create(r, MVR_ERROR_OUT_OF_MEMORY, "mvr_target_create: out of memory");
    t->renderer = r;
    t->desc = desc;
    /* linked first: a failure below releases through mvr_target_destroy */
    t->next = r->targets;
    r->targets = t;
    mvr_state_invalidate(&r->state);
    t->internal_format = gl_color_format(desc.color_format);
    res = make_arrays(t, factor, ss_format);
    /* an application texture of the wrong kind shows up as an incomplete FBO */
    GLuint fbo = 0;
    if (res == MVR_OK) {
        res = mvr_target_framebuffer(t, 0, 0, &fbo);
        if (res != MVR_OK && desc.external_color_texture) {
            char why[MVR_ERROR_MESSAGE_SIZE];
            mvr_str_copy(why, sizeof why, r->last_error);
            res = mvr_gl_fail(r, res,
                              "%s (external texture %u: a %s 2D array of at least %ux%u and %llu layers?)",
                              why, desc.external_color_texture,
                              mvr_color_format_name(desc.color_format), desc.width, desc.height,
                              (unsigned long long)last_layer);
        }
    }
    if (res == MVR_OK && desc.samples > 1)
        res = make_msaa(t);
    if (res == MVR_OK && desc.samples > 1)
        res = make_msaa_multiview(t);
    t->anti_aliasing = desc.samples > 1       ? MVR_ANTI_ALIASING_MSAA
                       : desc.supersample > 1 ? MVR_ANTI_ALIASING_SUPERSAMPLE
                                              : MVR_ANTI_ALIASING_NONE;
    res = mvr_gl_call_end(r, "mvr_target_create", res);
    if (res != MVR_OK) {
        mvr_target_destroy(t);
        return res;
    }
    *out = t;
    return MVR_OK;
}

void mvr_target_release_gl(mvr_target *t)
{
    mvr_renderer *r = t->renderer;
    for (uint32_t i = 0; i < t->fbo_count; ++i)
        mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &t->fbos[i].fbo);
    t->fbo_count = 0;
    if (t->owns_color)
        mvr_gl_delete(r, MVR_GL_TEXTURE, &t->color);
    GLuint *textures[] = {&t->depth,     &t->ss_color, &t->msaa_array_color,  &t->msaa_array_depth,  &t->hdr_color,
                          &t->msaa_hdr_array,
                          &t->lum,       &t->output_arrays[0], &t->output_arrays[1], &t->output_arrays[2]};
    _Static_assert(MVR_TARGET_OUTPUT_ARRAYS == 3, "every output array released");
    for (size_t i = 0; i < MVR_ARRAY_COUNT(textures); ++i)
        mvr_gl_delete(r, MVR_GL_TEXTURE, textures[i]);
    mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &t->msaa_fbo);
    mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &t->msaa_hdr_fbo);
    mvr_gl_delete(r, MVR_GL_RENDERBUFFER, &t->msaa_color);
    mvr_gl_delete(r, MVR_GL_RENDERBUFFER, &t->msaa_depth);
    mvr_gl_delete(r, MVR_GL_RENDERBUFFER, &t->msaa_hdr_color);
    t->msaa_multiview = MVR_MSAA_MV_NONE;
    t->lum_levels = 0;
}

void mvr_target_destroy(mvr_target *t)
{
    if (!t)
        return;
    mvr_renderer *r = t->renderer;
    if (r) {
        mvr_target_release_gl(t);
        for (mvr_target **p = &r->targets; *p; p = &(*p)->next)
            if (*p == t) {
                *p = t->next;
                break;
            }
    }
    free(t->fbos);
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
    /* without supersampling or an HDR frame the color array views are drawn into is the output */
    return target_framebuffer(t, base, count, t->ss_color != 0 || t->hdr_frame, out);
}

/* The target's framebuffer for a key (base, count, output, msaa, aux): the
 * cached one (*created false), or a new one, generated, recorded and bound
 * for drawing, for the caller to attach to and check (*created true). */
static mvr_result fbo_find_or_create(mvr_target *t, mvr_fbo_entry key, GLuint *out, bool *created)
{
    for (uint32_t i = 0; i < t->fbo_count; ++i) {
        const mvr_fbo_entry *e = &t->fbos[i];
        if (e->base == key.base && e->count == key.count && e->output == key.output && e->msaa == key.msaa &&
            e->aux == key.aux) {
            *out = e->fbo;
            *created = false;
            return MVR_OK;
        }
    }
    mvr_renderer *r = t->renderer;
    if (t->fbo_count == t->fbo_cap) {
        uint32_t cap = t->fbo_cap ? t->fbo_cap * 2 : 8;
        mvr_fbo_entry *p = realloc(t->fbos, cap * sizeof *p);
        if (!p)
            return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "framebuffers: out of memory");
        t->fbos = p;
        t->fbo_cap = cap;
    }
    key.fbo = 0;
    r->gl->GenFramebuffers(1, &key.fbo);
    mvr_state_draw_framebuffer(&r->state, key.fbo);
    t->fbos[t->fbo_count++] = key;
    *out = key.fbo;
    *created = true;
    return MVR_OK;
}

/* After attaching the framebuffer fbo_find_or_create made last: no GL error
 * and a complete framebuffer, or a message naming where (and the framebuffer
 * leaves the cache, so a later lookup never finds it). */
static mvr_result fbo_check(mvr_target *t, const char *where)
{
    mvr_renderer *r = t->renderer;
    mvr_result res = mvr_gl_check(r->ctx, where, true);
    if (res == MVR_OK)
        res = mvr_gl_check_framebuffer(r->ctx, GL_DRAW_FRAMEBUFFER, where);
    if (res != MVR_OK) {
        mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &t->fbos[--t->fbo_count].fbo);
        return mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    }
    return MVR_OK;
}

static mvr_result target_framebuffer(mvr_target *t, uint32_t base, uint32_t count, bool output, GLuint *out)
{
    /* an HDR frame draws views into the half-float array (a supersampled
     * target's own array is float already) */
    uint8_t aux = !output && t->hdr_frame && !t->ss_color ? (uint8_t)MVR_FBO_HDR : 0;
    mvr_fbo_entry key = {.base = base, .count = count, .output = output, .aux = aux};
    bool created = false;
    mvr_result res = fbo_find_or_create(t, key, out, &created);
    if (res != MVR_OK || !created)
        return res;
    const mvr_gl_api_table *gl = t->renderer->gl;
    /* the real level and base layer: the application's array may be a level
     * or a slice of a larger texture; a supersampled target draws views into
     * its own array and writes the application's only in the resolve */
    bool into_color = output || (!t->ss_color && !aux);
    GLuint color = into_color ? t->color : aux ? t->hdr_color : t->ss_color;
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
    /* the extra outputs: more layered attachments of the same views */
    if (!output && t->shader_outputs) {
        for (uint32_t k = 0; k < MVR_TARGET_OUTPUT_ARRAYS; ++k) {
            if (!t->output_arrays[k])
                continue;
            if (count > 0)
                gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT1 + k, t->output_arrays[k],
                                                   0, (GLint)base, (GLsizei)count);
            else
                gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT1 + k, t->output_arrays[k], 0,
                                            (GLint)base);
        }
        mvr_target_draw_buffers(t, MVR_DRAW_ALL);
    }
    char where[96];
    mvr_str_format(where, sizeof where, "framebuffer for layers %u..%u%s", base, base + (count ? count : 1) - 1,
                   count ? " (multiview)" : "");
    return fbo_check(t, where);
}

void mvr_target_draw_buffers(mvr_target *t, int which)
{
    if (!t->shader_outputs)
        return;
    GLenum bufs[1 + MVR_TARGET_OUTPUT_ARRAYS];
    bufs[0] = (which & MVR_DRAW_COLOR) ? GL_COLOR_ATTACHMENT0 : GL_NONE;
    for (uint32_t k = 0; k < MVR_TARGET_OUTPUT_ARRAYS; ++k)
        bufs[k + 1] = (which & MVR_DRAW_OUTPUTS) && t->output_arrays[k] ? GL_COLOR_ATTACHMENT1 + k : GL_NONE;
    t->renderer->gl->DrawBuffers((GLsizei)MVR_ARRAY_COUNT(bufs), bufs);
}

mvr_result mvr_target_output_array_framebuffer(mvr_target *t, uint32_t k, uint32_t layer, GLuint *out)
{
    mvr_fbo_entry key = {.base = layer, .count = 0, .output = true, .aux = (uint8_t)(MVR_FBO_OUTPUT_ARRAY + k)};
    bool created = false;
    mvr_result res = fbo_find_or_create(t, key, out, &created);
    if (res != MVR_OK || !created)
        return res;
    t->renderer->gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t->output_arrays[k], 0,
                                             (GLint)layer);
    char where[96];
    mvr_str_format(where, sizeof where, "framebuffer of output array %u, layer %u", k, layer);
    return fbo_check(t, where);
}

mvr_result mvr_target_msaa_framebuffer(mvr_target *t, uint32_t base, uint32_t count, GLuint *out)
{
    if (t->msaa_multiview == MVR_MSAA_MV_NONE)
        return mvr_gl_fail(t->renderer, MVR_ERROR_INTERNAL,
                           "multisampled multiview framebuffer without the GL's support");
    mvr_fbo_entry key = {.base = base, .count = count, .msaa = true};
    bool created = false;
    mvr_result res = fbo_find_or_create(t, key, out, &created);
    if (res != MVR_OK || !created)
        return res;
    const mvr_gl_api_table *gl = t->renderer->gl;
    GLsizei samples = (GLsizei)t->desc.samples;
    GLint layer = (GLint)(t->desc.external_base_layer + base);
    if (t->msaa_multiview == MVR_MSAA_MV_RENDER_TO_TEXTURE) {
        /* implicit multisampled storage, resolved into the layers by the GL */
        gl->FramebufferTextureMultisampleMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t->color, 0, samples,
                                                      layer, (GLsizei)count);
        gl->FramebufferTextureMultisampleMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, t->depth, 0, samples,
                                                      (GLint)base, (GLsizei)count);
    } else if (count > 0) {
        gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t->msaa_array_color, 0,
                                           (GLint)base, (GLsizei)count);
        gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, t->msaa_array_depth, 0,
                                           (GLint)base, (GLsizei)count);
    } else {
        /* one layer of the multisampled array, read by the resolve blit */
        gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t->msaa_array_color, 0, (GLint)base);
    }
    char where[96];
    mvr_str_format(where, sizeof where, "multisampled framebuffer for layers %u..%u", base,
                   base + (count ? count : 1) - 1);
    return fbo_check(t, where);
}

mvr_result mvr_target_ensure_hdr(mvr_target *t)
{
    mvr_renderer *r = t->renderer;
    const mvr_gl_api_table *gl = r->gl;
    if (t->ss_color)
        return MVR_OK; /* float already */
    GLsizei w = (GLsizei)t->desc.width, h = (GLsizei)t->desc.height;
    if (!t->hdr_color) {
        if (!r->ctx->caps.ext.ext_color_buffer_half_float && !r->ctx->caps.ext.ext_color_buffer_float)
            return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED,
                               "HDR frame (tone mapping, physical exposure or dithering): %s renders to no "
                               "half-float format", r->ctx->caps.renderer);
        mvr_result res = make_array(t, &t->hdr_color, "the target's HDR color array", GL_RGBA16F, "rgba16f",
                                    t->desc.width, t->desc.height);
        if (res != MVR_OK) {
            mvr_gl_delete(r, MVR_GL_TEXTURE, &t->hdr_color); /* made again by the next HDR frame */
            return res;
        }
    }
    const mvr_caps *c = &r->ctx->caps;
    bool ms_arrays = gl->TexStorage3DMultisample &&
                     (c->api == MVR_GL_API_GLES ? c->gl_major > 3 || (c->gl_major == 3 && c->gl_minor >= 2)
                                                : c->gl_major > 4 || (c->gl_major == 4 && c->gl_minor >= 2));
    if (t->desc.samples > 1 && ms_arrays && !t->msaa_hdr_array && !t->msaa_hdr_fbo) {
        gl->GenTextures(1, &t->msaa_hdr_array);
        mvr_state_texture(&r->state, 0, GL_TEXTURE_2D_MULTISAMPLE_ARRAY, t->msaa_hdr_array);
        gl->TexStorage3DMultisample(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, (GLsizei)t->desc.samples, GL_RGBA16F, w, h,
                                    (GLsizei)t->desc.layers, GL_TRUE);
        mvr_result res = mvr_gl_check(r->ctx, "multisampled HDR array", true);
        if (res != MVR_OK) { /* one renderbuffer instead, resolved before the post pass */
            mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL,
                    "mvr: no multisampled rgba16f array here (%s): the HDR frame resolves before tone mapping",
                    mvr_context_last_error(r->ctx));
            mvr_gl_delete(r, MVR_GL_TEXTURE, &t->msaa_hdr_array);
        }
    }
    if (t->desc.samples > 1 && !t->msaa_hdr_array && !t->msaa_hdr_fbo) {
        if (!t->msaa_hdr_color) {
            gl->GenRenderbuffers(1, &t->msaa_hdr_color);
            gl->BindRenderbuffer(GL_RENDERBUFFER, t->msaa_hdr_color);
            gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, (GLsizei)t->desc.samples, GL_RGBA16F, w, h);
            gl->BindRenderbuffer(GL_RENDERBUFFER, 0);
            mvr_result res = mvr_gl_check_alloc(r, "multisampled HDR renderbuffer (%dx%d rgba16f, %u samples)",
                                                w, h, t->desc.samples);
            if (res != MVR_OK) {
                mvr_gl_delete(r, MVR_GL_RENDERBUFFER, &t->msaa_hdr_color);
                return res;
            }
        }
        gl->GenFramebuffers(1, &t->msaa_hdr_fbo);
        mvr_state_draw_framebuffer(&r->state, t->msaa_hdr_fbo);
        gl->FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->msaa_hdr_color);
        gl->FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->msaa_depth);
        mvr_result res = mvr_gl_check(r->ctx, "multisampled HDR framebuffer", true);
        if (res == MVR_OK)
            res = mvr_gl_check_framebuffer(r->ctx, GL_DRAW_FRAMEBUFFER, "multisampled HDR framebuffer");
        if (res != MVR_OK) {
            mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &t->msaa_hdr_fbo);
            return mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
        }
    }
    return MVR_OK;
}

mvr_result mvr_target_msaa_hdr_framebuffer(mvr_target *t, uint32_t layer, GLuint *out)
{
    if (!t->msaa_hdr_array) {
        *out = t->msaa_hdr_fbo;
        return MVR_OK;
    }
    mvr_fbo_entry key = {.base = layer, .count = 0, .msaa = true, .aux = MVR_FBO_MSAA_HDR};
    bool created = false;
    mvr_result res = fbo_find_or_create(t, key, out, &created);
    if (res != MVR_OK || !created)
        return res;
    const mvr_gl_api_table *gl = t->renderer->gl;
    gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t->msaa_hdr_array, 0, (GLint)layer);
    gl->FramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->msaa_depth);
    return fbo_check(t, "multisampled HDR framebuffer");
}

mvr_result mvr_target_luminance_framebuffer(mvr_target *t, int kind, uint32_t base, uint32_t count, GLuint *out)
{
    mvr_renderer *r = t->renderer;
    const mvr_gl_api_table *gl = r->gl;
    if (!t->lum) {
        /* RG16F: renderable and filterable (the mip chain averages it) on GLES 3 with half-float rendering */
        uint32_t size = t->desc.width > t->desc.height ? t->desc.width : t->desc.height, levels = 1;
        while (size > 1) {
            size /= 2;
            levels++;
        }
        gl->GenTextures(1, &t->lum);
        mvr_state_texture(&r->state, 0, GL_TEXTURE_2D_ARRAY, t->lum);
        gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, (GLsizei)levels, GL_RG16F, (GLsizei)t->desc.width,
                         (GLsizei)t->desc.height, (GLsizei)t->desc.layers);
        mvr_result res = mvr_gl_check_alloc(r, "auto-exposure luminance array (%ux%u, %u layers, rg16f, %u mips)",
                                            t->desc.width, t->desc.height, t->desc.layers, levels);
        if (res != MVR_OK) {
            mvr_gl_delete(r, MVR_GL_TEXTURE, &t->lum);
            return res;
        }
        t->lum_levels = levels;
    }
    mvr_fbo_entry key = {.base = base, .count = count, .aux = (uint8_t)kind};
    bool created = false;
    mvr_result res = fbo_find_or_create(t, key, out, &created);
    if (res != MVR_OK || !created)
        return res;
    if (kind == MVR_FBO_LUMINANCE && count > 0)
        gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t->lum, 0, (GLint)base,
                                           (GLsizei)count);
    else
        gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t->lum,
                                    kind == MVR_FBO_LUMINANCE_TOP ? (GLint)t->lum_levels - 1 : 0, (GLint)base);
    return fbo_check(t, "luminance framebuffer");
}
