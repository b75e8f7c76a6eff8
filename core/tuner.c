/* The online tuner behind `auto` (tuner.h). */
#include "tuner.h"

#include <math.h>
#include <string.h>

/* a and b differ by more than a factor of 2; 0 is not known yet */
static bool factor_2(uint32_t a, uint32_t b)
{
    if (!a || !b)
        return false;
    uint64_t x = a, y = b;
    return x > 2 * y || y > 2 * x;
}

static bool key_changed(const mvr_tuner_key *a, const mvr_tuner_key *b)
{
    if (a->views != b->views || a->width != b->width || a->height != b->height || a->given != b->given)
        return true;
    /* the scene and what the views see of it: a factor of 2 (a few objects
     * more is the same workload) */
    return factor_2(a->draws, b->draws) || factor_2(a->visible, b->visible);
}

double mvr_tuner_estimate(const double *costs, uint32_t n)
{
    if (!n)
        return 0.0;
    if (n > MVR_TUNER_MAX_SAMPLES)
        n = MVR_TUNER_MAX_SAMPLES;
    double s[MVR_TUNER_MAX_SAMPLES];
    memcpy(s, costs, n * sizeof *costs);
    for (uint32_t i = 1; i < n; ++i) /* insertion sort: n is at most MVR_TUNER_MAX_SAMPLES */
        for (uint32_t j = i; j > 0 && s[j] < s[j - 1]; --j) {
            double tmp = s[j];
            s[j] = s[j - 1];
            s[j - 1] = tmp;
        }
    uint32_t keep = n / 2 ? n / 2 : 1;
    double sum = 0.0;
    for (uint32_t i = 0; i < keep; ++i)
        sum += s[i];
    return sum / keep;
}

/* ln(estimate of 1 / estimate of 0), clamped: > 0 when candidate 0 is cheaper */
static double log_ratio(const double est[MVR_TUNER_CANDIDATES])
{
    if (!(est[0] > 0.0) || !(est[1] > 0.0))
        return 0.0;
    double r = log(est[1] / est[0]);
    return r > 4.0 ? 4.0 : r < -4.0 ? -4.0 : r;
}

static void settle(mvr_tuner *t)
{
    for (uint32_t c = 0; c < MVR_TUNER_CANDIDATES; ++c)
        t->estimate[c] = mvr_tuner_estimate(t->costs[c], t->samples[c]);
    double now = log_ratio(t->estimate);
    /* the evidence: this run's, averaged with the remembered runs' */
    /* one run counts at most MVR_TUNER_RUN_LIMIT either way: a run whose
     * few samples were mostly outliers cannot undo the others */
    double lim = -log(1.0 - MVR_TUNER_RUN_LIMIT);
    double clamped = now > lim ? lim : now < -lim ? -lim : now;
    mvr_tuner_memory m = {0, clamped, 0.0, 1};
    uint32_t incumbent = t->incumbent;
    /* a first run whose choice a memory keeps: the lower estimate (tuner.h) */
    double band = t->remembers ? 0.0 : -log(1.0 - MVR_TUNER_HYSTERESIS);
    if (t->recalled) {
        /* a running mean and variance (Welford) over the last runs */
        uint32_t n = t->memory.runs;
        double d = clamped - t->memory.log_ratio;
        m.log_ratio = t->memory.log_ratio + d / (n + 1);
        m.spread = (t->memory.spread * n + d * (clamped - m.log_ratio)) / (n + 1);
        m.runs = n + 1 < MVR_TUNER_MEMORY_RUNS ? n + 1 : MVR_TUNER_MEMORY_RUNS;
        double se = sqrt(m.spread / (n + 1));
        band = -log(1.0 - MVR_TUNER_STICKY);
        band = band > 2.0 * se ? band : 2.0 * se;
    }
    /* the other candidate must be cheaper by more than the band */
    double gain = incumbent == 0 ? -m.log_ratio : m.log_ratio; /* > 0: the other is cheaper */
    uint32_t best = gain > band ? 1u - incumbent : incumbent;
    m.chosen = best;
    t->memory = m;
    t->store = true;
    t->chosen = best;
    double prior = t->estimate[t->prior];
    t->margin = best != t->prior && prior > 0.0 ? 1.0 - t->estimate[best] / prior : 0.0;
    t->phase = MVR_TUNER_SETTLED;
}

