/* mvr_renderer: create/destroy, programs, the uniform ring, timers, stats,
 * readback. Drawing is in passes.c, scene uploads in gpu_scene.c. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "renderer_internal.h"

const char *mvr_view_path_name(mvr_view_path path)
{
    switch (path) {
    case MVR_VIEW_PATH_AUTO: return "auto";
    case MVR_VIEW_PATH_MULTIVIEW: return "multiview";
    case MVR_VIEW_PATH_LOOP: return "loop";
    }
    return NULL;
}

const char *mvr_material_path_name(mvr_material_path path)
{
    switch (path) {
    case MVR_MATERIAL_PATH_AUTO: return "auto";
    case MVR_MATERIAL_PATH_ARRAYS: return "arrays";
    case MVR_MATERIAL_PATH_PER_MATERIAL: return "per_material";
    case MVR_MATERIAL_PATH_PER_DRAW: return "per_draw";
    }
    return NULL;
}

const char *mvr_transparency_order_name(mvr_transparency_order order)
{
    switch (order) {
    case MVR_TRANSPARENCY_ORDER_AUTO: return "auto";
    case MVR_TRANSPARENCY_ORDER_CENTROID: return "centroid";
    case MVR_TRANSPARENCY_ORDER_PER_VIEW: return "per_view";
    }
    return NULL;
}

const char *mvr_depth_mode_name(mvr_depth_mode mode)
{
    switch (mode) {
    case MVR_DEPTH_MODE_AUTO: return "auto";
    case MVR_DEPTH_MODE_REVERSED_Z: return "reversed_z";
    case MVR_DEPTH_MODE_STANDARD: return "standard";
    }
    return NULL;
}


const char *mvr_color_format_name(mvr_color_format format)
{
    switch (format) {
    case MVR_COLOR_FORMAT_DEFAULT: return "srgb8_alpha8";
    case MVR_COLOR_FORMAT_RGBA8: return "rgba8";
    case MVR_COLOR_FORMAT_RGBA16F: return "rgba16f";
    case MVR_COLOR_FORMAT_RGBA32F: return "rgba32f";
    }
    return NULL;
}

mvr_result mvr_renderer_fail(mvr_renderer *r, mvr_result result, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    mvr_error_record(r->last_error, sizeof r->last_error, &r->logger, result, fmt, ap);
    va_end(ap);
    r->failures++;
    return result;
}

const char *mvr_renderer_last_error(const mvr_renderer *r)
{
    return r ? r->last_error : "mvr_renderer_last_error: renderer is NULL";
}

const char *mvr_oversized_image_name(mvr_oversized_image policy)
{
    switch (policy) {
    case MVR_OVERSIZED_IMAGE_DEFAULT: return "default";
    case MVR_OVERSIZED_IMAGE_DOWNSCALE: return "downscale";
    case MVR_OVERSIZED_IMAGE_REFUSE: return "refuse";
    }
    return NULL;
}

mvr_result mvr_renderer_begin(mvr_renderer *r, const char *where)
{
    if (!r->ctx)
        return mvr_renderer_fail(r, MVR_ERROR_CONTEXT, "%s: the renderer's context was destroyed", where);
    mvr_result res = mvr_context_begin(r->ctx, where);
    if (res != MVR_OK)
        return mvr_renderer_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    return MVR_OK;
}

mvr_result mvr_renderer_end(mvr_renderer *r, const char *where, mvr_result res)
{
    /* always drained, so a failed call leaves no error behind either */
    mvr_result checked = mvr_gl_check(r->ctx, where, true);
    if (res == MVR_OK && checked != MVR_OK)
        res = mvr_renderer_fail(r, checked, "%s", mvr_context_last_error(r->ctx));
    return res;
}

mvr_result mvr_renderer_check_alloc(mvr_renderer *r, const char *fmt, ...)
{
    char what[256];
    va_list ap;
    va_start(ap, fmt);
    mvr_str_vformat(what, sizeof what, fmt, ap);
    va_end(ap);
    mvr_result res = mvr_gl_check(r->ctx, what, true);
    if (res != MVR_OK)
        return mvr_renderer_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    return MVR_OK;
}

void mvr_renderer_delete(mvr_renderer *r, mvr_gl_object kind, GLuint *name)
{
    if (!*name)
        return;
    switch (kind) {
    case MVR_GL_TEXTURE: mvr_state_forget_texture(&r->state, *name); break;
    case MVR_GL_BUFFER: mvr_state_forget_buffer(&r->state, *name); break;
    case MVR_GL_FRAMEBUFFER: mvr_state_forget_framebuffer(&r->state, *name); break;
    case MVR_GL_VERTEX_ARRAY: mvr_state_forget_vao(&r->state, *name); break;
    case MVR_GL_PROGRAM: mvr_state_forget_program(&r->state, *name); break;
    case MVR_GL_RENDERBUFFER:
    case MVR_GL_SAMPLER:
    case MVR_GL_QUERY:
    case MVR_GL_SYNC:
        break;
    }
    if (r->ctx)
        mvr_context_delete(r->ctx, kind, *name);
    *name = 0;
}

