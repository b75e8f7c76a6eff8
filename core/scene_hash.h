/* A fingerprint of a scene's content (what auto's remembered choices are
 * keyed by, gl/tuning.c): counts, every primitive's geometry, the images'
 * hashes and sizes, the materials' factors. Two loads of the same file give
 * the same value; an edit that changes what is drawn almost surely another. */
#ifndef MVR_SCENE_HASH_H
#define MVR_SCENE_HASH_H

#include <stdint.h>

#include "mvr/mvr.h"

uint64_t mvr_scene_content_hash(const mvr_scene *scene);

#endif
