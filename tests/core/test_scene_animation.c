/* core: skins, morph targets and animations of a scene (scene_animation.c)
 * and the frame's deformation data (frame.c). The CPU reference
 * (mvr_scene_posed_positions) puts a two-bone strip's vertices where the
 * skinning formula says, a morph target at weight 0.5 moves vertices
 * halfway, animations pose nodes and weights by time, bounds follow the
 * pose, and the frame's texels hold what deform.glsl reads. Tolerances: the
 * reference is double precision, 1e-12 of unit coordinates; the frame's
 * texels are the double values narrowed to float (exact float equality). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "frame.h"
#include "mvr_test.h"
#include "scene_internal.h"
#include "skin_scene.h"

static mvr_scene *new_scene(mvr_test_state *t, skin_scene *k, bool strip, bool quad)
{
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    if (!s)
        return NULL;
    mvr_result r = build_skin_scene(s, k, strip, quad);
    CHECK_MSG(t, r == MVR_OK, "%s", mvr_scene_last_error(s));
    return s;
}

/* tolerance: 1e-12 where every input is exact in float; 1e-6 where
 * animation keys hold float quaternions (cos 45 degrees rounded) */
static double tolerance = 1e-12;

static void expect_vertex(mvr_test_state *t, const double *pos, int v, double x, double y, double z)
{
    double e = fabs(pos[v * 3] - x) + fabs(pos[v * 3 + 1] - y) + fabs(pos[v * 3 + 2] - z);
    CHECK_MSG(t, e < tolerance, "vertex %d at (%.15g, %.15g, %.15g), expected (%g, %g, %g)", v, pos[v * 3],
              pos[v * 3 + 1], pos[v * 3 + 2], x, y, z);
}

static void two_bone_skin_90_degrees(mvr_test_state *t)
{
    skin_scene k;
    mvr_scene *s = new_scene(t, &k, true, false);
    if (!s)
        return;
    double pos[STRIP_VERTICES * 3];
    /* bind pose: where the vertices are (the node's (5, 5, 5) ignored) */
    CHECK(t, mvr_scene_posed_positions(s, k.body.id - 1, 0, pos));
    for (int v = 0; v < STRIP_VERTICES; ++v)
        expect_vertex(t, pos, v, v % 2 ? 0.125 : -0.125, 0.5 * (v / 2), 0.0);
    strip_rotate_tip(s, &k, 90.0);
    CHECK(t, mvr_scene_posed_positions(s, k.body.id - 1, 0, pos));
    for (int v = 0; v < STRIP_VERTICES; ++v) {
        double x = v % 2 ? 0.125 : -0.125, y = 0.5 * (v / 2);
        if (y < 1.0)
            expect_vertex(t, pos, v, x, y, 0.0);              /* root only */
        else if (y == 1.0)
            expect_vertex(t, pos, v, 0.5 * x, 1.0 + 0.5 * x, 0.0); /* halfway: (x, 1) and (0, 1 + x) */
        else
            expect_vertex(t, pos, v, -(y - 1.0), 1.0 + x, 0.0); /* the tip's 90 degrees */
    }
    /* normals: a rotation about Z keeps +Z; a node rotated about Y turns
     * an unskinned mesh's normals with it */
    double nrm[STRIP_VERTICES * 3];
    CHECK(t, mvr_scene_posed_normals(s, k.body.id - 1, 0, nrm));
    for (int v = 0; v < STRIP_VERTICES; ++v)
        expect_vertex(t, nrm, v, 0.0, 0.0, 1.0);
    /* the weights 2 and 2 were normalised */
    const scene_primitive *p = &s->primitives[0];
    CHECK(t, p->weights[0][4 * 4] == 0.5f && p->weights[0][4 * 4 + 1] == 0.5f);
    CHECK(t, p->max_joint == 1 && p->influence_sets == 1);
    mvr_scene_destroy(s);
}

