/* mvr render's options: the table (name, value kind and range, help,
 * conflicts), the help printed from it, and the parse that turns argv into
 * render_options and checks their combination; running them is
 * cmd_render.c's. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "cli_options.h"
#include "cli_env.h"
#include "cli_scene.h"
#include "commands.h"
#include "render_options.h"
#include "render_aovs.h"
#include "render_output.h"
#include "render_sampling.h"

enum {
    R_DEMO = 1, R_VIEWS, R_CAMERA, R_LAYOUT, R_IPD, R_SCENE, R_SIZE, R_OUT, R_VIEW_PATH, R_MATERIAL_PATH, R_DEPTH,
    R_TRANSPARENCY, R_SUPERSAMPLE, R_MSAA, R_AA, R_REFERENCE, R_FORMAT, R_TARGET_FORMAT, R_SHADOWS, R_SHADOW_SIZE,
    R_EXPOSURE, R_EXPOSURE_SCALE, R_CAMERA_EXPOSURE, R_EXPOSURE_PER_VIEW, R_DITHER, R_CLEAR, R_TONE_MAP, R_FRAMES,
    R_STATS, R_STRICT, R_MEMORY_BUDGET, R_PROGRAM_CACHE, R_QUIET, R_PLAN, R_ANIMATION, R_TIME, R_LOOP, R_FPS, R_VIDEO,
    R_SKINNING, R_VARIANT, R_COLMAP, R_OUTPUTS, R_NORMAL_SPACE, R_ALPHA_CUTOFF, R_READBACK, R_NO_PROGRESS, R_ENCODERS,
    R_CAMERAS, R_LIST, R_KEEP_GOING, R_SPLIT, R_NORMALIZE,
    R_OUTPUT_FILES
};

#define MAX_FRAMES 100000

#define EXPOSURE_GROUP "the exposure"
#define AA_GROUP "the anti-aliasing"
#define REFERENCE_WHY "--reference sets the loop path, per-view transparency and 4x4 supersampling itself"
#define END {CLI_OPT_END, 0, NULL, NULL, NULL, 0, 0, NULL, NULL, NULL, NULL, NULL}

/* name, value and range, help, conflicts; the order is --help's */
static const cli_option render_table[] = {
    {CLI_OPT_STRING, R_DEMO, "--demo", NULL, "NAME", 0, 0, NULL, "stereo | cube | city | ring (default: stereo)",
     NULL, NULL, NULL},
    {CLI_OPT_U32, R_VIEWS, "--views", NULL, "N", 1, 1024, NULL,
     "number of views (default: the demo's or layout's own), 1..1024;\n"
     "--demo stereo and city frame at most 35 at 640x480 (their\n"
     "outer frusta turn toward the centre; fewer on wider layers,\n"
     "the error says how many); cube repeats its six faces", NULL, NULL, NULL},
    {CLI_OPT_U32, R_CAMERA, "--camera", NULL, "K", 0, 1u << 20, NULL,
     "SCENE: view from the file's K-th camera node (0-based);\n"
     "N views are eyes --ipd apart along its right axis\n"
     "(default: the first camera when the file has one)", NULL, "--layout",
     "--layout frames the scene without a camera"},
    {CLI_OPT_CHOICE, R_LAYOUT, "--layout", NULL, "L", 0, 0, "stereo|cube|ring|grid|sphere|orbit|random",
     "SCENE without --camera: stereo | cube | ring | grid around\n"
     "the scene, looking down from 30 degrees (--elevation) with\n"
     "its bounding box fitted (--margin) (default: stereo); sphere:\n"
     "--views spread evenly over a sphere around it (default 50);\n"
     "orbit: a turntable of 3 rings from -15 to 60 degrees (default\n"
     "24 views); random: --views at random over the sphere,\n"
     "--min-spacing apart (default 50; --seed); sphere, orbit,\n"
     "random fit the bounding box too; camera sampling: --fov ...\n"
     "--up below", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_CAMERAS, "--cameras", NULL, "FILE", 0, 0, NULL,
     "the views from a camera file: mvr's cameras.json (the same\n"
     "views again, exactly), NeRF's transforms.json, or CSV with a\n"
     "header x,y,z,qx,qy,qz,qw,fx,fy,cx,cy[,width,height,znear]\n"
     "(docs/guide.md); told apart by content; the file's image size\n"
     "is the layers' unless --size is given (then the same fields of\n"
     "view at that size)", NULL, "--camera --layout --views --ipd",
     "the camera file gives every view"},
    {CLI_OPT_STRING, R_IPD, "--ipd", NULL, "M", 0, 0, NULL,
     "distance between stereo eyes in scene units (default: 1/30 of\n"
     "the distance to the scene: 0.064 at 1.9)", NULL, NULL, NULL},
    {CLI_OPT_U32, R_SCENE, "--scene", NULL, "K", 0, 1u << 20, NULL,
     "SCENE: the file's K-th scene (0-based; default: its default)", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_VARIANT, "--variant", NULL, "V", 0, 0, NULL,
     "SCENE: draw material variant V (KHR_materials_variants): its\n"
     "name, or its index (0-based) when no variant has that name;\n"
     "mvr info FILE lists them (default: the file's own materials)", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_SIZE, "--size", NULL, "WxH", 0, 0, NULL, "layer size in pixels (default: 640x480)", NULL,
     NULL, NULL},
    {CLI_OPT_STRING, R_OUT, "--out", NULL, "DIR", 0, 0, NULL,
     "output directory (default: out), created if missing; besides\n"
     "the images: cameras.json (each view's intrinsics, extrinsics and\n"
     "projection, conventions stated) and transforms.json (NeRF's\n"
     "layout), of the first frame's views",
     NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_VIEW_PATH, "--view-path", NULL, "P", 0, 0, "auto|multiview|loop",
     "auto | multiview | loop (default: auto; MVR_VIEW_PATH wins)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_MATERIAL_PATH, "--material-path", NULL, "P", 0, 0, "auto|arrays|per_material|per_draw",
     "auto | arrays | per_material | per_draw (default: auto = arrays;\n"
     "MVR_MATERIAL_PATH wins)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_DEPTH, "--depth", NULL, "D", 0, 0, "auto|reversed_z|standard",
     "auto | reversed_z | standard (default: auto = reversed_z\n"
     "where GL_EXT_clip_control exists; MVR_DEPTH wins)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_TRANSPARENCY, "--transparency", NULL, "T", 0, 0, "auto|centroid|per_view",
     "auto | centroid | per_view: blended draws in one order for\n"
     "all views of a multiview pass (from their centroid), or each\n"
     "view's own (its blend pass apart); auto: own order only where\n"
     "the views disagree (default: auto)", NULL, NULL, NULL},
    {CLI_OPT_U32, R_SUPERSAMPLE, "--supersample", NULL, "N", 1, 4, NULL,
     "render N x N samples per pixel into a float target and\n"
     "average them (1..4; default: 1)", AA_GROUP, NULL, NULL},
    {CLI_OPT_U32, R_MSAA, "--msaa", NULL, "N", 0, 64, NULL,
     "N samples per pixel (multisampling; resolves view by view,\n"
     "so it takes the loop path) (default: --aa's)", AA_GROUP, NULL, NULL},
    {CLI_OPT_CHOICE, R_AA, "--aa", NULL, "A", 0, 0, "none|msaa|supersample|auto",
     "none | msaa | supersample | auto: the library's anti-aliasing\n"
     "(msaa 4x, supersample 2x2 on the GPU; auto: 4x MSAA, in the\n"
     "multiview passes where the GL has multisampled multiview)\n"
     "(default: auto; none with --outputs)", AA_GROUP, NULL, NULL},
    {CLI_OPT_FLAG, R_REFERENCE, "--reference", NULL, NULL, 0, 0, NULL,
     "ground truth, slow: --view-path loop --transparency per_view\n"
     "--supersample 4, and the environment integrated per pixel\n"
     "(1024 samples per lobe) instead of its prefiltered maps", NULL,
     "--view-path --transparency --supersample --msaa --aa", REFERENCE_WHY},
    {CLI_OPT_CHOICE, R_FORMAT, "--format", NULL, "F", 0, 0, "png|exr",
     "png (8-bit sRGB) | exr (half float, linear) (default: png)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_TARGET_FORMAT, "--target-format", NULL, "F", 0, 0, "srgb8|rgba8|rgba16f",
     "srgb8 | rgba8 | rgba16f (default: srgb8; rgba16f for exr)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_SHADOWS, "--shadows", NULL, "S", 0, 0, "default|all|off",
     "default | all | off: shadow maps for the lights that ask\n"
     "(glTF has no such flag, so none), for every directional\n"
     "and spot light, or none (default: default)", NULL, NULL, NULL},
    {CLI_OPT_U32, R_SHADOW_SIZE, "--shadow-size", NULL, "N", 16, 16384, NULL,
     "shadow map texels per side (default: 1024)", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_EXPOSURE, "--exposure", NULL, "E", 0, 0, NULL,
     "auto | an EV100 (physical camera exposure; default: auto\n"
     "when the lights are in physical units, e.g. a sun of\n"
     "thousands of lux, else a linear 1)", EXPOSURE_GROUP, NULL, NULL},
    {CLI_OPT_STRING, R_EXPOSURE_SCALE, "--exposure-scale", NULL, "X", 0, 0, NULL,
     "linear exposure multiplier instead (default: 1)", EXPOSURE_GROUP, NULL, NULL},
    {CLI_OPT_STRING, R_CAMERA_EXPOSURE, "--camera-exposure", NULL, "N,T,ISO", 0, 0, NULL,
     "physical exposure of a camera: f-number,\n"
     "shutter seconds, ISO (e.g. 16,0.008,100)", EXPOSURE_GROUP, NULL, NULL},
    {CLI_OPT_FLAG, R_EXPOSURE_PER_VIEW, "--exposure-per-view", NULL, NULL, 0, 0, NULL,
     "auto-exposure per view (default: one for all views)", NULL, "--exposure-scale --camera-exposure",
     "--exposure-per-view is for auto exposure"},
    {CLI_OPT_FLAG, R_DITHER, "--dither", NULL, NULL, 0, 0, NULL, "+-1 step of noise before 8-bit storage (default: off)",
     NULL, NULL, NULL},
    {CLI_OPT_STRING, R_CLEAR, "--clear", NULL, "R,G,B[,A]", 0, 0, NULL, "linear clear color, a display colour (default: a dark opaque sky)",
     NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_TONE_MAP, "--tone-map", NULL, "T", 0, 0, "none|aces|pbr-neutral",
     "none | aces | pbr-neutral (default: pbr-neutral with auto\n"
     "exposure, none otherwise)", NULL, NULL, NULL},
    END,
};

