/* The renderer's internals, shared by gl/renderer.c, gpu_scene.c, targets.c
 * and passes.c. */
#ifndef MVR_RENDERER_INTERNAL_H
#define MVR_RENDERER_INTERNAL_H

#include "batch_plan.h"
#include "context_internal.h"
#include "frame.h"
#include "frame_plan.h"
#include "program.h"
#include "shadow_plan.h"
#include "state_cache.h"
#include "tuner.h"
#include "view_set.h"

/* gl/transmission.c: the opaque views transmissive draws sample. */
typedef struct mvr_transmission {
    GLuint texture, fbo, sampler;
    GLenum format;
    uint32_t width, height, layers;
    float rect[4];               /* the chunk's viewport in the array (0..1) */
    float lod;                   /* log2 of its width in texels */
    int32_t base;                /* the chunk's first view in its view block */
    uint64_t serial;             /* one per copy */
} mvr_transmission;

/* One compiled shader variant. */
typedef struct mvr_program_entry {
    mvr_shader_variant variant;
    GLuint program;
    GLint loc_view_base, loc_ambient, loc_exposure;
    GLint loc_output_alpha_cutoff;   /* outputs-only variants */
    float output_alpha_cutoff;       /* its value set (NaN: none yet) */
    GLint loc_layer_base, loc_factor, loc_post_exposure, loc_clear_depth;  /* composite programs */
    GLint loc_env_sh, loc_env_rotation, loc_env_intensity, loc_env_max_lod; /* mesh (IBL), background */
    GLint loc_face_base, loc_face_size, loc_equirect_lod, loc_roughness, loc_samples, loc_source_size,
        loc_source_max_lod;      /* environment programs */
    GLint loc_depth_range, loc_background_lod; /* background programs */
    GLint loc_env_samples;       /* mesh, the IBL reference */
    GLint loc_deform_info;       /* pre-skinning */
    GLint loc_transmission_base, loc_transmission_rect, loc_transmission_lod; /* mesh, transmission */
    uint64_t transmission_serial; /* the copy whose uniforms are set */
    int32_t view_base;           /* last value set (INT32_MIN = unknown) */
    uint64_t frame_serial;       /* frame whose per-frame uniforms are set */
    bool from_binary;            /* linked from the binary cache */
} mvr_program_entry;

/* GPU copy of one scene primitive. */
#define MVR_VERTEX_ATTRIBUTES 10 /* locations of mesh.vert.glsl and deform.glsl */
typedef struct mvr_gpu_primitive {
    GLuint vao, vbo, ibo;
    uint32_t attributes;         /* bit per location present in vbo */
    GLintptr attribute_offset[MVR_VERTEX_ATTRIBUTES];
    GLenum mode, index_type;
    GLsizei count;
} mvr_gpu_primitive;

typedef struct mvr_gpu_texture {
    uint32_t image;              /* scene image index; MVR_NO_INDEX - role: a role's 1 x 1 neutral texture */
    bool srgb;
    GLuint texture;
} mvr_gpu_texture;

typedef struct mvr_gpu_sampler {
    mvr_sampler_desc desc;
    GLuint sampler;
} mvr_gpu_sampler;

/* Per-material texture bindings (the per-material path: one 2D texture per image). */
typedef struct mvr_gpu_material {
    GLuint textures[MVR_ROLE_COUNT]; /* 0 = role unused */
    GLuint samplers[MVR_ROLE_COUNT];
} mvr_gpu_material;

/* What the renderer has uploaded of one scene. `scene` is an identity (with
 * its serial: a new scene at a freed one's address has another serial),
 * dereferenced only during the render that passed it in: a scene may be
 * destroyed between renders. */
