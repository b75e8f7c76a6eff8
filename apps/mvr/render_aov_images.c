/* mvr render --output-files png,exr,layers: a view's extra outputs as the
 * images other tools open (render_aovs.h lists the files).
 * OpenEXR's channel names (openexr.com, "Technical Introduction", Channel
 * Names and Layers): R, G, B, A for colour, Z for depth (the distance along
 * the camera's viewing direction), and a layer as a name prefix ending in a
 * period ("N.X"); channels of any name may be stored, each in its own pixel
 * type (HALF, FLOAT or UINT, the last for exact 32-bit IDs). */
#include "render_aovs.h"

#include "mvr/mvr_image.h"
#include "render_output.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The kinds of ID, the channels of MVR_OUTPUT_IDS in order. */
static const char *const id_kinds[4] = {"node", "mesh", "material", "primitive"};

/* DIR/<name>_VVVV.<ext>, or ..._VVVV_fFFFF.<ext> for a frame; false when --out is too long. */
static bool aov_path(char *buf, size_t size, const render_options *o, const render_aov_view *v, const char *name,
                     const char *ext)
{
    return render_output_file_name(buf, size, o->out_dir, name, v->view, v->frame, v->frame_digits, ext);
}

/* One channel of one type into DIR/<name>_VVVV.<ext> (rows bottom to top in memory). */
static bool write_channels(const render_options *o, const render_aov_view *v, const char *name, const char *ext,
                           const mvr_image_channel *channels, uint32_t count, char *why, size_t why_size)
{
    char path[4096];
    if (!aov_path(path, sizeof path, o, v, name, ext)) {
        snprintf(why, why_size, "--out is too long");
        return false;
    }
    mvr_image_channels image = {v->width, v->height, true, count, channels};
    mvr_error err;
    if (mvr_image_write_channels(path, &image, &err) != MVR_OK) {
        snprintf(why, why_size, "cannot write %s: %s", path, err.message);
        return false;
    }
    return true;
}

/* An sRGB-encoded byte as a linear value (IEC 61966-2-1's decoding). */
static float srgb_to_linear(uint8_t byte)
{
    double c = byte / 255.0;
    return (float)(c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4));
}

/* A 16-bit depth step: round(depth / scale); 0 = no surface (depth 0, or
 * not a number), at least 1 where a surface is, 65535 = that far or farther. */
static uint16_t depth_step(float depth, double scale)
{
    if (!(depth > 0.0f))
        return 0;
    double steps = floor((double)depth / scale + 0.5);
    return steps >= 65535.0 ? 65535 : steps < 1.0 ? 1 : (uint16_t)steps;
}

/* Whether pixel i is covered, by whichever of coverage, depth and IDs is there. */
static bool covered(const render_aov_view *v, size_t i)
{
    const float *cov = v->data[MVR_OUTPUT_COVERAGE], *depth = v->data[MVR_OUTPUT_DEPTH];
    const uint32_t *ids = v->data[MVR_OUTPUT_IDS];
    return (cov && cov[i] > 0.0f) || (depth && depth[i] > 0.0f) || (ids && ids[4 * i] != 0);
}

/* A stable colour for an ID (0: black): MurmurHash3's 32-bit finaliser
 * (fmix32) of the id, each byte lifted into 64..255 so no id is near black. */
static void id_colour(uint32_t id, uint8_t rgba[4])
{
    uint32_t h = id;
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    h *= 0xC2B2AE35u;
    h ^= h >> 16;
    for (int c = 0; c < 3; ++c)
        rgba[c] = id ? (uint8_t)(64u + ((h >> (8 * c)) & 0xFFu) * 191u / 255u) : 0;
    rgba[3] = 255;
}

/* ids_<kind>_VVVV.png (the low 16 bits) for each kind, and ids_<kind>_hi_VVVV.png
 * (the high 16 bits) for a kind whose ids in this view pass 65535, then the
 * node ids' preview ids_preview_VVVV.png. buf holds pixels * 4 bytes. */