static void morph_weight_half_moves_halfway(mvr_test_state *t)
{
    skin_scene k;
    mvr_scene *s = new_scene(t, &k, false, true);
    if (!s)
        return;
    double pos[12];
    CHECK(t, mvr_scene_posed_positions(s, k.quad.id - 1, 0, pos));
    expect_vertex(t, pos, 0, -1, -1, 0);
    expect_vertex(t, pos, 2, 1, 1.5, 0); /* the mesh's default weight 0.5 */
    const double tr[3] = {0, 0, 0}, ry[4] = {0, sqrt(0.5), 0, sqrt(0.5)}, one[3] = {1, 1, 1};
    mvr_scene_set_node_transform(s, k.quad, tr, ry, one);
    double nrm[12];
    CHECK(t, mvr_scene_posed_normals(s, k.quad.id - 1, 0, nrm));
    expect_vertex(t, nrm, 0, 1.0, 0.0, 0.0); /* +Z turned 90 degrees about +Y is +X */
    mvr_scene_reset_pose(s);
    const double identity[4] = {0, 0, 0, 1};
    mvr_scene_set_node_transform(s, k.quad, tr, identity, one);
    const float w[2] = {1.0f, 0.25f};
    CHECK(t, mvr_scene_set_node_weights(s, k.quad, w, 2) == MVR_OK);
    CHECK(t, mvr_scene_posed_positions(s, k.quad.id - 1, 0, pos));
    expect_vertex(t, pos, 0, -0.75, -1, 0);
    expect_vertex(t, pos, 3, -0.75, 2, 0);
    /* wrong counts are refused, naming the node */
    CHECK(t, mvr_scene_set_node_weights(s, k.quad, w, 1) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "quad") != NULL);
    /* count 0: back to the mesh's weights */
    CHECK(t, mvr_scene_set_node_weights(s, k.quad, NULL, 0) == MVR_OK);
    CHECK(t, mvr_scene_posed_positions(s, k.quad.id - 1, 0, pos));
    expect_vertex(t, pos, 2, 1, 1.5, 0);
    mvr_scene_destroy(s);
}

static void bounds_follow_the_pose(mvr_test_state *t)
{
    skin_scene k;
    mvr_scene *s = new_scene(t, &k, true, true);
    if (!s)
        return;
    strip_rotate_tip(s, &k, 90.0);
    mvr_scene_info info;
    mvr_scene_get_info(s, &info);
    CHECK(t, info.skins == 1 && info.joints == 2 && info.morph_targets == 2);
    /* the bent tip reaches x = -1 (and nothing is at the node's (5, 5, 5)) */
    CHECK_MSG(t, info.bounds_min[0] <= -1.0 && info.bounds_max[0] < 1.5 && info.bounds_max[1] <= 2.0 + 1e-9,
              "bounds (%g %g %g) .. (%g %g %g)", info.bounds_min[0], info.bounds_min[1], info.bounds_min[2],
              info.bounds_max[0], info.bounds_max[1], info.bounds_max[2]);
    /* the frame: each draw's sphere holds every posed vertex */
    mvr_frame f;
    memset(&f, 0, sizeof f);
    char why[256];
    mvr_dvec3 origin = mvr_dvec3_make(0.25, -0.5, 2.0);
    CHECK(t, mvr_frame_build(&f, s, origin, 144, 64, NULL, why, sizeof why) == MVR_OK);
    CHECK(t, f.draw_count == 2 && f.deform_count == 2 && f.joints == 2 && f.morph_active == 1);
    for (uint32_t i = 0; i < f.draw_count; ++i) {
        const mvr_draw *d = &f.draws[i];
        const scene_primitive *p = &s->primitives[d->primitive];
        double *pos = malloc((size_t)p->vertex_count * 3 * sizeof *pos);
        CHECK(t, pos && mvr_scene_posed_positions(s, d->node, d->primitive, pos));
        for (uint32_t v = 0; pos && v < p->vertex_count; ++v) {
            double dx = pos[v * 3] - origin.x - d->center[0], dy = pos[v * 3 + 1] - origin.y - d->center[1],
                   dz = pos[v * 3 + 2] - origin.z - d->center[2];
            CHECK_MSG(t, sqrt(dx * dx + dy * dy + dz * dz) <= d->radius, "draw %u vertex %u outside its sphere",
                      i, v);
        }
        free(pos);
        /* skinned: the features ask for skinning, the model is the identity */
        const mvr_deform *df = &f.deforms[d->deform];
        const float *model = (const float *)(f.draw_blocks + (size_t)d->block * 144 + MVR_DRAW_MODEL_OFFSET);
        const int32_t *info4 = (const int32_t *)(f.draw_blocks + (size_t)d->block * 144 + MVR_DRAW_INFO_OFFSET);
        CHECK(t, info4[1] == df->joint_base && info4[2] == df->morph_base && info4[3] == df->delta_base);
        if (df->joint_base >= 0) {
            CHECK(t, (d->features & MVR_FEATURE_SKIN) && !(d->features & MVR_FEATURE_MORPH));
            for (int c = 0; c < 16; ++c)
                CHECK(t, model[c] == (c % 5 == 0 ? 1.0f : 0.0f));
            /* joint 1's texels: the tip's matrix relative to the origin, narrowed */
            mvr_dmat4 world[4]; /* root, tip, body, quad */
            mvr_scene_world_matrices(s, world);
            mvr_dmat4 joints[2];
            mvr_scene_skin_matrices(s, 0, world, joints);
            mvr_mat4f m = mvr_dmat4_relative_to(&joints[1], origin);
            const float *texels = f.deform_data + ((size_t)df->joint_base + MVR_DEFORM_TEXELS_PER_JOINT) * 4;
            CHECK(t, memcmp(texels, m.m, sizeof m.m) == 0);
        } else {
            CHECK(t, (d->features & MVR_FEATURE_MORPH) && !(d->features & MVR_FEATURE_SKIN));
            /* the header and the one active (target, weight) pair: target 1
             * has weight 0 and costs nothing */
            const float *h = f.deform_data + (size_t)df->morph_base * 4;
            CHECK_MSG(t, h[0] == 1.0f && h[1] == 4.0f && h[2] == 1.0f && h[3] == (float)(0 | 3 << 2 | 3 << 4),
                      "header %g %g %g %g", h[0], h[1], h[2], h[3]);
            CHECK(t, h[4] == 0.0f && h[5] == 0.5f);
        }
    }
    /* the pre-skinning path takes the deformation out of the programs */
    f.preskin = true;
    CHECK(t, mvr_frame_build(&f, s, origin, 144, 64, NULL, why, sizeof why) == MVR_OK);
    for (uint32_t i = 0; i < f.draw_count; ++i)
        CHECK(t, !(f.draws[i].features & MVR_DEFORM_FEATURES) && f.draws[i].deform != MVR_NO_INDEX);
    mvr_frame_free(&f);
    mvr_scene_destroy(s);
}

