/* Files the CLI writes (stats, reports, plot scripts, camera exports): every
 * write, fflush and fclose is checked, and a reader never sees a partial
 * file. The text goes to a new temporary name beside the file (created
 * with O_EXCL, in the same folder so rename(2) is atomic) and is renamed
 * over it only once everything succeeded; on any failure the temporary is
 * removed, and a file that was there before is left as it was. A path that
 * is no regular file (/dev/stdout, a FIFO, a device such as /dev/full) is
 * written in place, every write still checked; a symbolic link to a regular
 * file has its target replaced, the link kept. */
#ifndef MVR_APP_CLI_WRITE_H
#define MVR_APP_CLI_WRITE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

typedef struct cli_write_file {
    FILE *f;            /* write into this */
    char path[4096];    /* the file as named */
    char target[4096];  /* what the rename replaces (path, or a link's target) */
    char temp[4096];    /* the temporary; "" when written in place */
} cli_write_file;

/* Opens path for writing (text and binary are the same on POSIX). false
 * with why ("cannot write PATH: reason"); nothing to close then. */
bool cli_write_open(cli_write_file *w, const char *path, char *why, size_t why_size);

/* Checks the stream's error flag, flushes and closes, then renames the
 * temporary over the file. false with why ("cannot write PATH: No space
 * left on device") when any of it failed; the temporary is removed then. */
bool cli_write_close(cli_write_file *w, char *why, size_t why_size);

/* Gives the file up (the caller failed while making its content): closes
 * and removes the temporary; an in-place file keeps what was written. */
void cli_write_abandon(cli_write_file *w);

#endif
