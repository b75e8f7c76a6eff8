/* mvr-viewer's command line: its option table (the same mechanism as mvr
 * render's, apps/mvr/cli_options.h), --help, and the checks made before a
 * window opens. */
#ifndef MVR_VIEWER_OPTIONS_H
#define MVR_VIEWER_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>

#include "cli_env.h"
#include "mvr/mvr.h"

typedef enum display_mode {
    DISPLAY_STEREO, DISPLAY_GRID, DISPLAY_ANAGLYPH, DISPLAY_SINGLE, DISPLAY_COUNT
} display_mode;

/* "stereo", "grid", "anaglyph", "single" (--display and the title). */
const char *viewer_display_name(display_mode display);

/* --clear R,G,B[,A]: the linear clear colour (--background color) */
typedef struct viewer_clear {
    bool set;                    /* given; else mvr render's default */
    float rgba[4];
} viewer_clear;

typedef struct viewer_options {
    const char *file;            /* SCENE; NULL: demo */
    const char *demo;            /* --demo (default: stereo) */
    const char *screenshot;      /* --screenshot FILE; NULL: none */
    uint32_t width, height;      /* --size: the window (default 1280x480) */
    uint32_t frames;             /* --frames N; 0: until the window closes */
    bool gles;                   /* --api gles */
    uint32_t views;              /* --views; 0: the scene's own */
    uint32_t single;             /* --single K */
    display_mode display;        /* --display */
    mvr_view_path view_path;     /* --view-path */
    mvr_anti_aliasing aa;        /* --aa; DEFAULT: the library's (auto) */
    cli_env_options env;         /* --env ... */
    const char *animation;       /* --animation; NULL: 0 when there is one */
    double time;                 /* --time; < 0: the clip's start */
    bool paused;                 /* --paused */
    viewer_clear clear;          /* --clear */
} viewer_options;

/* Parses and checks the command line into o. 0: open the window; -1:
 * --help was printed (exit 0); 2: a usage error (printed). */
int viewer_options_parse(int argc, char **argv, viewer_options *o);

#endif