/* animation, skins and morph targets */
static const cli_option render_table_animation[] = {
    {CLI_OPT_STRING, R_ANIMATION, "--animation", NULL, "A", 0, 0, NULL,
     "SCENE: pose the file with animation A: its name, its index K\n"
     "(0-based; mvr info FILE lists them) or all (every animation\n"
     "at once) (default: none, the file's rest pose; but --time,\n"
     "--loop and --frames play animation 0 when the file has one)", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_TIME, "--time", NULL, "T", 0, 0, NULL,
     "seconds on the file's animation clock, >= 0 (default: 0);\n"
     "before the clip's first key or after its last, the nearest\n"
     "key's pose", NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_LOOP, "--loop", NULL, NULL, 0, 0, NULL,
     "wrap --time into the clip [start, end) instead of holding\n"
     "its last pose after the end", NULL, NULL, NULL},
    {CLI_OPT_U32, R_FRAMES, "--frames", NULL, "N", 1, MAX_FRAMES, NULL,
     "render N frames at --time T, T + 1/F, T + 2/F, ... and write\n"
     "each: DIR/view_VVVV_fFFFF.png (view VVVV, frame FFFF from 0,\n"
     "at least 4 digits); contact_sheet.png shows the first frame\n"
     "(1..100000; default: one frame, view_VVVV.png)", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_FPS, "--fps", NULL, "F", 0, 0, NULL, "frames per second of --frames and --video, > 0 (default: 30)",
     NULL, NULL, NULL},
    {CLI_OPT_STRING, R_VIDEO, "--video", NULL, "FILE.mp4", 0, 0, NULL,
     "with --frames: also encode each view's sequence at --fps\n"
     "with ffmpeg (on PATH) into FILE.mp4 (one view) or\n"
     "FILE_view_VVVV.mp4 (several)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_SKINNING, "--skinning", NULL, "S", 0, 0, "auto|vertex|preskin",
     "auto | vertex | preskin: where skinning and morphing run (in\n"
     "each pass's vertex shader, or once per frame by transform\n"
     "feedback; same pixels) (default: auto; MVR_SKINNING_PATH wins)", NULL, NULL, NULL},
    END,
};

