/* mvr-viewer: a window (GLFW) showing N views rendered by the library
 * through the EXTERNAL context provider: stereo side by side, a grid, a
 * red/cyan anaglyph, or one view. Views reach the window by a draw per
 * layer that reads the layer as a texture (never out of a multiview
 * framebuffer). A scene opens as mvr render shows it (the same code:
 * apps/mvr/cli_scene.c and cli_env.c): a file from its camera or framed by
 * its size, exposed for its lights, lit by the same environment.
 *
 * A file's animation plays (viewer_playback.c: animation 0, looping, unless
 * --animation, --time and --paused say otherwise); the command line is
 * viewer_options.c's.
 *
 * mouse: left drag orbits, right drag pans, wheel zooms
 * keys:  [ ] IPD   + - views   P view path   M material path   D display
 *        R reset   Esc quit    (drop a .gltf / .glb on the window to open it)
 *        Space play/pause   Left Right step 1/30 s (Shift: 1/10 of the clip)
 *        Home clip start    N next animation (Shift+N previous)
 *        V next material variant, then the file's own (Shift+V previous) */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <GLES3/gl3.h>

#include "cli_common.h"
#include "cli_env.h"
#include "cli_options.h"
#include "cli_scene.h"
#include "commands.h"
#include "mvr/mvr.h"
#include "mvr/mvr_image.h"
#include "viewer_options.h"
#include "viewer_playback.h"

/* The GL entry points the composite needs, loaded through GLFW. */
typedef struct viewer_gl {
    PFNGLBINDFRAMEBUFFERPROC BindFramebuffer;
    PFNGLCLEARCOLORPROC ClearColor;
    PFNGLCLEARPROC Clear;
    PFNGLREADPIXELSPROC ReadPixels;
    PFNGLCOLORMASKPROC ColorMask;
    PFNGLVIEWPORTPROC Viewport;
    PFNGLDISABLEPROC Disable;
    PFNGLPIXELSTOREIPROC PixelStorei;
    PFNGLCREATESHADERPROC CreateShader;
    PFNGLSHADERSOURCEPROC ShaderSource;
    PFNGLCOMPILESHADERPROC CompileShader;
    PFNGLGETSHADERIVPROC GetShaderiv;
    PFNGLGETSHADERINFOLOGPROC GetShaderInfoLog;
    PFNGLDELETESHADERPROC DeleteShader;
    PFNGLCREATEPROGRAMPROC CreateProgram;
    PFNGLATTACHSHADERPROC AttachShader;
    PFNGLLINKPROGRAMPROC LinkProgram;
    PFNGLGETPROGRAMIVPROC GetProgramiv;
    PFNGLDELETEPROGRAMPROC DeleteProgram;
    PFNGLUSEPROGRAMPROC UseProgram;
    PFNGLGETUNIFORMLOCATIONPROC GetUniformLocation;
    PFNGLUNIFORM1IPROC Uniform1i;
    PFNGLUNIFORM2IPROC Uniform2i;
    PFNGLACTIVETEXTUREPROC ActiveTexture;
    PFNGLBINDTEXTUREPROC BindTexture;
    PFNGLGENVERTEXARRAYSPROC GenVertexArrays;
    PFNGLDELETEVERTEXARRAYSPROC DeleteVertexArrays;
    PFNGLBINDVERTEXARRAYPROC BindVertexArray;
    PFNGLDRAWARRAYSPROC DrawArrays;
} viewer_gl;

typedef struct viewer {
    GLFWwindow *window;
    viewer_gl gl;
    mvr_context *ctx;
    mvr_renderer *renderer;
    mvr_target *target;
    mvr_scene *scene;
    mvr_view_set *views;
    mvr_render_desc render;      /* as mvr render's defaults give it for the scene */
    cli_env_options env_options;
    viewer_clear clear;          /* --clear */
    mvr_environment *env;
    GLuint program, vao;
    GLint loc_layers, loc_origin, loc_mode;
    /* camera: orbit around a target, from home (where the scene opened) */
    double center[3], distance, yaw, pitch, yfov;
    double ipd;
    struct {
        double center[3], distance, yaw, pitch, ipd;
    } home;                      /* the orbit where the scene opened (R returns there) */
    uint32_t view_count, single;
    display_mode display;
    mvr_view_path view_path;
    mvr_anti_aliasing aa; /* --aa */
    mvr_material_path material_path;
    int fb_width, fb_height;
    uint32_t layer_w, layer_h;
    bool dragging_orbit, dragging_pan;
    double last_x, last_y;
    bool dirty_renderer, dirty_views;
    bool desktop;
    char scene_name[256];
    viewer_playback playback;
    /* the command line's playback, for the first scene opened (a file
     * dropped later plays its animation 0 from the start) */
    const char *start_animation; /* --animation; NULL: 0 when there is one */
    double start_time;           /* --time; < 0: the clip's start */
    bool start_paused;           /* --paused */
} viewer;

