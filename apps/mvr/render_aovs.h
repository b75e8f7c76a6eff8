/* mvr render --outputs: each view's extra outputs (depth, distance, normals,
 * IDs, coverage) as NumPy .npy files next to its image. */
#ifndef MVR_APP_RENDER_AOVS_H
#define MVR_APP_RENDER_AOVS_H

#include <stdbool.h>
#include <stdint.h>

#include "mvr/mvr.h"

/* "depth,normal,ids" (or "all") -> mvr_target_desc.outputs bits; false with a message on stderr. */
bool render_aovs_parse(const char *list, uint32_t *out_bits);

/* One view's output from memory: DIR/<output>_VVVV.npy (or
 * <output>_VVVV_fNNNN.npy for frame >= 0, NNNN frame_digits wide) from data
 * as the GL reads it (mvr_renderer_read_output's bytes: rows bottom to top),
 * rows top to bottom in the output's own type (float32 H x W, float32
 * H x W x 3, uint32 H x W x 4). Prints nothing (any thread may call it):
 * false with the reason in why. */
bool render_aovs_write_view(const char *dir, mvr_output output, uint32_t view, int64_t frame, int frame_digits,
                            uint32_t width, uint32_t height, const void *data, char *why, size_t why_size);

/* render_aovs_write_view for every output in bits and view of the target,
 * each read with mvr_renderer_read_output (the synchronous path). */
bool render_aovs_write(const char *dir, mvr_renderer *r, mvr_target *t, uint32_t views, uint32_t width,
                       uint32_t height, uint32_t bits, int64_t frame, int frame_digits);

/* DIR/ids.json: what the IDs of --outputs ids name (nodes with their mesh,
 * meshes, materials: id and name). */
bool render_aovs_write_ids(const char *dir, const mvr_scene *scene);

#endif
