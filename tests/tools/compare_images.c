/* Test tool: compares a rectangle of image A with image B (RGB channels, as
 * stored) and fails when a channel differs by more than MAX steps of 1/255.
 * With --channels C, only those of R, G, B count (e.g. --channels r).
 * usage: compare_images A B [--crop X,Y,W,H] [--max N] [--channels rgb] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mvr/mvr_image.h"

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: compare_images A B [--crop X,Y,W,H] [--max N] [--channels rgb]\n");
        return 2;
    }
    unsigned cx = 0, cy = 0, cw = 0, ch = 0;
    int max_allowed = 0;
    const char *channels = "rgb";
    for (int i = 3; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--crop") == 0 && sscanf(argv[i + 1], "%u,%u,%u,%u", &cx, &cy, &cw, &ch) == 4)
            continue;
        if (strcmp(argv[i], "--max") == 0) {
            max_allowed = atoi(argv[i + 1]);
            continue;
        }
        if (strcmp(argv[i], "--channels") == 0) {
            channels = argv[i + 1];
            continue;
        }
        fprintf(stderr, "compare_images: bad option %s\n", argv[i]);
        return 2;
    }
    mvr_image_data a, b;
    mvr_error err;
    if (mvr_image_read(argv[1], MVR_PIXEL_U8, &a, &err) != MVR_OK ||
        mvr_image_read(argv[2], MVR_PIXEL_U8, &b, &err) != MVR_OK) {
        fprintf(stderr, "compare_images: %s\n", err.message);
        return 2;
    }
    if (cw == 0) {
        cw = a.width;
        ch = a.height;
    }
    if (cx + cw > a.width || cy + ch > a.height || cw != b.width || ch != b.height) {
        fprintf(stderr, "compare_images: crop %u,%u %ux%u of %ux%u does not match %ux%u\n", cx, cy, cw, ch, a.width,
                a.height, b.width, b.height);
        return 1;
    }
    const uint8_t *pa = a.pixels, *pb = b.pixels;
    int worst = 0;
    size_t over = 0;
    for (unsigned y = 0; y < ch; ++y)
        for (unsigned x = 0; x < cw; ++x)
            for (int c = 0; c < 3; ++c) {
                if (!strchr(channels, "rgb"[c]))
                    continue;
                int va = pa[((size_t)(cy + y) * a.width + cx + x) * 4 + (size_t)c];
                int vb = pb[((size_t)y * b.width + x) * 4 + (size_t)c];
                int d = abs(va - vb);
                worst = d > worst ? d : worst;
                over += d > max_allowed;
            }
    printf("compare_images: max difference %d/255 (allowed %d), %zu values over\n", worst, max_allowed, over);
    mvr_image_free(&a);
    mvr_image_free(&b);
    return worst <= max_allowed ? 0 : 1;
}
