/* mvr render --outputs: each view's extra outputs (depth, distance, normals,
 * IDs, coverage) as NumPy .npy files next to its image, and (--output-files)
 * as the images people open: 16-bit depth and ID PNGs, 8-bit masks, float
 * EXRs and one EXR of named layers per view (render_aov_images.c). */
#ifndef MVR_APP_RENDER_AOVS_H
#define MVR_APP_RENDER_AOVS_H

#include <stdbool.h>
#include <stdint.h>

#include "render_options.h"
#include "mvr/mvr.h"

/* "depth,normal,ids" (or "all") -> mvr_target_desc.outputs bits; false with a message on stderr. */
bool render_aovs_parse(const char *list, uint32_t *out_bits);

/* --output-files: which files carry the extra outputs (render_options.output_files). */
enum {
    RENDER_AOV_NPY = 1u << 0,    /* <output>_VVVV.npy, every output asked for */
    RENDER_AOV_PNG = 1u << 1,    /* depth_VVVV.png (16-bit), mask_VVVV.png (8-bit), ids_<kind>_VVVV.png
                                    (16-bit) and ids_preview_VVVV.png */
    RENDER_AOV_EXR = 1u << 2,    /* depth_VVVV.exr: float32 channel Z */
    RENDER_AOV_LAYERS = 1u << 3  /* layers_VVVV.exr: colour, depth, normal, IDs as named channels */
};
#define RENDER_AOV_FILES_DEFAULT (RENDER_AOV_NPY | RENDER_AOV_PNG)
/* "npy,png,exr,layers" -> RENDER_AOV_* bits; false with a message on stderr. */
bool render_aovs_parse_files(const char *list, uint32_t *out_bits);

/* One view's extra outputs in memory, as the GL reads them (rows bottom to top). */
typedef struct render_aov_view {
    uint32_t view;
    int64_t frame;               /* >= 0: a sequence's frame (names end _fFFFF) */
    int frame_digits;            /* of FFFF (render_output_frame_digits) */
    uint32_t width, height;
    const void *data[MVR_OUTPUT_COUNT]; /* each output of o->outputs in its own type; the others NULL */
    const uint8_t *color;        /* the view's RGBA8 display bytes (sRGB), for layers_VVVV.exr; NULL = none */
} render_aov_view;

/* Every file of o->output_files (0 = RENDER_AOV_FILES_DEFAULT) for one view
 * (DIR/<output>_VVVV.npy, <output>_VVVV_fFFFF.npy for a frame, the PNGs and
 * EXRs likewise), rows top to bottom. The .npy files hold each output in its
 * own type (float32 H x W, float32 H x W x 3, uint32 H x W x 4), coverage as
 * uint8 H x W (1 = covered). Prints nothing (any thread may call it): false
 * with the reason in why. */
bool render_aovs_write_view(const render_options *o, const render_aov_view *v, char *why, size_t why_size);

/* render_aovs_write_view for every view of the target, each output read with
 * mvr_renderer_read_output (the synchronous path); colors[k]: view k's display
 * bytes (NULL = none). */
bool render_aovs_write(const render_options *o, mvr_renderer *r, mvr_target *t, uint32_t views,
                       uint8_t *const *colors, int64_t frame, int frame_digits);

/* The header of output's h x w .npy as mvr writes it (NumPy's .npy 1.0:
 * magic, version 1 0, little-endian uint16 length, the dict padded with
 * spaces to a multiple of 64 ending in '\n'; this machine's byte order;
 * coverage as uint8) into buf; its length, 0 when size is too small. The
 * dataset passes compare the files they read back with it. */
size_t render_aovs_npy_header(char *buf, size_t size, mvr_output output, uint32_t h, uint32_t w);

/* DIR/ids.json: what the IDs of --outputs ids name (nodes with their mesh,
 * meshes, materials: id and name). */
bool render_aovs_write_ids(const char *dir, const mvr_scene *scene);

/* The scene units per step of depth_VVVV.png for these views: the farthest a
 * surface of the scene's bounds can be from any view's camera, / 65535,
 * rounded up to 1, 2 or 5 x 10^k, at least 1e-4 (1e-4 for a scene without
 * bounds). */
double render_aovs_depth_scale(const mvr_scene *scene, const mvr_view_set *views);

/* render_aov_images.c: the PNG and EXR files of one view (the .npy files are
 * render_aovs_write_view's own). */
bool render_aov_images_write(const render_options *o, const render_aov_view *v, char *why, size_t why_size);

#endif
