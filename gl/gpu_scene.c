/* Uploads of a scene: geometry once per geometry change, textures once per
 * image (and color space), the material table once per material change.
 * Nothing here depends on the views. */
#include <stdlib.h>
#include <string.h>

#include "renderer_internal.h"


static GLenum gl_filter(mvr_filter f, bool min)
{
    switch (f) {
    case MVR_FILTER_DEFAULT: return min ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR;
    case MVR_FILTER_NEAREST: return GL_NEAREST;
    case MVR_FILTER_LINEAR: return GL_LINEAR;
    case MVR_FILTER_NEAREST_MIPMAP_NEAREST: return min ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST;
    case MVR_FILTER_LINEAR_MIPMAP_NEAREST: return min ? GL_LINEAR_MIPMAP_NEAREST : GL_LINEAR;
    case MVR_FILTER_NEAREST_MIPMAP_LINEAR: return min ? GL_NEAREST_MIPMAP_LINEAR : GL_NEAREST;
    case MVR_FILTER_LINEAR_MIPMAP_LINEAR: return min ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR;
    }
    return GL_LINEAR;
}

static GLenum gl_wrap(mvr_wrap w)
{
    switch (w) {
    case MVR_WRAP_DEFAULT:
    case MVR_WRAP_REPEAT: return GL_REPEAT;
    case MVR_WRAP_CLAMP_TO_EDGE: return GL_CLAMP_TO_EDGE;
    case MVR_WRAP_MIRRORED_REPEAT: return GL_MIRRORED_REPEAT;
    }
    return GL_REPEAT;
}

static GLenum gl_mode(mvr_primitive_mode m)
{
    switch (m) {
    case MVR_PRIMITIVE_TRIANGLES: return GL_TRIANGLES;
    case MVR_PRIMITIVE_LINES: return GL_LINES;
    case MVR_PRIMITIVE_POINTS: return GL_POINTS;
    }
    return GL_TRIANGLES;
}

static bool same_sampler(const mvr_sampler_desc *a, const mvr_sampler_desc *b)
{
    return gl_filter(a->mag_filter, false) == gl_filter(b->mag_filter, false) &&
           gl_filter(a->min_filter, true) == gl_filter(b->min_filter, true) &&
           gl_wrap(a->wrap_s) == gl_wrap(b->wrap_s) && gl_wrap(a->wrap_t) == gl_wrap(b->wrap_t);
}

static GLuint sampler_for(mvr_renderer *r, const mvr_sampler_desc *d)
{
    mvr_gpu_scene *g = &r->gpu;
    for (uint32_t i = 0; i < g->sampler_count; ++i)
        if (same_sampler(&g->samplers[i].desc, d))
            return g->samplers[i].sampler;
    if (g->sampler_count == g->sampler_cap) {
        uint32_t cap = g->sampler_cap ? g->sampler_cap * 2 : 8;
        mvr_gpu_sampler *p = realloc(g->samplers, cap * sizeof *p);
        if (!p)
            return 0;
        g->samplers = p;
        g->sampler_cap = cap;
    }
    const mvr_gl_api_table *gl = r->gl;
    GLuint s = 0;
    gl->GenSamplers(1, &s);
    gl->SamplerParameteri(s, GL_TEXTURE_MAG_FILTER, (GLint)gl_filter(d->mag_filter, false));
    gl->SamplerParameteri(s, GL_TEXTURE_MIN_FILTER, (GLint)gl_filter(d->min_filter, true));
    gl->SamplerParameteri(s, GL_TEXTURE_WRAP_S, (GLint)gl_wrap(d->wrap_s));
    gl->SamplerParameteri(s, GL_TEXTURE_WRAP_T, (GLint)gl_wrap(d->wrap_t));
    g->samplers[g->sampler_count].desc = *d;
    g->samplers[g->sampler_count++].sampler = s;
    return s;
}

