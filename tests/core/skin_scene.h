/* Test scenes with a skin and morph targets, built through the public API
 * (shared by tests/core/test_scene_animation.c and tests/gl/test_skinning.c).
 *
 * The two-bone strip: a vertical strip x in [-0.125, 0.125], y in [0, 2], rows
 * every 0.5; joint "root" at the origin, joint "tip" (its child) at y = 1.
 * Rows y <= 0.5 follow root, the row y = 1 both (weights 2 and 2, which the
 * scene normalises to 0.5 and 0.5), rows y >= 1.5 tip. The mesh's node is
 * translated by (5, 5, 5): a skinned mesh ignores its node's transform.
 * With tip rotated by `degrees` about +Z, a vertex (x, y) of a tip row lands
 * at tip(x, y - 1) + (0, 1): for 90 degrees (-(y - 1), 1 + x).
 *
 * The morph quad: [-1, 1] x [-1, 1] at z = 0 with two targets: 0 moves the
 * top edge by (0, 1, 0), 1 moves every vertex by (1, 0, 0); default weights
 * (0.5, 0). */
#ifndef MVR_TEST_SKIN_SCENE_H
#define MVR_TEST_SKIN_SCENE_H

#include <math.h>
#include <string.h>

#include "mvr/mvr.h"

typedef struct skin_scene {
    mvr_node_id root, tip, body;
    mvr_skin_id skin;
    mvr_node_id quad;
} skin_scene;

#define STRIP_ROWS 5
#define STRIP_VERTICES (2 * STRIP_ROWS)

static inline void strip_rotate_tip(mvr_scene *s, const skin_scene *k, double degrees)
{
    double a = degrees * 3.14159265358979323846 / 180.0;
    const double t[3] = {0, 1, 0}, r[4] = {0, 0, sin(a / 2), cos(a / 2)}, sc[3] = {1, 1, 1};
    mvr_scene_set_node_transform(s, k->tip, t, r, sc);
}

/* eight: the strip's tip influence of the row y = 1 moves to a second
 * set (JOINTS_1 / WEIGHTS_1): the same skin through eight influences. */
