/* What mvr render writes (render_output.c): the frame sequence's animation,
 * each view's image per frame, the contact sheet, the videos and the
 * summary lines about them (the stats JSON: render_stats.h). Messages are
 * prefixed "mvr render". */
#ifndef MVR_APP_RENDER_OUTPUT_H
#define MVR_APP_RENDER_OUTPUT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "cli_env.h"
#include "mvr/mvr.h"
#include "mvr/mvr_gltf.h"
#include "render_options.h"

/* Which animation poses the frames: --animation, else animation 0 when
 * --time, --loop or --frames ask for a time and the file has one; none (the
 * file's rest pose) otherwise. false (printed) when --animation names none
 * the file has. */
bool render_output_choose_animation(const render_options *o, const mvr_scene *scene, render_animation *a);

/* Reads every layer as display bytes into layers[k] (and, for EXR, the
 * linear values into floats) and writes each view's image of the frame:
 * DIR/view_VVVV.EXT, or with frame >= 0 DIR/view_VVVV_fFFFF.EXT (frame -1: not
 * a sequence). */
bool render_output_write_views(const render_options *o, mvr_renderer *r, mvr_target *t, uint32_t n, uint8_t **layers,
                               float *floats, int64_t frame);

/* The file of view `view` of frame `frame` (-1: not a sequence):
 * DIR/view_VVVV.EXT or DIR/view_VVVV_fFFFF.EXT ("" when it does not fit). */
void render_output_view_file(char *buf, size_t size, const render_options *o, uint32_t view, int64_t frame);
/* Every per-view file's name: DIR/PREFIX_VVVV.EXT (VVVV 4 digits: names sort
 * in view order up to mvr's 1024 views), or a sequence's frame f:
 * DIR/PREFIX_VVVV_fFFFF.EXT (FFFF frame_digits wide); dir NULL: the name
 * alone. false (buf "") when it does not fit. */
bool render_output_file_name(char *buf, size_t size, const char *dir, const char *prefix, uint32_t view,
                             int64_t frame, int frame_digits, const char *ext);

/* Lays the n bottom-up w x h layers out in a grid (side by side up to 4,
 * then ~square) and writes them to path as one image. */
bool render_output_write_contact_sheet(const char *path, uint8_t *const *layers, uint32_t n, uint32_t w, uint32_t h);

/* --video: each of the n views' PNG sequence through o->ffmpeg at --fps;
 * odd sizes padded to even ones, yuv420p as players expect. */
bool render_output_encode_videos(const render_options *o, uint32_t n);

/* The first executable name in the directories of $PATH, into buf (size
 * bytes); false (buf "") when there is none. */
bool render_output_find_on_path(const char *name, char *buf, size_t size);

/* The summary's line on how the images came back: the path, and images
 * written per second from the first render to the last file. */
void render_output_print_readback(const render_readback_info *readback);

/* The summary's lines for the first and the last frame's pose and the last
 * frame's skinning (none when nothing was posed or skinned). */
void render_output_print_animation(const render_options *o, const mvr_scene *scene, const render_animation *a,
                                   const mvr_frame_stats *s);

/* The summary's lines naming what was written for n views: the first and
 * the last image, the contact sheet (sheet) and the videos. */
void render_output_print_files(const render_options *o, uint32_t n, const char *sheet);

/* The views' camera metadata next to the images (the first frame's poses):
 * cameras.json (mvr_view_set_get_camera's, conventions stated in it);
 * transforms.json and COLMAP's model are dataset.h's. */
bool render_output_write_cameras(const render_options *o, const mvr_view_set *views, uint32_t n);

/* Digits of a sequence's frame numbers (view_0000_fNNNN.png). */
int render_output_frame_digits(uint32_t frames);

#endif
