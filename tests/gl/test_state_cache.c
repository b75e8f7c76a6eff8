/* gl: the state cache agrees with the GL after an object it holds is
 * deleted. GL unbinds a deleted texture, sampler, buffer, framebuffer or
 * vertex array wherever the context has it bound; a cache that still holds
 * the name skips the next bind of that name, and a GL that hands deleted
 * names out again (NVIDIA's does at once; Mesa counts up) then draws with
 * nothing bound. Each kind: bound through the cache, deleted as
 * mvr_gl_delete does (forget, then glDelete*), the cache's entry compared
 * with what the GL reports, and a new object bound through the cache must
 * be what the GL has bound, whatever name it got. */
#include "gl/gl_test_util.h"
#include "state_cache.h"

#define UNIT 3

static GLint get_int(const mvr_gl_api_table *gl, GLenum what)
{
    GLint v = -1;
    gl->GetIntegerv(what, &v);
    return v;
}

static void deleted_objects_leave_the_cache(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_gl_api_table *gl = &ctx->gl;
    mvr_state_cache s;
    memset(&s, 0, sizeof s);
    mvr_state_init(&s, gl, true); /* a fresh context: GL's initial state */

    /* sampler */
    GLuint a = 0, b = 0;
    gl->GenSamplers(1, &a);
    mvr_state_sampler(&s, UNIT, a);
    mvr_state_forget_sampler(&s, a);
    gl->DeleteSamplers(1, &a);
    gl->ActiveTexture(GL_TEXTURE0 + UNIT);
    CHECK_EQ_INT(t, get_int(gl, GL_SAMPLER_BINDING), 0);
    CHECK_MSG(t, s.samplers[UNIT] == 0, "the cache still holds deleted sampler %u on unit %d", a, UNIT);
    gl->GenSamplers(1, &b);
    mvr_state_sampler(&s, UNIT, b);
    gl->ActiveTexture(GL_TEXTURE0 + UNIT);
    CHECK_EQ_INT(t, get_int(gl, GL_SAMPLER_BINDING), (GLint)b);
    gl->DeleteSamplers(1, &b);
    mvr_state_forget_sampler(&s, b);

    /* texture */
    gl->GenTextures(1, &a);
    mvr_state_texture(&s, UNIT, GL_TEXTURE_2D, a);
    mvr_state_forget_texture(&s, a);
    gl->DeleteTextures(1, &a);
    gl->ActiveTexture(GL_TEXTURE0 + UNIT);
    CHECK_EQ_INT(t, get_int(gl, GL_TEXTURE_BINDING_2D), 0);
    CHECK_MSG(t, s.textures[UNIT] == 0, "the cache still holds deleted texture %u", a);
    gl->GenTextures(1, &b);
    mvr_state_texture(&s, UNIT, GL_TEXTURE_2D, b);
    gl->ActiveTexture(GL_TEXTURE0 + UNIT);
    s.active_unit = UNIT; /* what the test just did behind the cache's back */
    CHECK_EQ_INT(t, get_int(gl, GL_TEXTURE_BINDING_2D), (GLint)b);
    mvr_state_forget_texture(&s, b);
    gl->DeleteTextures(1, &b);

    /* uniform buffer range */
    gl->GenBuffers(1, &a);
    gl->BindBuffer(GL_UNIFORM_BUFFER, a);
    gl->BufferData(GL_UNIFORM_BUFFER, 256, NULL, GL_DYNAMIC_DRAW);
    mvr_state_ubo_range(&s, 1, a, 0, 256);
    mvr_state_forget_buffer(&s, a);
    gl->DeleteBuffers(1, &a);
    GLint bound = -1;
    gl->GetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 1, &bound);
    CHECK_EQ_INT(t, bound, 0);
    CHECK_MSG(t, s.ubo[1].buffer == 0, "the cache still holds deleted buffer %u", a);
    gl->GenBuffers(1, &b);
    gl->BindBuffer(GL_UNIFORM_BUFFER, b);
    gl->BufferData(GL_UNIFORM_BUFFER, 256, NULL, GL_DYNAMIC_DRAW);
    mvr_state_ubo_range(&s, 1, b, 0, 256);
    gl->GetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 1, &bound);
    CHECK_EQ_INT(t, bound, (GLint)b);
    mvr_state_forget_buffer(&s, b);
    gl->DeleteBuffers(1, &b);

    /* framebuffer and vertex array */
    gl->GenFramebuffers(1, &a);
    mvr_state_draw_framebuffer(&s, a);
    mvr_state_forget_framebuffer(&s, a);
    gl->DeleteFramebuffers(1, &a);
    CHECK_EQ_INT(t, get_int(gl, GL_DRAW_FRAMEBUFFER_BINDING), 0);
    CHECK(t, s.draw_fbo == 0);
    gl->GenVertexArrays(1, &a);
    mvr_state_vao(&s, a);
    mvr_state_forget_vao(&s, a);
    gl->DeleteVertexArrays(1, &a);
    CHECK_EQ_INT(t, get_int(gl, GL_VERTEX_ARRAY_BINDING), 0);
    CHECK(t, s.vao == 0);

    CHECK_EQ_INT(t, gl->GetError(), GL_NO_ERROR);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(deleted_objects_leave_the_cache))
