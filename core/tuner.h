/*
 * The online tuner behind `auto` (issues 22, 37): for a decision with several
 * correct paths (the view path, the material path, the skinning path), it runs the
 * candidates on the real frames, interleaved, and settles on the cheapest.
 * Backend-free: the GL side says which frame ran which candidate at what
 * cost; the tuner says which candidate the next frame runs. One mvr_tuner per
 * decision.
 *
 * Schedule, from a change of inputs (the key): the candidates take turns of
 * two frames, the incumbent first (the remembered choice, else the prior:
 * the rule's first guess), so the first frame is never slower than what
 * would run untuned. The first frame of a turn is not measured: it follows a
 * switch of path (and, in a candidate's first turn, compiles its programs,
 * ~130 ms per variant on llvmpipe, or uploads what it needs). Measured here
 * (city, 6 views, llvmpipe): frames that alternate path every frame made the
 * loop look 10-15% slower against multiview than runs of either path did.
 * The turns alternate until each candidate has MVR_TUNER_SAMPLES costs.
 *
 * The estimate of a candidate is the mean of the cheaper half of its
 * samples (rounded down; the cheapest of 3): a trimmed mean, since on a
 * shared machine interference only adds time (identical work differs by up
 * to 26% frame to frame; issue 37 saw one 55.7 ms sample against 25-32 ms
 * forced), so the upper half is dropped and no one slow frame decides (nor
 * two of 3). Where the estimates are within MVR_TUNER_CLOSE of each other
 * the turns go on, up to MVR_TUNER_MAX_SAMPLES each, until they part or the
 * samples run out.
 *
 * Hysteresis: without a memory to keep the choice (none handed in, none to
 * be stored), the incumbent is kept unless the other candidate is cheaper by
 * more than MVR_TUNER_HYSTERESIS, so two candidates inside the noise do not
 * flip between processes on one run's noise; what either costs there is
 * within that band. Where a memory will keep it (the caller says so), a
 * first run takes the lower estimate (the incumbent on a tie): the memory
 * then holds that choice across runs, so a bias towards the prior would
 * only make the first run's choice the worse one more often (issue 37:
 * stereo's multiview measured 0.2-3% cheaper than the prior's loop in every
 * run, was kept out by the 3% and taken by the memory's mean 4 runs later,
 * a choice changed once in 10 runs).
 *
 * Memory (mvr_tuner_memory): a settled choice may be stored (the GL side
 * writes it into the program cache folder, keyed by scene, views, size,
 * outputs and GL) and handed back at the next key change, in this or a later
 * process. It becomes the incumbent, and its evidence (the mean log ratio of
 * the two estimates over earlier runs, up to MVR_TUNER_MEMORY_RUNS of them)
 * is averaged with this run's; the remembered choice then stays unless that
 * mean says the other is cheaper by more than MVR_TUNER_STICKY and by more
 * than twice its standard error (the runs' spread / sqrt(runs)): on a
 * loaded machine, where runs disagree by +-20% (issue 37's city: 44 to 222
 * ms for the same frames), the band widens and the choice holds; on a quiet
 * one it is the 5%. One run's
 * estimates of two candidates 4% apart under +-30% frame noise pick the
 * wrong one in 1 run of 4 or 5 (tests/core/test_tuner.c's simulation); the
 * average of several runs does not, and either choice inside the band costs
 * less than 5%. One run's log ratio counts at most +-MVR_TUNER_RUN_LIMIT in
 * that mean (a run whose few samples were mostly outliers), so the memory
 * follows a real change over a few runs and one bad run changes nothing.
 *
 * Tuning costs 4 x MVR_TUNER_SAMPLES frames (12) where the candidates differ
 * clearly, at most 4 x MVR_TUNER_MAX_SAMPLES (36) where they are close, half
 * of them on a candidate other than the incumbent; after that no frame is
 * measured. A key change (view count, target size, the draw count or the
 * draws visible after culling by more than a factor of 2 -- a count of 0 is
 * "not known yet" and takes the next one -- or another decision's choice the
 * key carries) starts again.
 */
#ifndef MVR_TUNER_H
#define MVR_TUNER_H

#include <stdbool.h>
#include <stdint.h>

