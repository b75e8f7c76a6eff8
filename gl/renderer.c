/* mvr_renderer: create/destroy, the frame loop (mvr_renderer_render) and
 * its stats. Drawing is in passes.c, scene uploads in gpu_scene.c; programs,
 * the uniform ring, timers and readback have their own files. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "environment_gl.h"
#include "errors.h"
#include "gpu_scene.h"
#include "overrides.h"
#include "passes.h"
#include "post.h"
#include "program_cache.h"
#include "readback_async.h"
#include "renderer.h"
#include "ring.h"
#include "shadows.h"
#include "targets.h"
#include "timers.h"
#include "transmission.h"
#include "tuning.h"

/* The descriptor's enums and overrides, and the depth mode it asks for
 * (*clip_control: whether the GL can give reversed-Z). */
static mvr_result check_desc(const mvr_renderer_desc *desc, mvr_depth_mode *depth_mode, bool *clip_control,
                             mvr_error *error)
{
    if (!mvr_view_path_name(desc->view_path))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: view_path %d is not an mvr_view_path",
                             (int)desc->view_path);
    if (!mvr_transparency_order_name(desc->transparency_order))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: transparency_order %d is not an mvr_transparency_order",
                             (int)desc->transparency_order);
    if (!mvr_depth_mode_name(desc->depth_mode))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: depth_mode %d is not an mvr_depth_mode", (int)desc->depth_mode);
    const mvr_renderer_overrides *ov = &desc->overrides;
    mvr_result checked = mvr_overrides_check(ov, error);
    if (checked != MVR_OK)
        return checked;
    /* the override enums are the desc's enums + 1 (0 = none) */
    *depth_mode = ov->depth_mode ? (mvr_depth_mode)(ov->depth_mode - 1) : desc->depth_mode;
    *clip_control = desc->context->caps.ext.ext_clip_control && desc->context->gl.ClipControl;
    if (*depth_mode == MVR_DEPTH_MODE_REVERSED_Z && !*clip_control)
        return mvr_error_set(error, MVR_ERROR_UNSUPPORTED,
                             "mvr_renderer_create: depth_mode reversed_z needs GL_EXT_clip_control (or GL 4.5)");
    if ((unsigned)desc->tuning.mode > MVR_TUNING_OFF)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_create: tuning.mode %d is not an mvr_tuning",
                             (int)desc->tuning.mode);
    if (!mvr_skinning_path_name(desc->skinning_path))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: skinning_path %d is not an mvr_skinning_path",
                             (int)desc->skinning_path);
    if (!mvr_material_path_name(desc->material_path))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: material_path %d is not an mvr_material_path",
                             (int)desc->material_path);
    if (!mvr_oversized_image_name(desc->oversized_images))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: oversized_images %d is not an mvr_oversized_image",
                             (int)desc->oversized_images);
    return MVR_OK;
}

/* The settings of the descriptor and its overrides (the override enums
 * are the desc's enums + 1, 0 = none). */
