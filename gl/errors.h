/* The renderer's error and allocation layer, shared by every gl/ file that
 * works for a renderer: failures recorded on the renderer, GL allocation
 * checks, deferred deletes and the begin / end of a public call. */
#ifndef MVR_ERRORS_H
#define MVR_ERRORS_H

#include "context_internal.h"

/* Records a failure on the renderer (mvr_renderer_last_error, its logger,
 * its failure count). Returns result. */
mvr_result mvr_gl_fail(mvr_renderer *r, mvr_result result, const char *fmt, ...) MVR_PRINTF(3, 4);

/* Every public call that touches GL starts with begin (the renderer's
 * context alive and current, the application's pending GL errors dropped)
 * and ends with end, which fails the call if mvr's own work left a GL error
 * (release builds too), so no call returns MVR_OK with one pending. */
mvr_result mvr_gl_call_begin(mvr_renderer *r, const char *where);
mvr_result mvr_gl_call_end(mvr_renderer *r, const char *where, mvr_result res);

/* After a GL allocation (storage of a texture, buffer or renderbuffer, or a
 * framebuffer's attachments): fails naming the object (printf-style), with
 * MVR_ERROR_OUT_OF_MEMORY for GL_OUT_OF_MEMORY, else MVR_ERROR_GL. */
mvr_result mvr_gl_check_alloc(mvr_renderer *r, const char *fmt, ...) MVR_PRINTF(2, 3);

/* Deletes a GL object of the renderer's (forgotten by the state cache) and
 * zeroes *name: now when the context is current, later when it is not,
 * never once the context is gone. */
void mvr_gl_delete(mvr_renderer *r, mvr_gl_object kind, GLuint *name);

#endif