static void log_fn(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    (void)id;
    (void)user;
    if (level == MVR_LOG_ERROR || level == MVR_LOG_WARNING)
        fprintf(stderr, "mvr-viewer: %s\n", message);
}

static void *get_proc(const char *name, void *user)
{
    (void)user;
    /* mvr's loader takes entry points as void * (as eglGetProcAddress and
     * dlsym give them; POSIX makes the two pointer kinds interchangeable) */
    GLFWglproc fn = glfwGetProcAddress(name);
    void *p = NULL;
    memcpy(&p, &fn, sizeof p);
    return p;
}

static bool load_gl(viewer_gl *gl)
{
#define LOAD(type, name)                                                    \
    gl->name = (type)glfwGetProcAddress("gl" #name);                        \
    if (!gl->name) {                                                        \
        fprintf(stderr, "mvr-viewer: gl" #name " missing\n");               \
        return false;                                                       \
    }
    LOAD(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)
    LOAD(PFNGLCLEARCOLORPROC, ClearColor)
    LOAD(PFNGLCLEARPROC, Clear)
    LOAD(PFNGLREADPIXELSPROC, ReadPixels)
    LOAD(PFNGLCOLORMASKPROC, ColorMask)
    LOAD(PFNGLVIEWPORTPROC, Viewport)
    LOAD(PFNGLDISABLEPROC, Disable)
    LOAD(PFNGLPIXELSTOREIPROC, PixelStorei)
    LOAD(PFNGLCREATESHADERPROC, CreateShader)
    LOAD(PFNGLSHADERSOURCEPROC, ShaderSource)
    LOAD(PFNGLCOMPILESHADERPROC, CompileShader)
    LOAD(PFNGLGETSHADERIVPROC, GetShaderiv)
    LOAD(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)
    LOAD(PFNGLDELETESHADERPROC, DeleteShader)
    LOAD(PFNGLCREATEPROGRAMPROC, CreateProgram)
    LOAD(PFNGLATTACHSHADERPROC, AttachShader)
    LOAD(PFNGLLINKPROGRAMPROC, LinkProgram)
    LOAD(PFNGLGETPROGRAMIVPROC, GetProgramiv)
    LOAD(PFNGLDELETEPROGRAMPROC, DeleteProgram)
    LOAD(PFNGLUSEPROGRAMPROC, UseProgram)
    LOAD(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)
    LOAD(PFNGLUNIFORM1IPROC, Uniform1i)
    LOAD(PFNGLUNIFORM2IPROC, Uniform2i)
    LOAD(PFNGLACTIVETEXTUREPROC, ActiveTexture)
    LOAD(PFNGLBINDTEXTUREPROC, BindTexture)
    LOAD(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)
    LOAD(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)
    LOAD(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)
    LOAD(PFNGLDRAWARRAYSPROC, DrawArrays)
#undef LOAD
    return true;
}

/* Columns of the grid display: the smallest square that holds count views. */
static uint32_t grid_columns(uint32_t count)
{
    uint32_t cols = 1;
    while (cols * cols < count)
        cols++;
    return cols;
}

/* Layers per window for count views: the display decides how the window is
 * split. count 0 (a demo's own count, not known before it opens) sizes as
 * for one view; open_scene sizes again for the count the scene brings. */
static void layer_size(const viewer *v, uint32_t count, uint32_t *w, uint32_t *h)
{
    uint32_t fw = (uint32_t)(v->fb_width > 0 ? v->fb_width : 1), fh = (uint32_t)(v->fb_height > 0 ? v->fb_height : 1);
    if (count == 0)
        count = 1;
    switch (v->display) {
    case DISPLAY_STEREO: *w = fw / 2 ? fw / 2 : 1; *h = fh; return;
    case DISPLAY_GRID: {
        uint32_t cols = grid_columns(count);
        uint32_t rows = (count + cols - 1) / cols;
        *w = fw / cols ? fw / cols : 1;
        *h = fh / rows ? fh / rows : 1;
        return;
    }
    case DISPLAY_ANAGLYPH:
    case DISPLAY_SINGLE:
    case DISPLAY_COUNT: *w = fw; *h = fh; return;
    }
}

/* N eyes on a line through the orbit camera, ipd apart, all looking at the target. */
static bool make_views(viewer *v)
{
    mvr_view_desc *views = calloc(v->view_count, sizeof *views);
    if (!views)
        return false;
    double cp = cos(v->pitch), sp = sin(v->pitch), cy = cos(v->yaw), sy = sin(v->yaw);
    double dir[3] = {cp * sy, sp, cp * cy}; /* from target to camera */
    double right[3] = {cy, 0, -sy};
    double aspect = (double)v->layer_w / (double)v->layer_h;
    for (uint32_t i = 0; i < v->view_count; ++i) {
        double off = ((double)i - (double)(v->view_count - 1) * 0.5) * v->ipd;
        double eye[3], look[3];
        for (int c = 0; c < 3; ++c) {
            eye[c] = v->center[c] + dir[c] * v->distance + right[c] * off;
            look[c] = v->center[c] + right[c] * off; /* parallel eyes */
        }
        const double up[3] = {0, 1, 0};
        mvr_view_look_at(&views[i], eye, look, up);
        views[i].projection.yfov = v->yfov;
        views[i].projection.aspect = aspect;
        views[i].projection.znear = fmax(v->distance * 1e-3, 1e-4);
    }
    mvr_view_set_desc d = {v->view_count, views, false, {0, 0, 0}};
    mvr_view_set *vs = NULL;
    mvr_error err;
    bool ok = mvr_view_set_create(&d, &vs, &err) == MVR_OK;
    if (!ok)
        fprintf(stderr, "mvr-viewer: %s\n", err.message);
    free(views);
    if (ok) {
        mvr_view_set_destroy(v->views);
        v->views = vs;
    }
    return ok;
}

static bool make_renderer(viewer *v)
{
    mvr_target_destroy(v->target);
    mvr_renderer_destroy(v->renderer);
    v->target = NULL;
    v->renderer = NULL;
    mvr_renderer_desc rd = {.context = v->ctx, .view_path = v->view_path, .material_path = v->material_path};
    mvr_error err;
    /* the viewer reads the library's MVR_* debugging variables (docs/guide.md) */
    if (mvr_renderer_overrides_from_env(&rd.overrides, &err) != MVR_OK ||
        mvr_renderer_create(&rd, &v->renderer, &err) != MVR_OK) {
        fprintf(stderr, "mvr-viewer: %s\n", err.message);
        return false;
    }
    layer_size(v, v->view_count, &v->layer_w, &v->layer_h);
    /* the sRGB target mvr render uses (blending in linear light); its bytes
     * are copied to the window as they are */
    mvr_target_desc td = {v->layer_w, v->layer_h, v->view_count, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, v->aa, 0};
    if (mvr_target_create(v->renderer, &td, &v->target) != MVR_OK) {
        fprintf(stderr, "mvr-viewer: %s\n", mvr_renderer_last_error(v->renderer));
        return false;
    }
    return true;
}

static void go_home(viewer *v)
{
    memcpy(v->center, v->home.center, sizeof v->center);
    v->distance = v->home.distance;
    v->yaw = v->home.yaw;
    v->pitch = v->home.pitch;
    v->ipd = v->home.ipd;
}

/* The orbit starts where the scene's own views are, so the first drag
 * moves on from the picture shown: a file's row of eyes (cli_load_scene:
 * on its first camera, else the library's default framing, from above with
 * the bounding box fitted) gives the orbit's eye (the row's centre),
 * direction and field of view, its target where the view axis passes the
 * scene's centre. A demo's
 * views may look anywhere (the cube's six from the centre): the orbit looks
 * at its bounds from above. Eyes ipd apart: mvr_stereo_default_ipd of the
 * distance, as the library's views have. */
static void set_home(viewer *v, bool file)
{
    mvr_scene_info info;
    mvr_scene_get_info(v->scene, &info);
    double c[3] = {0, 0, 0}, radius = 0;
    for (int k = 0; k < 3; ++k) {
        c[k] = 0.5 * (info.bounds_min[k] + info.bounds_max[k]);
        double half = 0.5 * (info.bounds_max[k] - info.bounds_min[k]);
        radius += half * half;
    }
    radius = sqrt(radius);
    if (!(radius > 0) || !isfinite(radius)) {
        radius = 1;
        c[0] = c[1] = c[2] = 0;
    }
    double distance = radius * 2.5, yaw = 0.0, pitch = 0.25, yfov = 0.9, ipd = 0;
    double center[3] = {c[0], c[1], c[2]};
    mvr_view_desc cam, last;
    uint32_t n = v->views ? mvr_view_set_count(v->views) : 0;
    /* a file's row of parallel eyes (on its camera, or framed): its centre */
    bool posed = file && n > 0 && mvr_view_set_get_view(v->views, 0, &cam) == MVR_OK &&
                 mvr_view_set_get_view(v->views, n - 1, &last) == MVR_OK;
    for (int k = 0; posed && k < 3; ++k)
        cam.position[k] = 0.5 * (cam.position[k] + last.position[k]);
    if (posed) {
        double x = cam.orientation[0], y = cam.orientation[1], z = cam.orientation[2], w = cam.orientation[3];
        double f[3] = {-2 * (x * z + w * y), -2 * (y * z - w * x), -(1 - 2 * (x * x + y * y))}; /* its -Z */
        double along = 0, d2 = 0;
        for (int k = 0; k < 3; ++k) {
            along += (c[k] - cam.position[k]) * f[k];
            d2 += (c[k] - cam.position[k]) * (c[k] - cam.position[k]);
        }
        distance = along > radius * 1e-3 && isfinite(along) ? along : radius * 2.5;
        for (int k = 0; k < 3; ++k)
            center[k] = cam.position[k] + f[k] * distance;
        pitch = asin(fmax(-1.0, fmin(1.0, -f[1])));
        yaw = atan2(-f[0], -f[2]);
        ipd = mvr_stereo_default_ipd(sqrt(d2)); /* as mvr_view_set_from_camera's */
        if (cam.projection.type == MVR_PROJECTION_PERSPECTIVE && cam.projection.yfov > 0)
            yfov = cam.projection.yfov;
    }
    v->yfov = yfov;
    memcpy(v->home.center, center, sizeof center);
    v->home.distance = distance;
    v->home.yaw = yaw;
    v->home.pitch = pitch;
    v->home.ipd = ipd > 0 ? ipd : mvr_stereo_default_ipd(distance); /* each scene its own; [ and ] scale it */
    go_home(v);
}

/* Opens a file or a demo as mvr render shows it: the same scene and views
 * (cli_load_scene: a file's first camera, else the stereo framing), the
 * same render defaults, exposure (mvr_render_desc_choose_exposure) and
 * environment (cli_env_create: neutral for files, none for demos unless
 * --env says). The views' aspect is the layers' for the display and the
 * view count: a demo opened with its own count (view_count 0) whose count
 * changes the layer size (grid) is opened again with that count. On
 * failure the scene shown stays. */
static bool open_scene(viewer *v, const char *file, const char *demo)
{
    mvr_scene *scene = NULL;
    mvr_view_set *views = NULL;
    uint32_t count = v->view_count, layer_w, layer_h;
    for (int attempt = 0;; ++attempt) {
        layer_size(v, count, &layer_w, &layer_h);
        cli_scene_options so = {.demo = demo, .scene_file = file, .camera = file ? CLI_CAMERA_IF_ANY : -1,
                                .layout = MVR_LAYOUT_STEREO, .views = count, .width = layer_w, .height = layer_h};
        so.logger.fn = log_fn;
        if (cli_load_scene("mvr-viewer", &so, &scene, &views) != MVR_EXIT_OK)
            return false;
        uint32_t got = mvr_view_set_count(views), w = 0, h = 0;
        layer_size(v, got, &w, &h);
        if (attempt > 0 || (w == layer_w && h == layer_h))
            break;
        mvr_view_set_destroy(views);
        mvr_scene_destroy(scene);
        views = NULL;
        scene = NULL;
        count = got;
    }
    mvr_render_desc render;
    cli_render_desc_defaults(&render);
    if (v->clear.set)
        memcpy(render.clear_color, v->clear.rgba, sizeof v->clear.rgba);
    mvr_environment *env = NULL;
    if (cli_env_create("mvr-viewer", &v->env_options, file != NULL, &render, &env, NULL) != MVR_EXIT_OK) {
        mvr_view_set_destroy(views);
        mvr_scene_destroy(scene);
        return false;
    }
    mvr_render_desc_choose_exposure(scene, &render); /* after the environment: it weighs in */
    viewer_playback playback;
    if (!viewer_playback_open(&playback, scene, file ? file : demo, v->start_animation, v->start_time,
                              v->start_paused)) {
        mvr_environment_destroy(env);
        mvr_view_set_destroy(views);
        mvr_scene_destroy(scene);
        return false;
    }
    v->playback = playback;
    v->start_animation = NULL;
    v->start_time = -1.0;
    v->start_paused = false;
    snprintf(v->scene_name, sizeof v->scene_name, "%s", file ? file : demo);
    mvr_scene_destroy(v->scene);
    mvr_view_set_destroy(v->views);
    mvr_environment_destroy(v->env);
    v->scene = scene;
    v->views = views;
    v->env = env;
    v->render = render;
    v->view_count = mvr_view_set_count(views);
    v->layer_w = layer_w;
    v->layer_h = layer_h;
    set_home(v, file != NULL);
    v->dirty_views = false;    /* the scene's own views until the camera moves */
    v->dirty_renderer = true;  /* the layer count may have changed */
    return true;
}

/* The composite: a per-layer draw into the layer's rectangle of the window.
 * It reads texels exactly (texelFetch: the sRGB sampler decodes them) and
 * writes the exact sRGB encoding back, so the window shows the stored bytes
 * on any default framebuffer (a blit would decode sRGB on the way on Mesa,
 * desktop GL and GLES alike). mode 1: anaglyph, red from layer x, green and
 * blue from layer y. */
static const char *composite_fs =
    "precision highp float;\n"
    "precision highp int;\n"
    "precision highp sampler2DArray;\n"
    "uniform sampler2DArray layers_tex;\n"
    "uniform ivec2 layers;   /* x: the layer; anaglyph: x left, y right */\n"
    "uniform ivec2 origin;   /* the rectangle's lower-left corner in the window */\n"

    "uniform int mode;\n"
    "out vec4 o_color;\n"
    "vec3 encode(vec3 c) {\n"
    "    c = clamp(c, 0.0, 1.0);\n"
    "    return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, c * 12.92, vec3(lessThanEqual(c, vec3(0.0031308))));\n"
    "}\n"
    "void main() {\n"
    "    ivec2 p = ivec2(gl_FragCoord.xy) - origin; /* both bottom-up, as GL stores them */\n"
    "    vec3 a = texelFetch(layers_tex, ivec3(p, layers.x), 0).rgb;\n"
    "    if (mode == 1)\n"
    "        a = vec3(a.r, texelFetch(layers_tex, ivec3(p, layers.y), 0).gb);\n"
    "    o_color = vec4(encode(a), 1.0);\n"
    "}\n";
static const char *composite_vs =
    "void main() {\n"
    "    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
    "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
    "}\n";

static bool make_composite(viewer *v, bool gles)
{
    const viewer_gl *gl = &v->gl;
    const char *version = gles ? "#version 300 es\n" : "#version 330 core\n";
    const char *srcs[2][2] = {{version, composite_vs}, {version, composite_fs}};
    GLenum kinds[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    v->program = gl->CreateProgram();
    for (int i = 0; i < 2; ++i) {
        GLuint sh = gl->CreateShader(kinds[i]);
        gl->ShaderSource(sh, 2, srcs[i], NULL);
        gl->CompileShader(sh);
        GLint ok = 0;
        gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[1024] = "";
            gl->GetShaderInfoLog(sh, sizeof log, NULL, log);
            fprintf(stderr, "mvr-viewer: composite shader: %s\n", log);
            return false;
        }
        gl->AttachShader(v->program, sh);
        gl->DeleteShader(sh);
    }
    gl->LinkProgram(v->program);
    GLint linked = 0;
    gl->GetProgramiv(v->program, GL_LINK_STATUS, &linked);
    if (!linked) {
        fprintf(stderr, "mvr-viewer: composite program does not link\n");
        return false;
    }
    v->loc_layers = gl->GetUniformLocation(v->program, "layers");
    v->loc_origin = gl->GetUniformLocation(v->program, "origin");
    v->loc_mode = gl->GetUniformLocation(v->program, "mode");
    gl->GenVertexArrays(1, &v->vao);
    return true;
}

static void composite(viewer *v)
{
    const viewer_gl *gl = &v->gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->Disable(GL_SCISSOR_TEST);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_BLEND);
    gl->Disable(GL_CULL_FACE);
    if (v->desktop) /* mvr leaves sRGB writes on (desktop GL); the shader encodes itself */
        gl->Disable(0x8DB9 /* GL_FRAMEBUFFER_SRGB */);
    gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->Viewport(0, 0, v->fb_width, v->fb_height);
    gl->ClearColor(0.05f, 0.05f, 0.05f, 1.0f);
    gl->Clear(GL_COLOR_BUFFER_BIT);
    gl->UseProgram(v->program);
    gl->BindVertexArray(v->vao);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D_ARRAY, mvr_target_color_texture(v->target));
    GLint w = (GLint)v->layer_w, h = (GLint)v->layer_h;
    uint32_t cols = grid_columns(v->view_count);
    for (uint32_t k = 0; k < v->view_count; ++k) {
        GLint x = 0, y = 0, mode = 0, other = 0;
        switch (v->display) {
        case DISPLAY_STEREO:
            if (k > 1)
                continue;
            x = (GLint)k * w;
            break;
        case DISPLAY_GRID:
            x = (GLint)(k % cols) * w;
            y = v->fb_height - (GLint)(k / cols + 1) * h; /* first row at the top */
            break;
        case DISPLAY_ANAGLYPH:
            if (k > 0)
                continue;
            mode = 1;
            other = v->view_count > 1 ? 1 : 0;
            break;
        case DISPLAY_SINGLE:
            if (k != v->single % v->view_count) /* k < view_count: not 0 here */
                continue;
            break;
        case DISPLAY_COUNT:
            continue;
        }
        gl->Viewport(x, y, w, h);
        gl->Uniform2i(v->loc_layers, (GLint)k, other);
        gl->Uniform2i(v->loc_origin, x, y);
        gl->Uniform1i(v->loc_mode, mode);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
    }
    gl->BindVertexArray(0);
    gl->UseProgram(0);
}