static bool write_id_pngs(const render_options *o, const render_aov_view *v, uint8_t *buf, char *why,
                          size_t why_size)
{
    size_t pixels = (size_t)v->width * v->height;
    const uint32_t *ids = v->data[MVR_OUTPUT_IDS];
    uint16_t *steps = (uint16_t *)buf;
    for (int kind = 0; kind < 4; ++kind) {
        uint32_t most = 0;
        for (size_t i = 0; i < pixels; ++i) {
            uint32_t id = ids[4 * i + (size_t)kind];
            steps[i] = (uint16_t)(id & 0xFFFFu);
            most = id > most ? id : most;
        }
        char name[48];
        snprintf(name, sizeof name, "ids_%s", id_kinds[kind]);
        mvr_image_channel c = {NULL, MVR_CHANNEL_U16, steps, 2, (size_t)v->width * 2};
        if (!write_channels(o, v, name, "png", &c, 1, why, why_size))
            return false;
        if (most <= 0xFFFFu)
            continue;
        for (size_t i = 0; i < pixels; ++i)
            steps[i] = (uint16_t)(ids[4 * i + (size_t)kind] >> 16);
        snprintf(name, sizeof name, "ids_%s_hi", id_kinds[kind]);
        if (!write_channels(o, v, name, "png", &c, 1, why, why_size))
            return false;
    }
    for (size_t i = 0; i < pixels; ++i)
        id_colour(ids[4 * i], buf + 4 * i);
    char path[4096];
    if (!aov_path(path, sizeof path, o, v, "ids_preview", "png")) {
        snprintf(why, why_size, "--out is too long");
        return false;
    }
    mvr_image_view preview = {v->width, v->height, MVR_PIXEL_U8, true, buf};
    mvr_error err;
    if (mvr_image_write(path, &preview, &err) != MVR_OK) {
        snprintf(why, why_size, "cannot write %s: %s", path, err.message);
        return false;
    }
    return true;
}

/* depth_VVVV.png, mask_VVVV.png, the ID PNGs. */
static bool write_pngs(const render_options *o, const render_aov_view *v, uint8_t *buf, char *why, size_t why_size)
{
    size_t pixels = (size_t)v->width * v->height;
    const float *depth = v->data[MVR_OUTPUT_DEPTH];
    if (depth) {
        if (!(o->depth_png_scale > 0.0)) {
            snprintf(why, why_size, "depth_%04u.png: the depth scale was not set", v->view);
            return false;
        }
        uint16_t *steps = (uint16_t *)buf;
        for (size_t i = 0; i < pixels; ++i)
            steps[i] = depth_step(depth[i], o->depth_png_scale);
        mvr_image_channel c = {NULL, MVR_CHANNEL_U16, steps, 2, (size_t)v->width * 2};
        if (!write_channels(o, v, "depth", "png", &c, 1, why, why_size))
            return false;
    }
    if (depth || v->data[MVR_OUTPUT_COVERAGE] || v->data[MVR_OUTPUT_IDS]) {
        for (size_t i = 0; i < pixels; ++i)
            buf[i] = covered(v, i) ? 255 : 0;
        mvr_image_channel c = {NULL, MVR_CHANNEL_U8, buf, 1, v->width};
        if (!write_channels(o, v, "mask", "png", &c, 1, why, why_size))
            return false;
    }
    return !v->data[MVR_OUTPUT_IDS] || write_id_pngs(o, v, buf, why, why_size);
}

/* layers_VVVV.exr: R G B A (half, linear: the display bytes sRGB-decoded),
 * Z (float), N.X N.Y N.Z (float), id.node id.mesh id.material id.primitive
 * (uint), each where it was asked for. buf holds pixels * 16 bytes. */
