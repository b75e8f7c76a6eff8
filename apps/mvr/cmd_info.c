/* mvr info: what GL mvr gets from a context provider, and what it can use;
 * mvr info FILE: what a glTF file holds (no GL needed). */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "commands.h"
#include "json.h"
#include "mvr/mvr.h"
#include "mvr/mvr_gltf.h"

typedef struct info_options {
    mvr_context_desc desc;
    bool json;
    bool require_multiview;
    bool verbose;
    const char *file;            /* mvr info FILE: the file's contents instead of the GL */
    uint32_t gltf_scene;         /* --scene K + 1; 0 = the file's default */
    const char *gl_option;       /* the first GL option given (refused with FILE) */
} info_options;

static void info_usage(FILE *out)
{
    fprintf(out,
            "usage: mvr info [options]\n"
            "       mvr info SCENE.gltf|SCENE.glb [--scene K] [--json]\n"
            "\n"
            "Creates a GL context through a provider and prints its version, the\n"
            "extensions and limits mvr uses, and the known driver bugs it detected.\n"
            "With a file: what it holds (no GL needed): nodes, meshes, materials,\n"
            "lights, cameras, skins and joints, morph targets, each animation\n"
            "(index, name, start .. end seconds, channels) as mvr render --animation\n"
            "takes them, and each material variant (KHR_materials_variants: index,\n"
            "name) as mvr render --variant takes them.\n"
            "\n"
            "options:\n");
    const cli_option *const context[] = {cli_context_options, NULL};
    cli_print_options(out, context, 20);
    fprintf(out,
            "  --json              machine-readable output on stdout\n"
            "  --debug             debug context; driver messages go to stderr\n"
            "  --require-multiview exit with status 3 unless GL_OVR_multiview2 is usable\n"
            "  --scene K           with a file: its K-th scene (0-based; default: its default)\n"
            "  --verbose           log what the library does to stderr\n"
            "  -h, --help          this text\n"
            "\n"
            "exit status: 0 ok, 1 no context, 2 bad usage, 3 a required capability is missing\n");
}

static int parse(int argc, char **argv, info_options *o)
{
    memset(o, 0, sizeof *o);
    cli_logger(&o->desc.logger, "info", false);
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        int c = cli_context_option("info", argc, argv, &i, &o->desc);
        if (c < 0)
            return MVR_EXIT_USAGE;
        if (c > 0) {
            o->gl_option = o->gl_option ? o->gl_option : a;
            continue;
        }
        if (a[0] != '-' || a[1] == '\0') {
            if (o->file) {
                fprintf(stderr, "mvr info: one SCENE file at a time (got %s and %s)\n", o->file, a);
                return MVR_EXIT_USAGE;
            }
            o->file = a;
            continue;
        }
        if (strcmp(a, "--scene") == 0) {
            uint32_t k = 0;
            if (i + 1 >= argc || !cli_parse_u32(argv[i + 1], 0, 1u << 20, &k)) {
                fprintf(stderr, "mvr info: --scene takes a scene index K (0-based)\n");
                return MVR_EXIT_USAGE;
            }
            o->gltf_scene = k + 1;
            ++i;
            continue;
        }
        if (strcmp(a, "--debug") == 0 || strcmp(a, "--require-multiview") == 0)
            o->gl_option = o->gl_option ? o->gl_option : a;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            info_usage(stdout);
            return -1;
        } else if (strcmp(a, "--json") == 0) {
            o->json = true;
        } else if (strcmp(a, "--debug") == 0) {
            o->desc.debug = true;
        } else if (strcmp(a, "--verbose") == 0) {
            o->verbose = true;
            cli_logger(&o->desc.logger, "info", true);
        } else if (strcmp(a, "--require-multiview") == 0) {
            o->require_multiview = true;
        } else {
            fprintf(stderr, "mvr info: unknown option '%s'\n\n", a);
            info_usage(stderr);
            return MVR_EXIT_USAGE;
        }
    }
    if (o->file && o->gl_option) {
        fprintf(stderr, "mvr info: %s is about the GL; with a SCENE file mvr info reports the file (no GL): give "
                        "one or the other\n", o->gl_option);
        return MVR_EXIT_USAGE;
    }
    if (!o->file && o->gltf_scene) {
        fprintf(stderr, "mvr info: --scene is for a SCENE file\n");
        return MVR_EXIT_USAGE;
    }
    if (!cli_context_check("info", &o->desc))
        return MVR_EXIT_USAGE;
    return MVR_EXIT_OK;
}