typedef struct mvr_gpu_scene {
    const mvr_scene *scene;
    uint64_t scene_serial;
    uint64_t geometry_version, material_version;
    mvr_gpu_primitive *primitives;
    uint32_t primitive_count;
    mvr_gpu_texture *textures;
    uint32_t texture_count, texture_cap;
    mvr_gpu_sampler *samplers;
    uint32_t sampler_count, sampler_cap;
    mvr_gpu_material *materials; /* scene materials + the default one (per-material paths) */
    /* Two representations of the materials: [1] the array path's (texture
     * arrays, blocks with layer indices), [0] the per-material paths' (2D
     * textures, blocks without). The frame's is uploaded when first needed;
     * both stay resident only while auto's tuner measures them. */
    bool resident[2];
    GLuint material_ubos[2];
    bool arrays;                 /* this frame draws with the array path's */
    mvr_batch_plan plan;         /* array path: texture groups and material slots */
    GLuint *group_textures;      /* one GL_TEXTURE_2D_ARRAY per plan group */
    GLuint *group_samplers;
    uint32_t material_count;
    GLuint material_ubo;         /* this frame's: material_ubos[arrays] */
    uint32_t material_pages;
    GLsizeiptr material_page_stride; /* bytes between pages (aligned) */
    /* images stored smaller than the scene's (too large for the GL): one
     * flag per scene image, and how many are set */
    uint8_t *downscaled;
    uint32_t downscaled_cap, downscaled_count;
    /* the same for images held block-compressed, and for images whose
     * format the GL cannot sample (drawn with their roles' neutral values) */
    uint8_t *compressed, *unsampleable;
    uint32_t compressed_cap, compressed_count, unsampleable_cap, unsampleable_count;
} mvr_gpu_scene;

/* Skins and morph targets on the GPU (gl/skinning.c): the morph deltas
 * (once per scene geometry), the frame's deformation texels (joints and
 * weights, once per frame for every view), and on the pre-skinning path
 * one captured vertex buffer per deform. */
typedef struct mvr_preskin_buffer {
    GLuint buffer, vao;
    uint32_t primitive;          /* the primitive whose vertices it holds (MVR_NO_INDEX: none) */
    uint32_t vertices;
} mvr_preskin_buffer;

typedef struct mvr_skinning {
    mvr_skinning_path requested;  /* the renderer's setting (AUTO allowed) */
    mvr_skinning_path path;       /* this frame's: VERTEX or PRESKIN */
    mvr_skinning_path tuned;      /* auto's tuner's choice for this frame (AUTO: the rule's) */
    GLuint deltas;                /* RGBA32F, rows of 2^MVR_DEFORM_WIDTH_LOG2 texels */
    uint64_t deltas_geometry;     /* the geometry version they are of (0: none) */
    GLuint data;                  /* RGBA32F, this frame's joints and weights */
    uint32_t data_rows;           /* allocated */
    mvr_preskin_buffer *buffers;  /* per frame deform (pre-skinning path) */
    uint32_t buffer_count, buffer_cap;
    uint64_t captured_key;        /* the frame key the buffers hold (0: stale) */
    /* a complete 1x1 framebuffer bound during the capture: a draw with the
     * rasterizer off still fails without one (GL_INVALID_FRAMEBUFFER_OPERATION
     * on surfaceless contexts, which have no default framebuffer) */
    GLuint capture_fbo, capture_color;
} mvr_skinning;

/* Uniform data of one frame goes into one segment of a ring buffer; a fence
 * per segment keeps the CPU from overwriting what the GPU still reads. */
#define MVR_RING_SEGMENTS 3
typedef struct mvr_ring {
    GLuint buffer;
    GLsizeiptr static_size;      /* a region before the segments: per-draw blocks and lights,
                                    re-sent only when they change (same buffer as the views:
                                    binds of another buffer's ranges cost more in Mesa) */
    GLsizeiptr segment_size;
    uint32_t current;
    GLsync fences[MVR_RING_SEGMENTS];
} mvr_ring;

typedef struct mvr_fbo_entry {
    uint32_t base, count;        /* layers; count 0 = a single-layer (non-multiview) FBO */
    bool output;                 /* the color array alone (supersampled targets: the resolve's) */
    bool msaa;                   /* multisampled multiview (count > 0), or one multisampled layer to read */
    uint8_t aux;                 /* 0, or MVR_FBO_HDR / MVR_FBO_LUMINANCE / MVR_FBO_LUMINANCE_TOP */
    GLuint fbo;
} mvr_fbo_entry;

/* The extra outputs' arrays of a target: colour attachment k + 1 and the
 * shader's location k + 1 (core/shader_gen.h MVR_SHADER_OUT_*). */
enum { MVR_TARGET_OUTPUT_GEOMETRY = 0, MVR_TARGET_OUTPUT_NORMAL, MVR_TARGET_OUTPUT_IDS, MVR_TARGET_OUTPUT_ARRAYS };

