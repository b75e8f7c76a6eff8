/*
 * The HDR frame's final passes. Lighting went into a half-float array
 * (multiplied by a pre-exposure that keeps half floats in range); then, per
 * chunk of views, one full-screen pass (multiview over the chunk's layers,
 * or one per view on the loop path: the same shader code per layer, so the
 * same bytes) applies exposure, tone mapping, dithering and the sRGB encode
 * into the target's layers. Auto-exposure first writes log2 luminance into
 * an RG16F array whose mip chain the GL averages, and reads each layer's last
 * level back (a few floats; the frame's exposure needs them now).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "environment.h"
#include "environment_gl.h"
#include "errors.h"
#include "post.h"
#include "program_cache.h"
#include "renderer.h"
#include "targets.h"

#define POST_VIEWS 32 /* MVR_POST_VIEWS of composite.frag.glsl */

bool mvr_post_needed(const mvr_render_desc *d)
{
    return d->tone_map != MVR_TONE_MAP_NONE || d->exposure_mode != MVR_EXPOSURE_LINEAR || d->dither;
}

/* The EV100 a manual mode asks (compensation included). */
static double manual_ev100(const mvr_render_desc *d)
{
    switch (d->exposure_mode) {
    case MVR_EXPOSURE_EV100:
        return d->ev100 - d->exposure_compensation;
    case MVR_EXPOSURE_CAMERA:
        return mvr_ev100_from_camera(d->aperture, d->shutter, d->iso) - d->exposure_compensation;
    case MVR_EXPOSURE_LINEAR:
    case MVR_EXPOSURE_AUTO:
        break;
    }
    /* LINEAR: the EV100 whose exposure is the multiplier */
    return log2(1.0 / (1.2 * (double)d->exposure));
}

static float exposure_key(const mvr_render_desc *d)
{
    return d->exposure_key > 0.0f ? d->exposure_key : 0.18f;
}

/* A first guess for auto-exposure, before any frame was measured: middle
 * grey lit by the lights (lux; candela at their distance from the origin,
 * at least 1), so the half floats stay in range. */
static double guess_auto_exposure(const mvr_renderer *r, const mvr_render_desc *d)
{
    const mvr_frame *f = &r->frame;
    uint32_t n = f->light_counts[0] + f->light_counts[1] + f->light_counts[2];
    double lux = 0.0;
    for (uint32_t i = 0; i < n; ++i) {
        double intensity = f->lights[i].peak;
        if (f->lights[i].type == MVR_LIGHT_DIRECTIONAL)
            lux += intensity;
        else
            lux += intensity / fmax(mvr_dvec3_dot(f->lights[i].position, f->lights[i].position), 1.0);
    }
    double luminance = fmax(lux * 0.18 / 3.14159265358979323846, 1e-3);
    /* an environment: a grey card under its average diffuse light */
    if (d->environment)
        luminance += 0.18 * mvr_environment_average_diffuse(d->environment);
    return exposure_key(d) / luminance;
}

double mvr_post_pre_exposure(mvr_renderer *r, const mvr_target *t, const mvr_render_desc *d)
{
    if (d->exposure_mode == MVR_EXPOSURE_AUTO)
        return t->last_auto_exposure > 0.0 ? t->last_auto_exposure : guess_auto_exposure(r, d);
    return mvr_exposure_from_ev100(manual_ev100(d));
}

static uint32_t post_features(const mvr_target *t, const mvr_render_desc *d)
{
    uint32_t f = MVR_FEATURE_POST;
    if (t->ss_color)
        f |= MVR_FEATURE_DOWNSAMPLE;
    if (t->internal_format == GL_RGBA8)
        f |= MVR_FEATURE_SRGB_ENCODE;
    if (d->tone_map == MVR_TONE_MAP_ACES)
        f |= MVR_FEATURE_POST_ACES;
    else if (d->tone_map == MVR_TONE_MAP_KHR_PBR_NEUTRAL)
        f |= MVR_FEATURE_POST_PBR_NEUTRAL;
    if (d->dither && (t->internal_format == GL_RGBA8 || t->internal_format == GL_SRGB8_ALPHA8))
        f |= MVR_FEATURE_DITHER;
    if (t->hdr_frame && t->msaa_hdr_array)
        f |= MVR_FEATURE_POST_MSAA;
    return f;
}

void mvr_full_screen_state(mvr_renderer *r)
{
    mvr_state_cache *st = &r->state;
    if (!r->empty_vao)
        r->gl->GenVertexArrays(1, &r->empty_vao); /* attributeless draws still need one (core GL) */
    mvr_state_depth(st, false, GL_ALWAYS, GL_FALSE);
    mvr_state_blend(st, false, GL_ONE, GL_ZERO, GL_ONE, GL_ZERO);
    mvr_state_cull(st, false, GL_CCW);
    mvr_state_color_mask(st, true);
    mvr_state_scissor_test(st, false);
    mvr_state_vao(st, r->empty_vao);
}

