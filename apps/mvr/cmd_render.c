/* mvr render: a demo scene (or, with the glTF loader, a file) into N views,
 * one PNG per view plus a contact sheet, and the frame's stats: running it,
 * in steps (load, set up, each frame posed and rendered, write); its
 * options are render_options.c's, what it writes render_output.c's. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "cli_progress.h" /* cli_now */
#include "cli_env.h"
#include "cli_scene.h"
#include "cli_write.h"
#include "commands.h"
#include "dataset.h" /* transforms.json, COLMAP */
#include "mvr/mvr_gltf.h"
#include "render_files.h" /* SCENE... and --list */
#include "render_options.h"
#include "render_aovs.h"
#include "render_output.h"
#include "render_stats.h"
#include "render_stream.h"
#include "run_plan.h"

/* What the files of one run share: the context, the renderer (and with it
 * the program cache and the prefiltered environment) and the environment,
 * each made when the first file needs it, so one file runs in today's
 * order; render_one makes and frees everything of its own file. */
typedef struct render_session {
    const render_options *base;
    mvr_context *ctx;
    mvr_renderer *renderer;
    mvr_renderer_desc rd;
    mvr_environment *env;
    bool env_made;
    cli_env_used env_used;
    mvr_render_desc render;      /* the options' render desc with the environment in it */
    char cache_buf[4096];
} render_session;

/* DIR/<name of path> for several files: --stats and --video per file. */
static const char *per_file_path(char *buf, size_t size, const char *dir, const char *path)
{
    const char *name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    snprintf(buf, size, "%s/%s", dir, name);
    return buf;
}

/* One scene's run: its options (the session's, with its file and
 * directory), what it makes and frees, and what the summary and the stats
 * report of it. */
typedef struct render_job {
    render_options o;
    char stats_buf[4096 + 256], video_buf[4096 + 256];
    mvr_scene *scene;
    mvr_view_set *views;
    mvr_renderer *renderer;      /* the session's */
    mvr_target *target;
    uint8_t **layers;            /* the synchronous path: every view's bytes */
    float *floats;               /* the synchronous path with EXR: one view's floats */
    render_stream *stream;       /* --readback stream (the default) */
    uint32_t n;                  /* views */
    mvr_gltf_info gltf_info;
    uint32_t variant;
    cli_env_used env_used;
    render_animation anim;
    mvr_node_id camera_node;     /* a file's camera an animation moves, or 0 */
    char sheet[4096];
    double started;
    dataset_views dataset;       /* the first frame's cameras, for the run's dataset files */
} render_job;

/* The job's options: the session's, with file and out_dir (several files:
 * --stats and --video go into out_dir too); the directory created. */
static bool job_options(render_job *j, const render_options *base, const char *file, const char *out_dir)
{
    render_options *o = &j->o;
    *o = *base;
    if (file)
        o->scene_file = file;
    if (out_dir) {
        o->out_dir = out_dir;
        if (o->stats_file)
            o->stats_file = per_file_path(j->stats_buf, sizeof j->stats_buf, out_dir, o->stats_file);
        if (o->video)
            o->video = per_file_path(j->video_buf, sizeof j->video_buf, out_dir, o->video);
    }
    return cli_make_dirs("mvr render", o->out_dir);
}

/* Load: the session's context (made by the first file), the scene and its
 * views, the material variant, the session's environment, and the
 * exposure the scene asks for. */
/* The scene loaded on a thread of its own while the first file's context is
 * made: scene and context know nothing of each other, and the context is
 * made, made current and used on the one thread (EGL binds a context to the
 * thread that makes it current). */
typedef struct load_task {
    const cli_scene_options *so;
    mvr_scene **scene;
    mvr_view_set **views;
    int rc;
} load_task;

static void *load_on_thread(void *arg)
{
    load_task *t = arg;
    t->rc = cli_load_scene("mvr render", t->so, t->scene, t->views);
    return NULL;
}

/* The context (the session's first file only) and the scene: at once on two
 * threads, unless MVR_DECODE_THREADS=1 asks for one thread (then in order,
 * as before). A context that fails is the answer, the scene dropped. */
