/* gl: GL errors never hide. A target the GL cannot hold fails its create
 * with MVR_ERROR_OUT_OF_MEMORY and a message naming the array; an image too
 * large for the GL is downscaled (stats.images_downscaled, the image's own
 * colours, never black) or, with MVR_OVERSIZED_IMAGE_REFUSE, fails the render
 * naming the image; on both material paths. No call returns MVR_OK with a GL
 * error pending, and an error the application left pending is not mvr's.
 *
 * Cheap on purpose (2 cores, ASan): the GL's limits are met without
 * gigabytes. The target asks for GL_MAX_TEXTURE_SIZE squared times
 * GL_MAX_ARRAY_TEXTURE_LAYERS (2 TiB on llvmpipe: refused at once, as over
 * its 2 GiB per-resource limit; no GL allocates that). Images: over
 * GL_MAX_TEXTURE_SIZE with the context's limit lowered (a GLES device with
 * a small limit), and GL_OUT_OF_MEMORY from storage calls wrapped to refuse
 * more than a budget (what llvmpipe answers past 2 GiB: an image of
 * 16384x16384 with its mips and the array's white layer needs 2.7 GiB, and 1
 * GiB of pixels to get there). That real case runs with
 * MVR_TEST_LARGE_IMAGES=1. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <time.h>

#include "renderer.h"
#include "stress/stress_util.h"

#define W 32
#define H 32

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* ---- storage calls that refuse more than a budget, as a GL out of memory does */

typedef struct gl_budget {
    PFNGLTEXSTORAGE2DPROC storage2d;
    PFNGLTEXSTORAGE3DPROC storage3d;
    PFNGLGETERRORPROC get_error;
    uint64_t bytes;              /* 0 = no budget */
    GLenum pending;
    uint32_t refused;
} gl_budget;

/* The GL calls carry no user pointer: one budget for the test process. */
static gl_budget budget;

