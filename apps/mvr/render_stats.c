/* mvr render's --stats JSON: one table of its keys (a field of the frame's
 * stats, an enum's name, or a section such as the environment or the
 * programs) walked by one writer, so the keys and their order live in one
 * place. */
#include "render_stats.h"

#include <stddef.h>

#include "json.h"

/* The animation that posed the frames (null: none, the rest pose) and the
 * last frame's skinning and morphing. */
static void write_animation_json(json_writer *jw, const render_options *o, const render_animation *a,
                                 const mvr_frame_stats *s)
{
    if (a->applied) {
        json_begin_object(jw, "animation");
        if (a->index == MVR_ANIMATION_ALL)
            json_string(jw, "index", "all");
        else
            json_int(jw, "index", a->index);
        json_string(jw, "label", a->label);
        json_double(jw, "start", a->start);
        json_double(jw, "end", a->end);
        json_bool(jw, "loop", o->loop);
        json_double(jw, "first_time", a->first_time);
        json_double(jw, "time", a->last_time);
        json_end_object(jw);
    } else {
        json_null(jw, "animation");
    }
    json_int(jw, "frames", o->frames);
    json_double(jw, "fps", o->fps);
    json_string(jw, "skinning_path", mvr_skinning_path_name(s->skinning_path));
    json_int(jw, "joints", s->joints);
    json_int(jw, "morph_targets_active", s->morph_targets_active);
    json_int(jw, "animation_upload_bytes", (long long)s->animation_upload_bytes);
    json_int(jw, "preskin_passes", s->preskin_passes);
}

/* One of auto's decisions: state, the rule's choice, what runs once
 * settled, and what each candidate measured (ms; null before a sample). */
static void write_decision(json_writer *jw, const char *key, mvr_auto_state state, const char *prior,
                           const char *chosen, const char *const names[2], const double cost_ms[2])
{
    json_begin_object(jw, key);
    json_string(jw, "state", mvr_auto_state_name(state));
    json_string(jw, "prior", prior);
    json_string(jw, "chosen", chosen);
    json_begin_object(jw, "cost_ms");
    for (int c = 0; c < 2; ++c)
        if (cost_ms[c] >= 0.0)
            json_double(jw, names[c], cost_ms[c]);
        else
            json_null(jw, names[c]);
    json_end_object(jw);
    json_end_object(jw);
}

/* What auto's tuner measured and chose for each path left to it. */
static void write_auto(json_writer *jw, const mvr_frame_stats *s)
{
    json_begin_object(jw, "auto");
    const mvr_auto_material_choice *m = &s->auto_material;
    if (m->state != MVR_AUTO_NONE) {
        const char *names[2] = {mvr_material_path_name(m->candidates[0]), mvr_material_path_name(m->candidates[1])};
        write_decision(jw, "material_path", m->state, mvr_material_path_name(m->prior), mvr_material_path_name(m->chosen),
                       names, m->cost_ms);
    }
    const mvr_auto_choice *v = &s->auto_choice;
    if (v->state != MVR_AUTO_NONE) {
        const char *names[2] = {mvr_view_path_name(v->candidates[0]), mvr_view_path_name(v->candidates[1])};
        write_decision(jw, "view_path", v->state, mvr_view_path_name(v->prior), mvr_view_path_name(v->chosen), names,
                       v->cost_ms);
    }
    const mvr_auto_skinning_choice *k = &s->auto_skinning;
    if (k->state != MVR_AUTO_NONE) {
        const char *names[2] = {mvr_skinning_path_name(k->candidates[0]), mvr_skinning_path_name(k->candidates[1])};
        write_decision(jw, "skinning_path", k->state, mvr_skinning_path_name(k->prior),
                       mvr_skinning_path_name(k->chosen), names, k->cost_ms);
    }
    json_end_object(jw);
}

/* What the stats' rows read: the frame's stats and what the run adds. */
typedef struct stats_source {
    const mvr_renderer *r;
    const mvr_frame_stats *s;
    const char *scene;
    uint32_t width, height, supersample;
    const mvr_gltf_info *load;
    const cli_env_used *env;
    const mvr_render_desc *rd;
    const render_options *o;
    const render_animation *anim;
    const render_readback_info *readback;
} stats_source;

