/* One option table mechanism for mvr render, mvr bench and mvr-viewer: each
 * option's name, value kind and range, help text and what it cannot be
 * combined with. The parser gives unknown options, missing values, bad
 * values and conflicts their own messages (exit 2); --help is printed from
 * the same tables. */
#ifndef MVR_CLI_OPTIONS_H
#define MVR_CLI_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

typedef enum cli_opt_kind {
    CLI_OPT_END = 0,  /* terminates a table */
    CLI_OPT_TEXT,     /* not an option: help text printed verbatim (a heading) */
    CLI_OPT_FLAG,     /* takes no value */
    CLI_OPT_STRING,   /* any value (checked by the command) */
    CLI_OPT_U32,      /* a decimal number in lo..hi, checked by the parser */
    CLI_OPT_CHOICE    /* one of choices ("auto|multiview|loop"), checked by the parser */
} cli_opt_kind;

typedef struct cli_option {
    cli_opt_kind kind;
    int id;                  /* the command's own; shared tables use CLI_ID_CONTEXT/ENV ranges */
    const char *name;        /* "--size" */
    const char *alias;       /* "-h", or NULL */
    const char *value_name;  /* "WxH": shown in the help and in "--size needs a value (WxH)" */
    uint32_t lo, hi;         /* CLI_OPT_U32: the range */
    const char *choices;     /* CLI_OPT_CHOICE: "a|b|c" */
    const char *help;        /* lines (no trailing newline); NULL: not listed (internal) */
    const char *group;       /* conflict group: two different options of one group are refused;
                                the text says what they both set ("the exposure") */
    const char *conflicts;   /* other options refused with this one: "--view-path --msaa" */
    const char *why;         /* with conflicts: why ("--reference sets its own view path, ...") */
} cli_option;

#define CLI_ID_CONTEXT 1000  /* 1000..1099: cli_context_options */
#define CLI_ID_ENV 1100      /* 1100..1199: cli_env_option_table */
#define CLI_ID_HELP 1200     /* cli_help_option */

/* One parsed argument. opt NULL: a positional argument (value). */
typedef struct cli_arg {
    const cli_option *opt;
    const char *value;       /* NULL for a flag */
    uint32_t number;         /* CLI_OPT_U32 */
    int choice;              /* CLI_OPT_CHOICE: the index in choices */
} cli_arg;

#define CLI_MAX_GIVEN 128

typedef struct cli_parser {
    const char *command;              /* "mvr render": prefixes every message */
    const cli_option *const *tables;  /* NULL-terminated; their order is the help's */
    int argc;
    char **argv;
    int i;
    unsigned given_count;
    const cli_option *given[CLI_MAX_GIVEN];
    const char *positional;           /* the SCENE argument, once given (a second is refused) */
    bool many_positionals;            /* set after init: every positional argument is returned
                                         (mvr render SCENE...), none refused */
} cli_parser;

void cli_parser_init(cli_parser *p, const char *command, const cli_option *const *tables, int argc, char **argv);

/* The next argument: 1 with *arg filled, 0 at the end, -1 on a usage error
 * (printed: "unknown option --bogus (see --help)", "--size needs a value
 * (WxH)", "--views takes 1..1024 (got '0')", "--aa takes none, msaa,
 * supersample or auto (got 'x')", a refused conflict naming both, or a
 * second positional argument: "one SCENE file at a time (got a and b)"). */
int cli_next(cli_parser *p, cli_arg *arg);

/* Whether the option named name (e.g. "--layout") was given. */
bool cli_given(const cli_parser *p, const char *name);

/* Prints the tables' options: the label ("--size WxH") in a column of
 * width, then the help lines. */
void cli_print_options(FILE *out, const cli_option *const *tables, int width);

/* "-h, --help  this text", for every command's table list. */
extern const cli_option cli_help_option[];

/* "WxH" with each side in lo..hi. */
bool cli_parse_size(const char *v, uint32_t lo, uint32_t hi, uint32_t *w, uint32_t *h);

/* --program-cache DIR given explicitly: creates DIR (and its parents) when
 * missing, then checks it is a directory this user can write to. Prints why
 * not (prefixed with command) and returns false. */
bool cli_check_writable_dir(const char *command, const char *option, const char *dir);

#endif
