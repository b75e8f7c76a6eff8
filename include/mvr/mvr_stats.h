/*
 * mvr: what a render did: frame and pass stats, what `auto` chose,
 * the programs built, the frame plan.
 *
 * Part of the public C API; include <mvr/mvr.h>, whose conventions apply.
 */
#ifndef MVR_STATS_API_H
#define MVR_STATS_API_H

#include "mvr/mvr_renderer.h"
#include "mvr/mvr_target.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ stats */

/* What `auto` measured and why the path runs (mvr_tuning_desc). */
typedef enum mvr_auto_state {
    MVR_AUTO_NONE = 0,           /* the path was asked for (not auto), or only one works here */
    MVR_AUTO_RULE,               /* tuning off: the caps rule */
    MVR_AUTO_TUNING,             /* this frame is one of the measured ones */
    MVR_AUTO_SETTLED             /* the measured choice */
} mvr_auto_state;
const char *mvr_auto_state_name(mvr_auto_state state);

typedef struct mvr_auto_choice {
    mvr_auto_state state;
    mvr_view_path prior;         /* the caps rule's choice */
    mvr_view_path chosen;        /* what runs once settled (the prior until then) */
    mvr_view_path candidates[2]; /* multiview, loop */
    uint32_t samples[2];         /* measured frames of each */
    double cost_ms[2];           /* their medians (settled), or the latest (tuning); < 0: none */
    double margin;               /* settled: the chosen path's saving over the prior's median (0..1) */
    uint32_t retunes;            /* input changes that started the measurement again */
} mvr_auto_choice;

/* The same for the material path (material path AUTO; MVR_AUTO_NONE
 * otherwise). */
typedef struct mvr_auto_material_choice {
    mvr_auto_state state;
    mvr_material_path prior;     /* arrays */
    mvr_material_path chosen;
    mvr_material_path candidates[2]; /* per_material, arrays */
    uint32_t samples[2];
    double cost_ms[2];
    double margin;
    uint32_t retunes;
} mvr_auto_material_choice;

/* The same for the skinning path (skinning path AUTO, a scene with skins or
 * morph targets; MVR_AUTO_NONE otherwise). */
typedef struct mvr_auto_skinning_choice {
    mvr_auto_state state;
    mvr_skinning_path prior;     /* the rule's choice */
    mvr_skinning_path chosen;
    mvr_skinning_path candidates[2]; /* vertex, preskin */
    uint32_t samples[2];
    double cost_ms[2];
    double margin;
    uint32_t retunes;
} mvr_auto_skinning_choice;

