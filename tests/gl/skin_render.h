/* Rendering helpers of the skinning tests (tests/gl/test_skinning.c,
 * tests/io/test_rigged_file.c): one render of a view set with forced view
 * and skinning paths, read back; pixel differences. */
#ifndef MVR_TEST_SKIN_RENDER_H
#define MVR_TEST_SKIN_RENDER_H

#include <stdlib.h>
#include <string.h>

#include "mvr/mvr.h"
#include "mvr_test.h"
#include "scene_internal.h"

typedef struct shot {
    uint8_t *pixels;             /* views x width x height RGBA8, NULL when the render failed */
    mvr_frame_stats stats;       /* of the first frame */
} shot;

/* frames renders (the last one is read back; the stats are the first's)
 * of every view into width x height layers; shadows from every
 * directional light when asked. */
static inline bool render_shot(mvr_test_state *t, mvr_context *ctx, mvr_scene *scene, mvr_view_set *vs,
                               mvr_view_path path, mvr_skinning_path skin, bool shadows, uint32_t width,
                               uint32_t height, int frames, shot *out)
{
    memset(out, 0, sizeof *out);
    uint32_t views = mvr_view_set_count(vs);
    mvr_renderer_desc rd = {.context = ctx, .view_path = path, .skinning_path = skin};
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_error err;
    mvr_target_desc td = {.width = width, .height = height, .layers = views, .anti_aliasing = MVR_ANTI_ALIASING_NONE};
    bool ok = mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK;
    CHECK_MSG(t, ok, "renderer / target: %s", r ? mvr_renderer_last_error(r) : err.message);
    mvr_render_desc desc = {.clear_color = {0.05f, 0.05f, 0.05f, 1.0f}, .exposure = 1.0f};
    desc.shadows.mode = shadows ? MVR_SHADOWS_ALL : MVR_SHADOWS_OFF;
    for (int frame = 0; ok && frame < frames; ++frame) {
        ok = mvr_renderer_render(r, scene, vs, target, &desc) == MVR_OK;
        CHECK_MSG(t, ok, "render (%s, %s): %s", mvr_view_path_name(path), mvr_skinning_path_name(skin),
                  mvr_renderer_last_error(r));
        if (ok && frame == 0)
            mvr_renderer_get_stats(r, &out->stats);
    }
    size_t layer = (size_t)width * height * 4;
    if (ok && (out->pixels = malloc(views * layer)) != NULL) {
        for (uint32_t k = 0; ok && k < views; ++k)
            ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, out->pixels + k * layer, layer) ==
                 MVR_OK;
        CHECK(t, ok);
        if (!ok) {
            free(out->pixels);
            out->pixels = NULL;
        }
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    return ok && out->pixels;
}

/* The CPU reference of one primitive as node `node` of `posed` draws it:
 * a plain mesh (and node) in `s` at its posed vertices (double, narrowed
 * once), with its posed normals (posed_normals) or its own bind-pose ones. */
static inline void add_posed_copy(mvr_test_state *t, mvr_scene *s, const mvr_scene *posed, uint32_t node,
                                  uint32_t primitive, mvr_material_id mat, bool posed_normals)
{
    const scene_primitive *p = &posed->primitives[primitive];
    size_t n = (size_t)p->vertex_count * 3;
    double *pos = malloc(n * sizeof *pos), *nrm = posed_normals ? malloc(n * sizeof *nrm) : NULL;
    float *fpos = malloc(n * sizeof *fpos), *fnrm = posed_normals ? malloc(n * sizeof *fnrm) : NULL;
    bool ok = pos && fpos && mvr_scene_posed_positions(posed, node, primitive, pos);
    ok = ok && (!posed_normals || (nrm && fnrm && mvr_scene_posed_normals(posed, node, primitive, nrm)));
    CHECK(t, ok);
    for (size_t i = 0; ok && i < n; ++i) {
        fpos[i] = (float)pos[i];
        if (fnrm)
            fnrm[i] = (float)nrm[i];
    }
    if (ok) {
        mvr_primitive_desc pd = {.vertex_count = p->vertex_count, .positions = fpos,
                                 .normals = posed_normals ? fnrm : p->normals, .index_count = p->index_count,
                                 .indices32 = p->indices, .material = mat};
        mvr_mesh_desc mesh = {.primitives = &pd, .primitive_count = 1, .name = "posed"};
        mvr_mesh_id mid;
        CHECK(t, mvr_scene_add_mesh(s, &mesh, &mid) == MVR_OK);
        mvr_node_desc nd = {.mesh = mid};
        mvr_node_id id;
        CHECK(t, mvr_scene_add_node(s, &nd, &id) == MVR_OK);
    }
    free(pos);
    free(nrm);
    free(fpos);
    free(fnrm);
}

/* Pixels whose RGBA differs by more than tolerance in some channel. */
static inline uint32_t count_diff(const uint8_t *a, const uint8_t *b, size_t pixels, int tolerance)
{
    uint32_t n = 0;
    for (size_t i = 0; i < pixels; ++i)
        for (size_t c = 0; c < 4; ++c)
            if (abs((int)a[i * 4 + c] - (int)b[i * 4 + c]) > tolerance) {
                n++;
                break;
            }
    return n;
}

#endif
