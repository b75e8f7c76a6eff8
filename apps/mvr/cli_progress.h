/* A progress line on a terminal: items done of a total, items per second
 * and the time left, redrawn in place on stderr at most ten times a second.
 * Off (every call does nothing) unless enabled and stderr is a terminal. */
#ifndef MVR_APP_CLI_PROGRESS_H
#define MVR_APP_CLI_PROGRESS_H

#include <stdbool.h>
#include <stdint.h>

typedef struct cli_progress {
    bool on;
    const char *unit;            /* "views" */
    uint64_t total;
    double start, last_draw;     /* seconds (CLOCK_MONOTONIC) */
    int width;                   /* characters of the last line drawn */
} cli_progress;

/* The monotonic clock in seconds. */
double cli_now(void);

/* Starts the clock; on only when `enabled` and stderr is a terminal. */
void cli_progress_start(cli_progress *p, bool enabled, uint64_t total, const char *unit);
/* Redraws the line with `done` items (at most every 0.1 s unless force). */
void cli_progress_update(cli_progress *p, uint64_t done, bool force);
/* The final line (done items, the rate over the whole run), then a newline. */
void cli_progress_end(cli_progress *p, uint64_t done);

#endif
