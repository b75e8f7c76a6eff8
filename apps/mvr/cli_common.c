/* dl_iterate_phdr and RTLD_NODELETE (cli_pin_loaded_libraries, sanitizer builds) are GNU extensions */
#define _GNU_SOURCE 1
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#if defined(__SANITIZE_ADDRESS__)
#define CLI_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CLI_ASAN 1
#endif
#endif
#ifdef CLI_ASAN
#include <dlfcn.h>
#include <link.h>
#endif

#include "cli_common.h"

static void log_to_stderr(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    if (id == MVR_LOG_ID_ERROR_RESULT)
        return; /* the command prints the error it got back itself */
    static const char *const names[] = {"", "error", "warning", "info", "debug"};
    fprintf(stderr, "mvr %s: %s: %s\n", (const char *)user, (unsigned)level < 5 ? names[level] : "?",
            message);
}

void cli_logger(mvr_logger *logger, const char *command, bool verbose)
{
    logger->fn = log_to_stderr;
    logger->user_data = (void *)(uintptr_t)command;
    logger->level = verbose ? MVR_LOG_DEBUG : MVR_LOG_WARNING;
}

enum { CTX_CONTEXT = CLI_ID_CONTEXT, CTX_API, CTX_DEVICE };

const cli_option cli_context_options[] = {
    {CLI_OPT_STRING, CTX_CONTEXT, "--context", NULL, "NAME", 0, 0, NULL,
     "default | surfaceless | device | pbuffer | osmesa\n(default: surfaceless, then device, then pbuffer)", NULL, NULL,
     NULL},
    {CLI_OPT_CHOICE, CTX_API, "--api", NULL, "NAME", 0, 0, "gles|desktop",
     "gles | desktop (default: gles on EGL, desktop on osmesa)", NULL, NULL, NULL},
    {CLI_OPT_U32, CTX_DEVICE, "--device", NULL, "N", 1, 1024, NULL,
     "with --context device: the N-th EGL device (1-based)", NULL, NULL, NULL},
    {CLI_OPT_END, 0, NULL, NULL, NULL, 0, 0, NULL, NULL, NULL, NULL, NULL},
};

int cli_context_apply(const char *command, const cli_arg *arg, mvr_context_desc *desc)
{
    if (!arg->opt || arg->opt->id < CTX_CONTEXT || arg->opt->id > CTX_DEVICE)
        return 0;
    switch (arg->opt->id) {
    case CTX_CONTEXT:
        if (mvr_context_provider_from_name(arg->value, &desc->provider) != MVR_OK ||
            desc->provider == MVR_CONTEXT_PROVIDER_EXTERNAL) {
            fprintf(stderr, "%s: unknown context provider '%s' (default, surfaceless, device, "
                            "pbuffer, osmesa)\n", command, arg->value);
            return -1;
        }
        break;
    case CTX_API:
        desc->api = arg->choice == 0 ? MVR_GL_API_GLES : MVR_GL_API_DESKTOP;
        break;
    default:
        desc->device_index = (int)arg->number;
    }
    return 1;
}

int cli_context_option(const char *command, int argc, char **argv, int *i, mvr_context_desc *desc)
{
    const char *a = argv[*i];
    const char *value = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (strcmp(a, "--context") != 0 && strcmp(a, "--api") != 0 && strcmp(a, "--device") != 0)
        return 0;
    if (!value) {
        fprintf(stderr, "mvr %s: %s needs a value\n", command, a);
        return -1;
    }
    if (strcmp(a, "--context") == 0) {
        if (mvr_context_provider_from_name(value, &desc->provider) != MVR_OK ||
            desc->provider == MVR_CONTEXT_PROVIDER_EXTERNAL) {
            fprintf(stderr, "mvr %s: unknown context provider '%s' (default, surfaceless, device, "
                            "pbuffer, osmesa)\n", command, value);
            return -1;
        }
    } else if (strcmp(a, "--api") == 0) {
        if (strcmp(value, "gles") == 0)
            desc->api = MVR_GL_API_GLES;
        else if (strcmp(value, "desktop") == 0)
            desc->api = MVR_GL_API_DESKTOP;
        else {
            fprintf(stderr, "mvr %s: unknown api '%s' (gles, desktop)\n", command, value);
            return -1;
        }
    } else {
        char *end = NULL;
        long n = strtol(value, &end, 10);
        if (!end || *end || n < 1 || n > 1024) {
            fprintf(stderr, "mvr %s: --device takes a number from 1\n", command);
            return -1;
        }
        desc->device_index = (int)n;
    }
    *i += 1;
    return 1;
}