static void apply_settings(mvr_renderer *r, const mvr_renderer_desc *desc)
{
    const mvr_renderer_overrides *ov = &desc->overrides;
    r->logger = desc->logger.fn ? desc->logger : desc->context->logger;
    r->requested_path = ov->view_path ? (mvr_view_path)(ov->view_path - 1) : desc->view_path;
    r->material_requested = ov->material_path ? (mvr_material_path)(ov->material_path - 1) : desc->material_path;
    r->skinning.requested = ov->skinning_path ? (mvr_skinning_path)(ov->skinning_path - 1) : desc->skinning_path;
    /* 2D texture arrays are core in GLES 3.0 and GL 3.0: auto's first guess
     * (and its choice without tuning) is arrays; each frame sets its own */
    r->material_path =
        r->material_requested == MVR_MATERIAL_PATH_AUTO ? MVR_MATERIAL_PATH_ARRAYS : r->material_requested;
    r->force_inert_features = ov->force_inert_features;
    r->frame.disabled_features = ov->disable_features;
    r->culling = ov->culling ? ov->culling == MVR_OVERRIDE_ON : !desc->disable_culling;
    r->tuning = ov->tuning ? ov->tuning == MVR_OVERRIDE_ON : desc->tuning.mode != MVR_TUNING_OFF;
    r->tuning_desc = desc->tuning;
    r->msaa_multiview_off = ov->msaa_multiview == MVR_OVERRIDE_OFF;
    r->anisotropic_on = ov->anisotropic == MVR_OVERRIDE_ON;
    r->blend_policy = desc->transparency_order;
    r->oversized_images = desc->oversized_images == MVR_OVERSIZED_IMAGE_DEFAULT ? MVR_OVERSIZED_IMAGE_DOWNSCALE
                                                                                : desc->oversized_images;
    /* the image formats this GL samples (caps), less the override's */
    r->sampleable_formats = 1u << MVR_IMAGE_FORMAT_RGBA8;
    if (desc->context->caps.ext.etc2)
        for (int f = MVR_IMAGE_FORMAT_ETC2_RGB8; f <= MVR_IMAGE_FORMAT_EAC_RG11; ++f)
            r->sampleable_formats |= 1u << f;
    if (desc->context->caps.ext.astc_ldr)
        for (int f = MVR_IMAGE_FORMAT_ASTC_4x4; f <= MVR_IMAGE_FORMAT_ASTC_12x12; ++f)
            r->sampleable_formats |= 1u << f;
    r->sampleable_formats &= ~(ov->disable_image_formats & ~(1u << MVR_IMAGE_FORMAT_RGBA8));
}

mvr_result mvr_renderer_create(const mvr_renderer_desc *desc, mvr_renderer **out, mvr_error *error)
{
    if (!out || !desc)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_create: NULL argument");
    *out = NULL;
    if (!desc->context)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_create: no context");
    mvr_depth_mode depth_mode = MVR_DEPTH_MODE_AUTO;
    bool clip_control = false;
    mvr_result checked = check_desc(desc, &depth_mode, &clip_control, error);
    if (checked != MVR_OK)
        return checked;
    if (mvr_context_begin(desc->context, "mvr_renderer_create") != MVR_OK)
        return mvr_error_set(error, MVR_ERROR_CONTEXT, "%s", mvr_context_last_error(desc->context));
    mvr_renderer *r = calloc(1, sizeof *r);
    if (!r)
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_renderer_create: out of memory");
    r->ctx = desc->context;
    r->gl = &desc->context->gl;
    apply_settings(r, desc);
    /* linked first: every failure below goes through mvr_renderer_destroy */
    r->next_in_context = r->ctx->renderers;
    r->ctx->renderers = r;
    const mvr_caps *c = &r->ctx->caps;
    const mvr_renderer_overrides *ov = &desc->overrides;
    r->reversed_z = depth_mode == MVR_DEPTH_MODE_AUTO ? clip_control : depth_mode == MVR_DEPTH_MODE_REVERSED_Z;
    r->ubo_alignment = (uint32_t)(c->limits.uniform_buffer_offset_alignment > 0
                                      ? c->limits.uniform_buffer_offset_alignment : 256);
    /* overrides.ubo_alignment (a power of two above the GL's): lays uniform
     * data out as a GL with that alignment needs (tests of the padded
     * layouts desktop GPUs use, on a GL that needs less) */
    if (ov->ubo_alignment > r->ubo_alignment)
        r->ubo_alignment = ov->ubo_alignment;
    uint32_t cap = (uint32_t)c->limits.max_uniform_block_size / MVR_MATERIAL_BLOCK_SIZE;
    r->material_capacity = cap > MVR_SHADER_MAX_MATERIAL_CAPACITY ? MVR_SHADER_MAX_MATERIAL_CAPACITY : cap;
    if (r->material_capacity == 0) {
        int max_block = c->limits.max_uniform_block_size;
        mvr_renderer_destroy(r);
        return mvr_error_set(error, MVR_ERROR_UNSUPPORTED,
                             "mvr_renderer_create: GL_MAX_UNIFORM_BLOCK_SIZE %d holds no material", max_block);
    }
    if (desc->program_cache_dir && desc->program_cache_dir[0]) {
        size_t n = strlen(desc->program_cache_dir);
        r->program_cache_dir = malloc(n + 1);
        if (!r->program_cache_dir) {
            mvr_renderer_destroy(r);
            return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_renderer_create: out of memory");
        }
        memcpy(r->program_cache_dir, desc->program_cache_dir, n + 1);
    }
    /* auto's settled choices are remembered beside the program binaries (gl/tuning.c) */
    r->tuning_memory.enabled = r->program_cache_dir && r->tuning;
    /* instancing: the draw block becomes an array indexed by gl_InstanceID
     * whose std140 stride is the ring's block stride (144 bytes, padded up
     * to the uniform offset alignment: 256 on many desktop GPUs), and whose
     * size fits the GL's uniform block limit */
    r->draw_stride = (uint32_t)((MVR_DRAW_BLOCK_SIZE + r->ubo_alignment - 1) / r->ubo_alignment * r->ubo_alignment);
    bool instancing = (ov->instancing ? ov->instancing == MVR_OVERRIDE_ON : !desc->disable_instancing) &&
                      r->material_path != MVR_MATERIAL_PATH_PER_DRAW && r->draw_stride % 16 == 0 &&
                      r->draw_stride <= 4096;
    uint32_t draw_cap = (uint32_t)c->limits.max_uniform_block_size / r->draw_stride;
    if (draw_cap > MVR_SHADER_MAX_DRAW_CAPACITY)
        draw_cap = MVR_SHADER_MAX_DRAW_CAPACITY;
    r->draw_capacity = instancing && draw_cap > 1 ? draw_cap : 1;
    mvr_state_init(&r->state, r->gl, false);
    mvr_timer_init(r);
    mvr_result res = mvr_gl_call_end(r, "mvr_renderer_create", MVR_OK);
    if (res != MVR_OK) {
        mvr_error_set(error, res, "%s", r->last_error);
        mvr_renderer_destroy(r);
        return res;
    }
    *out = r;
    return MVR_OK;
}