static int context_and_scene(render_session *s, render_job *j, const cli_scene_options *so, bool *fatal)
{
    mvr_error err;
    const char *threads = getenv("MVR_DECODE_THREADS");
    bool overlap = !s->ctx && !(threads && strcmp(threads, "1") == 0);
    load_task task = {.so = so, .scene = &j->scene, .views = &j->views, .rc = MVR_EXIT_OK};
    pthread_t loader;
    overlap = overlap && pthread_create(&loader, NULL, load_on_thread, &task) == 0;
    mvr_result made = s->ctx ? MVR_OK : mvr_context_create(&j->o.context, &s->ctx, &err);
    if (overlap)
        pthread_join(loader, NULL);
    if (made != MVR_OK) {
        if (overlap) {
            mvr_view_set_destroy(j->views);
            mvr_scene_destroy(j->scene);
            j->views = NULL;
            j->scene = NULL;
        }
        fprintf(stderr, "mvr render: %s\n", err.message);
        *fatal = true;
        return MVR_EXIT_FAILURE;
    }
    return overlap ? task.rc : cli_load_scene("mvr render", so, &j->scene, &j->views);
}

static int step_load(render_session *s, render_job *j, bool *fatal)
{
    render_options *o = &j->o;
    cli_scene_options so = {.demo = o->demo, .scene_file = o->scene_file, .camera = o->camera, .layout = o->layout,
                            .ipd = o->ipd, .framing = &o->framing, .gltf_scene = o->gltf_scene, .views = o->views, .width = o->width,
                            .height = o->height, .logger = o->context.logger, .strict = o->strict,
                            .memory_budget = o->memory_budget, .gltf_info = &j->gltf_info,
                            .given_views = o->camera_views, .given_view_count = o->camera_count};
    int rc = context_and_scene(s, j, &so, fatal);
    if (rc != MVR_EXIT_OK)
        return rc;
    j->variant = MVR_VARIANT_DEFAULT;
    if (o->variant && (!cli_find_variant("mvr render", o->scene_file, j->scene, o->variant, &j->variant) ||
                       mvr_scene_select_variant(j->scene, j->variant) != MVR_OK))
        return MVR_EXIT_USAGE;
    if (!s->env_made) {
        s->render = o->render;
        rc = cli_env_create("mvr render", &o->env, o->scene_file != NULL, &s->render, &s->env, &s->env_used);
        if (rc != MVR_EXIT_OK) {
            *fatal = true;
            return rc;
        }
        s->env_made = true;
    }
    o->render = s->render;
    j->env_used = s->env_used;
    /* the library's choice for the scene and its environment (auto exposure
     * and PBR Neutral for lights in physical units, PBR Neutral under an
     * environment, as mvr-viewer shows it); options given win */
    if (!o->exposure_set)
        mvr_render_desc_choose_exposure(j->scene, &o->render);
    else if (o->render.exposure_mode == MVR_EXPOSURE_AUTO)
        o->render.tone_map = MVR_TONE_MAP_KHR_PBR_NEUTRAL;
    if (o->tone_map_set)
        o->render.tone_map = o->tone_map;
    return MVR_EXIT_OK;
}

/* The session's renderer, made by the first file. */
static int step_renderer(render_session *s, render_job *j, bool *fatal)
{
    const render_options *o = &j->o;
    mvr_error err;
    if (!s->renderer) {
        s->rd = (mvr_renderer_desc){.context = s->ctx, .view_path = o->view_path, .logger = o->context.logger,
                                    .material_path = o->material_path, .depth_mode = o->depth_mode,
                                    .transparency_order = o->transparency, .skinning_path = o->skinning,
                                    .program_cache_dir = cli_program_cache_dir("mvr render", o->program_cache, s->cache_buf, sizeof s->cache_buf)};
        /* mvr render reads the library's MVR_* debugging variables (docs/guide.md) */
        if (mvr_renderer_overrides_from_env(&s->rd.overrides, &err) != MVR_OK) {
            fprintf(stderr, "mvr render: %s\n", err.message);
            *fatal = true;
            return MVR_EXIT_USAGE;
        }
        if (mvr_renderer_create(&s->rd, &s->renderer, &err) != MVR_OK) {
            fprintf(stderr, "mvr render: %s\n", err.message);
            *fatal = true;
            return MVR_EXIT_FAILURE;
        }
    }
    j->renderer = s->renderer;
    return MVR_EXIT_OK;
}