#define MVR_TUNER_CANDIDATES 2
#define MVR_TUNER_SAMPLES 3
#define MVR_TUNER_MAX_SAMPLES 9
#define MVR_TUNER_CLOSE 0.10
#define MVR_TUNER_HYSTERESIS 0.03
#define MVR_TUNER_STICKY 0.05
#define MVR_TUNER_RUN_LIMIT 0.20
#define MVR_TUNER_MEMORY_RUNS 8

typedef enum mvr_tuner_phase {
    MVR_TUNER_IDLE = 0,          /* never keyed */
    MVR_TUNER_TUNING,
    MVR_TUNER_SETTLED
} mvr_tuner_phase;

typedef struct mvr_tuner_key {
    uint32_t views, width, height, draws;
    uint32_t given;              /* what the other decisions chose (compared exactly) */
    /* draws drawn over all views after culling (the last frame's; 0 = not
     * known): a camera that moves from a sparse to a dense part of a scene
     * changes the work as much as new draws do (factor 2, as draws) */
    uint32_t visible;
} mvr_tuner_key;

/* What a settled decision leaves for the next run with the same inputs. */
typedef struct mvr_tuner_memory {
    uint32_t chosen;             /* the candidate kept */
    double log_ratio;            /* mean over runs of ln(estimate[1] / estimate[0]): > 0 = candidate 0 cheaper */
    double spread;               /* mean over runs of the squared deviation from that mean (a variance) */
    uint32_t runs;               /* runs in that mean, 1..MVR_TUNER_MEMORY_RUNS */
} mvr_tuner_memory;

typedef struct mvr_tuner {
    mvr_tuner_phase phase;
    mvr_tuner_key key;
    uint32_t prior;              /* the caps rule's candidate */
    uint32_t incumbent;          /* the remembered choice, else the prior: runs first, kept on a tie */
    bool recalled;               /* memory was handed in at this key */
    bool remembers;              /* the caller keeps what settles for later runs */
    mvr_tuner_memory memory;     /* recalled: the earlier runs'; settled: what to store */
    bool store;                  /* settled on measurements: memory is worth storing (cleared by the caller) */
    uint32_t chosen;             /* what runs once settled (the incumbent while tuning) */
    uint32_t issued[MVR_TUNER_CANDIDATES];   /* measured frames run on each since the key changed */
    uint32_t current;            /* the candidate of the turn under way */
    bool in_turn;                /* its first (unmeasured) frame ran; the next is measured */
    uint32_t samples[MVR_TUNER_CANDIDATES];  /* costs recorded (warm-ups not counted) */
    uint32_t want;               /* samples each before settling (grows while close) */
    double costs[MVR_TUNER_CANDIDATES][MVR_TUNER_MAX_SAMPLES];
    double estimate[MVR_TUNER_CANDIDATES];   /* once settled: mean of the cheaper half of the samples */
    double margin;               /* settled: 1 - chosen's estimate / prior's */
    uint32_t retunes;            /* key changes that restarted tuning */
} mvr_tuner;

/* The candidate the next frame runs, for these inputs and this prior; starts
 * tuning again when the key changed materially. *measure: record the frame's
 * cost (mvr_tuner_record) once known. */
uint32_t mvr_tuner_next(mvr_tuner *t, mvr_tuner_key key, uint32_t prior, bool *measure);
/* The same, with what an earlier run settled on for these inputs (NULL =
 * nothing), used only when this call starts tuning again; `remembers`: the
 * caller stores what settles (mvr_tuner.memory) for later runs, so a run
 * without a recalled memory takes the lower estimate (no hysteresis). */
uint32_t mvr_tuner_next_recalled(mvr_tuner *t, mvr_tuner_key key, uint32_t prior, const mvr_tuner_memory *recalled,
                                 bool remembers, bool *measure);
/* Whether mvr_tuner_next with these inputs would start tuning again (the
 * moment to look up a memory). */
bool mvr_tuner_restarts(const mvr_tuner *t, mvr_tuner_key key, uint32_t prior);
/* The trimmed estimate of n costs: the mean of the cheaper n/2, at least 1 (0 for none). */
double mvr_tuner_estimate(const double *costs, uint32_t n);
/* The cost (ms) of a frame that ran candidate c and was to be measured. */
void mvr_tuner_record(mvr_tuner *t, uint32_t c, double cost_ms);
/* The settled choice for these inputs without measuring or restarting
 * (a decision waiting for another's measurement); else `prior`. */
uint32_t mvr_tuner_settled_or(const mvr_tuner *t, mvr_tuner_key key, uint32_t prior);

#endif
