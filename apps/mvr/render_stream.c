/* mvr render's streamed readback (render_stream.h).
 *
 * The pipeline, per chunk of views (at most GL_MAX_VIEWS_OVR, never across
 * the library's 64-view blocks, so each chunk's passes are those a render
 * of every view makes):
 *   render thread: [render chunk k into ring target k % R] [begin read k]
 *                  [finish the oldest read into a free chunk buffer, queue
 *                   one job per view]
 *   encoders:      [convert, encode, write one view (and its extra outputs'
 *                   .npy files); put its tile into the contact sheet; the
 *                   chunk buffer's last job frees it]
 * A chunk's read is only waited for when its ring target comes round
 * again (or when the GL already says it is done), so rendering chunk k + 1
 * overlaps reading chunk k, and the encoders write while both go on. The
 * render thread blocks for a free chunk buffer when the encoders fall
 * behind: that is the bound on memory. With --outputs each ring slot has
 * one more readback per output, begun after the colour's, and a chunk
 * buffer holds the chunk's colour layers and then each output's layers, so
 * the bound grows with the bytes of a view's outputs, not with the views. */
#define _POSIX_C_SOURCE 200809L
#include "render_stream.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli_progress.h"
#include "cli_scene.h"
#include "mvr/mvr_image.h"
#include "render_aovs.h"
#include "render_output.h"
#include "render_sheet.h"

#define RING 2                   /* targets (and readbacks) in flight (fewer for fewer chunks) */
#define SPARE_BUFFERS 1          /* chunk buffers beyond the ring's, for the encoders to work from */
#define MAX_ENCODERS 64
#define VIEW_BLOCK 64            /* the library's view blocks (MVR_VIEWS_PER_BLOCK): its multiview
                                    chunks never cross one, and neither do the stream's */
#define SLOT_BUDGET ((size_t)64 << 20) /* bytes of one chunk's readback before the chunk shrinks */
#define METER_SIZE 128           /* auto-exposure metering: layers at most this on their long side */

typedef struct chunk_buffer {
    uint8_t *pixels;             /* chunk layers as read back: the colour's, then each output's */
    uint32_t pending;            /* jobs not yet done */
    struct chunk_buffer *next;   /* in the free list */
} chunk_buffer;

typedef struct job {
    chunk_buffer *buffer;
    const uint8_t *pixels;       /* one layer in buffer */
    uint32_t index;              /* the view's in the chunk (its outputs' layers in buffer) */
    uint32_t view;
    int64_t frame;
    bool sheet;
} job;

typedef struct ring_slot {
    mvr_target *target;
    mvr_readback *readback;
    mvr_readback *outputs[MVR_OUTPUT_COUNT]; /* --outputs: one per output asked for, by mvr_output */
    mvr_readback *last;          /* the read begun last: when it is ready, all are (fences signal in order) */
    bool busy;                   /* a read is pending */
    uint64_t serial;             /* order of the reads begun */
    uint32_t base, count;        /* the chunk's views */
    int64_t frame;
    bool sheet;
} ring_slot;

typedef struct encoder {
    struct render_stream *s;
    pthread_t thread;
    bool started;
    uint8_t *bytes;              /* w x h x 4: display bytes */
    float *floats;               /* w x h x 4: linear values (EXR, supersampling) */
} encoder;