typedef enum stats_kind {
    STATS_END = 0,
    STATS_U32,          /* a uint32_t of mvr_frame_stats at offset */
    STATS_U64,          /* a uint64_t */
    STATS_DOUBLE,       /* a double */
    STATS_BOOL,         /* a bool */
    STATS_MS_OR_NULL,   /* a double, null when < 0 (not measured) */
    STATS_NAME,         /* text(): an enum's name */
    STATS_SECTION       /* section(): an object, an array or several keys */
} stats_kind;

typedef struct stats_field {
    const char *key;
    stats_kind kind;
    size_t offset;
    const char *(*text)(const stats_source *x);
    void (*section)(json_writer *jw, const stats_source *x);
} stats_field;

/* A field of mvr_frame_stats, its kind from its type (another type does not compile). */
#define STATS_FIELD(key, field)                                                                                     \
    {key,                                                                                                           \
     _Generic(((mvr_frame_stats *)0)->field, uint32_t: STATS_U32, uint64_t: STATS_U64, double: STATS_DOUBLE,       \
              bool: STATS_BOOL),                                                                                    \
     offsetof(mvr_frame_stats, field), NULL, NULL}
#define STATS_NAMED(key, fn) {key, STATS_NAME, 0, fn, NULL}
#define STATS_SECTION_OF(fn) {NULL, STATS_SECTION, 0, NULL, fn}

static const char *transparency_name(const stats_source *x)
{
    return mvr_transparency_order_name(x->s->transparency_order);
}

static const char *view_path_name(const stats_source *x)
{
    return mvr_view_path_name(x->s->view_path);
}

static const char *anti_aliasing_name(const stats_source *x)
{
    return mvr_anti_aliasing_name(x->s->anti_aliasing);
}

static const char *material_path_name(const stats_source *x)
{
    return mvr_material_path_name(x->s->material_path);
}

static const char *exposure_mode_name(const stats_source *x)
{
    return mvr_exposure_mode_name(x->s->exposure_mode);
}

static const char *tone_mapper_name(const stats_source *x)
{
    return mvr_tone_map_name(x->s->tone_mapper);
}

static const char *depth_mode_name(const stats_source *x)
{
    return mvr_depth_mode_name(x->s->depth_mode);
}

/* The scene, the glTF load's own accounting (mvr_gltf_info) and the layers' size. */
static void write_scene_section(json_writer *jw, const stats_source *x)
{
    json_string(jw, "scene", x->scene);
    const mvr_gltf_info *load = x->load;
    if (load) {
        json_begin_object(jw, "load");
        json_int(jw, "warnings", load->warnings);
        json_int(jw, "images_missing", load->images_missing);
        json_int(jw, "images_decoded", load->images_decoded);
        json_int(jw, "buffers_read", load->buffers_read);
        json_int(jw, "memory_budget", (long long)load->memory_budget);
        json_int(jw, "memory_peak", (long long)load->memory_peak);
        json_int(jw, "json_bytes_estimate", (long long)load->json_bytes_estimate);
        json_end_object(jw);
    }
    json_int(jw, "width", x->width);
    json_int(jw, "height", x->height);
    json_int(jw, "supersample", x->supersample);
}

static void write_auto_section(json_writer *jw, const stats_source *x)
{
    write_auto(jw, x->s);
}

static void write_culled_section(json_writer *jw, const stats_source *x)
{
    json_begin_array(jw, "culled_per_view");
    for (uint32_t v = 0; v < x->s->views; ++v)
        json_int(jw, NULL, x->readback->culled_per_view ? x->readback->culled_per_view[v]
                                                        : mvr_renderer_view_culled(x->r, v));
    json_end_array(jw);
    json_begin_object(jw, "sub_passes");
    json_int(jw, "opaque", x->s->sub_passes[0]);
    json_int(jw, "mask", x->s->sub_passes[1]);
    json_int(jw, "blend", x->s->sub_passes[2]);
    json_end_object(jw);
}

