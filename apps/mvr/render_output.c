/* What mvr render writes and the frame sequence it writes: which animation
 * poses the frames, each view's image per frame (view_VVVV.png or
 * view_VVVV_fFFFF.png), the contact sheet, the videos through ffmpeg and
 * the summary's animation and file lines (the stats JSON is
 * render_stats.c's). */
#define _POSIX_C_SOURCE 200809L
#include "render_output.h"

#include <errno.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_scene.h"
#include "cli_write.h"
#include "json.h"
#include "mvr/mvr_image.h"

/* The first and the last frame's pose, and the last frame's skinning. */
void render_output_print_animation(const render_options *o, const mvr_scene *scene, const render_animation *a,
                                   const mvr_frame_stats *s)
{
    if (a->applied) {
        printf("  animation   %s: clip %g .. %g s, ", a->label, a->start, a->end);
        if (o->frames_set && o->frames > 1)
            printf("t = %g .. %g s (%u frames at %g fps)", a->first_time, a->last_time, o->frames, o->fps);
        else
            printf("t = %g s", a->first_time);
        printf(", %s\n", o->loop ? "looped" : "clamped");
    }
    mvr_scene_info info;
    mvr_scene_get_info(scene, &info);
    if (info.skins || info.morph_targets || s->joints || s->morph_targets_active)
        printf("  skinning    %s: %u joint%s, %u morph target%s active, %llu bytes of joints and weights, %u pre-skin "
               "pass%s\n",
               mvr_skinning_path_name(s->skinning_path), s->joints, s->joints == 1 ? "" : "s",
               s->morph_targets_active, s->morph_targets_active == 1 ? "" : "s",
               (unsigned long long)s->animation_upload_bytes, s->preskin_passes, s->preskin_passes == 1 ? "" : "es");
}

void render_output_print_readback(const render_readback_info *rb)
{
    double rate = rb->seconds > 0 ? (double)rb->images / rb->seconds : 0.0;
    if (rb->mode == RENDER_READBACK_STREAM) {
        printf("  readback    stream: chunks of %u view%s through %u target%s, %u encoder thread%s; %llu images in "
               "%.2f s (%.1f views/s)\n",
               rb->chunk, rb->chunk == 1 ? "" : "s", rb->ring, rb->ring == 1 ? "" : "s", rb->encoders,
               rb->encoders == 1 ? "" : "s",
               (unsigned long long)rb->images, rb->seconds, rate);
        if (rb->sheet_factor > 1)
            printf("  contact     tiles at 1/%u of the views' size (the sheet stays within 4 megapixels)\n",
                   rb->sheet_factor);
        if (rb->exposure_metered)
            printf("  exposure    metered over every view first: EV100 %.2f for all of them\n", rb->exposure_ev100);
        if (rb->shadows_per_chunk)
            printf("  shadows     directional cascades fitted to each chunk's views (--readback sync: to the "
                   "first 64 views)\n");
    } else {
        printf("  readback    sync: every view in one target, read and written in turn; %llu images in %.2f s "
               "(%.1f views/s)\n",
               (unsigned long long)rb->images, rb->seconds, rate);
    }
}

/* Lays the views out in a grid (side by side up to 4, then ~square). */
bool render_output_write_contact_sheet(const char *path, uint8_t *const *layers, uint32_t n, uint32_t w, uint32_t h)
{
    uint32_t cols = n <= 4 ? n : 1;
    while (n > 4 && cols * cols < n)
        cols++;
    uint32_t rows = (n + cols - 1) / cols;
    uint32_t gap = 4, W = cols * w + (cols - 1) * gap, H = rows * h + (rows - 1) * gap;
    uint8_t *sheet = calloc((size_t)W * H, 4);
    if (!sheet)
        return false;
    for (size_t i = 0; i < (size_t)W * H; ++i)
        sheet[i * 4 + 3] = 255;
    for (uint32_t k = 0; k < n; ++k) {
        uint32_t cx = (k % cols) * (w + gap), cy = (k / cols) * (h + gap); /* from the top */
        for (uint32_t y = 0; y < h; ++y) {
            /* layers are bottom-up; the sheet is written top-down */
            const uint8_t *src = layers[k] + (size_t)(h - 1 - y) * w * 4;
            memcpy(sheet + ((size_t)(cy + y) * W + cx) * 4, src, (size_t)w * 4);
        }
    }
    mvr_image_view view = {W, H, MVR_PIXEL_U8, false, sheet};
    mvr_error err;
    bool ok = mvr_image_write(path, &view, &err) == MVR_OK;
    if (!ok)
        fprintf(stderr, "mvr render: %s\n", err.message);
    free(sheet);
    return ok;
}

/* Which animation poses the frames: --animation, else animation 0 when
 * --time, --loop or --frames ask for a time and the file has one; none (the
 * file's rest pose) otherwise. false (printed) when --animation names none
 * the file has. */