/* Whether any material samples the image with a mipmapped minification filter. */
static bool image_needs_mipmaps(const mvr_scene *s, uint32_t image)
{
    for (uint32_t i = 0; i < s->material_count; ++i) {
        const mvr_material_desc *m = &s->materials[i].desc;
        const mvr_texture_ref *roles[5] = {&m->base_color, &m->metallic_roughness, &m->normal, &m->occlusion,
                                           &m->emissive};
        for (int k = 0; k < 5; ++k)
            if (roles[k]->image.id == image + 1 && mvr_sampler_uses_mipmaps(&roles[k]->sampler))
                return true;
    }
    return false;
}

/* The GL texture of an image in a color space, uploaded on first use, with a
 * mip chain only where a sampler that reads it needs one. */
static GLuint texture_for(mvr_renderer *r, const mvr_scene *s, uint32_t image, bool srgb)
{
    mvr_gpu_scene *g = &r->gpu;
    for (uint32_t i = 0; i < g->texture_count; ++i)
        if (g->textures[i].image == image && g->textures[i].srgb == srgb)
            return g->textures[i].texture;
    if (g->texture_count == g->texture_cap) {
        uint32_t cap = g->texture_cap ? g->texture_cap * 2 : 16;
        mvr_gpu_texture *p = realloc(g->textures, cap * sizeof *p);
        if (!p)
            return 0;
        g->textures = p;
        g->texture_cap = cap;
    }
    const scene_image *img = &s->images[image];
    const mvr_gl_api_table *gl = r->gl;
    GLuint t = 0;
    gl->GenTextures(1, &t);
    mvr_state_texture(&r->state, 0, GL_TEXTURE_2D, t);
    bool mipmaps = image_needs_mipmaps(s, image);
    gl->TexStorage2D(GL_TEXTURE_2D, mipmaps ? (GLsizei)mvr_mip_levels(img->width, img->height) : 1,
                     srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, (GLsizei)img->width, (GLsizei)img->height);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    /* rows as stored, top first: glTF's uv (0, 0) is the image's top-left */
    gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, (GLsizei)img->width, (GLsizei)img->height, GL_RGBA,
                      GL_UNSIGNED_BYTE, img->rgba);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (mipmaps)
        gl->GenerateMipmap(GL_TEXTURE_2D);
    r->upload_bytes += (uint64_t)img->width * img->height * 4;
    g->textures[g->texture_count].image = image;
    g->textures[g->texture_count].srgb = srgb;
    g->textures[g->texture_count++].texture = t;
    return t;
}

/* Array path: one GL_TEXTURE_2D_ARRAY per plan group, layers in plan order,
 * white for a group's neutral layer; mips generated for the whole array. */
static mvr_result upload_arrays(mvr_renderer *r, const mvr_scene *s)
{
    mvr_gpu_scene *g = &r->gpu;
    const mvr_gl_api_table *gl = r->gl;
    mvr_result res = mvr_batch_plan_build(&g->plan, s, (uint32_t)r->ctx->caps.limits.max_array_texture_layers);
    if (res != MVR_OK)
        return mvr_renderer_fail(r, res, "batch plan: out of memory");
    for (uint32_t n = 0; n < g->plan.note_count; ++n)
        mvr_log(&r->logger, MVR_LOG_DEBUG, MVR_LOG_ID_GENERAL, "mvr: batch plan: %s", g->plan.notes[n]);
    uint32_t count = g->plan.group_count;
    g->group_textures = calloc(count ? count : 1, sizeof *g->group_textures);
    g->group_samplers = calloc(count ? count : 1, sizeof *g->group_samplers);
    if (!g->group_textures || !g->group_samplers)
        return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "texture arrays: out of memory");
    uint8_t *white = NULL;
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (uint32_t k = 0; k < count; ++k) {
        const mvr_texture_group *grp = &g->plan.groups[k];
        GLuint t = 0;
        gl->GenTextures(1, &t);
        g->group_textures[k] = t;
        mvr_state_texture(&r->state, 0, GL_TEXTURE_2D_ARRAY, t);
        gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, (GLsizei)grp->levels, grp->srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8,
                         (GLsizei)grp->width, (GLsizei)grp->height, (GLsizei)grp->layer_count);
        for (uint32_t layer = 0; layer < grp->layer_count; ++layer) {
            const uint8_t *pixels;
            uint32_t image = grp->layer_images[layer];
            if (image == MVR_NO_INDEX) {
                if (!white) {
                    size_t bytes = (size_t)grp->width * grp->height * 4;
                    white = malloc(bytes);
                    if (!white)
                        return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "texture arrays: out of memory");
                    memset(white, 255, bytes);
                } else {
                    uint8_t *w = realloc(white, (size_t)grp->width * grp->height * 4);
                    if (!w) {
                        free(white);
                        return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "texture arrays: out of memory");
                    }
                    white = w;
                    memset(white, 255, (size_t)grp->width * grp->height * 4);
                }
                pixels = white;
            } else {
                pixels = s->images[image].rgba;
            }
            gl->TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, (GLint)layer, (GLsizei)grp->width,
                              (GLsizei)grp->height, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
            r->upload_bytes += (uint64_t)grp->width * grp->height * 4;
        }
        if (grp->levels > 1)
            gl->GenerateMipmap(GL_TEXTURE_2D_ARRAY);
        g->group_samplers[k] = sampler_for(r, &grp->sampler);
    }
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    free(white);
    return MVR_OK;
}

