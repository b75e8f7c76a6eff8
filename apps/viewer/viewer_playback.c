/* Animation playback in mvr-viewer (viewer_playback.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "cli_scene.h"
#include "viewer_playback.h"

/* t wrapped into [start, end): the library's MVR_ANIMATION_LOOP, so the
 * title shows the time the pose is sampled at. An empty clip: its start. */
static double wrap(double t, double start, double end)
{
    double length = end - start;
    if (!(length > 0.0) || !isfinite(t))
        return start;
    double r = fmod(t - start, length);
    if (r < 0.0)
        r += length;
    return start + r;
}

/* Plays animation index from its clip's start. */
static void pick(viewer_playback *pb, const mvr_scene *scene, uint32_t index)
{
    pb->index = index;
    cli_animation_clip(scene, index, &pb->start, &pb->end);
    pb->time = pb->start;
    pb->posed = false;
    pb->reset = true;
}

bool viewer_playback_open(viewer_playback *pb, const mvr_scene *scene, const char *what, const char *spec,
                          double time, bool paused)
{
    memset(pb, 0, sizeof *pb);
    pb->count = mvr_scene_animation_count(scene);
    uint32_t index = 0;
    if (spec && !cli_find_animation("mvr-viewer", what, scene, spec, &index))
        return false;
    if (pb->count == 0)
        return true; /* the rest pose; nothing to play */
    pick(pb, scene, index);
    pb->reset = false; /* a scene just loaded is at rest */
    if (time >= 0.0)
        pb->time = wrap(time, pb->start, pb->end);
    pb->playing = !paused;
    return true;
}

void viewer_playback_advance(viewer_playback *pb, double dt)
{
    if (!pb->count || !pb->playing || !(dt > 0.0))
        return;
    pb->time = wrap(pb->time + dt, pb->start, pb->end);
    pb->posed = false;
}

bool viewer_playback_apply(viewer_playback *pb, mvr_scene *scene)
{
    if (!pb->count || pb->posed)
        return true;
    if (pb->reset) /* the previous animation's nodes go back to rest */
        mvr_scene_reset_pose(scene);
    pb->reset = false;
    if (mvr_scene_apply_animation(scene, pb->index, pb->time, MVR_ANIMATION_LOOP) != MVR_OK) {
        fprintf(stderr, "mvr-viewer: animation %u at %g s: %s\n", pb->index, pb->time, mvr_scene_last_error(scene));
        return false;
    }
    pb->posed = true;
    return true;
}

bool viewer_playback_key(viewer_playback *pb, const mvr_scene *scene, int key, int mods)
{
    if (!pb->count)
        return false;
    bool shift = (mods & GLFW_MOD_SHIFT) != 0;
    double step = shift ? (pb->end - pb->start) * 0.1 : VIEWER_PLAYBACK_STEP;
    if (!(step > 0.0))
        step = VIEWER_PLAYBACK_STEP;
    switch (key) {
    case GLFW_KEY_SPACE: pb->playing = !pb->playing; return true;
    case GLFW_KEY_LEFT:
    case GLFW_KEY_RIGHT:
        pb->playing = false;
        pb->time = wrap(pb->time + (key == GLFW_KEY_LEFT ? -step : step), pb->start, pb->end);
        pb->posed = false;
        return true;
    case GLFW_KEY_HOME:
        pb->time = pb->start;
        pb->posed = false;
        return true;
    case GLFW_KEY_N: {
        /* all (when --animation all picked it) steps to 0 or the last */
        uint32_t k = pb->index == MVR_ANIMATION_ALL ? (shift ? pb->count - 1 : 0)
                     : shift                        ? (pb->index + pb->count - 1) % pb->count
                                                    : (pb->index + 1) % pb->count;
        pick(pb, scene, k);
        return true;
    }
    default: return false;
    }
}

void viewer_playback_title(const viewer_playback *pb, const mvr_scene *scene, char *buf, size_t size)
{
    if (!pb->count) {
        if (size)
            buf[0] = '\0';
        return;
    }
    char label[192];
    cli_animation_label(scene, pb->index, label, sizeof label);
    snprintf(buf, size, " | animation %s %.3f s of %g..%g (%s)", label, pb->time, pb->start, pb->end,
             pb->playing ? "playing" : "paused");
}