/* mvr info FILE as JSON: the scene's counts and its animations. */
static void print_scene_json(const char *file, const mvr_scene *scene, const mvr_scene_info *si,
                             const mvr_gltf_info *gi)
{
    json_writer w = {stdout, 0, {false}, {0}};
    json_begin_object(&w, NULL);
    json_string(&w, "file", file);
    json_int(&w, "nodes", si->nodes);
    json_int(&w, "meshes", si->meshes);
    json_int(&w, "primitives", si->primitives);
    json_int(&w, "materials", si->materials);
    json_int(&w, "images", si->images);
    json_int(&w, "lights", si->lights);
    json_int(&w, "cameras", si->cameras);
    json_int(&w, "skins", si->skins);
    json_int(&w, "joints", si->joints);
    json_int(&w, "morph_targets", si->morph_targets);
    json_begin_array(&w, "bounds_min");
    for (int k = 0; k < 3; ++k)
        json_double(&w, NULL, si->bounds_min[k]);
    json_end_array(&w);
    json_begin_array(&w, "bounds_max");
    for (int k = 0; k < 3; ++k)
        json_double(&w, NULL, si->bounds_max[k]);
    json_end_array(&w);
    json_begin_array(&w, "animations");
    uint32_t count = mvr_scene_animation_count(scene);
    for (uint32_t i = 0; i < count; ++i) {
        mvr_animation_info ai;
        if (mvr_scene_get_animation_info(scene, i, &ai) != MVR_OK)
            break;
        json_begin_object(&w, NULL);
        json_int(&w, "index", i);
        json_string(&w, "name", ai.name ? ai.name : "");
        json_double(&w, "start", ai.start);
        json_double(&w, "end", ai.end);
        json_int(&w, "channels", ai.channels);
        json_int(&w, "samplers", ai.samplers);
        json_end_object(&w);
    }
    json_end_array(&w);
    json_begin_array(&w, "variants");
    for (uint32_t i = 0; i < mvr_scene_variant_count(scene); ++i) {
        json_begin_object(&w, NULL);
        json_int(&w, "index", i);
        json_string(&w, "name", mvr_scene_variant_name(scene, i));
        json_end_object(&w);
    }
    json_end_array(&w);
    json_int(&w, "animation_channels_ignored", gi->animation_channels_ignored);
    json_int(&w, "images_occlusion_packed", gi->images_occlusion_packed);
    json_int(&w, "load_warnings", gi->warnings);
    json_end_object(&w);
}

