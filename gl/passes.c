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

#include "draw_list.h"
#include "environment.h"
#include "environment_gl.h"
#include "errors.h"
#include "frame_upload.h"
#include "passes.h"
#include "post.h"
#include "renderer.h"
#include "ring.h"
#include "shadows.h"
#include "skinning.h"
#include "targets.h"
#include "transmission.h"

/* Views per uniform block (MVR_MAX_VIEWS of shaders/views.glsl); the
 * block's layout is MVR_VIEWS_* of core/frame.h. */
#define VIEWS_PER_BLOCK MVR_VIEWS_PER_BLOCK
#define VIEW_BLOCK_SIZE MVR_VIEWS_BLOCK_SIZE
/* Exact sRGB encode (IEC 61966-2-1) for clear colors of UNORM targets. */
static float srgb_encode(float c)
{
    c = c < 0.0f ? 0.0f : c > 1.0f ? 1.0f : c;
    return c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
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
    mvr_frame_layout lay;
    mvr_pass_context pc;
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
    uint32_t stride = (uint32_t)mvr_align_up(MVR_DRAW_BLOCK_SIZE, (GLsizeiptr)r->ubo_alignment);
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
            return mvr_gl_fail(r, res, "frame: %s", why);
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
            return mvr_gl_fail(r, res, "culling: out of memory");
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
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "render: out of memory");
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
    mvr_pass_context *pc = &fx->pc;
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
    if (fx->plan->post || fx->plan->factor > 1) {
        /* an HDR or supersampled frame: the clear colour is a display
         * colour, which the final pass clears the output to and keeps where
         * the alpha stays 0 (no surface); the colour under it is what
         * transmission sees behind glass */
        mvr_target *t = fx->t;
        memcpy(t->post_clear, desc->clear_color, sizeof t->post_clear);
        for (int c = 0; c < 3 && t->internal_format == GL_RGBA8; ++c)
            t->post_clear[c] = srgb_encode(t->post_clear[c]);
        for (int c = 0; c < 3 && fx->plan->post; ++c)
            fx->clear[c] = (float)(fx->clear[c] * fx->pre_exposure);
        fx->clear[3] = 0.0f;
    }
    fx->clear_depth = r->reversed_z ? 0.0f : 1.0f;
    fx->view_block_stride = mvr_align_up(VIEW_BLOCK_SIZE, (GLsizeiptr)r->ubo_alignment);
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
    mvr_result res = mvr_frame_upload(r, fx->views, t, plan->chunks, plan->chunk_count, &fx->lay, fx->static_current);
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
    fx->msaa_fbo = t->msaa_fbo;
    if (res == MVR_OK && t->hdr_frame && msaa) /* (one view a pass) */
        res = mvr_target_msaa_hdr_framebuffer(t, ch->base, &fx->msaa_fbo);
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
    mvr_pass_context *pc = &fx->pc;
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
        bool diverged = mvr_blend_orders_diverge(r, pc);
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
    mvr_pass_context *pc = &fx->pc;
    pc->num_views = rec->multiview ? ch->count : 0;
    pc->first_view = ch->base;
    pc->views = ch->count;
    pc->view_base = (int32_t)(ch->base - block * VIEWS_PER_BLOCK);
    pc->compact = -1;
    pc->last_program = NULL;
    pc->outputs_only = true;
    mvr_target_draw_buffers(fx->t, MVR_DRAW_OUTPUTS);
    res = mvr_draw_list(pc, MVR_PASS_BLEND);
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
    mvr_pass_context *pc = &fx->pc;
    pc->num_views = 0;
    pc->first_view = rec->first_view;
    pc->views = 1;
    pc->view_base = (int32_t)(rec->first_view - fx->block * VIEWS_PER_BLOCK);
    pc->last_program = NULL; /* the loop variant of each program */
    res = mvr_draw_list(pc, MVR_PASS_BLEND);
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
        return mvr_draw_list(&fx->pc, MVR_PASS_OPAQUE);
    case MVR_PLAN_MASK:
        return mvr_draw_list(&fx->pc, MVR_PASS_MASK);
    case MVR_PLAN_BACKGROUND:
        return exec_background(fx);
    case MVR_PLAN_TRANSMISSION:
        return mvr_transmission_copy(fx->r, fx->t, fx->plan, rec, (int32_t)(fx->block * VIEWS_PER_BLOCK), fx->msaa_fbo,
                                     fx->draw_fbo);
    case MVR_PLAN_BLEND:
        return mvr_draw_list(&fx->pc, MVR_PASS_BLEND);
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
