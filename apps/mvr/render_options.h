/* mvr render's options as parsed (render_options.c) and what posed its
 * frames: shared by the command (cmd_render.c) and what it writes
 * (render_output.c). */
#ifndef MVR_APP_RENDER_OPTIONS_H
#define MVR_APP_RENDER_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>

#include "camera_file.h"
#include "cli_env.h"
#include "render_files.h"
#include "run_options.h"
#include "mvr/mvr.h"

/* --readback: how the views come back from the GL and go to files. */
typedef enum render_readback {
    RENDER_READBACK_STREAM = 0,  /* chunks of GL_MAX_VIEWS_OVR views through a ring of targets, read
                                    asynchronously, encoded on threads (render_stream.c) */
    RENDER_READBACK_SYNC         /* one target of every view, each layer read and written in turn */
} render_readback;

typedef struct render_options {
    mvr_context_desc context;
    const char *demo;
    const char *scene_file;
    int camera;                  /* -1 = frame the scene with layout */
    mvr_view_layout layout;
    double ipd;
    /* camera sampling of --layout (render_sampling.c: --fov, --radius, --margin,
     * --hemisphere, --seed, --min-spacing, --elevation, --up); its layout, views,
     * ipd and aspect are the fields above */
    mvr_framing_desc framing;
    bool elevation_single;       /* --elevation DEG (stereo, ring, grid), not MIN,MAX */
    uint32_t gltf_scene;         /* 1-based; 0 = the file's default */
    const char *variant;         /* --variant NAME|K: a material variant; NULL = the file's own materials */
    uint32_t views, width, height, frames;
    const char *out_dir;
    const char *stats_file;
    bool plan;                   /* --plan */
    bool colmap;                 /* --colmap */
    /* the dataset's files (dataset.h): --split TRAIN,VAL[,TEST] fractions
     * (summing to 1), --normalize (poses into instant-ngp's unit cube) */
    double split[3];
    bool split_set, normalize;
    uint32_t outputs;            /* --outputs: mvr_target_desc.outputs (0 = colour alone) */
    double depth_png_scale;      /* scene units per step of a 16-bit depth PNG (depth_VVVV.png): set
                                    per run before the first view is written (0 = not yet) */
    uint32_t output_files;       /* --output-files: RENDER_AOV_* bits (render_aovs.h); 0 = npy,png */
    mvr_view_path view_path;
    mvr_material_path material_path;
    mvr_depth_mode depth_mode;
    mvr_transparency_order transparency;
    uint32_t supersample;        /* samples per pixel side; 1 = none */
    uint32_t msaa;               /* multisample count; 0 = none */
    mvr_anti_aliasing aa;        /* --aa: the library's anti-aliasing choice */
    bool exposure_set, tone_map_set, layout_set;
    mvr_tone_map tone_map;       /* --tone-map, when tone_map_set */
    cli_env_options env;
    bool reference;
    mvr_color_format format;
    bool format_set;
    bool exr;                    /* output EXR (linear float) instead of PNG */
    mvr_render_desc render;
    const char *program_cache;   /* directory; NULL = the user's cache directory; "off" = none */
    bool quiet;
    bool strict;                 /* glTF: missing or undecodable images are errors */
    uint64_t memory_budget;      /* glTF load budget in bytes; 0 = the loader's default */
    /* animation: --animation NAME|K|all at --time (+ k / --fps for frame k
     * of --frames); none given = the file's rest pose */
    const char *animation;
    double time, fps;
    bool time_set, loop, frames_set;
    const char *video;           /* --video FILE: each view's sequence through ffmpeg */
    char ffmpeg[4096];           /* with video: the ffmpeg found on PATH */
    mvr_skinning_path skinning;
    render_readback readback;    /* --readback */
    bool no_progress;            /* --no-progress */
    uint32_t encoders;           /* --encoders N: image encoding threads of the stream (0 = 2) */
    /* --cameras FILE: its views (owned by the command), instead of a camera
     * or a layout; size_set: --size was given (else the file's size wins) */
    const char *cameras_file;
    const mvr_view_desc *camera_views;
    uint32_t camera_count;
    const char *camera_format;   /* camera_file.format */
    bool size_set;
    /* several SCENE files (arguments and --list FILE): keep_going skips one
     * that fails instead of stopping there */
    const char *list_file;
    bool keep_going;
    render_run_options run;      /* --shard, --resume, --serve, ... (run_options.h) */
    /* one unit of a sharded run (run_units.c): only views [view_first,
     * view_end) of frames [frame_first, frame_end) are written, and none
     * of the file's own files (contact sheet, cameras, dataset files) */
    bool unit;
    uint32_t view_first, view_end, frame_first, frame_end;
} render_options;

/* The SCENE arguments and --list's, and the --cameras file's views. */
typedef struct render_inputs {
    render_file_list files;
    camera_file cameras;
    /* the arguments that decide what the run writes (all but --out, --quiet,
     * --shard, --resume, ...): plan.json's "args"; pointers into argv */
    const char **plan_args;
    uint32_t plan_arg_count;
} render_inputs;

/* argv (after "render") into o and in, checked: MVR_EXIT_OK, -1 after
 * --help (printed: nothing to run), or the exit code of a usage error
 * (printed). in is zeroed by the caller and freed by it either way. */
int render_options_parse(int argc, char **argv, render_options *o, render_inputs *in);

/* How the frames were read back and written: the summary and the stats. */
typedef struct render_readback_info {
    render_readback mode;
    uint32_t chunk;              /* stream: views per chunk (per target of the ring) */
    uint32_t ring;               /* stream: targets (and readbacks) in the ring */
    uint32_t encoders;           /* stream: encoding threads */
    uint32_t sheet_factor;       /* stream: contact sheet tiles 1/N of a view's size (1 = full size) */
    bool exposure_metered;       /* stream: auto-exposure metered over every view first, then fixed */
    double exposure_ev100;       /* the EV100 it fixed */
    bool shadows_per_chunk;      /* stream: directional shadow cascades fitted to each chunk's views */
    const uint32_t *culled_per_view; /* stream: the last frame's, per view; NULL: the renderer's */
    uint64_t images;             /* view images written */
    double seconds;              /* from the first render to the last file written (the contact sheet) */
} render_readback_info;

/* What posed the frames (for the summary and the stats). */
typedef struct render_animation {
    bool applied;                /* an animation posed the scene */
    uint32_t index;              /* or MVR_ANIMATION_ALL */
    char label[192];             /* cli_animation_label */
    double first_time, last_time;
    double start, end;           /* its clip */
} render_animation;

#endif
