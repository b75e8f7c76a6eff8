/* embed.c: mvr inside an application that owns the GL. It creates its own
 * EGL context and its own 2-layer color texture array (as an OpenXR GLES
 * swapchain hands one over), gives both to mvr, renders a scene built in
 * code, and reads the two layers back. Pure C: links mvr_gl and mvr_core,
 * EGL, and nothing of C++.
 *
 * usage: embed [--demo NAME] [--size WxH] [--out PREFIX]
 *        writes PREFIX_0.ppm and PREFIX_1.ppm (default PREFIX: embed) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>

#include "mvr/mvr.h"

/* The application's own GL calls, loaded through EGL. */
typedef struct app_gl {
    PFNGLGENTEXTURESPROC GenTextures;
    PFNGLBINDTEXTUREPROC BindTexture;
    PFNGLTEXSTORAGE3DPROC TexStorage3D;
    PFNGLDELETETEXTURESPROC DeleteTextures;
} app_gl;

static void *get_proc(const char *name, void *user)
{
    (void)user;
    void (*fn)(void) = eglGetProcAddress(name);
    void *p = NULL;
    memcpy(&p, &fn, sizeof p); /* POSIX: function and object pointers convert */
    return p;
}

static void log_fn(mvr_log_level level, mvr_log_id id, const char *message, void *user)
{
    (void)id;
    (void)user;
    if (level == MVR_LOG_ERROR || level == MVR_LOG_WARNING)
        fprintf(stderr, "embed: mvr: %s\n", message);
}

/* The application's EGL context: surfaceless Mesa, GLES 3. */
static bool make_context(EGLDisplay *out_dpy, EGLContext *out_ctx)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL)
                                 : EGL_NO_DISPLAY;
    EGLint major = 0, minor = 0;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor) || !eglBindAPI(EGL_OPENGL_ES_API)) {
        fprintf(stderr, "embed: no surfaceless EGL display (0x%x)\n", eglGetError());
        return false;
    }
    const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 1, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attrs);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        fprintf(stderr, "embed: no GLES 3.1 context (0x%x)\n", eglGetError());
        return false;
    }
    *out_dpy = dpy;
    *out_ctx = ctx;
    return true;
}

/* A scene built in code: a floor, three boxes, a light. */
static mvr_scene *make_scene(void)
{
    mvr_scene *s = NULL;
    if (mvr_scene_create(NULL, &s, NULL) != MVR_OK)
        return NULL;
    static const float pos[24] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1};
    static const uint16_t idx[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                     3, 6, 2, 3, 7, 6, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
    const float colors[4][3] = {{0.8f, 0.8f, 0.8f}, {0.9f, 0.2f, 0.1f}, {0.1f, 0.7f, 0.2f}, {0.2f, 0.3f, 0.9f}};
    const double places[4][6] = {{0, -1.1, 0, 6, 0.1, 6}, {-1.5, 0, 0, 0.5, 1, 0.5},
                                 {0, 0, -1, 0.6, 0.6, 0.6}, {1.6, 0.2, 0.5, 0.4, 1.2, 0.4}};
    for (int i = 0; i < 4; ++i) {
        mvr_material_desc m = mvr_material_defaults();
        memcpy(m.base_color_factor, colors[i], sizeof colors[i]);
        m.metallic_factor = 0;
        m.roughness_factor = 0.6f;
        mvr_material_id mat;
        mvr_primitive_desc p = {.vertex_count = 8, .positions = pos, .index_count = 36, .indices16 = idx};
        mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "box"};
        mvr_mesh_id mesh;
        mvr_node_id node;
        if (mvr_scene_add_material(s, &m, &mat) != MVR_OK)
            break;
        p.material = mat;
        mvr_node_desc nd = {.translation = {places[i][0], places[i][1], places[i][2]},
                            .scale = {places[i][3], places[i][4], places[i][5]}};
        if (mvr_scene_add_mesh(s, &md, &mesh) != MVR_OK)
            break;
        nd.mesh = mesh;
        mvr_scene_add_node(s, &nd, &node);
    }
    mvr_light_desc ld = {.type = MVR_LIGHT_POINT, .intensity = 40.0f};
    mvr_light_id light;
    mvr_node_id ln;
    if (mvr_scene_add_light(s, &ld, &light) == MVR_OK) {
        mvr_node_desc nd = {.light = light, .translation = {2, 4, 3}};
        mvr_scene_add_node(s, &nd, &ln);
    }
    const float ambient[3] = {0.08f, 0.08f, 0.1f};
    mvr_scene_set_ambient(s, ambient);
    return s;
}

static mvr_view_set *make_views(uint32_t w, uint32_t h)
{
    mvr_view_desc v[2];
    memset(v, 0, sizeof v);
    for (int i = 0; i < 2; ++i) {
        const double eye[3] = {i ? 0.032 : -0.032, 1.5, 6}, target[3] = {i ? 0.032 : -0.032, 0, 0}, up[3] = {0, 1, 0};
        mvr_view_look_at(&v[i], eye, target, up);
        v[i].projection.yfov = 0.8;
        v[i].projection.aspect = (double)w / (double)h;
    }
    mvr_view_set_desc d = {2, v, false, {0, 0, 0}};
    mvr_view_set *vs = NULL;
    return mvr_view_set_create(&d, &vs, NULL) == MVR_OK ? vs : NULL;
}

