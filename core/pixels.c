/* Pixel utilities without GL: the supersampling resolve. */
#include "core_util.h"

mvr_result mvr_downsample_rgba32f(const float *src, uint32_t width, uint32_t height, uint32_t factor, float *dst)
{
    if (!src || !dst || factor == 0 || width % factor != 0 || height % factor != 0)
        return MVR_ERROR_INVALID_ARGUMENT;
    uint32_t w = width / factor, h = height / factor;
    double scale = 1.0 / ((double)factor * factor);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            /* a box of factor x factor samples, summed in double (exact for
             * 16 float samples, whatever their order) */
            double sum[4] = {0, 0, 0, 0};
            for (uint32_t sy = 0; sy < factor; ++sy) {
                const float *row = src + ((size_t)(y * factor + sy) * width + (size_t)x * factor) * 4;
                for (uint32_t sx = 0; sx < factor * 4; ++sx)
                    sum[sx % 4] += row[sx];
            }
            float *out = dst + ((size_t)y * w + x) * 4;
            for (int c = 0; c < 4; ++c)
                out[c] = (float)(sum[c] * scale);
        }
    return MVR_OK;
}
