/* mvr render's stats JSON (render_stats.c). */
#ifndef MVR_APP_RENDER_STATS_H
#define MVR_APP_RENDER_STATS_H

#include <stdint.h>
#include <stdio.h>

#include "cli_env.h"
#include "mvr/mvr.h"
#include "mvr/mvr_gltf.h"
#include "render_options.h"

/* The last frame's stats as JSON into f: the scene (demo: its name or
 * file), the glTF load (load NULL: none), the environment used, the
 * programs and passes, the animation that posed the frames, and how the
 * images came back (readback; its culled_per_view, when set, replaces the
 * renderer's). */
void render_stats_write_json(FILE *f, const mvr_renderer *r, const mvr_frame_stats *s, const char *demo,
                             uint32_t w, uint32_t h, uint32_t supersample, const mvr_gltf_info *load,
                             const cli_env_used *env, const mvr_render_desc *rd, const render_options *o,
                             const render_animation *anim, const render_readback_info *readback);

#endif