struct render_stream {
    const render_options *o;
    mvr_renderer *r;
    uint32_t views, chunk, w, h, ss;
    uint32_t first, end;         /* the views written: [first, end) (a unit's range; else all) */
    bool float_target;           /* the ring's layers are floats (RGBA16F / RGBA32F) */
    mvr_readback_format read_format;
    size_t layer_bytes;          /* one layer as read back */
    size_t output_offset[MVR_OUTPUT_COUNT]; /* where an output's layers start in a chunk buffer */
    size_t output_layer_bytes[MVR_OUTPUT_COUNT]; /* one layer of it (0: not asked for) */
    size_t buffer_bytes;         /* one chunk buffer */
    int frame_digits;            /* of the outputs' file names (render_output_frame_digits) */
    ring_slot ring[RING];
    uint32_t ring_count;         /* slots used: RING, or the chunks of the whole run if fewer */
    uint64_t serial;
    mvr_target *meter;           /* auto-exposure metering (made on first use) */
    bool metered;
    double metered_ev100;
    bool shadows_per_chunk;      /* shadow maps drawn, fitted to chunks of a larger set */
    /* encoders, buffers and jobs: under lock */
    pthread_mutex_t lock;
    pthread_cond_t work, done;   /* a job queued or stop; a job done */
    bool lock_made;
    chunk_buffer buffers[RING + SPARE_BUFFERS];
    uint32_t buffer_count;       /* likewise */
    chunk_buffer *free_buffers;
    job *queue;
    uint32_t queue_cap, queue_head, queue_count;
    bool stop;
    bool failed;                 /* an encoder failed: message in error */
    char error[1024];
    uint64_t images_done;
    encoder encoders[MAX_ENCODERS];
    uint32_t encoder_count;
    render_sheet sheet;
    /* what the summary and the stats show */
    mvr_frame_stats stats;       /* the last frame's, summed over its chunks */
    uint32_t *culled;            /* per view, the last frame's */
    cli_progress progress;
    uint64_t total_images;
    double start;                /* first render */
    double seconds;
};

/* ------------------------------------------------------------------ encoders */

static void fail_locked(render_stream *s, const char *message)
{
    if (!s->failed) {
        s->failed = true;
        snprintf(s->error, sizeof s->error, "%s", message);
    }
}

/* One view's file from its layer as read back, as the synchronous path
 * makes it (render_output_write_views, cli_read_display_layer): the display
 * bytes (sRGB-encoded resolved samples when supersampled; the stored bytes,
 * or floats clamped to bytes; an EXR's RGBA16F layer sRGB-encoded for the
 * sheet) and, for EXR, the linear values. */
static bool encode(encoder *e, const job *j, char *why, size_t why_size)
{
    render_stream *s = e->s;
    const render_options *o = s->o;
    size_t pixels = (size_t)s->w * s->h;
    const uint8_t *bytes = j->pixels;
    const float *linear = NULL;
    if (s->ss > 1) {
        if (mvr_downsample_rgba32f((const float *)j->pixels, s->w * s->ss, s->h * s->ss, s->ss, e->floats) !=
            MVR_OK) {
            snprintf(why, why_size, "view %u: the supersample resolve failed", j->view);
            return false;
        }
        cli_encode_srgb(e->floats, e->bytes, pixels);
        bytes = e->bytes;
        linear = e->floats;
    } else if (s->float_target) {
        const float *in = (const float *)j->pixels;
        if (o->exr && o->format == MVR_COLOR_FORMAT_RGBA16F) {
            cli_encode_srgb(in, e->bytes, pixels); /* the sheet shows display values */
        } else {
            /* as mvr_renderer_read_layer gives a float layer as RGBA8 */
            for (size_t i = 0; i < pixels * 4; ++i) {
                float v = in[i] < 0.0f ? 0.0f : in[i] > 1.0f ? 1.0f : in[i];
                e->bytes[i] = (uint8_t)(v * 255.0f + 0.5f);
            }
        }
        bytes = e->bytes;
        linear = in;
    } else if (o->exr) {
        /* as mvr_renderer_read_layer gives a byte layer as RGBA32F */
        for (size_t i = 0; i < pixels * 4; ++i)
            e->floats[i] = (float)j->pixels[i] / 255.0f;
        linear = e->floats;
    }
    char path[4096];
    render_output_view_file(path, sizeof path, o, j->view, j->frame);
    mvr_image_view view = {s->w, s->h, o->exr ? MVR_PIXEL_F32 : MVR_PIXEL_U8, true,
                           o->exr ? (const void *)linear : (const void *)bytes};
    mvr_error err;
    if (mvr_image_write(path, &view, &err) != MVR_OK) {
        snprintf(why, why_size, "%s", err.message);
        return false;
    }
    /* the extra outputs, as render_aovs_write writes them */
    render_aov_view aov = {.view = j->view, .frame = j->frame, .frame_digits = s->frame_digits, .width = s->w,
                           .height = s->h, .color = bytes};
    bool any = false;
    for (int k = MVR_OUTPUT_DEPTH; k < MVR_OUTPUT_COUNT; ++k)
        if (s->output_layer_bytes[k]) {
            aov.data[k] = j->buffer->pixels + s->output_offset[k] + s->output_layer_bytes[k] * j->index;
            any = true;
        }
    if (any && !render_aovs_write_view(o, &aov, why, why_size))
        return false;
    if (j->sheet)
        render_sheet_put(&s->sheet, j->view, bytes, s->w, s->h);
    return true;
}

