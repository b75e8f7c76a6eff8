/*
 * A minimal test harness: each test executable registers cases with
 * MVR_TEST_CASE and runs them from main with mvr_test_run. A failed CHECK
 * prints where and what, and the case goes on; the executable exits non-zero
 * if any check failed, and with MVR_TEST_SKIP (77, ctest's SKIP_RETURN_CODE)
 * when every case was skipped, after printing why.
 */
#ifndef MVR_TEST_H
#define MVR_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MVR_TEST_SKIP 77

typedef struct mvr_test_state {
    int failed_checks;
    int skipped;
} mvr_test_state;

typedef void (*mvr_test_fn)(mvr_test_state *t);

typedef struct mvr_test_case {
    const char *name;
    mvr_test_fn fn;
} mvr_test_case;

#define CHECK(t, cond)                                                          \
    do {                                                                        \
        if (!(cond)) {                                                          \
            printf("  FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);             \
            (t)->failed_checks++;                                               \
        }                                                                       \
    } while (0)

#define CHECK_MSG(t, cond, ...)                                                 \
    do {                                                                        \
        if (!(cond)) {                                                          \
            printf("  FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);             \
            printf(__VA_ARGS__);                                                \
            printf("\n");                                                       \
            (t)->failed_checks++;                                               \
        }                                                                       \
    } while (0)

#define CHECK_EQ_INT(t, a, b)                                                   \
    do {                                                                        \
        long long a_ = (long long)(a), b_ = (long long)(b);                     \
        if (a_ != b_) {                                                         \
            printf("  FAIL %s:%d: %s == %s (%lld != %lld)\n", __FILE__, __LINE__, \
                   #a, #b, a_, b_);                                             \
            (t)->failed_checks++;                                               \
        }                                                                       \
    } while (0)

/* Marks the running case skipped, with a reason ctest's output shows. */
#define SKIP(t, ...)                                                            \
    do {                                                                        \
        printf("  SKIP: ");                                                     \
        printf(__VA_ARGS__);                                                    \
        printf("\n");                                                           \
        (t)->skipped = 1;                                                       \
        return;                                                                 \
    } while (0)

static inline int mvr_test_run(const mvr_test_case *cases, size_t count)
{
    int passed = 0, failed = 0, skipped = 0;
    for (size_t i = 0; i < count; ++i) {
        mvr_test_state t = {0, 0};
        printf("[ RUN  ] %s\n", cases[i].name);
        fflush(stdout);
        cases[i].fn(&t);
        if (t.failed_checks) {
            printf("[ FAIL ] %s (%d failed checks)\n", cases[i].name, t.failed_checks);
            failed++;
        } else if (t.skipped) {
            printf("[ SKIP ] %s\n", cases[i].name);
            skipped++;
        } else {
            printf("[  OK  ] %s\n", cases[i].name);
            passed++;
        }
        fflush(stdout);
    }
    printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
    if (failed)
        return 1;
    return passed == 0 && skipped > 0 ? MVR_TEST_SKIP : 0;
}

#define MVR_TEST_MAIN(...)                                                      \
    int main(void)                                                              \
    {                                                                           \
        static const mvr_test_case cases_[] = {__VA_ARGS__};                    \
        return mvr_test_run(cases_, sizeof cases_ / sizeof cases_[0]);          \
    }

#define TEST(fn) {#fn, fn}

/* True when the test must not skip what CI has to exercise. */
static inline int mvr_test_in_ci(void)
{
    const char *ci = getenv("CI");
    const char *req = getenv("MVR_REQUIRE_MULTIVIEW");
    return (ci && strcmp(ci, "true") == 0) || (req && strcmp(req, "1") == 0);
}

#endif