static uint64_t storage_bytes(GLsizei levels, GLenum format, GLsizei w, GLsizei h, GLsizei layers)
{
    uint64_t texel = format == GL_RGBA32F ? 16 : format == GL_RGBA16F ? 8 : format == GL_R8 ? 1 : 4, sum = 0;
    for (GLsizei l = 0; l < levels; ++l) {
        sum += (uint64_t)w * (uint64_t)h * (uint64_t)layers * texel;
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
    return sum;
}

static bool over_budget(uint64_t bytes)
{
    if (!budget.bytes || bytes <= budget.bytes)
        return false;
    budget.pending = GL_OUT_OF_MEMORY;
    budget.refused++;
    return true;
}

static void GL_APIENTRY budget_storage2d(GLenum target, GLsizei levels, GLenum format, GLsizei w, GLsizei h)
{
    if (!over_budget(storage_bytes(levels, format, w, h, 1)))
        budget.storage2d(target, levels, format, w, h);
}

static void GL_APIENTRY budget_storage3d(GLenum target, GLsizei levels, GLenum format, GLsizei w, GLsizei h,
                                         GLsizei layers)
{
    if (!over_budget(storage_bytes(levels, format, w, h, layers)))
        budget.storage3d(target, levels, format, w, h, layers);
}

static GLenum GL_APIENTRY budget_get_error(void)
{
    GLenum e = budget.pending;
    if (e) {
        budget.pending = GL_NO_ERROR;
        return e;
    }
    return budget.get_error();
}

static void budget_install(mvr_context *ctx, uint64_t bytes)
{
    budget.storage2d = ctx->gl.TexStorage2D;
    budget.storage3d = ctx->gl.TexStorage3D;
    budget.get_error = ctx->gl.GetError;
    budget.bytes = bytes;
    budget.pending = GL_NO_ERROR;
    budget.refused = 0;
    ctx->gl.TexStorage2D = budget_storage2d;
    ctx->gl.TexStorage3D = budget_storage3d;
    ctx->gl.GetError = budget_get_error;
}

static void budget_remove(mvr_context *ctx)
{
    ctx->gl.TexStorage2D = budget.storage2d;
    ctx->gl.TexStorage3D = budget.storage3d;
    ctx->gl.GetError = budget.get_error;
    budget.bytes = 0;
}

/* ---- a target the GL cannot hold */

static void target_too_large_fails(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_caps *c = mvr_context_caps(ctx);
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_renderer_create(&rd, &r, &err) == MVR_OK, "%s", err.message);
    if (!r) {
        mvr_context_destroy(ctx);
        return;
    }
    uint32_t size = (uint32_t)c->limits.max_texture_size, layers = (uint32_t)c->limits.max_array_texture_layers;
    mvr_target_desc td = {.width = size, .height = size, .layers = layers};
    mvr_target *target = NULL;
    double t0 = now_ms();
    mvr_result res = mvr_target_create(r, &td, &target);
    double ms = now_ms() - t0;
    printf("  %ux%u x %u layers (%.0f GiB of color): %s in %.2f ms: %s\n", size, size, layers,
           (double)size * size * layers * 4 / (1024.0 * 1024.0 * 1024.0), mvr_result_name(res), ms,
           mvr_renderer_last_error(r));
    CHECK(t, target == NULL);
    if (res == MVR_ERROR_FRAMEBUFFER && !c->is_software) {
        /* a GL that reserves storage lazily (NVIDIA H100, driver 580) takes
         * the array and refuses the framebuffer: still an error naming it */
        CHECK(t, strstr(mvr_renderer_last_error(r), "framebuffer") != NULL);
        CHECK(t, strstr(mvr_renderer_last_error(r), "GL_FRAMEBUFFER_") != NULL);
    } else {
        CHECK_EQ_INT(t, res, MVR_ERROR_OUT_OF_MEMORY);
        CHECK(t, strstr(mvr_renderer_last_error(r), "color array") != NULL);
        CHECK(t, strstr(mvr_renderer_last_error(r), "GL_OUT_OF_MEMORY") != NULL);
    }
    CHECK_EQ_INT(t, ctx->gl.GetError(), GL_NO_ERROR);

    /* the supersampled array refused after the color array was made: the color array goes too */
    mvr_target_desc small = {.width = W, .height = H, .layers = 2};
    if (c->ext.ext_color_buffer_half_float || c->ext.ext_color_buffer_float) {
        budget_install(ctx, (uint64_t)W * H * 2 * 4);
        mvr_target_desc ss = small;
        ss.supersample = 2;
        res = mvr_target_create(r, &ss, &target);
        CHECK_EQ_INT(t, res, MVR_ERROR_OUT_OF_MEMORY);
        CHECK(t, target == NULL && budget.refused == 1);
        CHECK_MSG(t, strstr(mvr_renderer_last_error(r), "supersampled color array") != NULL, "%s",
                  mvr_renderer_last_error(r));
        budget_remove(ctx);
        CHECK(t, r->targets == NULL);
    }

    /* the renderer is not worse for it */
    mvr_scene *s = stress_scene();
    stress_node(t, s, stress_add_quad(t, s, stress_unlit(t, s, 1, 1, 1)), 0, 0, -1, 1.0);
    mvr_view_set *vs = stress_front_view_set(t);
    CHECK(t, mvr_target_create(r, &small, &target) == MVR_OK);
    CHECK_MSG(t, mvr_renderer_render(r, s, vs, target, NULL) == MVR_OK, "%s", mvr_renderer_last_error(r));
    mvr_target_destroy(target);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_renderer_destroy(r);
    mvr_context_destroy(ctx);
}

/* ---- images too large for the GL */

static const uint8_t orange[3] = {230, 120, 20}, blue[3] = {20, 60, 200};

/* A quad filling an orthographic view, textured (unlit) with an image whose
 * left half is orange and right half blue. */
static mvr_scene *image_scene(mvr_test_state *t, uint32_t iw, uint32_t ih)
{
    mvr_scene *s = stress_scene();
    uint8_t *px = malloc((size_t)iw * ih * 4);
    if (!s || !px) {
        free(px);
        mvr_scene_destroy(s);
        return NULL;
    }
    for (uint32_t y = 0; y < ih; ++y)
        for (uint32_t x = 0; x < iw; ++x) {
            uint8_t *p = px + ((size_t)y * iw + x) * 4;
            memcpy(p, x < iw / 2 ? orange : blue, 3);
            p[3] = 255;
        }
    mvr_image_desc id = {.width = iw, .height = ih, .rgba8 = px, .name = "huge"};
    stress_unlit_image_quad(t, s, &id);
    free(px);
    return s;
}

