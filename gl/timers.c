/* The renderer's GPU timer: two GL_TIMESTAMP queries around a frame's
 * passes, read into stats.gpu_ms. */
#include <string.h>

#include "errors.h"
#include "renderer.h"
#include "timers.h"

void mvr_timer_init(mvr_renderer *r)
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

void mvr_timer_start(mvr_renderer *r)
{
    if (r->timer.timestamps) {
        mvr_state_draw_framebuffer(&r->state, 0); /* never time with a multiview FBO bound */
        r->gl->QueryCounter(r->timer.queries[0], GL_TIMESTAMP_EXT);
    }
}

void mvr_timer_stop(mvr_renderer *r, bool ok)
{
    if (r->timer.timestamps) {
        mvr_state_draw_framebuffer(&r->state, 0);
        r->gl->QueryCounter(r->timer.queries[1], GL_TIMESTAMP_EXT);
        r->timer.pending = ok;
    }
}

void mvr_timer_read(mvr_renderer *r)
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

void mvr_timer_release(mvr_renderer *r)
{
    if (r->timer.timestamps)
        for (int i = 0; i < 2; ++i)
            mvr_gl_delete(r, MVR_GL_QUERY, &r->timer.queries[i]);
    r->timer.timestamps = r->timer.pending = false;
}
