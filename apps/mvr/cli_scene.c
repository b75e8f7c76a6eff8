/* Scenes and images shared by the commands: a demo or a glTF file with its
 * views, and layers read back as display bytes (supersampled ones resolved). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "cli_scene.h"
#include "commands.h"
#include "mvr/mvr_gltf.h"

static int load_scene_file(const char *command, const cli_scene_options *o, mvr_scene **scene, mvr_view_set **views)
{
    mvr_gltf_options go;
    memset(&go, 0, sizeof go);
    go.scene = o->gltf_scene;
    go.logger = o->logger;
    go.strict = o->strict;
    go.memory_budget = o->memory_budget;
    mvr_gltf_info info;
    mvr_error err;
    mvr_result loaded = mvr_gltf_load_file(o->scene_file, &go, scene, &info, &err);
    if (o->gltf_info)
        *o->gltf_info = info;
    if (loaded != MVR_OK) {
        fprintf(stderr, "%s: %s (%s)\n", command, err.message, mvr_result_name(err.result));
        return MVR_EXIT_FAILURE;
    }
    mvr_result r;
    if (o->given_views) {
        mvr_view_set_desc vd = {.view_count = o->given_view_count, .views = o->given_views};
        r = mvr_view_set_create(&vd, views, &err);
    } else if (o->camera >= 0 || (o->camera == CLI_CAMERA_IF_ANY && mvr_scene_camera_node_count(*scene) > 0)) {
        /* N eyes ipd apart along the camera's x axis (ipd 0: scaled to the
         * camera's distance to the scene) */
        uint32_t k = o->camera >= 0 ? (uint32_t)o->camera : 0;
        mvr_node_id node = mvr_scene_camera_node(*scene, k);
        if (!node.id) {
            fprintf(stderr, "%s: %s: the file has %u camera nodes; --camera %u is not one\n", command, o->scene_file,
                    mvr_scene_camera_node_count(*scene), k);
            return MVR_EXIT_FAILURE;
        }
        r = mvr_view_set_from_camera(*scene, node, o->views ? o->views : 2, o->ipd, views, &err);
    } else {
        /* ipd 0: the library's, scaled to the framing distance */
        mvr_framing_desc fd = {0};
        if (o->framing)
            fd = *o->framing;
        fd.layout = o->layout;
        fd.views = o->views;
        fd.ipd = o->ipd;
        fd.aspect = (double)o->width / (double)o->height;
        r = mvr_view_set_frame_scene(*scene, &fd, views, &err);
    }
    if (r != MVR_OK) {
        fprintf(stderr, "%s: %s: %s\n", command, o->scene_file, err.message);
        return MVR_EXIT_FAILURE;
    }
    return MVR_EXIT_OK;
}

void cli_render_desc_defaults(mvr_render_desc *desc)
{
    memset(desc, 0, sizeof *desc);
    desc->exposure = 1.0f;
    /* an opaque dark sky: the library's default clear is transparent black */
    const float sky[4] = {0.02f, 0.025f, 0.035f, 1.0f};
    memcpy(desc->clear_color, sky, sizeof sky);
}

uint32_t cli_demo_max_views(const char *demo, uint32_t width, uint32_t height)
{
    if (strcmp(demo, "cube") == 0 || strcmp(demo, "ring") == 0)
        return 1024;
    if (strcmp(demo, "stereo") != 0 && strcmp(demo, "city") != 0)
        return 0;
    /* core/demo.c: eyes 0.064 apart, each frustum turned toward the centre
     * by 0.9 rad per metre of offset; the library takes frustum angles
     * below 1.5707 rad. The outer eye of n is (n - 1) / 2 eyes out. */
    double aspect = width && height ? (double)width / (double)height : 1.0;
    double half_h = atan(tan(0.45) * aspect);
    uint32_t n = 1;
    while (n < 1024 && half_h + (double)n * 0.5 * 0.064 * 0.9 < 1.5707)
        ++n;
    return n;
}

bool cli_check_demo_views(const char *command, const char *demo, uint32_t views, uint32_t width, uint32_t height)
{
    uint32_t most = demo ? cli_demo_max_views(demo, width, height) : 0;
    if (!most || views <= most)
        return true;
    fprintf(stderr, "%s: --demo %s frames at most %u views at %ux%u (eyes 64 mm apart, the outer frusta turned "
                    "toward the centre: more would turn them past 90 degrees); --demo ring and cube take up to "
                    "1024\n", command, demo, most, width, height);
    return false;
}