static bool near_colour(const uint8_t *p, const uint8_t want[3])
{
    for (int c = 0; c < 3; ++c)
        if (abs((int)p[c] - (int)want[c]) > 2)
            return false;
    return true;
}

typedef struct image_case {
    const char *name;
    mvr_material_path path;
    mvr_oversized_image policy;
    mvr_result want;             /* of the render */
    const char *message;         /* in the failure's message */
} image_case;

/* Renders the scene; on success checks stats and the two halves' colours. */
static void run_image_case(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, const image_case *ic,
                           uint32_t want_downscaled)
{
    log_sink sink = {0};
    mvr_renderer_desc rd = {.context = ctx, .material_path = ic->path, .oversized_images = ic->policy,
                            .logger = {log_sink_fn, &sink, MVR_LOG_INFO}};
    mvr_renderer *r = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_renderer_create(&rd, &r, &err) == MVR_OK, "%s", err.message);
    mvr_target_desc td = {.width = W, .height = H, .layers = 1};
    mvr_target *target = NULL;
    CHECK(t, r && mvr_target_create(r, &td, &target) == MVR_OK);
    mvr_view_set *vs = stress_front_view_set(t);
    if (target && vs) {
        mvr_render_desc desc = {.clear_color = {0, 0, 0, 1}};
        double t0 = now_ms();
        mvr_result res = mvr_renderer_render(r, s, vs, target, &desc);
        double ms = now_ms() - t0;
        printf("  %s: %s in %.0f ms%s%s\n", ic->name, mvr_result_name(res), ms, res ? ": " : "",
               res ? mvr_renderer_last_error(r) : "");
        CHECK_MSG(t, res == ic->want, "%s: %s, want %s (%s)", ic->name, mvr_result_name(res),
                  mvr_result_name(ic->want), mvr_renderer_last_error(r));
        CHECK_EQ_INT(t, ctx->gl.GetError(), GL_NO_ERROR);
        if (res != MVR_OK && ic->message)
            CHECK_MSG(t, strstr(mvr_renderer_last_error(r), ic->message) != NULL, "%s: message '%s' lacks '%s'",
                      ic->name, mvr_renderer_last_error(r), ic->message);
        if (res == MVR_OK) {
            mvr_frame_stats st;
            mvr_renderer_get_stats(r, &st);
            CHECK_MSG(t, st.images_downscaled == want_downscaled, "%s: %u images downscaled, want %u", ic->name,
                      st.images_downscaled, want_downscaled);
            CHECK_EQ_INT(t, st.material_path, ic->path);
            if (want_downscaled)
                CHECK_MSG(t, sink.warnings > 0, "%s: the downscale was not logged", ic->name);
            uint8_t px[W * H * 4];
            CHECK(t, mvr_renderer_read_layer(r, target, 0, MVR_READBACK_RGBA8, px, sizeof px) == MVR_OK);
            const uint8_t *left = px + ((H / 2) * W + W / 4) * 4, *right = px + ((H / 2) * W + 3 * W / 4) * 4;
            CHECK_MSG(t, near_colour(left, orange) && near_colour(right, blue),
                      "%s: left %u,%u,%u (want orange), right %u,%u,%u (want blue)", ic->name, left[0], left[1],
                      left[2], right[0], right[1], right[2]);
            /* the next frame (nothing to upload) reports the same */
            CHECK(t, mvr_renderer_render(r, s, vs, target, &desc) == MVR_OK);
            mvr_renderer_get_stats(r, &st);
            CHECK_EQ_INT(t, st.images_downscaled, want_downscaled);
        } else {
            /* refused, and still refused: nothing half made is taken for done */
            CHECK_EQ_INT(t, mvr_renderer_render(r, s, vs, target, &desc), ic->want);
            CHECK_EQ_INT(t, ctx->gl.GetError(), GL_NO_ERROR);
        }
    }
    mvr_view_set_destroy(vs);
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
}

static const mvr_material_path paths[2] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL};

/* auto's material tuner told that `cheap` costs less: it settles there. */
static double material_cost(void *user, mvr_view_path path, const mvr_frame_stats *stats)
{
    (void)path;
    return stats->material_path == *(const mvr_material_path *)user ? 1.0 : 2.0;
}

/* The material path tuned (both representations resident while measured,
 * the other released once settled): the downscaled image is still counted,
 * and still drawn in its colours. */
