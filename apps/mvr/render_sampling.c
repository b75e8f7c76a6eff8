/* mvr render's camera sampling options (render_sampling.h): angles are
 * given in degrees here and handed to the library in radians; its ranges
 * are checked here first, so a bad value is a usage error naming the
 * option, before any scene is loaded. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "render_sampling.h"

#define PI 3.14159265358979323846

enum {
    S_FOV = RENDER_ID_SAMPLING, S_RADIUS, S_MARGIN, S_HEMISPHERE, S_SEED, S_MIN_SPACING, S_ELEVATION, S_UP
};

#define DISTANCE_GROUP "the camera distance"

const cli_option render_sampling_table[] = {
    {CLI_OPT_STRING, S_FOV, "--fov", NULL, "DEG", 0, 0, NULL,
     "--layout: vertical field of view of the views in degrees,\n"
     "0.06..177 (default: 50)", NULL, NULL, NULL},
    {CLI_OPT_STRING, S_RADIUS, "--radius", NULL, "R", 0, 0, NULL,
     "--layout: the cameras' distance from the centre of the\n"
     "scene's bounds, in scene units, (0, 1e9] (default: the\n"
     "bounding box fitted; stereo, grid: of their plane)", DISTANCE_GROUP, NULL, NULL},
    {CLI_OPT_STRING, S_MARGIN, "--margin", NULL, "M", 0, 0, NULL,
     "--layout: the fit of the scene's bounding box: each view as\n"
     "close as keeps every corner inside the image less M of its\n"
     "half-size on each side, 0..0.9; the box touches that inset\n"
     "on one axis (stereo, grid: in one of their views)\n"
     "(default: 0.05)", DISTANCE_GROUP, NULL, NULL},
    {CLI_OPT_CHOICE, S_HEMISPHERE, "--hemisphere", NULL, "H", 0, 0, "full|upper",
     "--layout sphere, random, orbit: full | upper: upper keeps\n"
     "every view at or above the scene centre's horizon (default:\n"
     "full)", NULL, NULL, NULL},
    {CLI_OPT_U32, S_SEED, "--seed", NULL, "S", 0, 4294967295u, NULL,
     "--layout random: the seed of its views (the same seed, the\n"
     "same views) (default: 0)", NULL, NULL, NULL},
    {CLI_OPT_STRING, S_MIN_SPACING, "--min-spacing", NULL, "DEG", 0, 0, NULL,
     "--layout random: the least angle between two views, seen\n"
     "from the centre, 0..180 degrees (default: half the mean\n"
     "spacing, 0.5 sqrt(area / views)); too large for --views is\n"
     "refused", NULL, NULL, NULL},
    {CLI_OPT_STRING, S_ELEVATION, "--elevation", NULL, "DEG|MIN,MAX", 0, 0, NULL,
     "--layout stereo, ring, grid: DEG, the angle the views look\n"
     "down at the scene from, inside (-90, 90), 0 level (default:\n"
     "30); sphere, random: MIN,MAX, the band of elevations the\n"
     "views lie in, degrees in -90..90 (default: all); orbit:\n"
     "MIN,MAX, its lowest and highest ring, inside (-90, 90)\n"
     "(default: -15,60)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, S_UP, "--up", NULL, "A", 0, 0, "y|z",
     "--layout: the world's up axis: the layouts orbit it and the\n"
     "cameras' up follows it; z for a Z-up world (Blender's),\n"
     "seen from -Y as its front view (default: y, glTF's)", NULL, NULL, NULL},
    {CLI_OPT_END, 0, NULL, NULL, NULL, 0, 0, NULL, NULL, NULL, NULL, NULL},
};

/* A number in [lo, hi], the whole string; prints what was wanted. */
static bool parse_in(const char *option, const char *v, double lo, double hi, const char *what, double *out)
{
    if (cli_parse_double(v, out) && *out >= lo && *out <= hi)
        return true;
    fprintf(stderr, "mvr render: %s takes %s (got '%s')\n", option, what, v);
    return false;
}