bool render_output_choose_animation(const render_options *o, const mvr_scene *scene, render_animation *a)
{
    memset(a, 0, sizeof *a);
    a->first_time = a->last_time = o->time;
    const char *what = o->scene_file ? o->scene_file : o->demo;
    if (o->animation) {
        if (!cli_find_animation("mvr render", what, scene, o->animation, &a->index))
            return false;
        a->applied = true;
    } else if (o->time_set || o->loop || o->frames_set) {
        a->applied = mvr_scene_animation_count(scene) > 0;
        if (!a->applied && (o->time_set || o->loop) && !o->quiet)
            fprintf(stderr, "mvr render: warning: %s has no animations: --time and --loop change nothing\n", what);
    }
    if (a->applied) {
        cli_animation_label(scene, a->index, a->label, sizeof a->label);
        cli_animation_clip(scene, a->index, &a->start, &a->end);
    }
    return true;
}

/* Digits of a sequence's frame numbers: 4, more past 10000 frames. */
int render_output_frame_digits(uint32_t frames)
{
    int digits = 4;
    for (uint32_t last = frames - 1; last >= 10000; last /= 10)
        digits++;
    return digits;
}

bool render_output_file_name(char *buf, size_t size, const char *dir, const char *prefix, uint32_t view,
                             int64_t frame, int frame_digits, const char *ext)
{
    const char *slash = dir ? "/" : "";
    dir = dir ? dir : "";
    int len = frame < 0 ? snprintf(buf, size, "%s%s%s_%04u.%s", dir, slash, prefix, view, ext)
                        : snprintf(buf, size, "%s%s%s_%04u_f%0*lld.%s", dir, slash, prefix, view, frame_digits,
                                   (long long)frame, ext);
    if (len < 0 || (size_t)len >= size) {
        buf[0] = '\0'; /* --out too long: the write fails, naming no file */
        return false;
    }
    return true;
}

/* DIR/view_VVVV.EXT, or frame f of a sequence: DIR/view_VVVV_fFFFF.EXT. */
void render_output_view_file(char *buf, size_t size, const render_options *o, uint32_t view, int64_t frame)
{
    render_output_file_name(buf, size, o->out_dir, "view", view, frame, render_output_frame_digits(o->frames),
                            o->exr ? "exr" : "png");
}

/* Reads every layer as display bytes into layers[k] and writes each view's
 * image of the frame (-1: not a sequence). */
bool render_output_write_views(const render_options *o, mvr_renderer *r, mvr_target *t, uint32_t n, uint8_t **layers,
                               float *floats, int64_t frame)
{
    size_t pixels = (size_t)o->width * o->height;
    uint32_t ss = o->supersample;
    for (uint32_t k = 0; k < n; ++k) {
        if (!cli_read_display_layer(r, t, k, o->width, o->height, ss, layers[k], floats)) {
            fprintf(stderr, "mvr render: reading layer %u: %s\n", k, mvr_renderer_last_error(r));
            return false;
        }
        if (o->exr && ss <= 1 && o->format == MVR_COLOR_FORMAT_RGBA16F)
            cli_encode_srgb(floats, layers[k], pixels); /* the sheet shows display values */
        char path[4096];
        render_output_view_file(path, sizeof path, o, k, frame);
        mvr_image_view view = {o->width, o->height, o->exr ? MVR_PIXEL_F32 : MVR_PIXEL_U8, true,
                               o->exr ? (const void *)floats : (const void *)layers[k]};
        mvr_error err;
        if (mvr_image_write(path, &view, &err) != MVR_OK) {
            fprintf(stderr, "mvr render: %s\n", err.message);
            return false;
        }
    }
    return true;
}

/* --video FILE: FILE itself for one view, else FILE's stem + _view_VVVV +
 * its extension. */
static void video_file(char *buf, size_t size, const char *video, uint32_t view, uint32_t views)
{
    const char *slash = strrchr(video, '/'), *dot = strrchr(video, '.');
    if (dot && (dot == video || (slash && dot <= slash + 1)))
        dot = NULL; /* a dot in a directory's name, or a hidden file's */
    if (views == 1)
        snprintf(buf, size, "%s", video);
    else
        snprintf(buf, size, "%.*s_view_%04u%s", dot ? (int)(dot - video) : (int)strlen(video), video, view,
                 dot ? dot : "");
}

extern char **environ;

/* Each view's PNG sequence through ffmpeg (found by parse) at --fps; odd
 * sizes padded to even ones, yuv420p as players expect. */