/* What the frames render into and are read back through: the target (or
 * the stream's ring), the animation that poses them, the synchronous
 * path's buffers, and the file's camera an animation moves. */
static int step_setup(render_session *s, render_job *j)
{
    render_options *o = &j->o;
    j->n = mvr_view_set_count(j->views);
    uint32_t ss = o->supersample;
    mvr_target_desc td = {.width = o->width * ss, .height = o->height * ss, .layers = j->n, .color_format = o->format,
                          .samples = o->msaa, .anti_aliasing = o->aa, .outputs = o->outputs};
    if (o->readback == RENDER_READBACK_STREAM) {
        if (!render_stream_create(o, s->ctx, j->renderer, j->n, o->frames, &j->stream))
            return MVR_EXIT_FAILURE;
        if (o->unit) /* a unit of a sharded run: its views of the whole set */
            render_stream_set_range(j->stream, o->view_first, o->view_end, o->frame_end - o->frame_first);
    } else if (mvr_target_create(j->renderer, &td, &j->target) != MVR_OK) {
        fprintf(stderr, "mvr render: %s\n", mvr_renderer_last_error(j->renderer));
        return MVR_EXIT_FAILURE;
    }
    if (!render_output_choose_animation(o, j->scene, &j->anim))
        return MVR_EXIT_USAGE;
    /* the synchronous path holds every view's bytes (the stream its own few buffers) */
    j->layers = j->stream ? NULL : calloc(j->n, sizeof *j->layers);
    if (!j->stream && !j->layers)
        return MVR_EXIT_FAILURE;
    size_t pixels = (size_t)o->width * o->height;
    for (uint32_t k = 0; j->layers && k < j->n; ++k)
        if (!(j->layers[k] = malloc(pixels * 4)))
            return MVR_EXIT_FAILURE;
    j->floats = o->exr && !j->stream ? malloc(pixels * 4 * sizeof *j->floats) : NULL;
    if (o->exr && !j->stream && !j->floats)
        return MVR_EXIT_FAILURE;
    j->started = cli_now();
    snprintf(j->sheet, sizeof j->sheet, "%s/contact_sheet.png", o->out_dir);
    /* views from a file's camera follow it when an animation moves it (or
     * its parents): made again from the posed camera every frame */
    if (j->anim.applied && o->scene_file &&
        (o->camera >= 0 || (o->camera == CLI_CAMERA_IF_ANY && mvr_scene_camera_node_count(j->scene) > 0)))
        j->camera_node = mvr_scene_camera_node(j->scene, o->camera >= 0 ? (uint32_t)o->camera : 0);
    return MVR_EXIT_OK;
}

/* Frame: the scene posed at time t, and the views of a camera it moved. */
static bool step_frame(render_job *j, double t)
{
    const render_options *o = &j->o;
    if (j->anim.applied &&
        mvr_scene_apply_animation(j->scene, j->anim.index, t, o->loop ? MVR_ANIMATION_LOOP : MVR_ANIMATION_CLAMP) !=
            MVR_OK) {
        fprintf(stderr, "mvr render: animation %s at %g s: %s\n", j->anim.label, t, mvr_scene_last_error(j->scene));
        return false;
    }
    if (j->camera_node.id) {
        mvr_view_set *posed = NULL;
        mvr_error err;
        if (mvr_view_set_from_camera(j->scene, j->camera_node, j->n, o->ipd, &posed, &err) != MVR_OK) {
            fprintf(stderr, "mvr render: the camera at %g s: %s\n", t, err.message);
            return false;
        }
        mvr_view_set_destroy(j->views);
        j->views = posed;
    }
    j->anim.last_time = t;
    return true;
}

/* Render: frame f into the views' files (the stream writes its own), and
 * with the first frame the contact sheet and the camera metadata. */
