/* Scenes and images shared by the commands. */
#ifndef MVR_CLI_SCENE_H
#define MVR_CLI_SCENE_H

#include <stdbool.h>
#include <stddef.h>

#include "mvr/mvr.h"

#define CLI_CAMERA_IF_ANY (-2)

typedef struct cli_scene_options {
    const char *demo;            /* used when scene_file is NULL */
    const char *scene_file;      /* .gltf / .glb */
    int camera;                  /* file: view from this camera node; -1 = frame with layout;
                                    CLI_CAMERA_IF_ANY: the first camera when the file has one */
    mvr_view_layout layout;
    double ipd;                  /* 0 = mvr_stereo_default_ipd of the viewing distance */
    const mvr_framing_desc *framing; /* optional: the layout's camera sampling (fov, distance, ...);
                                        its layout, views, ipd and aspect are the fields here */
    uint32_t gltf_scene;         /* 1-based; 0 = the file's default */
    uint32_t views, width, height;
    mvr_logger logger;
    bool strict;                 /* glTF: a missing or undecodable image fails the load */
    uint64_t memory_budget;      /* glTF: the load's memory budget in bytes; 0 = the loader's default */
    struct mvr_gltf_info *gltf_info; /* optional: what the glTF load reports */
    const mvr_view_desc *given_views; /* views from a camera file (--cameras): used instead of the
                                         file's camera, a layout or the demo's own views */
    uint32_t given_view_count;
} cli_scene_options;

/* A demo or a glTF file and its views (a file's camera through
 * mvr_view_set_from_camera, a layout through mvr_view_set_frame_scene);
 * prints what failed (prefixed with command, e.g. "mvr render") and returns
 * an MVR_EXIT_ code. mvr render and mvr-viewer both load through it, so
 * they show a file alike. */
int cli_load_scene(const char *command, const cli_scene_options *o, mvr_scene **scene, mvr_view_set **views);

/* Which views a command gives a file (mvr render, mvr bench): camera node K
 * when asked for (camera >= 0); else a layout asked for, or a camera
 * file's views (-1); else the file's first camera when it has one
 * (CLI_CAMERA_IF_ANY), the default layout otherwise. The value for
 * cli_scene_options.camera. */
int cli_scene_camera_choice(bool scene_file, int camera, bool layout_set, bool camera_file);

/* The most views a demo frames at width x height (layer size; 0 = square):
 * stereo and city turn their outer frusta toward the centre, 0.9 rad per
 * metre of offset, eyes 64 mm apart, and a frustum edge must stay inside
 * 90 degrees; cube (its six faces, repeated) and ring take any count up to
 * 1024. 0 for an unknown demo. */
uint32_t cli_demo_max_views(const char *demo, uint32_t width, uint32_t height);

/* Whether views (0: the demo's own) is at most cli_demo_max_views; prints
 * the limit and why (prefixed with command) when not. */
bool cli_check_demo_views(const char *command, const char *demo, uint32_t views, uint32_t width, uint32_t height);

/* --animation NAME|K|all against a scene's animations: "all" is
 * MVR_ANIMATION_ALL, a decimal number an index (0-based), anything else a
 * name (the first animation with it). When the scene has no such animation
 * (or none at all) prints why, prefixed with command and naming what (the
 * file or demo), and lists the animations there are; false then. */
bool cli_find_animation(const char *command, const char *what, const mvr_scene *scene, const char *spec,
                        uint32_t *out);

/* The clip of animation index in the file's seconds: its first and last
 * key; MVR_ANIMATION_ALL: from the earliest start to the latest end of all.
 * false (0, 0) when there is no such animation. */
bool cli_animation_clip(const mvr_scene *scene, uint32_t index, double *start, double *end);

/* "1 'walk'", "1 (unnamed)", or "all 3" for MVR_ANIMATION_ALL. */
void cli_animation_label(const mvr_scene *scene, uint32_t index, char *buf, size_t size);

/* --variant NAME|K against a scene's material variants: a name (the first
 * variant with it), else a decimal number as an index (0-based). When the
 * scene has no such variant (or none at all) prints why, prefixed with
 * command and naming what (the file), and lists the variants there are;
 * false then. */
bool cli_find_variant(const char *command, const char *what, const mvr_scene *scene, const char *spec,
                      uint32_t *out);

/* "1 'blue'" (the variant's index and name), or "default" for MVR_VARIANT_DEFAULT. */
void cli_variant_label(const mvr_scene *scene, uint32_t index, char *buf, size_t size);

/* The render desc mvr render and mvr-viewer start from: an opaque dark sky
 * as the clear colour, exposure 1; everything else the library's default. */
void cli_render_desc_defaults(mvr_render_desc *desc);

/* Exact sRGB encode of linear RGBA floats (alpha kept linear) into bytes. */
void cli_encode_srgb(const float *in, uint8_t *out, size_t pixels);

/* Reads a layer as display bytes (w x h RGBA8, sRGB-encoded). A target of
 * ss x ss samples per pixel (RGBA32F, ss > 1) is resolved with a box filter
 * in linear light first. linear (optional, w x h x 4 floats) receives the
 * linear values. */
bool cli_read_display_layer(mvr_renderer *r, mvr_target *t, uint32_t layer, uint32_t w, uint32_t h, uint32_t ss,
                            uint8_t *out, float *linear);

#endif
