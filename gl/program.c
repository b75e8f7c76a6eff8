#include <stdlib.h>
#include <string.h>

#include "program.h"
#include "program_binary_file.h"

/* Deletes a program, made not current first. A deleted program that is
 * current stays in use until another replaces it (ES 3.2, 7.3), and an
 * NVIDIA driver (H100, 580.159) then hands its name to the next program
 * made while it is still current: glUseProgram of that new program was
 * taken for the current one, and draws ran the deleted program's code
 * (seen as renders that differed at random between renderers made one
 * after another in one context; docs/gpu_check.md). */
void mvr_gl_delete_program(const mvr_gl_api_table *gl, GLuint program)
{
    if (!program)
        return;
    GLint current = 0;
    gl->GetIntegerv(GL_CURRENT_PROGRAM, &current);
    if ((GLuint)current == program)
        gl->UseProgram(0);
    gl->DeleteProgram(program);
}

static mvr_result compile_stage(mvr_context *ctx, const char *name, mvr_shader_stage stage, const char *text,
                                GLuint *out)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    GLuint shader = gl->CreateShader(stage == MVR_SHADER_STAGE_VERTEX ? GL_VERTEX_SHADER
                                                                      : GL_FRAGMENT_SHADER);
    gl->ShaderSource(shader, 1, &text, NULL);
    gl->CompileShader(shader);
    GLint ok = GL_FALSE;
    gl->GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[MVR_ERROR_MESSAGE_SIZE - 64] = "";
        gl->GetShaderInfoLog(shader, (GLsizei)sizeof log, NULL, log);
        gl->DeleteShader(shader);
        mvr_log(&ctx->logger, MVR_LOG_ERROR, MVR_LOG_ID_SHADER, "mvr: %s.%s: %s", name,
                mvr_shader_stage_name(stage), log);
        return mvr_context_fail(ctx, MVR_ERROR_SHADER, "compiling %s.%s: %s", name,
                                mvr_shader_stage_name(stage), log);
    }
    *out = shader;
    return MVR_OK;
}

static void bind_block(const mvr_gl_api_table *gl, GLuint program, const char *name, GLuint binding)
{
    GLuint index = gl->GetUniformBlockIndex(program, name);
    if (index != GL_INVALID_INDEX)
        gl->UniformBlockBinding(program, index, binding);
}

static void bind_sampler(const mvr_gl_api_table *gl, GLuint program, const char *name, GLint unit)
{
    GLint loc = gl->GetUniformLocation(program, name);
    if (loc >= 0)
        gl->Uniform1i(loc, unit);
}

/* Driver identity for binary cache keys: a binary is only ever handed back
 * to the driver (API, vendor, renderer and version strings) that wrote it. */
void mvr_gl_driver_identity(const mvr_context *ctx, char *out, size_t size)
{
    const mvr_caps *c = &ctx->caps;
    mvr_str_format(out, size, "%s|%s|%s|%s", c->api == MVR_GL_API_GLES ? "gles" : "gl", c->vendor,
                   c->renderer, c->version);
}

/* Links a program from a cached binary; 0 when the driver refuses it (a
 * driver update can make a binary stale without changing its strings). */
static GLuint load_binary(mvr_context *ctx, uint32_t format, const void *data, size_t size)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    mvr_gl_clear_errors(gl);
    GLuint program = gl->CreateProgram();
    gl->ProgramBinary(program, (GLenum)format, data, (GLsizei)size);
    GLint ok = GL_FALSE;
    gl->GetProgramiv(program, GL_LINK_STATUS, &ok);
    bool clean = gl->GetError() == GL_NO_ERROR;
    mvr_gl_clear_errors(gl);
    if (ok && clean)
        return program;
    mvr_gl_delete_program(gl, program);
    return 0;
}

static void store_binary(mvr_context *ctx, GLuint program, const char *path, const mvr_program_cache_key *mac,
                         const char *driver, uint64_t key, mvr_program_build_info *info)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    GLint length = 0;
    gl->GetProgramiv(program, GL_PROGRAM_BINARY_LENGTH, &length);
    if (length <= 0) {
        mvr_gl_clear_errors(gl);
        return;
    }
    void *data = malloc((size_t)length);
    if (!data)
        return;
    GLsizei written = 0;
    GLenum format = 0;
    gl->GetProgramBinary(program, length, &written, &format, data);
    if (gl->GetError() == GL_NO_ERROR && written > 0 &&
        mvr_program_binary_write(path, mac, driver, key, format, data, (size_t)written, info->why, sizeof info->why))
        info->binary_stored = true;
    else if (info->why[0])
        info->binary_store_failed = true;
    mvr_gl_clear_errors(gl);
    free(data);
}