int render_sampling_apply(const cli_arg *arg, render_options *o)
{
    mvr_framing_desc *f = &o->framing;
    const char *v = arg->value;
    double x = 0;
    switch (arg->opt->id) {
    case S_FOV:
        if (!parse_in("--fov", v, 0.06, 177.0, "degrees in 0.06..177", &x))
            return -1;
        f->yfov = x * PI / 180.0;
        break;
    case S_RADIUS:
        if (!cli_parse_double(v, &x) || !(x > 0 && x <= 1e9)) {
            fprintf(stderr, "mvr render: --radius takes a distance in (0, 1e9] scene units (got '%s')\n", v);
            return -1;
        }
        f->radius = x;
        break;
    case S_MARGIN:
        if (!parse_in("--margin", v, 0.0, 0.9, "a fraction of the image in 0..0.9", &x))
            return -1;
        f->fit_box = true;
        f->margin = x;
        break;
    case S_HEMISPHERE: f->hemisphere = arg->choice == 1 ? MVR_HEMISPHERE_UPPER : MVR_HEMISPHERE_FULL; break;
    case S_SEED: f->seed = arg->number; break;
    case S_MIN_SPACING:
        if (!parse_in("--min-spacing", v, 0.0, 180.0, "degrees in 0..180", &x))
            return -1;
        f->min_spacing = x * PI / 180.0;
        break;
    case S_ELEVATION: {
        double lo = 0, hi = 0;
        char extra = 0;
        if (!strchr(v, ',')) { /* stereo, ring, grid: one angle; 0 is level */
            if (!cli_parse_double(v, &x) || !(x > -90.0 && x < 90.0)) {
                fprintf(stderr, "mvr render: --elevation takes DEG inside (-90, 90) or MIN,MAX (got '%s')\n", v);
                return -1;
            }
            f->elevation = x * PI / 180.0;
            f->level = x == 0;
            o->elevation_single = true;
            break;
        }
        if (sscanf(v, "%lf,%lf%c", &lo, &hi, &extra) != 2 || !(lo >= -90.0 && hi <= 90.0 && lo <= hi)) {
            fprintf(stderr, "mvr render: --elevation takes MIN,MAX in degrees, -90 <= MIN <= MAX <= 90 (got '%s')\n",
                    v);
            return -1;
        }
        f->elevation_min = lo * PI / 180.0;
        f->elevation_max = hi * PI / 180.0;
        break;
    }
    case S_UP: f->up = arg->choice == 1 ? MVR_UP_Z : MVR_UP_Y; break;
    default: return 0;
    }
    return 1;
}

int render_sampling_check(const cli_parser *p, const render_options *o)
{
    const char *given = NULL;
    for (const cli_option *opt = render_sampling_table; opt->kind != CLI_OPT_END && !given; ++opt)
        if (cli_given(p, opt->name))
            given = opt->name;
    if (!given)
        return MVR_EXIT_OK;
    if (!o->scene_file || o->cameras_file || !o->layout_set) {
        fprintf(stderr, "mvr render: %s is for a SCENE file framed with --layout L (%s)\n", given,
                !o->scene_file    ? "a demo brings its own views"
                : o->cameras_file ? "--cameras gives every view"
                                  : "without --layout a file is seen from its own camera");
        return MVR_EXIT_USAGE;
    }
    mvr_view_layout l = o->layout;
    const char *layout = mvr_view_layout_name(l);
    if ((cli_given(p, "--seed") || cli_given(p, "--min-spacing")) && l != MVR_LAYOUT_RANDOM) {
        fprintf(stderr, "mvr render: %s is for --layout random (not %s)\n",
                cli_given(p, "--seed") ? "--seed" : "--min-spacing", layout);
        return MVR_EXIT_USAGE;
    }
    bool around = l == MVR_LAYOUT_SPHERE || l == MVR_LAYOUT_RANDOM || l == MVR_LAYOUT_ORBIT;
    bool elevated = l == MVR_LAYOUT_STEREO || l == MVR_LAYOUT_RING || l == MVR_LAYOUT_GRID;
    if (cli_given(p, "--elevation") && elevated != o->elevation_single) {
        fprintf(stderr, "mvr render: --elevation %s is for --layout %s (not %s)\n",
                o->elevation_single ? "DEG" : "MIN,MAX", o->elevation_single ? "stereo, ring or grid"
                                                                           : "sphere, random or orbit", layout);
        return MVR_EXIT_USAGE;
    }
    if (cli_given(p, "--hemisphere") && !around) {
        fprintf(stderr, "mvr render: --hemisphere is for --layout sphere, random or orbit (not %s)\n", layout);
        return MVR_EXIT_USAGE;
    }
    if (l == MVR_LAYOUT_CUBE && (cli_given(p, "--fov") || cli_given(p, "--radius") || cli_given(p, "--margin"))) {
        fprintf(stderr, "mvr render: --layout cube's six 90-degree views stand at the centre: --fov, --radius and "
                        "--margin do not apply\n");
        return MVR_EXIT_USAGE;
    }
    return MVR_EXIT_OK;
}