/* value among choices: *out = its index + 1 (the override enums' order);
 * else the failure, naming the variable and what it takes */
static mvr_result parse_choice(const char *name, const char *value, const char *const *choices, int count, int *out,
                               mvr_error *error)
{
    char list[128] = "";
    for (int k = 0; k < count; ++k) {
        if (strcmp(value, choices[k]) == 0) {
            *out = k + 1;
            return MVR_OK;
        }
        size_t used = strlen(list);
        snprintf(list + used, sizeof list - used, "%s%s", k == 0 ? "" : k == count - 1 ? " or " : ", ", choices[k]);
    }
    return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "%s=%s is not %s", name, value, list);
}

static bool valid_ubo_alignment(unsigned long a)
{
    return a >= 1 && a <= 4096 && (a & (a - 1)) == 0;
}

/* The mesh feature bits an override may take out: material extensions,
 * whose absence is a valid (if different) look, never what a draw needs. */
#define DISABLEABLE_FEATURES                                                                                \
    (MVR_FEATURE_SPECULAR | MVR_FEATURE_CLEARCOAT | MVR_FEATURE_TRANSMISSION | MVR_FEATURE_SHEEN |              \
     MVR_FEATURE_IRIDESCENCE | MVR_FEATURE_ANISOTROPY)

/* "SPECULAR,CLEARCOAT" -> feature bits; names as mvr_program_feature_name. */
static mvr_result parse_feature_list(const char *var, const char *value, uint32_t *out, mvr_error *error)
{
    *out = 0;
    const char *p = value;
    for (;;) {
        size_t n = strcspn(p, ",");
        uint32_t bit = 0;
        for (uint32_t b = 1; b && !bit; b <<= 1) {
            const char *name = (b & DISABLEABLE_FEATURES) ? mvr_program_feature_name(b) : NULL;
            if (name && strlen(name) == n && strncmp(name, p, n) == 0)
                bit = b;
        }
        if (!bit)
            return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                                 "%s=%s: '%.*s' is not a feature that can be disabled (SPECULAR, CLEARCOAT, "
                                 "TRANSMISSION, SHEEN, IRIDESCENCE, ANISOTROPY)",
                                 var,
                                 value, (int)n, p);
        *out |= bit;
        p += n;
        if (*p != ',')
            return MVR_OK;
        ++p; /* a name must follow: "CLEARCOAT," is refused as '' */
    }
}

mvr_result mvr_renderer_overrides_from_env(mvr_renderer_overrides *out, mvr_error *error)
{
    if (!out)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_overrides_from_env: out is NULL");
    memset(out, 0, sizeof *out);
    /* the choices in the order of the override enums (after their NONE) */
    static const char *const view_paths[] = {"auto", "multiview", "loop"};
    static const char *const material_paths[] = {"auto", "arrays", "per_material", "per_draw"};
    static const char *const depth_modes[] = {"auto", "reversed_z", "standard"};
    static const char *const switches[] = {"off", "on"};
    static const char *const features[] = {"inert"};
    static const char *const skinning_paths[] = {"auto", "vertex", "preskin"};
    enum { VIEW_PATH, MATERIAL_PATH, DEPTH, CULLING, INSTANCING, MSAA_MULTIVIEW, FORCE_FEATURES, UBO_ALIGNMENT,
           SKINNING_PATH, DISABLE_FEATURES, TUNING, COUNT };
    static const char *const names[COUNT] = {"MVR_VIEW_PATH",      "MVR_MATERIAL_PATH", "MVR_DEPTH",
                                             "MVR_CULLING",        "MVR_INSTANCING",    "MVR_MSAA_MULTIVIEW",
                                             "MVR_FORCE_FEATURES", "MVR_UBO_ALIGNMENT", "MVR_SKINNING_PATH",
                                             "MVR_DISABLE_FEATURES", "MVR_TUNING"};
    mvr_renderer_overrides o;
    memset(&o, 0, sizeof o);
    for (int v = 0; v < COUNT; ++v) {
        const char *value = getenv(names[v]);
        if (!value || !*value)
            continue;
        int k = 0;
        mvr_result res = MVR_OK;
        switch (v) {
        case VIEW_PATH:
            res = parse_choice(names[v], value, view_paths, 3, &k, error);
            o.view_path = (mvr_view_path_override)k;
            break;
        case MATERIAL_PATH:
            res = parse_choice(names[v], value, material_paths, 4, &k, error);
            o.material_path = (mvr_material_path_override)k;
            break;
        case DEPTH:
            res = parse_choice(names[v], value, depth_modes, 3, &k, error);
            o.depth_mode = (mvr_depth_mode_override)k;
            break;
        case CULLING:
        case INSTANCING:
        case MSAA_MULTIVIEW:
        case TUNING:
            res = parse_choice(names[v], value, switches, 2, &k, error);
            *(v == CULLING      ? &o.culling
              : v == INSTANCING ? &o.instancing
              : v == TUNING     ? &o.tuning
                                : &o.msaa_multiview) = (mvr_override_switch)k;
            break;
        case SKINNING_PATH:
            res = parse_choice(names[v], value, skinning_paths, 3, &k, error);
            o.skinning_path = (mvr_skinning_path_override)k;
            break;
        case DISABLE_FEATURES:
            res = parse_feature_list(names[v], value, &o.disable_features, error);
            break;
        case FORCE_FEATURES:
            res = parse_choice(names[v], value, features, 1, &k, error);
            o.force_inert_features = k == 1;
            break;
        case UBO_ALIGNMENT: {
            char *end = NULL;
            unsigned long a = strtoul(value, &end, 10);
            if (value[0] < '0' || value[0] > '9' || *end || !valid_ubo_alignment(a))
                res = mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                                    "%s=%s is not a power of two from 1 to 4096", names[v], value);
            o.ubo_alignment = (uint32_t)a;
            break;
        }
        }
        if (res != MVR_OK)
            return res;
    }
    *out = o;
    return MVR_OK;
}