static void *encoder_main(void *arg)
{
    encoder *e = arg;
    render_stream *s = e->s;
    pthread_mutex_lock(&s->lock);
    for (;;) {
        while (s->queue_count == 0 && !s->stop)
            pthread_cond_wait(&s->work, &s->lock);
        if (s->queue_count == 0)
            break;
        job j = s->queue[s->queue_head];
        s->queue_head = (s->queue_head + 1) % s->queue_cap;
        s->queue_count--;
        bool skip = s->failed || s->stop;
        pthread_mutex_unlock(&s->lock);
        char why[1024] = "";
        bool ok = skip || encode(e, &j, why, sizeof why);
        pthread_mutex_lock(&s->lock);
        if (!ok)
            fail_locked(s, why);
        s->images_done += !skip && ok;
        if (--j.buffer->pending == 0) {
            j.buffer->next = s->free_buffers;
            s->free_buffers = j.buffer;
        }
        pthread_cond_broadcast(&s->done);
    }
    pthread_mutex_unlock(&s->lock);
    return NULL;
}

/* Waits (under lock) for a free chunk buffer, drawing the progress line
 * meanwhile; NULL when an encoder failed. */
static chunk_buffer *take_buffer_locked(render_stream *s)
{
    while (!s->free_buffers && !s->failed) {
        struct timespec until;
        clock_gettime(CLOCK_REALTIME, &until);
        until.tv_nsec += 100 * 1000 * 1000;
        if (until.tv_nsec >= 1000000000L) {
            until.tv_sec++;
            until.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&s->done, &s->lock, &until);
        cli_progress_update(&s->progress, s->images_done, false);
    }
    if (s->failed)
        return NULL;
    chunk_buffer *b = s->free_buffers;
    s->free_buffers = b->next;
    return b;
}

/* ------------------------------------------------------------------ the ring */

static bool worker_failed(render_stream *s)
{
    pthread_mutex_lock(&s->lock);
    bool failed = s->failed;
    if (failed)
        fprintf(stderr, "mvr render: %s\n", s->error);
    pthread_mutex_unlock(&s->lock);
    return failed;
}

/* The slot's read into a free chunk buffer, and one job per view. */
static bool harvest(render_stream *s, ring_slot *slot)
{
    pthread_mutex_lock(&s->lock);
    chunk_buffer *b = take_buffer_locked(s);
    pthread_mutex_unlock(&s->lock);
    if (!b)
        return !worker_failed(s);
    slot->busy = false;
    bool read = mvr_renderer_finish_read(s->r, slot->readback, b->pixels, s->layer_bytes * s->chunk) == MVR_OK;
    for (int k = MVR_OUTPUT_DEPTH; read && k < MVR_OUTPUT_COUNT; ++k)
        read = !slot->outputs[k] ||
               mvr_renderer_finish_read(s->r, slot->outputs[k], b->pixels + s->output_offset[k],
                                        s->output_layer_bytes[k] * s->chunk) == MVR_OK;
    if (!read) {
        fprintf(stderr, "mvr render: reading views %u .. %u: %s\n", slot->base, slot->base + slot->count - 1,
                mvr_renderer_last_error(s->r));
        pthread_mutex_lock(&s->lock);
        b->next = s->free_buffers;
        s->free_buffers = b;
        pthread_mutex_unlock(&s->lock);
        return false;
    }
    pthread_mutex_lock(&s->lock);
    b->pending = 0;
    for (uint32_t k = 0; k < slot->count; ++k)
        b->pending += slot->base + k >= s->first && slot->base + k < s->end;
    for (uint32_t k = 0; k < slot->count; ++k) {
        if (slot->base + k < s->first || slot->base + k >= s->end)
            continue; /* rendered with its chunk, written by another unit */
        job *j = &s->queue[(s->queue_head + s->queue_count++) % s->queue_cap];
        *j = (job){.buffer = b, .pixels = b->pixels + s->layer_bytes * k, .index = k, .view = slot->base + k,
                   .frame = slot->frame, .sheet = slot->sheet};
    }
    pthread_cond_broadcast(&s->work);
    pthread_mutex_unlock(&s->lock);
    return true;
}

