/* mvr info: what GL mvr gets from a context provider, and what it can use. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "json.h"
#include "mvr/mvr.h"

typedef struct info_options {
    mvr_context_desc desc;
    bool json;
    bool require_multiview;
    bool verbose;
} info_options;

static void info_usage(FILE *out)
{
    fprintf(out,
            "usage: mvr info [options]\n"
            "\n"
            "Creates a GL context through a provider and prints its version, the\n"
            "extensions and limits mvr uses, and the known driver bugs it detected.\n"
            "\n"
            "options:\n"
            "  --context NAME      default | surfaceless | device | pbuffer | osmesa\n"
            "                      (default: surfaceless, then device, then pbuffer)\n"
            "  --api NAME          gles | desktop (default: gles on EGL, desktop on osmesa)\n"
            "  --device N          with --context device: the N-th EGL device (1-based)\n"
            "  --json              machine-readable output on stdout\n"
            "  --debug             debug context; driver messages go to stderr\n"
            "  --require-multiview exit with status 3 unless GL_OVR_multiview2 is usable\n"
            "  --verbose           log what the library does to stderr\n"
            "  -h, --help          this text\n"
            "\n"
            "exit status: 0 ok, 1 no context, 2 bad usage, 3 a required capability is missing\n");
}

static void log_to_stderr(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    (void)user;
    if (id == MVR_LOG_ID_ERROR_RESULT)
        return; /* the command prints the error it got back itself */
    static const char *const names[] = {"", "error", "warning", "info", "debug"};
    fprintf(stderr, "mvr info: %s: %s\n", (unsigned)level < 5 ? names[level] : "?", message);
}

static int parse(int argc, char **argv, info_options *o)
{
    memset(o, 0, sizeof *o);
    o->desc.logger.fn = log_to_stderr;
    o->desc.logger.level = MVR_LOG_WARNING;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            info_usage(stdout);
            return -1;
        } else if (strcmp(a, "--json") == 0) {
            o->json = true;
        } else if (strcmp(a, "--debug") == 0) {
            o->desc.debug = true;
        } else if (strcmp(a, "--verbose") == 0) {
            o->verbose = true;
            o->desc.logger.level = MVR_LOG_DEBUG;
        } else if (strcmp(a, "--require-multiview") == 0) {
            o->require_multiview = true;
        } else if (strcmp(a, "--context") == 0 && value) {
            if (mvr_context_provider_from_name(value, &o->desc.provider) != MVR_OK ||
                o->desc.provider == MVR_CONTEXT_PROVIDER_EXTERNAL) {
                fprintf(stderr, "mvr info: unknown context provider '%s' (default, surfaceless, "
                                "device, pbuffer, osmesa)\n", value);
                return MVR_EXIT_USAGE;
            }
            ++i;
        } else if (strcmp(a, "--api") == 0 && value) {
            if (strcmp(value, "gles") == 0)
                o->desc.api = MVR_GL_API_GLES;
            else if (strcmp(value, "desktop") == 0)
                o->desc.api = MVR_GL_API_DESKTOP;
            else {
                fprintf(stderr, "mvr info: unknown api '%s' (gles, desktop)\n", value);
                return MVR_EXIT_USAGE;
            }
            ++i;
        } else if (strcmp(a, "--device") == 0 && value) {
            char *end = NULL;
            long n = strtol(value, &end, 10);
            if (!end || *end || n < 1 || n > 1024) {
                fprintf(stderr, "mvr info: --device takes a number from 1\n");
                return MVR_EXIT_USAGE;
            }
            o->desc.device_index = (int)n;
            ++i;
        } else {
            fprintf(stderr, "mvr info: unknown or incomplete option '%s'\n\n", a);
            info_usage(stderr);
            return MVR_EXIT_USAGE;
        }
    }
    if (o->desc.device_index > 0 && o->desc.provider != MVR_CONTEXT_PROVIDER_DEVICE) {
        fprintf(stderr, "mvr info: --device needs --context device\n");
        return MVR_EXIT_USAGE;
    }
    return MVR_EXIT_OK;
}