/* Every override field a value its type has. */
static mvr_result check_overrides(const mvr_renderer_overrides *o, mvr_error *error)
{
    const char *field = NULL;
    int value = 0;
    if ((unsigned)o->view_path > MVR_VIEW_PATH_OVERRIDE_LOOP)
        field = "view_path", value = (int)o->view_path;
    else if ((unsigned)o->material_path > MVR_MATERIAL_PATH_OVERRIDE_PER_DRAW)
        field = "material_path", value = (int)o->material_path;
    else if ((unsigned)o->depth_mode > MVR_DEPTH_MODE_OVERRIDE_STANDARD)
        field = "depth_mode", value = (int)o->depth_mode;
    else if ((unsigned)o->skinning_path > MVR_SKINNING_PATH_OVERRIDE_PRESKIN)
        field = "skinning_path", value = (int)o->skinning_path;
    else if (o->disable_features & ~(uint32_t)DISABLEABLE_FEATURES)
        field = "disable_features", value = (int)o->disable_features;
    else if ((unsigned)o->culling > MVR_OVERRIDE_ON)
        field = "culling", value = (int)o->culling;
    else if ((unsigned)o->instancing > MVR_OVERRIDE_ON)
        field = "instancing", value = (int)o->instancing;
    else if ((unsigned)o->msaa_multiview > MVR_OVERRIDE_ON)
        field = "msaa_multiview", value = (int)o->msaa_multiview;
    else if ((unsigned)o->tuning > MVR_OVERRIDE_ON)
        field = "tuning", value = (int)o->tuning;
    if (field)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: overrides.%s %d is out of its enum's range", field, value);
    if (o->ubo_alignment != 0 && !valid_ubo_alignment(o->ubo_alignment))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: overrides.ubo_alignment %u is not a power of two up to 4096",
                             (unsigned)o->ubo_alignment);
    return MVR_OK;
}

static void timer_init(mvr_renderer *r)
{
    const mvr_caps *c = &r->ctx->caps;
    memset(&r->timer, 0, sizeof r->timer);
    if (!c->ext.ext_disjoint_timer_query)
        return;
    GLint bits = 0;
    r->gl->GetQueryiv(GL_TIMESTAMP_EXT, GL_QUERY_COUNTER_BITS_EXT, &bits);
    mvr_gl_clear_errors(r->gl);
    /* Timestamps are taken with no multiview framebuffer bound (timer queries
     * are undefined while one is), so they bracket the passes from outside. */
    r->timer.timestamps = bits > 0;
    if (r->timer.timestamps)
        r->gl->GenQueries(2, r->timer.queries);
}

