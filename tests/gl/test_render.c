/* gl: the multiview and loop view paths give byte-identical layers (this holds
 * on llvmpipe), for every demo and 1, 2, 6 and 10 views, into mvr's own
 * target and into an application's texture array; the stats count what the
 * frame model promises. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>

#include "gl_test_util.h"
#include "renderer.h"

#define W 64
#define H 48

typedef struct rendered {
    uint32_t views;
    uint8_t *pixels;             /* views * W * H * 4 */
    mvr_frame_stats first, second;
} rendered;

static mvr_renderer *make_renderer_with(mvr_test_state *t, mvr_context *ctx, mvr_view_path path,
                                        const mvr_renderer_overrides *overrides)
{
    /* tuning off: these frames check steady-state uploads and binds, which
     * auto's measured frames (switching paths) would not show */
    mvr_renderer_desc rd = {.context = ctx, .view_path = path, .tuning = {.mode = MVR_TUNING_OFF}};
    if (overrides)
        rd.overrides = *overrides;
    mvr_renderer *r = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_renderer_create(&rd, &r, &err) == MVR_OK, "%s", err.message);
    return r;
}

static mvr_renderer *make_renderer(mvr_test_state *t, mvr_context *ctx, mvr_view_path path)
{
    return make_renderer_with(t, ctx, path, NULL);
}

/* Renders a demo twice (the second frame is the steady state) and reads
 * every layer; overrides (NULL = none) go into the renderer desc. */