struct mvr_frame_stats {
    mvr_view_path view_path;     /* the path that ran */
    uint32_t views;              /* enabled views rendered */
    uint32_t passes;             /* framebuffer passes (multiview chunks or loop views) */
    uint32_t multiview_passes;   /* passes through a multiview framebuffer (a chunk of one
                                    view takes a plain pass: same pixels, less work) */
    uint32_t draws;              /* objects drawn (an instanced draw counts each instance) */
    uint32_t draw_calls;         /* GL draw commands */
    uint32_t instanced_draw_calls; /* of those, instanced ones (more than one object) */
    uint32_t program_binds;
    uint32_t texture_binds;
    uint32_t ubo_range_binds;
    uint64_t upload_bytes;       /* view-independent: geometry, textures, materials, per-draw data */
    uint64_t view_upload_bytes;  /* per-view matrices */
    uint64_t compacted_bytes;    /* per-pass copies of the visible draws' blocks, where culling
                                    would otherwise split instanced runs */
    uint32_t programs_compiled;  /* variants compiled from source in this render */
    uint32_t program_cache_hits; /* variant lookups served by a program already built */
    uint32_t program_binary_loads;   /* variants linked from the binary cache */
    uint32_t program_binary_rejects; /* cache entries found corrupt, stale or refused (rebuilt) */
    mvr_depth_mode depth_mode;   /* the depth mode that ran (never AUTO) */
    mvr_transparency_order transparency_order; /* the policy that ran */
    uint32_t blend_diverged_chunks; /* multiview chunks whose views disagree on the blend order */
    uint32_t blend_fallback_passes; /* per-view blend passes after a multiview pass */
    mvr_material_path material_path; /* the material path that ran */
    uint32_t texture_groups;     /* texture arrays of the scene's batch plan (array path) */
    uint32_t culled;             /* summed over views: draws outside a view's frustum */
    uint32_t sanitized;          /* the scene's repaired degenerate values (mvr_scene_sanitized_count) */
    uint32_t samples;            /* the target's samples per pixel (1 = no multisampling) */
    mvr_anti_aliasing anti_aliasing; /* what ran: NONE, MSAA or SUPERSAMPLE */
    bool msaa_multiview;         /* multisampled multiview passes (else MSAA went view by view) */
    uint32_t resolves;           /* multisample resolves (one per view) and supersample resolve
                                    passes (one per chunk of views) */
    uint32_t supersample;        /* the target's samples per pixel side (1 = none) */
    /* Sub-passes drawn, summed over passes: [0] opaque, [1] alpha-masked,
     * [2] blended (transparent). A pass skips a list with nothing to draw in
     * it, state changes included: a scene without transparency runs no
     * blend sub-pass. */
    uint32_t sub_passes[3];
    uint32_t shadow_passes;      /* shadow map passes: 1 per frame (multiview, <= GL_MAX_VIEWS_OVR
                                    layers) whatever the view count; one per layer without multiview */
    uint32_t shadow_layers;      /* layers of the shadow map array in use (cascades + spot maps) */
    uint32_t shadow_draws;       /* caster objects drawn into the shadow maps */
    mvr_exposure_mode exposure_mode;
    double exposure_ev100;       /* the EV100 that ran (view 0's with per-view auto exposure;
                                    LINEAR: the EV100 whose exposure is that multiplier) */
    mvr_tone_map tone_mapper;
    uint32_t post_passes;        /* final full-screen passes (1 per multiview chunk, 1 per view on
                                    the loop path; 0 without an HDR frame) */
    uint32_t luminance_passes;   /* auto-exposure log-luminance passes */
    /* Environment prefiltering (view-independent: only in the render that
     * first meets an environment or its new pixels; 0 on every later frame
     * whatever the view count): passes drawn (one per cube level: the six
     * faces are six views of one multiview pass, else six passes), and
     * their time on the submitting thread with the GL finished (ms; 0 when
     * none ran). */
    uint32_t env_prefilter_passes;
    double env_prefilter_ms;
    uint32_t background_draws;   /* environment background draws (one per pass that drew one) */
    double cpu_ms;               /* submitting thread, render call */
    double gpu_ms;               /* timer queries; < 0 when not available */
    uint32_t images_downscaled;  /* scene images stored smaller than given: too large for the GL
                                    (mvr_oversized_image) */
    /* Skins and morph targets: joints posed this frame (summed over the
     * skins drawn), the path skinning ran on (AUTO when nothing is skinned
     * or morphed), morph targets with a non-zero weight summed over the
     * morphed draws (the only ones that cost work), the bytes of joint
     * matrices and weights sent this frame (once for all views), and the
     * transform feedback passes of the pre-skinning path. */
    uint32_t joints;
    mvr_skinning_path skinning_path;
    uint32_t morph_targets_active;
    uint64_t animation_upload_bytes;
    uint32_t preskin_passes;
    /* KHR_materials_transmission: views whose opaque colour was copied for
     * the transmissive draws (0 when nothing is transmissive), and the
     * bytes of the mip-mapped copy array */
    uint32_t transmission_copies;
    uint64_t transmission_bytes;
    /* Scene images the GL holds block-compressed as given (no RGBA8
     * decode), and scene images whose format the GL cannot sample, drawn
     * with their roles' neutral values (each warned about once per upload). */
    uint32_t images_compressed;
    uint32_t images_unsampleable;
    /* Extra outputs: the target's (mvr_target_desc.outputs) that were
     * drawn, and the outputs-only passes of blended draws (one per chunk
     * of views with blended draws; 0 without outputs). */
    uint32_t outputs;
    uint32_t output_blend_passes;
    /* Auto-exposure: the views whose luminance was measured (some lit
     * pixel; the others do not count) and the mean over them of each one's
     * average log2 luminance (before exposure), which the shared EV100
     * follows from (EV100 = it - log2(1.2 * exposure_key) - compensation,
     * clamped): what a caller that renders a view set in parts needs to
     * meter them all as one render would. 0 without auto-exposure. */
    uint32_t exposure_measured_views;
    double exposure_log2_luminance;
    mvr_auto_choice auto_choice; /* the view path's `auto` */
    mvr_auto_skinning_choice auto_skinning; /* the skinning path's `auto` */
    mvr_auto_material_choice auto_material; /* the material path's `auto` */
};

/* Stats of the last render (waits for its GPU timer result where there is one). */
void mvr_renderer_get_stats(mvr_renderer *renderer, mvr_frame_stats *out);

typedef struct mvr_pass_stats {
    uint32_t first_view, views;  /* the views (layers) the pass rendered */
    bool multiview;
    uint32_t draws, program_binds, texture_binds, ubo_range_binds;
    uint32_t texture_groups;     /* distinct texture arrays the pass sampled (array path) */
} mvr_pass_stats;

/* The shader variants a renderer has built, in build order: each is one
 * feature key (the scene's features, the path and the output) compiled with
 * #defines, so a scene without textures has no texturing code. */
typedef struct mvr_program_info {
    char name[64];               /* e.g. "mesh-mv2-f10021-l1.0.0" */
    bool mesh;                   /* mesh program (else the composite copy) */
    uint32_t features;           /* feature bits; mvr_program_feature_name names them */
    uint32_t num_views;          /* multiview views; 0 = loop path */
    uint32_t lights[3];          /* directional, point, spot (mesh) */
    bool from_binary_cache;
} mvr_program_info;

uint32_t mvr_renderer_program_count(const mvr_renderer *renderer);
bool mvr_renderer_get_program_info(const mvr_renderer *renderer, uint32_t index, mvr_program_info *out);
/* The name of one mesh feature bit ("BASE_COLOR_TEX", "NORMAL_TEX", ...);
 * NULL when the bit is not one. */
const char *mvr_program_feature_name(uint32_t bit);

/* Draws culled in view `view` of the last render (outside its frustum). */
uint32_t mvr_renderer_view_culled(const mvr_renderer *renderer, uint32_t view);

/* Stats of pass `index` of the last render (the first 256 passes); false past the end. */
bool mvr_renderer_get_pass_stats(const mvr_renderer *renderer, uint32_t index, mvr_pass_stats *out);

/* The frame plan of the last render as text (what `mvr render --plan`
 * prints): a summary line, then one line per pass record in order (view-
 * independent passes, each view pass with its sub-passes and resolve, the
 * supersampling resolve and post), each with its views, whether it runs, is
 * skipped or depends on the drawn data, and why. Writes at most size bytes,
 * NUL-terminated when size > 0 (buf may be NULL when size is 0); returns the
 * length of the whole text, as snprintf does. */
size_t mvr_renderer_format_plan(const mvr_renderer *renderer, char *buf, size_t size);

#ifdef __cplusplus
}
#endif
#endif /* MVR_STATS_API_H */