struct mvr_target {
    mvr_renderer *renderer;      /* NULL once the renderer (or its context) is destroyed */
    mvr_target *next;            /* in renderer->targets */
    mvr_target_desc desc;
    GLenum internal_format;
    GLuint color, depth;
    bool owns_color;
    mvr_fbo_entry *fbos;
    uint32_t fbo_count, fbo_cap;
    /* multisampling (desc.samples > 1): one view's color and depth, resolved
     * into its layer after its pass */
    GLuint msaa_fbo, msaa_color, msaa_depth;
    /* multisampled multiview, where the GL has it: the GL resolves
     * (render to texture), or these arrays are resolved layer by layer */
    mvr_msaa_multiview_mode msaa_multiview; /* (core/frame_plan.h) */
    GLuint msaa_array_color, msaa_array_depth;
    mvr_anti_aliasing anti_aliasing; /* resolved: NONE, MSAA or SUPERSAMPLE */
    /* HDR frames (a post pass): views draw into hdr_color (RGBA16F, or the
     * supersampled array, already float); auto-exposure reduces log2
     * luminance through lum's mip levels. Made on first use. */
    bool hdr_frame;
    GLuint hdr_color;
    GLuint msaa_hdr_color, msaa_hdr_fbo; /* multisampled HDR frames */
    GLuint lum;
    uint32_t lum_levels;
    double last_auto_exposure;   /* pre-exposure of the next auto-exposed frame (0 = none yet) */
    /* supersampling (desc.supersample > 1): views are drawn into these (N
     * times the size, linear float) and resolved into the color array */
    GLuint ss_color;
    GLenum ss_format;
    /* extra outputs (desc.outputs): the arrays behind colour attachments
     * 1..3 of every view framebuffer (0 = not asked for) */
    GLuint output_arrays[MVR_TARGET_OUTPUT_ARRAYS];
    uint32_t shader_outputs;     /* MVR_SHADER_OUT_GEOMETRY / _NORMAL / _IDS they give */
};

typedef struct mvr_timer {
    GLuint queries[2];
    bool pending;
    bool timestamps;             /* GL_TIMESTAMP counters usable */
} mvr_timer;

/* Shadow maps: one depth array shared by every view, drawn once per frame
 * (gl/shadows.c), with the plan of the frame that drew it. */
#define MVR_SHADOW_FBOS 32
typedef struct mvr_shadow_maps {
    GLuint depth;                /* GL_TEXTURE_2D_ARRAY, DEPTH_COMPONENT32F */
    GLuint color;                /* R8 array: multiview passes keep a color attachment (masked) */
    uint32_t size, layers;       /* allocated */
    GLuint sampler;              /* linear, comparison (GEQUAL reversed-Z, LEQUAL standard) */
    GLenum compare;
    struct { uint32_t base, count; GLuint fbo; } fbos[MVR_SHADOW_FBOS];
    uint32_t fbo_count;
    mvr_shadow_desc settings;    /* resolved, this frame */
    mvr_shadow_plan plan;        /* this frame's */
} mvr_shadow_maps;

/* An environment prefiltered for this renderer (gl/environment.c): made
 * when a render meets an environment whose serial differs, kept until then. */
typedef struct mvr_gpu_environment {
    uint64_t serial;             /* the environment's pixels these are of; 0 = none */
    GLuint source;               /* cube map RGBA16F with mips: the sharp background, the prefilter's input */
    uint32_t source_size, source_levels;
    GLuint specular;             /* cube map RGBA16F: level k = GGX of roughness k / (levels - 1) */
    uint32_t specular_size, specular_levels;
    GLuint cube_sampler;         /* trilinear, clamped */
    GLuint dfg;                  /* the DFG table, RG16F, once per renderer */
    GLuint dfg_sampler;
    /* KHR_materials_sheen, only for a frame with sheen: */
    GLuint charlie;              /* cube map RGBA16F, as specular: level k = Charlie of sheen roughness
                                    k / (levels - 1) */
    uint64_t charlie_serial;     /* the environment it is of; 0 = none */
    GLuint sheen_lut;            /* the sheen albedo table (core/sheen_lut.c), RG16F, once per renderer */
} mvr_gpu_environment;


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
    uint32_t failures;           /* calls of mvr_renderer_fail (did a step record its message?) */
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