static void print_scene_text(const char *file, const mvr_scene *scene, const mvr_scene_info *si,
                             const mvr_gltf_info *gi)
{
    printf("file          %s\n", file);
    printf("nodes         %u (%u camera%s, %u light%s)\n", si->nodes, si->cameras, si->cameras == 1 ? "" : "s",
           si->lights, si->lights == 1 ? "" : "s");
    printf("meshes        %u (%u primitive%s), %u material%s, %u image%s\n", si->meshes, si->primitives,
           si->primitives == 1 ? "" : "s", si->materials, si->materials == 1 ? "" : "s", si->images,
           si->images == 1 ? "" : "s");
    if (gi->images_occlusion_packed)
        printf("packed        %u occlusion image%s in the red channel of %s metallic-roughness image%s (one fetch)\n",
               gi->images_occlusion_packed, gi->images_occlusion_packed == 1 ? "" : "s",
               gi->images_occlusion_packed == 1 ? "its" : "their", gi->images_occlusion_packed == 1 ? "" : "s");
    printf("bounds        (%g, %g, %g) .. (%g, %g, %g)\n", si->bounds_min[0], si->bounds_min[1], si->bounds_min[2],
           si->bounds_max[0], si->bounds_max[1], si->bounds_max[2]);
    printf("skins         %u (%u joint%s)\n", si->skins, si->joints, si->joints == 1 ? "" : "s");
    printf("morph targets %u (summed over primitives)\n", si->morph_targets);
    uint32_t count = mvr_scene_animation_count(scene);
    printf("animations    %u", count);
    if (gi->animation_channels_ignored)
        printf(" (%u channel%s left out: unknown target paths, or nodes outside the scene)",
               gi->animation_channels_ignored, gi->animation_channels_ignored == 1 ? "" : "s");
    printf("\n");
    for (uint32_t i = 0; i < count; ++i) {
        mvr_animation_info ai;
        if (mvr_scene_get_animation_info(scene, i, &ai) != MVR_OK)
            break;
        char name[160];
        if (ai.name && ai.name[0])
            snprintf(name, sizeof name, "'%s'", ai.name);
        else
            snprintf(name, sizeof name, "(unnamed)");
        printf("  %-4u %-24s %g .. %g s, %u channel%s, %u sampler%s\n", i, name, ai.start, ai.end, ai.channels,
               ai.channels == 1 ? "" : "s", ai.samplers, ai.samplers == 1 ? "" : "s");
    }
    uint32_t variants = mvr_scene_variant_count(scene);
    printf("variants      %u%s\n", variants, variants ? " (material variants: mvr render --variant NAME|K)" : "");
    for (uint32_t i = 0; i < variants; ++i)
        printf("  %-4u '%s'\n", i, mvr_scene_variant_name(scene, i));
}

/* mvr info FILE: loads the file (no GL) and prints what it holds. */
static int info_file(const info_options *o)
{
    mvr_gltf_options go;
    memset(&go, 0, sizeof go);
    go.scene = o->gltf_scene;
    go.logger = o->desc.logger;
    mvr_gltf_info gi;
    memset(&gi, 0, sizeof gi);
    mvr_scene *scene = NULL;
    mvr_error err;
    if (mvr_gltf_load_file(o->file, &go, &scene, &gi, &err) != MVR_OK) {
        fprintf(stderr, "mvr info: %s (%s)\n", err.message, mvr_result_name(err.result));
        return MVR_EXIT_FAILURE;
    }
    mvr_scene_info si;
    mvr_scene_get_info(scene, &si);
    if (o->json)
        print_scene_json(o->file, scene, &si, &gi);
    else
        print_scene_text(o->file, scene, &si, &gi);
    mvr_scene_destroy(scene);
    return MVR_EXIT_OK;
}

/* One table per caps section drives both the JSON and the text output, so
 * the two never list different fields. */
typedef struct bool_field {
    const char *key;    /* JSON key (the extension name where there is one) */
    const char *label;  /* text label */
    size_t offset;      /* of a bool in mvr_caps */
} bool_field;

typedef struct int_field {
    const char *key;
    const char *label;
    size_t offset;      /* of an int in mvr_caps */
} int_field;