static bool render_demo_with(mvr_test_state *t, mvr_context *ctx, const char *demo, uint32_t views,
                             mvr_view_path path, const mvr_target_desc *external,
                             const mvr_renderer_overrides *overrides, rendered *out)
{
    memset(out, 0, sizeof *out);
    mvr_scene *scene = NULL;
    mvr_view_set *vs = NULL;
    mvr_error err;
    mvr_demo_desc dd = {views, W, H, {0}};
    if (mvr_demo_create(demo, &dd, &scene, &vs, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "demo %s: %s", demo, err.message);
        return false;
    }
    mvr_renderer *r = make_renderer_with(t, ctx, path, overrides);
    mvr_target *target = NULL;
    mvr_target_desc td = {W, H, views, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    if (external)
        td = *external;
    bool ok = r && mvr_target_create(r, &td, &target) == MVR_OK;
    CHECK_MSG(t, ok, "target: %s", r ? mvr_renderer_last_error(r) : "no renderer");
    mvr_render_desc rdesc = {.clear_color = {0.1f, 0.2f, 0.3f, 1.0f}, .exposure = 1.0f, .tone_map = MVR_TONE_MAP_NONE};
    for (int frame = 0; ok && frame < 2; ++frame) {
        ok = mvr_renderer_render(r, scene, vs, target, &rdesc) == MVR_OK;
        CHECK_MSG(t, ok, "%s x%u %s: %s", demo, views, mvr_view_path_name(path), mvr_renderer_last_error(r));
        if (ok)
            mvr_renderer_get_stats(r, frame == 0 ? &out->first : &out->second);
    }
    if (ok) {
        out->views = views;
        out->pixels = malloc((size_t)views * W * H * 4);
        for (uint32_t k = 0; ok && k < views; ++k) {
            ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, out->pixels + (size_t)k * W * H * 4,
                                         (size_t)W * H * 4) == MVR_OK;
            CHECK_MSG(t, ok, "read layer %u: %s", k, mvr_renderer_last_error(r));
        }
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    return ok;
}

static bool render_demo(mvr_test_state *t, mvr_context *ctx, const char *demo, uint32_t views,
                        mvr_view_path path, const mvr_target_desc *external, rendered *out)
{
    return render_demo_with(t, ctx, demo, views, path, external, NULL, out);
}

static uint32_t count_diff(const uint8_t *a, const uint8_t *b, size_t pixels)
{
    uint32_t n = 0;
    for (size_t i = 0; i < pixels; ++i)
        n += memcmp(a + i * 4, b + i * 4, 4) != 0;
    return n;
}

/* Not a blank frame: enough distinct colors that a broken draw would show. */
static uint32_t distinct_colors(const uint8_t *p, size_t pixels)
{
    uint32_t seen[64] = {0}, n = 0;
    for (size_t i = 0; i < pixels && n < 64; ++i) {
        uint32_t c = (uint32_t)p[i * 4] | (uint32_t)p[i * 4 + 1] << 8 | (uint32_t)p[i * 4 + 2] << 16;
        bool found = false;
        for (uint32_t k = 0; k < n; ++k)
            found |= seen[k] == c;
        if (!found)
            seen[n++] = c;
    }
    return n;
}

static void paths_agree(mvr_test_state *t, const char *demo)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_caps *c = mvr_context_caps(ctx);
    if (!c->ext.ovr_multiview2) {
        mvr_context_destroy(ctx);
        CHECK_MSG(t, !mvr_test_in_ci(), "CI needs GL_OVR_multiview2");
        SKIP(t, "no GL_OVR_multiview2: nothing to compare the loop path with");
    }
    uint32_t max_views = (uint32_t)c->limits.max_views_ovr;
    static const uint32_t counts[] = {1, 2, 6, 10};
    uint64_t steady_upload = 0;
    for (size_t i = 0; i < MVR_ARRAY_COUNT(counts); ++i) {
        uint32_t n = counts[i];
        rendered mv, loop;
        memset(&mv, 0, sizeof mv);
        memset(&loop, 0, sizeof loop);
        bool ok = render_demo(t, ctx, demo, n, MVR_VIEW_PATH_MULTIVIEW, NULL, &mv) &&
                  render_demo(t, ctx, demo, n, MVR_VIEW_PATH_LOOP, NULL, &loop);
        if (ok) {
            for (uint32_t k = 0; k < n; ++k) {
                const uint8_t *a = mv.pixels + (size_t)k * W * H * 4, *b = loop.pixels + (size_t)k * W * H * 4;
                uint32_t d = count_diff(a, b, (size_t)W * H);
                CHECK_MSG(t, d == 0, "%s, %u views, layer %u: %u of %u pixels differ between multiview and loop",
                          demo, n, k, d, W * H);
                CHECK_MSG(t, distinct_colors(a, (size_t)W * H) >= 8, "%s layer %u looks blank", demo, k);
            }
            /* distinct views render distinct images (not one view copied) */
            if (n >= 2)
                CHECK_MSG(t, count_diff(mv.pixels, mv.pixels + (size_t)W * H * 4, (size_t)W * H) > 0,
                          "%s: views 0 and 1 are identical", demo);
            uint32_t expect_passes = (n + max_views - 1) / max_views;
            CHECK_MSG(t, mv.second.passes == expect_passes, "%s x%u multiview: %u passes, expected %u", demo, n,
                      mv.second.passes, expect_passes);
            CHECK_MSG(t, loop.second.passes == n, "%s x%u loop: %u passes", demo, n, loop.second.passes);
            CHECK_EQ_INT(t, mv.second.view_path, MVR_VIEW_PATH_MULTIVIEW);
            CHECK_EQ_INT(t, loop.second.view_path, MVR_VIEW_PATH_LOOP);
            CHECK_EQ_INT(t, mv.second.views, n);
            /* chunks of one view take plain passes: 10 views at 6 per pass = 6 + 4 */
            uint32_t expect_mv = n / max_views + (n % max_views > 1);
            CHECK_MSG(t, mv.second.multiview_passes == expect_mv, "%s x%u: %u multiview passes, expected %u", demo,
                      n, mv.second.multiview_passes, expect_mv);
            CHECK_EQ_INT(t, loop.second.multiview_passes, 0);
            CHECK_EQ_INT(t, loop.second.views, n);
            /* culling is the same on both paths; the loop draws each view's
             * visible draws, multiview the union per chunk */
            CHECK_EQ_INT(t, mv.second.culled, loop.second.culled);
            CHECK_EQ_INT(t, (loop.second.draws + loop.second.culled) % n, 0);
            CHECK(t, mv.second.draws <= loop.second.draws && mv.second.draws * n >= loop.second.draws);
            /* view-independent uploads do not grow with N, and are the same on both paths */
            if (i == 0)
                steady_upload = mv.second.upload_bytes;
            CHECK_MSG(t, mv.second.upload_bytes == steady_upload && loop.second.upload_bytes == steady_upload,
                      "%s x%u: upload_bytes %llu / %llu, with 1 view %llu", demo, n,
                      (unsigned long long)mv.second.upload_bytes, (unsigned long long)loop.second.upload_bytes,
                      (unsigned long long)steady_upload);
            CHECK(t, mv.first.upload_bytes > mv.second.upload_bytes); /* geometry and textures once */
            CHECK_EQ_INT(t, mv.second.upload_bytes, 0); /* nothing changed: only views are sent */
            CHECK_EQ_INT(t, mv.second.view_upload_bytes, (uint64_t)n * 96u); /* matrix, eye, light mask */
            CHECK_EQ_INT(t, mv.second.programs_compiled, 0); /* cached after the first frame */
        }
        free(mv.pixels);
        free(loop.pixels);
    }
    mvr_context_destroy(ctx);
}

static void stereo_paths_agree(mvr_test_state *t) { paths_agree(t, "stereo"); }
static void cube_paths_agree(mvr_test_state *t) { paths_agree(t, "cube"); }
static void city_paths_agree(mvr_test_state *t) { paths_agree(t, "city"); }
static void ring_paths_agree(mvr_test_state *t) { paths_agree(t, "ring"); }

/* An application-owned array (as an XR swapchain image): views land in its
 * layers from base_layer on, at its mip level; layers outside stay untouched;
 * the pixels equal those of mvr's own target. */
static GLuint app_array(const mvr_gl_api_table *gl, GLsizei levels, GLsizei w, GLsizei h)
{
    GLuint tex = 0, fbo = 0;
    gl->GenTextures(1, &tex);
    gl->BindTexture(GL_TEXTURE_2D_ARRAY, tex);
    gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, levels, GL_SRGB8_ALPHA8, w, h, 4);
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    const float magenta[4] = {1, 0, 1, 1};
    for (GLint level = 0; level < levels; ++level)
        for (GLint layer = 0; layer < 4; ++layer) {
            gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, tex, level, layer);
            gl->ClearBufferfv(GL_COLOR, 0, magenta);
        }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->DeleteFramebuffers(1, &fbo);
    return tex;
}

