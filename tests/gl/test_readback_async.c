/* gl: asynchronous readback (gl/readback_async.c). What a readback gives is
 * mvr_renderer_read_layer's bytes, layer for layer: several layer ranges,
 * both formats of 8-bit and float targets, the multiview and loop paths,
 * one readback reused over several frames; each extra output (depth,
 * distance, normals, IDs, coverage) read is mvr_renderer_read_output's
 * bytes, on both paths; a read is of the target as it
 * was when the read began, whatever is rendered into it afterwards; bad
 * arguments (an output the target lacks among them) are refused with a
 * message naming what is wrong, and a
 * readback outlives its renderer without a leak or a crash (ASan). */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>

#include "gl_test_util.h"

#define W 40
#define H 30
#define VIEWS 8

/* The city demo's 8 views, the clear colour moved per frame so that frames
 * differ everywhere the sky shows. */
static bool render_frame(mvr_test_state *t, mvr_renderer *r, mvr_scene *s, mvr_view_set *vs, mvr_target *tg,
                         int frame)
{
    mvr_render_desc rd = {.clear_color = {0.1f * (float)frame, 0.2f, 0.3f, 1.0f}};
    mvr_result res = mvr_renderer_render(r, s, vs, tg, &rd);
    CHECK_MSG(t, res == MVR_OK, "render: %s", mvr_renderer_last_error(r));
    return res == MVR_OK;
}

/* Layers [first, first + count) by mvr_renderer_read_layer, one after another. */
static void *read_sync(mvr_test_state *t, mvr_renderer *r, mvr_target *tg, uint32_t first, uint32_t count,
                       mvr_readback_format f)
{
    size_t layer = (size_t)W * H * (f == MVR_READBACK_RGBA32F ? 16 : 4);
    uint8_t *px = malloc(layer * count);
    for (uint32_t k = 0; px && k < count; ++k)
        CHECK_MSG(t, mvr_renderer_read_layer(r, tg, first + k, f, px + layer * k, layer) == MVR_OK, "read_layer: %s",
                  mvr_renderer_last_error(r));
    return px;
}

static void *finish(mvr_test_state *t, mvr_renderer *r, mvr_readback *rb, size_t want)
{
    size_t size = mvr_readback_size(rb);
    CHECK_EQ_INT(t, size, want);
    void *px = malloc(size ? size : 1);
    mvr_result res = mvr_renderer_finish_read(r, rb, px, size);
    CHECK_MSG(t, res == MVR_OK, "finish: %s", mvr_renderer_last_error(r));
    CHECK_EQ_INT(t, mvr_readback_size(rb), 0); /* free for the next read */
    return px;
}

/* Both paths, 8-bit (sRGB) and float targets, both formats each, layer
 * ranges at the start, in the middle and at the end, one readback for all
 * of a renderer's reads over three frames. */