static void print_json(const mvr_context *ctx, const mvr_caps *c)
{
    json_writer w = {stdout, 0, {false}};
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
    json_begin_object(&w, "extensions");
    json_bool(&w, "GL_OVR_multiview", c->ext.ovr_multiview);
    json_bool(&w, "GL_OVR_multiview2", c->ext.ovr_multiview2);
    json_bool(&w, "GL_OVR_multiview_multisampled_render_to_texture",
              c->ext.ovr_multiview_multisampled_render_to_texture);
    json_bool(&w, "GL_EXT_clip_control", c->ext.ext_clip_control);
    json_bool(&w, "GL_EXT_disjoint_timer_query", c->ext.ext_disjoint_timer_query);
    json_bool(&w, "GL_KHR_debug", c->ext.khr_debug);
    json_bool(&w, "GL_EXT_texture_filter_anisotropic", c->ext.ext_texture_filter_anisotropic);
    json_bool(&w, "GL_EXT_color_buffer_float", c->ext.ext_color_buffer_float);
    json_bool(&w, "GL_EXT_color_buffer_half_float", c->ext.ext_color_buffer_half_float);
    json_bool(&w, "program_binary", c->ext.program_binary);
    json_bool(&w, "multiview_msaa_array", c->ext.multiview_msaa_array);
    json_end_object(&w);
    json_begin_object(&w, "compressed_formats");
    json_bool(&w, "etc2", c->ext.etc2);
    json_bool(&w, "astc_ldr", c->ext.astc_ldr);
    json_bool(&w, "s3tc", c->ext.s3tc);
    json_bool(&w, "rgtc", c->ext.rgtc);
    json_bool(&w, "bptc", c->ext.bptc);
    json_end_object(&w);
    json_begin_object(&w, "limits");
    json_int(&w, "max_views_ovr", c->limits.max_views_ovr);
    json_int(&w, "max_array_texture_layers", c->limits.max_array_texture_layers);
    json_int(&w, "max_texture_size", c->limits.max_texture_size);
    json_int(&w, "uniform_buffer_offset_alignment", c->limits.uniform_buffer_offset_alignment);
    json_int(&w, "max_uniform_block_size", c->limits.max_uniform_block_size);
    json_int(&w, "max_uniform_buffer_bindings", c->limits.max_uniform_buffer_bindings);
    json_int(&w, "max_samples", c->limits.max_samples);
    json_int(&w, "max_combined_texture_image_units", c->limits.max_combined_texture_image_units);
    json_int(&w, "max_draw_buffers", c->limits.max_draw_buffers);
    json_int(&w, "program_binary_formats", c->limits.program_binary_formats);
    json_double(&w, "max_anisotropy", (double)c->limits.max_anisotropy);
    json_end_object(&w);
    json_begin_object(&w, "bugs");
    json_bool(&w, "timer_query_in_multiview_undefined", c->bugs.timer_query_in_multiview_undefined);
    json_bool(&w, "mediump_is_fp16", c->bugs.mediump_is_fp16);
    json_bool(&w, "multiview_pass_defers_raster", c->bugs.multiview_pass_defers_raster);
    json_end_object(&w);
    json_end_object(&w);
}

static const char *yes(bool b)
{
    return b ? "yes" : "no";
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
    printf("\nextensions\n");
    printf("  GL_OVR_multiview                                %s\n", yes(c->ext.ovr_multiview));
    printf("  GL_OVR_multiview2                               %s\n", yes(c->ext.ovr_multiview2));
    printf("  GL_OVR_multiview_multisampled_render_to_texture %s\n",
           yes(c->ext.ovr_multiview_multisampled_render_to_texture));
    printf("  multisampled 2D array under multiview           %s\n",
           yes(c->ext.multiview_msaa_array));
    printf("  GL_EXT_clip_control                             %s\n", yes(c->ext.ext_clip_control));
    printf("  GL_EXT_disjoint_timer_query                     %s\n",
           yes(c->ext.ext_disjoint_timer_query));
    printf("  GL_KHR_debug                                    %s\n", yes(c->ext.khr_debug));
    printf("  GL_EXT_texture_filter_anisotropic               %s\n",
           yes(c->ext.ext_texture_filter_anisotropic));
    printf("  GL_EXT_color_buffer_float                       %s\n",
           yes(c->ext.ext_color_buffer_float));
    printf("  GL_EXT_color_buffer_half_float                  %s\n",
           yes(c->ext.ext_color_buffer_half_float));
    printf("  program binaries                                %s (%d formats)\n",
           yes(c->ext.program_binary), c->limits.program_binary_formats);
    printf("  compressed: etc2 %s, astc %s, s3tc %s, rgtc %s, bptc %s\n", yes(c->ext.etc2),
           yes(c->ext.astc_ldr), yes(c->ext.s3tc), yes(c->ext.rgtc), yes(c->ext.bptc));
    printf("\nlimits\n");
    printf("  GL_MAX_VIEWS_OVR                    %d\n", c->limits.max_views_ovr);
    printf("  GL_MAX_ARRAY_TEXTURE_LAYERS         %d\n", c->limits.max_array_texture_layers);
    printf("  GL_MAX_TEXTURE_SIZE                 %d\n", c->limits.max_texture_size);
    printf("  GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT  %d\n", c->limits.uniform_buffer_offset_alignment);
    printf("  GL_MAX_UNIFORM_BLOCK_SIZE           %d\n", c->limits.max_uniform_block_size);
    printf("  GL_MAX_UNIFORM_BUFFER_BINDINGS      %d\n", c->limits.max_uniform_buffer_bindings);
    printf("  GL_MAX_SAMPLES                      %d\n", c->limits.max_samples);
    printf("  GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS %d\n", c->limits.max_combined_texture_image_units);
    printf("  GL_MAX_DRAW_BUFFERS                 %d\n", c->limits.max_draw_buffers);
    printf("  max anisotropy                      %g\n", (double)c->limits.max_anisotropy);
    printf("\nknown driver bugs\n");
    printf("  timer queries undefined under multiview  %s\n",
           yes(c->bugs.timer_query_in_multiview_undefined));
    printf("  mediump computed in fp16                 %s\n", yes(c->bugs.mediump_is_fp16));
    printf("  multiview pass defers rasterization      %s\n",
           yes(c->bugs.multiview_pass_defers_raster));
}

int mvr_cmd_info(int argc, char **argv)
{
    info_options o;
    int rc = parse(argc, argv, &o);
    if (rc != MVR_EXIT_OK)
        return rc < 0 ? MVR_EXIT_OK : rc;
    if (o.desc.provider == MVR_CONTEXT_PROVIDER_OSMESA &&
        !mvr_context_provider_built(MVR_CONTEXT_PROVIDER_OSMESA)) {
        fprintf(stderr, "mvr info: this mvr was built without the osmesa provider\n");
        return MVR_EXIT_FAILURE;
    }
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