mvr_result mvr_renderer_create(const mvr_renderer_desc *desc, mvr_renderer **out, mvr_error *error)
{
    if (!out || !desc)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_create: NULL argument");
    *out = NULL;
    if (!desc->context)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_create: no context");
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
    mvr_result checked = check_overrides(ov, error);
    if (checked != MVR_OK)
        return checked;
    /* the override enums are the desc's enums + 1 (0 = none) */
    mvr_depth_mode depth_mode = ov->depth_mode ? (mvr_depth_mode)(ov->depth_mode - 1) : desc->depth_mode;
    bool clip_control = desc->context->caps.ext.ext_clip_control && desc->context->gl.ClipControl;
    if (depth_mode == MVR_DEPTH_MODE_REVERSED_Z && !clip_control)
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
    if (mvr_context_begin(desc->context, "mvr_renderer_create") != MVR_OK)
        return mvr_error_set(error, MVR_ERROR_CONTEXT, "%s", mvr_context_last_error(desc->context));
    mvr_renderer *r = calloc(1, sizeof *r);
    if (!r)
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_renderer_create: out of memory");
    r->ctx = desc->context;
    r->gl = &desc->context->gl;
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
    /* linked first: every failure below goes through mvr_renderer_destroy */
    r->next_in_context = r->ctx->renderers;
    r->ctx->renderers = r;
    const mvr_caps *c = &r->ctx->caps;
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
    timer_init(r);
    mvr_result res = mvr_renderer_end(r, "mvr_renderer_create", MVR_OK);
    if (res != MVR_OK) {
        mvr_error_set(error, res, "%s", r->last_error);
        mvr_renderer_destroy(r);
        return res;
    }
    *out = r;
    return MVR_OK;
}

/* Every GL object of the renderer and of its targets, through
 * mvr_renderer_delete (now, later, or never once the context is gone); the
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
    mvr_renderer_delete(r, MVR_GL_SAMPLER, &r->nearest_sampler);
    mvr_gpu_scene_release(r);
    for (uint32_t i = 0; i < r->program_count; ++i)
        mvr_renderer_delete(r, MVR_GL_PROGRAM, &r->programs[i].program);
    for (int i = 0; i < MVR_RING_SEGMENTS; ++i) {
        if (r->ctx)
            mvr_context_delete_sync(r->ctx, r->ring.fences[i]);
        r->ring.fences[i] = 0;
    }
    mvr_renderer_delete(r, MVR_GL_BUFFER, &r->ring.buffer);
    r->ring.static_size = r->ring.segment_size = 0;
    if (r->timer.timestamps)
        for (int i = 0; i < 2; ++i)
            mvr_renderer_delete(r, MVR_GL_QUERY, &r->timer.queries[i]);
    r->timer.timestamps = r->timer.pending = false;
    mvr_renderer_delete(r, MVR_GL_VERTEX_ARRAY, &r->empty_vao);
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
    free(r->programs);
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

static bool same_variant(const mvr_shader_variant *a, const mvr_shader_variant *b)
{
    return a->program == b->program && a->features == b->features && a->num_views == b->num_views &&
           a->directional_lights == b->directional_lights && a->point_lights == b->point_lights &&
           a->spot_lights == b->spot_lights && a->material_capacity == b->material_capacity &&
           a->draw_capacity == b->draw_capacity && a->draw_stride == b->draw_stride && a->outputs == b->outputs;
}

mvr_shader_variant mvr_renderer_mesh_variant(const mvr_renderer *r, uint32_t features, uint32_t num_views)
{
    mvr_shader_variant v;
    memset(&v, 0, sizeof v);
    v.program = MVR_PROGRAM_MESH;
    v.features = features;
    v.num_views = num_views;
    v.material_capacity = (uint16_t)r->material_capacity;
    v.draw_capacity = (uint16_t)r->draw_capacity;
    /* padded blocks only matter to instanced draws, which index the array */
    v.draw_stride = r->draw_capacity > 1 && r->draw_stride > MVR_DRAW_BLOCK_SIZE ? (uint16_t)r->draw_stride : 0;
    return v;
}