/* Every GL object of the renderer and of its targets, through
 * mvr_gl_delete (now, later, or never once the context is gone); the
 * targets are detached. Memory stays: a later destroy frees it. */
static void release_gl(mvr_renderer *r)
{
    while (r->targets) {
        mvr_target *t = r->targets;
        mvr_target_release_gl(t);
        r->targets = t->next;
        t->next = NULL;
        t->renderer = NULL;
    }
    mvr_readbacks_release(r);
    mvr_shadows_release(r);
    mvr_transmission_release(r);
    mvr_environment_release(r);
    mvr_gl_delete(r, MVR_GL_SAMPLER, &r->nearest_sampler);
    mvr_gpu_scene_release(r);
    mvr_program_cache_release(r);
    mvr_ring_release(r);
    mvr_timer_release(r);
    mvr_gl_delete(r, MVR_GL_VERTEX_ARRAY, &r->empty_vao);
    r->frame_key.valid = false;
}

static void unlink_from_context(mvr_renderer *r)
{
    if (!r->ctx)
        return;
    for (mvr_renderer **p = &r->ctx->renderers; *p; p = &(*p)->next_in_context)
        if (*p == r) {
            *p = r->next_in_context;
            break;
        }
    r->next_in_context = NULL;
}

void mvr_renderer_context_destroyed(mvr_renderer *r)
{
    release_gl(r);
    unlink_from_context(r);
    r->ctx = NULL;
    r->gl = NULL;
}

void mvr_renderer_destroy(mvr_renderer *r)
{
    if (!r)
        return;
    release_gl(r);
    unlink_from_context(r);
    mvr_program_cache_free(r);
    mvr_frame_free(&r->frame);
    mvr_visibility_free(&r->vis);
    free(r->program_cache_dir);
    free(r->compact_scratch);
    free(r->blend_order);
    mvr_frame_plan_free(&r->plan);
    free(r->chunk_compact);
    free(r->groups_used);
    free(r);
}

