/* core: the online tuner behind auto (core/tuner.h), without GL: its
 * schedule (turns of two frames, the prior first, the first of each turn not measured), the
 * choice (the cheaper median, the prior only on a tie), and when it
 * measures again. */
#include <string.h>

#include "mvr_test.h"
#include "tuner.h"

/* Runs frames until settled with fixed costs per candidate; returns the frames run. */
static uint32_t run(mvr_tuner *t, mvr_tuner_key key, uint32_t prior, const double cost[2], uint32_t ran[2])
{
    uint32_t frames = 0;
    ran[0] = ran[1] = 0;
    while (frames < 100) {
        bool measure = false;
        uint32_t c = mvr_tuner_next(t, key, prior, &measure);
        if (t->phase == MVR_TUNER_SETTLED && !measure)
            break;
        ran[c]++;
        frames++;
        if (measure)
            mvr_tuner_record(t, c, cost[c]);
    }
    return frames;
}

static void prior_first_then_interleaved(mvr_test_state *t)
{
    mvr_tuner tu;
    memset(&tu, 0, sizeof tu);
    mvr_tuner_key key = {6, 256, 256, 100, 0, 0};
    /* turns of two frames, the prior (1) first; the first frame of each turn
     * (a switch, or a candidate's warm-up) is not measured */
    uint32_t seq[12];
    bool measured[12];
    for (int i = 0; i < 12; ++i) {
        seq[i] = mvr_tuner_next(&tu, key, 1, &measured[i]);
        if (measured[i])
            mvr_tuner_record(&tu, seq[i], seq[i] == 0 ? 5.0 : 10.0);
    }
    const uint32_t expect[12] = {1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0};
    for (int i = 0; i < 12; ++i)
        CHECK_MSG(t, seq[i] == expect[i] && measured[i] == (i % 2 == 1), "frame %d: candidate %u, measured %d", i,
                  seq[i], (int)measured[i]);
    CHECK(t, tu.phase == MVR_TUNER_SETTLED && tu.chosen == 0);
    CHECK(t, tu.median[0] == 5.0 && tu.median[1] == 10.0 && tu.margin == 0.5);
    /* settled: the choice, unmeasured */
    bool measure = true;
    CHECK(t, mvr_tuner_next(&tu, key, 1, &measure) == 0 && !measure);
}

static void close_paths_take_the_lower_median(mvr_test_state *t)
{
    mvr_tuner tu;
    memset(&tu, 0, sizeof tu);
    mvr_tuner_key key = {4, 128, 128, 10, 0, 0};
    uint32_t ran[2];
    /* 2% cheaper: inside the noise, so measured up to the most samples; then the lower median */
    const double close[2] = {9.8, 10.0};
    uint32_t frames = run(&tu, key, 1, close, ran);
    CHECK_MSG(t, frames == 4 * MVR_TUNER_MAX_SAMPLES && tu.chosen == 0 && tu.margin > 0.019 && tu.margin < 0.021,
              "%u frames", frames);
    CHECK(t, tu.samples[0] == MVR_TUNER_MAX_SAMPLES && tu.samples[1] == MVR_TUNER_MAX_SAMPLES);
    /* at most half of the tuning frames on the other candidate */
    CHECK(t, ran[0] <= frames / 2);
    /* a tie keeps the prior */
    memset(&tu, 0, sizeof tu);
    const double tie[2] = {10.0, 10.0};
    run(&tu, key, 1, tie, ran);
    CHECK(t, tu.phase == MVR_TUNER_SETTLED && tu.chosen == 1 && tu.margin == 0.0);
    /* 12% cheaper pays, and is clear after the first samples */
    memset(&tu, 0, sizeof tu);
    const double clear[2] = {8.8, 10.0};
    frames = run(&tu, key, 1, clear, ran);
    CHECK(t, tu.chosen == 0 && tu.margin > 0.11 && tu.margin < 0.13 && frames == 4 * MVR_TUNER_SAMPLES);
    /* medians: one outlier frame does not decide */
    memset(&tu, 0, sizeof tu);
    bool measure;
    const double costs[6] = {10.0, 12.0, 10.0, 50.0, 10.0, 12.0}; /* c0, c1, c0, c1, c0, c1 */
    for (int i = 0, k = 0; i < 12; ++i) {
        uint32_t c = mvr_tuner_next(&tu, key, 0, &measure);
        if (measure)
            mvr_tuner_record(&tu, c, costs[k++]);
    }
    CHECK(t, tu.phase == MVR_TUNER_SETTLED && tu.median[1] == 12.0 && tu.chosen == 0);
}

/* Close after the first samples (4.8% apart: inside the noise), the
 * candidates go on alternating until their medians part. */