/* Window contents (the back buffer before the swap) as a PNG. */
static bool screenshot(viewer *v, const char *path)
{
    const viewer_gl *gl = &v->gl;
    uint8_t *px = malloc((size_t)v->fb_width * (size_t)v->fb_height * 4);
    if (!px)
        return false;
    gl->BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl->ReadPixels(0, 0, v->fb_width, v->fb_height, GL_RGBA, GL_UNSIGNED_BYTE, px);
    mvr_image_view img = {(uint32_t)v->fb_width, (uint32_t)v->fb_height, MVR_PIXEL_U8, true /* GL's row order */, px};
    mvr_error err;
    bool ok = mvr_image_write(path, &img, &err) == MVR_OK;
    if (!ok)
        fprintf(stderr, "mvr-viewer: %s\n", err.message);
    free(px);
    return ok;
}

static void update_title(viewer *v, double frame_ms)
{
    mvr_frame_stats st;
    mvr_renderer_get_stats(v->renderer, &st);
    char anim[320], variant[160] = "", title[1024];
    viewer_playback_title(&v->playback, v->scene, anim, sizeof anim);
    if (mvr_scene_variant_count(v->scene)) {
        char label[128];
        cli_variant_label(v->scene, mvr_scene_selected_variant(v->scene), label, sizeof label);
        snprintf(variant, sizeof variant, " | variant %s", label);
    }
    snprintf(title, sizeof title,
             "mvr-viewer: %s | %u views (%s) | %.1f ms | %s, %u passes | %s | %u draws in %u calls | ipd %.3g%s%s",
             v->scene_name, v->view_count, viewer_display_name(v->display), frame_ms, mvr_view_path_name(st.view_path),
             st.passes, mvr_material_path_name(st.material_path), st.draws, st.draw_calls, v->ipd, anim, variant);
    glfwSetWindowTitle(v->window, title);
}