mvr_result mvr_renderer_program(mvr_renderer *r, const mvr_shader_variant *v, mvr_program_entry **out)
{
    for (uint32_t i = 0; i < r->program_count; ++i) {
        if (same_variant(&r->programs[i].variant, v)) {
            r->cache_hits_this_frame++;
            *out = &r->programs[i];
            return MVR_OK;
        }
    }
    if (r->program_count == r->program_cap) {
        uint32_t cap = r->program_cap ? r->program_cap * 2 : 16;
        mvr_program_entry *p = realloc(r->programs, cap * sizeof *p);
        if (!p)
            return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "program cache: out of memory");
        r->programs = p;
        r->program_cap = cap;
    }
    mvr_program_build_info info;
    mvr_result res = mvr_gl_program_build_cached(r->ctx, v, r->program_cache_dir, &info);
    if (res != MVR_OK)
        return mvr_renderer_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    GLuint program = info.program;
    mvr_state_assume_program(&r->state, program);
    mvr_program_entry *e = &r->programs[r->program_count++];
    memset(e, 0, sizeof *e);
    e->variant = *v;
    e->program = program;
    e->loc_view_base = r->gl->GetUniformLocation(program, "mvr_view_base");
    e->loc_ambient = r->gl->GetUniformLocation(program, "mvr_ambient");
    e->loc_exposure = r->gl->GetUniformLocation(program, "mvr_exposure");
    e->loc_output_alpha_cutoff = r->gl->GetUniformLocation(program, "mvr_output_alpha_cutoff");
    e->output_alpha_cutoff = NAN;
    e->loc_layer_base = r->gl->GetUniformLocation(program, "mvr_layer_base");
    e->loc_factor = r->gl->GetUniformLocation(program, "mvr_factor");
    e->loc_post_exposure = r->gl->GetUniformLocation(program, "mvr_post_exposure");
    e->loc_clear_depth = r->gl->GetUniformLocation(program, "mvr_clear_depth");
    e->loc_transmission_base = r->gl->GetUniformLocation(program, "mvr_transmission_base");
    e->loc_transmission_rect = r->gl->GetUniformLocation(program, "mvr_transmission_rect");
    e->loc_transmission_lod = r->gl->GetUniformLocation(program, "mvr_transmission_lod");
    static const struct { size_t offset; const char *name; } env_uniforms[] = {
        {offsetof(mvr_program_entry, loc_env_sh), "mvr_env_sh"},
        {offsetof(mvr_program_entry, loc_env_rotation), "mvr_env_rotation"},
        {offsetof(mvr_program_entry, loc_env_intensity), "mvr_env_intensity"},
        {offsetof(mvr_program_entry, loc_env_max_lod), "mvr_env_max_lod"},
        {offsetof(mvr_program_entry, loc_face_base), "mvr_face_base"},
        {offsetof(mvr_program_entry, loc_face_size), "mvr_face_size"},
        {offsetof(mvr_program_entry, loc_equirect_lod), "mvr_equirect_lod"},
        {offsetof(mvr_program_entry, loc_roughness), "mvr_roughness"},
        {offsetof(mvr_program_entry, loc_samples), "mvr_samples"},
        {offsetof(mvr_program_entry, loc_source_size), "mvr_source_size"},
        {offsetof(mvr_program_entry, loc_source_max_lod), "mvr_source_max_lod"},
        {offsetof(mvr_program_entry, loc_depth_range), "mvr_depth_range"},
        {offsetof(mvr_program_entry, loc_background_lod), "mvr_background_lod"},
        {offsetof(mvr_program_entry, loc_env_samples), "mvr_env_samples"},
        {offsetof(mvr_program_entry, loc_deform_info), "mvr_deform_info"},
    };
    for (size_t i = 0; i < MVR_ARRAY_COUNT(env_uniforms); ++i)
        *(GLint *)((char *)e + env_uniforms[i].offset) = r->gl->GetUniformLocation(program, env_uniforms[i].name);
    e->view_base = INT32_MIN;
    e->from_binary = info.from_binary;
    if (info.from_binary)
        r->binary_loads_this_frame++;
    else
        r->compiled_this_frame++;
    if (info.binary_rejected) {
        r->binary_rejects_this_frame++;
        mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_SHADER, "mvr: program binary cache: %s; rebuilt", info.why);
    }
    if (info.binary_store_failed && !r->program_cache_warned) {
        /* once per renderer: an unwritable directory fails for every variant */
        r->program_cache_warned = true;
        mvr_log(&r->logger, MVR_LOG_WARNING, MVR_LOG_ID_SHADER,
                "mvr: program binary cache: %s (programs still build; later failures are not reported)",
                info.why);
    }
    *out = e;
    return MVR_OK;
}

/* Replaces the ring buffer with one of the given region sizes. The old
 * buffer may still be read by queued draws; GL keeps it alive until they
 * finish, so deleting it here is safe. On failure the ring is empty. */
static mvr_result ring_allocate(mvr_renderer *r, GLsizeiptr static_size, GLsizeiptr segment_size)
{
    const mvr_gl_api_table *gl = r->gl;
    mvr_ring *ring = &r->ring;
    for (int i = 0; i < MVR_RING_SEGMENTS; ++i) {
        if (ring->fences[i])
            gl->DeleteSync(ring->fences[i]);
        ring->fences[i] = 0;
    }
    mvr_renderer_delete(r, MVR_GL_BUFFER, &ring->buffer);
    r->frame_key.valid = false; /* the static region is empty now */
    GLsizeiptr total = static_size + segment_size * MVR_RING_SEGMENTS;
    gl->GenBuffers(1, &ring->buffer);
    gl->BindBuffer(GL_UNIFORM_BUFFER, ring->buffer);
    gl->BufferData(GL_UNIFORM_BUFFER, total, NULL, GL_DYNAMIC_DRAW);
    mvr_result res = mvr_renderer_check_alloc(r, "uniform ring buffer (%lld bytes)", (long long)total);
    if (res != MVR_OK) {
        mvr_renderer_delete(r, MVR_GL_BUFFER, &ring->buffer);
        ring->static_size = ring->segment_size = 0;
        return res;
    }
    ring->static_size = static_size;
    ring->segment_size = segment_size;
    ring->current = 0;
    return MVR_OK;
}

