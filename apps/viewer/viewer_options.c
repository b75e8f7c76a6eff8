/* mvr-viewer's command line (viewer_options.h). */
#define _POSIX_C_SOURCE 200809L
#include "viewer_options.h"

#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "cli_options.h"

static const char *display_names[DISPLAY_COUNT] = {"stereo", "grid", "anaglyph", "single"};

const char *viewer_display_name(display_mode display)
{
    return display_names[display];
}

enum {
    V_DEMO = 1, V_VIEWS, V_DISPLAY, V_SINGLE, V_SIZE, V_API, V_VIEW_PATH, V_AA, V_FRAMES, V_SCREENSHOT, V_ANIMATION, V_TIME,
    V_PAUSED, V_CLEAR
};

/* name, value and range, help; the order is --help's */
static const cli_option viewer_table[] = {
    {CLI_OPT_STRING, V_DEMO, "--demo", NULL, "NAME", 0, 0, NULL, "stereo | cube | city | ring (default: stereo)",
     NULL, NULL, NULL},
    {CLI_OPT_U32, V_VIEWS, "--views", NULL, "N", 1, 64, NULL,
     "views (default: the scene's own, 2 for files), 1..64;\n"
     "--demo stereo and city frame at most 35 at 640x480 layers", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, V_DISPLAY, "--display", NULL, "D", 0, 0, "stereo|grid|anaglyph|single",
     "stereo | grid | anaglyph | single (default: stereo)", NULL, NULL, NULL},
    {CLI_OPT_U32, V_SINGLE, "--single", NULL, "K", 0, 63, NULL, "with --display single: the view shown (default 0)",
     NULL, NULL, NULL},
    {CLI_OPT_STRING, V_SIZE, "--size", NULL, "WxH", 0, 0, NULL, "window size (default 1280x480)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, V_API, "--api", NULL, "A", 0, 0, "gles|desktop",
     "gles | desktop: the context GLFW makes (default desktop)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, V_VIEW_PATH, "--view-path", NULL, "P", 0, 0, "auto|multiview|loop",
     "auto | multiview | loop (default auto)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, V_AA, "--aa", NULL, "A", 0, 0, "none|msaa|supersample|auto",
     "none | msaa | supersample | auto: anti-aliasing, as mvr render\n"
     "takes it (default: auto)", NULL, NULL, NULL},
    {CLI_OPT_STRING, V_ANIMATION, "--animation", NULL, "A", 0, 0, NULL,
     "SCENE: play animation A: its name, its index (0-based) or\n"
     "all, as mvr render takes them (default: 0 when the file has\n"
     "animations; they loop)", NULL, NULL, NULL},
    {CLI_OPT_STRING, V_TIME, "--time", NULL, "T", 0, 0, NULL,
     "start at T seconds on the file's animation clock, >= 0,\n"
     "wrapped into the clip (default: the clip's start)", NULL, NULL, NULL},
    {CLI_OPT_FLAG, V_PAUSED, "--paused", NULL, NULL, 0, 0, NULL, "start paused (Space plays)", NULL, NULL, NULL},
    {CLI_OPT_U32, V_FRAMES, "--frames", NULL, "N", 1, 1000000, NULL,
     "render N frames, then exit (with --screenshot: save the last);\n"
     "playback then steps 1/30 s per frame, not by the clock, so\n"
     "frame k shows --time + k/30", NULL, NULL, NULL},
    {CLI_OPT_STRING, V_SCREENSHOT, "--screenshot", NULL, "FILE", 0, 0, NULL,
     "the window's contents after the last frame (PNG)", NULL, NULL, NULL},
    /* the shared --background help names it: color is the clear colour */
    {CLI_OPT_STRING, V_CLEAR, "--clear", NULL, "R,G,B[,A]", 0, 0, NULL,
     "linear clear color, as mvr render takes it (default: a dark\n"
     "opaque sky)", NULL, NULL, NULL},
    {CLI_OPT_END, 0, NULL, NULL, NULL, 0, 0, NULL, NULL, NULL, NULL, NULL},
};

static const cli_option *const viewer_tables[] = {viewer_table, cli_env_option_table, cli_help_option, NULL};