static bool write_layers(const render_options *o, const render_aov_view *v, uint8_t *buf, char *why,
                         size_t why_size)
{
    mvr_image_channel ch[12];
    uint32_t n = 0;
    size_t w = v->width;
    if (v->color) {
        float *linear = (float *)buf;
        size_t values = (size_t)v->width * v->height * 4;
        for (size_t i = 0; i < values; ++i)
            linear[i] = i % 4 == 3 ? (float)v->color[i] / 255.0f : srgb_to_linear(v->color[i]);
        static const char *const rgba[4] = {"R", "G", "B", "A"};
        for (int c = 0; c < 4; ++c)
            ch[n++] = (mvr_image_channel){rgba[c], MVR_CHANNEL_F16, linear + c, 16, w * 16};
    }
    if (v->data[MVR_OUTPUT_DEPTH])
        ch[n++] = (mvr_image_channel){"Z", MVR_CHANNEL_F32, v->data[MVR_OUTPUT_DEPTH], 4, w * 4};
    static const char *const normal[3] = {"N.X", "N.Y", "N.Z"};
    for (int c = 0; v->data[MVR_OUTPUT_NORMAL] && c < 3; ++c)
        ch[n++] = (mvr_image_channel){normal[c], MVR_CHANNEL_F32, (const float *)v->data[MVR_OUTPUT_NORMAL] + c, 12,
                                      w * 12};
    static const char *const id_names[4] = {"id.node", "id.mesh", "id.material", "id.primitive"};
    for (int c = 0; v->data[MVR_OUTPUT_IDS] && c < 4; ++c)
        ch[n++] = (mvr_image_channel){id_names[c], MVR_CHANNEL_U32, (const uint32_t *)v->data[MVR_OUTPUT_IDS] + c,
                                      16, w * 16};
    return n == 0 || write_channels(o, v, "layers", "exr", ch, n, why, why_size);
}

bool render_aov_images_write(const render_options *o, const render_aov_view *v, char *why, size_t why_size)
{
    uint32_t files = o->output_files ? o->output_files : RENDER_AOV_FILES_DEFAULT;
    if (!(files & (RENDER_AOV_PNG | RENDER_AOV_EXR | RENDER_AOV_LAYERS)))
        return true;
    uint8_t *buf = malloc((size_t)v->width * v->height * 16);
    if (!buf) {
        snprintf(why, why_size, "view %u: out of memory for its output images", v->view);
        return false;
    }
    bool ok = !(files & RENDER_AOV_PNG) || write_pngs(o, v, buf, why, why_size);
    if (ok && (files & RENDER_AOV_EXR) && v->data[MVR_OUTPUT_DEPTH]) {
        mvr_image_channel z = {"Z", MVR_CHANNEL_F32, v->data[MVR_OUTPUT_DEPTH], 4, (size_t)v->width * 4};
        ok = write_channels(o, v, "depth", "exr", &z, 1, why, why_size);
    }
    if (ok && (files & RENDER_AOV_LAYERS))
        ok = write_layers(o, v, buf, why, why_size);
    free(buf);
    return ok;
}

double render_aovs_depth_scale(const mvr_scene *scene, const mvr_view_set *views)
{
    mvr_scene_info info;
    mvr_scene_get_info(scene, &info);
    double farthest = 0.0;
    uint32_t n = mvr_view_set_count(views);
    for (uint32_t k = 0; k < n; ++k) {
        mvr_view_desc d;
        if (mvr_view_set_get_view(views, k, &d) != MVR_OK)
            continue;
        /* distance is convex, so its largest over the box is at a corner */
        for (int corner = 0; corner < 8; ++corner) {
            double sum = 0.0;
            for (int a = 0; a < 3; ++a) {
                double c = (corner >> a) & 1 ? info.bounds_max[a] : info.bounds_min[a];
                sum += (c - d.position[a]) * (c - d.position[a]);
            }
            farthest = sqrt(sum) > farthest ? sqrt(sum) : farthest;
        }
    }
    double raw = farthest / 65535.0;
    if (!isfinite(raw) || raw <= 1e-4)
        return 1e-4;
    double decade = pow(10.0, floor(log10(raw)));
    static const double tidy[4] = {1.0, 2.0, 5.0, 10.0};
    for (int m = 0; m < 4; ++m)
        if (tidy[m] * decade >= raw * (1.0 - 1e-12))
            return tidy[m] * decade;
    return 10.0 * decade;
}