mvr_result mvr_renderer_fail(mvr_renderer *r, mvr_result result, const char *fmt, ...) MVR_PRINTF(3, 4);

/* Every public call that touches GL starts with begin (the renderer's
 * context alive and current, the application's pending GL errors dropped)
 * and ends with end, which fails the call if mvr's own work left a GL error
 * (release builds too), so no call returns MVR_OK with one pending. */
mvr_result mvr_renderer_begin(mvr_renderer *r, const char *where);
mvr_result mvr_renderer_end(mvr_renderer *r, const char *where, mvr_result res);

/* After a GL allocation (storage of a texture, buffer or renderbuffer, or a
 * framebuffer's attachments): fails naming the object (printf-style), with
 * MVR_ERROR_OUT_OF_MEMORY for GL_OUT_OF_MEMORY, else MVR_ERROR_GL. */
mvr_result mvr_renderer_check_alloc(mvr_renderer *r, const char *fmt, ...) MVR_PRINTF(2, 3);

/* Deletes a GL object of the renderer's (forgotten by the state cache) and
 * zeroes *name: now when the context is current, later when it is not,
 * never once the context is gone. */
void mvr_renderer_delete(mvr_renderer *r, mvr_gl_object kind, GLuint *name);

/* A mesh variant as this renderer's blocks lay out: features, views (0 =
 * loop), its material table and per-draw block sizes; no lights. */
mvr_shader_variant mvr_renderer_mesh_variant(const mvr_renderer *r, uint32_t features, uint32_t num_views);

/* Program of a variant, compiled on first use. */
mvr_result mvr_renderer_program(mvr_renderer *r, const mvr_shader_variant *v, mvr_program_entry **out);

/* gpu_scene.c: uploads what changed in the scene (geometry, textures,
 * materials) and the representation of the materials this frame's material
 * path draws with; keep_both: the other stays resident (auto's tuner is
 * measuring both), else it is released. */
mvr_result mvr_gpu_scene_sync(mvr_renderer *r, const mvr_scene *scene, bool keep_both);
void mvr_gpu_scene_release(mvr_renderer *r);

/* The last frame's timer queries into stats.gpu_ms (waits for them; -1 when
 * disjoint); the context current and a frame's queries pending. */
void mvr_renderer_read_timer(mvr_renderer *r);

/* tuning.c: the view path this frame runs (prior: the caps rule's choice
 * for auto, or the path asked for; tune_view: auto, and both paths can draw
 * this frame) and its skinning path (r->skinning.tuned); after the frame,
 * what to measure and the stats' auto_choice / auto_skinning. */
mvr_view_path mvr_tuning_choose(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t,
                                mvr_view_path prior, bool tune_view);
void mvr_tuning_end_frame(mvr_renderer *r, mvr_view_path ran, bool ok);

/* targets.c: a framebuffer for layers [base, base + count) (multiview when
 * count > 0) or one layer (count = 0), created on first use: the one views
 * are drawn into (color and depth; a supersampled target's own arrays), or
 * with output the color array alone (what is read back, and what a
 * supersample resolve writes). */
mvr_result mvr_target_framebuffer(mvr_target *t, uint32_t base, uint32_t count, GLuint *out);
mvr_result mvr_target_output_framebuffer(mvr_target *t, uint32_t base, uint32_t count, GLuint *out);
enum { MVR_FBO_HDR = 1, MVR_FBO_LUMINANCE = 2, MVR_FBO_LUMINANCE_TOP = 3, MVR_FBO_OUTPUT_ARRAY = 4 /* + k */ };
/* outputs.c: where an extra output lives: its array (MVR_TARGET_OUTPUT_*,
 * ARRAYS for colour), its first channel and channel count in the 4 x 32-bit
 * texels, and the format and type GLES always reads that array with. The
 * synchronous and the asynchronous readback both read through it. */
typedef struct mvr_output_place {
    uint32_t array, first, count;
    GLenum gl_format, gl_type;
} mvr_output_place;
mvr_output_place mvr_output_place_of(mvr_output output);
/* Extra outputs: one layer of output array k alone (what read_output reads). */
mvr_result mvr_target_output_array_framebuffer(mvr_target *t, uint32_t k, uint32_t layer, GLuint *out);
/* Which colour attachments of the bound view framebuffer are drawn: the
 * colour (MVR_DRAW_COLOR), the extra outputs (MVR_DRAW_OUTPUTS) or both
 * (the framebuffer's own setting, which every sub-pass leaves behind). */