/* The pending reads the GL has finished, oldest first, without waiting. */
static bool harvest_ready(render_stream *s)
{
    for (;;) {
        ring_slot *oldest = NULL;
        for (uint32_t i = 0; i < s->ring_count; ++i)
            if (s->ring[i].busy && (!oldest || s->ring[i].serial < oldest->serial))
                oldest = &s->ring[i];
        bool ready = false;
        if (!oldest)
            return true;
        if (mvr_renderer_read_ready(s->r, oldest->last, &ready) != MVR_OK) {
            fprintf(stderr, "mvr render: %s\n", mvr_renderer_last_error(s->r));
            return false;
        }
        if (!ready)
            return true;
        if (!harvest(s, oldest))
            return false;
    }
}

static void add_stats(mvr_frame_stats *sum, const mvr_frame_stats *c, bool first)
{
    if (first) {
        *sum = *c;
        return;
    }
    mvr_frame_stats keep = *sum;
    *sum = *c; /* paths, modes, formats: the last chunk's */
#define ADD(f) sum->f = keep.f + c->f
    ADD(views); ADD(passes); ADD(multiview_passes); ADD(draws); ADD(draw_calls); ADD(instanced_draw_calls);
    ADD(program_binds); ADD(texture_binds); ADD(ubo_range_binds); ADD(upload_bytes); ADD(view_upload_bytes);
    ADD(compacted_bytes); ADD(programs_compiled); ADD(program_cache_hits); ADD(program_binary_loads);
    ADD(program_binary_rejects); ADD(blend_diverged_chunks); ADD(blend_fallback_passes); ADD(culled); ADD(resolves);
    ADD(shadow_passes); ADD(shadow_draws); ADD(post_passes); ADD(luminance_passes); ADD(env_prefilter_passes);
    ADD(env_prefilter_ms); ADD(background_draws); ADD(cpu_ms); ADD(animation_upload_bytes); ADD(preskin_passes);
    ADD(transmission_copies);
#undef ADD
    for (int i = 0; i < 3; ++i)
        sum->sub_passes[i] = keep.sub_passes[i] + c->sub_passes[i];
    sum->shadow_layers = keep.shadow_layers > c->shadow_layers ? keep.shadow_layers : c->shadow_layers;
    sum->gpu_ms = keep.gpu_ms < 0 || c->gpu_ms < 0 ? -1.0 : keep.gpu_ms + c->gpu_ms;
}

/* Views [base, base + count) of the set, with its origin: they render as
 * they do in a render of the whole set. */
static mvr_view_set *chunk_views(const mvr_view_set *views, uint32_t base, uint32_t count)
{
    mvr_view_desc part[VIEW_BLOCK];
    mvr_view_set_desc d = {.view_count = count, .views = part, .origin_set = true};
    for (uint32_t k = 0; k < count; ++k)
        if (mvr_view_set_get_view(views, base + k, &part[k]) != MVR_OK)
            return NULL;
    mvr_view_set *out = NULL;
    mvr_error err;
    if (mvr_view_set_get_origin(views, d.origin) != MVR_OK || mvr_view_set_create(&d, &out, &err) != MVR_OK) {
        fprintf(stderr, "mvr render: views %u .. %u: %s\n", base, base + count - 1, err.message);
        return NULL;
    }
    return out;
}

/* Views in the chunk starting at base. */
static uint32_t chunk_count(const render_stream *s, uint32_t base)
{
    uint32_t count = s->chunk;
    if (count > s->views - base)
        count = s->views - base;
    if (count > VIEW_BLOCK - base % VIEW_BLOCK)
        count = VIEW_BLOCK - base % VIEW_BLOCK;
    return count;
}

