/* mvr render's camera sampling options (issue 33): --fov, --radius,
 * --margin, --hemisphere, --seed, --min-spacing, --elevation, --up; their
 * table, their values into an mvr_framing_desc, and their combination with
 * the rest checked. */
#ifndef MVR_APP_RENDER_SAMPLING_H
#define MVR_APP_RENDER_SAMPLING_H

#include "cli_options.h"
#include "render_options.h"

/* ids 1400..1499: apart from render_options.c's own and the shared tables' */
#define RENDER_ID_SAMPLING 1400

extern const cli_option render_sampling_table[];

/* One option's value into o->framing: 1 applied, 0 not one of these, -1 a
 * bad value (printed). */
int render_sampling_apply(const cli_arg *arg, render_options *o);

/* After the scene is settled: the options are for a SCENE framed by
 * --layout (not a demo, a file's camera or --cameras), --seed and
 * --min-spacing for --layout random, --elevation and --hemisphere for
 * sphere, random and orbit. MVR_EXIT_OK, or MVR_EXIT_USAGE (printed). */
int render_sampling_check(const cli_parser *p, const render_options *o);

#endif
