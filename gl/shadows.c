/*
 * Shadow maps: a view-independent pass. The frame's shadow layers (cascades
 * of directional lights, one map per spot light; core/shadow_plan.c) live in
 * one depth texture array, drawn once per frame before any view: one
 * multiview pass over up to GL_MAX_VIEWS_OVR layers where the GL has
 * multiview (so a frame of any number of views draws its casters once per
 * chunk of layers, usually once), one pass per layer otherwise, then read by
 * every view's pass with PCF.
 */
#include <string.h>

#include "draw_list.h"
#include "errors.h"
#include "program_cache.h"
#include "renderer.h"
#include "shadows.h"
#include "skinning.h"
#include "targets.h"

#ifndef GL_TEXTURE_COMPARE_MODE
#define GL_TEXTURE_COMPARE_MODE 0x884C
#define GL_TEXTURE_COMPARE_FUNC 0x884D
#define GL_COMPARE_REF_TO_TEXTURE 0x884E
#endif

const char *mvr_shadow_mode_name(mvr_shadow_mode mode)
{
    switch (mode) {
    case MVR_SHADOWS_DEFAULT: return "default";
    case MVR_SHADOWS_ALL: return "all";
    case MVR_SHADOWS_OFF: return "off";
    }
    return NULL;
}

static bool shadow_multiview(const mvr_renderer *r)
{
    const mvr_caps *c = &r->ctx->caps;
    /* the loop fallback, when forced, draws shadow layers one by one too:
     * that is the path without multiview, and tests compare the two */
    return c->ext.ovr_multiview2 && c->limits.max_views_ovr >= 2 && r->gl->FramebufferTextureMultiviewOVR &&
           r->requested_path != MVR_VIEW_PATH_LOOP;
}

void mvr_shadows_plan(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t, const mvr_render_desc *desc)
{
    mvr_shadow_maps *sm = &r->shadows;
    sm->settings = mvr_shadow_desc_resolve(&desc->shadows);
    if (sm->settings.map_size > (uint32_t)r->ctx->caps.limits.max_texture_size)
        sm->settings.map_size = (uint32_t)r->ctx->caps.limits.max_texture_size;
    mvr_shadow_plan_build(&sm->plan, &r->frame, views, t->desc.width, t->desc.height, r->reversed_z, &sm->settings);
    if (sm->plan.lights_unshadowed)
        mvr_log(&r->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                "mvr: %u lights cast no shadow: the %d shadow layers are taken", sm->plan.lights_unshadowed,
                MVR_SHADOW_MAX_LAYERS);
}

void mvr_shadows_release(mvr_renderer *r)
{
    mvr_shadow_maps *sm = &r->shadows;
    for (uint32_t i = 0; i < sm->fbo_count; ++i)
        mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &sm->fbos[i].fbo);
    sm->fbo_count = 0;
    mvr_gl_delete(r, MVR_GL_TEXTURE, &sm->depth);
    mvr_gl_delete(r, MVR_GL_TEXTURE, &sm->color);
    sm->size = sm->layers = 0;
    mvr_gl_delete(r, MVR_GL_SAMPLER, &sm->sampler);
}

