/* The online tuner behind `auto` (tuner.h). */
#include "tuner.h"

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

static double median(const double *v, uint32_t n)
{
    double s[MVR_TUNER_MAX_SAMPLES];
    memcpy(s, v, n * sizeof *v);
    for (uint32_t i = 1; i < n; ++i) /* insertion sort: n is at most 7 */
        for (uint32_t j = i; j > 0 && s[j] < s[j - 1]; --j) {
            double tmp = s[j];
            s[j] = s[j - 1];
            s[j - 1] = tmp;
        }
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

static void settle(mvr_tuner *t)
{
    for (uint32_t c = 0; c < MVR_TUNER_CANDIDATES; ++c)
        t->median[c] = median(t->costs[c], t->samples[c]);
    uint32_t best = t->prior;
    for (uint32_t c = 0; c < MVR_TUNER_CANDIDATES; ++c)
        if (t->median[c] < t->median[best])
            best = c;
    double prior = t->median[t->prior];
    t->chosen = best; /* the prior on a tie */
    t->margin = best != t->prior && prior > 0.0 ? 1.0 - t->median[best] / prior : 0.0;
    t->phase = MVR_TUNER_SETTLED;
}

uint32_t mvr_tuner_next(mvr_tuner *t, mvr_tuner_key key, uint32_t prior, bool *measure)
{
    *measure = false;
    if (prior >= MVR_TUNER_CANDIDATES)
        prior = 0;
    if (t->phase == MVR_TUNER_IDLE || key_changed(&t->key, &key) || prior != t->prior) {
        uint32_t retunes = t->retunes + (t->phase != MVR_TUNER_IDLE);
        memset(t, 0, sizeof *t);
        t->retunes = retunes;
        t->phase = MVR_TUNER_TUNING;
        t->key = key;
        t->prior = t->chosen = prior;
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
    /* a new turn: the candidate with the fewest measured frames, the prior on a tie */
    uint32_t next = prior;
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
            t->phase = MVR_TUNER_SETTLED; /* nothing measurable: the prior */
        return t->chosen;
    }
    t->current = next;
    t->in_turn = true;
    return next;
}

void mvr_tuner_record(mvr_tuner *t, uint32_t c, double cost_ms)
{
    if (t->phase != MVR_TUNER_TUNING || c >= MVR_TUNER_CANDIDATES || !(cost_ms >= 0.0) || t->samples[c] >= t->want)
        return;
    t->costs[c][t->samples[c]++] = cost_ms;
    bool done = true;
    for (uint32_t k = 0; k < MVR_TUNER_CANDIDATES; ++k)
        done = done && t->samples[k] == t->want;
    if (!done)
        return;
    /* close medians: inside the noise; more samples while there are any left */
    double lo = median(t->costs[0], t->samples[0]), hi = median(t->costs[1], t->samples[1]);
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