bool render_output_encode_videos(const render_options *o, uint32_t n)
{
    char rate[32], dir[4096], input[4096 + 64], output[4096];
    snprintf(rate, sizeof rate, "%.10g", o->fps);
    /* the input is a pattern: a % in --out's name is written %% */
    size_t d = 0;
    for (const char *c = o->out_dir; *c && d + 2 < sizeof dir; ++c) {
        if (*c == '%')
            dir[d++] = '%';
        dir[d++] = *c;
    }
    dir[d] = '\0';
    for (uint32_t k = 0; k < n; ++k) {
        snprintf(input, sizeof input, "%s/view_%04u_f%%0%dd.png", dir, k, render_output_frame_digits(o->frames));
        video_file(output, sizeof output, o->video, k, n);
        char *args[] = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", "-y", "-framerate", rate,
                        "-start_number", "0", "-i", input, "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt",
                        "yuv420p", output, NULL};
        pid_t pid;
        int e = posix_spawn(&pid, o->ffmpeg, NULL, NULL, args, environ);
        if (e != 0) {
            fprintf(stderr, "mvr render: --video: cannot run %s: %s\n", o->ffmpeg, strerror(e));
            return false;
        }
        int status = 0;
        while (waitpid(pid, &status, 0) < 0)
            if (errno != EINTR) {
                fprintf(stderr, "mvr render: --video: waiting for %s: %s\n", o->ffmpeg, strerror(errno));
                return false;
            }
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            fprintf(stderr, "mvr render: --video: %s failed (%s %d) encoding %s into %s\n", o->ffmpeg,
                    WIFEXITED(status) ? "exit status" : "signal",
                    WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status), input, output);
            return false;
        }
    }
    return true;
}

/* The summary's lines naming what was written: the first and the last image,
 * the contact sheet and the videos. */
void render_output_print_files(const render_options *o, uint32_t n, const char *sheet)
{
    char first[4096], last[4096];
    render_output_view_file(first, sizeof first, o, 0, o->frames_set ? 0 : -1);
    render_output_view_file(last, sizeof last, o, n - 1, o->frames_set ? (int64_t)o->frames - 1 : -1);
    const char *last_name = strrchr(last, '/') ? strrchr(last, '/') + 1 : last;
    if (o->frames_set)
        printf("  images      %s .. %s (%u frame%s of %u view%s)\n", first, last_name, o->frames,
               o->frames == 1 ? "" : "s", n, n == 1 ? "" : "s");
    else
        printf("  images      %s .. %s\n", first, last_name);
    printf("  contact     %s%s\n", sheet, o->frames_set && o->frames > 1 ? " (the first frame)" : "");
    if (o->video) {
        char video[4096];
        video_file(video, sizeof video, o->video, 0, n);
        if (n == 1) {
            printf("  video       %s (%u frames at %g fps, ffmpeg %s)\n", video, o->frames, o->fps, o->ffmpeg);
        } else {
            char last_video[4096];
            video_file(last_video, sizeof last_video, o->video, n - 1, n);
            printf("  video       %s .. %s (%u frames at %g fps, ffmpeg %s)\n", video, last_video, o->frames,
                   o->fps, o->ffmpeg);
        }
    }
}

/* The first executable name in the directories of $PATH, into buf. */
bool render_output_find_on_path(const char *name, char *buf, size_t size)
{
    const char *path = getenv("PATH");
    if (!path || !path[0])
        return false;
    for (const char *d = path; *d;) {
        size_t len = strcspn(d, ":");
        /* an empty entry is the current directory, as the shell takes it */
        int n = len ? snprintf(buf, size, "%.*s/%s", (int)len, d, name) : snprintf(buf, size, "./%s", name);
        struct stat st;
        if (n > 0 && (size_t)n < size && stat(buf, &st) == 0 && S_ISREG(st.st_mode) && access(buf, X_OK) == 0)
            return true;
        d += len + (d[len] == ':');
    }
    buf[0] = '\0';
    return false;
}

/* a column-major 4x4 as 4 rows of 4 (JSON's natural reading order) */
static void json_matrix_rows(json_writer *jw, const char *key, const double m[16])
{
    json_begin_array(jw, key);
    for (int r = 0; r < 4; ++r) {
        json_begin_array(jw, NULL);
        for (int c = 0; c < 4; ++c)
            json_double_exact(jw, NULL, m[c * 4 + r]);
        json_end_array(jw);
    }
    json_end_array(jw);
}

/* The view as it was given (mvr_view_set_get_view), 17 digits: mvr render
 * --cameras of this file makes the same views bit for bit (camera_file.c). */