static const cli_option render_table_tail[] = {
    {CLI_OPT_STRING, R_STATS, "--stats", NULL, "FILE.json", 0, 0, NULL, "write the last frame's stats as JSON", NULL,
     NULL, NULL},
    {CLI_OPT_STRING, R_OUTPUTS, "--outputs", NULL, "LIST", 0, 0, NULL,
     "also write each view's depth, distance, normal, ids, coverage\n"
     "(a comma list, or all) as NumPy files DIR/depth_VVVV.npy ...:\n"
     "float32 H x W (depth along the camera's -Z, ray distance,\n"
     "coverage), float32 H x W x 3 (normal), uint32 H x W x 4 (node,\n"
     "mesh, material, primitive ids); 0 where nothing is; rows top\n"
     "to bottom, as the images", NULL, "--msaa --supersample --aa --reference",
     "extra outputs are not averaged: they need a target without anti-aliasing"},
    {CLI_OPT_STRING, R_OUTPUT_FILES, "--output-files", NULL, "LIST", 0, 0, NULL,
     "the files of --outputs, a comma list (default: npy,png): npy;\n"
     "png: depth_VVVV.png (16-bit, depth / scale), mask_VVVV.png,\n"
     "ids_<kind>_VVVV.png (16-bit), ids_preview_VVVV.png; exr:\n"
     "depth_VVVV.exr (float Z); layers: layers_VVVV.exr (R G B A,\n"
     "Z, N.X N.Y N.Z, id.node ...)", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_NORMAL_SPACE, "--normal-space", NULL, "S", 0, 0, "world|camera",
     "world | camera: the space of --outputs normal (default: world;\n"
     "camera: OpenGL's, x right, y up, +Z towards the viewer)", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_ALPHA_CUTOFF, "--alpha-cutoff", NULL, "A", 0, 0, NULL,
     "--outputs: a blended surface is recorded where its alpha is at\n"
     "least A, in (0, 1] (default: 0.5; below: seen through)", NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_COLMAP, "--colmap", NULL, NULL, 0, 0, NULL,
     "also write COLMAP's text model of the views into DIR/colmap:\n"
     "cameras.txt (PINHOLE), images.txt (world-to-camera poses),\n"
     "points3D.txt (surface points sampled from --outputs depth,\n"
     "each with its colour and the views that see it; empty without\n"
     "depth) and their 2D points in images.txt", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_SPLIT, "--split", NULL, "T,V[,E]", 0, 0, NULL,
     "train, val[, test] fractions summing to 1 (e.g. 0.9,0.1):\n"
     "views spread evenly into transforms_train.json,\n"
     "transforms_val.json, transforms_test.json, and listed in\n"
     "transforms.json as train_filenames ... (nerfstudio)", NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_NORMALIZE, "--normalize", NULL, NULL, 0, 0, NULL,
     "transforms.json's poses, aabb and depth scale moved and scaled\n"
     "so the scene and every camera lie in [0, 1]^3 (the applied\n"
     "scale and offset stated in it)", NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_PLAN, "--plan", NULL, NULL, 0, 0, NULL,
     "print the last frame's plan: its passes in order, each with\n"
     "its views and why it runs", NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_STRICT, "--strict", NULL, NULL, 0, 0, NULL,
     "a glTF image that is missing or cannot be decoded fails the\n"
     "load (default: its textures take their defaults, warned)", NULL, NULL, NULL},
    {CLI_OPT_U32, R_MEMORY_BUDGET, "--memory-budget", NULL, "MIB", 1, 1u << 20, NULL,
     "most memory a glTF load, or decoding the --env image, may\n"
     "hold (default: 2048)", NULL, NULL, NULL},
    {CLI_OPT_STRING, R_PROGRAM_CACHE, "--program-cache", NULL, "D", 0, 0, NULL,
     "program binaries in D, so a later run compiles no shader;\n"
     "off disables it (default: $XDG_CACHE_HOME/mvr/programs or\n"
     "~/.cache/mvr/programs); D is created if missing and must be\n"
     "a directory you can write to", NULL, NULL, NULL},
    {CLI_OPT_CHOICE, R_READBACK, "--readback", NULL, "R", 0, 0, "stream|sync",
     "stream: chunks of GL_MAX_VIEWS_OVR views through a ring of\n"
     "targets, read back asynchronously, encoded on threads (memory\n"
     "bounded whatever the view count); sync: one target of every\n"
     "view, each read and written in turn (default: stream)", NULL, NULL, NULL},
    {CLI_OPT_U32, R_ENCODERS, "--encoders", NULL, "N", 1, 64, NULL,
     "image encoding threads of --readback stream (default: 2)", NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_NO_PROGRESS, "--no-progress", NULL, NULL, 0, 0, NULL,
     "no progress line (shown on a terminal: views done, views/s,\n"
     "time left)", NULL, NULL, NULL},
    {CLI_OPT_FLAG, R_QUIET, "--quiet", NULL, NULL, 0, 0, NULL, "print only errors (no progress line)", NULL, NULL,
     NULL},
    {CLI_OPT_STRING, R_LIST, "--list", NULL, "FILE", 0, 0, NULL,
     "also render the SCENE files FILE names: one path a line\n"
     "(from the current directory), '#' starts a comment; with more\n"
     "than one SCENE in all, each goes to DIR/<its name>/ (a name\n"
     "that repeats gets _K, its place in the run), with --stats and\n"
     "--video there too, in one process: one context, renderer and\n"
     "program cache; a summary at the end", NULL, "--demo", "--demo renders a built-in scene"},
    {CLI_OPT_FLAG, R_KEEP_GOING, "--keep-going", NULL, NULL, 0, 0, NULL,
     "with several SCENE files: report one that fails and go on\n"
     "(default: stop there); the exit status is the first failure's",
     NULL, NULL, NULL},
    END,
};