/* The arrays, (re)made when the size changes or more layers are needed. */
static mvr_result ensure_maps(mvr_renderer *r, uint32_t size, uint32_t layers)
{
    mvr_shadow_maps *sm = &r->shadows;
    const mvr_gl_api_table *gl = r->gl;
    GLenum compare = r->reversed_z ? GL_GEQUAL : GL_LEQUAL;
    if (sm->depth && sm->size == size && sm->layers >= layers && sm->compare == compare)
        return MVR_OK;
    mvr_shadows_release(r);
    gl->GenTextures(1, &sm->depth);
    mvr_state_texture(&r->state, MVR_UNIT_SHADOW_MAP, GL_TEXTURE_2D_ARRAY, sm->depth);
    gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_DEPTH_COMPONENT32F, (GLsizei)size, (GLsizei)size, (GLsizei)layers);
    mvr_result res = mvr_gl_check_alloc(r, "shadow map depth array (%ux%u, %u layers, depth32f)", size, size,
                                        layers);
    if (res == MVR_OK) {
        gl->GenTextures(1, &sm->color);
        mvr_state_texture(&r->state, MVR_UNIT_SHADOW_MAP, GL_TEXTURE_2D_ARRAY, sm->color);
        gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_R8, (GLsizei)size, (GLsizei)size, (GLsizei)layers);
        res = mvr_gl_check_alloc(r, "shadow map color array (%ux%u, %u layers, r8)", size, size, layers);
    }
    if (res != MVR_OK) {
        mvr_shadows_release(r); /* made again, whole, by the next frame that asks */
        return res;
    }
    gl->GenSamplers(1, &sm->sampler);
    /* linear + comparison: the GL's bilinear 2x2 PCF per tap */
    gl->SamplerParameteri(sm->sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->SamplerParameteri(sm->sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->SamplerParameteri(sm->sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->SamplerParameteri(sm->sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->SamplerParameteri(sm->sampler, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl->SamplerParameteri(sm->sampler, GL_TEXTURE_COMPARE_FUNC, (GLint)compare);
    sm->size = size;
    sm->layers = layers;
    sm->compare = compare;
    r->upload_bytes += (uint64_t)size * size * layers * 5u;
    return MVR_OK;
}

static mvr_result shadow_framebuffer(mvr_renderer *r, uint32_t base, uint32_t count, GLuint *out)
{
    mvr_shadow_maps *sm = &r->shadows;
    for (uint32_t i = 0; i < sm->fbo_count; ++i)
        if (sm->fbos[i].base == base && sm->fbos[i].count == count) {
            *out = sm->fbos[i].fbo;
            return MVR_OK;
        }
    if (sm->fbo_count == MVR_SHADOW_FBOS)
        return mvr_gl_fail(r, MVR_ERROR_INTERNAL, "shadow framebuffers: more than %d", MVR_SHADOW_FBOS);
    const mvr_gl_api_table *gl = r->gl;
    GLuint fbo = 0;
    gl->GenFramebuffers(1, &fbo);
    mvr_state_draw_framebuffer(&r->state, fbo);
    if (count > 0) {
        /* a depth-only multiview pass still gets a color attachment: some
         * drivers mishandle multiview framebuffers without one */
        gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, sm->color, 0, (GLint)base,
                                           (GLsizei)count);
        gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, sm->depth, 0, (GLint)base,
                                           (GLsizei)count);
    } else {
        gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, sm->color, 0, (GLint)base);
        gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, sm->depth, 0, (GLint)base);
    }
    sm->fbos[sm->fbo_count].base = base;
    sm->fbos[sm->fbo_count].count = count;
    sm->fbos[sm->fbo_count++].fbo = fbo;
    char where[96];
    mvr_str_format(where, sizeof where, "shadow framebuffer for layers %u..%u%s", base,
                   base + (count ? count : 1) - 1, count ? " (multiview)" : "");
    mvr_result res = mvr_gl_check(r->ctx, where, true);
    if (res == MVR_OK)
        res = mvr_gl_check_framebuffer(r->ctx, GL_DRAW_FRAMEBUFFER, where);
    if (res != MVR_OK) {
        mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &sm->fbos[--sm->fbo_count].fbo);
        return mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    }
    *out = fbo;
    return MVR_OK;
}

/* What a caster's program needs of its features: an opaque caster writes
 * depth alone (one program for all of them); a masked one runs the alpha
 * test, so keeps what its base color alpha reads. */
static uint32_t caster_features(const mvr_draw *d)
{
    /* a caster casts its posed shape: skinning and morphing stay (the
     * vertex path; pre-skinned draws have none and draw their capture) */
    uint32_t deform = d->features & MVR_DEFORM_FEATURES;
    if (d->pass != MVR_PASS_MASK)
        return MVR_FEATURE_SHADOW_CASTER | deform;
    return MVR_FEATURE_SHADOW_CASTER | deform |
           (d->features & (MVR_FEATURE_ALPHA_MASK | MVR_FEATURE_UV0 | MVR_FEATURE_UV1 | MVR_FEATURE_COLOR0 |
                           MVR_FEATURE_BASE_COLOR_TEX | MVR_FEATURE_TEXTURE_TRANSFORM |
                           MVR_FEATURE_MATERIAL_ARRAYS));
}