/* A shared auto-exposure is one EV100 from every view's luminance. Chunks
 * rendered apart would each meter their own, so the views are first
 * rendered small (METER_SIZE on the long side), chunk by chunk, and their
 * measured log2 luminances pooled as one render pools them (mvr_frame_stats:
 * exposure_measured_views, exposure_log2_luminance); the frame is then
 * rendered at that fixed EV100. */
static bool meter_exposure(render_stream *s, mvr_scene *scene, const mvr_view_set *views,
                           const mvr_render_desc *desc, double *ev100)
{
    if (!s->meter) {
        uint32_t w = s->w, h = s->h, longest = w > h ? w : h;
        if (longest > METER_SIZE) {
            w = (uint32_t)((uint64_t)w * METER_SIZE / longest);
            h = (uint32_t)((uint64_t)h * METER_SIZE / longest);
        }
        mvr_target_desc td = {.width = w ? w : 1, .height = h ? h : 1, .layers = s->chunk};
        if (mvr_target_create(s->r, &td, &s->meter) != MVR_OK) {
            fprintf(stderr, "mvr render: the exposure metering target: %s\n", mvr_renderer_last_error(s->r));
            return false;
        }
    }
    double sum = 0.0, first_ev = 0.0;
    uint32_t measured = 0;
    for (uint32_t base = 0; base < s->views;) {
        uint32_t count = chunk_count(s, base);
        mvr_view_set *part = chunk_views(views, base, count);
        if (!part)
            return false;
        mvr_result res = mvr_renderer_render(s->r, scene, part, s->meter, desc);
        mvr_view_set_destroy(part);
        if (res != MVR_OK) {
            fprintf(stderr, "mvr render: metering the exposure: %s\n", mvr_renderer_last_error(s->r));
            return false;
        }
        mvr_frame_stats st;
        mvr_renderer_get_stats(s->r, &st);
        if (base == 0)
            first_ev = st.exposure_ev100;
        sum += st.exposure_log2_luminance * st.exposure_measured_views;
        measured += st.exposure_measured_views;
        base += count;
    }
    if (measured == 0) {
        *ev100 = first_ev; /* nothing lit anywhere: the renderer's own answer for that */
        return true;
    }
    /* the renderer's rule (mvr_frame_stats.exposure_log2_luminance): the
     * average on the key, less the compensation, within the clamps */
    double key = desc->exposure_key > 0.0f ? desc->exposure_key : 0.18;
    double lo = desc->ev100_min, hi = desc->ev100_max;
    if (lo == 0.0 && hi == 0.0) {
        lo = -8.0;
        hi = 24.0;
    }
    double e = sum / measured - log2(1.2 * key) - desc->exposure_compensation;
    *ev100 = e < lo ? lo : e > hi ? hi : e;
    return true;
}