static viewer *from(GLFWwindow *w)
{
    return glfwGetWindowUserPointer(w);
}

static void on_resize(GLFWwindow *w, int width, int height)
{
    viewer *v = from(w);
    v->fb_width = width;
    v->fb_height = height;
    v->dirty_renderer = true;
    v->dirty_views = true;
}

static void on_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    viewer *v = from(w);
    bool down = action == GLFW_PRESS;
    if (button == GLFW_MOUSE_BUTTON_LEFT)
        v->dragging_orbit = down;
    else if (button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE)
        v->dragging_pan = down;
    glfwGetCursorPos(w, &v->last_x, &v->last_y);
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
    viewer *v = from(w);
    double dx = x - v->last_x, dy = y - v->last_y;
    v->last_x = x;
    v->last_y = y;
    if (v->dragging_orbit) {
        v->yaw -= dx * 0.01;
        v->pitch += dy * 0.01;
        v->pitch = fmax(-1.5, fmin(1.5, v->pitch));
        v->dirty_views = true;
    } else if (v->dragging_pan) {
        double s = v->distance * 0.002;
        double cy = cos(v->yaw), sy = sin(v->yaw);
        v->center[0] -= (dx * cy) * s;
        v->center[2] -= (-dx * sy) * s;
        v->center[1] += dy * s;
        v->dirty_views = true;
    }
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    viewer *v = from(w);
    v->distance *= pow(0.9, dy);
    v->dirty_views = true;
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    if (action != GLFW_PRESS && action != GLFW_REPEAT)
        return;
    viewer *v = from(w);
    if (viewer_playback_key(&v->playback, v->scene, key, mods))
        return;
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    case GLFW_KEY_LEFT_BRACKET: v->ipd /= 1.25; v->dirty_views = true; break;
    case GLFW_KEY_RIGHT_BRACKET: v->ipd *= 1.25; v->dirty_views = true; break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
        if (v->view_count < 64)
            v->view_count++;
        v->dirty_views = v->dirty_renderer = true;
        break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
        if (v->view_count > 1)
            v->view_count--;
        v->dirty_views = v->dirty_renderer = true;
        break;
    case GLFW_KEY_P:
        v->view_path = (mvr_view_path)((v->view_path + 1) % 3); /* auto, multiview, loop */
        v->dirty_renderer = true;
        break;
    case GLFW_KEY_M:
        v->material_path = v->material_path == MVR_MATERIAL_PATH_PER_MATERIAL ? MVR_MATERIAL_PATH_ARRAYS
                                                                              : MVR_MATERIAL_PATH_PER_MATERIAL;
        v->dirty_renderer = true;
        break;
    case GLFW_KEY_D:
        v->display = (display_mode)((v->display + 1) % DISPLAY_COUNT);
        v->dirty_renderer = v->dirty_views = true;
        break;
    case GLFW_KEY_TAB: v->single++; break;
    case GLFW_KEY_R: go_home(v); v->dirty_views = true; break;
    case GLFW_KEY_V: {
        /* material variants in turn, the file's own materials after the last (position n) */
        uint32_t n = mvr_scene_variant_count(v->scene), at = mvr_scene_selected_variant(v->scene);
        at = at == MVR_VARIANT_DEFAULT ? n : at;
        at = (mods & GLFW_MOD_SHIFT) ? (at + n) % (n + 1) : (at + 1) % (n + 1);
        if (n)
            mvr_scene_select_variant(v->scene, at == n ? MVR_VARIANT_DEFAULT : at);
        break;
    }
    default: break;
    }
}