static void check_untouched(mvr_test_state *t, const mvr_gl_api_table *gl, GLuint tex, GLint level)
{
    GLuint fbo = 0;
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    for (GLint layer = 0; layer < 4; layer += 3) {
        uint8_t px[4] = {0};
        gl->FramebufferTextureLayer(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, tex, level, layer);
        gl->ReadPixels(W / 2, H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
        CHECK_MSG(t, px[0] == 255 && px[1] == 0 && px[2] == 255, "level %d layer %d was written: %u %u %u",
                  level, layer, px[0], px[1], px[2]);
    }
    gl->BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl->DeleteFramebuffers(1, &fbo);
}

static void application_texture_array(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_gl_api_table *gl = &ctx->gl;
    GLuint mipped = app_array(gl, 2, W * 2, H * 2); /* level 1 is W x H */
    GLuint plain = app_array(gl, 1, W, H);
    CHECK(t, mvr_gl_check(ctx, "test setup", true) == MVR_OK);
    rendered own;
    memset(&own, 0, sizeof own);
    bool have_own = render_demo(t, ctx, "stereo", 2, MVR_VIEW_PATH_AUTO, NULL, &own);
    const mvr_caps *caps = mvr_context_caps(ctx);
    const struct { GLuint tex; uint32_t level; mvr_view_path path; } cases[] = {
        {plain, 0, MVR_VIEW_PATH_MULTIVIEW}, {plain, 0, MVR_VIEW_PATH_AUTO}, {plain, 0, MVR_VIEW_PATH_LOOP},
        {mipped, 1, MVR_VIEW_PATH_AUTO}, {mipped, 1, MVR_VIEW_PATH_LOOP}};
    for (size_t i = 0; have_own && i < MVR_ARRAY_COUNT(cases); ++i) {
        if (cases[i].path == MVR_VIEW_PATH_MULTIVIEW && !caps->ext.ovr_multiview2)
            continue;
        mvr_target_desc ext = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, cases[i].tex, cases[i].level, 1, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
        rendered app;
        memset(&app, 0, sizeof app);
        if (render_demo(t, ctx, "stereo", 2, cases[i].path, &ext, &app)) {
            CHECK_MSG(t, count_diff(app.pixels, own.pixels, (size_t)W * H * 2) == 0,
                      "application array (level %u, %s) and mvr's target differ", cases[i].level,
                      mvr_view_path_name(cases[i].path));
            /* auto: the loop where the driver cannot attach the level with
             * multiview or where multiview passes defer rasterization */
            bool level_ok = cases[i].level == 0 || !caps->bugs.multiview_level_zero_only;
            bool mv = cases[i].path == MVR_VIEW_PATH_MULTIVIEW ||
                      (cases[i].path == MVR_VIEW_PATH_AUTO && caps->ext.ovr_multiview2 && level_ok &&
                       !caps->bugs.multiview_pass_defers_raster);
            /* (auto: the rule is the tuner's prior; its second frame may try the other path) */
            CHECK_EQ_INT(t, cases[i].path == MVR_VIEW_PATH_AUTO ? app.second.auto_choice.prior : app.second.view_path,
                         mv ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP);
        }
        free(app.pixels);
        check_untouched(t, gl, cases[i].tex, (GLint)cases[i].level);
    }
    free(own.pixels);
    gl->DeleteTextures(1, &mipped);
    gl->DeleteTextures(1, &plain);
    mvr_context_destroy(ctx);
}

/* A wrong application texture is refused with a message, not a crash. */
static void bad_targets_are_refused(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_renderer *r = make_renderer(t, ctx, MVR_VIEW_PATH_AUTO);
    mvr_target *target = NULL;
    mvr_target_desc d = {0, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    CHECK(t, mvr_target_create(r, &d, &target) == MVR_ERROR_INVALID_ARGUMENT && !target);
    d = (mvr_target_desc){W, H, 100000, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    CHECK(t, mvr_target_create(r, &d, &target) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_renderer_last_error(r), "GL_MAX_ARRAY_TEXTURE_LAYERS") != NULL);
    /* a 2D texture is not a 2D array */
    GLuint tex = 0;
    ctx->gl.GenTextures(1, &tex);
    ctx->gl.BindTexture(GL_TEXTURE_2D, tex);
    ctx->gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, W, H);
    d = (mvr_target_desc){W, H, 2, MVR_COLOR_FORMAT_RGBA8, tex, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    mvr_result res = mvr_target_create(r, &d, &target);
    CHECK_MSG(t, res == MVR_ERROR_GL || res == MVR_ERROR_FRAMEBUFFER, "%s", mvr_result_name(res));
    CHECK(t, target == NULL);
    ctx->gl.DeleteTextures(1, &tex);
    /* more views than layers */
    mvr_scene *scene = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {3, W, H, {0}};
    CHECK(t, mvr_demo_create("ring", &dd, &scene, &vs, NULL) == MVR_OK);
    d = (mvr_target_desc){W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    CHECK(t, mvr_target_create(r, &d, &target) == MVR_OK);
    CHECK(t, mvr_renderer_render(r, scene, vs, target, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_renderer_last_error(r), "3 views") != NULL);
    uint8_t small[16];
    CHECK(t, mvr_renderer_read_layer(r, target, 0, MVR_READBACK_RGBA8, small, sizeof small) ==
                 MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_renderer_read_layer(r, target, 5, MVR_READBACK_RGBA8, small, sizeof small) ==
                 MVR_ERROR_INVALID_ARGUMENT);
    mvr_target_destroy(target);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    mvr_renderer_destroy(r);
    mvr_context_destroy(ctx);
}

/* Disabled views leave their layer alone and cost no pass. */
static void disabled_views_are_skipped(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *scene = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {4, W, H, {0}};
    CHECK(t, mvr_demo_create("ring", &dd, &scene, &vs, NULL) == MVR_OK);
    mvr_view_desc v = vs->views[2];
    v.disabled = true;
    CHECK(t, mvr_view_set_update(vs, 2, &v) == MVR_OK);
    mvr_renderer *r = make_renderer(t, ctx, MVR_VIEW_PATH_AUTO);
    mvr_target *target = NULL;
    mvr_target_desc d = {W, H, 4, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    CHECK(t, mvr_target_create(r, &d, &target) == MVR_OK);
    CHECK(t, mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK);
    mvr_frame_stats st;
    mvr_renderer_get_stats(r, &st);
    CHECK_EQ_INT(t, st.views, 3);
    /* views 0,1 and 3 are not consecutive: two multiview passes (or three loop passes) */
    CHECK_EQ_INT(t, st.passes, st.view_path == MVR_VIEW_PATH_MULTIVIEW ? 2 : 3);
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
}

/* Renders the ring demo's first view (no blended materials: a UNORM target
 * blends sRGB-encoded values, an sRGB target blends in linear space, so
 * blended pixels differ by design) into a target of the given format, and
 * reads it back as RGBA32F. */
static float *render_format(mvr_test_state *t, mvr_context *ctx, mvr_color_format format, mvr_tone_map tone)
{
    mvr_scene *scene = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {1, W, H, {0}};
    CHECK(t, mvr_demo_create("ring", &dd, &scene, &vs, NULL) == MVR_OK);
    mvr_renderer *r = make_renderer(t, ctx, MVR_VIEW_PATH_AUTO);
    mvr_target *target = NULL;
    mvr_target_desc td = {W, H, 1, format, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    mvr_render_desc rd = {.clear_color = {0.2f, 0.1f, 0.05f, 1.0f}, .exposure = 1.0f, .tone_map = tone};
    float *px = malloc((size_t)W * H * 4 * sizeof *px);
    bool ok = mvr_target_create(r, &td, &target) == MVR_OK && mvr_renderer_render(r, scene, vs, target, &rd) == MVR_OK &&
              mvr_renderer_read_layer(r, target, 0, MVR_READBACK_RGBA32F, px, (size_t)W * H * 4 * sizeof *px) == MVR_OK;
    CHECK_MSG(t, ok, "%s: %s", mvr_color_format_name(format), mvr_renderer_last_error(r));
    if (ok && format != MVR_COLOR_FORMAT_RGBA16F) {
        /* RGBA32F readback of 8-bit storage = the RGBA8 readback / 255 */
        uint8_t *bytes = malloc((size_t)W * H * 4);
        CHECK(t, mvr_renderer_read_layer(r, target, 0, MVR_READBACK_RGBA8, bytes, (size_t)W * H * 4) == MVR_OK);
        for (size_t i = 0; i < (size_t)W * H * 4; ++i)
            if (px[i] != (float)bytes[i] / 255.0f) {
                CHECK_MSG(t, 0, "float readback %g vs byte %u at %zu", (double)px[i], bytes[i], i);
                break;
            }
        free(bytes);
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    if (!ok) {
        free(px);
        return NULL;
    }
    return px;
}

static float srgb_encode(float c)
{
    c = c < 0.0f ? 0.0f : c > 1.0f ? 1.0f : c;
    return c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

/* The shader's exact sRGB encode (UNORM target) and the GL's (sRGB target)
 * agree to within one step; a linear half-float target, encoded here, too.
 * Tone mapping changes the image but keeps it within [0, 1]. */
static void color_formats_agree(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    float *srgb = render_format(t, ctx, MVR_COLOR_FORMAT_DEFAULT, MVR_TONE_MAP_NONE);
    float *unorm = render_format(t, ctx, MVR_COLOR_FORMAT_RGBA8, MVR_TONE_MAP_NONE);
    float *half = render_format(t, ctx, MVR_COLOR_FORMAT_RGBA16F, MVR_TONE_MAP_NONE);
    float *aces = render_format(t, ctx, MVR_COLOR_FORMAT_DEFAULT, MVR_TONE_MAP_ACES);
    if (srgb && unorm && half && aces) {
        float worst_unorm = 0, worst_half = 0;
        size_t aces_changed = 0;
        for (size_t i = 0; i < (size_t)W * H * 4; ++i) {
            bool alpha = i % 4 == 3;
            float d1 = fabsf(srgb[i] - unorm[i]);
            float d2 = fabsf(srgb[i] - (alpha ? half[i] : srgb_encode(half[i])));
            worst_unorm = d1 > worst_unorm ? d1 : worst_unorm;
            worst_half = d2 > worst_half ? d2 : worst_half;
            aces_changed += aces[i] != srgb[i];
            CHECK(t, aces[i] >= 0.0f && aces[i] <= 1.0f);
        }
        printf("  sRGB target vs shader encode: %.2f/255; vs half float: %.2f/255\n", worst_unorm * 255.0f,
               worst_half * 255.0f);
        /* one step: the two encodes round differently near half-way values */
        CHECK_MSG(t, worst_unorm <= 1.0f / 255.0f + 1e-6f, "shader sRGB encode is %g/255 off", worst_unorm * 255.0);
        CHECK_MSG(t, worst_half <= 1.0f / 255.0f + 1e-3f, "half-float target is %g/255 off", worst_half * 255.0);
        CHECK(t, aces_changed > (size_t)W * H);
    }
    free(srgb);
    free(unorm);
    free(half);
    free(aces);
    mvr_context_destroy(ctx);
}

/* Two views looking down -Z from x = -3 and x = +3 (about 34 degrees of
 * vertical field): a unit triangle 5 in front of one is outside the other. */
static mvr_view_set *side_by_side_views(mvr_test_state *t)
{
    mvr_view_desc views[2] = {{.position = {-3, 0, 0}, .projection = {.yfov = 0.6}},
                              {.position = {3, 0, 0}, .projection = {.yfov = 0.6}}};
    mvr_view_set *vs = NULL;
    mvr_view_set_desc vd = {2, views, false, {0, 0, 0}};
    CHECK(t, mvr_view_set_create(&vd, &vs, NULL) == MVR_OK);
    return vs;
}

/* A draw outside every frustum is not drawn; one seen by one of two views
 * is drawn once in multiview and once in the loop; pixels do not change. */
static void culling_changes_cost_not_pixels(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *scene = NULL;
    mvr_scene_create(NULL, &scene, NULL);
    float tri[9] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0, 0.5f, 0};
    mvr_primitive_desc p = {.vertex_count = 3, .positions = tri};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "tri"};
    mvr_mesh_id mesh;
    CHECK(t, mvr_scene_add_mesh(scene, &md, &mesh) == MVR_OK);
    /* both views look down -Z from x = -3 and x = +3: one triangle in front of
     * each, one behind both */
    const double xs[3] = {-3.0, 3.0, 0.0}, zs[3] = {-5.0, -5.0, 50.0};
    for (int i = 0; i < 3; ++i) {
        mvr_node_desc nd = {.mesh = mesh, .translation = {xs[i], 0, zs[i]}};
        mvr_node_id id;
        CHECK(t, mvr_scene_add_node(scene, &nd, &id) == MVR_OK);
    }
    mvr_view_set *vs = side_by_side_views(t);
    uint8_t *img[2] = {malloc((size_t)W * H * 8), malloc((size_t)W * H * 8)};
    bool have_mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    mvr_view_path paths[2] = {have_mv ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_LOOP};
    for (int pi = 0; pi < 2; ++pi)
        for (int cull = 1; cull >= 0; --cull) {
            mvr_renderer_desc rd = {.context = ctx, .view_path = paths[pi], .disable_culling = !cull};
            mvr_renderer *r = NULL;
            mvr_target *target = NULL;
            mvr_target_desc td = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
            mvr_render_desc desc = {.clear_color = {0.1f, 0.1f, 0.1f, 1.0f}, .exposure = 1.0f, .tone_map = MVR_TONE_MAP_NONE};
            bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
                      mvr_renderer_render(r, scene, vs, target, &desc) == MVR_OK;
            CHECK(t, ok);
            mvr_frame_stats st;
            mvr_renderer_get_stats(r, &st);
            bool multiview = st.view_path == MVR_VIEW_PATH_MULTIVIEW;
            if (cull) {
                CHECK_EQ_INT(t, mvr_renderer_view_culled(r, 0), 2); /* the other side's and the one behind */
                CHECK_EQ_INT(t, mvr_renderer_view_culled(r, 1), 2);
                CHECK_EQ_INT(t, st.culled, 4);
                CHECK_EQ_INT(t, st.draws, 2); /* multiview: the union (2) in one pass; loop: one per view */
            } else {
                CHECK_EQ_INT(t, st.draws, multiview ? 3 : 6);
            }
            for (uint32_t k = 0; ok && k < 2; ++k)
                CHECK(t, mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, img[cull] + (size_t)k * W * H * 4,
                                                 (size_t)W * H * 4) == MVR_OK);
            mvr_target_destroy(target);
            mvr_renderer_destroy(r);
        }
    CHECK_MSG(t, memcmp(img[0], img[1], (size_t)W * H * 8) == 0, "culling changed pixels");
    free(img[0]);
    free(img[1]);
    /* every demo: the same pixels with culling off */
    for (uint32_t d = 0; mvr_demo_name(d); ++d) {
        rendered on, off;
        const mvr_renderer_overrides no_culling = {.culling = MVR_OVERRIDE_OFF};
        bool ok = render_demo_with(t, ctx, mvr_demo_name(d), 2, MVR_VIEW_PATH_AUTO, NULL, &no_culling, &off);
        ok = ok && render_demo(t, ctx, mvr_demo_name(d), 2, MVR_VIEW_PATH_AUTO, NULL, &on);
        if (ok) {
            CHECK_MSG(t, count_diff(on.pixels, off.pixels, (size_t)W * H * 2) == 0, "%s: culling changed pixels",
                      mvr_demo_name(d));
            CHECK(t, off.second.culled == 0 && on.second.draws <= off.second.draws);
            printf("  %-7s draws %u with culling, %u without (%u culled over 2 views)\n", mvr_demo_name(d),
                   on.second.draws, off.second.draws, on.second.culled);
        }
        free(on.pixels);
        free(off.pixels);
    }
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
}

/* A second identical frame sends only per-view data; a moved node re-sends
 * the per-draw blocks once; a new origin too; pixels follow. */
static void dirty_tracking_sends_only_changes(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *scene = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {2, W, H, {0}};
    CHECK(t, mvr_demo_create("ring", &dd, &scene, &vs, NULL) == MVR_OK);
    mvr_renderer_desc rd = {.context = ctx, .tuning = {.mode = MVR_TUNING_OFF}}; /* steady-state uploads */
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_target_desc td = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    CHECK(t, mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK);
    uint64_t up[5];
    uint8_t before[W * H * 4], after[W * H * 4];
    for (int f = 0; f < 5; ++f) {
        if (f == 2) { /* move the torus (node 3 of the ring demo) */
            double tr[3] = {0.3, 1.35, 0}, rot[4] = {0, 0, 0, 1}, sc[3] = {1, 1, 1};
            CHECK(t, mvr_scene_set_node_transform(scene, (mvr_node_id){3}, tr, rot, sc) == MVR_OK);
        }
        if (f == 4) { /* a new origin: blocks are relative to it */
            mvr_view_desc v = vs->views[0];
            v.position[0] += 0.5;
            CHECK(t, mvr_view_set_update(vs, 0, &v) == MVR_OK);
        }
        CHECK(t, mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK);
        mvr_frame_stats st;
        mvr_renderer_get_stats(r, &st);
        up[f] = st.upload_bytes;
        CHECK_EQ_INT(t, st.view_upload_bytes, 2 * 96); /* per view: matrix, eye, light mask */
        if (f == 1)
            mvr_renderer_read_layer(r, target, 1, MVR_READBACK_RGBA8, before, sizeof before);
        if (f == 3)
            mvr_renderer_read_layer(r, target, 1, MVR_READBACK_RGBA8, after, sizeof after);
    }
    printf("  upload bytes per frame: %llu %llu %llu %llu %llu\n", (unsigned long long)up[0],
           (unsigned long long)up[1], (unsigned long long)up[2], (unsigned long long)up[3],
           (unsigned long long)up[4]);
    CHECK(t, up[0] > 0 && up[1] == 0);          /* first frame: everything; then nothing */
    CHECK(t, up[2] > 0 && up[2] < up[0]);        /* transforms only: no geometry or textures */
    CHECK(t, up[3] == 0);
    CHECK(t, up[4] == up[2]);                    /* a new origin re-sends the blocks */
    CHECK_MSG(t, memcmp(before, after, sizeof before) != 0, "the moved node did not move");
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
}

/* Pass skipping: an opaque scene runs no blend sub-pass; a blended surface
 * adds one to each pass that sees it, and none where it is culled. */
static void blend_pass_only_where_needed(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *scene = NULL;
    mvr_scene_create(NULL, &scene, NULL);
    float tri[9] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0, 0.5f, 0};
    mvr_material_desc glass = mvr_material_defaults();
    glass.alpha_mode = MVR_ALPHA_BLEND;
    glass.base_color_factor[3] = 0.5f;
    mvr_material_id glass_id;
    CHECK(t, mvr_scene_add_material(scene, &glass, &glass_id) == MVR_OK);
    mvr_primitive_desc solid = {.vertex_count = 3, .positions = tri};
    mvr_primitive_desc clear = {.vertex_count = 3, .positions = tri, .material = glass_id};
    mvr_mesh_desc solid_md = {.primitives = &solid, .primitive_count = 1, .name = "solid"}, clear_md = {.primitives = &clear, .primitive_count = 1, .name = "glass"};
    mvr_mesh_id solid_mesh, clear_mesh;
    CHECK(t, mvr_scene_add_mesh(scene, &solid_md, &solid_mesh) == MVR_OK);
    CHECK(t, mvr_scene_add_mesh(scene, &clear_md, &clear_mesh) == MVR_OK);
    mvr_node_desc nd = {.mesh = solid_mesh, .translation = {0, 0, 50}};
    mvr_node_id node;
    CHECK(t, mvr_scene_add_node(scene, &nd, &node) == MVR_OK);
    mvr_view_set *vs = side_by_side_views(t);
    mvr_node_desc gd = {.mesh = clear_mesh, .translation = {0, 0, 50}}; /* behind both views */
    mvr_node_id glass_node;
    CHECK(t, mvr_scene_add_node(scene, &gd, &glass_node) == MVR_OK);
    const double hidden[3] = {0, 0, 50}, front0[3] = {-3, 0, -5}, front1[3] = {3, 0, -5};
    const double rot[4] = {0, 0, 0, 1}, one[3] = {1, 1, 1};
    mvr_view_path paths[2] = {mvr_context_caps(ctx)->ext.ovr_multiview2 ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP,
                              MVR_VIEW_PATH_LOOP};
    for (int pi = 0; pi < 2; ++pi) {
        mvr_renderer *r = make_renderer(t, ctx, paths[pi]);
        mvr_target *target = NULL;
        mvr_target_desc td = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
        CHECK(t, r && mvr_target_create(r, &td, &target) == MVR_OK);
        if (!target) {
            mvr_renderer_destroy(r);
            continue;
        }
        /* nothing in view: passes clear, no sub-pass runs */
        CHECK(t, mvr_scene_set_node_transform(scene, node, hidden, rot, one) == MVR_OK);
        CHECK(t, mvr_scene_set_node_transform(scene, glass_node, hidden, rot, one) == MVR_OK);
        mvr_frame_stats st;
        CHECK(t, mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK);
        mvr_renderer_get_stats(r, &st);
        CHECK_EQ_INT(t, st.sub_passes[0] + st.sub_passes[1] + st.sub_passes[2], 0);
        CHECK_EQ_INT(t, st.draws, 0);
        /* opaque only, in front of view 0: no blend sub-pass */
        CHECK(t, mvr_scene_set_node_transform(scene, node, front0, rot, one) == MVR_OK);
        CHECK(t, mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK);
        mvr_renderer_get_stats(r, &st);
        CHECK_EQ_INT(t, st.sub_passes[0], 1);
        CHECK_EQ_INT(t, st.sub_passes[2], 0);
        /* and the glass in front of view 1: one blend sub-pass (multiview:
         * in the pass of both views; loop: in view 1's pass only) */
        CHECK(t, mvr_scene_set_node_transform(scene, glass_node, front1, rot, one) == MVR_OK);
        CHECK(t, mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK);
        mvr_renderer_get_stats(r, &st);
        CHECK_EQ_INT(t, st.sub_passes[0], 1);
        CHECK_EQ_INT(t, st.sub_passes[1], 0);
        CHECK_EQ_INT(t, st.sub_passes[2], 1);
        CHECK_EQ_INT(t, st.passes, st.view_path == MVR_VIEW_PATH_MULTIVIEW ? 1 : 2);
        CHECK_EQ_INT(t, st.draws, 2);
        mvr_target_destroy(target);
        mvr_renderer_destroy(r);
    }
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
}

/* Instancing changes draw calls, not pixels: every demo at 2 and 10 views on
 * both view paths, with culling on and off, renders the same bytes with
 * instancing on and off; on city (one box mesh per material) most draws
 * ride in instanced calls. */
static void instancing_changes_calls_not_pixels(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool have_mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    const uint32_t view_counts[2] = {2, 10};
    for (uint32_t d = 0; mvr_demo_name(d); ++d)
        for (int vc = 0; vc < 2; ++vc)
            for (int pi = 0; pi < 2; ++pi) {
                uint32_t calls_without_culling = 0;
                for (int cull = 0; cull < 2; ++cull) {
                    const char *demo = mvr_demo_name(d);
                    uint32_t n = view_counts[vc];
                    mvr_view_path path = pi == 0 && have_mv ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP;
                    mvr_renderer_overrides ov = {.culling = cull ? MVR_OVERRIDE_NONE : MVR_OVERRIDE_OFF};
                    rendered on, off;
                    bool ok = render_demo_with(t, ctx, demo, n, path, NULL, &ov, &on);
                    ov.instancing = MVR_OVERRIDE_OFF;
                    ok = render_demo_with(t, ctx, demo, n, path, NULL, &ov, &off) && ok;
                    if (ok) {
                        size_t diff = count_diff(on.pixels, off.pixels, (size_t)W * H * n);
                        CHECK_MSG(t, diff == 0, "%s x%u %s culling %d: instancing changed %zu pixels", demo, n,
                                  mvr_view_path_name(path), cull, diff);
                        CHECK_EQ_INT(t, on.second.draws, off.second.draws);
                        CHECK_EQ_INT(t, off.second.draw_calls, off.second.draws);
                        CHECK_EQ_INT(t, off.second.instanced_draw_calls, 0);
                        CHECK(t, on.second.draw_calls <= off.second.draw_calls);
                        /* culled passes copy their visible blocks together, so
                         * culling never splits a run: at most as many calls as
                         * without culling (same passes, subsets of its runs) */
                        CHECK_EQ_INT(t, off.second.compacted_bytes, 0);
                        if (!cull) {
                            calls_without_culling = on.second.draw_calls;
                            CHECK_EQ_INT(t, on.second.compacted_bytes, 0);
                        } else {
                            CHECK_MSG(t, on.second.draw_calls <= calls_without_culling,
                                      "%s x%u %s: %u calls with culling, %u without", demo, n,
                                      mvr_view_path_name(path), on.second.draw_calls, calls_without_culling);
                            /* a pass compacts where a chunk's views all cull a draw: on
                             * the loop path (a view a chunk) any culled draw; a multiview
                             * chunk may see every draw in some view (NVIDIA: 10 views in
                             * one chunk, 48 culls, nothing culled by all of them) */
                            if (path == MVR_VIEW_PATH_LOOP && on.second.culled > 0 &&
                                on.second.instanced_draw_calls > 0)
                                CHECK_MSG(t, on.second.compacted_bytes > 0,
                                          "%s x%u %s: %llu culled, %u instanced of %u calls, %u draws, "
                                          "material path %s, yet nothing compacted",
                                          demo, n, mvr_view_path_name(path), (unsigned long long)on.second.culled,
                                          on.second.instanced_draw_calls, on.second.draw_calls, on.second.draws,
                                          mvr_material_path_name(on.second.material_path));
                        }
                        if (strcmp(demo, "city") == 0) {
                            CHECK(t, on.second.instanced_draw_calls > 0);
                            /* without culling: one call per box mesh per pass, (4097 draws, 73 meshes) */
                            if (!cull)
                                CHECK_MSG(t, on.second.draw_calls * 20 < on.second.draws,
                                          "city x%u %s: %u calls for %u draws", n, mvr_view_path_name(path),
                                          on.second.draw_calls, on.second.draws);
                        }
                        if (vc == 0 && cull)
                            printf("  %-6s x%u %-9s: %u draws in %u calls (instancing off: %u)\n", demo, n,
                                   mvr_view_path_name(path), on.second.draws, on.second.draw_calls,
                                   off.second.draw_calls);
                    }
                    free(on.pixels);
                    free(off.pixels);
                }
            }
    mvr_context_destroy(ctx);
}


/* Desktop GL (OSMesa) and GLES give the same image: desktop GL writes sRGB
 * targets encoded only with GL_FRAMEBUFFER_SRGB enabled (a stored linear
 * value is 70 steps darker in mid-tones), and blends in linear light only
 * then. Same Mesa, same shader source: at most one rounding apart. */
static void desktop_and_gles_agree(mvr_test_state *t)
{
    mvr_context_desc dd = {0};
    dd.provider = MVR_CONTEXT_PROVIDER_OSMESA;
    mvr_context *desktop = NULL;
    if (mvr_context_create(&dd, &desktop, NULL) != MVR_OK) {
        CHECK_MSG(t, !mvr_test_in_ci(), "CI builds the OSMesa provider");
        SKIP(t, "no OSMesa provider");
    }
    mvr_context *gles = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    rendered a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    /* the stereo demo has blended glass: both conversions show */
    /* a renderer draws with the context current on the thread */
    bool ok = gles && mvr_context_make_current(desktop) == MVR_OK &&
              render_demo(t, desktop, "stereo", 2, MVR_VIEW_PATH_LOOP, NULL, &a) &&
              mvr_context_make_current(gles) == MVR_OK && render_demo(t, gles, "stereo", 2, MVR_VIEW_PATH_LOOP, NULL, &b);
    CHECK_EQ_INT(t, mvr_context_caps(desktop)->api, MVR_GL_API_DESKTOP);
    if (ok) {
        unsigned worst = 0;
        for (size_t i = 0; i < (size_t)W * H * 2 * 4; ++i) {
            unsigned d = (unsigned)abs((int)a.pixels[i] - (int)b.pixels[i]);
            worst = d > worst ? d : worst;
        }
        CHECK_MSG(t, worst <= 1, "desktop GL and GLES differ by %u/255", worst);
    }
    free(a.pixels);
    free(b.pixels);
    mvr_context_destroy(gles);
    mvr_context_destroy(desktop);
}


/* Desktop GPUs align uniform buffer offsets to 256 bytes: per-draw blocks
 * are then 256 apart, and the instanced draw block pads each element to
 * match (MVR_DRAW_PAD). Emulated here with overrides.ubo_alignment = 256: the same
 * pixels and the same instanced runs as with llvmpipe's 16. */
static void instancing_with_padded_blocks(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    bool have_mv = mvr_context_caps(ctx)->ext.ovr_multiview2;
    const char *demos[2] = {"city", "stereo"};
    for (int d = 0; d < 2; ++d)
        for (int pi = 0; pi < 2; ++pi) {
            mvr_view_path path = pi == 0 && have_mv ? MVR_VIEW_PATH_MULTIVIEW : MVR_VIEW_PATH_LOOP;
            rendered native, padded;
            bool ok = render_demo(t, ctx, demos[d], 2, path, NULL, &native);
            const mvr_renderer_overrides padded_blocks = {.ubo_alignment = 256};
            ok = render_demo_with(t, ctx, demos[d], 2, path, NULL, &padded_blocks, &padded) && ok;
            if (ok) {
                CHECK_MSG(t, count_diff(native.pixels, padded.pixels, (size_t)W * H * 2) == 0,
                          "%s %s: 256-byte blocks changed pixels", demos[d], mvr_view_path_name(path));
                CHECK_EQ_INT(t, padded.second.draw_calls, native.second.draw_calls);
                CHECK_EQ_INT(t, padded.second.instanced_draw_calls, native.second.instanced_draw_calls);
                if (d == 0)
                    CHECK(t, padded.second.instanced_draw_calls > 0);
            }
            free(native.pixels);
            free(padded.pixels);
        }
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(instancing_with_padded_blocks), TEST(desktop_and_gles_agree), TEST(instancing_changes_calls_not_pixels), TEST(blend_pass_only_where_needed), TEST(dirty_tracking_sends_only_changes), TEST(culling_changes_cost_not_pixels), TEST(color_formats_agree), TEST(stereo_paths_agree), TEST(cube_paths_agree), TEST(city_paths_agree), TEST(ring_paths_agree),
              TEST(application_texture_array), TEST(bad_targets_are_refused), TEST(disabled_views_are_skipped))