bool render_stream_frame(render_stream *s, mvr_scene *scene, const mvr_view_set *views, const mvr_render_desc *desc,
                         int64_t frame, bool sheet)
{
    if (mvr_view_set_count(views) != s->views) {
        fprintf(stderr, "mvr render: %u views where the stream was made for %u\n", mvr_view_set_count(views),
                s->views);
        return false;
    }
    if (s->start == 0.0)
        s->start = cli_now();
    mvr_render_desc rd = *desc;
    if (desc->exposure_mode == MVR_EXPOSURE_AUTO && !desc->exposure_per_view && s->views > chunk_count(s, 0)) {
        double ev = 0.0;
        if (!meter_exposure(s, scene, views, desc, &ev))
            return false;
        /* the renderer's EV100 has the compensation in it already */
        rd.exposure_mode = MVR_EXPOSURE_EV100;
        rd.ev100 = ev + desc->exposure_compensation;
        s->metered = true;
        s->metered_ev100 = ev;
    }
    bool first = true;
    for (uint32_t base = 0; base < s->views;) {
        uint32_t count = chunk_count(s, base);
        if (base + count <= s->first || base >= s->end) {
            base += count; /* no view of the range: another unit's chunk */
            continue;
        }
        /* the target the oldest read came from: read it out first */
        ring_slot *slot = &s->ring[s->serial % s->ring_count];
        if (slot->busy && !harvest(s, slot))
            return false;
        mvr_view_set *part = chunk_views(views, base, count);
        if (!part)
            return false;
        mvr_result res = mvr_renderer_render(s->r, scene, part, slot->target, &rd);
        mvr_view_set_destroy(part);
        if (res != MVR_OK) {
            fprintf(stderr, "mvr render: views %u .. %u: %s\n", base, base + count - 1, mvr_renderer_last_error(s->r));
            return false;
        }
        mvr_frame_stats st;
        mvr_renderer_get_stats(s->r, &st);
        add_stats(&s->stats, &st, first);
        first = false;
        s->shadows_per_chunk = s->shadows_per_chunk || (st.shadow_layers > 0 && count < s->views);
        for (uint32_t k = 0; k < count; ++k)
            s->culled[base + k] = mvr_renderer_view_culled(s->r, k);
        mvr_read_desc read = {.first_layer = 0, .layer_count = count, .format = s->read_format};
        bool begun = mvr_renderer_begin_read(s->r, slot->target, &read, slot->readback) == MVR_OK;
        slot->last = slot->readback;
        for (int k = MVR_OUTPUT_DEPTH; begun && k < MVR_OUTPUT_COUNT; ++k) {
            if (!slot->outputs[k])
                continue;
            read.output = (mvr_output)k;
            begun = mvr_renderer_begin_read(s->r, slot->target, &read, slot->outputs[k]) == MVR_OK;
            slot->last = slot->outputs[k];
        }
        if (!begun) {
            fprintf(stderr, "mvr render: reading views %u .. %u: %s\n", base, base + count - 1,
                    mvr_renderer_last_error(s->r));
            return false;
        }
        slot->busy = true, slot->serial = s->serial++, slot->base = base, slot->count = count;
        slot->frame = frame, slot->sheet = sheet;
        /* the encoders get whatever the GL has finished already */
        if (!harvest_ready(s) || worker_failed(s))
            return false;
        pthread_mutex_lock(&s->lock);
        cli_progress_update(&s->progress, s->images_done, false);
        pthread_mutex_unlock(&s->lock);
        base += count;
    }
    return true;
}

bool render_stream_finish(render_stream *s, const char *sheet_path)
{
    /* what is in flight, oldest first */
    for (uint32_t k = 0; k < s->ring_count; ++k) {
        ring_slot *slot = &s->ring[(s->serial + k) % s->ring_count];
        if (slot->busy && !harvest(s, slot))
            return false;
    }
    pthread_mutex_lock(&s->lock);
    while (s->queue_count > 0 || s->images_done < s->total_images) {
        if (s->failed)
            break;
        bool busy = false;
        for (uint32_t i = 0; i < s->buffer_count; ++i)
            busy = busy || s->buffers[i].pending > 0;
        if (!busy)
            break;
        struct timespec until;
        clock_gettime(CLOCK_REALTIME, &until);
        until.tv_nsec += 100 * 1000 * 1000;
        if (until.tv_nsec >= 1000000000L) {
            until.tv_sec++;
            until.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&s->done, &s->lock, &until);
        cli_progress_update(&s->progress, s->images_done, false);
    }
    bool failed = s->failed;
    if (failed)
        fprintf(stderr, "mvr render: %s\n", s->error);
    uint64_t done = s->images_done;
    pthread_mutex_unlock(&s->lock);
    cli_progress_end(&s->progress, done);
    if (failed)
        return false;
    if (sheet_path) {
        mvr_image_view view = {s->sheet.width, s->sheet.height, MVR_PIXEL_U8, false, s->sheet.pixels};
        mvr_error err;
        if (mvr_image_write(sheet_path, &view, &err) != MVR_OK) {
            fprintf(stderr, "mvr render: %s\n", err.message);
            return false;
        }
    }
    /* as the synchronous path counts: every file, the sheet included */
    s->seconds = s->start > 0.0 ? cli_now() - s->start : 0.0;
    return true;
}

/* ------------------------------------------------------------------ create, destroy */

static void stop_encoders(render_stream *s)
{
    if (!s->lock_made)
        return;
    pthread_mutex_lock(&s->lock);
    s->stop = true;
    pthread_cond_broadcast(&s->work);
    pthread_mutex_unlock(&s->lock);
    for (uint32_t i = 0; i < s->encoder_count; ++i)
        if (s->encoders[i].started)
            pthread_join(s->encoders[i].thread, NULL);
    s->encoder_count = 0;
}

