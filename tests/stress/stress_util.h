/* Helpers of the stress suite: scenes built through the public API, one
 * render call returning every layer, and the accuracy record (each test
 * prints its threshold and measured value; scripts/accuracy_report turns
 * them into the README's accuracy section). */
#ifndef MVR_STRESS_UTIL_H
#define MVR_STRESS_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_test_util.h"
#include "mvr/mvr.h"

/* One line per measured figure: "ACCURACY<TAB>name<TAB>threshold<TAB>
 * measured<TAB>reason", on stdout and appended to $MVR_ACCURACY_OUT. */
static inline void stress_record(const char *name, const char *threshold, const char *measured,
                                 const char *reason)
{
    printf("ACCURACY\t%s\t%s\t%s\t%s\n", name, threshold, measured, reason);
    const char *path = getenv("MVR_ACCURACY_OUT");
    FILE *f = path && path[0] ? fopen(path, "a") : NULL;
    if (f) {
        fprintf(f, "%s\t%s\t%s\t%s\n", name, threshold, measured, reason);
        fclose(f);
    }
}

static inline mvr_scene *stress_scene(void)
{
    mvr_scene *s = NULL;
    mvr_scene_create(NULL, &s, NULL);
    return s;
}

/* An axis-aligned box of half size h: 24 vertices (normals, UVs), 36 indices. */
static inline mvr_mesh_id stress_add_box(mvr_test_state *t, mvr_scene *s, float h, mvr_material_id material)
{
    static const float axes[6][3][3] = {
        /* normal, u axis, v axis */
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    };
    float pos[72], nrm[72], uv[48];
    uint16_t idx[36];
    for (int f = 0; f < 6; ++f) {
        for (int c = 0; c < 4; ++c) {
            float su = (c == 1 || c == 2) ? 1.0f : -1.0f, sv = c >= 2 ? 1.0f : -1.0f;
            for (int k = 0; k < 3; ++k) {
                pos[(f * 4 + c) * 3 + k] = h * (axes[f][0][k] + su * axes[f][1][k] + sv * axes[f][2][k]);
                nrm[(f * 4 + c) * 3 + k] = axes[f][0][k];
            }
            uv[(f * 4 + c) * 2 + 0] = su > 0 ? 1.0f : 0.0f;
            uv[(f * 4 + c) * 2 + 1] = sv > 0 ? 0.0f : 1.0f;
        }
        const uint16_t quad[6] = {0, 1, 2, 0, 2, 3};
        for (int k = 0; k < 6; ++k)
            idx[f * 6 + k] = (uint16_t)(f * 4 + quad[k]);
    }
    mvr_primitive_desc p = {.vertex_count = 24, .positions = pos, .normals = nrm, .texcoords0 = uv,
                            .index_count = 36, .indices16 = idx, .material = material};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "box"};
    mvr_mesh_id id = {0};
    CHECK_MSG(t, mvr_scene_add_mesh(s, &md, &id) == MVR_OK, "box: %s", mvr_scene_last_error(s));
    return id;
}

/* A unit quad in the XY plane facing +Z (half size 1), UV (0,0) top-left. */
static inline mvr_mesh_id stress_add_quad(mvr_test_state *t, mvr_scene *s, mvr_material_id material)
{
    static const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    static const float nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    static const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    static const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    mvr_primitive_desc p = {.vertex_count = 4, .positions = pos, .normals = nrm, .texcoords0 = uv,
                            .index_count = 6, .indices16 = idx, .material = material};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "quad"};
    mvr_mesh_id id = {0};
    CHECK_MSG(t, mvr_scene_add_mesh(s, &md, &id) == MVR_OK, "quad: %s", mvr_scene_last_error(s));
    return id;
}

static inline mvr_material_id stress_unlit(mvr_test_state *t, mvr_scene *s, float r, float g, float b)
{
    mvr_material_desc m = mvr_material_defaults();
    m.base_color_factor[0] = r;
    m.base_color_factor[1] = g;
    m.base_color_factor[2] = b;
    m.unlit = true;
    mvr_material_id id = {0};
    CHECK(t, mvr_scene_add_material(s, &m, &id) == MVR_OK);
    return id;
}

static inline mvr_node_id stress_node(mvr_test_state *t, mvr_scene *s, mvr_mesh_id mesh, double x, double y,
                                      double z, double scale)
{
    mvr_node_desc nd = {.mesh = mesh, .translation = {x, y, z}, .scale = {scale, scale, scale}};
    mvr_node_id id = {0};
    CHECK(t, mvr_scene_add_node(s, &nd, &id) == MVR_OK);
    return id;
}

/* The image as an unlit texture on a stress_add_quad at z = -1, which fills
 * stress_front_view_set's view. */
static inline void stress_unlit_image_quad(mvr_test_state *t, mvr_scene *s, const mvr_image_desc *image)
{
    mvr_image_id img = {0};
    CHECK_MSG(t, mvr_scene_add_image(s, image, &img) == MVR_OK, "image: %s", mvr_scene_last_error(s));
    mvr_material_desc m = mvr_material_defaults();
    m.unlit = true;
    m.base_color.image = img;
    mvr_material_id mat = {0};
    CHECK(t, mvr_scene_add_material(s, &m, &mat) == MVR_OK);
    stress_node(t, s, stress_add_quad(t, s, mat), 0, 0, -1, 1.0);
}

