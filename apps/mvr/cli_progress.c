/* The progress line (cli_progress.h). */
#define _POSIX_C_SOURCE 200809L
#include "cli_progress.h"

#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

double cli_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

void cli_progress_start(cli_progress *p, bool enabled, uint64_t total, const char *unit)
{
    memset(p, 0, sizeof *p);
    p->on = enabled && total > 0 && isatty(STDERR_FILENO);
    p->unit = unit;
    p->total = total;
    p->start = cli_now();
    p->last_draw = -1.0;
}

/* h:mm:ss, or m:ss under an hour */
static void format_duration(char *buf, size_t size, double seconds)
{
    /* at most 99:59:59 */
    unsigned s = seconds < 0 ? 0u : seconds > 359999.0 ? 359999u : (unsigned)(seconds + 0.5);
    if (s >= 3600)
        snprintf(buf, size, "%u:%02u:%02u", s / 3600 % 100, s / 60 % 60, s % 60);
    else
        snprintf(buf, size, "%u:%02u", s / 60 % 60, s % 60);
}

static void draw(cli_progress *p, uint64_t done, double now, bool final)
{
    enum { BAR = 30 };
    double elapsed = now - p->start;
    double rate = elapsed > 0 ? (double)done / elapsed : 0.0;
    uint64_t filled = p->total ? done * BAR / p->total : 0;
    char bar[BAR + 1];
    for (int i = 0; i < BAR; ++i)
        bar[i] = (uint64_t)i < filled ? '#' : '.';
    bar[BAR] = '\0';
    char tail[32];
    if (final) {
        char t[24];
        format_duration(t, sizeof t, elapsed);
        snprintf(tail, sizeof tail, "in %s", t);
    } else if (done > 0 && rate > 0) {
        char t[24];
        format_duration(t, sizeof t, (double)(p->total - done) / rate);
        snprintf(tail, sizeof tail, "ETA %s", t);
    } else {
        snprintf(tail, sizeof tail, "ETA -");
    }
    char line[160];
    int n = snprintf(line, sizeof line, "[%s] %llu/%llu %s  %.1f %s/s  %s", bar, (unsigned long long)done,
                     (unsigned long long)p->total, p->unit, rate, p->unit, tail);
    if (n < 0)
        return;
    /* spaces over what a longer previous line left */
    fprintf(stderr, "\r%s%*s", line, p->width > n ? p->width - n : 0, "");
    fflush(stderr);
    p->width = n;
}

void cli_progress_update(cli_progress *p, uint64_t done, bool force)
{
    if (!p->on)
        return;
    double now = cli_now();
    if (!force && p->last_draw >= 0 && now - p->last_draw < 0.1)
        return;
    p->last_draw = now;
    draw(p, done, now, false);
}

void cli_progress_end(cli_progress *p, uint64_t done)
{
    if (!p->on)
        return;
    draw(p, done, cli_now(), true);
    fputc('\n', stderr);
    fflush(stderr);
    p->on = false;
}