void render_stream_destroy(render_stream *s)
{
    if (!s)
        return;
    stop_encoders(s);
    for (int i = 0; i < RING; ++i) {
        mvr_readback_destroy(s->ring[i].readback);
        for (int k = 0; k < MVR_OUTPUT_COUNT; ++k)
            mvr_readback_destroy(s->ring[i].outputs[k]);
        mvr_target_destroy(s->ring[i].target);
    }
    mvr_target_destroy(s->meter);
    for (int i = 0; i < RING + SPARE_BUFFERS; ++i)
        free(s->buffers[i].pixels);
    for (uint32_t i = 0; i < MAX_ENCODERS; ++i) {
        free(s->encoders[i].bytes);
        free(s->encoders[i].floats);
    }
    if (s->lock_made) {
        pthread_cond_destroy(&s->work);
        pthread_cond_destroy(&s->done);
        pthread_mutex_destroy(&s->lock);
    }
    free(s->queue);
    free(s->sheet.pixels);
    free(s->culled);
    free(s);
}

bool render_stream_create(const render_options *o, mvr_context *ctx, mvr_renderer *r, uint32_t views,
                          uint32_t frames, render_stream **out)
{
    *out = NULL;
    render_stream *s = calloc(1, sizeof *s);
    if (!s) {
        fprintf(stderr, "mvr render: out of memory\n");
        return false;
    }
    s->o = o;
    s->r = r;
    s->views = views;
    s->first = 0;
    s->end = views;
    s->w = o->width;
    s->h = o->height;
    s->ss = o->supersample > 1 ? o->supersample : 1;
    s->float_target = o->format == MVR_COLOR_FORMAT_RGBA16F || o->format == MVR_COLOR_FORMAT_RGBA32F;
    s->read_format = s->float_target ? MVR_READBACK_RGBA32F : MVR_READBACK_RGBA8;
    s->layer_bytes = (size_t)s->w * s->ss * s->h * s->ss * (s->float_target ? 16 : 4);
    /* a view's bytes in a chunk buffer: its colour, then its outputs (the
     * target refuses outputs with supersampling, so these are w x h) */
    s->frame_digits = render_output_frame_digits(frames);
    size_t view_bytes = s->layer_bytes;
    for (int k = MVR_OUTPUT_DEPTH; k < MVR_OUTPUT_COUNT; ++k)
        if (o->outputs & MVR_OUTPUT_BIT(k)) {
            s->output_layer_bytes[k] = (size_t)s->w * s->h * mvr_output_pixel_size((mvr_output)k);
            view_bytes += s->output_layer_bytes[k];
        }
    /* a chunk: one multiview pass; when the views take more than one, fewer
     * views where its layers would take more than SLOT_BUDGET to read back
     * (supersampled float layers), as the ring holds several */
    int max_views = mvr_context_caps(ctx)->limits.max_views_ovr;
    s->chunk = max_views > 1 ? (uint32_t)max_views : 1u;
    if (s->chunk > VIEW_BLOCK)
        s->chunk = VIEW_BLOCK;
    if (s->chunk >= views)
        s->chunk = views;
    while (s->chunk > 1 && view_bytes * s->chunk > SLOT_BUDGET && s->chunk < views)
        s->chunk--;
    s->buffer_bytes = s->layer_bytes * s->chunk;
    for (int k = MVR_OUTPUT_DEPTH; k < MVR_OUTPUT_COUNT; ++k) {
        s->output_offset[k] = s->buffer_bytes;
        s->buffer_bytes += s->output_layer_bytes[k] * s->chunk;
    }
    s->total_images = (uint64_t)views * frames;
    bool ok = (s->culled = calloc(views, sizeof *s->culled)) != NULL;
    /* no more targets and buffers than the run has chunks */
    uint64_t chunks = 0;
    for (uint32_t base = 0; base < views; base += chunk_count(s, base))
        chunks++;
    chunks *= frames;
    s->ring_count = chunks < RING ? (uint32_t)chunks : RING;
    s->buffer_count = chunks < RING + SPARE_BUFFERS ? (uint32_t)chunks : RING + SPARE_BUFFERS;
    s->queue_cap = s->buffer_count * s->chunk;
    ok = ok && (s->queue = calloc(s->queue_cap, sizeof *s->queue)) != NULL;
    for (uint32_t i = 0; ok && i < s->buffer_count; ++i) {
        ok = (s->buffers[i].pixels = malloc(s->buffer_bytes)) != NULL;
        s->buffers[i].next = s->free_buffers;
        s->free_buffers = &s->buffers[i];
    }
    ok = ok && render_sheet_create(&s->sheet, views, s->w, s->h);
    if (!ok) {
        fprintf(stderr, "mvr render: out of memory for the stream's buffers\n");
        render_stream_destroy(s);
        return false;
    }
    mvr_target_desc td = {.width = s->w * s->ss, .height = s->h * s->ss, .layers = s->chunk,
                          .color_format = o->format, .samples = o->msaa, .anti_aliasing = o->aa,
                          .outputs = o->outputs};
    for (uint32_t i = 0; i < s->ring_count; ++i) {
        ring_slot *slot = &s->ring[i];
        ok = mvr_target_create(r, &td, &slot->target) == MVR_OK && mvr_readback_create(r, &slot->readback) == MVR_OK;
        for (int k = MVR_OUTPUT_DEPTH; ok && k < MVR_OUTPUT_COUNT; ++k)
            ok = !s->output_layer_bytes[k] || mvr_readback_create(r, &slot->outputs[k]) == MVR_OK;
        if (!ok) {
            fprintf(stderr, "mvr render: %s\n", mvr_renderer_last_error(r));
            render_stream_destroy(s);
            return false;
        }
    }
    if (pthread_mutex_init(&s->lock, NULL) != 0) {
        render_stream_destroy(s);
        return false;
    }
    if (pthread_cond_init(&s->work, NULL) != 0) {
        pthread_mutex_destroy(&s->lock);
        render_stream_destroy(s);
        return false;
    }
    if (pthread_cond_init(&s->done, NULL) != 0) {
        pthread_cond_destroy(&s->work);
        pthread_mutex_destroy(&s->lock);
        render_stream_destroy(s);
        return false;
    }
    s->lock_made = true;
    uint32_t n = o->encoders ? o->encoders : 2;
    if (n > MAX_ENCODERS)
        n = MAX_ENCODERS;
    size_t pixels = (size_t)s->w * s->h;
    for (uint32_t i = 0; i < n; ++i) {
        encoder *e = &s->encoders[i];
        e->s = s;
        e->bytes = malloc(pixels * 4);
        e->floats = malloc(pixels * 4 * sizeof *e->floats);
        int err = e->bytes && e->floats ? pthread_create(&e->thread, NULL, encoder_main, e) : ENOMEM;
        if (err != 0) {
            fprintf(stderr, "mvr render: cannot start encoder thread %u: %s\n", i, strerror(err));
            render_stream_destroy(s);
            return false;
        }
        e->started = true;
        s->encoder_count = i + 1;
    }
    cli_progress_start(&s->progress, !o->quiet && !o->no_progress, s->total_images, "views");
    *out = s;
    return true;
}

void render_stream_set_range(render_stream *s, uint32_t first, uint32_t end, uint32_t frames)
{
    s->first = first < s->views ? first : s->views;
    s->end = end < s->views ? end : s->views;
    s->total_images = (uint64_t)(s->end > s->first ? s->end - s->first : 0) * frames;
    cli_progress_start(&s->progress, !s->o->quiet && !s->o->no_progress, s->total_images, "views");
}

void render_stream_get_stats(const render_stream *s, mvr_frame_stats *out)
{
    *out = s->stats;
}

void render_stream_get_info(const render_stream *s, render_readback_info *out)
{
    memset(out, 0, sizeof *out);
    out->mode = RENDER_READBACK_STREAM;
    out->chunk = s->chunk;
    out->ring = s->ring_count;
    out->encoders = s->encoder_count;
    out->sheet_factor = s->sheet.factor;
    out->exposure_metered = s->metered;
    out->exposure_ev100 = s->metered_ev100;
    out->shadows_per_chunk = s->shadows_per_chunk;
    out->culled_per_view = s->culled;
    out->images = s->images_done;
    out->seconds = s->seconds;
}