static bool step_render(render_job *j, uint32_t f)
{
    render_options *o = &j->o;
    int64_t frame = o->frames_set ? (int64_t)f : -1;
    bool ok;
    /* depth_VVVV.png's step, from the first frame's views (issue 33) */
    if (f == 0 && (o->outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH)))
        o->depth_png_scale = render_aovs_depth_scale(j->scene, j->views);
    if (j->stream) {
        ok = render_stream_frame(j->stream, j->scene, j->views, &o->render, frame, f == 0);
    } else if (mvr_renderer_render(j->renderer, j->scene, j->views, j->target, &o->render) != MVR_OK) {
        fprintf(stderr, "mvr render: %s\n", mvr_renderer_last_error(j->renderer));
        return false;
    } else {
        ok = render_output_write_views(o, j->renderer, j->target, j->n, j->layers, j->floats, frame);
        if (ok && o->outputs)
            ok = render_aovs_write(o, j->renderer, j->target, j->n, j->layers, frame,
                                   render_output_frame_digits(o->frames));
    }
    if (!ok || f != 0 || o->unit)
        return ok; /* a unit's file-level files are the merge's (run_merge.c) */
    /* the contact sheet: the first frame (the one --time alone gives) */
    if (!j->stream && !render_output_write_contact_sheet(j->sheet, j->layers, j->n, o->width, o->height)) {
        fprintf(stderr, "mvr render: cannot write %s\n", j->sheet);
        return false;
    }
    /* the camera metadata of the first frame's views (and what the IDs name) */
    if (!render_output_write_cameras(o, j->views, j->n) ||
        !dataset_views_capture(&j->dataset, o, j->views, j->n, j->scene) || !dataset_write_transforms(o, &j->dataset))
        return false;
    if (o->outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_IDS))
        return render_aovs_write_ids(o->out_dir, j->scene);
    return true;
}

/* Every frame: frame f at --time + f / --fps; without --frames one frame,
 * written as view_VVVV.png. */
static bool render_frames(render_job *j)
{
    bool frames_ok = true;
    uint32_t first = j->o.unit ? j->o.frame_first : 0, end = j->o.unit ? j->o.frame_end : j->o.frames;
    /* a unit of later frames: depth_VVVV.png's step from the first frame's views, as a whole run's */
    if (first > 0 && (j->o.outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH))) {
        frames_ok = step_frame(j, j->o.time);
        j->o.depth_png_scale = render_aovs_depth_scale(j->scene, j->views);
    }
    for (uint32_t f = first; f < end && frames_ok; ++f)
        frames_ok = step_frame(j, j->o.time + (double)f / j->o.fps) && step_render(j, f);
    free(j->floats);
    j->floats = NULL;
    if (frames_ok && j->stream)
        frames_ok = render_stream_finish(j->stream, j->o.unit ? NULL : j->sheet);
    if (j->o.unit)
        return frames_ok;
    /* COLMAP's model and the COCO annotations read the written views back: after the last one */
    if (frames_ok && j->o.colmap)
        frames_ok = dataset_write_colmap(&j->o, &j->dataset);
    if (frames_ok && (j->o.outputs & MVR_OUTPUT_BIT(MVR_OUTPUT_IDS)))
        frames_ok = dataset_write_coco(&j->o, &j->dataset, j->scene);
    return frames_ok;
}

