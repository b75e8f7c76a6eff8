/* One render of a view set into width x height layers, read back, with the
 * mesh programs' feature bits and the frame's stats: the material extension
 * tests' (tests/gl/test_material_ext.c, test_transmission.c). */
#ifndef MVR_TEST_RENDER_VIEWS_H
#define MVR_TEST_RENDER_VIEWS_H

#include <stdlib.h>

#include "mvr/mvr.h"
#include "mvr_test.h"

typedef struct render_views_opts {
    uint32_t width, height;
    mvr_view_path path;
    mvr_material_path material_path;
    mvr_color_format format;       /* RGBA32F: floats read back, else bytes */
    bool environment;              /* image-based lighting from environment_source */
    mvr_environment_source environment_source;
    float clear[4];
} render_views_opts;

/* The material tests' sun: a white directional light of intensity 2 from
 * above and to the side, on a node of its own. */
static inline void render_views_add_sun(mvr_test_state *t, mvr_scene *s)
{
    mvr_light_desc ld = {.type = MVR_LIGHT_DIRECTIONAL, .color = {1, 1, 1}, .intensity = 2.0f};
    mvr_light_id lid;
    CHECK(t, mvr_scene_add_light(s, &ld, &lid) == MVR_OK);
    mvr_node_desc ln = {.light = lid, .rotation = {-0.25, 0.2, 0.0, 0.95}};
    mvr_node_id n;
    CHECK(t, mvr_scene_add_node(s, &ln, &n) == MVR_OK);
}

typedef struct render_views_out {
    void *pixels;                  /* the layers, NULL when the render failed */
    uint32_t features;             /* the mesh programs' bits */
    mvr_frame_stats stats;
} render_views_out;

static inline render_views_out render_views(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, mvr_view_set *vs,
                                            const render_views_opts *o)
{
    render_views_out out = {0};
    uint32_t n = mvr_view_set_count(vs);
    mvr_renderer_desc rd = {.context = ctx, .view_path = o->path, .material_path = o->material_path};
    mvr_renderer *r = NULL;
    mvr_target *tg = NULL;
    mvr_environment *env = NULL;
    mvr_environment_desc ed = {.source = o->environment_source};
    mvr_target_desc td = {.width = o->width, .height = o->height, .layers = n, .color_format = o->format,
                          .anti_aliasing = MVR_ANTI_ALIASING_NONE};
    bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK &&
              (!o->environment || mvr_environment_create(&ed, &env, NULL) == MVR_OK);
    CHECK(t, ok);
    mvr_render_desc desc = {.exposure = 1.0f, .environment = env};
    memcpy(desc.clear_color, o->clear, sizeof desc.clear_color);
    ok = ok && mvr_renderer_render(r, s, vs, tg, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "render: %s", r ? mvr_renderer_last_error(r) : "");
    bool f32 = o->format == MVR_COLOR_FORMAT_RGBA32F;
    size_t layer = (size_t)o->width * o->height * 4 * (f32 ? sizeof(float) : 1);
    uint8_t *px = ok ? malloc(layer * n) : NULL;
    for (uint32_t k = 0; px && k < n; ++k)
        CHECK(t, mvr_renderer_read_layer(r, tg, k, f32 ? MVR_READBACK_RGBA32F : MVR_READBACK_RGBA8, px + k * layer,
                                         layer) == MVR_OK);
    out.pixels = px;
    if (r) {
        mvr_renderer_get_stats(r, &out.stats);
        for (uint32_t i = 0; i < mvr_renderer_program_count(r); ++i) {
            mvr_program_info info;
            if (mvr_renderer_get_program_info(r, i, &info) && info.mesh)
                out.features |= info.features;
        }
    }
    mvr_environment_destroy(env);
    mvr_target_destroy(tg);
    mvr_renderer_destroy(r);
    return out;
}

#endif
