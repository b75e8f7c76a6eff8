/*
 * Environment lighting on the GPU: view-independent work, done once per
 * environment (its pixels' serial), never per view or per frame.
 *
 * 1. The equirectangular image goes into a mip-mapped half-float 2D texture
 *    and is resampled into the source cube map (the sharp background, and
 *    the prefilter's input), whose mips the GL then averages.
 * 2. The specular chain: level k of `levels` holds the GGX prefilter of
 *    roughness k / (levels - 1) (the Khronos glTF Sample Renderer's mapping;
 *    its lowest level is 16 texels, as theirs), filtered importance sampling
 *    from the source cube (shaders/env_prefilter.frag.glsl).
 * 3. The DFG table, once per renderer, computed on the CPU in double
 *    (core/ibl_lut.c) and stored as RG16F.
 * KHR_materials_sheen adds, only for a frame that draws sheen: the Charlie
 * chain (as the specular one, the sheen lobe's distribution instead of
 * GGX, from the same source cube) once per environment, and the sheen
 * albedo table (core/sheen_lut.c) once per renderer, which lights without
 * an environment read too.
 * Diffuse light is the environment's spherical harmonics (CPU, at creation).
 *
 * Each cube level is one multiview pass whose six views are the six faces
 * (into a 2D array level, then copied face by face into the cube: a cube map
 * cannot be a multiview attachment), or six plain passes straight into the
 * faces where multiview is missing or the loop path is forced: the same
 * shader per texel, so the same values.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "environment.h"
#include "environment_cache.h"
#include "environment_gl.h"
#include "errors.h"
#include "post.h"
#include "program_cache.h"
#include "renderer.h"

#define ENV_LOWEST_FACE 16u      /* roughness 1's level */
#define ENV_MAX_SOURCE 512u      /* source cube face size, at most */
#define ENV_DFG_SIZE 64u
#define ENV_DFG_SAMPLES 512u
#define SHEEN_LUT_SIZE 32u

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static uint32_t log2_floor(uint32_t v)
{
    uint32_t l = 0;
    while (v > 1u) {
        v >>= 1u;
        ++l;
    }
    return l;
}

static uint32_t pow2_floor(uint32_t v)
{
    return v ? 1u << log2_floor(v) : 1u;
}

/* The maps of one environment (the DFG table stays: it is the renderer's). */
static void release_maps(mvr_renderer *r)
{
    mvr_gpu_environment *g = &r->env;
    mvr_gl_delete(r, MVR_GL_TEXTURE, &g->source);
    mvr_gl_delete(r, MVR_GL_TEXTURE, &g->specular);
    mvr_gl_delete(r, MVR_GL_TEXTURE, &g->charlie);
    mvr_gl_delete(r, MVR_GL_SAMPLER, &g->cube_sampler);
    g->serial = 0;
    g->charlie_serial = 0;
}

void mvr_environment_release(mvr_renderer *r)
{
    release_maps(r);
    mvr_gl_delete(r, MVR_GL_TEXTURE, &r->env.dfg);
    mvr_gl_delete(r, MVR_GL_SAMPLER, &r->env.dfg_sampler);
    mvr_gl_delete(r, MVR_GL_TEXTURE, &r->env.sheen_lut);
}

static mvr_result check_fbo(mvr_renderer *r, const char *where)
{
    mvr_result res = mvr_gl_check(r->ctx, where, true);
    if (res == MVR_OK)
        res = mvr_gl_check_framebuffer(r->ctx, GL_DRAW_FRAMEBUFFER, where);
    return res == MVR_OK ? MVR_OK : mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
}

typedef struct level_job {
    GLuint cube;                 /* written */
    uint32_t level, size;        /* its level and that level's size */
    GLuint scratch;              /* multiview: a 6-layer array of size x size (level 0) */
    GLuint fbo;                  /* drawn into: the six faces (multiview) or one face */
    GLuint read_fbo, copy_fbo;   /* multiview: one layer of the array, one face of the cube */
} level_job;

/* Draws one cube level with the bound program and input (face_base and the
 * program's other uniforms set by the caller, except the face). */