static void tuned_keeps_the_downscaled_count(mvr_test_state *t, mvr_context *ctx, mvr_scene *s)
{
    for (int p = 0; p < 2; ++p) {
        mvr_material_path cheap = paths[p];
        mvr_renderer_desc rd = {.context = ctx, .tuning = {.frame_cost = material_cost, .user = &cheap}};
        mvr_renderer *r = NULL;
        mvr_target *target = NULL;
        mvr_target_desc td = {.width = W, .height = H, .layers = 1};
        CHECK(t, mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK);
        mvr_view_set *vs = stress_front_view_set(t);
        mvr_frame_stats st;
        memset(&st, 0, sizeof st);
        mvr_render_desc desc = {.clear_color = {0, 0, 0, 1}};
        for (int f = 0; target && vs && f < 40 && st.auto_material.state != MVR_AUTO_SETTLED; ++f) {
            CHECK(t, mvr_renderer_render(r, s, vs, target, &desc) == MVR_OK);
            mvr_renderer_get_stats(r, &st);
            CHECK_MSG(t, st.images_downscaled == 1, "frame %d (%s): %u images downscaled", f,
                      mvr_material_path_name(st.material_path), st.images_downscaled);
        }
        CHECK(t, st.auto_material.state == MVR_AUTO_SETTLED && st.auto_material.chosen == cheap);
        /* settled: the other representation released, the count unchanged */
        if (target && vs && mvr_renderer_render(r, s, vs, target, &desc) == MVR_OK) {
            mvr_renderer_get_stats(r, &st);
            CHECK_MSG(t, st.material_path == cheap && st.images_downscaled == 1, "settled on %s: %u downscaled",
                      mvr_material_path_name(st.material_path), st.images_downscaled);
            uint8_t px[W * H * 4];
            CHECK(t, mvr_renderer_read_layer(r, target, 0, MVR_READBACK_RGBA8, px, sizeof px) == MVR_OK);
            const uint8_t *left = px + ((H / 2) * W + W / 4) * 4, *right = px + ((H / 2) * W + 3 * W / 4) * 4;
            CHECK(t, near_colour(left, orange) && near_colour(right, blue));
        }
        mvr_view_set_destroy(vs);
        mvr_target_destroy(target);
        mvr_renderer_destroy(r);
    }
}

/* Over GL_MAX_TEXTURE_SIZE: the context's limit lowered to 64 (the GL's own
 * limit is the scene's maximum, 16384, here), a 256x256 image. */
