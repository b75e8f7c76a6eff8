/* Several files in one mvr render run (render_files.h): the list, the
 * output directories, the loop and its summary. */
#define _POSIX_C_SOURCE 200809L
#include "render_files.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "commands.h"

bool render_files_add(render_file_list *list, const char *path)
{
    if (list->count >= RENDER_FILES_MAX) {
        fprintf(stderr, "mvr render: more than %u SCENE files in one run\n", RENDER_FILES_MAX);
        return false;
    }
    if (list->count == list->capacity) {
        uint32_t cap = list->capacity ? list->capacity * 2 : 16;
        char **paths = realloc(list->paths, cap * sizeof *paths);
        if (!paths) {
            fprintf(stderr, "mvr render: out of memory for the list of files\n");
            return false;
        }
        list->paths = paths;
        list->capacity = cap;
    }
    char *copy = strdup(path);
    if (!copy) {
        fprintf(stderr, "mvr render: out of memory for the list of files\n");
        return false;
    }
    list->paths[list->count++] = copy;
    return true;
}

bool render_files_read_list(const char *file, render_file_list *list)
{
    FILE *f = fopen(file, "rb");
    if (!f) {
        fprintf(stderr, "mvr render: --list %s: cannot open it: %s\n", file, strerror(errno));
        return false;
    }
    char line[RENDER_FILES_MAX_PATH + 2];
    uint32_t line_no = 0, listed = 0;
    bool ok = true;
    for (;;) {
        size_t len = 0;
        int c = 0;
        bool too_long = false, nul = false;
        /* one line by hand: fgets cannot tell a NUL byte from the end */
        while ((c = fgetc(f)) != EOF && c != '\n') {
            if (c == '\0')
                nul = true;
            if (len < sizeof line - 1)
                line[len++] = (char)c;
            else
                too_long = true;
        }
        if (c == EOF && len == 0 && !too_long)
            break;
        ++line_no;
        line[len] = '\0';
        if (nul) {
            fprintf(stderr, "mvr render: --list %s: line %u holds a NUL byte (not a list of paths)\n", file, line_no);
            ok = false;
            break;
        }
        if (too_long || len > RENDER_FILES_MAX_PATH) {
            fprintf(stderr, "mvr render: --list %s: line %u is longer than %u bytes\n", file, line_no,
                    RENDER_FILES_MAX_PATH);
            ok = false;
            break;
        }
        /* blanks around the path (and a "\r\n" end) are not part of it */
        char *s = line, *e = line + len;
        while (s < e && (*s == ' ' || *s == '\t'))
            ++s;
        while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r'))
            --e;
        *e = '\0';
        if (s == e || *s == '#')
            continue;
        if (!render_files_add(list, s)) {
            ok = false;
            break;
        }
        ++listed;
        if (c == EOF)
            break;
    }
    if (ok && ferror(f)) {
        fprintf(stderr, "mvr render: --list %s: cannot read it\n", file);
        ok = false;
    }
    fclose(f);
    if (ok && listed == 0) {
        fprintf(stderr, "mvr render: --list %s names no file (one path a line; '#' starts a comment)\n", file);
        ok = false;
    }
    return ok;
}

void render_files_free(render_file_list *list)
{
    for (uint32_t k = 0; k < list->count; ++k)
        free(list->paths[k]);
    free(list->paths);
    memset(list, 0, sizeof *list);
}

/* The file's name without its directory and its last extension; a leading
 * dot (a hidden file's) is kept. */
static void stem(const char *path, char *buf, size_t size)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    size_t len = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    snprintf(buf, size, "%.*s", (int)(len < size ? len : size - 1), base);
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Marks the names that another one repeats (sorted, neighbours compared);
 * true when any does. */
static bool mark_repeats(char (*names)[256], uint32_t n, char **order, bool *repeated)
{
    for (uint32_t k = 0; k < n; ++k) {
        order[k] = names[k];
        repeated[k] = false;
    }
    qsort(order, n, sizeof *order, compare_names);
    bool any = false;
    for (uint32_t k = 1; k < n; ++k)
        if (strcmp(order[k - 1], order[k]) == 0) {
            repeated[(order[k - 1] - names[0]) / 256] = repeated[(order[k] - names[0]) / 256] = true;
            any = true;
        }
    return any;
}