static void release_arrays(mvr_renderer *r)
{
    mvr_gpu_scene *g = &r->gpu;
    for (uint32_t k = 0; g->group_textures && k < g->plan.group_count; ++k) {
        mvr_state_forget_texture(&r->state, g->group_textures[k]);
        r->gl->DeleteTextures(1, &g->group_textures[k]);
    }
    free(g->group_textures);
    free(g->group_samplers);
    g->group_textures = g->group_samplers = NULL;
    mvr_batch_plan_free(&g->plan);
}

static void release_geometry(mvr_renderer *r)
{
    mvr_gpu_scene *g = &r->gpu;
    const mvr_gl_api_table *gl = r->gl;
    for (uint32_t i = 0; i < g->primitive_count; ++i) {
        mvr_gpu_primitive *p = &g->primitives[i];
        mvr_state_forget_vao(&r->state, p->vao);
        mvr_state_forget_buffer(&r->state, p->vbo);
        gl->DeleteVertexArrays(1, &p->vao);
        gl->DeleteBuffers(1, &p->vbo);
        if (p->ibo)
            gl->DeleteBuffers(1, &p->ibo);
    }
    free(g->primitives);
    g->primitives = NULL;
    g->primitive_count = 0;
    release_arrays(r);
    for (uint32_t i = 0; i < g->texture_count; ++i) {
        mvr_state_forget_texture(&r->state, g->textures[i].texture);
        gl->DeleteTextures(1, &g->textures[i].texture);
    }
    g->texture_count = 0;
}

