/* The contact sheet (render_sheet.h). */
#include "render_sheet.h"

#include <stdlib.h>
#include <string.h>

#define SHEET_MAX 4096           /* contact sheet side, pixels */
#define SHEET_PIXELS (2048u * 2048u) /* and area: 16 MiB */

/* The synchronous path's layout (render_output_write_contact_sheet): side
 * by side up to 4 views, then about square, 4 pixels apart; tiles shrunk
 * by the smallest integer factor that keeps the sheet within SHEET_MAX on
 * each side and SHEET_PIXELS in all (1 = full size, the same image as the
 * synchronous path's). */
bool render_sheet_create(render_sheet *c, uint32_t n, uint32_t w, uint32_t h)
{
    uint32_t cols = n <= 4 ? n : 1;
    while (n > 4 && cols * cols < n)
        cols++;
    uint32_t rows = (n + cols - 1) / cols, gap = 4;
    uint32_t f = 1;
    for (;; ++f) {
        uint32_t tw = w / f ? w / f : 1, th = h / f ? h / f : 1;
        uint64_t W = (uint64_t)cols * tw + (cols - 1) * gap, H = (uint64_t)rows * th + (rows - 1) * gap;
        if ((W <= SHEET_MAX && H <= SHEET_MAX && W * H <= SHEET_PIXELS) || (tw == 1 && th == 1)) {
            c->tile_w = tw;
            c->tile_h = th;
            c->width = (uint32_t)W;
            c->height = (uint32_t)H;
            break;
        }
    }
    c->factor = f;
    c->cols = cols;
    c->pixels = calloc((size_t)c->width * c->height, 4);
    if (!c->pixels)
        return false;
    for (size_t i = 0; i < (size_t)c->width * c->height; ++i)
        c->pixels[i * 4 + 3] = 255;
    return true;
}

/* View k's display bytes (w x h, rows bottom-up) into its tile: each tile
 * pixel the rounded mean of its factor x factor pixels. Tiles do not
 * overlap, so encoders put theirs at once without a lock. */
void render_sheet_put(render_sheet *c, uint32_t k, const uint8_t *px, uint32_t w, uint32_t h)
{
    uint32_t f = c->factor, gap = 4;
    uint32_t cx = (k % c->cols) * (c->tile_w + gap), cy = (k / c->cols) * (c->tile_h + gap);
    for (uint32_t y = 0; y < c->tile_h; ++y) {
        uint8_t *dst = c->pixels + ((size_t)(cy + y) * c->width + cx) * 4;
        if (f == 1) {
            memcpy(dst, px + (size_t)(h - 1 - y) * w * 4, (size_t)w * 4);
            continue;
        }
        for (uint32_t x = 0; x < c->tile_w; ++x)
            for (uint32_t ch = 0; ch < 4; ++ch) {
                uint32_t sum = 0, count = 0;
                for (uint32_t j = 0; j < f && y * f + j < h; ++j)
                    for (uint32_t i = 0; i < f && x * f + i < w; ++i, ++count)
                        sum += px[((size_t)(h - 1 - (y * f + j)) * w + x * f + i) * 4 + ch];
                dst[x * 4 + ch] = (uint8_t)(count ? (sum + count / 2) / count : 0);
            }
    }
}