enum { MVR_DRAW_COLOR = 1, MVR_DRAW_OUTPUTS = 2, MVR_DRAW_ALL = 3 };
void mvr_target_draw_buffers(mvr_target *t, int which);
/* HDR frames: makes hdr_color (and the multisampled HDR renderbuffer). */
mvr_result mvr_target_ensure_hdr(mvr_target *t);
/* Auto-exposure: the log-luminance array; framebuffers of its level 0
 * (layers [base, base + count), multiview when count > 0) or of one layer's
 * last level (MVR_FBO_LUMINANCE_TOP, count 0). */
mvr_result mvr_target_luminance_framebuffer(mvr_target *t, int kind, uint32_t base, uint32_t count, GLuint *out);

/* Multisampled multiview (t->msaa_multiview): the framebuffer views
 * [base, base + count) are drawn into (count > 1), or (count 0) one
 * multisampled layer to resolve from (the array mode). */
mvr_result mvr_target_msaa_framebuffer(mvr_target *t, uint32_t base, uint32_t count, GLuint *out);
/* readback_async.c: releases every readback's GL objects and detaches it. */
void mvr_readbacks_release(mvr_renderer *r);
/* Releases the target's GL objects (mvr_renderer_delete) and keeps its memory. */
void mvr_target_release_gl(mvr_target *t);
/* The size views are drawn at: the layer size times the supersample factor. */
uint32_t mvr_target_factor(const mvr_target *t);

/* shadows.c: plans this frame's shadow layers (r->shadows.plan) */
void mvr_shadows_plan(mvr_renderer *r, const mvr_view_set *views, const mvr_target *t, const mvr_render_desc *desc);
/* Draws the planned layers: caster matrices in a view block at views_at,
 * per-draw blocks from draws_at (the ring's static region). */
mvr_result mvr_shadows_draw(mvr_renderer *r, GLintptr views_at, GLintptr draws_at);
/* Binds the maps and the receiver block (at block_at) for the view passes. */
void mvr_shadows_bind(mvr_renderer *r, GLintptr block_at);
void mvr_shadows_release(mvr_renderer *r);

/* environment.c: prefilters a new environment (nothing when it is the one
 * already prefiltered, or NULL); binds its maps for the mesh programs; sets
 * a program's environment uniforms; draws the background of one pass (its
 * views: num_views multiview, 0 = one view at view_base) after the opaque
 * geometry; releases the maps. */
/* sheen: also the Charlie chain (a frame with KHR_materials_sheen) */
mvr_result mvr_environment_sync(mvr_renderer *r, const mvr_environment *env, bool sheen);
void mvr_environment_bind(mvr_renderer *r, bool reference);
/* Whether a frame with this environment must prefilter first. */
bool mvr_environment_stale(const mvr_renderer *r, const mvr_environment *env, bool sheen);
/* KHR_materials_sheen: the albedo table (made once) and, with an
 * environment, the Charlie cube map, on their units. */
mvr_result mvr_sheen_lut_sync(mvr_renderer *r);
void mvr_sheen_bind(mvr_renderer *r, bool environment);
void mvr_environment_set_uniforms(mvr_renderer *r, const mvr_program_entry *e, const mvr_environment *env,
                                  uint32_t samples);
mvr_result mvr_environment_draw_background(mvr_renderer *r, const mvr_render_desc *desc, uint32_t num_views,
                                           int32_t view_base, bool srgb_output, float exposure);
void mvr_environment_release(mvr_renderer *r);
/* The luminance of a white Lambertian surface, averaged over directions. */
double mvr_environment_average_diffuse(const mvr_environment *env);

/* A pass's views: mvr_view_chunk of core/frame_plan.h (the frame plan
 * splits the view set into these; a loop-path chunk is one view). */

/* post.c: full-screen composite passes reading `source` (bound to the
 * composite unit, with the state such passes need): per chunk one
 * multiview pass over its layers (multiview) or one pass per view, into the
 * target's output layers, or (luminance) level 0 of its log-luminance
 * array. post_mul: per view, exposure / pre-exposure (MVR_FEATURE_POST),
 * else NULL. Each pass adds 1 to *passes. */
