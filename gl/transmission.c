/*
 * KHR_materials_transmission across views: after a chunk's opaque, masked
 * and background sub-passes, each of its views' colour is copied into its
 * own layer of a mip-mapped 2D array (layer = view - the chunk's first
 * view), and the transmissive draws of the blend sub-pass sample their
 * view's layer (gl_ViewID_OVR on the multiview path, 0 on the loop path's
 * one-view chunks), at a level that grows with roughness: the Khronos glTF
 * Sample Renderer's transmission framebuffer, one per view. Loop and
 * multiview copy and filter each view alone, so they give the same bytes.
 * Nothing of it exists in a frame without transmissive draws.
 */
#include <math.h>

#include "errors.h"
#include "program.h"
#include "program_cache.h"
#include "renderer.h"
#include "targets.h"
#include "transmission.h"

/* The format views are drawn in, and the copy's: the same (a multisampled
 * source resolves only into its own format), except RGBA32F, which ES 3.0
 * cannot filter: half floats hold a blurred background well. */
static GLenum copy_format(const mvr_target *t, uint32_t factor, bool msaa, bool *ok)
{
    GLenum f = t->hdr_frame ? GL_RGBA16F : factor > 1 ? t->ss_format : t->internal_format;
    *ok = true;
    if (f == GL_RGBA32F) {
        *ok = !msaa;
        f = GL_RGBA16F;
    }
    return f;
}

static mvr_result ensure_array(mvr_renderer *r, GLenum format, uint32_t w, uint32_t h, uint32_t layers)
{
    mvr_transmission *tr = &r->transmission;
    if (tr->texture && tr->format == format && tr->width == w && tr->height == h && tr->layers >= layers)
        return MVR_OK;
    const mvr_gl_api_table *gl = r->gl;
    mvr_gl_delete(r, MVR_GL_TEXTURE, &tr->texture);
    uint32_t levels = mvr_mip_levels(w, h);
    gl->GenTextures(1, &tr->texture);
    mvr_state_texture(&r->state, MVR_UNIT_TRANSMISSION, GL_TEXTURE_2D_ARRAY, tr->texture);
    gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, (GLsizei)levels, format, (GLsizei)w, (GLsizei)h, (GLsizei)layers);
    mvr_result res = mvr_gl_check_alloc(r, "transmission array (%ux%u, %u layers, %u levels)", w, h, layers,
                                        levels);
    if (res != MVR_OK) {
        mvr_gl_delete(r, MVR_GL_TEXTURE, &tr->texture);
        return res;
    }
    tr->format = format;
    tr->width = w;
    tr->height = h;
    tr->layers = layers;
    if (!tr->fbo)
        gl->GenFramebuffers(1, &tr->fbo);
    if (!tr->sampler) {
        gl->GenSamplers(1, &tr->sampler);
        gl->SamplerParameteri(tr->sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl->SamplerParameteri(tr->sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl->SamplerParameteri(tr->sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->SamplerParameteri(tr->sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    return MVR_OK;
}

mvr_result mvr_transmission_copy(mvr_renderer *r, mvr_target *t, const mvr_frame_plan *plan,
                                 const mvr_plan_record *rec, int32_t block_base, GLuint loop_msaa_fbo,
                                 GLuint resume_fbo)
{
    const mvr_view_chunk *ch = &plan->chunks[rec->chunk];
    const mvr_gl_api_table *gl = r->gl;
    mvr_state_cache *st = &r->state;
    bool mv_msaa = plan->msaa && rec->multiview;
    bool ok;
    GLenum format = copy_format(t, plan->factor, plan->msaa, &ok);
    if (!ok)
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED,
                           "transmission: a multisampled RGBA32F target cannot be resolved into a filterable "
                           "copy (use RGBA16F or no MSAA)");
    uint32_t w = t->desc.width * plan->factor, h = t->desc.height * plan->factor;
    /* layers for the frame's largest chunk (one on the loop path) */
    uint32_t layers = 1;
    for (uint32_t c = 0; c < plan->chunk_count; ++c)
        layers = plan->chunks[c].count > layers ? plan->chunks[c].count : layers;
    mvr_result res = ensure_array(r, format, w, h, layers);
    if (res != MVR_OK)
        return res;
    mvr_transmission *tr = &r->transmission;
    GLint x0 = ch->viewport.x * (GLint)plan->factor, y0 = ch->viewport.y * (GLint)plan->factor;
    GLint x1 = x0 + (GLint)(ch->viewport.width * plan->factor), y1 = y0 + (GLint)(ch->viewport.height * plan->factor);
    mvr_state_scissor_test(st, false);
    for (uint32_t k = 0; k < ch->count; ++k) {
        /* one layer at a time: never read from a multiview framebuffer */
        GLuint read_fbo = loop_msaa_fbo;
        if (mv_msaa)
            res = mvr_target_msaa_framebuffer(t, ch->base + k, 0, &read_fbo);
        else if (!plan->msaa)
            res = mvr_target_framebuffer(t, ch->base + k, 0, &read_fbo);
        if (res != MVR_OK)
            return res;
        mvr_state_read_framebuffer(st, read_fbo);
        mvr_state_draw_framebuffer(st, tr->fbo);
        gl->FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, tr->texture, 0, (GLint)k);
        gl->BlitFramebuffer(x0, y0, x1, y1, x0, y0, x1, y1, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    mvr_state_texture(st, MVR_UNIT_TRANSMISSION, GL_TEXTURE_2D_ARRAY, tr->texture);
    mvr_state_sampler(st, MVR_UNIT_TRANSMISSION, tr->sampler);
    /* the levels roughness reads; the whole array (layers past the chunk's
     * are not read) */
    gl->GenerateMipmap(GL_TEXTURE_2D_ARRAY);
    mvr_state_draw_framebuffer(st, resume_fbo);
    tr->rect[0] = (float)x0 / (float)w;
    tr->rect[1] = (float)y0 / (float)h;
    tr->rect[2] = (float)(x1 - x0) / (float)w;
    tr->rect[3] = (float)(y1 - y0) / (float)h;
    tr->lod = log2f((float)(x1 - x0));
    tr->base = (int32_t)(ch->base) - block_base;
    tr->serial++;
    r->stats.transmission_copies += ch->count;
    /* the array with its mips (a third more), every frame it is used */
    r->stats.transmission_bytes =
        (uint64_t)tr->width * tr->height * tr->layers * (tr->format == GL_RGBA16F ? 8u : 4u) * 4u / 3u;
    return MVR_OK;
}

void mvr_transmission_set_uniforms(mvr_renderer *r, mvr_program_entry *e)
{
    const mvr_transmission *tr = &r->transmission;
    if (!(e->variant.features & MVR_FEATURE_TRANSMISSION) || e->transmission_serial == tr->serial)
        return;
    const mvr_gl_api_table *gl = r->gl;
    gl->Uniform1i(e->loc_transmission_base, tr->base);
    gl->Uniform4fv(e->loc_transmission_rect, 1, tr->rect);
    gl->Uniform1f(e->loc_transmission_lod, tr->lod);
    e->transmission_serial = tr->serial;
}

void mvr_transmission_release(mvr_renderer *r)
{
    mvr_transmission *tr = &r->transmission;
    mvr_gl_delete(r, MVR_GL_TEXTURE, &tr->texture);
    mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &tr->fbo);
    mvr_gl_delete(r, MVR_GL_SAMPLER, &tr->sampler);
    tr->width = tr->height = tr->layers = 0;
}
