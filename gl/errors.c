/* The renderer's error and allocation layer (gl/errors.h). */
#include <stdarg.h>

#include "errors.h"
#include "renderer.h"

mvr_result mvr_gl_fail(mvr_renderer *r, mvr_result result, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    mvr_error_record(r->last_error, sizeof r->last_error, &r->logger, result, fmt, ap);
    va_end(ap);
    r->failures++;
    return result;
}

mvr_result mvr_gl_call_begin(mvr_renderer *r, const char *where)
{
    if (!r->ctx)
        return mvr_gl_fail(r, MVR_ERROR_CONTEXT, "%s: the renderer's context was destroyed", where);
    mvr_result res = mvr_context_begin(r->ctx, where);
    if (res != MVR_OK)
        return mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    return MVR_OK;
}

mvr_result mvr_gl_call_end(mvr_renderer *r, const char *where, mvr_result res)
{
    /* always drained, so a failed call leaves no error behind either */
    mvr_result checked = mvr_gl_check(r->ctx, where, true);
    if (res == MVR_OK && checked != MVR_OK)
        res = mvr_gl_fail(r, checked, "%s", mvr_context_last_error(r->ctx));
    return res;
}

mvr_result mvr_gl_check_alloc(mvr_renderer *r, const char *fmt, ...)
{
    char what[256];
    va_list ap;
    va_start(ap, fmt);
    mvr_str_vformat(what, sizeof what, fmt, ap);
    va_end(ap);
    mvr_result res = mvr_gl_check(r->ctx, what, true);
    if (res != MVR_OK)
        return mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    return MVR_OK;
}

void mvr_gl_delete(mvr_renderer *r, mvr_gl_object kind, GLuint *name)
{
    if (!*name)
        return;
    switch (kind) {
    case MVR_GL_TEXTURE: mvr_state_forget_texture(&r->state, *name); break;
    case MVR_GL_BUFFER: mvr_state_forget_buffer(&r->state, *name); break;
    case MVR_GL_FRAMEBUFFER: mvr_state_forget_framebuffer(&r->state, *name); break;
    case MVR_GL_VERTEX_ARRAY: mvr_state_forget_vao(&r->state, *name); break;
    case MVR_GL_PROGRAM: mvr_state_forget_program(&r->state, *name); break;
    case MVR_GL_SAMPLER: mvr_state_forget_sampler(&r->state, *name); break;
    case MVR_GL_RENDERBUFFER:
    case MVR_GL_QUERY:
    case MVR_GL_SYNC:
        break;
    }
    if (r->ctx)
        mvr_context_delete(r->ctx, kind, *name);
    *name = 0;
}

const char *mvr_renderer_last_error(const mvr_renderer *r)
{
    return r ? r->last_error : "mvr_renderer_last_error: renderer is NULL";
}