/* The summary on stdout: what ran, how, and what was written. */
static void print_summary(const render_session *s, const render_job *j, const mvr_frame_stats *st,
                          const render_readback_info *readback)
{
    const render_options *o = &j->o;
    const mvr_caps *c = mvr_context_caps(s->ctx);
    const mvr_gltf_info *gi = &j->gltf_info;
    const cli_env_used *env_used = &j->env_used;
    printf("mvr render: %s, %u views of %ux%u on %s (%s)\n", o->scene_file ? o->scene_file : o->demo, j->n, o->width,
           o->height, c->renderer, mvr_context_provider_name(mvr_context_get_provider(s->ctx)));
    printf("  view path   %s: %u pass%s for %u view%s (GL_MAX_VIEWS_OVR %d)\n",
           mvr_view_path_name(st->view_path), st->passes, st->passes == 1 ? "" : "es", st->views,
           st->views == 1 ? "" : "s", c->limits.max_views_ovr);
    if (o->scene_file)
        printf("  load        %u image%s decoded, %u missing (their textures take defaults), %u buffer%s read; "
               "peak %.1f of %.0f MiB budget\n",
               gi->images_decoded, gi->images_decoded == 1 ? "" : "s", gi->images_missing,
               gi->buffers_read, gi->buffers_read == 1 ? "" : "s",
               (double)gi->memory_peak / 1048576.0, (double)gi->memory_budget / 1048576.0);
    printf("  depth       %s\n", st->depth_mode == MVR_DEPTH_MODE_REVERSED_Z ? "reversed-Z (clip control, float depth)" : "standard");
    if (st->post_passes)
        printf("  exposure    %s: EV100 %.2f, tone map %s, %u post pass%s, %u luminance pass%s\n",
               mvr_exposure_mode_name(st->exposure_mode), st->exposure_ev100, mvr_tone_map_name(st->tone_mapper),
               st->post_passes, st->post_passes == 1 ? "" : "es", st->luminance_passes,
               st->luminance_passes == 1 ? "" : "es");
    if (env_used->present && env_used->file)
        printf("  environment %s (%ux%u), intensity %g, rotation %g, background %s\n", env_used->file,
               env_used->width, env_used->height, env_used->intensity, env_used->rotation,
               mvr_background_name(o->render.background));
    else if (env_used->present)
        printf("  environment %s, intensity %g, rotation %g, background %s\n",
               mvr_environment_source_name(env_used->source), env_used->intensity, env_used->rotation,
               mvr_background_name(o->render.background));
    else
        printf("  environment none\n");
    if (st->env_prefilter_passes)
        printf("  prefilter   %u pass%s, %.2f ms (once per environment)\n", st->env_prefilter_passes,
               st->env_prefilter_passes == 1 ? "" : "es", st->env_prefilter_ms);
    if (st->shadow_layers)
        printf("  shadows     %u layer%s in %u pass%s, %u caster draws\n", st->shadow_layers,
               st->shadow_layers == 1 ? "" : "s", st->shadow_passes, st->shadow_passes == 1 ? "" : "es",
               st->shadow_draws);
    printf("  materials   %s: %u texture arrays\n", mvr_material_path_name(st->material_path), st->texture_groups);
    uint32_t loaded = 0, count = mvr_renderer_program_count(j->renderer);
    mvr_program_info pi;
    for (uint32_t i = 0; mvr_renderer_get_program_info(j->renderer, i, &pi); ++i)
        loaded += pi.from_binary_cache;
    printf("  programs    %u variant%s: %u compiled, %u from the binary cache%s%s\n", count,
           count == 1 ? "" : "s", count - loaded, loaded, s->rd.program_cache_dir ? " in " : " (off)",
           s->rd.program_cache_dir ? s->rd.program_cache_dir : "");
    printf("  draws %u in %u draw calls (%u instanced); binds: program %u, texture %u, uniform range %u\n",
           st->draws, st->draw_calls, st->instanced_draw_calls, st->program_binds, st->texture_binds,
           st->ubo_range_binds);
    if (st->gpu_ms >= 0)
        printf("  time        cpu %.2f ms, gpu %.2f ms (last frame)\n", st->cpu_ms, st->gpu_ms);
    else
        printf("  time        cpu %.2f ms, gpu n/a (last frame)\n", st->cpu_ms);
    if (o->variant) {
        char label[128];
        cli_variant_label(j->scene, j->variant, label, sizeof label);
        printf("  variant     %s (of %u)\n", label, mvr_scene_variant_count(j->scene));
    }
    if (o->cameras_file)
        printf("  cameras     %s: %u view%s (%s)\n", o->cameras_file, o->camera_count, o->camera_count == 1 ? "" : "s",
               o->camera_format);
    render_output_print_animation(o, j->scene, &j->anim, st);
    render_output_print_files(o, j->n, j->sheet);
    render_output_print_readback(readback);
}

/* Write: the videos, the plan, the stats file and the summary, once every
 * frame's images are written. */
