/* mvr: command-line front end of the library. */
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "mvr/mvr.h"

static void usage(FILE *out)
{
    fprintf(out,
            "usage: mvr <command> [options]\n"
            "\n"
            "commands:\n"
            "  render   render a scene into N views headless; one PNG per view\n"
            "  bench    time against error of the configurations, side by side, with a plot\n"
            "  info     print the GL capabilities mvr sees through a context provider,\n"
            "           or what a glTF file holds (mvr info FILE: skins, animations, ...)\n"
            "\n"
            "  mvr <command> --help   options of a command\n"
            "  mvr --version          the version of mvr\n");
}

int main(int argc, char **argv)
{
    cli_tune_allocator();
    if (argc < 2) {
        usage(stderr);
        return MVR_EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        usage(stdout);
        return MVR_EXIT_OK;
    }
    if (strcmp(cmd, "--version") == 0) {
        printf("mvr %d.%d.%d\n", MVR_VERSION_MAJOR, MVR_VERSION_MINOR, MVR_VERSION_PATCH);
        return MVR_EXIT_OK;
    }
    if (strcmp(cmd, "info") == 0)
        return mvr_cmd_info(argc - 1, argv + 1);
    if (strcmp(cmd, "render") == 0)
        return mvr_cmd_render(argc - 1, argv + 1);
    if (strcmp(cmd, "bench") == 0)
        return mvr_cmd_bench(argc - 1, argv + 1);
    fprintf(stderr, "mvr: unknown command '%s'\n\n", cmd);
    usage(stderr);
    return MVR_EXIT_USAGE;
}
