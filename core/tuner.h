/*
 * The online tuner behind `auto` (issue 22): for a decision with several
 * correct paths (the material path, the view path, the skinning path), it runs the
 * candidates on the real frames, interleaved, and settles on the cheapest.
 * Backend-free: the GL side says which frame ran which candidate at what
 * cost; the tuner says which candidate the next frame runs. One mvr_tuner per
 * decision.
 *
 * Schedule, from a change of inputs (the key): the candidates take turns of
 * two frames, the prior (the rule's first guess) first, so the first frame
 * is never slower than the rule. The first frame of a turn is not measured: it
 * follows a switch of path (and, in a candidate's first turn, compiles its
 * programs, ~130 ms per variant on llvmpipe, or uploads what it needs).
 * Measured here (city, 6 views, llvmpipe): frames that alternate path every
 * frame made the loop look 10-15% slower against multiview than runs of
 * either path did, and the second frame of each run of two measured what runs
 * do. The turns alternate until each candidate has MVR_TUNER_SAMPLES costs.
 * Where the medians are then within MVR_TUNER_CLOSE of each other the ranking
 * is inside the frame-to-frame noise (identical work differs by up to 26% on a
 * shared 2-core machine), so the turns go on, up to MVR_TUNER_MAX_SAMPLES each,
 * until the medians part or the samples run out. The one with the lowest
 * median wins, the prior only on a tie: once the samples are taken a switch
 * costs nothing, and a margin for the prior kept it against the measured
 * order in both choices `mvr bench` found more than 5% off (docs/
 * benchmarks.md; the tuner had measured the other path 1.5-2.4% cheaper, the
 * bench 7.9-9.8%). Tuning costs 4 x MVR_TUNER_SAMPLES frames (12) where the
 * candidates differ clearly, at most 4 x MVR_TUNER_MAX_SAMPLES (28) where
 * they are close (and a wrong choice costs little), half of them on a
 * candidate other than the prior; after that no frame is measured. A key
 * change (view count, target size, the draw count or the draws visible after
 * culling by more than a factor of 2 -- a count of 0 is "not known yet" and
 * takes the next one -- or another decision's choice the key carries) starts
 * again.
 */
#ifndef MVR_TUNER_H
#define MVR_TUNER_H

#include <stdbool.h>
#include <stdint.h>

#define MVR_TUNER_CANDIDATES 2
#define MVR_TUNER_SAMPLES 3
#define MVR_TUNER_MAX_SAMPLES 7
#define MVR_TUNER_CLOSE 0.10

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

typedef struct mvr_tuner {
    mvr_tuner_phase phase;
    mvr_tuner_key key;
    uint32_t prior;              /* the caps rule's candidate */
    uint32_t chosen;             /* what runs once settled (the prior while tuning) */
    uint32_t issued[MVR_TUNER_CANDIDATES];   /* measured frames run on each since the key changed */
    uint32_t current;            /* the candidate of the turn under way */
    bool in_turn;                /* its first (unmeasured) frame ran; the next is measured */
    uint32_t samples[MVR_TUNER_CANDIDATES];  /* costs recorded (warm-ups not counted) */
    uint32_t want;               /* samples each before settling (grows while close) */
    double costs[MVR_TUNER_CANDIDATES][MVR_TUNER_MAX_SAMPLES];
    double median[MVR_TUNER_CANDIDATES];     /* once settled */
    double margin;               /* settled: 1 - chosen's median / prior's */
    uint32_t retunes;            /* key changes that restarted tuning */
} mvr_tuner;

/* The candidate the next frame runs, for these inputs and this prior; starts
 * tuning again when the key changed materially. *measure: record the frame's
 * cost (mvr_tuner_record) once known. */
uint32_t mvr_tuner_next(mvr_tuner *t, mvr_tuner_key key, uint32_t prior, bool *measure);
/* The cost (ms) of a frame that ran candidate c and was to be measured. */
void mvr_tuner_record(mvr_tuner *t, uint32_t c, double cost_ms);
/* The settled choice for these inputs without measuring or restarting
 * (a decision waiting for another's measurement); else `prior`. */
uint32_t mvr_tuner_settled_or(const mvr_tuner *t, mvr_tuner_key key, uint32_t prior);

#endif
