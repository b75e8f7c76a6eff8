/* The option table parser and help printer shared by mvr render, mvr bench
 * and mvr-viewer (cli_options.h). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_common.h"
#include "cli_options.h"

const cli_option cli_help_option[] = {
    {CLI_OPT_FLAG, CLI_ID_HELP, "--help", "-h", NULL, 0, 0, NULL, "this text", NULL, NULL, NULL},
    {CLI_OPT_END, 0, NULL, NULL, NULL, 0, 0, NULL, NULL, NULL, NULL, NULL},
};

void cli_parser_init(cli_parser *p, const char *command, const cli_option *const *tables, int argc, char **argv)
{
    memset(p, 0, sizeof *p);
    p->command = command;
    p->tables = tables;
    p->argc = argc;
    p->argv = argv;
    p->i = 1;
}

static const cli_option *find(const cli_option *const *tables, const char *name)
{
    for (const cli_option *const *t = tables; *t; ++t)
        for (const cli_option *o = *t; o->kind != CLI_OPT_END; ++o)
            if (o->kind != CLI_OPT_TEXT &&
                (strcmp(o->name, name) == 0 || (o->alias && strcmp(o->alias, name) == 0)))
                return o;
    return NULL;
}

/* Whether name is a whole word of the space-separated list. */
static bool listed(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *s = list; s && (s = strstr(s, name)) != NULL; s += n)
        if ((s == list || s[-1] == ' ') && (s[n] == '\0' || s[n] == ' '))
            return true;
    return false;
}

/* "a|b|c" -> "a, b or c" */
static void print_choices(FILE *out, const char *choices)
{
    size_t count = 1;
    for (const char *c = choices; *c; ++c)
        count += *c == '|';
    size_t k = 0;
    for (const char *c = choices; *c; ++k) {
        size_t len = strcspn(c, "|");
        fprintf(out, "%s%.*s", k == 0 ? "" : k + 1 == count ? " or " : ", ", (int)len, c);
        c += len + (c[len] == '|');
    }
}

static int choice_index(const char *choices, const char *v)
{
    int k = 0;
    size_t n = strlen(v);
    for (const char *c = choices; *c; ++k) {
        size_t len = strcspn(c, "|");
        if (len == n && strncmp(c, v, n) == 0)
            return k;
        c += len + (c[len] == '|');
    }
    return -1;
}

static bool conflict(cli_parser *p, const cli_option *a)
{
    for (unsigned k = 0; k < p->given_count; ++k) {
        const cli_option *b = p->given[k];
        if (a == b)
            continue;
        if (a->group && b->group && strcmp(a->group, b->group) == 0) {
            fprintf(stderr, "%s: %s and %s both set %s: give one of them\n", p->command, b->name, a->name, a->group);
            return true;
        }
        const cli_option *owner = listed(a->conflicts, b->name) ? a : listed(b->conflicts, a->name) ? b : NULL;
        if (owner) {
            fprintf(stderr, "%s: %s conflicts with %s", p->command, b->name, a->name);
            if (owner->why)
                fprintf(stderr, " (%s)", owner->why);
            fprintf(stderr, ": give one of them\n");
            return true;
        }
    }
    return false;
}