static const cli_option *const render_tables[] = {render_table,       render_sampling_table, cli_env_option_table,
                                                  render_table_animation, render_table_tail, render_run_table,
                                                  cli_context_options, cli_help_option,    NULL};

static void render_usage(FILE *out)
{
    fprintf(out,
            "usage: mvr render [--demo NAME | SCENE.gltf|.glb ... | --list FILE] [options]\n"
            "       mvr render --merge DIR [--quiet]   (a sharded run's merge: docs/guide.md)\n"
            "\n"
            "Renders a scene into N views headless and writes one image per view\n"
            "(view_0000.png, ...) and a contact sheet (PNG) of all views side by side;\n"
            "with --frames N, a numbered sequence per view (view_0000_f0000.png, ...).\n"
            "Several SCENE files render one after another, each into DIR/<its name>/.\n"
            "\n"
            "options:\n");
    cli_print_options(out, render_tables, 20);
}

/* A finite number, the whole string. */
static bool parse_double(const char *v, double *out)
{
    return cli_parse_double(v, out);
}

/* --split T,V[,E]: two or three fractions in [0, 1] summing to 1 */
static bool parse_split(const char *v, double split[3])
{
    char part[64];
    int count = 0;
    double sum = 0;
    split[2] = 0;
    for (const char *p = v; count < 3; ++count) {
        size_t len = strcspn(p, ",");
        if (len == 0 || len >= sizeof part)
            break;
        memcpy(part, p, len);
        part[len] = '\0';
        if (!parse_double(part, &split[count]) || !(split[count] >= 0.0 && split[count] <= 1.0))
            break;
        sum += split[count];
        p += len;
        if (*p == '\0') {
            count++;
            if (count >= 2 && fabs(sum - 1.0) <= 1e-6)
                return true;
            break;
        }
        p++;
    }
    fprintf(stderr, "mvr render: --split takes train,val[,test] fractions in [0, 1] that sum to 1 (e.g. 0.9,0.1), "
                    "not '%s'\n", v);
    return false;
}

