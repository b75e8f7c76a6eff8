/* Capability probe: version, extensions (counted only when their entry points
 * resolved), limits, and known driver bugs. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context_internal.h"

#ifndef GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT
#define GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT 0x84FF
#endif

typedef struct ext_list {
    const char **names;
    int count;
} ext_list;

static bool has(const ext_list *l, const char *name)
{
    for (int i = 0; i < l->count; ++i)
        if (l->names[i] && strcmp(l->names[i], name) == 0)
            return true;
    return false;
}

static bool version_at_least(const mvr_caps *c, int major, int minor)
{
    return c->gl_major > major || (c->gl_major == major && c->gl_minor >= minor);
}

static void copy_gl_string(mvr_context *ctx, GLenum name, char *dst, size_t size)
{
    const GLubyte *s = ctx->gl.GetString(name);
    mvr_str_copy(dst, size, s ? (const char *)s : "");
}

/* An advertised extension whose entry points are missing does not count. */
static bool with_entry_points(mvr_context *ctx, bool advertised, bool resolved, const char *name)
{
    if (advertised && !resolved)
        mvr_log(&ctx->logger, MVR_LOG_WARNING, MVR_LOG_ID_EXTENSION_DROPPED,
                "mvr: %s is advertised but its entry points did not resolve; not used", name);
    return advertised && resolved;
}

/* glGetIntegerv that leaves no error behind for a pname this GL lacks. */
static int get_int(mvr_context *ctx, GLenum pname)
{
    GLint v = 0;
    ctx->gl.GetIntegerv(pname, &v);
    if (ctx->gl.GetError() != GL_NO_ERROR)
        return 0;
    return (int)v;
}

/* Tries glFramebufferTextureMultiviewOVR on a tiny texture of `target` (made
 * by alloc) at `level`: true when it attaches without error and completes.
 * The bindings it touches are restored. */
static bool multiview_attaches(mvr_context *ctx, GLenum target, GLenum binding,
                               void (*alloc)(const mvr_gl_api_table *gl), GLint level)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    GLint old_fbo = 0, old_tex = 0;
    gl->GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &old_fbo);
    gl->GetIntegerv(binding, &old_tex);
    GLuint tex = 0, fbo = 0;
    gl->GenTextures(1, &tex);
    gl->BindTexture(target, tex);
    alloc(gl);
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, tex, level, 0, 2);
    bool ok = gl->GetError() == GL_NO_ERROR &&
              gl->CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    mvr_gl_clear_errors(gl);
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)old_fbo);
    gl->BindTexture(target, (GLuint)old_tex);
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteTextures(1, &tex);
    return ok;
}

static void alloc_msaa_array(const mvr_gl_api_table *gl)
{
    gl->TexStorage3DMultisample(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, 2, GL_RGBA8, 4, 4, 2, GL_TRUE);
}

static void alloc_mipped_array(const mvr_gl_api_table *gl)
{
    gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, 2, GL_RGBA8, 4, 4, 2);
}

/* Does a multisampled 2D array attach with glFramebufferTextureMultiviewOVR? */
static bool probe_multiview_msaa_array(mvr_context *ctx)
{
    bool core = ctx->caps.api == MVR_GL_API_GLES ? version_at_least(&ctx->caps, 3, 2)
                                                 : version_at_least(&ctx->caps, 4, 2);
    if (!ctx->caps.ext.ovr_multiview || !core || !ctx->gl.TexStorage3DMultisample ||
        ctx->caps.limits.max_samples < 2)
        return false;
    return multiview_attaches(ctx, GL_TEXTURE_2D_MULTISAMPLE_ARRAY, GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY,
                              alloc_msaa_array, 0);
}

/* Does glFramebufferTextureMultiviewOVR accept a mip level other than 0?
 * The extension allows any level of the texture, but Mesa 25 answers
 * GL_INVALID_OPERATION (measured here). */
static bool probe_multiview_level_zero_only(mvr_context *ctx)
{
    if (!ctx->caps.ext.ovr_multiview)
        return false;
    return !multiview_attaches(ctx, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BINDING_2D_ARRAY, alloc_mipped_array, 1);
}