static GLsizeiptr grown(GLsizeiptr have, GLsizeiptr need)
{
    GLsizeiptr v = have ? have : 64 * 1024;
    while (v < need)
        v *= 2;
    return v;
}

mvr_result mvr_ring_reserve_static(mvr_renderer *r, GLsizeiptr size, bool *reallocated)
{
    *reallocated = false;
    if (r->ring.buffer && size <= r->ring.static_size)
        return MVR_OK;
    *reallocated = true;
    return ring_allocate(r, grown(r->ring.static_size, size), r->ring.segment_size ? r->ring.segment_size : 64 * 1024);
}

mvr_result mvr_ring_begin_frame(mvr_renderer *r, GLsizeiptr size, bool *reallocated)
{
    const mvr_gl_api_table *gl = r->gl;
    mvr_ring *ring = &r->ring;
    *reallocated = false;
    if (!ring->buffer || size > ring->segment_size) {
        mvr_result res = ring_allocate(r, ring->static_size, grown(ring->segment_size, size));
        if (res != MVR_OK)
            return res;
        *reallocated = true;
    } else {
        ring->current = (ring->current + 1) % MVR_RING_SEGMENTS;
    }
    GLsync fence = ring->fences[ring->current];
    if (fence) {
        /* the GPU may still read this segment from three frames ago */
        gl->ClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, (GLuint64)10 * 1000 * 1000 * 1000);
        gl->DeleteSync(fence);
        ring->fences[ring->current] = 0;
    }
    gl->BindBuffer(GL_UNIFORM_BUFFER, ring->buffer);
    return MVR_OK;
}