/* What is rendered and from where: the scene, its views and the layers' size.
 * 1: applied, 0: not one of these, -1: a bad value (printed). */
static int apply_scene(const cli_arg *arg, render_options *o)
{
    const char *v = arg->value;
    switch (arg->opt->id) {
    case R_DEMO: o->demo = v; break;
    case R_VIEWS: o->views = arg->number; break;
    case R_CAMERA: o->camera = (int)arg->number; break;
    case R_SCENE: o->gltf_scene = arg->number + 1; break;
    case R_LAYOUT:
        o->layout = (mvr_view_layout)(MVR_LAYOUT_STEREO + arg->choice);
        o->layout_set = true;
        break;
    case R_IPD:
        if (!parse_double(v, &o->ipd) || !(o->ipd > 0.0)) {
            fprintf(stderr, "mvr render: --ipd takes a distance > 0\n");
            return -1;
        }
        break;
    case R_VARIANT:
        if (!v[0]) {
            fprintf(stderr, "mvr render: --variant takes a name or an index (got '')\n");
            return -1;
        }
        o->variant = v;
        break;
    case R_CAMERAS:
        if (!v[0]) {
            fprintf(stderr, "mvr render: --cameras takes a file (got '')\n");
            return -1;
        }
        o->cameras_file = v;
        break;
    case R_SIZE:
        if (!cli_parse_size(v, 1, 16384, &o->width, &o->height)) {
            fprintf(stderr, "mvr render: --size takes WxH with 1..16384 each, e.g. 640x480\n");
            return -1;
        }
        o->size_set = true;
        break;
    case R_LIST: o->list_file = v; break;
    case R_KEEP_GOING: o->keep_going = true; break;
    case R_STRICT: o->strict = true; break;
    case R_MEMORY_BUDGET: o->memory_budget = o->env.memory_budget = (uint64_t)arg->number << 20; break;
    default: return 0;
    }
    return 1;
}

/* The animation and the frames: --animation, --time, --frames, --video ...
 * 1: applied, 0: not one of these, -1: a bad value (printed). */
static int apply_animation(const cli_arg *arg, render_options *o)
{
    const char *v = arg->value;
    switch (arg->opt->id) {
    case R_FRAMES:
        o->frames = arg->number;
        o->frames_set = true;
        break;
    case R_ANIMATION:
        if (!v[0]) {
            fprintf(stderr, "mvr render: --animation takes a name, an index or all (got '')\n");
            return -1;
        }
        o->animation = v;
        break;
    case R_TIME:
        if (!parse_double(v, &o->time) || o->time < 0.0) {
            fprintf(stderr, "mvr render: --time takes seconds >= 0 (got '%s')\n", v);
            return -1;
        }
        o->time_set = true;
        break;
    case R_LOOP: o->loop = true; break;
    case R_FPS:
        if (!parse_double(v, &o->fps) || !(o->fps > 0.0)) {
            fprintf(stderr, "mvr render: --fps takes frames per second > 0 (got '%s')\n", v);
            return -1;
        }
        break;
    case R_VIDEO:
        if (!v[0]) {
            fprintf(stderr, "mvr render: --video takes a file name, e.g. out.mp4 (got '')\n");
            return -1;
        }
        o->video = v;
        break;
    case R_SKINNING: o->skinning = (mvr_skinning_path)(MVR_SKINNING_PATH_AUTO + arg->choice); break;
    default: return 0;
    }
    return 1;
}

/* The renderer's paths and the target: anti-aliasing, formats.
 * 1: applied, 0: not one of these, -1: a bad value (printed). */
static int apply_target(const cli_arg *arg, render_options *o)
{
    const char *v = arg->value;
    switch (arg->opt->id) {
    case R_PROGRAM_CACHE: o->program_cache = v; break;
    case R_VIEW_PATH: o->view_path = (mvr_view_path)(MVR_VIEW_PATH_AUTO + arg->choice); break;
    case R_MATERIAL_PATH: o->material_path = (mvr_material_path)(MVR_MATERIAL_PATH_AUTO + arg->choice); break;
    case R_DEPTH: o->depth_mode = (mvr_depth_mode)(MVR_DEPTH_MODE_AUTO + arg->choice); break;
    case R_TRANSPARENCY:
        o->transparency = (mvr_transparency_order)(MVR_TRANSPARENCY_ORDER_AUTO + arg->choice);
        break;
    case R_REFERENCE: o->reference = true; break;
    case R_MSAA: o->msaa = arg->number; break;
    case R_AA: o->aa = (mvr_anti_aliasing)(MVR_ANTI_ALIASING_NONE + arg->choice); break;
    case R_SUPERSAMPLE: o->supersample = arg->number; break;
    case R_FORMAT: o->exr = arg->choice == 1; break;
    case R_TARGET_FORMAT: {
        static const mvr_color_format formats[] = {MVR_COLOR_FORMAT_DEFAULT, MVR_COLOR_FORMAT_RGBA8,
                                                   MVR_COLOR_FORMAT_RGBA16F};
        o->format = formats[arg->choice];
        o->format_set = true;
        break;
    }
    default: return 0;
    }
    return 1;
}

