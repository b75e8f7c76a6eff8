/* mvr render SCENE... and --list FILE: the files of one run, the output
 * directory of each (DIR/<file's stem>/ when there is more than one), and
 * the loop that renders them one after another in one process (one context,
 * renderer and program cache: cmd_render.c's), with --keep-going and the
 * summary of what rendered and what failed. */
#ifndef MVR_APP_RENDER_FILES_H
#define MVR_APP_RENDER_FILES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define RENDER_FILES_MAX 100000u
#define RENDER_FILES_MAX_PATH 4095u

typedef struct render_file_list {
    char **paths;
    uint32_t count, capacity;
} render_file_list;

/* Appends a copy of path; false (printed, prefixed "mvr render") past
 * RENDER_FILES_MAX files or out of memory. */
bool render_files_add(render_file_list *list, const char *path);

/* Appends the paths listed in file: one a line, blanks around it trimmed,
 * empty lines and lines starting with '#' skipped, "\r\n" ends taken;
 * relative paths are taken from the current directory (as on the command
 * line). false (printed, naming the line) for a line longer than
 * RENDER_FILES_MAX_PATH, a NUL byte, an unreadable file, or a list that
 * names no file. */
bool render_files_read_list(const char *file, render_file_list *list);

void render_files_free(render_file_list *list);

/* The output directory of each file: DIR/<stem> (the file's name without
 * its directory and last extension), DIR/<stem>_<K> (K = its 1-based place
 * in the run) where stems repeat, "file_<K>" for a stem that is no usable
 * directory name ("", ".", ".."). dirs[k] is malloc'd; false when out of
 * memory. */
bool render_files_out_dirs(const render_file_list *list, const char *out_root, char **dirs);

/* Renders one file into out_dir: an MVR_EXIT_ code; *fatal set when
 * nothing after it can run either (no context or renderer). */
typedef int (*render_file_fn)(void *user, const char *file, const char *out_dir, bool *fatal);

/* Renders every file of list through fn, each into its own directory
 * (render_files_out_dirs). A failure is reported by fn (mvr's message on
 * stderr); with keep_going the next file is rendered, otherwise the run
 * stops there. Then the summary: rendered, failed (each named), not
 * attempted; on stdout unless quiet when all rendered, on stderr when any
 * failed. Returns MVR_EXIT_OK, or the first failure's code. */
int render_files_run(const render_file_list *list, const char *out_root, bool keep_going, bool quiet,
                     render_file_fn fn, void *user);

#endif
