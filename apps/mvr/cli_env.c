/* Environment and background options shared by mvr render and mvr-viewer. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_env.h"
#include "commands.h"
#include "mvr/mvr_image.h"

/* A finite float, the whole string. */
static bool parse_float(const char *s, float *out)
{
    char *end = NULL;
    float f = strtof(s, &end);
    if (end == s || !end || *end || !isfinite(f))
        return false;
    *out = f;
    return true;
}

/* "uniform" or "uniform:R,G,B" (each finite and >= 0, not all 0). */
static bool parse_uniform(const char *v, float rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 1.0f;
    if (strcmp(v, "uniform") == 0)
        return true;
    if (strncmp(v, "uniform:", 8) != 0)
        return false;
    char buf[128];
    if (strlen(v + 8) >= sizeof buf)
        return false;
    strcpy(buf, v + 8);
    char *parts[3], *rest = buf;
    for (int c = 0; c < 3; ++c) {
        parts[c] = rest;
        char *comma = strchr(rest, ',');
        if ((c < 2) != (comma != NULL))
            return false;
        if (comma) {
            *comma = '\0';
            rest = comma + 1;
        }
        if (!parse_float(parts[c], &rgb[c]) || rgb[c] < 0.0f)
            return false;
    }
    return rgb[0] > 0.0f || rgb[1] > 0.0f || rgb[2] > 0.0f;
}

enum { ENV_ENV = CLI_ID_ENV, ENV_INTENSITY, ENV_ROTATION, ENV_BACKGROUND, ENV_BLUR };

const cli_option cli_env_option_table[] = {
    {CLI_OPT_STRING, ENV_ENV, "--env", NULL, "E", 0, 0, NULL,
     "image-based lighting: FILE (an equirectangular .hdr or .exr,\n"
     "linear radiance) | neutral (the built-in studio) | uniform\n"
     "(radiance 1 from everywhere; uniform:R,G,B for a colour) |\n"
     "none (default: neutral for a glTF file; none for the demos,\n"
     "closed rooms with their own lights)", NULL, NULL, NULL},
    {CLI_OPT_STRING, ENV_INTENSITY, "--env-intensity", NULL, "X", 0, 0, NULL,
     "multiplies the environment's radiance (> 0; default: 1)", NULL, NULL, NULL},
    {CLI_OPT_STRING, ENV_ROTATION, "--env-rotation", NULL, "DEG", 0, 0, NULL,
     "turns the environment about +Y (default: 0)", NULL, NULL, NULL},
    {CLI_OPT_STRING, ENV_BACKGROUND, "--background", NULL, "B", 0, 0, NULL,
     "color (--clear) | env (the environment) | blur (the\n"
     "environment blurred) (default: color)", NULL, NULL, NULL},
    {CLI_OPT_STRING, ENV_BLUR, "--background-blur", NULL, "R", 0, 0, NULL,
     "the blurred background's roughness, 0..1 (0: sharp;\n"
     "default: 0.5); implies --background blur", NULL, NULL, NULL},
    {CLI_OPT_END, 0, NULL, NULL, NULL, 0, 0, NULL, NULL, NULL, NULL, NULL},
};

int cli_env_apply(const char *command, const cli_arg *arg, cli_env_options *o)
{
    if (!arg->opt || arg->opt->id < ENV_ENV || arg->opt->id > ENV_BLUR)
        return 0;
    const int id = arg->opt->id;
    const char *v = arg->value;
    if (id == ENV_ENV) {
        if (strncmp(v, "uniform", 7) == 0 && (v[7] == '\0' || v[7] == ':')) {
            if (!parse_uniform(v, o->uniform)) {
                fprintf(stderr, "%s: --env uniform:R,G,B takes three radiances >= 0, not all 0 (got '%s')\n",
                        command, v);
                return -1;
            }
        } else if (v[0] == '\0') {
            fprintf(stderr, "%s: --env takes FILE (.hdr, .exr), neutral, uniform[:R,G,B] or none\n", command);
            return -1;
        }
        o->env = v;
    } else if (id == ENV_INTENSITY) {
        if (!parse_float(v, &o->intensity) || !(o->intensity > 0.0f)) {
            fprintf(stderr, "%s: --env-intensity takes a finite number > 0 (got '%s'; --env none turns the "
                            "environment off)\n", command, v);
            return -1;
        }
        o->intensity_set = true;
    } else if (id == ENV_ROTATION) {
        if (!parse_float(v, &o->rotation)) {
            fprintf(stderr, "%s: --env-rotation takes a finite angle in degrees (got '%s')\n", command, v);
            return -1;
        }
        o->rotation_set = true;
    } else if (id == ENV_BACKGROUND) {
        if (strcmp(v, "color") == 0)
            o->background = MVR_BACKGROUND_COLOR;
        else if (strcmp(v, "env") == 0)
            o->background = MVR_BACKGROUND_ENVIRONMENT;
        else if (strcmp(v, "blur") == 0)
            o->background = MVR_BACKGROUND_BLUR;
        else {
            fprintf(stderr, "%s: --background takes color, env or blur (got '%s')\n", command, v);
            return -1;
        }
        o->background_set = true;
    } else {
        if (!parse_float(v, &o->background_blur) || o->background_blur < 0.0f || o->background_blur > 1.0f) {
            fprintf(stderr, "%s: --background-blur takes a roughness from 0 to 1 (got '%s')\n", command, v);
            return -1;
        }
        o->blur_set = true;
    }
    return 1;
}