static void full_screen_state(mvr_renderer *r, GLuint source)
{
    mvr_state_cache *st = &r->state;
    mvr_full_screen_state(r);
    mvr_state_texture(st, MVR_UNIT_COMPOSITE_SOURCE, GL_TEXTURE_2D_ARRAY, source);
    mvr_state_sampler(st, MVR_UNIT_COMPOSITE_SOURCE, 0);
}

mvr_result mvr_full_screen_passes(mvr_renderer *r, mvr_target *t, GLuint source, const mvr_view_chunk *chunks,
                                  uint32_t chunk_count, bool multiview, uint32_t features, const float *post_mul,
                                  bool luminance, uint32_t *passes)
{
    const mvr_gl_api_table *gl = r->gl;
    mvr_state_cache *st = &r->state;
    full_screen_state(r, source);
    for (uint32_t c = 0; c < chunk_count; ++c) {
        const mvr_view_chunk *ch = &chunks[c];
        bool mv_pass = multiview && ch->count > 1;
        for (uint32_t k = 0; k < (mv_pass ? 1u : ch->count); ++k) {
            uint32_t base = ch->base + k, count = mv_pass ? ch->count : 0;
            GLuint fbo = 0;
            mvr_result res = luminance ? mvr_target_luminance_framebuffer(t, MVR_FBO_LUMINANCE, base, count, &fbo)
                                       : mvr_target_output_framebuffer(t, base, count, &fbo);
            if (res != MVR_OK)
                return res;
            /* (making the luminance array binds it: the source goes back) */
            mvr_state_texture(st, MVR_UNIT_COMPOSITE_SOURCE, GL_TEXTURE_2D_ARRAY, source);
            mvr_shader_variant v;
            memset(&v, 0, sizeof v);
            v.program = MVR_PROGRAM_COMPOSITE;
            v.features = features;
            v.num_views = count;
            mvr_program_entry *e = NULL;
            res = mvr_program_cache_get(r, &v, &e);
            if (res != MVR_OK)
                return res;
            mvr_state_program(st, e->program);
            gl->Uniform1i(e->loc_layer_base, (GLint)base);
            if (e->loc_factor >= 0)
                gl->Uniform1i(e->loc_factor, (GLint)mvr_target_factor(t));
            if (e->loc_clear_depth >= 0)
                gl->Uniform1f(e->loc_clear_depth, r->reversed_z ? 0.0f : 1.0f);
            if (features & MVR_FEATURE_POST_MSAA) {
                mvr_state_texture(st, MVR_UNIT_COMPOSITE_DEPTH, GL_TEXTURE_2D_MULTISAMPLE_ARRAY, t->msaa_hdr_array);
                gl->Uniform1i(e->loc_samples, (GLint)t->desc.samples);
            }
            if (e->loc_clear_out >= 0)
                gl->Uniform4fv(e->loc_clear_out, 1, t->post_clear);
            if (e->loc_post_exposure >= 0)
                gl->Uniform1fv(e->loc_post_exposure, (GLsizei)(count ? count : 1), post_mul + base);
            mvr_state_draw_framebuffer(st, fbo);
            /* luminance: the whole layer (the auto-exposure averages it); post: the view's rectangle */
            if (luminance)
                mvr_state_viewport(st, 0, 0, (GLsizei)t->desc.width, (GLsizei)t->desc.height);
            else
                mvr_state_viewport(st, ch->viewport.x, ch->viewport.y, (GLsizei)ch->viewport.width,
                                   (GLsizei)ch->viewport.height);
            if (!luminance && (features & (MVR_FEATURE_POST | MVR_FEATURE_DOWNSAMPLE))) {
                /* the display clear colour, which the pass keeps where no surface was drawn */
                mvr_state_scissor_test(st, true);
                gl->Scissor(ch->viewport.x, ch->viewport.y, (GLsizei)ch->viewport.width, (GLsizei)ch->viewport.height);
                gl->ClearBufferfv(GL_COLOR, 0, t->post_clear);
                mvr_state_scissor_test(st, false);
            }
            gl->DrawArrays(GL_TRIANGLES, 0, 3);
            (*passes)++;
        }
    }
    return MVR_OK;
}

/* Auto-exposure: the mean log2 luminance of each enabled layer (of the
 * pre-exposed source), through the mip chain. */