bool render_files_out_dirs(const render_file_list *list, const char *out_root, char **dirs)
{
    uint32_t n = list->count;
    char (*names)[256] = calloc(n ? n : 1, sizeof *names);
    char **order = calloc(n ? n : 1, sizeof *order);
    bool *repeated = calloc(n ? n : 1, sizeof *repeated);
    bool ok = names && order && repeated;
    for (uint32_t k = 0; ok && k < n; ++k) {
        stem(list->paths[k], names[k], sizeof names[k]);
        if (!names[k][0] || strcmp(names[k], ".") == 0 || strcmp(names[k], "..") == 0)
            snprintf(names[k], sizeof names[k], "file_%u", k + 1);
    }
    /* repeated stems take their place in the run; once more where that made
     * a name another file has (a.glb twice and an a_3.glb), until none repeat;
     * file_K for all as the last resort */
    bool any = ok;
    for (int round = 0; ok && any && round < 8; ++round) {
        any = mark_repeats(names, n, order, repeated);
        for (uint32_t k = 0; k < n; ++k)
            if (repeated[k]) {
                char base[256];
                memcpy(base, names[k], sizeof base);
                size_t len = strlen(base);
                /* room for the suffix: the stem is cut, never the number */
                snprintf(names[k], sizeof names[k], "%.*s_%u", (int)(len > 240 ? 240 : len), base, k + 1);
            }
    }
    if (ok && any && mark_repeats(names, n, order, repeated))
        for (uint32_t k = 0; k < n; ++k)
            snprintf(names[k], sizeof names[k], "file_%u", k + 1);
    for (uint32_t k = 0; ok && k < n; ++k) {
        size_t size = strlen(out_root) + 1 + strlen(names[k]) + 1;
        dirs[k] = malloc(size);
        if (!dirs[k])
            ok = false;
        else
            snprintf(dirs[k], size, "%s/%s", out_root, names[k]);
    }
    free(names);
    free(order);
    free(repeated);
    return ok;
}

int render_files_run(const render_file_list *list, const char *out_root, bool keep_going, bool quiet,
                     render_file_fn fn, void *user)
{
    uint32_t n = list->count, rendered = 0, failed = 0, attempted = 0;
    char **dirs = calloc(n, sizeof *dirs);
    bool *failures = calloc(n, sizeof *failures);
    if (!dirs || !failures || !render_files_out_dirs(list, out_root, dirs)) {
        fprintf(stderr, "mvr render: out of memory for the output directories\n");
        if (dirs)
            for (uint32_t k = 0; k < n; ++k)
                free(dirs[k]);
        free(dirs);
        free(failures);
        return MVR_EXIT_FAILURE;
    }
    int rc = MVR_EXIT_OK;
    bool fatal = false;
    for (uint32_t k = 0; k < n; ++k) {
        ++attempted;
        int frc = fn(user, list->paths[k], dirs[k], &fatal);
        if (frc == MVR_EXIT_OK) {
            ++rendered;
            continue;
        }
        failures[k] = true;
        ++failed;
        rmdir(dirs[k]); /* the failed file's directory, when it is empty (made for it) */
        if (rc == MVR_EXIT_OK)
            rc = frc;
        if (fatal || !keep_going)
            break;
    }
    FILE *out = failed ? stderr : stdout;
    if (failed || !quiet) {
        fprintf(out, "mvr render: %u of %u file%s rendered", rendered, n, n == 1 ? "" : "s");
        if (failed) {
            fprintf(out, ", %u failed:", failed);
            for (uint32_t k = 0; k < n; ++k)
                if (failures[k])
                    fprintf(out, " %s", list->paths[k]);
        }
        if (attempted < n)
            fprintf(out, "; %u not attempted (%s)", n - attempted,
                    fatal ? "nothing can render without a context and a renderer"
                          : "the run stops at the first failure without --keep-going");
        fputc('\n', out);
    }
    for (uint32_t k = 0; k < n; ++k)
        free(dirs[k]);
    free(dirs);
    free(failures);
    return rc;
}
