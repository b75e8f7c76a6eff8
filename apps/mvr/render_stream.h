/* mvr render --readback stream (the default): any number of views in
 * chunks of GL_MAX_VIEWS_OVR views, each rendered into one target of a
 * small ring while the previous chunk's layers come back through an
 * asynchronous readback (pixel buffer objects and a fence), and encoded
 * into files on worker threads; --outputs (depth, normals, IDs ...) come
 * back the same way, one more readback per output, and are written as the
 * synchronous path writes them (render_aovs_write_view). Memory is bounded
 * by the ring, the few chunk buffers the encoders work from and the contact
 * sheet (at most 4 megapixels, 4096 a side), whatever the number of views.
 * The images (and .npy files) are the synchronous path's, byte for byte
 * (docs/guide.md says where a render of every view at once may differ:
 * shadow cascades, dithering, per-view auto exposure; a shared
 * auto-exposure is metered over every view first).
 * Only the calling thread touches GL. Messages are prefixed "mvr render". */
#ifndef MVR_APP_RENDER_STREAM_H
#define MVR_APP_RENDER_STREAM_H

#include <stdbool.h>
#include <stdint.h>

#include "mvr/mvr.h"
#include "render_options.h"

typedef struct render_stream render_stream;

/* The ring's targets and readbacks, the encoder threads and the contact
 * sheet for `views` views a frame, `frames` frames. false (printed) when any
 * of them cannot be made. */
bool render_stream_create(const render_options *o, mvr_context *ctx, mvr_renderer *r, uint32_t views,
                          uint32_t frames, render_stream **out);

/* Writes only views [first, end) of each frame, of `frames` frames (a
 * unit of a sharded run): the chunks are the whole set's, so the bytes are
 * those a run of every view writes; chunks without a view of the range are
 * not rendered. Call before the first frame. */
void render_stream_set_range(render_stream *s, uint32_t first, uint32_t end, uint32_t frames);

/* One frame of every view: frame -1 writes view_VVVV.EXT, frame >= 0
 * view_VVVV_fFFFF.EXT (render_output's names), and each output's
 * <output>_VVVV[_fFFFF].npy. sheet: this frame's views go
 * into the contact sheet. Returns before the last chunks are written;
 * false (printed) on the first failure, a worker's included. */
bool render_stream_frame(render_stream *s, mvr_scene *scene, const mvr_view_set *views, const mvr_render_desc *desc,
                         int64_t frame, bool sheet);

/* Reads and writes what is still in flight, waits for the encoders, and
 * writes the contact sheet to sheet_path (NULL: none). false (printed) on a
 * failure. */
bool render_stream_finish(render_stream *s, const char *sheet_path);

/* The last frame's stats summed over its chunks (the counters; shadow
 * layers the most of any chunk; the rest as the last chunk's). */
void render_stream_get_stats(const render_stream *s, mvr_frame_stats *out);
/* What ran: chunk, ring, encoders, sheet scale, exposure, images, time. */
void render_stream_get_info(const render_stream *s, render_readback_info *out);

/* Stops the encoders (dropping what they had not written) and frees
 * everything. NULL is ignored. */
void render_stream_destroy(render_stream *s);

#endif