/* Lighting and the image: shadows, clear colour, exposure, tone mapping.
 * 1: applied, 0: not one of these, -1: a bad value (printed). */
static int apply_lighting(const cli_arg *arg, render_options *o)
{
    const char *v = arg->value;
    switch (arg->opt->id) {
    case R_SHADOWS: o->render.shadows.mode = (mvr_shadow_mode)(MVR_SHADOWS_DEFAULT + arg->choice); break;
    case R_SHADOW_SIZE: o->render.shadows.map_size = arg->number; break;
    case R_CLEAR: {
        float rgba[4] = {0, 0, 0, 1};
        if (sscanf(v, "%f,%f,%f,%f", &rgba[0], &rgba[1], &rgba[2], &rgba[3]) < 3) {
            fprintf(stderr, "mvr render: --clear takes R,G,B[,A] (linear, 0..1)\n");
            return -1;
        }
        memcpy(o->render.clear_color, rgba, sizeof rgba);
        break;
    }
    case R_EXPOSURE:
        o->exposure_set = true;
        if (strcmp(v, "auto") == 0) {
            o->render.exposure_mode = MVR_EXPOSURE_AUTO;
        } else {
            o->render.exposure_mode = MVR_EXPOSURE_EV100;
            if (!parse_double(v, &o->render.ev100)) {
                fprintf(stderr, "mvr render: --exposure takes auto or an EV100 (e.g. 15 for sunlight)\n");
                return -1;
            }
        }
        break;
    case R_EXPOSURE_SCALE: {
        double x = 0.0;
        o->exposure_set = true;
        o->render.exposure_mode = MVR_EXPOSURE_LINEAR;
        if (!parse_double(v, &x) || !(x > 0.0) || !isfinite((float)x)) {
            fprintf(stderr, "mvr render: --exposure-scale takes a number > 0\n");
            return -1;
        }
        o->render.exposure = (float)x;
        break;
    }
    case R_CAMERA_EXPOSURE: {
        double n = 0, sh = 0, iso = 0;
        o->exposure_set = true;
        if (sscanf(v, "%lf,%lf,%lf", &n, &sh, &iso) != 3 || !(n > 0) || !(sh > 0) || !(iso > 0)) {
            fprintf(stderr, "mvr render: --camera-exposure takes f-number,shutter-seconds,ISO (e.g. 16,0.008,100)\n");
            return -1;
        }
        o->render.exposure_mode = MVR_EXPOSURE_CAMERA;
        o->render.aperture = n;
        o->render.shutter = sh;
        o->render.iso = iso;
        break;
    }
    case R_EXPOSURE_PER_VIEW: o->render.exposure_per_view = true; break;
    case R_DITHER: o->render.dither = true; break;
    case R_TONE_MAP: {
        static const mvr_tone_map maps[] = {MVR_TONE_MAP_NONE, MVR_TONE_MAP_ACES, MVR_TONE_MAP_KHR_PBR_NEUTRAL};
        o->tone_map = maps[arg->choice];
        o->tone_map_set = true;
        break;
    }
    default: return 0;
    }
    return 1;
}

/* What is written and told: the directory, stats, extra outputs, readback, progress.
 * 1: applied, 0: not one of these, -1: a bad value (printed). */
static int apply_outputs(const cli_arg *arg, render_options *o)
{
    const char *v = arg->value;
    switch (arg->opt->id) {
    case R_QUIET: o->quiet = true; break;
    case R_READBACK: o->readback = arg->choice == 1 ? RENDER_READBACK_SYNC : RENDER_READBACK_STREAM; break;
    case R_NO_PROGRESS: o->no_progress = true; break;
    case R_ENCODERS: o->encoders = arg->number; break;
    case R_OUT: o->out_dir = v; break;
    case R_STATS: o->stats_file = v; break;
    case R_PLAN: o->plan = true; break;
    case R_COLMAP: o->colmap = true; break;
    case R_NORMALIZE: o->normalize = true; break;
    case R_SPLIT:
        if (!parse_split(v, o->split))
            return -1;
        o->split_set = true;
        break;
    case R_OUTPUTS:
        if (!render_aovs_parse(v, &o->outputs))
            return -1;
        break;
    case R_OUTPUT_FILES:
        if (!render_aovs_parse_files(v, &o->output_files))
            return -1;
        break;
    case R_NORMAL_SPACE: o->render.normal_space = (mvr_normal_space)arg->choice; break;
    case R_ALPHA_CUTOFF: {
        double a = 0;
        if (!parse_double(v, &a) || !(a > 0.0 && a <= 1.0)) {
            fprintf(stderr, "mvr render: --alpha-cutoff takes a number in (0, 1]\n");
            return -1;
        }
        o->render.output_alpha_cutoff = (float)a;
        break;
    }
    default: return 0;
    }
    return 1;
}

/* One option's value into the options (the parser checked kinds and ranges). */
static bool apply(const cli_arg *arg, render_options *o)
{
    int (*const steps[])(const cli_arg *, render_options *) = {apply_scene, apply_animation, apply_target,
                                                               apply_lighting, apply_outputs};
    for (size_t k = 0; k < sizeof steps / sizeof *steps; ++k) {
        int done = steps[k](arg, o);
        if (done != 0)
            return done > 0;
    }
    return false;
}