static double thread_cpu_ms(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static bool multiview_usable(const mvr_renderer *r)
{
    const mvr_caps *c = &r->ctx->caps;
    return c->ext.ovr_multiview2 && c->limits.max_views_ovr >= 1 &&
           r->gl->FramebufferTextureMultiviewOVR != NULL;
}

static bool t_level_ok(const mvr_renderer *r, const mvr_target *t)
{
    return t->desc.external_level == 0 || !r->ctx->caps.bugs.multiview_level_zero_only;
}

/* auto: multiview where it works, except where a multiview pass starts
 * rasterizing only at its end (llvmpipe). There a loop pass per view lets
 * the rasterizer threads work on view k while the submitting thread sends
 * view k + 1, and measured wall time per frame (tests/bench/run_bench_auto.sh,
 * docs/benchmarks.md) never favours multiview by more than noise (< 1%),
 * while the loop wins by up to 27% (city, 256x256, 6 views). The loop costs
 * the submitting thread more instructions (36% more at 6 views on city): an
 * application that counts CPU time rather than frame time forces multiview. */
static mvr_view_path auto_view_path(const mvr_renderer *r, bool level_ok)
{
    if (!multiview_usable(r) || !level_ok)
        return MVR_VIEW_PATH_LOOP;
    if (r->ctx->caps.bugs.multiview_pass_defers_raster)
        return MVR_VIEW_PATH_LOOP;
    return MVR_VIEW_PATH_MULTIVIEW;
}

/* The render descriptor (NULL: the defaults) into *d, its exposure
 * defaulted; fails naming what is out of range. */
static mvr_result check_render_desc(mvr_renderer *r, const mvr_render_desc *desc, mvr_render_desc *d)
{
    if (desc)
        *d = *desc;
    else
        memset(d, 0, sizeof *d);
    if ((unsigned)d->tone_map > MVR_TONE_MAP_KHR_PBR_NEUTRAL)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_render: unknown tone map %d",
                           (int)d->tone_map);
    if (d->exposure == 0.0f)
        d->exposure = 1.0f;
    if (!mvr_exposure_mode_name(d->exposure_mode) || !(d->exposure > 0.0f) || !isfinite(d->exposure) ||
        !isfinite(d->ev100) || !(d->aperture >= 0.0) || !(d->shutter >= 0.0) || !(d->iso >= 0.0) ||
        !isfinite(d->exposure_compensation) || !(d->exposure_key >= 0.0f) || !isfinite(d->ev100_min) ||
        !isfinite(d->ev100_max) || d->ev100_min > d->ev100_max)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_renderer_render: exposure: mode %d, exposure %g, ev100 %g, camera f/%g %gs ISO %g, "
                           "key %g, clamps %g..%g (finite, >= 0, min <= max)",
                           (int)d->exposure_mode, (double)d->exposure, d->ev100, d->aperture, d->shutter, d->iso,
                           (double)d->exposure_key, (double)d->ev100_min, (double)d->ev100_max);
    const mvr_shadow_desc *sd = &d->shadows;
    if ((unsigned)sd->mode > MVR_SHADOWS_OFF || sd->cascades > MVR_SHADOW_MAX_CASCADES ||
        sd->map_size > 16384 || !(sd->distance >= 0.0) || !(sd->slope_bias >= 0.0f) ||
        !(sd->constant_bias >= 0.0f) || !(sd->normal_bias >= 0.0f))
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_renderer_render: shadows: mode %d, cascades %u (at most %d), map size %u "
                           "(at most 16384), distance and biases >= 0 and finite",
                           (int)sd->mode, sd->cascades, MVR_SHADOW_MAX_CASCADES, sd->map_size);

    if (!mvr_background_name(d->background) || !(d->background_blur >= 0.0f && d->background_blur <= 1.0f) ||
        d->environment_samples > 65536u)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_renderer_render: background %d with blur %g (a roughness, 0..1), "
                           "environment samples %u (at most 65536)",
                           (int)d->background, (double)d->background_blur, d->environment_samples);
    if (d->background != MVR_BACKGROUND_COLOR && !d->environment)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_renderer_render: background '%s' needs an environment (render desc "
                           "environment is NULL)",
                           mvr_background_name(d->background));
    return MVR_OK;
}

