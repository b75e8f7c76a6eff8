/* Animation playback in mvr-viewer: which of the scene's animations plays,
 * the time on the file's clock (looped into the clip), playing or paused,
 * the keys that change them and the words the window title shows. The
 * scene is posed through the library (mvr_scene_apply_animation) as mvr
 * render --animation A --time T poses it, so a paused frame equals mvr
 * render's at the same time. */
#ifndef MVR_VIEWER_PLAYBACK_H
#define MVR_VIEWER_PLAYBACK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mvr/mvr.h"

/* Left / right step: one frame at 30 fps. */
#define VIEWER_PLAYBACK_STEP (1.0 / 30.0)

typedef struct viewer_playback {
    uint32_t count;              /* the scene's animations; 0: nothing plays, the rest pose shows */
    uint32_t index;              /* the animation played, or MVR_ANIMATION_ALL */
    double start, end;           /* its clip in seconds (all: the union of every clip) */
    double time;                 /* seconds on the file's clock, in [start, end) */
    bool playing;
    bool posed;                  /* the scene shows index at time (else apply poses it) */
    bool reset;                  /* another animation was picked: back to the rest pose first */
} viewer_playback;

/* Playback of a scene just opened. spec: --animation (a name, an index or
 * all, as mvr render takes it; NULL: animation 0 when the scene has any);
 * time: --time (< 0: the clip's start), wrapped into the clip; paused:
 * --paused. A scene without animations plays nothing (spec must then be
 * NULL). false, printed naming what (the file), when spec names no
 * animation of the scene. */
bool viewer_playback_open(viewer_playback *pb, const mvr_scene *scene, const char *what, const char *spec,
                          double time, bool paused);

/* A playing clip moves on dt seconds (looping); a paused one stays. */
void viewer_playback_advance(viewer_playback *pb, double dt);

/* Poses the scene for the current animation and time when they changed;
 * false (printed) when the library refuses. */
bool viewer_playback_apply(viewer_playback *pb, mvr_scene *scene);

/* The playback keys (GLFW key and mods): Space plays / pauses; Left /
 * Right step 1/30 s (with Shift a tenth of the clip) and pause; Home goes
 * to the clip's start; N the next animation, Shift+N the previous. true
 * when key was one of them (and the scene has animations). */
bool viewer_playback_key(viewer_playback *pb, const mvr_scene *scene, int key, int mods);

/* The title's part: " | animation 0 'slide' 0.533 s of 0..1 (playing)",
 * "" when the scene has no animations. */
void viewer_playback_title(const viewer_playback *pb, const mvr_scene *scene, char *buf, size_t size);

#endif