static void animation_poses_by_time(mvr_test_state *t)
{
    skin_scene k;
    mvr_scene *s = new_scene(t, &k, true, true);
    if (!s)
        return;
    /* tip: 0 -> 90 degrees about Z over a second (LINEAR: slerp); quad
     * weights STEP (0, 0) then (1, 1) at 0.5 s */
    const double h = sqrt(0.5);
    const float times[2] = {0.0f, 1.0f};
    const float rot[8] = {0, 0, 0, 1, 0, 0, (float)h, (float)h};
    const float wtimes[2] = {0.0f, 0.5f};
    const float weights[4] = {0, 0, 1, 1};
    mvr_animation_sampler_desc samplers[2] = {
        {.times = times, .key_count = 2, .values = rot, .value_count = 8},
        {.times = wtimes, .key_count = 2, .values = weights, .value_count = 4,
         .interpolation = MVR_INTERPOLATION_STEP}};
    mvr_animation_channel_desc channels[2] = {{0, k.tip, MVR_ANIMATION_PATH_ROTATION},
                                              {1, k.quad, MVR_ANIMATION_PATH_WEIGHTS}};
    mvr_animation_desc ad = {samplers, 2, channels, 2, "bend"};
    uint32_t index = 99;
    CHECK_MSG(t, mvr_scene_add_animation(s, &ad, &index) == MVR_OK, "%s", mvr_scene_last_error(s));
    CHECK(t, index == 0 && mvr_scene_animation_count(s) == 1);
    mvr_animation_info info;
    CHECK(t, mvr_scene_get_animation_info(s, 0, &info) == MVR_OK);
    CHECK(t, strcmp(info.name, "bend") == 0 && info.start == 0.0 && info.end == 1.0 && info.channels == 2);
    uint32_t found = 9;
    CHECK(t, mvr_scene_find_animation(s, "bend", &found) == MVR_OK && found == 0);
    CHECK(t, mvr_scene_find_animation(s, "walk", &found) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "'bend'") != NULL);

    double pos[STRIP_VERTICES * 3], quad[12];
    tolerance = 1e-6;
    CHECK(t, mvr_scene_apply_animation(s, 0, 1.0, MVR_ANIMATION_CLAMP) == MVR_OK);
    CHECK(t, mvr_scene_posed_positions(s, k.body.id - 1, 0, pos));
    expect_vertex(t, pos, 9, -1.0, 1.125, 0.0); /* (0.125, 2) at 90 degrees */
    CHECK(t, mvr_scene_posed_positions(s, k.quad.id - 1, 1, quad));
    expect_vertex(t, quad, 2, 2.0, 2.0, 0.0); /* weights (1, 1) */
    /* 0.5 s: 45 degrees (slerp); the STEP weights switch exactly at their key */
    CHECK(t, mvr_scene_apply_animation(s, MVR_ANIMATION_ALL, 0.5, MVR_ANIMATION_CLAMP) == MVR_OK);
    CHECK(t, mvr_scene_posed_positions(s, k.body.id - 1, 0, pos));
    double c = cos(3.14159265358979323846 / 4), sn = sin(3.14159265358979323846 / 4);
    expect_vertex(t, pos, 9, 0.125 * c - 1.0 * sn, 1.0 + 0.125 * sn + 1.0 * c, 0.0);
    CHECK(t, mvr_scene_posed_positions(s, k.quad.id - 1, 1, quad));
    expect_vertex(t, quad, 2, 2.0, 2.0, 0.0);
    /* the same pose again changes nothing (a paused player sends nothing) */
    uint64_t version = s->transform_version;
    CHECK(t, mvr_scene_apply_animation(s, MVR_ANIMATION_ALL, 0.5, MVR_ANIMATION_CLAMP) == MVR_OK);
    CHECK(t, s->transform_version == version);
    CHECK(t, mvr_scene_apply_animation(s, MVR_ANIMATION_ALL, 0.75, MVR_ANIMATION_CLAMP) == MVR_OK);
    CHECK(t, s->transform_version != version);
    /* loop: 1.25 s is 0.25 s; clamp: 3 s is 1 s */
    CHECK(t, mvr_scene_apply_animation(s, 0, 1.25, MVR_ANIMATION_LOOP) == MVR_OK);
    CHECK(t, mvr_scene_posed_positions(s, k.quad.id - 1, 1, quad));
    expect_vertex(t, quad, 2, 1.0, 1.0, 0.0); /* before the STEP key: weights (0, 0) */
    CHECK(t, mvr_scene_apply_animation(s, 0, 3.0, MVR_ANIMATION_CLAMP) == MVR_OK);
    CHECK(t, mvr_scene_posed_positions(s, k.body.id - 1, 0, pos));
    expect_vertex(t, pos, 9, -1.0, 1.125, 0.0);
    /* back to rest: the tip straight, the mesh's default weights */
    mvr_scene_reset_pose(s);
    CHECK(t, mvr_scene_posed_positions(s, k.body.id - 1, 0, pos));
    expect_vertex(t, pos, 9, 0.125, 2.0, 0.0);
    CHECK(t, mvr_scene_posed_positions(s, k.quad.id - 1, 1, quad));
    expect_vertex(t, quad, 2, 1.0, 1.5, 0.0);
    /* bad input: out of range, NaN time */
    CHECK(t, mvr_scene_apply_animation(s, 1, 0.0, MVR_ANIMATION_CLAMP) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_scene_apply_animation(s, 0, NAN, MVR_ANIMATION_CLAMP) == MVR_ERROR_INVALID_ARGUMENT);
    tolerance = 1e-12;
    mvr_scene_destroy(s);
}

