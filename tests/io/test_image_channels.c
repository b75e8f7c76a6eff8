/* mvr_image_write_channels: a 16-bit gray PNG keeps its values (read back
 * through mvr_image_read, which scales 16 to 8 bits as (v * 255 + 32767) /
 * 65535), and hostile descriptions are refused with a message naming the
 * file, never written: a PNG of two channels or of floats, repeated or empty
 * EXR names, a row stride that holds no row, an unknown type, 0 or 65
 * channels, a name without .png / .exr. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mvr/mvr_image.h"

static int failures;

static void expect(int ok, const char *what)
{
    if (!ok) {
        failures++;
        printf("FAIL: %s\n", what);
    }
}

/* The call is refused as an invalid argument, its message names the file, and no file is left. */
static void refused(const char *path, const mvr_image_channels *image, const char *what)
{
    remove(path);
    mvr_error err;
    mvr_result r = mvr_image_write_channels(path, image, &err);
    FILE *f = fopen(path, "rb");
    expect(r == MVR_ERROR_INVALID_ARGUMENT && strstr(err.message, path) != NULL && !f, what);
    if (f)
        fclose(f);
}

int main(void)
{
    enum { W = 5, H = 3 };
    uint16_t gray[W * H];
    for (int i = 0; i < W * H; ++i)
        gray[i] = (uint16_t)(i * 4369); /* 0 .. 61166 */
    const char *png = "image_channels.png", *exr = "image_channels.exr";
    mvr_image_channel c = {NULL, MVR_CHANNEL_U16, gray, 2, W * 2};
    mvr_image_channels one = {W, H, false, 1, &c};
    mvr_error err;
    expect(mvr_image_write_channels(png, &one, &err) == MVR_OK, "a 16-bit gray PNG is written");
    mvr_image_data back = {0};
    if (mvr_image_read(png, MVR_PIXEL_U8, &back, &err) == MVR_OK) {
        int same = back.width == W && back.height == H;
        for (int i = 0; same && i < W * H; ++i)
            same = ((uint8_t *)back.pixels)[4 * i] == (uint8_t)(((uint32_t)gray[i] * 255u + 32767u) / 65535u);
        expect(same, "the PNG reads back as its values scaled to 8 bits");
        mvr_image_free(&back);
    } else {
        expect(0, err.message);
    }

    mvr_image_channel two[2] = {c, c};
    mvr_image_channels pair = {W, H, false, 2, two};
    refused(png, &pair, "a PNG of two channels");
    mvr_image_channel f = {"Z", MVR_CHANNEL_F32, gray, 4, W * 4};
    mvr_image_channels floats = {W, H, false, 1, &f};
    refused(png, &floats, "a PNG of floats");
    two[0].name = two[1].name = "Z";
    refused(exr, &pair, "an EXR with a repeated channel name");
    two[0].name = "";
    refused(exr, &pair, "an EXR channel without a name");
    mvr_image_channel short_rows = {"Y", MVR_CHANNEL_U16, gray, 2, W * 2 - 1};
    mvr_image_channels s = {W, H, false, 1, &short_rows};
    refused(png, &s, "a row stride that holds no row");
    mvr_image_channel unknown = {"Y", (mvr_channel_type)99, gray, 2, W * 2};
    mvr_image_channels u = {W, H, false, 1, &unknown};
    refused(exr, &u, "an unknown channel type");
    mvr_image_channels none = {W, H, false, 0, &c};
    refused(png, &none, "no channels");
    mvr_image_channel many[65];
    for (int k = 0; k < 65; ++k)
        many[k] = c;
    mvr_image_channels too_many = {W, H, false, 65, many};
    refused(exr, &too_many, "65 channels");
    refused("image_channels.tif", &one, "a name without .png or .exr");
    remove(png);
    printf("%d passed, %d failed\n", failures ? 0 : 1, failures ? 1 : 0);
    return failures ? 1 : 0;
}
