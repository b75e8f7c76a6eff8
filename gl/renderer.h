/* The renderer (gl/renderer.c): the struct every role of gl/ works on, and
 * what the context calls when it goes. The roles' own state and functions
 * are in their headers (gpu_scene.h, program_cache.h, ring.h, timers.h,
 * shadows.h, environment_gl.h, skinning.h, transmission.h). */
#ifndef MVR_RENDERER_H
#define MVR_RENDERER_H

#include "context_internal.h"
#include "environment_gl.h"
#include "frame.h"
#include "frame_plan.h"
#include "gpu_scene.h"
#include "program_cache.h"
#include "ring.h"
#include "shadows.h"
#include "skinning.h"
#include "state_cache.h"
#include "timers.h"
#include "transmission.h"
#include "tuner.h"
#include "tuner_memory.h"
#include "view_set.h"

/* auto's remembered choices (gl/tuning.c, core/tuner_memory.h): on with a
 * program cache folder; per decision the memory key of the last look-up,
 * what it found, and the key its tuning started with (where it stores). */
typedef struct mvr_tuning_memory {
    bool enabled, mac_loaded, hashed;
    mvr_program_cache_key mac;
    uint64_t scene_serial, geometry_version, scene_hash;
    struct {
        char key[MVR_TUNER_MEMORY_MAX_KEY + 1], tuned_key[MVR_TUNER_MEMORY_MAX_KEY + 1];
        bool found;
        mvr_tuner_memory memory;
    } d[3];
} mvr_tuning_memory;

struct mvr_renderer {
    mvr_context *ctx;            /* NULL once the context is destroyed: calls fail, destroy frees */
    const mvr_gl_api_table *gl;  /* &ctx->gl */
    mvr_renderer *next_in_context; /* in ctx->renderers */
    mvr_target *targets;         /* alive targets: detached when the renderer goes */
    struct mvr_readback *readbacks; /* alive readbacks (gl/readback_async.c): detached likewise */
    mvr_oversized_image oversized_images; /* resolved: never DEFAULT */
    uint32_t sampleable_formats; /* bits 1u << mvr_image_format the GL samples (caps, overrides) */
    mvr_logger logger;
    char last_error[MVR_ERROR_MESSAGE_SIZE];
    uint32_t failures;           /* calls of mvr_gl_fail (did a step record its message?) */
    mvr_view_path requested_path;
    mvr_material_path material_requested; /* the setting (AUTO: tuned, or arrays without tuning) */
    mvr_material_path material_path; /* this frame's: never AUTO */
    bool reversed_z;
    uint32_t ubo_alignment;
    uint32_t material_capacity;
    uint32_t draw_capacity;      /* per-draw blocks one instanced draw can read; 1 = no instancing */
    uint32_t draw_stride;        /* bytes between per-draw blocks (144 aligned up) */
    mvr_state_cache state;
    mvr_program_entry *programs;
    uint32_t program_count, program_cap;
    mvr_gpu_scene gpu;
    mvr_frame frame;
    bool sheen_frame;            /* a draw of this frame reads KHR_materials_sheen */
    bool culling;
    mvr_transparency_order blend_policy;
    mvr_view_path path_ran;      /* set by the frame: the path it took (0 before) */
    /* auto's online tuner (gl/tuning.c): on or off, the test hook, and the
     * frame whose cost is still to be recorded */
    bool tuning;
    mvr_tuning_desc tuning_desc;
    mvr_tuner view_tuner, material_tuner, skin_tuner;
    bool view_tuned_frame, material_tuned_frame, skin_tuned_frame; /* this frame's paths are the tuners' */
    struct { bool pending; uint32_t decision, candidate; double cpu_ms; } tuning_frame;
    mvr_tuning_memory tuning_memory;
    void *blend_order;           /* per-view order of the blend list (scratch) */
    size_t blend_order_cap;
    mvr_visibility vis;          /* per-view visibility of the frame's draws */
    /* Dirty tracking: the frame (draw list, per-draw blocks, lights) is
     * rebuilt and re-uploaded only when what it depends on changed. */
    struct {
        bool valid;
        bool arrays;             /* built for the array path's material slots */
        uint64_t scene_serial, geometry_version, material_version, transform_version;
        mvr_dvec3 origin;
    } frame_key;

    mvr_ring ring;
    mvr_timer timer;
    uint64_t frame_serial;
    mvr_frame_stats stats;
#define MVR_MAX_PASS_STATS 256
    mvr_pass_stats pass_stats[MVR_MAX_PASS_STATS];
    uint32_t pass_stats_count;
    uint32_t compiled_this_frame, cache_hits_this_frame, binary_loads_this_frame, binary_rejects_this_frame;
    char *program_cache_dir;     /* NULL = no binary cache */
    bool program_cache_warned;
    /* overrides.force_inert_features: every draw's key gains the features
     * that cannot change its pixels (tests: skipping changes cost, not pixels) */
    bool force_inert_features;
    bool msaa_multiview_off;     /* overrides.msaa_multiview: MSAA targets take the loop path */
    bool anisotropic_on;         /* overrides.anisotropic: anisotropic material samplers */
    uint64_t upload_bytes, view_upload_bytes;
    /* per-pass compaction: the visible draws' blocks of each culled pass,
     * consecutive, so culling does not cut instanced runs apart */
    uint8_t *compact_scratch;
    size_t compact_scratch_cap;
    /* the frame plan (core/frame_plan.h) of the last render, and the
     * executor's scratch, grown as needed: per chunk its compacted blocks'
     * offset; per texture group whether the pass sampled it */
    mvr_frame_plan plan;
    GLintptr *chunk_compact;
    uint32_t chunk_compact_cap;
    uint8_t *groups_used;
    uint32_t groups_used_cap;
    GLuint empty_vao;            /* for attributeless full-screen passes */
    mvr_shadow_maps shadows;
    GLuint nearest_sampler;      /* texel reads of depth (auto-exposure metering) */
    mvr_gpu_environment env;
    mvr_skinning skinning;
    mvr_transmission transmission;
};

/* The renderer's context is being destroyed: its GL objects and its
 * targets' are released (now, or with the context), and it unlinks itself
 * from ctx->renderers; later calls on it fail. */
void mvr_renderer_context_destroyed(mvr_renderer *r);

#endif