#define EXT(member, key, label) {key, label, offsetof(mvr_caps, ext.member)}
static const bool_field extension_fields[] = {
    EXT(ovr_multiview, "GL_OVR_multiview", "GL_OVR_multiview"),
    EXT(ovr_multiview2, "GL_OVR_multiview2", "GL_OVR_multiview2"),
    EXT(ovr_multiview_multisampled_render_to_texture,
        "GL_OVR_multiview_multisampled_render_to_texture",
        "GL_OVR_multiview_multisampled_render_to_texture"),
    EXT(multiview_msaa_array, "multiview_msaa_array", "multisampled 2D array under multiview"),
    EXT(ext_clip_control, "GL_EXT_clip_control", "GL_EXT_clip_control"),
    EXT(ext_disjoint_timer_query, "GL_EXT_disjoint_timer_query", "GL_EXT_disjoint_timer_query"),
    EXT(khr_debug, "GL_KHR_debug", "GL_KHR_debug"),
    EXT(ext_texture_filter_anisotropic, "GL_EXT_texture_filter_anisotropic",
        "GL_EXT_texture_filter_anisotropic"),
    EXT(ext_color_buffer_float, "GL_EXT_color_buffer_float", "GL_EXT_color_buffer_float"),
    EXT(ext_color_buffer_half_float, "GL_EXT_color_buffer_half_float",
        "GL_EXT_color_buffer_half_float"),
    EXT(oes_texture_float_linear, "GL_OES_texture_float_linear", "GL_OES_texture_float_linear"),
    EXT(program_binary, "program_binary", "program binaries"),
};
static const bool_field compressed_fields[] = {
    EXT(etc2, "etc2", "ETC2 / EAC"),
    EXT(astc_ldr, "astc_ldr", "ASTC LDR"),
    EXT(s3tc, "s3tc", "S3TC (BC1-3)"),
    EXT(rgtc, "rgtc", "RGTC (BC4-5)"),
    EXT(bptc, "bptc", "BPTC (BC6H-7)"),
};
#undef EXT

#define LIMIT(member, label) {#member, label, offsetof(mvr_caps, limits.member)}
static const int_field limit_fields[] = {
    LIMIT(max_views_ovr, "GL_MAX_VIEWS_OVR"),
    LIMIT(max_array_texture_layers, "GL_MAX_ARRAY_TEXTURE_LAYERS"),
    LIMIT(max_texture_size, "GL_MAX_TEXTURE_SIZE"),
    LIMIT(uniform_buffer_offset_alignment, "GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT"),
    LIMIT(max_uniform_block_size, "GL_MAX_UNIFORM_BLOCK_SIZE"),
    LIMIT(max_uniform_buffer_bindings, "GL_MAX_UNIFORM_BUFFER_BINDINGS"),
    LIMIT(max_samples, "GL_MAX_SAMPLES"),
    LIMIT(max_combined_texture_image_units, "GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS"),
    LIMIT(max_draw_buffers, "GL_MAX_DRAW_BUFFERS"),
    LIMIT(program_binary_formats, "GL_NUM_PROGRAM_BINARY_FORMATS"),
};
#undef LIMIT

#define BUG(member, label) {#member, label, offsetof(mvr_caps, bugs.member)}
static const bool_field bug_fields[] = {
    BUG(timer_query_in_multiview_undefined, "timer queries undefined under multiview"),
    BUG(multiview_level_zero_only, "multiview attaches mip level 0 only"),
    BUG(mediump_is_fp16, "mediump computed in fp16"),
    BUG(multiview_pass_defers_raster, "multiview pass defers rasterization"),
    BUG(half_float_sampling_slow, "half float textures sample slower than float"),
};
#undef BUG

static bool bool_at(const mvr_caps *c, size_t offset)
{
    bool v;
    memcpy(&v, (const char *)c + offset, sizeof v);
    return v;
}

static int int_at(const mvr_caps *c, size_t offset)
{
    int v;
    memcpy(&v, (const char *)c + offset, sizeof v);
    return v;
}

static void json_bools(json_writer *w, const char *section, const bool_field *f, size_t n,
                       const mvr_caps *c)
{
    json_begin_object(w, section);
    for (size_t i = 0; i < n; ++i)
        json_bool(w, f[i].key, bool_at(c, f[i].offset));
    json_end_object(w);
}