mvr_result mvr_full_screen_passes(mvr_renderer *r, mvr_target *t, GLuint source, const mvr_view_chunk *chunks,
                                  uint32_t chunk_count, bool multiview, uint32_t features, const float *post_mul,
                                  bool luminance, uint32_t *passes);
/* The state of an attributeless full-screen triangle: no depth, blend,
 * culling or scissor, all colour channels, the empty vertex array. */
void mvr_full_screen_state(mvr_renderer *r);
/* The HDR frame's final passes (exposure, tone map, encode), with
 * auto-exposure's luminance reduction first. chunks: as the views' passes. */
bool mvr_post_needed(const mvr_render_desc *desc);
/* The pre-exposure the lighting pass multiplies by (keeps half floats in range). */
double mvr_post_pre_exposure(mvr_renderer *r, const mvr_target *t, const mvr_render_desc *desc);
mvr_result mvr_post_run(mvr_renderer *r, mvr_target *t, const mvr_view_set *views, const mvr_render_desc *desc,
                        const mvr_view_chunk *chunks, uint32_t chunk_count, bool multiview, double pre_exposure);

/* skinning.c: the morph deltas of a scene's geometry (after its upload);
 * this frame's path, deformation texels and, on the pre-skinning path, the
 * capture pass (frame_changed: the frame was rebuilt, so joints or weights
 * may have moved; nothing is sent or captured otherwise); the vertex array
 * a draw of a deform uses (0: the primitive's own). */
mvr_result mvr_skinning_sync_scene(mvr_renderer *r, const mvr_scene *scene);
mvr_skinning_path mvr_skinning_choose(const mvr_renderer *r, const mvr_scene *scene, uint32_t views);
/* auto's rule (the tuner's prior): pre-skinning above one view */
mvr_skinning_path mvr_skinning_rule(uint32_t views);
mvr_result mvr_skinning_frame(mvr_renderer *r, bool frame_changed);
mvr_result mvr_skinning_capture(mvr_renderer *r);
GLuint mvr_skinning_vao(const mvr_renderer *r, const mvr_draw *d);
void mvr_skinning_release(mvr_renderer *r);

/* transmission.c: the chunk of rec's opaque views into the transmission
 * array (its mips generated), the draw framebuffer resume_fbo bound again
 * after; loop_msaa_fbo: the multisampled renderbuffers a one-view MSAA
 * chunk draws into. block_base: the first view of the chunk's view block. */
mvr_result mvr_transmission_copy(mvr_renderer *r, mvr_target *t, const mvr_frame_plan *plan,
                                 const mvr_plan_record *rec, int32_t block_base, GLuint loop_msaa_fbo,
                                 GLuint resume_fbo);
/* A transmissive program's uniforms for the last copy. */
void mvr_transmission_set_uniforms(mvr_renderer *r, mvr_program_entry *e);
void mvr_transmission_release(mvr_renderer *r);

/* passes.c */
/* Binds the textures of the roles in `features` a draw samples (array
 * path: its groups' arrays, marking them in groups_used when given; else
 * its material's 2D textures). */
void mvr_bind_draw_textures(mvr_renderer *r, const mvr_draw *d, uint32_t features, uint8_t *groups_used,
                            uint32_t *groups_used_count);
/* Face culling for the draw's winding and sidedness, its vertex array, and
 * the draw command for `instances` consecutive per-draw blocks. */
void mvr_submit_draw(mvr_renderer *r, const mvr_draw *d, uint32_t instances);
mvr_result mvr_renderer_draw_frame(mvr_renderer *r, const mvr_scene *scene, const mvr_view_set *views,
                                   mvr_target *target, const mvr_render_desc *desc, mvr_view_path path);

/* Ring: room for `size` bytes of this frame's uniform data; the offset is
 * aligned to the GL's uniform buffer offset alignment. Sets *reallocated when
 * the buffer was replaced (the static region's contents are then gone). */
mvr_result mvr_ring_begin_frame(mvr_renderer *r, GLsizeiptr size, bool *reallocated);
/* Makes the static region at least `size` bytes (reallocating the ring;
 * *reallocated says so). */
mvr_result mvr_ring_reserve_static(mvr_renderer *r, GLsizeiptr size, bool *reallocated);
void mvr_ring_end_frame(mvr_renderer *r);

#endif