int cli_scene_camera_choice(bool scene_file, int camera, bool layout_set, bool camera_file)
{
    /* a file with a camera is seen from it unless a layout is asked for */
    if (scene_file && camera < 0 && !layout_set && !camera_file)
        return CLI_CAMERA_IF_ANY;
    return camera;
}

int cli_load_scene(const char *command, const cli_scene_options *o, mvr_scene **scene, mvr_view_set **views)
{
    if (o->scene_file)
        return load_scene_file(command, o, scene, views);
    if (!cli_check_demo_views(command, o->demo, o->views, o->width, o->height))
        return MVR_EXIT_USAGE;
    mvr_error err;
    mvr_demo_desc dd = {o->views, o->width, o->height, o->logger};
    if (mvr_demo_create(o->demo, &dd, scene, views, &err) != MVR_OK) {
        fprintf(stderr, "%s: %s\n", command, err.message);
        return err.result == MVR_ERROR_INVALID_ARGUMENT ? MVR_EXIT_USAGE : MVR_EXIT_FAILURE;
    }
    if (o->given_views) { /* the demo's scene, the file's views */
        mvr_view_set_destroy(*views);
        *views = NULL;
        mvr_view_set_desc vd = {.view_count = o->given_view_count, .views = o->given_views};
        if (mvr_view_set_create(&vd, views, &err) != MVR_OK) {
            fprintf(stderr, "%s: %s\n", command, err.message);
            return MVR_EXIT_USAGE;
        }
    }
    return MVR_EXIT_OK;
}

/* Prints the scene's animations as "0 'walk', 1 (unnamed), ..." (at most 16). */
static void list_animations(FILE *out, const mvr_scene *scene)
{
    uint32_t count = mvr_scene_animation_count(scene);
    for (uint32_t i = 0; i < count && i < 16; ++i) {
        mvr_animation_info ai;
        if (mvr_scene_get_animation_info(scene, i, &ai) != MVR_OK)
            break;
        if (ai.name && ai.name[0])
            fprintf(out, "%s%u '%s'", i ? ", " : "", i, ai.name);
        else
            fprintf(out, "%s%u (unnamed)", i ? ", " : "", i);
    }
    if (count > 16)
        fprintf(out, " and %u more", count - 16);
}

bool cli_find_animation(const char *command, const char *what, const mvr_scene *scene, const char *spec,
                        uint32_t *out)
{
    uint32_t count = mvr_scene_animation_count(scene);
    if (count == 0) {
        fprintf(stderr, "%s: --animation %s: %s has no animations\n", command, spec, what);
        return false;
    }
    if (strcmp(spec, "all") == 0) {
        *out = MVR_ANIMATION_ALL;
        return true;
    }
    bool number = spec[0] != '\0' && strspn(spec, "0123456789") == strlen(spec);
    uint32_t k = 0;
    if (number && cli_parse_u32(spec, 0, count - 1, &k)) {
        *out = k;
        return true;
    }
    /* by name without mvr_scene_find_animation, which would log the miss
     * as an error before this prints it */
    for (uint32_t i = 0; !number && i < count; ++i) {
        mvr_animation_info ai;
        if (mvr_scene_get_animation_info(scene, i, &ai) == MVR_OK && ai.name && strcmp(ai.name, spec) == 0) {
            *out = i;
            return true;
        }
    }
    if (number)
        fprintf(stderr, "%s: --animation %s: %s has %u animation%s (0..%u): ", command, spec, what, count,
                count == 1 ? "" : "s", count - 1);
    else
        fprintf(stderr, "%s: --animation %s: %s has no animation named '%s'; its animations: ", command, spec, what,
                spec);
    list_animations(stderr, scene);
    fprintf(stderr, " (a name, an index or all)\n");
    return false;
}

bool cli_animation_clip(const mvr_scene *scene, uint32_t index, double *start, double *end)
{
    *start = *end = 0.0;
    uint32_t count = mvr_scene_animation_count(scene);
    uint32_t first = index == MVR_ANIMATION_ALL ? 0 : index, last = index == MVR_ANIMATION_ALL ? count : index + 1;
    if (count == 0 || first >= count)
        return false;
    bool any = false;
    for (uint32_t i = first; i < last; ++i) {
        mvr_animation_info ai;
        if (mvr_scene_get_animation_info(scene, i, &ai) != MVR_OK)
            continue;
        *start = any ? fmin(*start, ai.start) : ai.start;
        *end = any ? fmax(*end, ai.end) : ai.end;
        any = true;
    }
    return any;
}

