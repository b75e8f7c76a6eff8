/* A scene's geometry on the GPU: per primitive one vertex buffer (its
 * attributes back to back), its vertex array and its index buffer. */
#include <stdlib.h>
#include <string.h>

#include "errors.h"
#include "gpu_scene.h"
#include "renderer.h"

static GLenum gl_mode(mvr_primitive_mode m)
{
    switch (m) {
    case MVR_PRIMITIVE_TRIANGLES: return GL_TRIANGLES;
    case MVR_PRIMITIVE_LINES: return GL_LINES;
    case MVR_PRIMITIVE_POINTS: return GL_POINTS;
    }
    return GL_TRIANGLES;
}

/* The primitive's index buffer (16-bit indices where they fit), bound to
 * its vertex array; or its vertex count, drawn without indices. */
static mvr_result upload_indices(mvr_renderer *r, const scene_primitive *sp, mvr_gpu_primitive *p, uint32_t i)
{
    const mvr_gl_api_table *gl = r->gl;
    if (sp->indices) {
        gl->GenBuffers(1, &p->ibo);
        gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, p->ibo); /* VAO state */
        if (sp->small_indices) {
            uint16_t *idx = malloc((size_t)sp->index_count * sizeof *idx);
            if (!idx) {
                mvr_state_vao(&r->state, 0);
                return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "upload: out of memory");
            }
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
        mvr_result ires = mvr_gl_check_alloc(r, "index buffer of primitive %u (%u indices)", i,
                                             sp->index_count);
        if (ires != MVR_OK) {
            mvr_state_vao(&r->state, 0);
            return ires;
        }
    } else {
        p->count = (GLsizei)sp->vertex_count;
    }
    return MVR_OK;
}

/* One primitive: its vertex buffer and vertex array, then its indices. */
static mvr_result upload_primitive(mvr_renderer *r, const mvr_scene *s, uint32_t i)
{
    const mvr_gl_api_table *gl = r->gl;
    const scene_primitive *sp = &s->primitives[i];
    mvr_gpu_primitive *p = &r->gpu.primitives[i];
    /* attribute arrays back to back in one buffer, at the locations of mesh.vert.glsl */
    const struct { const float *data; GLint size; GLuint location; } attrs[] = {
        {sp->positions, 3, 0}, {sp->normals, 3, 1}, {sp->tangents, 4, 2},
        {sp->uv0, 2, 3}, {sp->uv1, 2, 4}, {sp->colors, 4, 5}};
    /* skinning (deform.glsl): joints as integers, weights as floats */
    const struct { const void *data; size_t bytes; GLuint location; bool joints; } skin[] = {
        {sp->joints[0], sizeof(uint16_t), 6, true}, {sp->weights[0], sizeof(float), 7, false},
        {sp->joints[1], sizeof(uint16_t), 8, true}, {sp->weights[1], sizeof(float), 9, false}};
    size_t total = 0;
    for (size_t a = 0; a < MVR_ARRAY_COUNT(attrs); ++a)
        if (attrs[a].data)
            total += (size_t)sp->vertex_count * (size_t)attrs[a].size * sizeof(float);
    for (size_t a = 0; a < MVR_ARRAY_COUNT(skin); ++a)
        if (skin[a].data)
            total += (size_t)sp->vertex_count * 4 * skin[a].bytes;
    /* staged and uploaded in one call: sub-data updates of a STATIC_DRAW
     * buffer are a slow path drivers warn about */
    uint8_t *staging = malloc(total ? total : 1);
    if (!staging)
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "upload: out of memory");
    size_t at = 0;
    for (size_t a = 0; a < MVR_ARRAY_COUNT(attrs); ++a) {
        if (!attrs[a].data)
            continue;
        size_t bytes = (size_t)sp->vertex_count * (size_t)attrs[a].size * sizeof(float);
        memcpy(staging + at, attrs[a].data, bytes);
        at += bytes;
    }
    for (size_t a = 0; a < MVR_ARRAY_COUNT(skin); ++a) {
        if (!skin[a].data)
            continue;
        size_t bytes = (size_t)sp->vertex_count * 4 * skin[a].bytes;
        memcpy(staging + at, skin[a].data, bytes);
        at += bytes;
    }
    gl->GenVertexArrays(1, &p->vao);
    mvr_state_vao(&r->state, p->vao);
    gl->GenBuffers(1, &p->vbo);
    mvr_state_array_buffer(&r->state, p->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)total, staging, GL_STATIC_DRAW);
    free(staging);
    mvr_result res = mvr_gl_check_alloc(r, "vertex buffer of primitive %u (%u vertices, %zu bytes)", i,
                                        sp->vertex_count, total);
    if (res != MVR_OK) {
        mvr_state_vao(&r->state, 0);
        return res;
    }
    size_t offset = 0;
    for (size_t a = 0; a < MVR_ARRAY_COUNT(attrs); ++a) {
        if (!attrs[a].data)
            continue;
        size_t bytes = (size_t)sp->vertex_count * (size_t)attrs[a].size * sizeof(float);
        gl->EnableVertexAttribArray(attrs[a].location);
        gl->VertexAttribPointer(attrs[a].location, attrs[a].size, GL_FLOAT, GL_FALSE, 0,
                                (const void *)(uintptr_t)offset);
        p->attributes |= 1u << attrs[a].location;
        p->attribute_offset[attrs[a].location] = (GLintptr)offset;
        offset += bytes;
    }
    for (size_t a = 0; a < MVR_ARRAY_COUNT(skin); ++a) {
        if (!skin[a].data)
            continue;
        gl->EnableVertexAttribArray(skin[a].location);
        if (skin[a].joints)
            gl->VertexAttribIPointer(skin[a].location, 4, GL_UNSIGNED_SHORT, 0, (const void *)(uintptr_t)offset);
        else
            gl->VertexAttribPointer(skin[a].location, 4, GL_FLOAT, GL_FALSE, 0, (const void *)(uintptr_t)offset);
        p->attributes |= 1u << skin[a].location;
        p->attribute_offset[skin[a].location] = (GLintptr)offset;
        offset += (size_t)sp->vertex_count * 4 * skin[a].bytes;
    }
    r->upload_bytes += total;
    p->mode = gl_mode(sp->mode);
    return upload_indices(r, sp, p, i);
}

mvr_result mvr_gpu_primitives_upload(mvr_renderer *r, const mvr_scene *s)
{
    mvr_gpu_scene *g = &r->gpu;
    if (s->primitive_count == 0)
        return MVR_OK;
    g->primitives = calloc(s->primitive_count, sizeof *g->primitives);
    if (!g->primitives)
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "upload: out of memory");
    g->primitive_count = s->primitive_count;
    for (uint32_t i = 0; i < s->primitive_count; ++i) {
        mvr_result res = upload_primitive(r, s, i);
        if (res != MVR_OK)
            return res;
    }
    mvr_state_vao(&r->state, 0);
    return MVR_OK;
}

void mvr_gpu_primitives_release(mvr_renderer *r)
{
    mvr_gpu_scene *g = &r->gpu;
    for (uint32_t i = 0; i < g->primitive_count; ++i) {
        mvr_gpu_primitive *p = &g->primitives[i];
        mvr_gl_delete(r, MVR_GL_VERTEX_ARRAY, &p->vao);
        mvr_gl_delete(r, MVR_GL_BUFFER, &p->vbo);
        mvr_gl_delete(r, MVR_GL_BUFFER, &p->ibo);
    }
    free(g->primitives);
    g->primitives = NULL;
    g->primitive_count = 0;
}