static bool caster_visible(const mvr_renderer *r, const mvr_draw *d, uint32_t base, uint32_t count)
{
    if (r->culling == false)
        return true;
    for (uint32_t k = base; k < base + count; ++k)
        if (mvr_sphere_in_frustum(&r->shadows.plan.layers[k].frustum, d->center, d->radius))
            return true;
    return false;
}

typedef struct caster_pass {
    uint32_t base, count;        /* layers */
    uint32_t num_views;          /* multiview views, 0 = a single layer */
    GLintptr draws_at;
} caster_pass;

static mvr_result bind_caster_program(mvr_renderer *r, const caster_pass *cp, uint32_t features)
{
    mvr_shader_variant v = mvr_mesh_variant(r, features, cp->num_views);
    mvr_program_entry *e = NULL;
    mvr_result res = mvr_program_cache_get(r, &v, &e);
    if (res != MVR_OK)
        return res;
    mvr_state_program(&r->state, e->program);
    if (e->view_base != (int32_t)cp->base) {
        r->gl->Uniform1i(e->loc_view_base, (GLint)cp->base);
        e->view_base = (int32_t)cp->base;
    }
    return MVR_OK;
}

static mvr_result draw_casters(mvr_renderer *r, const caster_pass *cp)
{
    const mvr_frame *f = &r->frame;
    const mvr_gpu_scene *g = &r->gpu;
    mvr_state_cache *st = &r->state;
    GLsizeiptr draw_range = r->draw_capacity > 1 ? (GLsizeiptr)r->draw_capacity * r->draw_stride
                                                 : (GLsizeiptr)MVR_DRAW_BLOCK_SIZE;
    uint32_t bound_features = 0;
    /* opaque and masked draws, in the frame's order; blended ones cast nothing */
    for (int kind = MVR_PASS_OPAQUE; kind <= MVR_PASS_MASK; ++kind) {
    uint32_t end = f->pass_first[kind] + f->pass_count[kind];
    for (uint32_t pos = f->pass_first[kind]; pos < end; ++pos) {
        const mvr_draw *d = &f->draws[pos];
        if (!caster_visible(r, d, cp->base, cp->count))
            continue;
        uint32_t features = caster_features(d);
        /* instancing: following draws of the same primitive whose blocks
         * come next (blocks are stored in draw order) */
        uint32_t n = 1;
        while (r->draw_capacity > 1 && n < r->draw_capacity && pos + n < end) {
            const mvr_draw *b = &f->draws[pos + n];
            bool same = b->primitive == d->primitive && !mvr_skinning_vao(r, d) && !mvr_skinning_vao(r, b) &&
                        b->mirrored == d->mirrored &&
                        caster_features(b) == features &&
                        (b->features & MVR_FEATURE_DOUBLE_SIDED) == (d->features & MVR_FEATURE_DOUBLE_SIDED) &&
                        (d->pass != MVR_PASS_MASK ||
                         (b->material_page == d->material_page && b->group_key == d->group_key));
            if (!same || !caster_visible(r, b, cp->base, cp->count))
                break;
            n++;
        }
        if (features != bound_features) {
            mvr_result res = bind_caster_program(r, cp, features);
            if (res != MVR_OK)
                return res;
            bound_features = features;
        }
        mvr_state_ubo_range(st, MVR_BLOCK_DRAW, r->ring.buffer,
                            cp->draws_at + (GLintptr)d->block * f->block_stride, draw_range);
        if (d->pass == MVR_PASS_MASK) {
            mvr_state_ubo_range(st, MVR_BLOCK_MATERIALS, g->material_ubo,
                                (GLintptr)d->material_page * g->material_page_stride,
                                (GLsizeiptr)r->material_capacity * MVR_MATERIAL_BLOCK_SIZE);
            /* the base color a masked caster's alpha test reads */
            mvr_bind_draw_textures(r, d, d->features & MVR_FEATURE_BASE_COLOR_TEX, NULL, NULL);
        }
        mvr_submit_draw(r, d, n);
        r->stats.shadow_draws += n;
        r->stats.draw_calls++;
        pos += n - 1;
    }
    }
    return MVR_OK;
}