static void json_view_desc(json_writer *jw, const mvr_view_desc *v)
{
    json_begin_object(jw, "mvr_view");
    json_begin_array(jw, "position");
    for (int i = 0; i < 3; ++i)
        json_double_exact(jw, NULL, v->position[i]);
    json_end_array(jw);
    json_begin_array(jw, "orientation");
    for (int i = 0; i < 4; ++i)
        json_double_exact(jw, NULL, v->orientation[i]);
    json_end_array(jw);
    const mvr_projection *p = &v->projection;
    json_begin_object(jw, "projection");
    static const char *const types[] = {"perspective", "frustum", "orthographic", "matrix"};
    json_string(jw, "type", (unsigned)p->type <= MVR_PROJECTION_MATRIX ? types[p->type] : "unknown");
    switch (p->type) {
    case MVR_PROJECTION_PERSPECTIVE:
        json_double_exact(jw, "yfov", p->yfov);
        json_double_exact(jw, "aspect", p->aspect);
        break;
    case MVR_PROJECTION_FRUSTUM:
        json_double_exact(jw, "angle_left", p->angle_left);
        json_double_exact(jw, "angle_right", p->angle_right);
        json_double_exact(jw, "angle_down", p->angle_down);
        json_double_exact(jw, "angle_up", p->angle_up);
        break;
    case MVR_PROJECTION_ORTHOGRAPHIC:
        json_double_exact(jw, "xmag", p->xmag);
        json_double_exact(jw, "ymag", p->ymag);
        break;
    case MVR_PROJECTION_MATRIX: json_matrix_rows(jw, "matrix", p->matrix); break;
    }
    json_double_exact(jw, "znear", p->znear);
    json_double_exact(jw, "zfar", p->zfar);
    json_end_object(jw);
    json_end_object(jw);
}

bool render_output_write_cameras(const render_options *o, const mvr_view_set *views, uint32_t n)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/cameras.json", o->out_dir);
    cli_write_file out;
    char why[4200];
    if (!cli_write_open(&out, path, why, sizeof why)) {
        fprintf(stderr, "mvr render: %s\n", why);
        return false;
    }
    bool ok = true;
    FILE *f = out.f;
    json_writer jw = {.out = f};
    json_begin_object(&jw, NULL);
    json_string(&jw, "world", "glTF: right-handed, +Y up");
    json_string(&jw, "extrinsics", "world_to_camera, camera_to_world: 4 rows of 4; OpenGL camera: x right, "
                                   "y up, looking along -Z");
    json_string(&jw, "intrinsics", "fx, fy, cx, cy in pixels; OpenCV / COLMAP camera: x right, y down, "
                                   "looking along +Z; u = fx X / Z + cx from the image's left edge, v = fy "
                                   "Y / Z + cy from its top edge; pixel k covers [k, k + 1) (subtract 0.5 "
                                   "for integer pixel centres)");
    json_string(&jw, "projection", "OpenGL clip from camera space, 4 rows of 4, z in [-1, 1]");
    json_string(&jw, "mvr_view", "the view as mvr was given it (mvr_view_desc; zeros are defaults): mvr "
                                 "render --cameras of this file renders it again exactly, unless the "
                                 "matrices or intrinsics above were changed, which then win");
    json_begin_array(&jw, "frames");
    for (uint32_t k = 0; k < n && ok; ++k) {
        mvr_view_camera cam;
        if (mvr_view_set_get_camera(views, k, o->width, o->height, &cam) != MVR_OK) {
            ok = false;
            break;
        }
        char image[4096];
        render_output_view_file(image, sizeof image, o, k, o->frames_set ? 0 : -1);
        const char *name = strrchr(image, '/') ? strrchr(image, '/') + 1 : image;
        json_begin_object(&jw, NULL);
        json_string(&jw, "file_path", name);
        json_int(&jw, "w", cam.width);
        json_int(&jw, "h", cam.height);
        if (cam.perspective) {
            json_double_exact(&jw, "fl_x", cam.fx);
            json_double_exact(&jw, "fl_y", cam.fy);
            json_double_exact(&jw, "cx", cam.cx);
            json_double_exact(&jw, "cy", cam.cy);
            json_double_exact(&jw, "camera_angle_x", 2.0 * atan(0.5 * cam.width / cam.fx));
        }
        json_int(&jw, "view", k);
        json_bool(&jw, "perspective", cam.perspective);
        json_matrix_rows(&jw, "projection", cam.projection);
        json_matrix_rows(&jw, "world_to_camera", cam.world_to_camera);
        json_matrix_rows(&jw, "camera_to_world", cam.camera_to_world);
        mvr_view_desc desc;
        if (mvr_view_set_get_view(views, k, &desc) == MVR_OK)
            json_view_desc(&jw, &desc);
        json_end_object(&jw);
    }
    json_end_array(&jw);
    json_end_object(&jw);
    fputc('\n', f);
    if (!ok) {
        cli_write_abandon(&out);
        fprintf(stderr, "mvr render: writing %s failed: a view has no camera\n", path);
    } else if (!cli_write_close(&out, why, sizeof why)) {
        fprintf(stderr, "mvr render: %s\n", why);
        ok = false;
    }
    return ok;
}