void mvr_ring_end_frame(mvr_renderer *r)
{
    r->ring.fences[r->ring.current] = r->gl->FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
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

mvr_result mvr_renderer_render(mvr_renderer *r, mvr_scene *scene, const mvr_view_set *views,
                               mvr_target *target, const mvr_render_desc *desc)
{
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (!scene || !views || !target)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_render: NULL scene, views or target");
    if (target->renderer != r)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 target->renderer ? "mvr_renderer_render: the target belongs to another renderer"
                                                  : "mvr_renderer_render: the target was released with its renderer "
                                                    "or context");
    if (!r->ctx)
        return mvr_renderer_fail(r, MVR_ERROR_CONTEXT, "mvr_renderer_render: the renderer's context was destroyed");
    uint32_t layers = target->desc.layers;
    if (views->count > layers)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_renderer_render: %u views but the target has %u layers",
                                 views->count, layers);
    mvr_render_desc d;
    if (desc)
        d = *desc;
    else
        memset(&d, 0, sizeof d);
    if ((unsigned)d.tone_map > MVR_TONE_MAP_KHR_PBR_NEUTRAL)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_render: unknown tone map %d",
                                 (int)d.tone_map);
    if (d.exposure == 0.0f)
        d.exposure = 1.0f;
    if (!mvr_exposure_mode_name(d.exposure_mode) || !(d.exposure > 0.0f) || !isfinite(d.exposure) ||
        !isfinite(d.ev100) || !(d.aperture >= 0.0) || !(d.shutter >= 0.0) || !(d.iso >= 0.0) ||
        !isfinite(d.exposure_compensation) || !(d.exposure_key >= 0.0f) || !isfinite(d.ev100_min) ||
        !isfinite(d.ev100_max) || d.ev100_min > d.ev100_max)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_renderer_render: exposure: mode %d, exposure %g, ev100 %g, camera f/%g %gs ISO %g, "
                                 "key %g, clamps %g..%g (finite, >= 0, min <= max)",
                                 (int)d.exposure_mode, (double)d.exposure, d.ev100, d.aperture, d.shutter, d.iso,
                                 (double)d.exposure_key, (double)d.ev100_min, (double)d.ev100_max);
    const mvr_shadow_desc *sd = &d.shadows;
    if ((unsigned)sd->mode > MVR_SHADOWS_OFF || sd->cascades > MVR_SHADOW_MAX_CASCADES ||
        sd->map_size > 16384 || !(sd->distance >= 0.0) || !(sd->slope_bias >= 0.0f) ||
        !(sd->constant_bias >= 0.0f) || !(sd->normal_bias >= 0.0f))
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_renderer_render: shadows: mode %d, cascades %u (at most %d), map size %u "
                                 "(at most 16384), distance and biases >= 0 and finite",
                                 (int)sd->mode, sd->cascades, MVR_SHADOW_MAX_CASCADES, sd->map_size);

    if (!mvr_background_name(d.background) || !(d.background_blur >= 0.0f && d.background_blur <= 1.0f) ||
        d.environment_samples > 65536u)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_renderer_render: background %d with blur %g (a roughness, 0..1), "
                                 "environment samples %u (at most 65536)",
                                 (int)d.background, (double)d.background_blur, d.environment_samples);
    if (d.background != MVR_BACKGROUND_COLOR && !d.environment)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_renderer_render: background '%s' needs an environment (render desc "
                                 "environment is NULL)",
                                 mvr_background_name(d.background));

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
        return mvr_renderer_fail(r, MVR_ERROR_UNSUPPORTED,
                                 "mvr_renderer_render: the multiview path was forced but %s has no "
                                 "usable GL_OVR_multiview2",
                                 r->ctx->caps.renderer);
    if (path == MVR_VIEW_PATH_MULTIVIEW && !level_ok)
        return mvr_renderer_fail(r, MVR_ERROR_UNSUPPORTED,
                                 "mvr_renderer_render: the multiview path was forced but %s attaches "
                                 "only mip level 0 with multiview (the target is level %u)",
                                 r->ctx->caps.renderer, target->desc.external_level);

    /* the last check: nothing above touched GL or the renderer's state */
    mvr_result res = mvr_renderer_begin(r, "mvr_renderer_render");
    if (res != MVR_OK)
        return res;
    /* tuned only where both paths can draw this frame (MSAA may rule
     * multiview out; transmission as the last frame had it) */
    bool drawable = mvr_frame_plan_multiview_drawable(target->desc.samples, mvr_post_needed(&d), target->msaa_multiview,
                                                      r->frame.transmissive_draws != 0);
    path = mvr_tuning_choose(r, views, target, path, tune && multiview_usable(r) && level_ok && drawable);
    double cpu_start = thread_cpu_ms();
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

    if (r->timer.timestamps) {
        mvr_state_draw_framebuffer(&r->state, 0); /* never time with a multiview FBO bound */
        r->gl->QueryCounter(r->timer.queries[0], GL_TIMESTAMP_EXT);
    }
    uint32_t failures = r->failures;
    res = mvr_gpu_scene_sync(r, scene, r->material_tuner.phase == MVR_TUNER_TUNING);
    /* the frame plan prefilters a new environment (mvr_environment_sync) first */
    if (res == MVR_OK)
        res = mvr_renderer_draw_frame(r, scene, views, target, &d, path);
    if (r->timer.timestamps) {
        mvr_state_draw_framebuffer(&r->state, 0);
        r->gl->QueryCounter(r->timer.queries[1], GL_TIMESTAMP_EXT);
        r->timer.pending = res == MVR_OK;
    }
    res = mvr_renderer_end(r, "mvr_renderer_render", res);
    if (res != MVR_OK && r->failures == failures) /* failed where only the context kept the message */
        mvr_renderer_fail(r, res, "%s", mvr_context_last_error(r->ctx));

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
    st->cpu_ms = thread_cpu_ms() - cpu_start;
    mvr_tuning_end_frame(r, prior, res == MVR_OK);
    return res;
}

void mvr_renderer_read_timer(mvr_renderer *r)
{
    GLuint64 t0 = 0, t1 = 0;
    GLint disjoint = 0;
    r->gl->GetQueryObjectui64v(r->timer.queries[0], GL_QUERY_RESULT, &t0);
    r->gl->GetQueryObjectui64v(r->timer.queries[1], GL_QUERY_RESULT, &t1);
    if (r->ctx->caps.api == MVR_GL_API_GLES)
        r->gl->GetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
    r->stats.gpu_ms = (!disjoint && t1 >= t0) ? (double)(t1 - t0) * 1e-6 : -1.0;
    r->timer.pending = false;
}

void mvr_renderer_get_stats(mvr_renderer *r, mvr_frame_stats *out)
{
    if (!r || !out)
        return;
    /* the timer result is read only with the renderer's context current (else kept for later) */
    if (r->timer.pending && r->ctx && mvr_context_is_current(r->ctx) &&
        mvr_context_begin(r->ctx, "mvr_renderer_get_stats") == MVR_OK) {
        mvr_renderer_read_timer(r);
        /* a void call: an error of its own is logged, not left for the next call to blame on the application */
        mvr_gl_check(r->ctx, "mvr_renderer_get_stats", true);
    }
    *out = r->stats;
}