mvr_result mvr_shadows_draw(mvr_renderer *r, GLintptr views_at, GLintptr draws_at)
{
    mvr_shadow_maps *sm = &r->shadows;
    const mvr_shadow_plan *plan = &sm->plan;
    mvr_state_cache *st = &r->state;
    if (plan->layer_count == 0)
        return MVR_OK;
    mvr_result res = ensure_maps(r, sm->settings.map_size, plan->layer_count);
    if (res != MVR_OK)
        return res;
    /* the maps are written here: no unit may sample them meanwhile */
    mvr_state_texture(st, MVR_UNIT_SHADOW_MAP, GL_TEXTURE_2D_ARRAY, 0);
    mvr_state_ubo_range(st, MVR_BLOCK_VIEWS, r->ring.buffer, views_at, (GLsizeiptr)MVR_VIEWS_BLOCK_SIZE);
    mvr_state_viewport(st, 0, 0, (GLsizei)sm->size, (GLsizei)sm->size);
    mvr_state_scissor_test(st, false);
    mvr_state_blend(st, false, GL_ONE, GL_ZERO, GL_ONE, GL_ZERO);
    mvr_state_color_mask(st, false);
    GLenum depth_func = r->reversed_z ? GL_GREATER : GL_LESS;
    mvr_state_depth(st, true, depth_func, GL_TRUE);
    /* slope-scaled bias pushes casters away from the light: towards 0 in
     * reversed-Z, towards 1 in standard depth */
    float sign = r->reversed_z ? -1.0f : 1.0f;
    mvr_state_polygon_offset(st, true, sign * sm->settings.slope_bias, sign * sm->settings.constant_bias);
    float clear_depth = r->reversed_z ? 0.0f : 1.0f;
    bool multiview = shadow_multiview(r);
    uint32_t max_views = (uint32_t)r->ctx->caps.limits.max_views_ovr;
    for (uint32_t base = 0; base < plan->layer_count && res == MVR_OK;) {
        uint32_t count = 1;
        if (multiview) {
            count = plan->layer_count - base;
            if (count > max_views)
                count = max_views;
        }
        bool mv_pass = multiview && count > 1;
        GLuint fbo = 0;
        res = shadow_framebuffer(r, base, mv_pass ? count : 0, &fbo);
        if (res != MVR_OK)
            break;
        mvr_state_draw_framebuffer(st, fbo);
        r->gl->ClearBufferfv(GL_DEPTH, 0, &clear_depth);
        caster_pass cp = {base, count, mv_pass ? count : 0, draws_at};
        res = draw_casters(r, &cp);
        r->stats.shadow_passes++;
        base += count;
    }
    mvr_state_polygon_offset(st, false, 0.0f, 0.0f);
    mvr_state_color_mask(st, true);
    r->stats.shadow_layers = plan->layer_count;
    return res;
}

void mvr_shadows_bind(mvr_renderer *r, GLintptr block_at)
{
    mvr_shadow_maps *sm = &r->shadows;
    if (sm->plan.layer_count == 0 || !sm->depth)
        return;
    mvr_state_texture(&r->state, MVR_UNIT_SHADOW_MAP, GL_TEXTURE_2D_ARRAY, sm->depth);
    mvr_state_sampler(&r->state, MVR_UNIT_SHADOW_MAP, sm->sampler);
    mvr_state_ubo_range(&r->state, MVR_BLOCK_SHADOWS, r->ring.buffer, block_at, MVR_SHADOW_BLOCK_SIZE);
}