static mvr_result upload_geometry(mvr_renderer *r, const mvr_scene *s)
{
    mvr_gpu_scene *g = &r->gpu;
    const mvr_gl_api_table *gl = r->gl;
    release_geometry(r);
    if (s->primitive_count == 0)
        return MVR_OK;
    g->primitives = calloc(s->primitive_count, sizeof *g->primitives);
    if (!g->primitives)
        return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "upload: out of memory");
    g->primitive_count = s->primitive_count;
    for (uint32_t i = 0; i < s->primitive_count; ++i) {
        const scene_primitive *sp = &s->primitives[i];
        mvr_gpu_primitive *p = &g->primitives[i];
        /* attribute arrays back to back in one buffer, at the locations of mesh.vert.glsl */
        const struct { const float *data; GLint size; GLuint location; } attrs[] = {
            {sp->positions, 3, 0}, {sp->normals, 3, 1}, {sp->tangents, 4, 2},
            {sp->uv0, 2, 3}, {sp->uv1, 2, 4}, {sp->colors, 4, 5}};
        size_t total = 0;
        for (size_t a = 0; a < MVR_ARRAY_COUNT(attrs); ++a)
            if (attrs[a].data)
                total += (size_t)sp->vertex_count * (size_t)attrs[a].size * sizeof(float);
        /* staged and uploaded in one call: sub-data updates of a STATIC_DRAW
         * buffer are a slow path drivers warn about */
        uint8_t *staging = malloc(total ? total : 1);
        if (!staging)
            return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "upload: out of memory");
        size_t at = 0;
        for (size_t a = 0; a < MVR_ARRAY_COUNT(attrs); ++a) {
            if (!attrs[a].data)
                continue;
            size_t bytes = (size_t)sp->vertex_count * (size_t)attrs[a].size * sizeof(float);
            memcpy(staging + at, attrs[a].data, bytes);
            at += bytes;
        }
        gl->GenVertexArrays(1, &p->vao);
        mvr_state_vao(&r->state, p->vao);
        gl->GenBuffers(1, &p->vbo);
        mvr_state_array_buffer(&r->state, p->vbo);
        gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)total, staging, GL_STATIC_DRAW);
        free(staging);
        size_t offset = 0;
        for (size_t a = 0; a < MVR_ARRAY_COUNT(attrs); ++a) {
            if (!attrs[a].data)
                continue;
            size_t bytes = (size_t)sp->vertex_count * (size_t)attrs[a].size * sizeof(float);
            gl->EnableVertexAttribArray(attrs[a].location);
            gl->VertexAttribPointer(attrs[a].location, attrs[a].size, GL_FLOAT, GL_FALSE, 0,
                                    (const void *)(uintptr_t)offset);
            offset += bytes;
        }
        r->upload_bytes += total;
        p->mode = gl_mode(sp->mode);
        if (sp->indices) {
            gl->GenBuffers(1, &p->ibo);
            gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, p->ibo); /* VAO state */
            if (sp->small_indices) {
                uint16_t *idx = malloc((size_t)sp->index_count * sizeof *idx);
                if (!idx)
                    return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "upload: out of memory");
                for (uint32_t k = 0; k < sp->index_count; ++k)
                    idx[k] = (uint16_t)sp->indices[k];
                gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sp->index_count * sizeof *idx), idx,
                               GL_STATIC_DRAW);
                free(idx);
                p->index_type = GL_UNSIGNED_SHORT;
                r->upload_bytes += sp->index_count * 2u;
            } else {
                gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sp->index_count * sizeof(uint32_t)),
                               sp->indices, GL_STATIC_DRAW);
                p->index_type = GL_UNSIGNED_INT;
                r->upload_bytes += sp->index_count * 4u;
            }
            p->count = (GLsizei)sp->index_count;
        } else {
            p->count = (GLsizei)sp->vertex_count;
        }
    }
    mvr_state_vao(&r->state, 0);
    return MVR_OK;
}