/* A new frame: the GL state cache forgotten, the counters and stats zeroed. */
static void begin_frame(mvr_renderer *r)
{
    /* the application or another renderer may have changed GL state since */
    mvr_state_invalidate(&r->state);
    memset(&r->state.counters, 0, sizeof r->state.counters);
    r->compiled_this_frame = r->cache_hits_this_frame = 0;
    r->binary_loads_this_frame = r->binary_rejects_this_frame = 0;
    r->upload_bytes = r->view_upload_bytes = 0;
    r->frame_serial++;
    memset(&r->stats, 0, sizeof r->stats);
    r->path_ran = MVR_VIEW_PATH_AUTO;
    r->stats.gpu_ms = -1.0;
    r->pass_stats_count = 0;
}

/* The frame's stats from the renderer's counters and the target. */
static void end_frame_stats(mvr_renderer *r, const mvr_scene *scene, const mvr_target *target, mvr_view_path path)
{
    mvr_frame_stats *st = &r->stats;
    st->view_path = r->path_ran ? r->path_ran : path;
    st->transparency_order = r->blend_policy;
    st->program_binds = r->state.counters.program_binds;
    st->texture_binds = r->state.counters.texture_binds;
    st->ubo_range_binds = r->state.counters.ubo_range_binds;
    st->upload_bytes = r->upload_bytes;
    st->view_upload_bytes = r->view_upload_bytes;
    st->programs_compiled = r->compiled_this_frame;
    st->program_cache_hits = r->cache_hits_this_frame;
    st->program_binary_loads = r->binary_loads_this_frame;
    st->program_binary_rejects = r->binary_rejects_this_frame;
    st->sanitized = mvr_scene_sanitized_count(scene);
    st->samples = target->desc.samples > 1 ? target->desc.samples : 1;
    st->supersample = mvr_target_factor(target);
    st->depth_mode = r->reversed_z ? MVR_DEPTH_MODE_REVERSED_Z : MVR_DEPTH_MODE_STANDARD;
    st->material_path = r->material_path;
    st->texture_groups = r->gpu.arrays ? r->gpu.plan.group_count : 0;
    st->images_downscaled = r->gpu.downscaled_count;
    st->images_compressed = r->gpu.compressed_count;
    st->images_unsampleable = r->gpu.unsampleable_count;
}