static void print_json(const mvr_context *ctx, const mvr_caps *c)
{
    json_writer w = {stdout, 0, {false}, {0}};
    json_begin_object(&w, NULL);
    json_string(&w, "provider", mvr_context_provider_name(mvr_context_get_provider(ctx)));
    json_string(&w, "api", mvr_gl_api_name(c->api));
    json_string(&w, "vendor", c->vendor);
    json_string(&w, "renderer", c->renderer);
    json_string(&w, "version", c->version);
    json_int(&w, "gl_major", c->gl_major);
    json_int(&w, "gl_minor", c->gl_minor);
    json_string(&w, "glsl_version", c->glsl_version);
    json_string(&w, "egl_vendor", c->egl_vendor);
    json_string(&w, "egl_version", c->egl_version);
    json_string(&w, "egl_device", c->egl_device);
    json_bool(&w, "is_software", c->is_software);
    json_bools(&w, "extensions", extension_fields, sizeof extension_fields / sizeof *extension_fields, c);
    json_bools(&w, "compressed_formats", compressed_fields,
               sizeof compressed_fields / sizeof *compressed_fields, c);
    json_begin_object(&w, "limits");
    for (size_t i = 0; i < sizeof limit_fields / sizeof *limit_fields; ++i)
        json_int(&w, limit_fields[i].key, int_at(c, limit_fields[i].offset));
    json_double(&w, "max_anisotropy", (double)c->limits.max_anisotropy);
    json_end_object(&w);
    json_bools(&w, "bugs", bug_fields, sizeof bug_fields / sizeof *bug_fields, c);
    json_end_object(&w);
}

static void text_bools(const char *section, const bool_field *f, size_t n, const mvr_caps *c)
{
    printf("\n%s\n", section);
    for (size_t i = 0; i < n; ++i)
        printf("  %-48s %s\n", f[i].label, bool_at(c, f[i].offset) ? "yes" : "no");
}

static void print_text(const mvr_context *ctx, const mvr_caps *c)
{
    printf("provider      %s (%s)\n", mvr_context_provider_name(mvr_context_get_provider(ctx)),
           mvr_gl_api_name(c->api));
    printf("GL            %s\n", c->version);
    printf("renderer      %s (%s)%s\n", c->renderer, c->vendor, c->is_software ? ", software" : "");
    printf("GLSL          %s\n", c->glsl_version);
    if (c->egl_version[0])
        printf("EGL           %s (%s)\n", c->egl_version, c->egl_vendor);
    if (c->egl_device[0])
        printf("EGL device    %s\n", c->egl_device);
    text_bools("extensions", extension_fields, sizeof extension_fields / sizeof *extension_fields, c);
    text_bools("compressed formats", compressed_fields,
               sizeof compressed_fields / sizeof *compressed_fields, c);
    printf("\nlimits\n");
    for (size_t i = 0; i < sizeof limit_fields / sizeof *limit_fields; ++i)
        printf("  %-48s %d\n", limit_fields[i].label, int_at(c, limit_fields[i].offset));
    printf("  %-48s %g\n", "max anisotropy", (double)c->limits.max_anisotropy);
    text_bools("known driver bugs", bug_fields, sizeof bug_fields / sizeof *bug_fields, c);
}

int mvr_cmd_info(int argc, char **argv)
{
    info_options o;
    int rc = parse(argc, argv, &o);
    if (rc != MVR_EXIT_OK)
        return rc < 0 ? MVR_EXIT_OK : rc;
    if (o.file)
        return info_file(&o);
    mvr_context *ctx = NULL;
    mvr_error err;
    if (mvr_context_create(&o.desc, &ctx, &err) != MVR_OK) {
        fprintf(stderr, "mvr info: %s (%s)\n", err.message, mvr_result_name(err.result));
        return MVR_EXIT_FAILURE;
    }
    const mvr_caps *c = mvr_context_caps(ctx);
    if (o.json)
        print_json(ctx, c);
    else
        print_text(ctx, c);
    rc = MVR_EXIT_OK;
    if (o.require_multiview && !(c->ext.ovr_multiview2 && c->limits.max_views_ovr >= 2)) {
        fprintf(stderr,
                "mvr info: GL_OVR_multiview2 is required but %s (%s) %s; the multiview path "
                "cannot run. On Debian 12, scripts/setup installs Mesa >= 25 from backports.\n",
                c->renderer, c->version,
                c->ext.ovr_multiview2 ? "reports GL_MAX_VIEWS_OVR < 2" : "does not offer it");
        rc = MVR_EXIT_MISSING;
    }
    mvr_context_destroy(ctx);
    return rc;
}
