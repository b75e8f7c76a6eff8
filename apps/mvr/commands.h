#ifndef MVR_APP_COMMANDS_H
#define MVR_APP_COMMANDS_H

/* Exit codes of the mvr CLI. */
enum {
    MVR_EXIT_OK = 0,
    MVR_EXIT_FAILURE = 1,   /* the library returned an error */
    MVR_EXIT_USAGE = 2,     /* bad command line */
    MVR_EXIT_MISSING = 3    /* a --require'd capability is missing, or a program an option runs
                               (ffmpeg for mvr render --video) */
};

int mvr_cmd_info(int argc, char **argv);
int mvr_cmd_render(int argc, char **argv);
int mvr_cmd_bench(int argc, char **argv);

#endif