/* --cameras: read once before any GL, its views shared by every file; the
 * file's size is the layers' unless --size was given. */
static int load_cameras(render_options *o, render_inputs *in)
{
    char why[512];
    if (!camera_file_load(o->cameras_file, o->width, o->height, &in->cameras, why, sizeof why)) {
        fprintf(stderr, "mvr render: --cameras %s: %s\n", o->cameras_file, why);
        return MVR_EXIT_USAGE;
    }
    if (in->cameras.width && !o->size_set) {
        o->width = in->cameras.width;
        o->height = in->cameras.height;
    }
    if (in->cameras.edited && !o->quiet)
        fprintf(stderr, "mvr render: --cameras %s: %u view%s (the first: view %u) no longer match%s their mvr_view: "
                        "their matrices and intrinsics are used\n", o->cameras_file, in->cameras.edited,
                in->cameras.edited == 1 ? "" : "s", in->cameras.first_edited, in->cameras.edited == 1 ? "es" : "");
    o->camera_views = in->cameras.views;
    o->camera_count = in->cameras.count;
    o->camera_format = in->cameras.format;
    return MVR_EXIT_OK;
}

/* Keeps an argument that decides what the run writes for plan.json: all
 * but the run's control, where it writes and how it reports. */
static bool keep_plan_arg(const cli_arg *arg, render_inputs *in)
{
    if (arg->opt && (render_run_option_is_control(arg->opt->id) || arg->opt->id == R_OUT ||
                     arg->opt->id == R_QUIET || arg->opt->id == R_NO_PROGRESS || arg->opt->id == R_ENCODERS ||
                     arg->opt->id == R_PROGRAM_CACHE))
        return true;
    const char **args = realloc(in->plan_args, (in->plan_arg_count + 2) * sizeof *args);
    if (!args) {
        fprintf(stderr, "mvr render: out of memory\n");
        return false;
    }
    in->plan_args = args;
    if (arg->opt)
        args[in->plan_arg_count++] = arg->opt->name;
    if (!arg->opt || arg->value)
        args[in->plan_arg_count++] = arg->value;
    return true;
}

/* The arguments into o (SCENE files into in); -1 after --help (printed). */
static int parse_args(cli_parser *p, render_options *o, render_inputs *in)
{
    cli_arg arg;
    int c;
    while ((c = cli_next(p, &arg)) > 0) {
        if (!keep_plan_arg(&arg, in))
            return MVR_EXIT_USAGE;
        if (!arg.opt) { /* a SCENE */
            if (!render_files_add(&in->files, arg.value))
                return MVR_EXIT_USAGE;
            continue;
        }
        if (arg.opt->id == CLI_ID_HELP) {
            render_usage(stdout);
            return -1;
        }
        int done = cli_context_apply("mvr render", &arg, &o->context);
        if (done == 0)
            done = cli_env_apply("mvr render", &arg, &o->env);
        if (done == 0)
            done = render_sampling_apply(&arg, o);
        if (done == 0)
            done = render_run_apply(&arg, &o->run);
        if (done == 0)
            done = apply(&arg, o) ? 1 : -1;
        if (done < 0)
            return MVR_EXIT_USAGE;
    }
    if (c < 0)
        return MVR_EXIT_USAGE;
    return MVR_EXIT_OK;
}

/* Which scene and what of it: a demo or SCENE files, --camera, --scene,
 * --animation and --variant against it. */
static int check_scene(render_options *o, render_inputs *in)
{
    if (o->list_file && !render_files_read_list(o->list_file, &in->files))
        return MVR_EXIT_USAGE;
    if (in->files.count)
        o->scene_file = in->files.paths[0]; /* the options are checked against a file */
    if (!o->scene_file && (o->camera >= 0 || o->gltf_scene)) {
        fprintf(stderr, "mvr render: --camera and --scene are for a SCENE file\n");
        return MVR_EXIT_USAGE;
    }
    if (o->demo && o->scene_file) {
        fprintf(stderr, "mvr render: give --demo NAME or a SCENE file, not both\n");
        return MVR_EXIT_USAGE;
    }
    if (!o->demo && !o->scene_file)
        o->demo = "stereo";
    o->camera = cli_scene_camera_choice(o->scene_file != NULL, o->camera, o->layout_set, o->cameras_file != NULL);
    if (!cli_context_check("render", &o->context))
        return MVR_EXIT_USAGE;
    if (!o->scene_file && o->animation) {
        fprintf(stderr, "mvr render: --animation is for a SCENE file (the demos have no animations)\n");
        return MVR_EXIT_USAGE;
    }
    if (!o->scene_file && o->variant) {
        fprintf(stderr, "mvr render: --variant is for a SCENE file (the demos have no material variants)\n");
        return MVR_EXIT_USAGE;
    }
    return MVR_EXIT_OK;
}

/* What a sharded run cannot do (each unit writes only its views' files):
 * refused with the option named. */