void cli_animation_label(const mvr_scene *scene, uint32_t index, char *buf, size_t size)
{
    mvr_animation_info ai;
    if (index == MVR_ANIMATION_ALL)
        snprintf(buf, size, "all %u", mvr_scene_animation_count(scene));
    else if (mvr_scene_get_animation_info(scene, index, &ai) == MVR_OK && ai.name && ai.name[0])
        snprintf(buf, size, "%u '%s'", index, ai.name);
    else
        snprintf(buf, size, "%u (unnamed)", index);
}

/* Prints the scene's variants as "0 'red', 1 'blue', ..." (at most 16). */
static void list_variants(FILE *out, const mvr_scene *scene)
{
    uint32_t count = mvr_scene_variant_count(scene);
    for (uint32_t i = 0; i < count && i < 16; ++i)
        fprintf(out, "%s%u '%s'", i ? ", " : "", i, mvr_scene_variant_name(scene, i));
    if (count > 16)
        fprintf(out, " and %u more", count - 16);
}

bool cli_find_variant(const char *command, const char *what, const mvr_scene *scene, const char *spec,
                      uint32_t *out)
{
    uint32_t count = mvr_scene_variant_count(scene);
    if (count == 0) {
        fprintf(stderr, "%s: --variant %s: %s has no material variants (KHR_materials_variants)\n", command, spec,
                what);
        return false;
    }
    /* by name first (without mvr_scene_find_variant, which would log the
     * miss as an error before this prints it), then as an index */
    for (uint32_t i = 0; i < count; ++i)
        if (strcmp(mvr_scene_variant_name(scene, i), spec) == 0) {
            *out = i;
            return true;
        }
    bool number = spec[0] != '\0' && strspn(spec, "0123456789") == strlen(spec);
    uint32_t k = 0;
    if (number && cli_parse_u32(spec, 0, count - 1, &k)) {
        *out = k;
        return true;
    }
    if (number)
        fprintf(stderr, "%s: --variant %s: %s has no variant named '%s' and %u variant%s (0..%u): ", command, spec,
                what, spec, count, count == 1 ? "" : "s", count - 1);
    else
        fprintf(stderr, "%s: --variant %s: %s has no variant named '%s'; its variants: ", command, spec, what, spec);
    list_variants(stderr, scene);
    fprintf(stderr, " (a name or an index)\n");
    return false;
}

void cli_variant_label(const mvr_scene *scene, uint32_t index, char *buf, size_t size)
{
    const char *name = mvr_scene_variant_name(scene, index);
    if (name)
        snprintf(buf, size, "%u '%s'", index, name);
    else
        snprintf(buf, size, "default");
}

/* Exact sRGB encode (IEC 61966-2-1) of linear floats into display bytes. */
void cli_encode_srgb(const float *in, uint8_t *out, size_t pixels)
{
    for (size_t i = 0; i < pixels * 4; ++i) {
        float c = in[i] < 0.0f ? 0.0f : in[i] > 1.0f ? 1.0f : in[i];
        if (i % 4 != 3)
            c = c <= 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
        out[i] = (uint8_t)(c * 255.0f + 0.5f);
    }
}

bool cli_read_display_layer(mvr_renderer *r, mvr_target *t, uint32_t layer, uint32_t w, uint32_t h, uint32_t ss,
                            uint8_t *out, float *linear)
{
    size_t pixels = (size_t)w * h;
    if (ss <= 1)
        return mvr_renderer_read_layer(r, t, layer, MVR_READBACK_RGBA8, out, pixels * 4) == MVR_OK &&
               (!linear || mvr_renderer_read_layer(r, t, layer, MVR_READBACK_RGBA32F, linear,
                                                   pixels * 4 * sizeof *linear) == MVR_OK);
    size_t samples = pixels * ss * ss;
    float *sampled = malloc(samples * 4 * sizeof *sampled);
    float *resolved = linear ? linear : malloc(pixels * 4 * sizeof *resolved);
    /* the resolve: a box over each pixel's ss x ss samples, in linear float */
    bool ok = sampled && resolved &&
              mvr_renderer_read_layer(r, t, layer, MVR_READBACK_RGBA32F, sampled, samples * 4 * sizeof *sampled) ==
                  MVR_OK &&
              mvr_downsample_rgba32f(sampled, w * ss, h * ss, ss, resolved) == MVR_OK;
    if (ok)
        cli_encode_srgb(resolved, out, pixels);
    free(sampled);
    if (resolved != linear)
        free(resolved);
    return ok;
}