static void hostile_input_is_refused(mvr_test_state *t)
{
    skin_scene k;
    mvr_scene *s = new_scene(t, &k, true, true);
    if (!s)
        return;
    /* a joint that is not a node, a joint twice, a NaN inverse bind */
    mvr_node_id bad[2] = {{1}, {99}};
    mvr_skin_desc sd = {.joints = bad, .joint_count = 2, .name = "bad"};
    mvr_skin_id skin;
    CHECK(t, mvr_scene_add_skin(s, &sd, &skin) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "joint 1 (node 99)") != NULL);
    mvr_node_id twice[2] = {{1}, {1}};
    sd.joints = twice;
    CHECK(t, mvr_scene_add_skin(s, &sd, &skin) == MVR_ERROR_INVALID_ARGUMENT);
    double ibm[16] = {NAN};
    mvr_node_id one[1] = {{1}};
    mvr_skin_desc nan_skin = {.joints = one, .joint_count = 1, .inverse_bind_matrices = ibm};
    CHECK(t, mvr_scene_add_skin(s, &nan_skin, &skin) == MVR_ERROR_INVALID_ARGUMENT);
    /* a skin with fewer joints than the mesh uses */
    nan_skin.inverse_bind_matrices = NULL;
    CHECK(t, mvr_scene_add_skin(s, &nan_skin, &skin) == MVR_OK);
    CHECK(t, mvr_scene_set_node_skin(s, k.body, skin) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "uses joint 1") != NULL);
    /* weights: negative, NaN; joints without weights */
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, w[12] = {1, 0, 0, 0, -1, 0, 0, 0, 1, 0, 0, 0};
    uint16_t j[12] = {0};
    mvr_primitive_desc p = {.vertex_count = 3, .positions = pos, .joints0 = j, .weights0 = w};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "neg"};
    mvr_mesh_id mid;
    CHECK(t, mvr_scene_add_mesh(s, &md, &mid) == MVR_ERROR_INVALID_ARGUMENT);
    w[4] = NAN;
    CHECK(t, mvr_scene_add_mesh(s, &md, &mid) == MVR_ERROR_INVALID_ARGUMENT);
    p.weights0 = NULL;
    CHECK(t, mvr_scene_add_mesh(s, &md, &mid) == MVR_ERROR_INVALID_ARGUMENT);
    /* all-zero weights are repaired (joint 0) and counted */
    float zero[12] = {0};
    p.weights0 = zero;
    uint32_t before = mvr_scene_sanitized_count(s);
    CHECK(t, mvr_scene_add_mesh(s, &md, &mid) == MVR_OK);
    CHECK(t, mvr_scene_sanitized_count(s) == before + 3);
    /* targets: NaN deltas, normals deltas without normals, counts differing
     * between primitives, default weights of the wrong count */
    float nan_delta[9] = {NAN};
    mvr_morph_target_desc td = {.positions = nan_delta};
    mvr_primitive_desc q = {.vertex_count = 3, .positions = pos, .targets = &td, .target_count = 1};
    md.primitives = &q;
    CHECK(t, mvr_scene_add_mesh(s, &md, &mid) == MVR_ERROR_INVALID_ARGUMENT);
    float delta[9] = {0};
    td.positions = NULL;
    td.normals = delta;
    CHECK(t, mvr_scene_add_mesh(s, &md, &mid) == MVR_ERROR_INVALID_ARGUMENT);
    td.normals = NULL;
    td.positions = delta;
    mvr_primitive_desc two[2] = {q, q};
    two[1].target_count = 0;
    mvr_mesh_desc md2 = {.primitives = two, .primitive_count = 2, .name = "uneven"};
    CHECK(t, mvr_scene_add_mesh(s, &md2, &mid) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "different numbers of morph targets") != NULL);
    const float weights3[3] = {0, 0, 0};
    md.weights = weights3;
    md.weight_count = 3;
    CHECK(t, mvr_scene_add_mesh(s, &md, &mid) == MVR_ERROR_INVALID_ARGUMENT);
    /* animations: too few values, times not increasing, an unknown interpolation, a matrix node, a
     * weights channel on a node without targets */
    const float times[2] = {0.0f, 1.0f}, back[2] = {1.0f, 0.0f};
    const float values[6] = {0, 0, 0, 1, 1, 1};
    mvr_animation_sampler_desc sa = {.times = times, .key_count = 2, .values = values, .value_count = 5};
    mvr_animation_channel_desc ch = {0, k.tip, MVR_ANIMATION_PATH_TRANSLATION};
    mvr_animation_desc ad = {&sa, 1, &ch, 1, "short"};
    CHECK(t, mvr_scene_add_animation(s, &ad, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    sa.value_count = 6;
    sa.times = back;
    CHECK(t, mvr_scene_add_animation(s, &ad, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    sa.times = times;
    sa.interpolation = (mvr_interpolation)7; /* no such interpolation: named, never a count read */
    CHECK(t, mvr_scene_add_animation(s, &ad, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(t, strstr(mvr_scene_last_error(s), "interpolation") != NULL, "%s", mvr_scene_last_error(s));
    sa.interpolation = MVR_INTERPOLATION_LINEAR;
    ch.path = MVR_ANIMATION_PATH_WEIGHTS;
    CHECK(t, mvr_scene_add_animation(s, &ad, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    mvr_node_desc nd = {.use_matrix = true, .matrix = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    mvr_node_id mnode;
    CHECK(t, mvr_scene_add_node(s, &nd, &mnode) == MVR_OK);
    ch.node = mnode;
    ch.path = MVR_ANIMATION_PATH_TRANSLATION;
    CHECK(t, mvr_scene_add_animation(s, &ad, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "matrix") != NULL);
    ch.node = (mvr_node_id){999};
    CHECK(t, mvr_scene_add_animation(s, &ad, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_scene_animation_count(s) == 0);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(two_bone_skin_90_degrees), TEST(morph_weight_half_moves_halfway), TEST(bounds_follow_the_pose),
              TEST(animation_poses_by_time), TEST(hostile_input_is_refused))