bool cli_context_check(const char *command, const mvr_context_desc *desc)
{
    if (desc->device_index > 0 && desc->provider != MVR_CONTEXT_PROVIDER_DEVICE) {
        fprintf(stderr, "mvr %s: --device needs --context device\n", command);
        return false;
    }
    if (desc->provider == MVR_CONTEXT_PROVIDER_OSMESA &&
        !mvr_context_provider_built(MVR_CONTEXT_PROVIDER_OSMESA)) {
        fprintf(stderr, "mvr %s: this mvr was built without the osmesa provider\n", command);
        return false;
    }
    return true;
}

/* mkdir -p */
bool cli_make_dirs(const char *command, const char *path)
{
    char buf[4096];
    size_t n = strlen(path);
    if (n == 0 || n >= sizeof buf) {
        fprintf(stderr, "%s: bad directory '%s'\n", command, path);
        return false;
    }
    memcpy(buf, path, n + 1);
    for (size_t i = 1; i <= n; ++i) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        char saved = buf[i];
        buf[i] = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
            fprintf(stderr, "%s: cannot create %s: %s\n", command, buf, strerror(errno));
            return false;
        }
        buf[i] = saved;
    }
    return true;
}

bool cli_parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *out)
{
    char *end = NULL;
    errno = 0;
    unsigned long v = strtoul(s, &end, 10);
    if (errno || !end || *end || v < lo || v > hi)
        return false;
    *out = (uint32_t)v;
    return true;
}

bool cli_parse_double(const char *s, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || !end || *end || errno == ERANGE || !isfinite(v))
        return false;
    *out = v;
    return true;
}

void cli_tune_allocator(void)
{
#ifdef __GLIBC__
    const char *off = getenv("MVR_MALLOPT"), *tunables = getenv("GLIBC_TUNABLES");
    if ((off && strcmp(off, "off") == 0) || (tunables && *tunables))
        return;
    /* measured (docs/benchmarks.md, "Allocator churn"): city, 16 views,
     * multiview, 12 frames: 93k-164k minor page faults -> 36k-47k */
    mallopt(M_MMAP_THRESHOLD, 64 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

#ifdef CLI_ASAN
static int pin_library(struct dl_phdr_info *info, size_t size, void *data)
{
    (void)size;
    (void)data;
    if (info->dlpi_name && info->dlpi_name[0])
        dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE); /* a reference never dropped */
    return 0;
}
#endif

void cli_pin_loaded_libraries(void)
{
#ifdef CLI_ASAN
    dl_iterate_phdr(pin_library, NULL);
#endif
}

const char *cli_program_cache_dir(const char *command, const char *option, char *buf, size_t size)
{
    if (option && strcmp(option, "off") == 0)
        return NULL;
    if (option) {
        snprintf(buf, size, "%s", option);
    } else {
        const char *xdg = getenv("XDG_CACHE_HOME");
        const char *home = getenv("HOME");
        int n;
        if (xdg && xdg[0] == '/') /* the XDG spec ignores relative paths */
            n = snprintf(buf, size, "%s/mvr/programs", xdg);
        else if (home && home[0])
            n = snprintf(buf, size, "%s/.cache/mvr/programs", home);
        else
            return NULL;
        if (n <= 0 || (size_t)n >= size)
            return NULL;
    }
    if (!cli_make_dirs(command, buf) || access(buf, W_OK | X_OK) != 0) {
        fprintf(stderr, "%s: warning: no program cache (cannot create or write %s)\n", command, buf);
        return NULL;
    }
    return buf;
}
