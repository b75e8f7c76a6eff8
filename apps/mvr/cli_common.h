/* Options and helpers every mvr command shares. */
#ifndef MVR_CLI_COMMON_H
#define MVR_CLI_COMMON_H

#include <stdbool.h>
#include <stdint.h>

#include "cli_options.h"
#include "mvr/mvr.h"

/* Logs warnings and errors (all levels with verbose) to stderr, prefixed with
 * the command; skips MVR_LOG_ID_ERROR_RESULT, which commands print themselves. */
void cli_logger(mvr_logger *logger, const char *command, bool verbose);

/* Parses --context NAME, --api NAME, --device N at argv[*i] into desc.
 * Returns 1 if consumed (advancing *i), 0 if not a context option, -1 on a
 * bad value (message printed). */
int cli_context_option(const char *command, int argc, char **argv, int *i, mvr_context_desc *desc);

/* --context, --api, --device as a table (ids CLI_ID_CONTEXT..), for
 * cli_parser; cli_context_apply stores a parsed one into desc. Returns 1 if
 * arg is one of them, 0 if not, -1 on a bad value (printed, prefixed with
 * command, e.g. "mvr render"). */
extern const cli_option cli_context_options[];
int cli_context_apply(const char *command, const cli_arg *arg, mvr_context_desc *desc);

/* Checks the combination; prints and returns false when it is not valid. */
bool cli_context_check(const char *command, const mvr_context_desc *desc);

/* A decimal number in [lo, hi], the whole string; false otherwise. */
bool cli_parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *out);

/* A finite number, the whole string ("nan", "inf", "1e999" and "2s" are
 * not); false otherwise. */
bool cli_parse_double(const char *s, double *out);

/* Creates path and its parents (mkdir -p); prints what failed. */
bool cli_make_dirs(const char *command, const char *path);

/* The program binary cache directory (which also keeps auto's settled
 * choices): option (--program-cache D), else the XDG cache directory
 * ($XDG_CACHE_HOME/mvr/programs or ~/.cache/mvr/programs); created if
 * missing, into buf. NULL for option "off", or (with a warning prefixed
 * with command) when the directory cannot be made: then the run compiles
 * as usual. */
const char *cli_program_cache_dir(const char *command, const char *option, char *buf, size_t size);

/* The allocator choice of mvr, mvr bench and mvr-viewer: glibc's
 * mmap and trim thresholds raised to 64 and 256 MiB, so the scene bins a GL
 * driver allocates and frees every frame (llvmpipe: megabytes per multiview
 * pass) stay in the heap instead of being mapped, unmapped and faulted in
 * again each frame. Left alone when GLIBC_TUNABLES is set (the user's
 * choice) or MVR_MALLOPT=off; a no-op without glibc. */
void cli_tune_allocator(void);

/* Sanitizer builds only (a no-op otherwise): keeps every shared library now
 * loaded in memory until exit (RTLD_NODELETE), so that what a GL driver
 * leaks in a library it later unloads (Mesa's GLX path dlcloses libgallium
 * at glfwTerminate) is still named at exit and tests/sanitizers/lsan.supp's
 * suppressions by library name match it, instead of an "<unknown module>". */
void cli_pin_loaded_libraries(void);

#endif