static int step_write(const render_session *s, render_job *j)
{
    const render_options *o = &j->o;
    render_readback_info readback = {.mode = RENDER_READBACK_SYNC, .images = (uint64_t)j->n * o->frames,
                                     .seconds = cli_now() - j->started};
    if (j->stream)
        render_stream_get_info(j->stream, &readback);
    if (o->video && !render_output_encode_videos(o, j->n))
        return MVR_EXIT_FAILURE;
    mvr_frame_stats st;
    if (j->stream)
        render_stream_get_stats(j->stream, &st); /* the last frame's chunks, summed */
    else
        mvr_renderer_get_stats(j->renderer, &st);
    if (o->plan) {
        size_t need = mvr_renderer_format_plan(j->renderer, NULL, 0) + 1;
        char *text = malloc(need);
        if (text) {
            mvr_renderer_format_plan(j->renderer, text, need);
            fputs(text, stdout);
            free(text);
        }
    }
    if (o->stats_file) {
        cli_write_file out; /* checked and atomic: no partial stats.json on a full disk */
        char why[4200];
        bool ok = cli_write_open(&out, o->stats_file, why, sizeof why);
        if (ok) {
            render_stats_write_json(out.f, j->renderer, &st, o->scene_file ? o->scene_file : o->demo, o->width,
                                    o->height, o->supersample, o->scene_file ? &j->gltf_info : NULL, &j->env_used,
                                    &o->render, o, &j->anim, &readback);
            ok = cli_write_close(&out, why, sizeof why);
        }
        if (!ok) {
            fprintf(stderr, "mvr render: %s\n", why);
            return MVR_EXIT_FAILURE;
        }
    }
    if (!o->quiet)
        print_summary(s, j, &st, &readback);
    return MVR_EXIT_OK;
}

/* What the job made (the renderer is the session's). */
static void job_release(render_job *j)
{
    if (j->layers)
        for (uint32_t k = 0; k < mvr_view_set_count(j->views); ++k)
            free(j->layers[k]);
    free(j->layers);
    free(j->floats);
    render_stream_destroy(j->stream);
    mvr_target_destroy(j->target);
    mvr_view_set_destroy(j->views);
    mvr_scene_destroy(j->scene);
    dataset_views_free(&j->dataset);
}

/* Renders one scene (file: a SCENE, NULL: the options' own) into out_dir
 * (NULL: --out) with the session's context and renderer: load, set up,
 * each frame posed and rendered, then written; an MVR_EXIT_ code, *fatal
 * set when the session itself could not be made. */
static int render_one(render_session *s, const char *file, const char *out_dir, bool *fatal)
{
    render_job j;
    memset(&j, 0, sizeof j);
    if (!job_options(&j, s->base, file, out_dir))
        return MVR_EXIT_FAILURE;
    int rc = step_load(s, &j, fatal);
    if (rc == MVR_EXIT_OK)
        rc = step_renderer(s, &j, fatal);
    if (rc == MVR_EXIT_OK)
        rc = step_setup(s, &j);
    if (rc == MVR_EXIT_OK)
        rc = !render_frames(&j) ? MVR_EXIT_FAILURE : j.o.unit ? MVR_EXIT_OK : step_write(s, &j);
    job_release(&j);
    return rc;
}


static int render_file_cb(void *user, const char *file, const char *out_dir, bool *fatal)
{
    return render_one(user, file, out_dir, fatal);
}

/* One unit of a sharded run (run_units.c): base is the unit's options. */
static int render_unit_cb(void *user, const render_options *base, const char *file, const char *out_dir,
                          bool *fatal)
{
    render_session *s = user;
    s->base = base;
    return render_one(s, file, out_dir, fatal);
}

int mvr_cmd_render(int argc, char **argv)
{
    for (int k = 1; k < argc; ++k)
        if (strcmp(argv[k], "--merge") == 0)
            return run_merge_main(argc, argv);
    render_options o;
    render_inputs in;
    memset(&in, 0, sizeof in);
    int rc = render_options_parse(argc, argv, &o, &in);
    if (rc == MVR_EXIT_OK) {
        render_session s = {.base = &o};
        bool fatal = false;
        if (render_run_active(&o.run)) /* --shard, --resume, --serve, --run-plan */
            rc = run_units_main(&o, &in, render_unit_cb, &s);
        else if (in.files.count > 1) /* DIR/<stem>/ each */
            rc = render_files_run(&in.files, o.out_dir, o.keep_going, o.quiet, render_file_cb, &s);
        else
            rc = render_one(&s, NULL, NULL, &fatal);
        mvr_renderer_destroy(s.renderer);
        mvr_environment_destroy(s.env);
        mvr_context_destroy(s.ctx);
    }
    render_files_free(&in.files);
    free(in.plan_args);
    camera_file_free(&in.cameras);
    return rc < 0 ? MVR_EXIT_OK : rc;
}