static mvr_result upload_materials(mvr_renderer *r, const mvr_scene *s)
{
    mvr_gpu_scene *g = &r->gpu;
    const mvr_gl_api_table *gl = r->gl;
    uint32_t slots = s->material_count + 1; /* + the default material */
    free(g->materials);
    g->materials = calloc(slots, sizeof *g->materials);
    if (!g->materials)
        return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "materials: out of memory");
    g->material_count = slots;
    uint32_t cap = r->material_capacity;
    g->material_pages = (slots + cap - 1) / cap;
    GLsizeiptr page_bytes = (GLsizeiptr)cap * MVR_MATERIAL_BLOCK_SIZE;
    GLsizeiptr align = (GLsizeiptr)r->ubo_alignment;
    g->material_page_stride = (page_bytes + align - 1) / align * align;
    size_t total = (size_t)g->material_page_stride * g->material_pages;
    uint8_t *data = calloc(1, total);
    if (!data)
        return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "materials: out of memory");
    for (uint32_t i = 0; i < slots; ++i) {
        const mvr_material_desc *m = mvr_scene_material(s, i < s->material_count ? i : MVR_NO_INDEX);
        size_t at = (size_t)(i / cap) * (size_t)g->material_page_stride + (size_t)(i % cap) * MVR_MATERIAL_BLOCK_SIZE;
        mvr_material_pack(m, data + at);
        if (g->arrays) {
            /* the array layers of each role (std140: ivec4 layers at 48, extra.x at 64) */
            const mvr_material_slots *ms = &g->plan.materials[i];
            int32_t layers[4], emissive;
            for (int k = 0; k < 4; ++k)
                layers[k] = ms->layer[k] == MVR_NO_GROUP ? 0 : ms->layer[k];
            emissive = ms->layer[4] == MVR_NO_GROUP ? 0 : ms->layer[4];
            memcpy(data + at + 48, layers, sizeof layers);
            memcpy(data + at + 64, &emissive, sizeof emissive);
            continue;
        }
        const mvr_texture_ref *roles[5] = {&m->base_color, &m->metallic_roughness, &m->normal,
                                           &m->occlusion, &m->emissive};
        for (int k = 0; k < 5; ++k) {
            if (!roles[k]->image.id)
                continue;
            bool srgb = k == 0 || k == 4; /* base color and emissive are sRGB (glTF 2.0 3.9.2) */
            g->materials[i].textures[k] = texture_for(r, s, roles[k]->image.id - 1, srgb);
            g->materials[i].samplers[k] = sampler_for(r, &roles[k]->sampler);
            if (!g->materials[i].textures[k] || !g->materials[i].samplers[k]) {
                free(data);
                return mvr_renderer_fail(r, MVR_ERROR_OUT_OF_MEMORY, "textures: out of memory");
            }
        }
    }
    if (!g->material_ubo)
        gl->GenBuffers(1, &g->material_ubo);
    gl->BindBuffer(GL_UNIFORM_BUFFER, g->material_ubo);
    gl->BufferData(GL_UNIFORM_BUFFER, (GLsizeiptr)total, data, GL_STATIC_DRAW);
    /* BufferData gives the name new storage; a cached range of it is stale */
    mvr_state_forget_buffer(&r->state, g->material_ubo);
    r->upload_bytes += total;
    free(data);
    return MVR_OK;
}

mvr_result mvr_gpu_scene_sync(mvr_renderer *r, const mvr_scene *s)
{
    mvr_gpu_scene *g = &r->gpu;
    bool same_scene = g->scene == s && g->scene_serial == mvr_scene_serial(s);
    if (!same_scene) {
        mvr_gpu_scene_release(r);
        g->scene = s;
        g->scene_serial = mvr_scene_serial(s);
    }
    mvr_result res = MVR_OK;
    bool arrays = r->material_path == MVR_MATERIAL_PATH_ARRAYS;
    bool geometry = !same_scene || g->geometry_version != s->geometry_version;
    bool materials = geometry || g->material_version != s->material_version;
    if (geometry) {
        res = upload_geometry(r, s);
        if (res != MVR_OK)
            return res;
        g->geometry_version = s->geometry_version;
    }
    if (materials && arrays) {
        /* the plan depends on images and materials: rebuilt with either */
        release_arrays(r);
        res = upload_arrays(r, s);
        if (res != MVR_OK)
            return res;
    }
    g->arrays = arrays;
    if (materials) {
        res = upload_materials(r, s);
        if (res != MVR_OK)
            return res;
        g->material_version = s->material_version;
    }
    return mvr_gl_check(r->ctx, "scene upload", false);
}

void mvr_gpu_scene_release(mvr_renderer *r)
{
    mvr_gpu_scene *g = &r->gpu;
    const mvr_gl_api_table *gl = r->gl;
    release_geometry(r);
    free(g->textures);
    for (uint32_t i = 0; i < g->sampler_count; ++i)
        gl->DeleteSamplers(1, &g->samplers[i].sampler);
    free(g->samplers);
    free(g->materials);
    if (g->material_ubo) {
        mvr_state_forget_buffer(&r->state, g->material_ubo);
        gl->DeleteBuffers(1, &g->material_ubo);
    }
    memset(g, 0, sizeof *g);
}