static bool write_ppm(const char *path, const uint8_t *rgba, uint32_t w, uint32_t h)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return false;
    fprintf(f, "P6\n%u %u\n255\n", w, h);
    /* GL reads back the bottom row first; PPM starts at the top */
    for (uint32_t y = h; y-- > 0;)
        for (uint32_t x = 0; x < w; ++x)
            fwrite(rgba + ((size_t)y * w + x) * 4, 1, 3, f);
    return fclose(f) == 0;
}

int main(int argc, char **argv)
{
    const char *demo = NULL, *out = "embed";
    unsigned w = 320, h = 240;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--demo") == 0)
            demo = argv[i + 1];
        else if (strcmp(argv[i], "--out") == 0)
            out = argv[i + 1];
        else if (strcmp(argv[i], "--size") != 0 || sscanf(argv[i + 1], "%ux%u", &w, &h) != 2) {
            fprintf(stderr, "usage: embed [--demo NAME] [--size WxH] [--out PREFIX]\n");
            return 2;
        }
    }
    EGLDisplay dpy;
    EGLContext egl_ctx;
    if (!make_context(&dpy, &egl_ctx))
        return 1;
    app_gl gl = {(PFNGLGENTEXTURESPROC)eglGetProcAddress("glGenTextures"),
                 (PFNGLBINDTEXTUREPROC)eglGetProcAddress("glBindTexture"),
                 (PFNGLTEXSTORAGE3DPROC)eglGetProcAddress("glTexStorage3D"),
                 (PFNGLDELETETEXTURESPROC)eglGetProcAddress("glDeleteTextures")};
    if (!gl.GenTextures || !gl.BindTexture || !gl.TexStorage3D || !gl.DeleteTextures) {
        fprintf(stderr, "embed: GL entry points missing\n");
        return 1;
    }
    /* the application's swapchain-like image: 2 layers, sRGB */
    GLuint swapchain = 0;
    gl.GenTextures(1, &swapchain);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, swapchain);
    gl.TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_SRGB8_ALPHA8, (GLsizei)w, (GLsizei)h, 2);

    int rc = 1;
    mvr_context *ctx = NULL;
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_scene *scene = NULL;
    mvr_view_set *views = NULL;
    uint8_t *pixels = malloc((size_t)w * h * 4);
    mvr_error err;
    mvr_context_desc cd = {0};
    cd.provider = MVR_CONTEXT_PROVIDER_EXTERNAL; /* ours: mvr creates nothing, makes nothing current */
    cd.get_proc_address = get_proc;
    cd.logger.fn = log_fn;
    if (!pixels || mvr_context_create(&cd, &ctx, &err) != MVR_OK) {
        fprintf(stderr, "embed: %s\n", pixels ? err.message : "out of memory");
        goto done;
    }
    if (demo) {
        mvr_demo_desc dd = {2, w, h, cd.logger};
        if (mvr_demo_create(demo, &dd, &scene, &views, &err) != MVR_OK) {
            fprintf(stderr, "embed: %s\n", err.message);
            goto done;
        }
    } else {
        scene = make_scene();
        views = make_views(w, h);
    }
    mvr_renderer_desc rd = {.context = ctx};
    mvr_target_desc td = {w, h, 2, MVR_COLOR_FORMAT_DEFAULT, swapchain, 0, 0, 0, 0, MVR_ANTI_ALIASING_DEFAULT, 0};
    if (!scene || !views || mvr_renderer_create(&rd, &r, &err) != MVR_OK) {
        fprintf(stderr, "embed: %s\n", scene && views ? err.message : "scene");
        goto done;
    }
    if (mvr_target_create(r, &td, &target) != MVR_OK || mvr_renderer_render(r, scene, views, target, NULL) != MVR_OK) {
        fprintf(stderr, "embed: %s\n", mvr_renderer_last_error(r));
        goto done;
    }
    for (uint32_t k = 0; k < 2; ++k) {
        char path[1024];
        snprintf(path, sizeof path, "%s_%u.ppm", out, k);
        if (mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, pixels, (size_t)w * h * 4) != MVR_OK ||
            !write_ppm(path, pixels, w, h)) {
            fprintf(stderr, "embed: layer %u: %s\n", k, mvr_renderer_last_error(r));
            goto done;
        }
        printf("embed: layer %u -> %s\n", k, path);
    }
    rc = 0;
done:
    mvr_target_destroy(target); /* the swapchain texture stays the application's */
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(views);
    mvr_scene_destroy(scene);
    mvr_context_destroy(ctx);
    gl.DeleteTextures(1, &swapchain);
    free(pixels);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, egl_ctx);
    eglTerminate(dpy);
    return rc;
}