static void close_medians_take_more_samples(mvr_test_state *t)
{
    mvr_tuner tu;
    memset(&tu, 0, sizeof tu);
    mvr_tuner_key key = {6, 256, 256, 100, 0, 0};
    const double c0[MVR_TUNER_MAX_SAMPLES] = {10.0, 10.0, 10.0, 8.0, 8.0, 8.0, 8.0};
    uint32_t n[2] = {0, 0}, frames = 0;
    bool measure;
    while (tu.phase != MVR_TUNER_SETTLED && frames < 40) {
        uint32_t c = mvr_tuner_next(&tu, key, 1, &measure);
        frames++;
        if (measure) {
            mvr_tuner_record(&tu, c, c == 0 ? c0[n[0]] : 10.5);
            n[c]++;
        }
    }
    /* 3 samples: 10 against 10.5; 4, 5: still 10; 6: 9 against 10.5, 14% apart */
    CHECK_MSG(t, tu.phase == MVR_TUNER_SETTLED && tu.samples[0] == 6 && tu.samples[1] == 6, "samples %u, %u",
              tu.samples[0], tu.samples[1]);
    CHECK(t, frames == 4 * 6 && tu.chosen == 0 && tu.median[0] == 9.0 && tu.median[1] == 10.5);
    CHECK(t, n[0] == 6 && n[1] == 6);
}

/* Another decision's choice in the key (the skinning tuner keys on the view
 * path) measures again when it changes. */
static void another_decision_in_the_key(mvr_test_state *t)
{
    mvr_tuner tu;
    memset(&tu, 0, sizeof tu);
    mvr_tuner_key key = {6, 256, 256, 100, 0, 0};
    uint32_t ran[2];
    const double cost[2] = {5.0, 10.0};
    run(&tu, key, 1, cost, ran);
    bool measure;
    CHECK(t, tu.phase == MVR_TUNER_SETTLED && mvr_tuner_next(&tu, key, 1, &measure) == 0);
    key.given = 1;
    CHECK(t, mvr_tuner_next(&tu, key, 1, &measure) == 1 && tu.phase == MVR_TUNER_TUNING && tu.retunes == 1);
}

static void a_material_change_measures_again(mvr_test_state *t)
{
    mvr_tuner tu;
    memset(&tu, 0, sizeof tu);
    mvr_tuner_key key = {6, 256, 256, 100, 0, 0};
    uint32_t ran[2];
    const double cost[2] = {5.0, 10.0};
    run(&tu, key, 1, cost, ran);
    CHECK(t, tu.phase == MVR_TUNER_SETTLED && tu.retunes == 0);
    bool measure;
    /* a few more draws (less than x2): the same workload */
    key.draws = 180;
    CHECK(t, mvr_tuner_next(&tu, key, 1, &measure) == 0 && tu.phase == MVR_TUNER_SETTLED);
    /* what the views see: half as much again is the same workload, more than twice is not */
    memset(&tu, 0, sizeof tu);
    mvr_tuner_key seen = {6, 256, 256, 100, 0, 400};
    run(&tu, seen, 1, cost, ran);
    seen.visible = 600;
    CHECK(t, mvr_tuner_next(&tu, seen, 1, &measure) == 0 && tu.phase == MVR_TUNER_SETTLED);
    seen.visible = 900;
    CHECK(t, mvr_tuner_next(&tu, seen, 1, &measure) == 1 && tu.phase == MVR_TUNER_TUNING && tu.retunes == 1);
    /* not known yet (0) takes the next count */
    memset(&tu, 0, sizeof tu);
    seen.visible = 0;
    mvr_tuner_next(&tu, seen, 1, &measure);
    seen.visible = 50;
    mvr_tuner_next(&tu, seen, 1, &measure);
    CHECK(t, tu.key.visible == 50 && tu.retunes == 0);
    /* the view count, the size, twice the draws, another prior: again, the prior first */
    mvr_tuner_key changes[3] = {{12, 256, 256, 100, 0, 0}, {6, 512, 256, 100, 0, 0}, {6, 256, 256, 361, 0, 0}};
    for (int i = 0; i < 3; ++i) {
        memset(&tu, 0, sizeof tu);
        run(&tu, key, 1, cost, ran);
        CHECK(t, mvr_tuner_next(&tu, changes[i], 1, &measure) == 1 && tu.phase == MVR_TUNER_TUNING);
        CHECK(t, tu.retunes == 1);
    }
    memset(&tu, 0, sizeof tu);
    run(&tu, key, 1, cost, ran);
    CHECK(t, mvr_tuner_next(&tu, key, 0, &measure) == 0 && tu.phase == MVR_TUNER_TUNING);
    /* costs that never come: settles on the prior, never loops */
    memset(&tu, 0, sizeof tu);
    uint32_t frames = 0;
    while (tu.phase != MVR_TUNER_SETTLED && frames < 50) {
        mvr_tuner_next(&tu, key, 1, &measure);
        frames++;
    }
    CHECK(t, tu.phase == MVR_TUNER_SETTLED && tu.chosen == 1 && frames <= 4 * MVR_TUNER_SAMPLES + 1);
    /* a negative or NaN cost is not a sample */
    memset(&tu, 0, sizeof tu);
    mvr_tuner_next(&tu, key, 1, &measure);
    mvr_tuner_next(&tu, key, 1, &measure);
    uint32_t c = mvr_tuner_next(&tu, key, 1, &measure);
    mvr_tuner_record(&tu, c, -1.0);
    mvr_tuner_record(&tu, c, 0.0 / 0.0);
    CHECK(t, tu.samples[c] == 0);
}

MVR_TEST_MAIN(TEST(prior_first_then_interleaved), TEST(close_paths_take_the_lower_median),
              TEST(close_medians_take_more_samples), TEST(another_decision_in_the_key),
              TEST(a_material_change_measures_again))