bool mvr_tuner_restarts(const mvr_tuner *t, mvr_tuner_key key, uint32_t prior)
{
    if (prior >= MVR_TUNER_CANDIDATES)
        prior = 0;
    return t->phase == MVR_TUNER_IDLE || key_changed(&t->key, &key) || prior != t->prior;
}

uint32_t mvr_tuner_next(mvr_tuner *t, mvr_tuner_key key, uint32_t prior, bool *measure)
{
    return mvr_tuner_next_recalled(t, key, prior, NULL, false, measure);
}

uint32_t mvr_tuner_next_recalled(mvr_tuner *t, mvr_tuner_key key, uint32_t prior, const mvr_tuner_memory *recalled,
                                 bool remembers, bool *measure)
{
    *measure = false;
    if (prior >= MVR_TUNER_CANDIDATES)
        prior = 0;
    if (mvr_tuner_restarts(t, key, prior)) {
        uint32_t retunes = t->retunes + (t->phase != MVR_TUNER_IDLE);
        memset(t, 0, sizeof *t);
        t->retunes = retunes;
        t->phase = MVR_TUNER_TUNING;
        t->key = key;
        t->prior = t->incumbent = prior;
        t->remembers = remembers;
        if (recalled && recalled->chosen < MVR_TUNER_CANDIDATES && recalled->runs > 0 &&
            isfinite(recalled->log_ratio)) {
            t->recalled = true;
            t->memory = *recalled;
            t->incumbent = recalled->chosen;
        }
        t->chosen = t->incumbent;
        t->want = MVR_TUNER_SAMPLES;
    }
    if (!t->key.draws)
        t->key.draws = key.draws;
    if (!t->key.visible)
        t->key.visible = key.visible;
    if (t->phase == MVR_TUNER_SETTLED)
        return t->chosen;
    if (t->in_turn) {
        /* the second frame of a turn: measured */
        t->in_turn = false;
        t->issued[t->current]++;
        *measure = true;
        return t->current;
    }
    /* a new turn: the candidate with the fewest measured frames, the incumbent on a tie */
    uint32_t next = t->incumbent;
    for (uint32_t c = 0; c < MVR_TUNER_CANDIDATES; ++c)
        if (t->issued[c] < t->issued[next])
            next = c;
    if (t->issued[next] >= t->want) {
        /* every sample issued but some not recorded (a cost never came): settle on what there is */
        bool all = true;
        for (uint32_t c = 0; c < MVR_TUNER_CANDIDATES; ++c)
            all = all && t->samples[c] > 0;
        if (all)
            settle(t);
        else
            t->phase = MVR_TUNER_SETTLED; /* nothing measurable: the incumbent, nothing to store */
        return t->chosen;
    }
    t->current = next;
    t->in_turn = true;
    return next;
}

void mvr_tuner_record(mvr_tuner *t, uint32_t c, double cost_ms)
{
    if (t->phase != MVR_TUNER_TUNING || c >= MVR_TUNER_CANDIDATES || !(cost_ms >= 0.0) || !isfinite(cost_ms) ||
        t->samples[c] >= t->want)
        return;
    t->costs[c][t->samples[c]++] = cost_ms;
    bool done = true;
    for (uint32_t k = 0; k < MVR_TUNER_CANDIDATES; ++k)
        done = done && t->samples[k] == t->want;
    if (!done)
        return;
    /* close estimates: inside the noise; more samples while there are any left */
    double lo = mvr_tuner_estimate(t->costs[0], t->samples[0]), hi = mvr_tuner_estimate(t->costs[1], t->samples[1]);
    if (lo > hi) {
        double tmp = lo;
        lo = hi;
        hi = tmp;
    }
    if (t->want < MVR_TUNER_MAX_SAMPLES && hi > 0.0 && 1.0 - lo / hi < MVR_TUNER_CLOSE) {
        t->want++;
        return;
    }
    settle(t);
}

uint32_t mvr_tuner_settled_or(const mvr_tuner *t, mvr_tuner_key key, uint32_t prior)
{
    if (t->phase == MVR_TUNER_SETTLED && !key_changed(&t->key, &key) && t->prior == prior)
        return t->chosen;
    return prior;
}