static void on_drop(GLFWwindow *w, int count, const char **paths)
{
    viewer *v = from(w);
    if (count > 0)
        open_scene(v, paths[0], NULL);
}

int main(int argc, char **argv)
{
    cli_tune_allocator();
    viewer_options o;
    int parsed = viewer_options_parse(argc, argv, &o);
    if (parsed != 0)
        return parsed < 0 ? 0 : parsed;
    const char *file = o.file, *demo = o.demo, *shot = o.screenshot;
    uint32_t frames = o.frames;
    bool gles = o.gles;
    viewer v;
    memset(&v, 0, sizeof v);
    v.display = o.display;
    v.view_count = o.views;
    v.single = o.single;
    v.view_path = o.view_path, v.aa = o.aa;
    v.env_options = o.env;
    v.clear = o.clear;
    v.start_animation = o.animation;
    v.start_time = o.time;
    v.start_paused = o.paused;
    if (!glfwInit()) {
        fprintf(stderr, "mvr-viewer: glfwInit failed (no display?)\n");
        return 1;
    }
    if (gles) {
        glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
        glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    } else {
        glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    }
    v.window = glfwCreateWindow((int)o.width, (int)o.height, "mvr-viewer", NULL, NULL);
    if (!v.window) {
        fprintf(stderr, "mvr-viewer: no %s window\n", gles ? "GLES 3.1" : "desktop GL 4.3 core");
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(v.window);
    v.desktop = !gles;
    glfwSwapInterval(frames ? 0 : 1);
    glfwSetWindowUserPointer(v.window, &v);
    glfwGetFramebufferSize(v.window, &v.fb_width, &v.fb_height);
    int rc = 1;
    mvr_context_desc cd = {0};
    cd.provider = MVR_CONTEXT_PROVIDER_EXTERNAL;
    cd.api = gles ? MVR_GL_API_GLES : MVR_GL_API_DESKTOP;
    cd.get_proc_address = get_proc;
    cd.logger.fn = log_fn;
    mvr_error err;
    if (!load_gl(&v.gl) || mvr_context_create(&cd, &v.ctx, &err) != MVR_OK) {
        fprintf(stderr, "mvr-viewer: %s\n", v.ctx ? "" : err.message);
        goto done;
    }
    if (v.view_count == 0 && file)
        v.view_count = 2;
    if (!open_scene(&v, file, demo))
        goto done;
    if (!make_composite(&v, gles))
        goto done;
    glfwSetFramebufferSizeCallback(v.window, on_resize);
    glfwSetMouseButtonCallback(v.window, on_button);
    glfwSetCursorPosCallback(v.window, on_cursor);
    glfwSetScrollCallback(v.window, on_scroll);
    glfwSetKeyCallback(v.window, on_key);
    glfwSetDropCallback(v.window, on_drop);
    v.dirty_renderer = true;
    double last_frame = glfwGetTime();
    for (unsigned f = 0; !glfwWindowShouldClose(v.window) && (frames == 0 || f < frames); ++f) {
        if (v.dirty_renderer) {
            if (!make_renderer(&v))
                goto done;
            v.dirty_renderer = false;
        }
        if (v.dirty_views) {
            if (!make_views(&v))
                goto done;
            v.dirty_views = false;
        }
        double t0 = glfwGetTime();
        /* playback: a fixed 1/30 s per frame with --frames (reproducible
         * screenshots), else the clock (at most 1/4 s at once: a stall
         * does not jump) */
        if (f > 0)
            viewer_playback_advance(&v.playback, frames ? VIEWER_PLAYBACK_STEP : fmin(t0 - last_frame, 0.25));
        last_frame = t0;
        if (!viewer_playback_apply(&v.playback, v.scene))
            goto done;
        if (mvr_renderer_render(v.renderer, v.scene, v.views, v.target, &v.render) != MVR_OK) {
            fprintf(stderr, "mvr-viewer: %s\n", mvr_renderer_last_error(v.renderer));
            goto done;
        }
        composite(&v);
        double ms = (glfwGetTime() - t0) * 1e3;
        update_title(&v, ms);
        if (shot && frames && f + 1 == frames && !screenshot(&v, shot))
            goto done;
        glfwSwapBuffers(v.window);
        glfwPollEvents();
    }
    rc = 0;
done:
    if (v.program) {
        v.gl.DeleteProgram(v.program);
        v.gl.DeleteVertexArrays(1, &v.vao);
    }
    mvr_target_destroy(v.target);
    mvr_renderer_destroy(v.renderer);
    mvr_view_set_destroy(v.views);
    mvr_scene_destroy(v.scene);
    mvr_environment_destroy(v.env);
    mvr_context_destroy(v.ctx);
    cli_pin_loaded_libraries(); /* sanitizer builds: the GL driver's libraries stay named at exit */
    glfwDestroyWindow(v.window);
    glfwTerminate();
    return rc;
}
