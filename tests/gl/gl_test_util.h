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
    mvr_context *ctx = NULL;
    mvr_error err;
    mvr_result r = mvr_context_create(&desc, &ctx, &err);
    CHECK_MSG(t, r == MVR_OK, "%s provider: %s", mvr_context_provider_name(provider), err.message);
    return r == MVR_OK ? ctx : NULL;
}

#endif
