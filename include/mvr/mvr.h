/*
 * mvr: render glTF 2.0 scenes into many views at once on OpenGL ES 3.
 *
 * Public C API. Conventions (see docs/guide.md):
 * - opaque handles with create/destroy pairs; destroy accepts NULL;
 * - descriptor structs are read once at create time, and a zeroed descriptor
 *   means "all defaults" (every enum has 0 = default);
 * - every call that can fail returns mvr_result. A create call that fails has
 *   no object to hold its message, so it fills an optional mvr_error; a live
 *   object keeps the message of its last failure (mvr_*_last_error);
 * - the library logs through the descriptor's logger, never to stdout/stderr;
 * - no global state: two contexts never see each other.
 */
#ifndef MVR_H
#define MVR_H

/* The API by role; each header includes those it builds on. */
#include "mvr/mvr_base.h"        /* version, results, errors, logging */
#include "mvr/mvr_context.h"     /* contexts, providers, capabilities */
#include "mvr/mvr_scene.h"       /* scenes: images, materials, meshes, lights, nodes, animation, variants */
#include "mvr/mvr_views.h"       /* view sets and view cameras */
#include "mvr/mvr_environment.h" /* image-based lighting */
#include "mvr/mvr_renderer.h"    /* renderers, their paths and overrides, the render desc */
#include "mvr/mvr_target.h"      /* targets, extra outputs, readback */
#include "mvr/mvr_stats.h"       /* frame and pass stats, auto choices, programs, the frame plan */
#include "mvr/mvr_framing.h"     /* default framing and exposure, demo scenes */

#endif /* MVR_H */