static int check_run(const render_options *o)
{
    const render_run_options *run = &o->run;
    if (!render_run_active(run)) {
        if (run->unit_views || run->unit_frames || run->worker) {
            fprintf(stderr, "mvr render: --unit-views, --unit-frames and --worker are for --shard, --resume, "
                            "--serve or --run-plan\n");
            return MVR_EXIT_USAGE;
        }
        return MVR_EXIT_OK;
    }
    const char *refused = o->video ? "--video (a view's sequence spans units)"
                          : o->stats_file ? "--stats (timings are per process, not per unit)"
                          : o->readback == RENDER_READBACK_SYNC ? "--readback sync (it renders every view at once)"
                          : o->exr ? "--format exr (the merge builds contact sheets from PNG views)"
                          : o->plan ? "--plan (its text would go between the records)"
                                    : NULL;
    if (refused) {
        fprintf(stderr, "mvr render: --shard, --resume, --serve and --run-plan cannot take %s\n", refused);
        return MVR_EXIT_USAGE;
    }
    return MVR_EXIT_OK;
}

/* --frames, --fps and --video together (ffmpeg found before anything is
 * rendered). */
static int check_frames(const cli_parser *p, render_options *o)
{
    if (cli_given(p, "--fps") && !o->frames_set) {
        fprintf(stderr, "mvr render: --fps is for --frames N (the time between frames)\n");
        return MVR_EXIT_USAGE;
    }
    if (o->video && !o->frames_set) {
        fprintf(stderr, "mvr render: --video needs --frames N (it encodes each view's sequence)\n");
        return MVR_EXIT_USAGE;
    }
    if (o->video && o->exr) {
        fprintf(stderr, "mvr render: --video encodes the PNG sequence: leave out --format exr\n");
        return MVR_EXIT_USAGE;
    }
    if (o->frames_set && !isfinite(o->time + (double)(o->frames - 1) / o->fps)) {
        fprintf(stderr, "mvr render: --frames %u at --fps %g from --time %g runs past any finite time\n", o->frames,
                o->fps, o->time);
        return MVR_EXIT_USAGE;
    }
    /* ffmpeg is looked for before anything is rendered */
    if (o->video && !render_output_find_on_path("ffmpeg", o->ffmpeg, sizeof o->ffmpeg)) {
        fprintf(stderr, "mvr render: --video %s: ffmpeg was not found on PATH (install it, or leave out --video: "
                        "the PNG sequence is written either way)\n", o->video);
        return MVR_EXIT_MISSING;
    }
    return MVR_EXIT_OK;
}

/* The environment, the camera file and what options imply for others
 * (--format exr, --reference, --supersample), then what needs the final
 * size (the demos' view limit) and the program cache directory. */
static int settle(render_options *o, render_inputs *in)
{
    if (!cli_env_check("mvr render", &o->env, o->scene_file != NULL))
        return MVR_EXIT_USAGE;
    if (o->cameras_file) {
        int crc = load_cameras(o, in);
        if (crc != MVR_EXIT_OK)
            return crc;
    }
    if (o->exr && !o->format_set)
        o->format = MVR_COLOR_FORMAT_RGBA16F; /* linear HDR values for EXR */
    if (o->reference) {
        o->view_path = MVR_VIEW_PATH_LOOP;
        o->transparency = MVR_TRANSPARENCY_ORDER_PER_VIEW;
        o->supersample = 4;
        o->render.environment_samples = 1024;
    }
    if (o->supersample == 0)
        o->supersample = 1;
    if (o->supersample > 1) {
        /* samples are averaged in linear float before any encoding */
        o->format = MVR_COLOR_FORMAT_RGBA32F;
        if ((uint64_t)o->width * o->supersample > 16384 || (uint64_t)o->height * o->supersample > 16384) {
            fprintf(stderr, "mvr render: --supersample %u makes a %ux%u target; the limit here is 16384\n",
                    o->supersample, o->width * o->supersample, o->height * o->supersample);
            return MVR_EXIT_USAGE;
        }
    }
    if (!o->scene_file && !o->cameras_file &&
        !cli_check_demo_views("mvr render", o->demo, o->views, o->width, o->height))
        return MVR_EXIT_USAGE;
    /* a directory given must be usable, or the run says why instead of
     * silently compiling without it */
    if (o->program_cache && strcmp(o->program_cache, "off") != 0 &&
        !cli_check_writable_dir("mvr render", "--program-cache", o->program_cache))
        return MVR_EXIT_USAGE;
    return MVR_EXIT_OK;
}

int render_options_parse(int argc, char **argv, render_options *o, render_inputs *in)
{
    memset(o, 0, sizeof *o);
    cli_logger(&o->context.logger, "render", false);
    o->width = 640;
    o->height = 480;
    o->frames = 1;
    o->fps = 30.0;
    o->out_dir = "out";
    o->camera = -1;
    cli_render_desc_defaults(&o->render); /* as mvr-viewer starts */
    cli_parser p;
    cli_parser_init(&p, "mvr render", render_tables, argc, argv);
    p.many_positionals = true;
    int rc = parse_args(&p, o, in);
    if (rc == MVR_EXIT_OK)
        rc = check_run(o);
    if (rc == MVR_EXIT_OK)
        rc = check_scene(o, in);
    if (rc == MVR_EXIT_OK)
        rc = render_sampling_check(&p, o);
    if (rc == MVR_EXIT_OK)
        rc = check_frames(&p, o);
    if (rc == MVR_EXIT_OK)
        rc = settle(o, in);
    return rc;
}