static void probe_bugs(mvr_context *ctx)
{
    mvr_caps *c = &ctx->caps;
    bool llvmpipe = strstr(c->renderer, "llvmpipe") != NULL;

    /* Timer queries while a multiview framebuffer is bound give undefined
     * results (seen on Mesa; no driver promises otherwise), so GPU timing
     * brackets multiview passes from outside, never inside. All drivers. */
    c->bugs.timer_query_in_multiview_undefined = c->ext.ovr_multiview;

    /* llvmpipe really computes mediump in fp16 (measured here), and so does
     * NVIDIA's GLES driver (the stress suite's probe on an H100, driver 580:
     * 2049 + 1 = 2048): a mediump world position or depth visibly loses
     * precision. mvr declares highp in every stage; the flag lets tests check
     * that this stays so. Besides llvmpipe's name, a driver that reports less
     * than fp32's 23 mantissa bits for a fragment mediump float says so itself
     * (GLES 3.0 4.5.2 asks only 10). */
    GLint range[2] = {0, 0}, precision = 23;
    ctx->gl.GetShaderPrecisionFormat(GL_FRAGMENT_SHADER, GL_MEDIUM_FLOAT, range, &precision);
    if (ctx->gl.GetError() != GL_NO_ERROR)
        precision = 23;
    c->bugs.mediump_is_fp16 = llvmpipe || (precision > 0 && precision < 23);

    /* llvmpipe bins a whole multiview pass as one scene and starts
     * rasterizing at its end, so a per-view loop overlaps one view's
     * rasterization with the next view's submission; measured on the
     * benchmark's matrix it is as fast or faster in wall time (auto takes
     * the loop here: gl/renderer.c, auto_view_path). */
    c->bugs.multiview_pass_defers_raster = llvmpipe && c->ext.ovr_multiview;

    /* llvmpipe filters a half float texture on its float path after
     * converting each texel it fetches, where a float texture's texels are
     * used as they are: fetches from the environment's RGBA16F specular
     * chain and RG16F DFG table cost more than from the same values as
     * 32-bit floats (docs/benchmarks.md, "Half floats"). Both are then
     * widened once made (gl/environment.c, widen_texture). */
    c->bugs.half_float_sampling_slow = llvmpipe;

    /* Targets at a mip level other than 0 then take the loop path. */
    c->bugs.multiview_level_zero_only = probe_multiview_level_zero_only(ctx);
    if (c->bugs.multiview_level_zero_only)
        mvr_log(&ctx->logger, MVR_LOG_DEBUG, MVR_LOG_ID_DRIVER_BUG,
                "mvr: %s attaches only mip level 0 with multiview; other levels use the loop path",
                c->renderer);

    if (c->bugs.mediump_is_fp16)
        mvr_log(&ctx->logger, MVR_LOG_DEBUG, MVR_LOG_ID_DRIVER_BUG,
                "mvr: %s computes mediump in fp16; shaders are highp throughout", c->renderer);
}