static mvr_result link_sources(mvr_context *ctx, const char *name, const char *vs_text, const char *fs_text,
                               bool retrievable, bool capture, GLuint *out)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    GLuint vs = 0, fs = 0;
    mvr_result r = compile_stage(ctx, name, MVR_SHADER_STAGE_VERTEX, vs_text, &vs);
    if (r != MVR_OK)
        return r;
    r = compile_stage(ctx, name, MVR_SHADER_STAGE_FRAGMENT, fs_text, &fs);
    if (r != MVR_OK) {
        gl->DeleteShader(vs);
        return r;
    }
    GLuint program = gl->CreateProgram();
    if (retrievable)
        gl->ProgramParameteri(program, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
    gl->AttachShader(program, vs);
    gl->AttachShader(program, fs);
    if (capture) {
        /* the pre-skinning program: its outputs, interleaved, in the
         * layout gl/skinning.c draws from (MVR_PRESKIN_STRIDE) */
        static const char *const varyings[3] = {"o_position", "o_normal", "o_tangent"};
        gl->TransformFeedbackVaryings(program, 3, varyings, GL_INTERLEAVED_ATTRIBS);
    }
    gl->LinkProgram(program);
    gl->DetachShader(program, vs);
    gl->DetachShader(program, fs);
    gl->DeleteShader(vs);
    gl->DeleteShader(fs);
    GLint ok = GL_FALSE;
    gl->GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[MVR_ERROR_MESSAGE_SIZE - 64] = "";
        gl->GetProgramInfoLog(program, (GLsizei)sizeof log, NULL, log);
        mvr_gl_delete_program(gl, program);
        mvr_log(&ctx->logger, MVR_LOG_ERROR, MVR_LOG_ID_SHADER, "mvr: linking %s: %s", name, log);
        return mvr_context_fail(ctx, MVR_ERROR_SHADER, "linking %s: %s", name, log);
    }
    *out = program;
    return MVR_OK;
}

