/* The contact sheet of --readback stream (render_stream.c) and of mvr
 * render --merge (run_merge.c, from the written views): every view's tile
 * in a grid, shrunk where the sheet would be too large. */
#ifndef MVR_APP_RENDER_SHEET_H
#define MVR_APP_RENDER_SHEET_H

#include <stdbool.h>
#include <stdint.h>

typedef struct render_sheet {
    uint8_t *pixels;             /* W x H RGBA, top row first */
    uint32_t width, height, cols, tile_w, tile_h, factor;
} render_sheet;

/* The sheet of n views of w x h (pixels opaque black); false when out of
 * memory. Free pixels with free(). */
bool render_sheet_create(render_sheet *c, uint32_t n, uint32_t w, uint32_t h);

/* View k's display bytes (w x h RGBA, rows bottom-up) into its tile. */
void render_sheet_put(render_sheet *c, uint32_t k, const uint8_t *px, uint32_t w, uint32_t h);

#endif