void mvr_caps_probe(mvr_context *ctx)
{
    mvr_caps *c = &ctx->caps;
    const mvr_gl_api_table *gl = &ctx->gl;
    bool desktop = c->api == MVR_GL_API_DESKTOP;

    /* Leave an application's pending errors alone in the log, not in our results. */
    mvr_gl_clear_errors(gl);
    copy_gl_string(ctx, GL_VENDOR, c->vendor, sizeof c->vendor);
    copy_gl_string(ctx, GL_RENDERER, c->renderer, sizeof c->renderer);
    copy_gl_string(ctx, GL_VERSION, c->version, sizeof c->version);
    copy_gl_string(ctx, GL_SHADING_LANGUAGE_VERSION, c->glsl_version, sizeof c->glsl_version);
    c->gl_major = get_int(ctx, GL_MAJOR_VERSION);
    c->gl_minor = get_int(ctx, GL_MINOR_VERSION);
    if (c->gl_major == 0) {
        /* GL 2 / ES 2 have no GL_MAJOR_VERSION: parse "OpenGL ES 2.0 ..." or "2.1 ...". */
        const char *v = strstr(c->version, "OpenGL ES ");
        v = v ? v + 10 : c->version;
        if (sscanf(v, "%d.%d", &c->gl_major, &c->gl_minor) != 2)
            c->gl_major = c->gl_minor = 0;
    }
    static const char *const software[] = {"llvmpipe", "softpipe", "SwiftShader", "lavapipe"};
    for (size_t i = 0; i < MVR_ARRAY_COUNT(software); ++i)
        if (strstr(c->renderer, software[i]))
            c->is_software = true;

    ext_list exts = {NULL, get_int(ctx, GL_NUM_EXTENSIONS)};
    if (exts.count > 0) {
        exts.names = calloc((size_t)exts.count, sizeof *exts.names);
        if (!exts.names)
            exts.count = 0;
        for (int i = 0; i < exts.count; ++i)
            exts.names[i] = (const char *)gl->GetStringi(GL_EXTENSIONS, (GLuint)i);
    }

    mvr_caps_ext *e = &c->ext;
    e->ovr_multiview = with_entry_points(ctx, has(&exts, "GL_OVR_multiview"),
                                         gl->FramebufferTextureMultiviewOVR != NULL,
                                         "GL_OVR_multiview");
    e->ovr_multiview2 = e->ovr_multiview && has(&exts, "GL_OVR_multiview2");
    e->ovr_multiview_multisampled_render_to_texture = with_entry_points(
        ctx, e->ovr_multiview && has(&exts, "GL_OVR_multiview_multisampled_render_to_texture"),
        gl->FramebufferTextureMultisampleMultiviewOVR != NULL,
        "GL_OVR_multiview_multisampled_render_to_texture");
    e->ext_clip_control = with_entry_points(
        ctx,
        desktop ? (version_at_least(c, 4, 5) || has(&exts, "GL_ARB_clip_control"))
                : has(&exts, "GL_EXT_clip_control"),
        gl->ClipControl != NULL, desktop ? "GL_ARB_clip_control" : "GL_EXT_clip_control");
    e->ext_disjoint_timer_query = with_entry_points(
        ctx,
        desktop ? (version_at_least(c, 3, 3) || has(&exts, "GL_ARB_timer_query"))
                : has(&exts, "GL_EXT_disjoint_timer_query"),
        gl->QueryCounter && gl->GetQueryObjectui64v,
        desktop ? "GL_ARB_timer_query" : "GL_EXT_disjoint_timer_query");
    e->khr_debug = with_entry_points(
        ctx,
        has(&exts, "GL_KHR_debug") ||
            (desktop ? version_at_least(c, 4, 3) : version_at_least(c, 3, 2)),
        gl->DebugMessageCallback && gl->DebugMessageControl && gl->ObjectLabel &&
            gl->PushDebugGroup && gl->PopDebugGroup,
        "GL_KHR_debug");
    e->ext_texture_filter_anisotropic = has(&exts, "GL_EXT_texture_filter_anisotropic") ||
                                        has(&exts, "GL_ARB_texture_filter_anisotropic") ||
                                        (desktop && version_at_least(c, 4, 6));
    e->ext_color_buffer_float = desktop || has(&exts, "GL_EXT_color_buffer_float");
    e->ext_color_buffer_half_float = e->ext_color_buffer_float ||
                                     has(&exts, "GL_EXT_color_buffer_half_float");
    e->oes_texture_float_linear = desktop || has(&exts, "GL_OES_texture_float_linear");
    e->etc2 = !desktop || version_at_least(c, 4, 3) || has(&exts, "GL_ARB_ES3_compatibility");
    e->astc_ldr = has(&exts, "GL_KHR_texture_compression_astc_ldr");
    e->s3tc = has(&exts, "GL_EXT_texture_compression_s3tc");
    e->rgtc = has(&exts, "GL_EXT_texture_compression_rgtc") ||
              (desktop && (version_at_least(c, 3, 0) || has(&exts, "GL_ARB_texture_compression_rgtc")));
    e->bptc = has(&exts, "GL_EXT_texture_compression_bptc") ||
              (desktop && (version_at_least(c, 4, 2) || has(&exts, "GL_ARB_texture_compression_bptc")));
    free(exts.names);

    mvr_caps_limits *l = &c->limits;
    l->max_views_ovr = e->ovr_multiview ? get_int(ctx, GL_MAX_VIEWS_OVR) : 0;
    l->max_array_texture_layers = get_int(ctx, GL_MAX_ARRAY_TEXTURE_LAYERS);
    l->max_texture_size = get_int(ctx, GL_MAX_TEXTURE_SIZE);
    l->uniform_buffer_offset_alignment = get_int(ctx, GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT);
    l->max_uniform_block_size = get_int(ctx, GL_MAX_UNIFORM_BLOCK_SIZE);
    l->max_uniform_buffer_bindings = get_int(ctx, GL_MAX_UNIFORM_BUFFER_BINDINGS);
    l->max_samples = get_int(ctx, GL_MAX_SAMPLES);
    l->max_combined_texture_image_units = get_int(ctx, GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS);
    l->max_draw_buffers = get_int(ctx, GL_MAX_DRAW_BUFFERS);
    l->program_binary_formats = get_int(ctx, GL_NUM_PROGRAM_BINARY_FORMATS);
    e->program_binary = l->program_binary_formats > 0;
    l->max_anisotropy = 1.0f;
    if (e->ext_texture_filter_anisotropic) {
        GLfloat a = 1.0f;
        gl->GetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &a);
        if (gl->GetError() == GL_NO_ERROR && a >= 1.0f)
            l->max_anisotropy = a;
    }
    e->multiview_msaa_array = probe_multiview_msaa_array(ctx);
    probe_bugs(ctx);
}