static mvr_result draw_level(mvr_renderer *r, const level_job *j, const mvr_program_entry *e)
{
    const mvr_gl_api_table *gl = r->gl;
    mvr_state_cache *st = &r->state;
    mvr_state_draw_framebuffer(st, j->fbo);
    mvr_state_viewport(st, 0, 0, (GLsizei)j->size, (GLsizei)j->size);
    gl->Uniform1f(e->loc_face_size, (GLfloat)j->size);
    if (j->scratch) {
        gl->FramebufferTextureMultiviewOVR(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, j->scratch, 0, 0, 6);
        mvr_result res = check_fbo(r, "environment prefilter framebuffer (multiview, six faces)");
        if (res != MVR_OK)
            return res;
        gl->Uniform1i(e->loc_face_base, 0);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
        r->stats.env_prefilter_passes++;
        /* never read from a multiview framebuffer: each layer alone into its face */
        mvr_state_read_framebuffer(st, j->read_fbo);
        mvr_state_draw_framebuffer(st, j->copy_fbo);
        for (GLint f = 0; f < 6; ++f) {
            gl->FramebufferTextureLayer(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, j->scratch, 0, f);
            gl->FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, (GLenum)(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f),
                                     j->cube, (GLint)j->level);
            gl->BlitFramebuffer(0, 0, (GLint)j->size, (GLint)j->size, 0, 0, (GLint)j->size, (GLint)j->size,
                                GL_COLOR_BUFFER_BIT, GL_NEAREST);
        }
        return MVR_OK;
    }
    for (GLint f = 0; f < 6; ++f) {
        gl->FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, (GLenum)(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f),
                                 j->cube, (GLint)j->level);
        mvr_result res = check_fbo(r, "environment prefilter framebuffer (one face)");
        if (res != MVR_OK)
            return res;
        gl->Uniform1i(e->loc_face_base, f);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
        r->stats.env_prefilter_passes++;
    }
    return MVR_OK;
}

static mvr_result make_texture(mvr_renderer *r, GLenum target, GLuint *tex, uint32_t levels, GLenum format,
                               uint32_t w, uint32_t h, uint32_t layers, const char *what)
{
    const mvr_gl_api_table *gl = r->gl;
    gl->GenTextures(1, tex);
    mvr_state_texture(&r->state, MVR_UNIT_ENV_INPUT, target, *tex);
    if (target == GL_TEXTURE_2D_ARRAY)
        gl->TexStorage3D(target, (GLsizei)levels, format, (GLsizei)w, (GLsizei)h, (GLsizei)layers);
    else
        gl->TexStorage2D(target, (GLsizei)levels, format, (GLsizei)w, (GLsizei)h);
    gl->TexParameteri(target, GL_TEXTURE_MAX_LEVEL, (GLint)levels - 1);
    return mvr_gl_check_alloc(r, "%s (%ux%u, %u levels)", what, w, h, levels);
}

/* bugs.half_float_sampling_slow: a half float texture (the specular cube
 * chain, the DFG table) again as its 32-bit float format, each level and
 * face blitted from it (so the same values, whether a prefilter, the cache
 * or an upload wrote them), which then replaces it: the mesh, background and
 * clearcoat fetches read the floats as they are. Where the GL cannot filter
 * float textures the half floats stay. */
