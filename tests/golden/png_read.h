/* Reads the PNGs mvr's own writer produces (RGBA8, stored deflate blocks),
 * for golden images; anything else is refused with a message. */
#ifndef MVR_PNG_READ_H
#define MVR_PNG_READ_H

#include <stddef.h>
#include <stdint.h>

/* Returns malloc'd RGBA rows top to bottom, or NULL with why filled. */
uint8_t *png_read_rgba8(const char *path, uint32_t *width, uint32_t *height, char *why, size_t why_size);

#endif