static inline mvr_result build_skin_scene_sets(mvr_scene *s, skin_scene *out, bool with_strip, bool with_quad,
                                               bool eight)
{
    memset(out, 0, sizeof *out);
    mvr_result res = MVR_OK;
    mvr_material_desc md = mvr_material_defaults();
    md.base_color_factor[0] = 0.9f;
    md.base_color_factor[1] = 0.6f;
    md.base_color_factor[2] = 0.2f;
    md.base_color_factor[3] = 1.0f;
    md.metallic_factor = 0.0f;
    md.roughness_factor = 0.6f;
    md.double_sided = true;
    mvr_material_id mat;
    if ((res = mvr_scene_add_material(s, &md, &mat)) != MVR_OK)
        return res;
    if (with_strip) {
        float pos[STRIP_VERTICES * 3], nrm[STRIP_VERTICES * 3], w[STRIP_VERTICES * 4], w1[STRIP_VERTICES * 4];
        uint16_t j[STRIP_VERTICES * 4], j1[STRIP_VERTICES * 4];
        memset(w, 0, sizeof w);
        memset(j, 0, sizeof j);
        memset(w1, 0, sizeof w1);
        memset(j1, 0, sizeof j1);
        for (int row = 0; row < STRIP_ROWS; ++row)
            for (int side = 0; side < 2; ++side) {
                int v = row * 2 + side;
                float y = 0.5f * (float)row;
                pos[v * 3] = side ? 0.125f : -0.125f;
                pos[v * 3 + 1] = y;
                pos[v * 3 + 2] = 0.0f;
                nrm[v * 3] = 0.0f;
                nrm[v * 3 + 1] = 0.0f;
                nrm[v * 3 + 2] = 1.0f;
                if (y < 1.0f) {
                    w[v * 4] = 1.0f;
                } else if (y == 1.0f) {
                    w[v * 4] = 2.0f;
                    if (eight) {
                        j1[v * 4] = 1;
                        w1[v * 4] = 2.0f;
                    } else {
                        j[v * 4 + 1] = 1;
                        w[v * 4 + 1] = 2.0f;
                    }
                } else {
                    j[v * 4] = 1;
                    w[v * 4] = 1.0f;
                }
            }
        uint16_t idx[(STRIP_ROWS - 1) * 6];
        for (int row = 0; row < STRIP_ROWS - 1; ++row) {
            uint16_t a = (uint16_t)(row * 2), b = (uint16_t)(a + 1), c = (uint16_t)(a + 2), d = (uint16_t)(a + 3);
            uint16_t tri[6] = {a, b, d, a, d, c};
            memcpy(idx + row * 6, tri, sizeof tri);
        }
        mvr_primitive_desc p = {.vertex_count = STRIP_VERTICES, .positions = pos, .normals = nrm,
                                .index_count = (STRIP_ROWS - 1) * 6, .indices16 = idx, .material = mat,
                                .joints0 = j, .weights0 = w, .joints1 = eight ? j1 : NULL,
                                .weights1 = eight ? w1 : NULL};
        mvr_mesh_desc mesh = {.primitives = &p, .primitive_count = 1, .name = "strip"};
        mvr_mesh_id mid;
        if ((res = mvr_scene_add_mesh(s, &mesh, &mid)) != MVR_OK)
            return res;
        mvr_node_desc root = {.name = "root"};
        if ((res = mvr_scene_add_node(s, &root, &out->root)) != MVR_OK)
            return res;
        mvr_node_desc tip = {.parent = out->root, .translation = {0, 1, 0}, .name = "tip"};
        if ((res = mvr_scene_add_node(s, &tip, &out->tip)) != MVR_OK)
            return res;
        mvr_node_desc body = {.translation = {5, 5, 5}, .mesh = mid, .name = "body"};
        if ((res = mvr_scene_add_node(s, &body, &out->body)) != MVR_OK)
            return res;
        mvr_node_id joints[2] = {out->root, out->tip};
        double ibm[32];
        memset(ibm, 0, sizeof ibm);
        for (int m = 0; m < 2; ++m)
            for (int i = 0; i < 4; ++i)
                ibm[m * 16 + i * 5] = 1.0;
        ibm[16 + 13] = -1.0; /* the tip's bind: translate(0, 1, 0), inverted */
        mvr_skin_desc sd = {.joints = joints, .joint_count = 2, .inverse_bind_matrices = ibm, .skeleton = out->root,
                            .name = "two bones"};
        if ((res = mvr_scene_add_skin(s, &sd, &out->skin)) != MVR_OK)
            return res;
        if ((res = mvr_scene_set_node_skin(s, out->body, out->skin)) != MVR_OK)
            return res;
    }
    if (with_quad) {
        const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
        const float nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
        const float up[12] = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0};
        const float right[12] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
        const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
        mvr_morph_target_desc targets[2] = {{.positions = up}, {.positions = right}};
        mvr_primitive_desc p = {.vertex_count = 4, .positions = pos, .normals = nrm, .index_count = 6,
                                .indices16 = idx, .material = mat, .targets = targets, .target_count = 2};
        const float weights[2] = {0.5f, 0.0f};
        mvr_mesh_desc mesh = {.primitives = &p, .primitive_count = 1, .name = "quad", .weights = weights,
                              .weight_count = 2};
        mvr_mesh_id mid;
        if ((res = mvr_scene_add_mesh(s, &mesh, &mid)) != MVR_OK)
            return res;
        mvr_node_desc quad = {.mesh = mid, .name = "quad"};
        if ((res = mvr_scene_add_node(s, &quad, &out->quad)) != MVR_OK)
            return res;
    }
    return MVR_OK;
}

static inline mvr_result build_skin_scene(mvr_scene *s, skin_scene *out, bool with_strip, bool with_quad)
{
    return build_skin_scene_sets(s, out, with_strip, with_quad, false);
}

#endif