static mvr_result widen_texture(mvr_renderer *r, GLenum target, GLuint *tex, GLenum wide_format, uint32_t size,
                                uint32_t levels, const char *what)
{
    const mvr_caps *caps = &r->ctx->caps;
    if (!caps->bugs.half_float_sampling_slow || !caps->ext.ext_color_buffer_float ||
        !caps->ext.oes_texture_float_linear)
        return MVR_OK;
    const mvr_gl_api_table *gl = r->gl;
    GLuint wide = 0, fbo[2] = {0, 0};
    mvr_result res = make_texture(r, target, &wide, levels, wide_format, size, size, 1, what);
    if (res == MVR_OK) {
        mvr_full_screen_state(r); /* a blit is scissored */
        gl->GenFramebuffers(2, fbo);
        mvr_state_read_framebuffer(&r->state, fbo[0]);
        mvr_state_draw_framebuffer(&r->state, fbo[1]);
        GLenum faces = target == GL_TEXTURE_CUBE_MAP ? 6u : 1u;
        for (uint32_t k = 0; k < levels; ++k) {
            GLint side = (GLint)(size >> k);
            for (GLenum f = 0; f < faces; ++f) {
                GLenum face = target == GL_TEXTURE_CUBE_MAP ? GL_TEXTURE_CUBE_MAP_POSITIVE_X + f : target;
                gl->FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, face, *tex, (GLint)k);
                gl->FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, face, wide, (GLint)k);
                gl->BlitFramebuffer(0, 0, side, side, 0, 0, side, side, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            }
        }
        res = check_fbo(r, what);
        mvr_state_read_framebuffer(&r->state, 0);
        mvr_state_draw_framebuffer(&r->state, 0);
    }
    mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &fbo[0]);
    mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &fbo[1]);
    if (res != MVR_OK) {
        mvr_gl_delete(r, MVR_GL_TEXTURE, &wide);
        return res;
    }
    mvr_gl_delete(r, MVR_GL_TEXTURE, tex);
    *tex = wide;
    return MVR_OK;
}

static mvr_result environment_program(mvr_renderer *r, uint32_t features, bool multiview, mvr_program_entry **e)
{
    mvr_shader_variant v;
    memset(&v, 0, sizeof v);
    v.program = MVR_PROGRAM_ENVIRONMENT;
    v.features = features;
    v.num_views = multiview ? 6u : 0u;
    mvr_result res = mvr_program_cache_get(r, &v, e);
    if (res == MVR_OK)
        mvr_state_program(&r->state, (*e)->program);
    return res;
}

static bool prefilter_multiview(const mvr_renderer *r)
{
    const mvr_caps *c = &r->ctx->caps;
    /* the loop path, when forced, prefilters face by face too (tests compare the two) */
    return c->ext.ovr_multiview2 && c->limits.max_views_ovr >= 6 && r->gl->FramebufferTextureMultiviewOVR &&
           r->requested_path != MVR_VIEW_PATH_LOOP;
}