/* the environment the frame was lit with (source "none": no IBL) */
static void write_environment_section(json_writer *jw, const stats_source *x)
{
    const cli_env_used *env = x->env;
    const mvr_render_desc *rd = x->rd;
    json_begin_object(jw, "environment");
    json_string(jw, "source", env->present ? mvr_environment_source_name(env->source) : "none");
    if (env->file)
        json_string(jw, "file", env->file);
    else
        json_null(jw, "file");
    if (env->present) {
        if (env->file) {
            json_int(jw, "width", env->width);
            json_int(jw, "height", env->height);
        }
        if (env->source == MVR_ENVIRONMENT_UNIFORM) {
            json_begin_array(jw, "color");
            for (int c = 0; c < 3; ++c)
                json_double(jw, NULL, env->color[c]);
            json_end_array(jw);
        }
        json_double(jw, "intensity", env->intensity);
        json_double(jw, "rotation", env->rotation);
    }
    json_string(jw, "background", mvr_background_name(rd->background));
    if (rd->background == MVR_BACKGROUND_BLUR)
        json_double(jw, "background_blur", rd->background_blur > 0.0f ? rd->background_blur : 0.5);
    json_end_object(jw);
}

static void write_programs_section(json_writer *jw, const stats_source *x)
{
    json_begin_array(jw, "programs");
    mvr_program_info pi;
    for (uint32_t i = 0; mvr_renderer_get_program_info(x->r, i, &pi); ++i) {
        json_begin_object(jw, NULL);
        json_string(jw, "name", pi.name);
        json_int(jw, "views", pi.num_views);
        json_begin_array(jw, "features");
        for (uint32_t bit = 1; bit != 0; bit <<= 1)
            if ((pi.features & bit) && mvr_program_feature_name(bit))
                json_string(jw, NULL, mvr_program_feature_name(bit));
        json_end_array(jw);
        json_bool(jw, "from_binary_cache", pi.from_binary_cache);
        json_end_object(jw);
    }
    json_end_array(jw);
}

static void write_pass_stats_section(json_writer *jw, const stats_source *x)
{
    json_begin_array(jw, "pass_stats");
    mvr_pass_stats ps;
    for (uint32_t i = 0; mvr_renderer_get_pass_stats(x->r, i, &ps); ++i) {
        json_begin_object(jw, NULL);
        json_int(jw, "first_view", ps.first_view);
        json_int(jw, "views", ps.views);
        json_bool(jw, "multiview", ps.multiview);
        json_int(jw, "draws", ps.draws);
        json_int(jw, "program_binds", ps.program_binds);
        json_int(jw, "texture_binds", ps.texture_binds);
        json_int(jw, "ubo_range_binds", ps.ubo_range_binds);
        json_int(jw, "texture_groups", ps.texture_groups);
        json_end_object(jw);
    }
    json_end_array(jw);
}

static void write_animation_section(json_writer *jw, const stats_source *x)
{
    write_animation_json(jw, x->o, x->anim, x->s);
}

/* how the images came back (pass_stats and --plan: the last chunk's when streamed) */
static void write_readback_section(json_writer *jw, const stats_source *x)
{
    const render_readback_info *readback = x->readback;
    json_begin_object(jw, "readback");
    json_string(jw, "mode", readback->mode == RENDER_READBACK_STREAM ? "stream" : "sync");
    if (readback->mode == RENDER_READBACK_STREAM) {
        json_int(jw, "chunk_views", readback->chunk);
        json_int(jw, "ring_targets", readback->ring);
        json_int(jw, "encoders", readback->encoders);
        json_int(jw, "contact_sheet_factor", readback->sheet_factor);
        json_bool(jw, "exposure_metered", readback->exposure_metered);
        json_bool(jw, "shadows_per_chunk", readback->shadows_per_chunk);
        if (readback->exposure_metered)
            json_double(jw, "metered_ev100", readback->exposure_ev100);
    }
    json_int(jw, "images", (long long)readback->images);
    json_double(jw, "seconds", readback->seconds);
    json_double(jw, "views_per_second", readback->seconds > 0 ? (double)readback->images / readback->seconds : 0.0);
    json_end_object(jw);
}