/* The --env the options resolve to for a file or a demo. */
static const char *env_name(const cli_env_options *o, bool scene_file)
{
    return o->env ? o->env : scene_file ? "neutral" : "none";
}

/* --background-blur alone asks for the blurred background. */
static mvr_background background_of(const cli_env_options *o)
{
    return o->blur_set && !o->background_set ? MVR_BACKGROUND_BLUR : o->background;
}

bool cli_env_check(const char *command, const cli_env_options *o, bool scene_file)
{
    bool none = strcmp(env_name(o, scene_file), "none") == 0;
    const char *why_none = o->env ? "--env is none" : "the demos have none unless --env gives one";
    if (none && (o->intensity_set || o->rotation_set)) {
        fprintf(stderr, "%s: %s needs an environment (%s)\n", command,
                o->intensity_set ? "--env-intensity" : "--env-rotation", why_none);
        return false;
    }
    if (o->blur_set && o->background_set && o->background != MVR_BACKGROUND_BLUR) {
        fprintf(stderr, "%s: --background-blur is for --background blur\n", command);
        return false;
    }
    mvr_background background = background_of(o);
    if (none && background != MVR_BACKGROUND_COLOR) {
        const char *option = !o->background_set ? "--background-blur"
                             : background == MVR_BACKGROUND_BLUR ? "--background blur" : "--background env";
        fprintf(stderr, "%s: %s needs an environment (%s)\n", command, option, why_none);
        return false;
    }
    return true;
}

int cli_env_create(const char *command, const cli_env_options *o, bool scene_file, mvr_render_desc *desc,
                   mvr_environment **env, cli_env_used *used)
{
    *env = NULL;
    cli_env_used u;
    memset(&u, 0, sizeof u);
    if (!cli_env_check(command, o, scene_file))
        return MVR_EXIT_USAGE;
    const char *name = env_name(o, scene_file);
    bool none = strcmp(name, "none") == 0;
    mvr_background background = background_of(o);
    desc->environment = NULL;
    desc->background = MVR_BACKGROUND_COLOR;
    if (none) {
        if (used)
            *used = u;
        return MVR_EXIT_OK;
    }

    mvr_environment_desc ed;
    memset(&ed, 0, sizeof ed);
    ed.intensity = o->intensity_set ? o->intensity : 1.0f;
    ed.rotation = o->rotation;
    mvr_image_data image;
    memset(&image, 0, sizeof image);
    mvr_error err;
    if (strcmp(name, "neutral") == 0) {
        ed.source = MVR_ENVIRONMENT_NEUTRAL;
    } else if (strncmp(name, "uniform", 7) == 0 && (name[7] == '\0' || name[7] == ':')) {
        ed.source = MVR_ENVIRONMENT_UNIFORM;
        memcpy(ed.color, o->uniform, sizeof ed.color);
    } else {
        /* an equirectangular image of linear radiance */
        if (mvr_image_read_within(name, MVR_PIXEL_F32, o->memory_budget, &image, &err) != MVR_OK) {
            fprintf(stderr, "%s: --env %s: %s\n", command, name, err.message);
            return MVR_EXIT_FAILURE;
        }
        ed.source = MVR_ENVIRONMENT_PIXELS;
        ed.pixels = image.pixels;
        ed.width = image.width;
        ed.height = image.height;
        u.file = name;
        u.width = image.width;
        u.height = image.height;
    }
    mvr_result r = mvr_environment_create(&ed, env, &err);
    mvr_image_free(&image);
    if (r != MVR_OK) {
        fprintf(stderr, "%s: --env %s: %s\n", command, name, err.message);
        return MVR_EXIT_FAILURE;
    }
    u.present = true;
    u.source = ed.source;
    memcpy(u.color, ed.color, sizeof u.color);
    u.intensity = mvr_environment_intensity(*env);
    u.rotation = mvr_environment_rotation(*env);
    desc->environment = *env;
    desc->background = background;
    /* roughness 0 is the sharp environment (the library's 0 means its default) */
    if (background == MVR_BACKGROUND_BLUR && o->blur_set) {
        if (o->background_blur > 0.0f)
            desc->background_blur = o->background_blur;
        else
            desc->background = MVR_BACKGROUND_ENVIRONMENT;
    }
    if (used)
        *used = u;
    return MVR_EXIT_OK;
}
