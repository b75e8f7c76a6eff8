/* The environment (image-based lighting) and background options that
 * mvr render and mvr-viewer share: parsed, checked and turned into an
 * mvr_environment and the render desc's environment fields in one place. */
#ifndef MVR_CLI_ENV_H
#define MVR_CLI_ENV_H

#include <stdbool.h>

#include "cli_options.h"
#include "mvr/mvr.h"

typedef struct cli_env_options {
    const char *env;             /* --env: FILE | neutral | uniform[:R,G,B] | none; NULL = the default */
    float uniform[3];            /* --env uniform:R,G,B (all 0 = 1, 1, 1) */
    float intensity;             /* --env-intensity (> 0); 0 = 1 */
    float rotation;              /* --env-rotation, degrees */
    mvr_background background;   /* --background (default: color) */
    float background_blur;       /* --background-blur, roughness 0..1 */
    bool intensity_set, rotation_set, background_set, blur_set;
    uint64_t memory_budget;      /* decoding the image FILE (--memory-budget); 0 = mvr_image's default */
} cli_env_options;

/* What a render used, for the stats and the summary. */
typedef struct cli_env_used {
    bool present;                /* false: --env none (no environment) */
    mvr_environment_source source;
    const char *file;            /* PIXELS: the image's path */
    uint32_t width, height;      /* PIXELS: the image's size as read */
    float color[3];              /* UNIFORM: the radiance */
    float intensity, rotation;
} cli_env_used;

/* --env, --env-intensity, --env-rotation, --background and
 * --background-blur as a table (ids CLI_ID_ENV..), for cli_parser;
 * cli_env_apply stores a parsed one. Returns 1 if arg is one of them, 0 if
 * not, -1 on a bad value (printed, prefixed with command, e.g. "mvr render"). */
extern const cli_option cli_env_option_table[];
int cli_env_apply(const char *command, const cli_arg *arg, cli_env_options *o);

/* Checks the options together for a glTF file (scene_file) or a demo: an
 * intensity, rotation or environment background without an environment,
 * --background-blur with another background. Prints what is wrong and
 * returns false. (cli_env_create checks too.) */
bool cli_env_check(const char *command, const cli_env_options *o, bool scene_file);

/* Creates the environment the options ask for, with the default for the
 * scene when --env was not given: the built-in neutral studio for a glTF
 * file (most real files ship without lights: peers light them with an
 * environment), none for a built-in demo (closed rooms lit by their own
 * lights, which an environment at infinity would light through the walls).
 * Sets desc->environment (*env, NULL for none), background and
 * background_blur; *env is the caller's to destroy after the renders.
 * Prints what failed and returns an MVR_EXIT_ code. used is optional. */
int cli_env_create(const char *command, const cli_env_options *o, bool scene_file, mvr_render_desc *desc,
                   mvr_environment **env, cli_env_used *used);

#endif