static mvr_result measure(mvr_renderer *r, mvr_target *t, const mvr_view_chunk *chunks, uint32_t chunk_count,
                          bool multiview, double *mean_log2, bool *measured)
{
    const mvr_gl_api_table *gl = r->gl;
    uint32_t features = MVR_FEATURE_LOG_LUMINANCE | (t->ss_color ? MVR_FEATURE_DOWNSAMPLE : 0u);
    /* the depth array, read texel by texel: a nearest sampler (a depth
     * texture with linear filtering and no comparison is incomplete) */
    if (!r->nearest_sampler) {
        gl->GenSamplers(1, &r->nearest_sampler);
        gl->SamplerParameteri(r->nearest_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->SamplerParameteri(r->nearest_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    mvr_state_texture(&r->state, MVR_UNIT_COMPOSITE_DEPTH, GL_TEXTURE_2D_ARRAY, t->depth);
    mvr_state_sampler(&r->state, MVR_UNIT_COMPOSITE_DEPTH, r->nearest_sampler);
    GLuint source = t->ss_color ? t->ss_color : t->hdr_color;
    mvr_result res = mvr_full_screen_passes(r, t, source, chunks, chunk_count, multiview, features, NULL, true,
                                        &r->stats.luminance_passes);
    if (res != MVR_OK)
        return res;
    mvr_state_texture(&r->state, MVR_UNIT_COMPOSITE_SOURCE, GL_TEXTURE_2D_ARRAY, t->lum);
    gl->GenerateMipmap(GL_TEXTURE_2D_ARRAY);
    for (uint32_t c = 0; c < chunk_count; ++c)
        for (uint32_t k = 0; k < chunks[c].count; ++k) {
            uint32_t layer = chunks[c].base + k;
            GLuint fbo = 0;
            res = mvr_target_luminance_framebuffer(t, MVR_FBO_LUMINANCE_TOP, layer, 0, &fbo);
            if (res != MVR_OK)
                return res;
            mvr_state_read_framebuffer(&r->state, fbo);
            float px[4] = {0, 0, 0, 0};
            gl->ReadPixels(0, 0, 1, 1, GL_RGBA, GL_FLOAT, px);
            /* r: mean of log2 luminance over all texels (0 where black), g: the lit fraction */
            measured[layer] = isfinite(px[0]) && px[1] > 1e-4f;
            mean_log2[layer] = measured[layer] ? px[0] / px[1] : 0.0;
        }
    res = mvr_gl_check(r->ctx, "auto-exposure reduction", true);
    return res == MVR_OK ? MVR_OK : mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
}

mvr_result mvr_post_run(mvr_renderer *r, mvr_target *t, const mvr_view_set *views, const mvr_render_desc *d,
                        const mvr_view_chunk *chunks, uint32_t chunk_count, bool multiview, double pre_exposure)
{
    uint32_t n = views->count;
    float post_mul[256];
    double ev[256];
    double mean_log2[256];
    bool measured[256];
    if (n > 256)
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED, "post pass: more than 256 views");
    GLuint source = t->ss_color ? t->ss_color : t->hdr_color;
    double manual = manual_ev100(d);
    for (uint32_t v = 0; v < n; ++v)
        ev[v] = manual;
    if (d->exposure_mode == MVR_EXPOSURE_AUTO) {
        memset(measured, 0, sizeof measured);
        mvr_result res = measure(r, t, chunks, chunk_count, multiview, mean_log2, measured);
        if (res != MVR_OK)
            return res;
        /* EV100 that puts the average log luminance on the key:
         * exposure(EV) * L_avg = key, L_avg = 2^mean / pre-exposure */
        double lo = d->ev100_min, hi = d->ev100_max;
        if (lo == 0.0 && hi == 0.0) {
            lo = -8.0;
            hi = 24.0;
        }
        double key = exposure_key(d), shared = 0.0;
        uint32_t count = 0;
        for (uint32_t v = 0; v < n; ++v)
            if (measured[v]) {
                shared += mean_log2[v];
                count++;
            }
        shared = count ? shared / count : log2(key);
        /* for a caller metering views over several renders (mvr render's stream) */
        r->stats.exposure_measured_views = count;
        r->stats.exposure_log2_luminance = count ? shared - log2(pre_exposure) : 0.0;
        for (uint32_t v = 0; v < n; ++v) {
            double m = d->exposure_per_view && measured[v] ? mean_log2[v] : shared;
            double log2_avg = m - log2(pre_exposure);
            double e = log2_avg - log2(1.2 * key) - d->exposure_compensation;
            ev[v] = e < lo ? lo : e > hi ? hi : e;
        }
        t->last_auto_exposure = mvr_exposure_from_ev100(ev[0]);
    }
    for (uint32_t v = 0; v < n; ++v) {
        double exposure = d->exposure_mode == MVR_EXPOSURE_LINEAR ? (double)d->exposure : mvr_exposure_from_ev100(ev[v]);
        post_mul[v] = (float)(exposure / pre_exposure);
    }
    /* the chunk's views index the exposures from its first layer */
    uint32_t max_chunk = 0;
    for (uint32_t c = 0; c < chunk_count; ++c)
        max_chunk = chunks[c].count > max_chunk ? chunks[c].count : max_chunk;
    if (multiview && max_chunk > POST_VIEWS)
        return mvr_gl_fail(r, MVR_ERROR_INTERNAL, "post pass: a chunk of %u views (at most %d)", max_chunk,
                           POST_VIEWS);
    r->stats.exposure_ev100 = ev[0];
    mvr_result res = mvr_full_screen_passes(r, t, source, chunks, chunk_count, multiview, post_features(t, d), post_mul, false,
                                        &r->stats.post_passes);
    r->stats.resolves += t->ss_color ? r->stats.post_passes : 0;
    return res;
}
