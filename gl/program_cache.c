/* The renderer's programs: one entry per shader variant, compiled (or
 * loaded from the binary cache) on first use, with its uniform locations. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "errors.h"
#include "program_cache.h"
#include "renderer.h"

static bool same_variant(const mvr_shader_variant *a, const mvr_shader_variant *b)
{
    return a->program == b->program && a->features == b->features && a->num_views == b->num_views &&
           a->directional_lights == b->directional_lights && a->point_lights == b->point_lights &&
           a->spot_lights == b->spot_lights && a->material_capacity == b->material_capacity &&
           a->draw_capacity == b->draw_capacity && a->draw_stride == b->draw_stride && a->outputs == b->outputs;
}

mvr_shader_variant mvr_mesh_variant(const mvr_renderer *r, uint32_t features, uint32_t num_views)
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

mvr_result mvr_program_cache_get(mvr_renderer *r, const mvr_shader_variant *v, mvr_program_entry **out)
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
            return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "program cache: out of memory");
        r->programs = p;
        r->program_cap = cap;
    }
    mvr_program_build_info info;
    mvr_result res = mvr_gl_program_build_cached(r->ctx, v, r->program_cache_dir, &info);
    if (res != MVR_OK)
        return mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
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
    e->loc_clear_out = r->gl->GetUniformLocation(program, "mvr_clear_out");
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

void mvr_program_cache_release(mvr_renderer *r)
{
    for (uint32_t i = 0; i < r->program_count; ++i)
        mvr_gl_delete(r, MVR_GL_PROGRAM, &r->programs[i].program);
}

void mvr_program_cache_free(mvr_renderer *r)
{
    free(r->programs);
}