int cli_next(cli_parser *p, cli_arg *arg)
{
    memset(arg, 0, sizeof *arg);
    if (p->i >= p->argc)
        return 0;
    const char *a = p->argv[p->i++];
    if (a[0] != '-' || a[1] == '\0') { /* a positional argument ("-" too: stdin is no scene) */
        if (p->positional && !p->many_positionals) { /* one SCENE at most, unless the command takes more */
            fprintf(stderr, "%s: one SCENE file at a time (got %s and %s)\n", p->command, p->positional, a);
            return -1;
        }
        p->positional = a;
        arg->value = a;
        return 1;
    }
    const cli_option *o = find(p->tables, a);
    if (!o) {
        fprintf(stderr, "%s: unknown option %s (see --help)\n", p->command, a);
        return -1;
    }
    arg->opt = o;
    if (o->kind != CLI_OPT_FLAG) {
        const char *v = p->i < p->argc ? p->argv[p->i] : NULL;
        if (!v || strncmp(v, "--", 2) == 0) { /* "--out --quiet": the value was forgotten */
            fprintf(stderr, "%s: %s needs a value (%s)\n", p->command, o->name, o->value_name ? o->value_name : "VALUE");
            return -1;
        }
        p->i++;
        arg->value = v;
        if (o->kind == CLI_OPT_U32 && !cli_parse_u32(v, o->lo, o->hi, &arg->number)) {
            fprintf(stderr, "%s: %s takes %u..%u (got '%s')\n", p->command, o->name, o->lo, o->hi, v);
            return -1;
        }
        if (o->kind == CLI_OPT_CHOICE && (arg->choice = choice_index(o->choices, v)) < 0) {
            fprintf(stderr, "%s: %s takes ", p->command, o->name);
            print_choices(stderr, o->choices);
            fprintf(stderr, " (got '%s')\n", v);
            return -1;
        }
    }
    if (conflict(p, o))
        return -1;
    bool seen = false;
    for (unsigned k = 0; k < p->given_count; ++k)
        seen |= p->given[k] == o;
    if (!seen && p->given_count < CLI_MAX_GIVEN)
        p->given[p->given_count++] = o;
    return 1;
}

bool cli_given(const cli_parser *p, const char *name)
{
    for (unsigned k = 0; k < p->given_count; ++k)
        if (strcmp(p->given[k]->name, name) == 0)
            return true;
    return false;
}

void cli_print_options(FILE *out, const cli_option *const *tables, int width)
{
    for (const cli_option *const *t = tables; *t; ++t)
        for (const cli_option *o = *t; o->kind != CLI_OPT_END; ++o) {
            if (o->kind == CLI_OPT_TEXT) {
                fputs(o->help, out);
                continue;
            }
            if (!o->help)
                continue;
            char label[128];
            if (o->alias)
                snprintf(label, sizeof label, "%s, %s", o->alias, o->name);
            else if (o->value_name)
                snprintf(label, sizeof label, "%s %s", o->name, o->value_name);
            else
                snprintf(label, sizeof label, "%s", o->name);
            int len = fprintf(out, "  %s", label) - 2;
            /* a label too long for the column: one space, the help after it */
            fprintf(out, "%*s", len < width ? width - len : 1, "");
            for (const char *h = o->help; *h;) {
                size_t n = strcspn(h, "\n");
                fprintf(out, "%.*s\n", (int)n, h);
                h += n;
                if (*h == '\n' && *++h)
                    fprintf(out, "  %*s", width, "");
            }
        }
}

bool cli_parse_size(const char *v, uint32_t lo, uint32_t hi, uint32_t *w, uint32_t *h)
{
    char ws[16] = "", hs[16] = "";
    const char *x = strchr(v, 'x');
    if (!x || (size_t)(x - v) >= sizeof ws || strlen(x + 1) >= sizeof hs)
        return false;
    memcpy(ws, v, (size_t)(x - v));
    strcpy(hs, x + 1);
    return cli_parse_u32(ws, lo, hi, w) && cli_parse_u32(hs, lo, hi, h);
}

bool cli_check_writable_dir(const char *command, const char *option, const char *dir)
{
    struct stat st;
    if (dir[0] == '\0') {
        fprintf(stderr, "%s: %s takes a directory (got '')\n", command, option);
        return false;
    }
    if (stat(dir, &st) == 0 && !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "%s: %s %s: not a directory\n", command, option, dir);
        return false;
    }
    if (!cli_make_dirs(command, dir)) { /* printed "cannot create ...: why" */
        fprintf(stderr, "%s: %s %s: no such directory, and it cannot be created\n", command, option, dir);
        return false;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        fprintf(stderr, "%s: %s %s: not writable: %s\n", command, option, dir, strerror(errno));
        return false;
    }
    return true;
}