static mvr_result make_dfg(mvr_renderer *r)
{
    mvr_gpu_environment *g = &r->env;
    if (g->dfg)
        return MVR_OK;
    float *table = malloc((size_t)ENV_DFG_SIZE * ENV_DFG_SIZE * 2 * sizeof *table);
    bool cached = table && mvr_env_cache_load_dfg(r, ENV_DFG_SIZE, ENV_DFG_SAMPLES, table);
    if (!table || (!cached && !mvr_ibl_dfg_lut(ENV_DFG_SIZE, ENV_DFG_SAMPLES, table))) {
        free(table);
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "environment: DFG table: out of memory");
    }
    if (!cached)
        mvr_env_cache_store_dfg(r, ENV_DFG_SIZE, ENV_DFG_SAMPLES, table);
    const mvr_gl_api_table *gl = r->gl;
    mvr_result res = make_texture(r, GL_TEXTURE_2D, &g->dfg, 1, GL_RG16F, ENV_DFG_SIZE, ENV_DFG_SIZE, 1,
                                  "environment DFG table (rg16f)");
    if (res == MVR_OK) {
        gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, ENV_DFG_SIZE, ENV_DFG_SIZE, GL_RG, GL_FLOAT, table);
        r->upload_bytes += (uint64_t)ENV_DFG_SIZE * ENV_DFG_SIZE * 4u;
        res = widen_texture(r, GL_TEXTURE_2D, &g->dfg, GL_RG32F, ENV_DFG_SIZE, 1,
                            "environment DFG table (rg32f copy)");
    }
    free(table);
    if (res != MVR_OK) {
        mvr_gl_delete(r, MVR_GL_TEXTURE, &g->dfg); /* not half made: the next frame tries again */
        return res;
    }
    gl->GenSamplers(1, &g->dfg_sampler);
    gl->SamplerParameteri(g->dfg_sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->SamplerParameteri(g->dfg_sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->SamplerParameteri(g->dfg_sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->SamplerParameteri(g->dfg_sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return MVR_OK;
}

/* The sampler both cubes are read with (trilinear, clamped), and the
 * prefilter's GL errors checked. */
static mvr_result make_cube_sampler(mvr_renderer *r)
{
    const mvr_gl_api_table *gl = r->gl;
    GLuint *sampler = &r->env.cube_sampler;
    gl->GenSamplers(1, sampler);
    gl->SamplerParameteri(*sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl->SamplerParameteri(*sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->SamplerParameteri(*sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->SamplerParameteri(*sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->SamplerParameteri(*sampler, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    mvr_result res = mvr_gl_check(r->ctx, "environment prefilter", true);
    return res == MVR_OK ? MVR_OK : mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
}

/* What a prefilter run draws through: framebuffers, and on the multiview
 * path a 6-layer array per level size (each its own level 0: Mesa attaches
 * only level 0 with multiview, bugs.multiview_level_zero_only), count of
 * them halving from size0. */
typedef struct prefilter_scratch {
    GLuint faces[12];
    uint32_t count;
    GLuint fbo, read_fbo, copy_fbo;
} prefilter_scratch;

static mvr_result scratch_create(mvr_renderer *r, prefilter_scratch *sc, bool multiview, uint32_t size0,
                                 uint32_t count)
{
    memset(sc, 0, sizeof *sc);
    sc->count = multiview ? (count < 12u ? count : 12u) : 0u;
    mvr_result res = MVR_OK;
    for (uint32_t k = 0; k < sc->count && res == MVR_OK; ++k)
        res = make_texture(r, GL_TEXTURE_2D_ARRAY, &sc->faces[k], 1, GL_RGBA16F, size0 >> k, size0 >> k, 6,
                           "environment prefilter faces (rgba16f array)");
    if (res == MVR_OK) {
        r->gl->GenFramebuffers(1, &sc->fbo);
        if (multiview) {
            r->gl->GenFramebuffers(1, &sc->read_fbo);
            r->gl->GenFramebuffers(1, &sc->copy_fbo);
        }
    }
    return res;
}

static void scratch_release(mvr_renderer *r, prefilter_scratch *sc)
{
    mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &sc->fbo);
    mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &sc->read_fbo);
    mvr_gl_delete(r, MVR_GL_FRAMEBUFFER, &sc->copy_fbo);
    for (uint32_t k = 0; k < 12u; ++k)
        mvr_gl_delete(r, MVR_GL_TEXTURE, &sc->faces[k]);
}

/* Step 2: the GGX chain from the source cube. */
static mvr_result filter_specular(mvr_renderer *r, const mvr_env_cache_maps *m, const prefilter_scratch *sc)
{
    const mvr_gl_api_table *gl = r->gl;
    mvr_program_entry *e = NULL;
    mvr_result res = environment_program(r, MVR_FEATURE_ENV_GGX, m->multiview, &e);
    if (res != MVR_OK)
        return res;
    mvr_state_texture(&r->state, MVR_UNIT_ENV_INPUT, GL_TEXTURE_CUBE_MAP, r->env.source);
    gl->Uniform1i(e->loc_samples, (GLint)m->env->specular_samples);
    gl->Uniform1f(e->loc_source_size, (GLfloat)m->source_size);
    gl->Uniform1f(e->loc_source_max_lod, (GLfloat)(m->source_levels - 1u));
    for (uint32_t k = 0; k < m->levels && res == MVR_OK; ++k) {
        uint32_t size = m->size >> k;
        gl->Uniform1f(e->loc_roughness, m->levels > 1 ? (GLfloat)k / (GLfloat)(m->levels - 1u) : 0.0f);
        level_job j = {r->env.specular, k, size, sc->faces[log2_floor(m->source_size / size)], sc->fbo,
                       sc->read_fbo, sc->copy_fbo};
        res = draw_level(r, &j, e);
    }
    return res;
}

/* Steps 1 and 2 into the allocated cubes: the image, the source cube's
 * level 0 from it, the GL's mips, the specular chain. */
static mvr_result filter_maps(mvr_renderer *r, const mvr_env_cache_maps *m)
{
    const mvr_environment *env = m->env;
    const mvr_gl_api_table *gl = r->gl;
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    GLuint equirect = 0;
    prefilter_scratch sc;
    memset(&sc, 0, sizeof sc);
    uint32_t eq_levels = log2_floor(env->width > env->height ? env->width : env->height) + 1u;
    mvr_result res = make_texture(r, GL_TEXTURE_2D, &equirect, eq_levels, GL_RGBA16F, env->width, env->height, 1,
                                  "environment image (rgba16f)");
    if (res == MVR_OK) {
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, (GLsizei)env->width, (GLsizei)env->height, GL_RGBA, GL_FLOAT,
                          env->pixels);
        gl->GenerateMipmap(GL_TEXTURE_2D);
        /* u wraps around the horizon; v stops at the poles */
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        r->upload_bytes += (uint64_t)env->width * env->height * 8u;
        res = scratch_create(r, &sc, m->multiview, m->source_size,
                             log2_floor(m->source_size / ENV_LOWEST_FACE) + 1u);
    }
    /* the source cube's level 0 from the image: the image level whose texel
     * angle (2 pi / width) matches a face texel's at its centre (pi/2 / size) */
    mvr_program_entry *e = NULL;
    if (res == MVR_OK) {
        mvr_full_screen_state(r);
        res = environment_program(r, 0u, m->multiview, &e);
    }
    if (res == MVR_OK) {
        mvr_state_texture(&r->state, MVR_UNIT_ENV_INPUT, GL_TEXTURE_2D, equirect);
        mvr_state_sampler(&r->state, MVR_UNIT_ENV_INPUT, 0);
        double lod = log2((double)env->width / (4.0 * (double)m->source_size));
        gl->Uniform1f(e->loc_equirect_lod, (GLfloat)(lod > 0.0 ? lod : 0.0));
        level_job j = {r->env.source, 0, m->source_size, sc.faces[0], sc.fbo, sc.read_fbo, sc.copy_fbo};
        res = draw_level(r, &j, e);
    }
    if (res == MVR_OK) {
        mvr_state_texture(&r->state, MVR_UNIT_ENV_INPUT, GL_TEXTURE_CUBE_MAP, r->env.source);
        gl->GenerateMipmap(GL_TEXTURE_CUBE_MAP);
        gl->TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl->TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        res = filter_specular(r, m, &sc);
    }
    scratch_release(r, &sc);
    mvr_gl_delete(r, MVR_GL_TEXTURE, &equirect);
    return res;
}

/* Steps 1 and 2 for a new environment: from the disk cache when it holds
 * these exact inputs' bytes, else filtered here and stored. */
static mvr_result prefilter(mvr_renderer *r, const mvr_environment *env)
{
    mvr_gpu_environment *g = &r->env;
    const mvr_gl_api_table *gl = r->gl;
    const mvr_caps *caps = &r->ctx->caps;
    if (!caps->ext.ext_color_buffer_half_float)
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED,
                           "environment: prefiltering needs renderable half floats "
                           "(GL_EXT_color_buffer_half_float), which this GL lacks");
    uint32_t max_cube = (uint32_t)caps->limits.max_texture_size;
    uint32_t spec_size = env->specular_size;
    /* the source: a face of a quarter of the image's width (its texels about
     * match the image's at the equator), at least the specular size */
    uint32_t source_size = pow2_floor(env->width / 4u);
    if (source_size > ENV_MAX_SOURCE)
        source_size = ENV_MAX_SOURCE;
    if (source_size < spec_size)
        source_size = spec_size;
    if (spec_size > max_cube || source_size > max_cube)
        return mvr_gl_fail(r, MVR_ERROR_UNSUPPORTED, "environment: cube faces of %u texels exceed the GL's %u",
                           source_size, max_cube);
    mvr_env_cache_maps m = {env, source_size, log2_floor(source_size) + 1u, spec_size,
                            log2_floor(spec_size / ENV_LOWEST_FACE) + 1u, prefilter_multiview(r)};

    release_maps(r);
    mvr_result res = make_texture(r, GL_TEXTURE_CUBE_MAP, &g->source, m.source_levels, GL_RGBA16F, source_size,
                                  source_size, 1, "environment source cube map (rgba16f)");
    if (res == MVR_OK)
        res = make_texture(r, GL_TEXTURE_CUBE_MAP, &g->specular, m.levels, GL_RGBA16F, spec_size, spec_size, 1,
                           "environment specular cube map (rgba16f)");
    if (res == MVR_OK && !mvr_env_cache_load(r, &m, g->source, g->specular)) {
        res = filter_maps(r, &m);
        if (res == MVR_OK)
            mvr_env_cache_store(r, &m, g->source, g->specular);
    }
    if (res == MVR_OK)
        res = widen_texture(r, GL_TEXTURE_CUBE_MAP, &g->specular, GL_RGBA32F, spec_size, m.levels,
                            "environment specular cube map (rgba32f copy)");
    if (res == MVR_OK) {
        /* read with these where no sampler object is bound (the Charlie prefilter) */
        mvr_state_texture(&r->state, MVR_UNIT_ENV_INPUT, GL_TEXTURE_CUBE_MAP, g->source);
        gl->TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl->TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        res = make_cube_sampler(r);
    }
    if (res != MVR_OK) {
        release_maps(r);
        return res;
    }
    g->source_size = source_size;
    g->source_levels = m.source_levels;
    g->specular_size = spec_size;
    g->specular_levels = m.levels;
    g->serial = env->serial;
    return MVR_OK;
}

/* KHR_materials_sheen: the Charlie chain of the environment already
 * prefiltered (its source cube), the specular chain's sizes and levels
 * (level k of sheen roughness k / (levels - 1), the Sample Renderer's
 * mapping), one multiview or six plain passes a level as the specular's. */
static mvr_result charlie_prefilter(mvr_renderer *r, const mvr_environment *env)
{
    mvr_gpu_environment *g = &r->env;
    const mvr_gl_api_table *gl = r->gl;
    bool multiview = prefilter_multiview(r);
    uint32_t levels = g->specular_levels, size0 = g->specular_size;
    mvr_gl_delete(r, MVR_GL_TEXTURE, &g->charlie);
    g->charlie_serial = 0;
    mvr_result res = make_texture(r, GL_TEXTURE_CUBE_MAP, &g->charlie, levels, GL_RGBA16F, size0, size0, 1,
                                  "environment sheen (Charlie) cube map (rgba16f)");
    prefilter_scratch sc;
    memset(&sc, 0, sizeof sc);
    if (res == MVR_OK)
        res = scratch_create(r, &sc, multiview, size0, levels);
    mvr_program_entry *e = NULL;
    if (res == MVR_OK) {
        mvr_full_screen_state(r);
        res = environment_program(r, MVR_FEATURE_ENV_CHARLIE, multiview, &e);
    }
    if (res == MVR_OK) {
        mvr_state_texture(&r->state, MVR_UNIT_ENV_INPUT, GL_TEXTURE_CUBE_MAP, g->source);
        mvr_state_sampler(&r->state, MVR_UNIT_ENV_INPUT, 0);
        gl->Uniform1i(e->loc_samples, (GLint)env->specular_samples);
        gl->Uniform1f(e->loc_source_size, (GLfloat)g->source_size);
        gl->Uniform1f(e->loc_source_max_lod, (GLfloat)(g->source_levels - 1u));
    }
    for (uint32_t k = 0; k < levels && res == MVR_OK; ++k) {
        gl->Uniform1f(e->loc_roughness, levels > 1 ? (GLfloat)k / (GLfloat)(levels - 1u) : 0.0f);
        level_job j = {g->charlie, k, size0 >> k, sc.faces[k], sc.fbo, sc.read_fbo, sc.copy_fbo};
        res = draw_level(r, &j, e);
    }
    if (res == MVR_OK) {
        res = mvr_gl_check(r->ctx, "environment sheen prefilter", true);
        if (res != MVR_OK)
            res = mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
    }
    scratch_release(r, &sc);
    if (res != MVR_OK) {
        mvr_gl_delete(r, MVR_GL_TEXTURE, &g->charlie);
        return res;
    }
    g->charlie_serial = env->serial;
    return MVR_OK;
}

mvr_result mvr_sheen_lut_sync(mvr_renderer *r)
{
    mvr_gpu_environment *g = &r->env;
    if (g->sheen_lut)
        return MVR_OK;
    float *table = malloc((size_t)SHEEN_LUT_SIZE * SHEEN_LUT_SIZE * 2 * sizeof *table);
    if (!table || !mvr_sheen_lut(SHEEN_LUT_SIZE, table)) {
        free(table);
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "sheen albedo table: out of memory");
    }
    const mvr_gl_api_table *gl = r->gl;
    mvr_result res = make_texture(r, GL_TEXTURE_2D, &g->sheen_lut, 1, GL_RG16F, SHEEN_LUT_SIZE, SHEEN_LUT_SIZE, 1,
                                  "sheen albedo table (rg16f)");
    if (res == MVR_OK) {
        gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, SHEEN_LUT_SIZE, SHEEN_LUT_SIZE, GL_RG, GL_FLOAT, table);
        /* sampled bilinearly, clamped (texture parameters: no sampler object) */
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        r->upload_bytes += (uint64_t)SHEEN_LUT_SIZE * SHEEN_LUT_SIZE * 4u;
    }
    free(table);
    return res;
}

void mvr_sheen_bind(mvr_renderer *r, bool environment)
{
    mvr_state_cache *st = &r->state;
    mvr_state_texture(st, MVR_UNIT_SHEEN_LUT, GL_TEXTURE_2D, r->env.sheen_lut);
    mvr_state_sampler(st, MVR_UNIT_SHEEN_LUT, 0);
    if (environment) {
        mvr_state_texture(st, MVR_UNIT_ENV_CHARLIE, GL_TEXTURE_CUBE_MAP, r->env.charlie);
        mvr_state_sampler(st, MVR_UNIT_ENV_CHARLIE, r->env.cube_sampler);
    }
}

bool mvr_environment_stale(const mvr_renderer *r, const mvr_environment *env, bool sheen)
{
    return env && (r->env.serial != env->serial || (sheen && r->env.charlie_serial != env->serial));
}

mvr_result mvr_environment_sync(mvr_renderer *r, const mvr_environment *env, bool sheen)
{
    if (!mvr_environment_stale(r, env, sheen))
        return MVR_OK;
    double t0 = now_ms();
    /* desktop GL filters across cube faces only when asked (GLES always does) */
    if (r->ctx->caps.api == MVR_GL_API_DESKTOP)
        r->gl->Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    mvr_result res = make_dfg(r);
    if (res == MVR_OK && r->env.serial != env->serial)
        res = prefilter(r, env);
    if (res == MVR_OK && sheen)
        res = charlie_prefilter(r, env);
    if (res != MVR_OK)
        return res;
    /* its cost, once: the GL finished (this render waits for it) */
    r->gl->Finish();
    r->stats.env_prefilter_ms = now_ms() - t0;
    mvr_log(&r->logger, MVR_LOG_INFO, MVR_LOG_ID_GENERAL,
            "mvr: environment prefiltered: %u passes, source %u, specular %u (%u levels, %u samples)%s, %.1f ms",
            r->stats.env_prefilter_passes, r->env.source_size, r->env.specular_size, r->env.specular_levels,
            env->specular_samples, sheen ? ", sheen (Charlie) chain" : "", r->stats.env_prefilter_ms);
    return MVR_OK;
}

double mvr_environment_average_diffuse(const mvr_environment *env)
{
    /* the mean of sum c_i Y_i over the sphere is c_0 Y_0 (the other bands average to 0) */
    const double y0 = 0.28209479177387814;
    double rgb[3];
    for (int c = 0; c < 3; ++c)
        rgb[c] = (double)env->sh[0][c] * y0 * (double)env->intensity;
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

void mvr_environment_bind(mvr_renderer *r, bool reference)
{
    mvr_state_cache *st = &r->state;
    /* the reference integrates the unfiltered source instead of reading the prefilter */
    mvr_state_texture(st, MVR_UNIT_ENV_SPECULAR, GL_TEXTURE_CUBE_MAP, reference ? r->env.source : r->env.specular);
    mvr_state_sampler(st, MVR_UNIT_ENV_SPECULAR, r->env.cube_sampler);
    mvr_state_texture(st, MVR_UNIT_ENV_DFG, GL_TEXTURE_2D, r->env.dfg);
    mvr_state_sampler(st, MVR_UNIT_ENV_DFG, r->env.dfg_sampler);
}

void mvr_environment_set_uniforms(mvr_renderer *r, const mvr_program_entry *e, const mvr_environment *env,
                                  uint32_t samples)
{
    const mvr_gl_api_table *gl = r->gl;
    float m[9];
    mvr_environment_rotation_matrix(env, m);
    if (e->loc_env_rotation >= 0)
        gl->UniformMatrix3fv(e->loc_env_rotation, 1, GL_FALSE, m);
    if (e->loc_env_intensity >= 0)
        gl->Uniform1f(e->loc_env_intensity, env->intensity);
    if (e->loc_env_sh >= 0)
        gl->Uniform3fv(e->loc_env_sh, 9, &env->sh[0][0]);
    if (e->loc_env_max_lod >= 0)
        gl->Uniform1f(e->loc_env_max_lod, (GLfloat)(r->env.specular_levels - 1u));
    if (e->loc_env_samples >= 0)
        gl->Uniform1i(e->loc_env_samples, (GLint)(samples ? samples : 1u));
}

mvr_result mvr_environment_draw_background(mvr_renderer *r, const mvr_render_desc *desc, uint32_t num_views,
                                           int32_t view_base, bool srgb_output, float exposure)
{
    const mvr_environment *env = desc->environment;
    mvr_state_cache *st = &r->state;
    mvr_shader_variant v;
    memset(&v, 0, sizeof v);
    v.program = MVR_PROGRAM_BACKGROUND;
    v.features = srgb_output ? MVR_FEATURE_BACKGROUND_SRGB_OUTPUT : 0u;
    v.num_views = num_views;
    mvr_program_entry *e = NULL;
    mvr_result res = mvr_program_cache_get(r, &v, &e);
    if (res != MVR_OK)
        return res;
    if (!r->empty_vao)
        r->gl->GenVertexArrays(1, &r->empty_vao);
    mvr_state_program(st, e->program);
    const mvr_gl_api_table *gl = r->gl;
    /* uncovered pixels only: their depth is still the clear value, which the
     * far plane's depth equals */
    mvr_state_depth(st, true, r->reversed_z ? GL_GEQUAL : GL_LEQUAL, GL_FALSE);
    mvr_state_blend(st, false, GL_ONE, GL_ZERO, GL_ONE, GL_ZERO);
    mvr_state_cull(st, false, GL_CCW);
    mvr_state_vao(st, r->empty_vao);
    bool blur = desc->background == MVR_BACKGROUND_BLUR;
    mvr_state_texture(st, MVR_UNIT_ENV_BACKGROUND, GL_TEXTURE_CUBE_MAP, blur ? r->env.specular : r->env.source);
    mvr_state_sampler(st, MVR_UNIT_ENV_BACKGROUND, r->env.cube_sampler);
    if (e->view_base != view_base) {
        gl->Uniform1i(e->loc_view_base, view_base);
        e->view_base = view_base;
    }
    float blur_roughness = desc->background_blur > 0.0f ? desc->background_blur : 0.5f;
    if (blur_roughness > 1.0f)
        blur_roughness = 1.0f;
    gl->Uniform1f(e->loc_background_lod, blur ? blur_roughness * (GLfloat)(r->env.specular_levels - 1u) : 0.0f);
    gl->Uniform1f(e->loc_exposure, exposure);
    /* clip z of the near and far planes: reversed-Z (zero to one) 1 and 0;
     * standard -1 and 1 */
    if (r->reversed_z)
        gl->Uniform2f(e->loc_depth_range, 1.0f, 0.0f);
    else
        gl->Uniform2f(e->loc_depth_range, -1.0f, 1.0f);
    mvr_environment_set_uniforms(r, e, env, 0);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    r->stats.background_draws++;
    return MVR_OK;
}
