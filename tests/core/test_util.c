/* core: results, errors, logging, strings, overflow-safe sizes. */
#include <stdint.h>

#include "core_util.h"
#include "mvr_test.h"

static void result_names_are_distinct(mvr_test_state *t)
{
    for (int i = 0; i < MVR_RESULT_COUNT_; ++i) {
        const char *a = mvr_result_name((mvr_result)i);
        CHECK(t, a && strncmp(a, "MVR_", 4) == 0);
        CHECK_MSG(t, strcmp(a, "MVR_ERROR_UNKNOWN") != 0, "result %d has no name", i);
        for (int j = 0; j < i; ++j)
            CHECK(t, strcmp(a, mvr_result_name((mvr_result)j)) != 0);
    }
    CHECK(t, strcmp(mvr_result_name((mvr_result)999), "MVR_ERROR_UNKNOWN") == 0);
}

static void error_set_truncates_and_tolerates_null(mvr_test_state *t)
{
    mvr_error e;
    char big[2000];
    memset(big, 'x', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    CHECK(t, mvr_error_set(&e, MVR_ERROR_PARSE, "%s", big) == MVR_ERROR_PARSE);
    CHECK_EQ_INT(t, e.result, MVR_ERROR_PARSE);
    CHECK_EQ_INT(t, strlen(e.message), sizeof e.message - 1);
    CHECK(t, mvr_error_set(NULL, MVR_ERROR_IO, "ignored") == MVR_ERROR_IO);
}

typedef struct log_capture {
    int calls;
    mvr_log_level last_level;
    mvr_log_id last_id;
    char last[256];
} log_capture;

static void capture(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    log_capture *c = user;
    c->calls++;
    c->last_level = level;
    c->last_id = id;
    mvr_str_copy(c->last, sizeof c->last, message);
}

static void logger_respects_threshold(mvr_test_state *t)
{
    log_capture c = {0};
    mvr_logger lg = {capture, &c, MVR_LOG_DEFAULT};
    mvr_log(&lg, MVR_LOG_DEBUG, MVR_LOG_ID_GENERAL, "hidden %d", 1);
    CHECK_EQ_INT(t, c.calls, 0);
    mvr_log(&lg, MVR_LOG_INFO, MVR_LOG_ID_CONTEXT, "shown %d", 2);
    CHECK_EQ_INT(t, c.calls, 1);
    CHECK(t, strcmp(c.last, "shown 2") == 0);
    CHECK_EQ_INT(t, c.last_id, MVR_LOG_ID_CONTEXT);
    lg.level = MVR_LOG_ERROR;
    mvr_log(&lg, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL, "hidden");
    CHECK_EQ_INT(t, c.calls, 1);
    mvr_log(&lg, MVR_LOG_ERROR, MVR_LOG_ID_GL_ERROR, "err");
    CHECK_EQ_INT(t, c.calls, 2);
    CHECK_EQ_INT(t, c.last_level, MVR_LOG_ERROR);
    mvr_log(NULL, MVR_LOG_ERROR, MVR_LOG_ID_GENERAL, "no logger is fine");
    mvr_logger none = {0};
    mvr_log(&none, MVR_LOG_ERROR, MVR_LOG_ID_GENERAL, "no callback is fine");
}

static void string_builder_grows(mvr_test_state *t)
{
    mvr_str_builder sb = {0};
    for (int i = 0; i < 1000; ++i)
        mvr_sb_appendf(&sb, "%d,", i);
    CHECK(t, !sb.failed);
    CHECK(t, sb.length == strlen(sb.data));
    CHECK(t, strncmp(sb.data, "0,1,2,", 6) == 0);
    CHECK(t, strstr(sb.data, ",999,") != NULL);
    mvr_sb_free(&sb);
    CHECK(t, sb.data == NULL && sb.length == 0);
}

static void str_copy_truncates(mvr_test_state *t)
{
    char buf[4];
    mvr_str_copy(buf, sizeof buf, "abcdef");
    CHECK(t, strcmp(buf, "abc") == 0);
    mvr_str_copy(buf, sizeof buf, NULL);
    CHECK(t, buf[0] == '\0');
    mvr_str_format(buf, sizeof buf, "%d", 123456);
    CHECK(t, strcmp(buf, "123") == 0);
}

static void size_arithmetic_detects_overflow(mvr_test_state *t)
{
    size_t out = 7;
    CHECK(t, mvr_size_mul(SIZE_MAX / 2 + 1, 2, &out) == 0);
    CHECK_EQ_INT(t, out, 7);
    CHECK(t, mvr_size_mul(1u << 20, 1u << 10, &out) == 1 && out == (size_t)1 << 30);
    CHECK(t, mvr_size_add(SIZE_MAX, 1, &out) == 0);
    CHECK(t, mvr_size_add(SIZE_MAX - 1, 1, &out) == 1 && out == SIZE_MAX);
    CHECK(t, mvr_size_mul(0, SIZE_MAX, &out) == 1 && out == 0);
}


/* The supersampling resolve: each output is the mean of its box. */
static void downsample_averages_boxes(mvr_test_state *t)
{
    float src[4 * 2 * 4]; /* 4 x 2 pixels */
    for (int i = 0; i < 8; ++i)
        for (int c = 0; c < 4; ++c)
            src[i * 4 + c] = (float)(i * 4 + c);
    float dst[2 * 1 * 4];
    CHECK(t, mvr_downsample_rgba32f(src, 4, 2, 2, dst) == MVR_OK);
    /* box 0: pixels 0, 1, 4, 5; box 1: 2, 3, 6, 7 */
    for (int c = 0; c < 4; ++c) {
        CHECK(t, dst[c] == (float)((0 + 1 + 4 + 5) * 4 + 4 * c) / 4.0f);
        CHECK(t, dst[4 + c] == (float)((2 + 3 + 6 + 7) * 4 + 4 * c) / 4.0f);
    }
    CHECK(t, mvr_downsample_rgba32f(src, 4, 2, 3, dst) == MVR_ERROR_INVALID_ARGUMENT); /* 4 % 3 */
    CHECK(t, mvr_downsample_rgba32f(src, 4, 2, 0, dst) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_downsample_rgba32f(NULL, 4, 2, 2, dst) == MVR_ERROR_INVALID_ARGUMENT);
}

MVR_TEST_MAIN(TEST(downsample_averages_boxes), TEST(result_names_are_distinct), TEST(error_set_truncates_and_tolerates_null),
              TEST(logger_respects_threshold), TEST(string_builder_grows),
              TEST(str_copy_truncates), TEST(size_arithmetic_detects_overflow))
