/* gl: the capability probe. Under CI (CI=true) or MVR_REQUIRE_MULTIVIEW=1 the
 * multiview path must be available: a machine that silently lacks it would
 * test only the fallback. */
#include "gl_test_util.h"

static void require_multiview(mvr_test_state *t, mvr_context_provider provider)
{
    if (provider == MVR_CONTEXT_PROVIDER_OSMESA && !mvr_context_provider_built(provider))
        SKIP(t, "this build has no OSMesa provider");
    mvr_context *ctx = create_or_report(t, provider, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_caps *c = mvr_context_caps(ctx);
    printf("  %s: %s, GL_OVR_multiview2 %s, GL_MAX_VIEWS_OVR %d\n",
           mvr_context_provider_name(provider), c->version, c->ext.ovr_multiview2 ? "yes" : "no",
           c->limits.max_views_ovr);
    if (!c->ext.ovr_multiview2 && !mvr_test_in_ci()) {
        mvr_context_destroy(ctx);
        SKIP(t, "GL_OVR_multiview2 missing on this GL; required under CI=true");
    }
    CHECK_MSG(t, c->ext.ovr_multiview2,
              "GL_OVR_multiview2 is missing on %s (%s): CI must exercise the multiview path. "
              "Run scripts/setup (Mesa >= 25 from Debian backports).",
              c->renderer, c->version);
    CHECK_MSG(t, c->limits.max_views_ovr >= 2, "GL_MAX_VIEWS_OVR = %d", c->limits.max_views_ovr);
    /* an extension counts only with its entry points */
    CHECK(t, !c->ext.ovr_multiview || ctx->gl.FramebufferTextureMultiviewOVR != NULL);
    mvr_context_destroy(ctx);
}

static void multiview_on_surfaceless(mvr_test_state *t)
{
    require_multiview(t, MVR_CONTEXT_PROVIDER_SURFACELESS);
}

static void multiview_on_osmesa(mvr_test_state *t)
{
    require_multiview(t, MVR_CONTEXT_PROVIDER_OSMESA);
}

/* Every reported extension has its entry points; limits agree with GL. */
static void caps_agree_with_the_gl(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_caps *c = mvr_context_caps(ctx);
    const mvr_gl_api_table *gl = &ctx->gl;
    CHECK(t, !c->ext.ext_clip_control || gl->ClipControl);
    CHECK(t, !c->ext.ext_disjoint_timer_query || (gl->QueryCounter && gl->GetQueryObjectui64v));
    CHECK(t, !c->ext.khr_debug || gl->DebugMessageCallback);
    CHECK(t, !c->ext.ovr_multiview_multisampled_render_to_texture ||
                 gl->FramebufferTextureMultisampleMultiviewOVR);
    CHECK(t, !c->ext.ovr_multiview2 || c->ext.ovr_multiview);
    CHECK(t, c->ext.ovr_multiview == (c->limits.max_views_ovr > 0));
    GLint v = 0;
    gl->GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &v);
    CHECK_EQ_INT(t, c->limits.max_array_texture_layers, v);
    gl->GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &v);
    CHECK_EQ_INT(t, c->limits.uniform_buffer_offset_alignment, v);
    CHECK(t, c->ext.etc2); /* core in GLES 3.0 */
    CHECK(t, c->limits.max_anisotropy >= 1.0f);
    /* the probe leaves no GL error and no binding behind */
    CHECK_EQ_INT(t, gl->GetError(), GL_NO_ERROR);
    gl->GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &v);
    CHECK_EQ_INT(t, v, 0);
    /* llvmpipe's known quirks are flagged on llvmpipe and nowhere else;
     * mediump below fp32 also where the driver reports it (NVIDIA's GLES) */
    bool llvmpipe = strstr(c->renderer, "llvmpipe") != NULL;
    GLint range[2] = {0, 0}, precision = 23;
    gl->GetShaderPrecisionFormat(GL_FRAGMENT_SHADER, GL_MEDIUM_FLOAT, range, &precision);
    CHECK_EQ_INT(t, c->bugs.mediump_is_fp16, llvmpipe || (precision > 0 && precision < 23));
    CHECK_EQ_INT(t, c->bugs.multiview_pass_defers_raster, llvmpipe && c->ext.ovr_multiview);
    CHECK_EQ_INT(t, c->bugs.half_float_sampling_slow, llvmpipe);
    CHECK(t, !llvmpipe || c->is_software);
    mvr_context_destroy(ctx);
}

/* The MSAA-array probe agrees with what actually happens when we try. */
static void msaa_array_probe_matches_behaviour(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_caps *c = mvr_context_caps(ctx);
    if (!c->ext.ovr_multiview || !ctx->gl.TexStorage3DMultisample || c->limits.max_samples < 4) {
        mvr_context_destroy(ctx);
        SKIP(t, "no multiview or no multisampled array textures here");
    }
    const mvr_gl_api_table *gl = &ctx->gl;
    GLuint tex = 0, fbo = 0;
    gl->GenTextures(1, &tex);
    gl->BindTexture(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, tex);
    gl->TexStorage3DMultisample(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, 4, GL_RGBA8, 16, 16, 2, GL_TRUE);
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, tex, 0, 0, 2);
    bool works = gl->GetError() == GL_NO_ERROR &&
                 gl->CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    while (gl->GetError() != GL_NO_ERROR) {
    }
    printf("  multisampled 2D array under multiview: %s\n", works ? "works" : "refused");
    CHECK_EQ_INT(t, c->ext.multiview_msaa_array, works);
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteTextures(1, &tex);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(multiview_on_surfaceless), TEST(multiview_on_osmesa),
              TEST(caps_agree_with_the_gl), TEST(msaa_array_probe_matches_behaviour))