static void usage(FILE *out)
{
    fprintf(out, "usage: mvr-viewer [SCENE.gltf | SCENE.glb | --demo NAME] [options]\n\n");
    cli_print_options(out, viewer_tables, 21);
    fprintf(out,
            "\n"
            "A file opens as mvr render shows it: from its first camera (else framed by its\n"
            "size), auto-exposed when its lights are in physical units, lit by the same\n"
            "environment (--env ... as mvr render takes them).\n"
            "\n"
            "mouse: left drag orbits, right drag pans, wheel zooms; keys: [ ] IPD, + - views,\n"
            "P view path, M material path, D display, Tab next single view, R reset, Esc quit;\n"
            "drop a glTF file on the window to open it.\n"
            "animation: Space play/pause, Left Right step 1/30 s (Shift: a tenth of the clip;\n"
            "both pause), Home the clip's start, N next animation, Shift+N previous; the\n"
            "title names the animation and the time.\n"
            "material variants (KHR_materials_variants): V the next, after the last the file's\n"
            "own materials, Shift+V the previous; the title names the variant.\n");
}

int viewer_options_parse(int argc, char **argv, viewer_options *o)
{
    memset(o, 0, sizeof *o);
    o->demo = "stereo";
    o->width = 1280;
    o->height = 480;
    o->display = DISPLAY_STEREO;
    o->time = -1.0;
    cli_parser p;
    cli_parser_init(&p, "mvr-viewer", viewer_tables, argc, argv);
    cli_arg arg;
    int c;
    while ((c = cli_next(&p, &arg)) > 0) {
        if (!arg.opt) { /* the SCENE (the parser refuses a second) */
            o->file = arg.value;
            continue;
        }
        int env_option = cli_env_apply("mvr-viewer", &arg, &o->env);
        if (env_option < 0)
            return 2;
        if (env_option > 0)
            continue;
        switch (arg.opt->id) {
        case CLI_ID_HELP: usage(stdout); return -1;
        case V_DEMO: o->demo = arg.value; break;
        case V_VIEWS: o->views = arg.number; break;
        case V_SINGLE: o->single = arg.number; break;
        case V_FRAMES: o->frames = arg.number; break;
        case V_SCREENSHOT: o->screenshot = arg.value; break;
        case V_ANIMATION:
            if (!arg.value[0]) {
                fprintf(stderr, "mvr-viewer: --animation takes a name, an index or all (got '')\n");
                return 2;
            }
            o->animation = arg.value;
            break;
        case V_TIME:
            if (!cli_parse_double(arg.value, &o->time) || o->time < 0.0) {
                fprintf(stderr, "mvr-viewer: --time takes seconds >= 0 (got '%s')\n", arg.value);
                return 2;
            }
            break;
        case V_PAUSED: o->paused = true; break;
        case V_CLEAR:
            o->clear.rgba[3] = 1.0f;
            if (sscanf(arg.value, "%f,%f,%f,%f", &o->clear.rgba[0], &o->clear.rgba[1], &o->clear.rgba[2],
                       &o->clear.rgba[3]) < 3) {
                fprintf(stderr, "mvr-viewer: --clear takes R,G,B[,A] (linear, 0..1)\n");
                return 2;
            }
            o->clear.set = true;
            break;
        case V_API: o->gles = arg.choice == 0; break;
        case V_VIEW_PATH: o->view_path = (mvr_view_path)(MVR_VIEW_PATH_AUTO + arg.choice); break;
        case V_AA: o->aa = (mvr_anti_aliasing)(MVR_ANTI_ALIASING_NONE + arg.choice); break;
        case V_DISPLAY: o->display = (display_mode)arg.choice; break;
        case V_SIZE:
            if (!cli_parse_size(arg.value, 1, 16384, &o->width, &o->height)) {
                fprintf(stderr, "mvr-viewer: --size takes WxH with 1..16384 each, e.g. 1280x480\n");
                return 2;
            }
            break;
        }
    }
    if (c < 0)
        return 2;
    if (cli_given(&p, "--single") && o->display != DISPLAY_SINGLE) {
        fprintf(stderr, "mvr-viewer: --single conflicts with --display %s (it is for --display single)\n",
                display_names[o->display]);
        return 2;
    }
    if (!o->file && (o->animation || cli_given(&p, "--time") || o->paused)) {
        fprintf(stderr, "mvr-viewer: --animation, --time and --paused are for a SCENE file (the demos have no "
                        "animations)\n");
        return 2;
    }
    if (cli_given(&p, "--screenshot") && !o->frames) {
        fprintf(stderr, "mvr-viewer: --screenshot needs --frames N (it saves the last of N frames)\n");
        return 2;
    }
    if (!cli_env_check("mvr-viewer", &o->env, o->file != NULL))
        return 2;
    return 0;
}