static void async_equals_read_layer(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {.views = VIEWS, .width = W, .height = H};
    CHECK(t, mvr_demo_create("city", &dd, &s, &vs, NULL) == MVR_OK);
    bool multiview = mvr_context_caps(ctx)->ext.ovr_multiview2;
    const mvr_view_path paths[2] = {MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_MULTIVIEW};
    const mvr_color_format formats[2] = {MVR_COLOR_FORMAT_DEFAULT, MVR_COLOR_FORMAT_RGBA32F};
    const uint32_t ranges[][2] = {{0, 1}, {2, 3}, {5, 3}, {0, VIEWS}};
    int compared = 0;
    for (int p = 0; p < 2 && s; ++p) {
        if (paths[p] == MVR_VIEW_PATH_MULTIVIEW && !multiview) {
            printf("  no GL_OVR_multiview2: the loop path only\n");
            continue;
        }
        for (int c = 0; c < 2; ++c) {
            mvr_renderer_desc rd = {.context = ctx, .view_path = paths[p]};
            mvr_renderer *r = NULL;
            mvr_target *tg = NULL;
            mvr_readback *rb = NULL;
            mvr_target_desc td = {.width = W, .height = H, .layers = VIEWS, .color_format = formats[c]};
            bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK &&
                      mvr_readback_create(r, &rb) == MVR_OK;
            CHECK(t, ok);
            for (int frame = 0; ok && frame < 3; ++frame) {
                ok = render_frame(t, r, s, vs, tg, frame);
                for (size_t i = 0; ok && i < sizeof ranges / sizeof ranges[0]; ++i)
                    for (int f = 0; f < 2; ++f) {
                        mvr_readback_format rf = f ? MVR_READBACK_RGBA32F : MVR_READBACK_RGBA8;
                        size_t layer = (size_t)W * H * (f ? 16 : 4);
                        mvr_read_desc d = {.first_layer = ranges[i][0],
                                           .layer_count = i == 3 ? 0 : ranges[i][1], /* 0: to the end */
                                           .format = rf};
                        mvr_result res = mvr_renderer_begin_read(r, tg, &d, rb);
                        CHECK_MSG(t, res == MVR_OK, "begin_read: %s", mvr_renderer_last_error(r));
                        if (res != MVR_OK)
                            continue;
                        CHECK_EQ_INT(t, mvr_readback_layer_count(rb), ranges[i][1]);
                        CHECK_EQ_INT(t, mvr_readback_layer_size(rb), layer);
                        bool ready = false;
                        CHECK(t, mvr_renderer_read_ready(r, rb, &ready) == MVR_OK);
                        void *async = finish(t, r, rb, layer * ranges[i][1]);
                        void *sync = read_sync(t, r, tg, ranges[i][0], ranges[i][1], rf);
                        CHECK_MSG(t, memcmp(async, sync, layer * ranges[i][1]) == 0,
                                  "%s path, %s target, %s, layers %u+%u, frame %d: async differs from read_layer",
                                  mvr_view_path_name(paths[p]), c ? "float" : "8-bit", f ? "RGBA32F" : "RGBA8",
                                  ranges[i][0], ranges[i][1], frame);
                        compared++;
                        free(async);
                        free(sync);
                    }
            }
            mvr_readback_destroy(rb);
            mvr_target_destroy(tg);
            mvr_renderer_destroy(r);
        }
    }
    printf("  %d reads compared\n", compared);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

#define ALL_OUTPUTS                                                                                                   \
    (MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH) | MVR_OUTPUT_BIT(MVR_OUTPUT_DISTANCE) | MVR_OUTPUT_BIT(MVR_OUTPUT_NORMAL) |       \
     MVR_OUTPUT_BIT(MVR_OUTPUT_IDS) | MVR_OUTPUT_BIT(MVR_OUTPUT_COVERAGE))

/* Every extra output of a target with all of them, read asynchronously over
 * several layer ranges, is mvr_renderer_read_output's bytes layer for layer,
 * on the loop and multiview paths; the colour of the same target still
 * reads as before. Several readbacks hold reads of different outputs at
 * once (as mvr render's stream does). */