/* The stats JSON's keys in their order (tests and scripts read them by name). */
static const stats_field stats_fields[] = {
    STATS_SECTION_OF(write_scene_section),
    STATS_NAMED("transparency_order", transparency_name),
    STATS_NAMED("view_path", view_path_name),
    STATS_NAMED("anti_aliasing", anti_aliasing_name),
    STATS_FIELD("msaa_multiview", msaa_multiview),
    STATS_FIELD("views", views),
    STATS_FIELD("passes", passes),
    STATS_FIELD("multiview_passes", multiview_passes),
    STATS_NAMED("material_path", material_path_name),
    STATS_FIELD("texture_groups", texture_groups),
    STATS_SECTION_OF(write_auto_section),
    STATS_FIELD("culled", culled),
    STATS_SECTION_OF(write_culled_section), /* culled_per_view, sub_passes */
    STATS_NAMED("exposure_mode", exposure_mode_name),
    STATS_FIELD("exposure_ev100", exposure_ev100),
    STATS_NAMED("tone_mapper", tone_mapper_name),
    STATS_FIELD("post_passes", post_passes),
    STATS_FIELD("luminance_passes", luminance_passes),
    STATS_SECTION_OF(write_environment_section),
    STATS_FIELD("env_prefilter_passes", env_prefilter_passes),
    STATS_FIELD("env_prefilter_ms", env_prefilter_ms),
    STATS_FIELD("background_draws", background_draws),
    STATS_FIELD("shadow_passes", shadow_passes),
    STATS_FIELD("shadow_layers", shadow_layers),
    STATS_FIELD("shadow_draws", shadow_draws),
    STATS_FIELD("draws", draws),
    STATS_FIELD("draw_calls", draw_calls),
    STATS_FIELD("instanced_draw_calls", instanced_draw_calls),
    STATS_FIELD("program_binds", program_binds),
    STATS_FIELD("texture_binds", texture_binds),
    STATS_FIELD("ubo_range_binds", ubo_range_binds),
    STATS_FIELD("upload_bytes", upload_bytes),
    STATS_FIELD("view_upload_bytes", view_upload_bytes),
    STATS_FIELD("transmission_copies", transmission_copies),
    STATS_FIELD("transmission_bytes", transmission_bytes),
    STATS_FIELD("compacted_bytes", compacted_bytes),
    STATS_FIELD("sanitized", sanitized),
    STATS_FIELD("samples", samples),
    STATS_FIELD("programs_compiled", programs_compiled),
    STATS_FIELD("program_cache_hits", program_cache_hits),
    STATS_FIELD("program_binary_loads", program_binary_loads),
    STATS_FIELD("program_binary_rejects", program_binary_rejects),
    STATS_SECTION_OF(write_programs_section),
    STATS_NAMED("depth_mode", depth_mode_name),
    STATS_FIELD("cpu_ms", cpu_ms),
    {"gpu_ms", STATS_MS_OR_NULL, offsetof(mvr_frame_stats, gpu_ms), NULL, NULL},
    STATS_SECTION_OF(write_pass_stats_section),
    STATS_SECTION_OF(write_animation_section), /* animation, frames, fps, skinning */
    STATS_SECTION_OF(write_readback_section),
    {NULL, STATS_END, 0, NULL, NULL},
};

/* One writer for the table: each row's key and value, in order. */
static void write_stats_fields(json_writer *jw, const stats_field *t, const stats_source *x)
{
    const char *base = (const char *)x->s;
    for (; t->kind != STATS_END; ++t) {
        const void *at = base + t->offset;
        switch (t->kind) {
        case STATS_U32: json_int(jw, t->key, *(const uint32_t *)at); break;
        case STATS_U64: json_int(jw, t->key, (long long)*(const uint64_t *)at); break;
        case STATS_DOUBLE: json_double(jw, t->key, *(const double *)at); break;
        case STATS_BOOL: json_bool(jw, t->key, *(const bool *)at); break;
        case STATS_MS_OR_NULL:
            if (*(const double *)at >= 0)
                json_double(jw, t->key, *(const double *)at);
            else
                json_null(jw, t->key);
            break;
        case STATS_NAME: json_string(jw, t->key, t->text(x)); break;
        case STATS_SECTION: t->section(jw, x); break;
        case STATS_END: break;
        }
    }
}

void render_stats_write_json(FILE *f, const mvr_renderer *r, const mvr_frame_stats *s, const char *demo,
                             uint32_t w, uint32_t h, uint32_t supersample, const mvr_gltf_info *load,
                             const cli_env_used *env, const mvr_render_desc *rd, const render_options *o,
                             const render_animation *anim, const render_readback_info *readback)
{
    const stats_source x = {r, s, demo, w, h, supersample, load, env, rd, o, anim, readback};
    json_writer jw = {f, 0, {false}, {0}};
    json_begin_object(&jw, NULL);
    write_stats_fields(&jw, stats_fields, &x);
    json_end_object(&jw);
}