mvr_result mvr_gl_program_build_cached(mvr_context *ctx, const mvr_shader_variant *variant, const char *cache_dir,
                                       mvr_program_build_info *info)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    memset(info, 0, sizeof *info);
    if (variant->num_views > 0 && !ctx->caps.ext.ovr_multiview2)
        return mvr_context_fail(ctx, MVR_ERROR_UNSUPPORTED,
                                "multiview shader variant on a GL without GL_OVR_multiview2");
    if (variant->num_views > (uint32_t)ctx->caps.limits.max_views_ovr)
        return mvr_context_fail(ctx, MVR_ERROR_UNSUPPORTED,
                                "multiview shader variant with %u views; GL_MAX_VIEWS_OVR is %d",
                                (unsigned)variant->num_views, ctx->caps.limits.max_views_ovr);
    char name[96];
    mvr_shader_variant_name(variant, name, sizeof name);
    char why[256] = "";
    mvr_str_builder vs_src = {0}, fs_src = {0};
    if (!mvr_shader_source(variant, MVR_SHADER_STAGE_VERTEX, &vs_src, why, sizeof why) ||
        !mvr_shader_source(variant, MVR_SHADER_STAGE_FRAGMENT, &fs_src, why, sizeof why)) {
        mvr_sb_free(&vs_src);
        mvr_sb_free(&fs_src);
        return mvr_context_fail(ctx, MVR_ERROR_INVALID_ARGUMENT, "shader variant %s: %s", name, why);
    }

    /* the binary cache: only where the driver offers a format */
    bool use_cache = cache_dir && cache_dir[0] && ctx->caps.ext.program_binary && gl->ProgramBinary &&
                     gl->GetProgramBinary;
    char driver[MVR_PROGRAM_BINARY_MAX_DRIVER];
    char path[4096];
    uint64_t key = 0;
    GLuint program = 0;
    if (use_cache) {
        mvr_gl_driver_identity(ctx, driver, sizeof driver);
        key = mvr_program_binary_key(driver, vs_src.data, fs_src.data);
        use_cache = mvr_program_binary_path(cache_dir, name, driver, path, sizeof path);
    }
    /* entries are authenticated with the user's key; an unsafe key file turns
     * the cache off, reported like an unwritable folder */
    mvr_program_cache_key mac = {{0}};
    if (use_cache && !mvr_program_cache_key_load(cache_dir, &mac, info->why, sizeof info->why)) {
        info->binary_store_failed = true;
        use_cache = false;
    }
    if (use_cache) {
        uint32_t format = 0;
        void *data = NULL;
        size_t size = 0;
        mvr_program_binary_status st =
            mvr_program_binary_read(path, &mac, driver, key, &format, &data, &size, why, sizeof why);
        if (st == MVR_PROGRAM_BINARY_HIT) {
            program = load_binary(ctx, format, data, size);
            if (!program)
                mvr_str_copy(why, sizeof why, "the driver refused the binary");
        }
        free(data);
        if (st != MVR_PROGRAM_BINARY_MISS && !program) {
            info->binary_rejected = true;
            mvr_str_format(info->why, sizeof info->why, "%s: %s", path, why);
        }
        info->from_binary = program != 0;
    }
    mvr_result r = MVR_OK;
    if (!program) {
        r = link_sources(ctx, name, vs_src.data, fs_src.data, use_cache, variant->program == MVR_PROGRAM_PRESKIN,
                         &program);
        if (r == MVR_OK && use_cache)
            store_binary(ctx, program, path, &mac, driver, key, info);
    }
    mvr_sb_free(&vs_src);
    mvr_sb_free(&fs_src);
    if (r != MVR_OK)
        return r;

    /* set after a binary load too: "a successful call to ProgramBinary will
     * reset all uniform variables to their initial values" (ES 3.0 spec,
     * Program Binaries), and block bindings are not promised either */
    bind_block(gl, program, "mvr_views", MVR_BLOCK_VIEWS);
    bind_block(gl, program, "mvr_draw", MVR_BLOCK_DRAW);
    bind_block(gl, program, "mvr_materials", MVR_BLOCK_MATERIALS);
    bind_block(gl, program, "mvr_lights", MVR_BLOCK_LIGHTS);
    bind_block(gl, program, "mvr_shadows", MVR_BLOCK_SHADOWS);
    /* ES 3.0 sets sampler units only on the current program; it stays current
     * (restoring the previous one by name is wrong when that one was deleted) */
    gl->UseProgram(program);
    for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role)
        bind_sampler(gl, program, mvr_role_sampler(role), mvr_role_unit(role));
    bind_sampler(gl, program, "mvr_transmission_source", MVR_UNIT_TRANSMISSION);
    bind_sampler(gl, program, "mvr_shadow_map", MVR_UNIT_SHADOW_MAP);
    bind_sampler(gl, program, "mvr_source", MVR_UNIT_COMPOSITE_SOURCE);
    bind_sampler(gl, program, "mvr_depth", MVR_UNIT_COMPOSITE_DEPTH);
    bind_sampler(gl, program, "mvr_source_ms", MVR_UNIT_COMPOSITE_DEPTH); /* the post pass reads no depth */
    bind_sampler(gl, program, "mvr_env_specular", MVR_UNIT_ENV_SPECULAR);
    bind_sampler(gl, program, "mvr_env_dfg", MVR_UNIT_ENV_DFG);
    bind_sampler(gl, program, "mvr_env_charlie", MVR_UNIT_ENV_CHARLIE);
    bind_sampler(gl, program, "mvr_sheen_lut", MVR_UNIT_SHEEN_LUT);
    bind_sampler(gl, program, "mvr_env_background", MVR_UNIT_ENV_BACKGROUND);
    bind_sampler(gl, program, "mvr_env_source", MVR_UNIT_ENV_INPUT);
    bind_sampler(gl, program, "mvr_env_equirect", MVR_UNIT_ENV_INPUT);
    bind_sampler(gl, program, "mvr_anim_data", MVR_UNIT_ANIM_DATA);
    bind_sampler(gl, program, "mvr_morph_deltas", MVR_UNIT_MORPH_DELTAS);
    r = mvr_gl_check(ctx, "mvr_gl_program_build", false);
    if (r != MVR_OK) {
        mvr_gl_delete_program(gl, program);
        return r;
    }
    info->program = program;
    return MVR_OK;
}

mvr_result mvr_gl_program_build(mvr_context *ctx, const mvr_shader_variant *variant, GLuint *out_program)
{
    mvr_program_build_info info;
    mvr_result r = mvr_gl_program_build_cached(ctx, variant, NULL, &info);
    *out_program = info.program;
    return r;
}

mvr_result mvr_context_check_shader_variant(mvr_context *ctx, const mvr_shader_variant *variant)
{
    GLuint program = 0;
    mvr_result r = mvr_gl_program_build(ctx, variant, &program);
    if (r == MVR_OK)
        mvr_gl_delete_program(&ctx->gl, program);
    return r;
}