static void outputs_equal_read_output(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {.views = VIEWS, .width = W, .height = H};
    CHECK(t, mvr_demo_create("city", &dd, &s, &vs, NULL) == MVR_OK);
    bool multiview = mvr_context_caps(ctx)->ext.ovr_multiview2;
    const mvr_view_path paths[2] = {MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_MULTIVIEW};
    const uint32_t ranges[][2] = {{0, VIEWS}, {2, 3}, {7, 1}};
    int compared = 0;
    for (int p = 0; p < 2 && s; ++p) {
        if (paths[p] == MVR_VIEW_PATH_MULTIVIEW && !multiview) {
            printf("  no GL_OVR_multiview2: the loop path only\n");
            continue;
        }
        mvr_renderer_desc rd = {.context = ctx, .view_path = paths[p]};
        mvr_renderer *r = NULL;
        mvr_target *tg = NULL;
        mvr_readback *rb[MVR_OUTPUT_COUNT] = {NULL};
        mvr_target_desc td = {.width = W, .height = H, .layers = VIEWS, .outputs = ALL_OUTPUTS};
        bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK;
        for (int k = 0; ok && k < MVR_OUTPUT_COUNT; ++k)
            ok = mvr_readback_create(r, &rb[k]) == MVR_OK;
        CHECK_MSG(t, ok, "setup: %s", r ? mvr_renderer_last_error(r) : "no renderer");
        ok = ok && render_frame(t, r, s, vs, tg, 1);
        for (size_t i = 0; ok && i < sizeof ranges / sizeof ranges[0]; ++i) {
            uint32_t first = ranges[i][0], count = ranges[i][1];
            /* every output's read begun before any is finished */
            for (int k = 0; k < MVR_OUTPUT_COUNT; ++k) {
                mvr_read_desc d = {.first_layer = first, .layer_count = count, .output = (mvr_output)k};
                mvr_result res = mvr_renderer_begin_read(r, tg, &d, rb[k]);
                CHECK_MSG(t, res == MVR_OK, "begin_read %s: %s", mvr_output_name((mvr_output)k),
                          mvr_renderer_last_error(r));
                ok = ok && res == MVR_OK;
            }
            for (int k = 0; ok && k < MVR_OUTPUT_COUNT; ++k) {
                mvr_output out = (mvr_output)k;
                size_t layer = (size_t)W * H * mvr_output_pixel_size(out);
                CHECK_EQ_INT(t, mvr_readback_layer_size(rb[k]), layer);
                CHECK_EQ_INT(t, mvr_readback_layer_count(rb[k]), count);
                uint8_t *async = finish(t, r, rb[k], layer * count);
                uint8_t *sync = malloc(layer * count);
                bool nonzero = false;
                for (uint32_t l = 0; sync && l < count; ++l)
                    CHECK_MSG(t, mvr_renderer_read_output(r, tg, first + l, out, sync + layer * l, layer) == MVR_OK,
                              "read_output: %s", mvr_renderer_last_error(r));
                for (size_t b = 0; sync && b < layer * count && !nonzero; ++b)
                    nonzero = sync[b] != 0;
                CHECK_MSG(t, nonzero, "%s of layers %u+%u is all zero: the test tests nothing", mvr_output_name(out),
                          first, count);
                CHECK_MSG(t, sync && memcmp(async, sync, layer * count) == 0,
                          "%s path, %s, layers %u+%u: async differs from read_output", mvr_view_path_name(paths[p]),
                          mvr_output_name(out), first, count);
                compared++;
                free(async);
                free(sync);
            }
        }
        for (int k = 0; k < MVR_OUTPUT_COUNT; ++k)
            mvr_readback_destroy(rb[k]);
        mvr_target_destroy(tg);
        mvr_renderer_destroy(r);
    }
    printf("  %d output reads compared\n", compared);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* A read is of the target as it was when it began: a frame rendered into
 * the same target before the read is finished does not show in it, and
 * the readiness query turns true without anyone waiting. Two readbacks in
 * flight at once keep their own frames. */
static void read_sees_the_frame_it_began_on(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {.views = VIEWS, .width = W, .height = H};
    CHECK(t, mvr_demo_create("city", &dd, &s, &vs, NULL) == MVR_OK);
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL;
    mvr_target *tg = NULL;
    mvr_readback *rb[2] = {NULL, NULL};
    mvr_target_desc td = {.width = W, .height = H, .layers = VIEWS};
    bool ok = s && mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK &&
              mvr_readback_create(r, &rb[0]) == MVR_OK && mvr_readback_create(r, &rb[1]) == MVR_OK;
    CHECK(t, ok);
    size_t bytes = (size_t)W * H * 4 * VIEWS;
    void *want[2] = {NULL, NULL};
    mvr_read_desc d = {0};
    for (int frame = 0; ok && frame < 2; ++frame) {
        ok = render_frame(t, r, s, vs, tg, frame);
        want[frame] = ok ? read_sync(t, r, tg, 0, VIEWS, MVR_READBACK_RGBA8) : NULL;
        ok = ok && mvr_renderer_begin_read(r, tg, &d, rb[frame]) == MVR_OK;
    }
    /* a third frame over both */
    ok = ok && render_frame(t, r, s, vs, tg, 2);
    CHECK(t, ok);
    if (ok) {
        CHECK_MSG(t, memcmp(want[0], want[1], bytes) != 0, "the frames do not differ: the test tests nothing");
        bool ready = false;
        for (int spin = 0; spin < 100000 && !ready; ++spin)
            CHECK(t, mvr_renderer_read_ready(r, rb[1], &ready) == MVR_OK);
        CHECK_MSG(t, ready, "the read never became ready without a wait");
        for (int k = 1; k >= 0; --k) {
            void *got = finish(t, r, rb[k], bytes);
            CHECK_MSG(t, memcmp(got, want[k], bytes) == 0, "readback %d does not hold frame %d", k, k);
            free(got);
        }
    }
    free(want[0]);
    free(want[1]);
    mvr_readback_destroy(rb[0]);
    mvr_readback_destroy(rb[1]);
    mvr_target_destroy(tg);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

static bool failed_with(mvr_test_state *t, mvr_renderer *r, mvr_result res, const char *needle, const char *what)
{
    bool ok = res != MVR_OK && strstr(mvr_renderer_last_error(r), needle) != NULL;
    CHECK_MSG(t, ok, "%s: result %d, message '%s' (want '%s')", what, (int)res, mvr_renderer_last_error(r), needle);
    return ok;
}

/* Each refusal names what is wrong, changes nothing (a good read works
 * after it), and leaves no GL error behind; the readback of a destroyed
 * renderer fails and frees. */
static void bad_arguments_are_refused(mvr_test_state *t)
{
    log_sink sink = {0};
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, &sink);
    if (!ctx)
        return;
    mvr_scene *s = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {.views = 2, .width = W, .height = H};
    CHECK(t, mvr_demo_create("stereo", &dd, &s, &vs, NULL) == MVR_OK);
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL, *other = NULL;
    mvr_target *tg = NULL, *other_tg = NULL;
    mvr_readback *rb = NULL, *other_rb = NULL;
    mvr_target_desc td = {.width = W, .height = H, .layers = 2};
    bool ok = s && mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_renderer_create(&rd, &other, NULL) == MVR_OK &&
              mvr_target_create(r, &td, &tg) == MVR_OK && mvr_target_create(other, &td, &other_tg) == MVR_OK &&
              mvr_readback_create(r, &rb) == MVR_OK && mvr_readback_create(other, &other_rb) == MVR_OK;
    CHECK(t, ok);
    if (ok)
        ok = render_frame(t, r, s, vs, tg, 0);
    if (ok) {
        uint8_t px[W * H * 4 * 2];
        bool ready = true;
        mvr_read_desc d = {.first_layer = 0, .layer_count = 2};
        CHECK(t, mvr_readback_create(NULL, &rb) == MVR_ERROR_INVALID_ARGUMENT);
        failed_with(t, r, mvr_readback_create(r, NULL), "out is NULL", "create without out");
        failed_with(t, r, mvr_renderer_begin_read(r, tg, &d, NULL), "readback is NULL", "NULL readback");
        failed_with(t, r, mvr_renderer_begin_read(r, NULL, &d, rb), "target or desc is NULL", "NULL target");
        failed_with(t, r, mvr_renderer_begin_read(r, tg, NULL, rb), "target or desc is NULL", "NULL desc");
        failed_with(t, r, mvr_renderer_begin_read(r, other_tg, &d, rb), "another renderer", "another's target");
        failed_with(t, r, mvr_renderer_begin_read(r, tg, &d, other_rb), "another renderer", "another's readback");
        mvr_read_desc bad = {.first_layer = 2};
        failed_with(t, r, mvr_renderer_begin_read(r, tg, &bad, rb), "first layer 2 of a target of 2", "past the end");
        bad = (mvr_read_desc){.first_layer = 1, .layer_count = 2};
        failed_with(t, r, mvr_renderer_begin_read(r, tg, &bad, rb), "layers 1 .. 2 of a target of 2", "range");
        bad = (mvr_read_desc){.format = (mvr_readback_format)7};
        failed_with(t, r, mvr_renderer_begin_read(r, tg, &bad, rb), "unknown format 7", "format");
        bad = (mvr_read_desc){.output = MVR_OUTPUT_DEPTH};
        failed_with(t, r, mvr_renderer_begin_read(r, tg, &bad, rb),
                    "the target was not created with the depth output", "an output the target lacks");
        bad = (mvr_read_desc){.output = MVR_OUTPUT_IDS, .format = MVR_READBACK_RGBA32F};
        failed_with(t, r, mvr_renderer_begin_read(r, tg, &bad, rb), "not created with the ids output", "ids");
        bad = (mvr_read_desc){.output = (mvr_output)9};
        failed_with(t, r, mvr_renderer_begin_read(r, tg, &bad, rb), "unknown output 9", "output");
        failed_with(t, r, mvr_renderer_finish_read(r, rb, px, sizeof px), "no read is pending", "finish, none");
        failed_with(t, r, mvr_renderer_read_ready(r, rb, &ready), "no read is pending", "ready, none");
        CHECK(t, !ready);
        CHECK_EQ_INT(t, mvr_readback_size(rb), 0);
        /* a good read, refused a second begin and a short buffer, still finishes */
        CHECK(t, mvr_renderer_begin_read(r, tg, &d, rb) == MVR_OK);
        failed_with(t, r, mvr_renderer_begin_read(r, tg, &d, rb), "a read not finished", "begin twice");
        failed_with(t, r, mvr_renderer_read_ready(r, rb, NULL), "ready is NULL", "ready NULL");
        failed_with(t, r, mvr_renderer_finish_read(r, rb, NULL, sizeof px), "dst is NULL", "finish NULL");
        failed_with(t, r, mvr_renderer_finish_read(r, rb, px, sizeof px - 1), "buffer of 9599 bytes, 9600 needed",
                    "short buffer");
        CHECK(t, mvr_renderer_finish_read(r, rb, px, sizeof px) == MVR_OK);
        uint8_t want[W * H * 4];
        CHECK(t, mvr_renderer_read_layer(r, tg, 1, MVR_READBACK_RGBA8, want, sizeof want) == MVR_OK);
        CHECK(t, memcmp(px + sizeof want, want, sizeof want) == 0);
        /* a pending read dropped by destroy, and one left to its renderer */
        CHECK(t, mvr_renderer_begin_read(r, tg, &d, rb) == MVR_OK);
        CHECK(t, mvr_renderer_begin_read(other, other_tg, &d, other_rb) == MVR_OK);
        mvr_renderer_destroy(other);
        other = NULL;
        failed_with(t, r, mvr_renderer_finish_read(r, other_rb, px, sizeof px), "released with its renderer",
                    "readback of a destroyed renderer");
    }
    CHECK_EQ_INT(t, mvr_gl_check(ctx, "after the refusals", false), MVR_OK);
    mvr_readback_destroy(rb);
    mvr_readback_destroy(other_rb);
    mvr_readback_destroy(NULL);
    mvr_target_destroy(tg);
    mvr_target_destroy(other_tg);
    mvr_renderer_destroy(r);
    mvr_renderer_destroy(other);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* The context destroyed under a pending read: the readback's calls fail
 * (its renderer's context is gone), and destroying it and the renderer
 * afterwards frees everything (ASan). */
static void readback_outlives_its_context(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {.views = 2, .width = W, .height = H};
    CHECK(t, mvr_demo_create("stereo", &dd, &s, &vs, NULL) == MVR_OK);
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL;
    mvr_target *tg = NULL;
    mvr_readback *rb = NULL;
    mvr_target_desc td = {.width = W, .height = H, .layers = 2};
    mvr_read_desc d = {0};
    bool ok = s && mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK &&
              mvr_readback_create(r, &rb) == MVR_OK && render_frame(t, r, s, vs, tg, 0) &&
              mvr_renderer_begin_read(r, tg, &d, rb) == MVR_OK;
    CHECK(t, ok);
    mvr_context_destroy(ctx);
    if (ok) {
        uint8_t px[W * H * 4 * 2];
        bool ready = true;
        failed_with(t, r, mvr_renderer_finish_read(r, rb, px, sizeof px), "released with its renderer", "finish");
        failed_with(t, r, mvr_renderer_read_ready(r, rb, &ready), "released with its renderer", "ready");
        CHECK_EQ_INT(t, mvr_readback_size(rb), 0);
        mvr_readback *late = NULL;
        failed_with(t, r, mvr_readback_create(r, &late), "context was destroyed", "create after");
        CHECK(t, late == NULL);
    }
    mvr_readback_destroy(rb);
    mvr_target_destroy(tg);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(async_equals_read_layer), TEST(outputs_equal_read_output), TEST(read_sees_the_frame_it_began_on), TEST(bad_arguments_are_refused),
              TEST(readback_outlives_its_context))