mvr_result mvr_renderer_render(mvr_renderer *r, mvr_scene *scene, const mvr_view_set *views,
                               mvr_target *target, const mvr_render_desc *desc)
{
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (!scene || !views || !target)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_render: NULL scene, views or target");
    if (target->renderer != r)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           target->renderer ? "mvr_renderer_render: the target belongs to another renderer"
                                            : "mvr_renderer_render: the target was released with its renderer "
                                              "or context");
    if (!r->ctx)
        return mvr_gl_fail(r, MVR_ERROR_CONTEXT, "mvr_renderer_render: the renderer's context was destroyed");
    uint32_t layers = target->desc.layers;
    if (views->count > layers)
        return mvr_gl_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                           "mvr_renderer_render: %u views but the target has %u layers",
                           views->count, layers);
    mvr_render_desc d;
    mvr_result res = check_render_desc(r, desc, &d);
    if (res != MVR_OK)
        return res;

    /* multiview where it works for this target: a mip level other than 0
     * cannot be attached with multiview on some drivers (bugs struct) */
    bool level_ok = t_level_ok(r, target);
    mvr_view_path path = r->requested_path;
    /* auto: the caps rule's choice is the prior the tuner measures around
     * (below, with the GL: it may wait for the last frame's timer) */
    bool tune = path == MVR_VIEW_PATH_AUTO;
    mvr_view_path prior = tune ? auto_view_path(r, level_ok) : path;
    if (tune)
        path = prior;
    if (path == MVR_VIEW_PATH_MULTIVIEW && !multiview_usable(r))
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED,
                           "mvr_renderer_render: the multiview path was forced but %s has no "
                           "usable GL_OVR_multiview2",
                           r->ctx->caps.renderer);
    if (path == MVR_VIEW_PATH_MULTIVIEW && !level_ok)
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED,
                           "mvr_renderer_render: the multiview path was forced but %s attaches "
                           "only mip level 0 with multiview (the target is level %u)",
                           r->ctx->caps.renderer, target->desc.external_level);

    /* the last check: nothing above touched GL or the renderer's state */
    res = mvr_gl_call_begin(r, "mvr_renderer_render");
    if (res != MVR_OK)
        return res;
    /* tuned only where both paths can draw this frame (MSAA may rule
     * multiview out; transmission as the last frame had it) */
    bool drawable = mvr_frame_plan_multiview_drawable(target->desc.samples, mvr_post_needed(&d), target->msaa_multiview,
                                                      r->frame.transmissive_draws != 0);
    path = mvr_tuning_choose(r, scene, views, target, path, tune && multiview_usable(r) && level_ok && drawable);
    double cpu_start = thread_cpu_ms();
    begin_frame(r);

    mvr_timer_start(r);
    uint32_t failures = r->failures;
    res = mvr_gpu_scene_sync(r, scene, r->material_tuner.phase == MVR_TUNER_TUNING);
    /* the frame plan prefilters a new environment (mvr_environment_sync) first */
    if (res == MVR_OK)
        res = mvr_renderer_draw_frame(r, scene, views, target, &d, path);
    mvr_timer_stop(r, res == MVR_OK);
    res = mvr_gl_call_end(r, "mvr_renderer_render", res);
    if (res != MVR_OK && r->failures == failures) /* failed where only the context kept the message */
        mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));

    end_frame_stats(r, scene, target, path);
    r->stats.cpu_ms = thread_cpu_ms() - cpu_start;
    mvr_tuning_end_frame(r, prior, res == MVR_OK);
    return res;
}

void mvr_renderer_get_stats(mvr_renderer *r, mvr_frame_stats *out)
{
    if (!r || !out)
        return;
    /* the timer result is read only with the renderer's context current (else kept for later) */
    if (r->timer.pending && r->ctx && mvr_context_is_current(r->ctx) &&
        mvr_context_begin(r->ctx, "mvr_renderer_get_stats") == MVR_OK) {
        mvr_timer_read(r);
        /* a void call: an error of its own is logged, not left for the next call to blame on the application */
        mvr_gl_check(r->ctx, "mvr_renderer_get_stats", true);
    }
    *out = r->stats;
}

uint32_t mvr_renderer_view_culled(const mvr_renderer *r, uint32_t view)
{
    if (!r || !r->culling || view >= r->vis.views)
        return 0;
    return r->vis.culled[view];
}

bool mvr_renderer_get_pass_stats(const mvr_renderer *r, uint32_t index, mvr_pass_stats *out)
{
    if (!r || !out || index >= r->pass_stats_count)
        return false;
    *out = r->pass_stats[index];
    return true;
}

size_t mvr_renderer_format_plan(const mvr_renderer *r, char *buf, size_t size)
{
    if (!r) {
        if (buf && size)
            buf[0] = '\0';
        return 0;
    }
    if (r->plan.count == 0) { /* no render planned yet */
        static const char none[] = "frame plan: none (no render yet)\n";
        if (buf && size)
            snprintf(buf, size, "%s", none);
        return sizeof none - 1;
    }
    return mvr_frame_plan_format(&r->plan, buf, size);
}

mvr_result mvr_renderer_finish(mvr_renderer *r)
{
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    mvr_result res = mvr_gl_call_begin(r, "mvr_renderer_finish");
    if (res != MVR_OK)
        return res;
    r->gl->Finish();
    return mvr_gl_call_end(r, "mvr_renderer_finish", MVR_OK);
}