uint32_t mvr_renderer_program_count(const mvr_renderer *r)
{
    return r ? r->program_count : 0;
}

bool mvr_renderer_get_program_info(const mvr_renderer *r, uint32_t index, mvr_program_info *out)
{
    if (!r || !out || index >= r->program_count)
        return false;
    const mvr_program_entry *e = &r->programs[index];
    memset(out, 0, sizeof *out);
    mvr_shader_variant_name(&e->variant, out->name, sizeof out->name);
    out->mesh = e->variant.program == MVR_PROGRAM_MESH;
    out->features = e->variant.features;
    out->num_views = e->variant.num_views;
    out->lights[0] = e->variant.directional_lights;
    out->lights[1] = e->variant.point_lights;
    out->lights[2] = e->variant.spot_lights;
    out->from_binary_cache = e->from_binary;
    return true;
}

const char *mvr_program_feature_name(uint32_t bit)
{
    const char *define = mvr_shader_feature_define(MVR_PROGRAM_MESH, bit);
    /* the #define without its MVR_ prefix */
    return define && strncmp(define, "MVR_", 4) == 0 ? define + 4 : define;
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
    mvr_result res = mvr_renderer_begin(r, "mvr_renderer_finish");
    if (res != MVR_OK)
        return res;
    r->gl->Finish();
    return mvr_renderer_end(r, "mvr_renderer_finish", MVR_OK);
}

mvr_result mvr_renderer_read_layer(mvr_renderer *r, mvr_target *t, uint32_t layer,
                                   mvr_readback_format format, void *dst, size_t size)
{
    if (!r)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (!t || !dst || t->renderer != r)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 t && dst && !t->renderer
                                     ? "mvr_renderer_read_layer: the target was released with its renderer or context"
                                     : "mvr_renderer_read_layer: bad target or buffer");
    if (layer >= t->desc.layers)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_renderer_read_layer: layer %u of %u", layer, t->desc.layers);
    if ((unsigned)format > MVR_READBACK_RGBA32F)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_read_layer: unknown format");
    size_t pixels = (size_t)t->desc.width * t->desc.height;
    size_t need = pixels * 4 * (format == MVR_READBACK_RGBA32F ? sizeof(float) : 1);
    if (size < need)
        return mvr_renderer_fail(r, MVR_ERROR_INVALID_ARGUMENT,
                                 "mvr_renderer_read_layer: buffer of %zu bytes, %zu needed", size, need);
    mvr_result res = mvr_renderer_begin(r, "mvr_renderer_read_layer");
    if (res != MVR_OK)
        return res;
    mvr_state_invalidate(&r->state);
    /* One layer attached alone: reading from a multiview framebuffer is an error. */
    GLuint fbo = 0;
    res = mvr_target_output_framebuffer(t, layer, 0, &fbo);
    if (res != MVR_OK)
        return mvr_renderer_end(r, "mvr_renderer_read_layer", res);
    const mvr_gl_api_table *gl = r->gl;
    mvr_state_read_framebuffer(&r->state, fbo);
    gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    bool float_target = t->internal_format == GL_RGBA16F || t->internal_format == GL_RGBA32F;
    GLsizei w = (GLsizei)t->desc.width, h = (GLsizei)t->desc.height;
    if (float_target == (format == MVR_READBACK_RGBA32F)) {
        gl->ReadPixels(0, 0, w, h, GL_RGBA, float_target ? GL_FLOAT : GL_UNSIGNED_BYTE, dst);
    } else if (float_target) {
        /* float storage read as bytes: GLES reads float buffers as FLOAT only */
        float *tmp = malloc(pixels * 4 * sizeof *tmp);
        if (!tmp)
            return mvr_renderer_end(r, "mvr_renderer_read_layer",
                                    mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY,
                                                      "mvr_renderer_read_layer: out of memory"));
        gl->ReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, tmp);
        uint8_t *out = dst;
        for (size_t i = 0; i < pixels * 4; ++i) {
            float v = tmp[i] < 0.0f ? 0.0f : tmp[i] > 1.0f ? 1.0f : tmp[i];
            out[i] = (uint8_t)(v * 255.0f + 0.5f);
        }
        free(tmp);
    } else {
        /* 8-bit storage read as floats: normalized */
        uint8_t *tmp = malloc(pixels * 4);
        if (!tmp)
            return mvr_renderer_end(r, "mvr_renderer_read_layer",
                                    mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY,
                                                      "mvr_renderer_read_layer: out of memory"));
        gl->ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, tmp);
        float *out = dst;
        for (size_t i = 0; i < pixels * 4; ++i)
            out[i] = (float)tmp[i] / 255.0f;
        free(tmp);
    }
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    return mvr_renderer_end(r, "mvr_renderer_read_layer", MVR_OK);
}