static void image_over_max_texture_size(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    ctx->caps.limits.max_texture_size = 64;
    mvr_scene *s = image_scene(t, 256, 256);
    for (int p = 0; p < 2 && s; ++p) {
        image_case down = {mvr_material_path_name(paths[p]), paths[p], MVR_OVERSIZED_IMAGE_DEFAULT, MVR_OK, NULL};
        run_image_case(t, ctx, s, &down, 1);
        image_case refuse = {"refuse", paths[p], MVR_OVERSIZED_IMAGE_REFUSE, MVR_ERROR_UNSUPPORTED, "image 1 'huge'"};
        run_image_case(t, ctx, s, &refuse, 0);
    }
    if (s)
        tuned_keeps_the_downscaled_count(t, ctx, s);
    /* within the limit: nothing downscaled */
    ctx->caps.limits.max_texture_size = 256;
    image_case fits = {"fits", MVR_MATERIAL_PATH_ARRAYS, MVR_OVERSIZED_IMAGE_REFUSE, MVR_OK, NULL};
    if (s)
        run_image_case(t, ctx, s, &fits, 0);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* GL_OUT_OF_MEMORY: storage over 256 KiB refused. A 512x512 image with its
 * mips is 1.3 MiB (2.7 with the array path's white layer): stored at
 * 128x128 on both paths. */
static void image_out_of_memory(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = image_scene(t, 512, 512);
    budget_install(ctx, 256 * 1024);
    for (int p = 0; p < 2 && s; ++p) {
        image_case down = {mvr_material_path_name(paths[p]), paths[p], MVR_OVERSIZED_IMAGE_DEFAULT, MVR_OK, NULL};
        budget.refused = 0;
        run_image_case(t, ctx, s, &down, 1);
        CHECK_MSG(t, budget.refused == 2, "%s: %u allocations refused, want 2 (512, 256: then 128 fits)",
                  down.name, budget.refused);
        image_case refuse = {"refuse", paths[p], MVR_OVERSIZED_IMAGE_REFUSE, MVR_ERROR_OUT_OF_MEMORY, "image 1 'huge'"};
        run_image_case(t, ctx, s, &refuse, 0);
        image_case oom = {"refuse", paths[p], MVR_OVERSIZED_IMAGE_REFUSE, MVR_ERROR_OUT_OF_MEMORY, "GL_OUT_OF_MEMORY"};
        run_image_case(t, ctx, s, &oom, 0);
    }
    budget_remove(ctx);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* The real thing on llvmpipe: 16384x16384 (1 GiB of pixels), whose array
 * with mips and a white layer (2.7 GiB) is over llvmpipe's 2 GiB. */
static void image_out_of_memory_for_real(mvr_test_state *t)
{
    const char *env = getenv("MVR_TEST_LARGE_IMAGES");
    if (!env || strcmp(env, "1") != 0)
        SKIP(t, "MVR_TEST_LARGE_IMAGES=1 runs it (2.2 GB of memory, 9 s on llvmpipe)");
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    double t0 = now_ms();
    mvr_scene *s = image_scene(t, 16384, 16384);
    printf("  scene with a 16384x16384 image: %.0f ms\n", now_ms() - t0);
    image_case down = {"arrays, 16384x16384", MVR_MATERIAL_PATH_ARRAYS, MVR_OVERSIZED_IMAGE_DEFAULT, MVR_OK, NULL};
    if (s)
        run_image_case(t, ctx, s, &down, 1);
    image_case refuse = {"arrays, 16384x16384, refuse", MVR_MATERIAL_PATH_ARRAYS, MVR_OVERSIZED_IMAGE_REFUSE,
                         MVR_ERROR_OUT_OF_MEMORY, "GL_OUT_OF_MEMORY"};
    if (s)
        run_image_case(t, ctx, s, &refuse, 0);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* An error the application left pending is not mvr's: logged as such,
 * dropped, and the call succeeds; an error of mvr's own fails its call. */
static void application_error_is_not_blamed(mvr_test_state *t)
{
    log_sink sink = {0};
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, &sink);
    if (!ctx)
        return;
    mvr_scene *s = image_scene(t, 8, 8);
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_renderer_create(&rd, &r, &err) == MVR_OK, "%s", err.message);
    mvr_target_desc td = {.width = W, .height = H, .layers = 1};
    mvr_target *target = NULL;
    CHECK(t, r && mvr_target_create(r, &td, &target) == MVR_OK);
    mvr_view_set *vs = stress_front_view_set(t);
    if (s && target && vs) {
        ctx->gl.Enable(0x1234); /* GL_INVALID_ENUM, the application's */
        int warnings = sink.warnings;
        CHECK_MSG(t, mvr_renderer_render(r, s, vs, target, NULL) == MVR_OK, "%s", mvr_renderer_last_error(r));
        CHECK_MSG(t, sink.warnings == warnings + 1, "the application's error was not reported as such");
        CHECK_EQ_INT(t, sink.errors, 0);
        CHECK_EQ_INT(t, ctx->gl.GetError(), GL_NO_ERROR);
        uint8_t px[W * H * 4];
        CHECK(t, mvr_renderer_read_layer(r, target, 0, MVR_READBACK_RGBA8, px, sizeof px) == MVR_OK);
        CHECK(t, near_colour(px + ((H / 2) * W + W / 4) * 4, orange));

        /* mvr's own error (its material buffer refused) fails the render, and none is left pending */
        budget_install(ctx, 1);
        mvr_scene *s2 = image_scene(t, 8, 8);
        mvr_result res = mvr_renderer_render(r, s2, vs, target, NULL);
        CHECK_MSG(t, res == MVR_ERROR_OUT_OF_MEMORY, "%s: %s", mvr_result_name(res), mvr_renderer_last_error(r));
        CHECK_EQ_INT(t, ctx->gl.GetError(), GL_NO_ERROR);
        budget_remove(ctx);
        mvr_scene_destroy(s2);
    }
    mvr_view_set_destroy(vs);
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(target_too_large_fails), TEST(image_over_max_texture_size), TEST(image_out_of_memory),
              TEST(image_out_of_memory_for_real), TEST(application_error_is_not_blamed))