/* One view at eye looking at target (up +Y unless looking along Y). */
static inline mvr_view_desc stress_view(const double eye[3], const double target[3], mvr_projection proj)
{
    mvr_view_desc v;
    memset(&v, 0, sizeof v);
    double up[3] = {0, 1, 0};
    if (fabs(target[0] - eye[0]) < 1e-12 && fabs(target[2] - eye[2]) < 1e-12)
        up[1] = 0, up[2] = -1;
    mvr_view_look_at(&v, eye, target, up);
    v.projection = proj;
    return v;
}

static inline mvr_view_set *stress_view_set(mvr_test_state *t, const mvr_view_desc *views, uint32_t count,
                                            const double *origin)
{
    mvr_view_set_desc d = {count, views, origin != NULL, {0, 0, 0}};
    if (origin)
        memcpy(d.origin, origin, sizeof d.origin);
    mvr_view_set *vs = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_view_set_create(&d, &vs, &err) == MVR_OK, "view set: %s", err.message);
    return vs;
}

typedef struct stress_options {
    mvr_view_path path;
    mvr_depth_mode depth;
    mvr_color_format format;
    mvr_readback_format readback; /* RGBA8: 4 bytes a pixel; RGBA32F: 16 */
    uint32_t width, height;
    float clear[4];
    mvr_shadow_desc shadows;
    const mvr_render_desc *render; /* the whole render desc (clear and shadows above unused); NULL = those */
    /* anti-aliasing: 0 (MVR_ANTI_ALIASING_DEFAULT) pins none, as these
     * renders compare bytes of other things; MSAA / SUPERSAMPLE / AUTO ask it */
    mvr_anti_aliasing aa;
} stress_options;

/* Renders every view of vs into its layer and reads them all back, layer
 * after layer. Returns NULL (after a failed check) on error. */
static inline void *stress_render(mvr_test_state *t, mvr_context *ctx, mvr_scene *scene, const mvr_view_set *vs,
                                  const stress_options *o, mvr_frame_stats *stats)
{
    uint32_t n = mvr_view_set_count(vs);
    size_t px = o->readback == MVR_READBACK_RGBA32F ? 16 : 4;
    size_t layer_bytes = (size_t)o->width * o->height * px;
    mvr_renderer_desc rd = {.context = ctx, .view_path = o->path, .depth_mode = o->depth};
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_error err;
    void *out = NULL;
    if (mvr_renderer_create(&rd, &r, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "renderer: %s", err.message);
        return NULL;
    }
    mvr_target_desc td = {o->width, o->height, n, o->format, 0, 0, 0, 0, 0,
                          o->aa == MVR_ANTI_ALIASING_DEFAULT ? MVR_ANTI_ALIASING_NONE : o->aa, 0};
    mvr_render_desc desc = {.clear_color = {o->clear[0], o->clear[1], o->clear[2], o->clear[3]},
                            .exposure = 1.0f,
                            .tone_map = MVR_TONE_MAP_NONE,
                            .shadows = o->shadows};
    if (o->render)
        desc = *o->render;
    bool ok = mvr_target_create(r, &td, &target) == MVR_OK && mvr_renderer_render(r, scene, vs, target, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "render: %s", mvr_renderer_last_error(r));
    if (ok) {
        out = malloc(layer_bytes * n);
        for (uint32_t k = 0; ok && k < n; ++k)
            ok = mvr_renderer_read_layer(r, target, k, o->readback, (uint8_t *)out + layer_bytes * k, layer_bytes) ==
                 MVR_OK;
        CHECK_MSG(t, ok, "read back: %s", mvr_renderer_last_error(r));
        if (stats)
            mvr_renderer_get_stats(r, stats);
    }
    if (!ok) {
        free(out);
        out = NULL;
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    return out;
}

static inline unsigned max_abs_diff8(const uint8_t *a, const uint8_t *b, size_t bytes)
{
    unsigned m = 0;
    for (size_t i = 0; i < bytes; ++i) {
        unsigned d = a[i] > b[i] ? (unsigned)(a[i] - b[i]) : (unsigned)(b[i] - a[i]);
        m = d > m ? d : m;
    }
    return m;
}

/* One orthographic view from the origin down -Z, 2 x 2 units: what
 * stress_unlit_image_quad fills. */
static inline mvr_view_set *stress_front_view_set(mvr_test_state *t)
{
    double eye[3] = {0, 0, 0}, target[3] = {0, 0, -1};
    mvr_projection proj = {.type = MVR_PROJECTION_ORTHOGRAPHIC, .xmag = 1, .ymag = 1, .znear = 0.1, .zfar = 10};
    mvr_view_desc v = stress_view(eye, target, proj);
    return stress_view_set(t, &v, 1, NULL);
}

#endif
