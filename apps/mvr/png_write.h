/* A minimal PNG writer (RGBA8, uncompressed deflate blocks) for the CLI until
 * image I/O through OpenImageIO lands. */
#ifndef MVR_PNG_WRITE_H
#define MVR_PNG_WRITE_H

#include <stdbool.h>
#include <stdint.h>

/* rows: height rows of width * 4 bytes; bottom_up: the first row is the
 * image's bottom (GL readback order). Returns false on an I/O error. */
bool png_write_rgba8(const char *path, const uint8_t *rgba, uint32_t width, uint32_t height, bool bottom_up);

#endif
