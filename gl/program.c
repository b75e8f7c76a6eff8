#include <stdlib.h>
#include <string.h>

#include "program.h"

static mvr_result compile_stage(mvr_context *ctx, const mvr_shader_variant *variant,
                                mvr_shader_stage stage, GLuint *out)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    char name[96];
    mvr_shader_variant_name(variant, name, sizeof name);
    char why[256] = "";
    mvr_str_builder src = {0};
    if (!mvr_shader_source(variant, stage, &src, why, sizeof why)) {
        mvr_sb_free(&src);
        return mvr_context_fail(ctx, MVR_ERROR_INVALID_ARGUMENT, "shader variant %s: %s", name, why);
    }
    GLuint shader = gl->CreateShader(stage == MVR_SHADER_STAGE_VERTEX ? GL_VERTEX_SHADER
                                                                      : GL_FRAGMENT_SHADER);
    const GLchar *text = src.data;
    gl->ShaderSource(shader, 1, &text, NULL);
    gl->CompileShader(shader);
    mvr_sb_free(&src);
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

mvr_result mvr_gl_program_build(mvr_context *ctx, const mvr_shader_variant *variant,
                                GLuint *out_program)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    *out_program = 0;
    if (variant->num_views > 0 && !ctx->caps.ext.ovr_multiview2)
        return mvr_context_fail(ctx, MVR_ERROR_UNSUPPORTED,
                                "multiview shader variant on a GL without GL_OVR_multiview2");
    if (variant->num_views > (uint32_t)ctx->caps.limits.max_views_ovr)
        return mvr_context_fail(ctx, MVR_ERROR_UNSUPPORTED,
                                "multiview shader variant with %u views; GL_MAX_VIEWS_OVR is %d",
                                (unsigned)variant->num_views, ctx->caps.limits.max_views_ovr);
    GLuint vs = 0, fs = 0;
    mvr_result r = compile_stage(ctx, variant, MVR_SHADER_STAGE_VERTEX, &vs);
    if (r != MVR_OK)
        return r;
    r = compile_stage(ctx, variant, MVR_SHADER_STAGE_FRAGMENT, &fs);
    if (r != MVR_OK) {
        gl->DeleteShader(vs);
        return r;
    }
    GLuint program = gl->CreateProgram();
    gl->AttachShader(program, vs);
    gl->AttachShader(program, fs);
    gl->LinkProgram(program);
    gl->DetachShader(program, vs);
    gl->DetachShader(program, fs);
    gl->DeleteShader(vs);
    gl->DeleteShader(fs);
    GLint ok = GL_FALSE;
    gl->GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[MVR_ERROR_MESSAGE_SIZE - 64] = "";
        char name[96];
        gl->GetProgramInfoLog(program, (GLsizei)sizeof log, NULL, log);
        gl->DeleteProgram(program);
        mvr_shader_variant_name(variant, name, sizeof name);
        mvr_log(&ctx->logger, MVR_LOG_ERROR, MVR_LOG_ID_SHADER, "mvr: linking %s: %s", name, log);
        return mvr_context_fail(ctx, MVR_ERROR_SHADER, "linking %s: %s", name, log);
    }

    bind_block(gl, program, "mvr_views", MVR_BLOCK_VIEWS);
    bind_block(gl, program, "mvr_draw", MVR_BLOCK_DRAW);
    bind_block(gl, program, "mvr_materials", MVR_BLOCK_MATERIALS);
    bind_block(gl, program, "mvr_lights", MVR_BLOCK_LIGHTS);
    /* ES 3.0 sets sampler units only on the current program; it stays current
     * (restoring the previous one by name is wrong when that one was deleted) */
    gl->UseProgram(program);
    bind_sampler(gl, program, "mvr_base_color_tex", MVR_UNIT_BASE_COLOR);
    bind_sampler(gl, program, "mvr_metal_rough_tex", MVR_UNIT_METAL_ROUGH);
    bind_sampler(gl, program, "mvr_normal_tex", MVR_UNIT_NORMAL);
    bind_sampler(gl, program, "mvr_occlusion_tex", MVR_UNIT_OCCLUSION);
    bind_sampler(gl, program, "mvr_emissive_tex", MVR_UNIT_EMISSIVE);
    bind_sampler(gl, program, "mvr_source", MVR_UNIT_COMPOSITE_SOURCE);
    r = mvr_gl_check(ctx, "mvr_gl_program_build", false);
    if (r != MVR_OK) {
        gl->DeleteProgram(program);
        return r;
    }
    *out_program = program;
    return MVR_OK;
}

mvr_result mvr_context_check_shader_variant(mvr_context *ctx, const mvr_shader_variant *variant)
{
    GLuint program = 0;
    mvr_result r = mvr_gl_program_build(ctx, variant, &program);
    if (r == MVR_OK)
        ctx->gl.DeleteProgram(program);
    return r;
}
