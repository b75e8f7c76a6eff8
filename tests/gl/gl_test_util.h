/* Helpers for the headless GL tests. */
#ifndef MVR_GL_TEST_UTIL_H
#define MVR_GL_TEST_UTIL_H

#include "context_internal.h"
#include "mvr_test.h"

/* Collects error-level log messages so tests can assert on them. */
typedef struct log_sink {
    int errors;
    int warnings;
    char last_error[1024];
} log_sink;

static inline void log_sink_fn(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    (void)id;
    log_sink *s = user;
    if (level == MVR_LOG_ERROR) {
        s->errors++;
        mvr_str_copy(s->last_error, sizeof s->last_error, message);
    } else if (level == MVR_LOG_WARNING) {
        s->warnings++;
    }
}

/* MVR_TEST_GL_DEBUG=1 (a diagnostic, as scripts/gpu_check's device runs
 * use it): the context is made with desc.debug (a KHR_debug context, GL
 * errors checked after mvr's work) and the driver's debug messages above
 * notification severity and mvr's GL errors go to stderr, each line
 * prefixed "gl-debug:", beside whatever sink the test gave. */
typedef struct debug_tee {
    log_sink *sink;
} debug_tee;

static inline void debug_tee_fn(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    debug_tee *tee = user;
    if ((id == MVR_LOG_ID_GL_DEBUG && level >= MVR_LOG_INFO) || id == MVR_LOG_ID_GL_ERROR)
        fprintf(stderr, "gl-debug: %s\n", message);
    if (tee->sink)
        log_sink_fn(level, id, message, tee->sink);
}

/* The tests render on the surfaceless provider; MVR_TEST_CONTEXT names
 * another for them (device: a GPU's EGL device, as scripts/gpu_check runs
 * them). Tests that ask for another provider on purpose keep it. */
static inline mvr_context *create_or_report(mvr_test_state *t, mvr_context_provider provider,
                                            mvr_gl_api api, log_sink *sink)
{
    const char *forced = getenv("MVR_TEST_CONTEXT");
    if (provider == MVR_CONTEXT_PROVIDER_SURFACELESS && forced && forced[0]) {
        mvr_context_provider p = provider;
        CHECK_MSG(t, mvr_context_provider_from_name(forced, &p) == MVR_OK,
                  "MVR_TEST_CONTEXT=%s is no provider name", forced);
        provider = p;
    }
    mvr_context_desc desc = {0};
    desc.provider = provider;
    desc.api = api;
    if (sink) {
        desc.logger.fn = log_sink_fn;
        desc.logger.user_data = sink;
    }
    const char *debug = getenv("MVR_TEST_GL_DEBUG");
    static debug_tee tees[8]; /* tests make a few contexts, one after another */
    static unsigned tee_next;
    if (debug && debug[0] == '1') {
        debug_tee *tee = &tees[tee_next++ % 8];
        tee->sink = sink;
        desc.debug = true;
        desc.logger.fn = debug_tee_fn;
        desc.logger.user_data = tee;
    }
    mvr_context *ctx = NULL;
    mvr_error err;
    mvr_result r = mvr_context_create(&desc, &ctx, &err);
    CHECK_MSG(t, r == MVR_OK, "%s provider: %s", mvr_context_provider_name(provider), err.message);
    return r == MVR_OK ? ctx : NULL;
}

/* Where two renders of w x h RGBA8 layers differ, as a picture of the
 * difference: per layer, the differing pixel count, the box holding them,
 * the largest channel difference and an 8x8 map of the layer ('.' same,
 * '1'-'9' tenths of the cell's pixels differing). Printed only when they
 * differ; the pattern says what kind of fault it is (one tile: a race; a
 * layer: a view mixed up; edges: rasterization; everywhere: state). */
static inline void report_image_diff(const char *label, const uint8_t *a, const uint8_t *b, uint32_t w,
                                     uint32_t h, uint32_t layers)
{
    for (uint32_t l = 0; l < layers; ++l) {
        const uint8_t *pa = a + (size_t)l * w * h * 4, *pb = b + (size_t)l * w * h * 4;
        uint32_t n = 0, x0 = w, y0 = h, x1 = 0, y1 = 0, worst = 0;
        uint32_t cell[8][8] = {{0}};
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                const uint8_t *ca = pa + ((size_t)y * w + x) * 4, *cb = pb + ((size_t)y * w + x) * 4;
                uint32_t d = 0;
                for (int c = 0; c < 4; ++c) {
                    uint32_t e = ca[c] > cb[c] ? (uint32_t)(ca[c] - cb[c]) : (uint32_t)(cb[c] - ca[c]);
                    d = e > d ? e : d;
                }
                if (!d)
                    continue;
                ++n;
                worst = d > worst ? d : worst;
                x0 = x < x0 ? x : x0;
                y0 = y < y0 ? y : y0;
                x1 = x > x1 ? x : x1;
                y1 = y > y1 ? y : y1;
                cell[y * 8 / h][x * 8 / w]++;
            }
        if (!n)
            continue;
        printf("  %s, layer %u: %u of %u pixels differ, box (%u,%u)-(%u,%u), worst %u/255\n", label, l, n, w * h, x0,
               y0, x1, y1, worst);
        uint32_t cell_pixels = (w / 8 ? w / 8 : 1) * (h / 8 ? h / 8 : 1);
        for (int cy = 0; cy < 8; ++cy) {
            char row[9];
            for (int cx = 0; cx < 8; ++cx) {
                uint32_t tenth = (cell[cy][cx] * 10 + cell_pixels - 1) / cell_pixels;
                row[cx] = cell[cy][cx] == 0 ? '.' : (char)('0' + (tenth > 9 ? 9 : tenth ? tenth : 1));
            }
            row[8] = 0;
            printf("    %s\n", row);
        }
    }
}

#endif
