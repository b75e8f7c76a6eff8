/* Skins, morph targets and animations of a scene: validated copies on the
 * way in (like the rest of core/scene.c), posing by time (double precision,
 * core/animation.c samples), and the posed bounds culling and shadows use. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "animation.h"
#include "scene_internal.h"

/* n elements of `size` bytes, NULL (and *oom) when the size overflows or
 * malloc fails */
static void *alloc_array(size_t n, size_t size, bool *oom)
{
    size_t bytes;
    if (!mvr_size_mul(n ? n : 1, size, &bytes)) {
        *oom = true;
        return NULL;
    }
    void *p = malloc(bytes);
    if (!p)
        *oom = true;
    return p;
}

void mvr_scene_free_deformers(scene_primitive *p)
{
    for (int k = 0; k < 2; ++k) {
        free(p->joints[k]);
        free(p->weights[k]);
        p->joints[k] = NULL;
        p->weights[k] = NULL;
    }
    free(p->joint_min);
    free(p->joint_max);
    free(p->target_positions);
    free(p->target_normals);
    free(p->target_tangents);
    free(p->target_extent);
    p->joint_min = p->joint_max = p->target_extent = NULL;
    p->target_positions = p->target_normals = p->target_tangents = NULL;
    p->influence_sets = p->target_count = 0;
}

static mvr_result copy_skinning(mvr_scene *s, scene_primitive *p, const mvr_primitive_desc *d, const char *mesh,
                                uint32_t k)
{
    if (!d->joints0 && !d->weights0 && !d->joints1 && !d->weights1)
        return MVR_OK;
    if (!d->joints0 || !d->weights0 || !d->joints1 != !d->weights1)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_mesh(%s): primitive %u: joints and weights come in pairs, set 0 first",
                              mesh, k);
    uint32_t sets = d->joints1 ? 2u : 1u;
    size_t n = (size_t)p->vertex_count * 4;
    const float *w[2] = {d->weights0, d->weights1};
    const uint16_t *j[2] = {d->joints0, d->joints1};
    for (uint32_t set = 0; set < sets; ++set)
        for (size_t i = 0; i < n; ++i)
            if (!isfinite(w[set][i]) || w[set][i] < 0.0f)
                return mvr_scene_fail(
                    s, MVR_ERROR_INVALID_ARGUMENT,
                    "mvr_scene_add_mesh(%s): primitive %u: weights%u of vertex %zu is %g (finite, >= 0)", mesh, k, set,
                    i / 4, (double)w[set][i]);
    bool oom = false;
    for (uint32_t set = 0; set < sets; ++set) {
        p->joints[set] = alloc_array(n, sizeof(uint16_t), &oom);
        p->weights[set] = alloc_array(n, sizeof(float), &oom);
        if (oom)
            return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_mesh(%s): out of memory", mesh);
        memcpy(p->joints[set], j[set], n * sizeof(uint16_t));
        memcpy(p->weights[set], w[set], n * sizeof(float));
    }
    p->influence_sets = sets;
    /* normalised (glTF 3.7.3.3: the weights of a vertex sum to 1; exporters
     * often store them quantized, a little off); an unused influence (weight
     * 0) joins no joint's box and limits no skin */
    uint32_t repaired = 0, max_joint = 0;
    for (uint32_t v = 0; v < p->vertex_count; ++v) {
        double sum = 0.0;
        for (uint32_t set = 0; set < sets; ++set)
            for (size_t c = 0; c < 4; ++c)
                sum += p->weights[set][(size_t)v * 4 + c];
        if (!(sum > 0.0)) {
            p->weights[0][(size_t)v * 4] = 1.0f;
            repaired++;
            sum = 1.0;
        }
        for (uint32_t set = 0; set < sets; ++set)
            for (size_t c = 0; c < 4; ++c) {
                float *wv = &p->weights[set][(size_t)v * 4 + c];
                *wv = (float)(*wv / sum);
                if (*wv > 0.0f && p->joints[set][(size_t)v * 4 + c] > max_joint)
                    max_joint = p->joints[set][(size_t)v * 4 + c];
            }
    }
    if (repaired) {
        s->sanitized += repaired;
        mvr_log(&s->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                "mvr_scene_add_mesh(%s): primitive %u: %u vertices have all skin weights 0 (they follow joint 0 "
                "of their first set)",
                mesh, k, repaired);
    }
    p->max_joint = max_joint;
    p->joint_min = alloc_array((size_t)max_joint + 1, sizeof *p->joint_min, &oom);
    p->joint_max = alloc_array((size_t)max_joint + 1, sizeof *p->joint_max, &oom);
    if (oom)
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_mesh(%s): out of memory", mesh);
    for (uint32_t i = 0; i <= max_joint; ++i) {
        p->joint_min[i] = mvr_dvec3_make(INFINITY, INFINITY, INFINITY);
        p->joint_max[i] = mvr_dvec3_make(-INFINITY, -INFINITY, -INFINITY);
    }
    for (uint32_t v = 0; v < p->vertex_count; ++v) {
        const float *pos = p->positions + (size_t)v * 3;
        for (uint32_t set = 0; set < sets; ++set)
            for (size_t c = 0; c < 4; ++c) {
                if (!(p->weights[set][(size_t)v * 4 + c] > 0.0f))
                    continue;
                uint32_t jt = p->joints[set][(size_t)v * 4 + c];
                mvr_dvec3 *lo = &p->joint_min[jt], *hi = &p->joint_max[jt];
                *lo = mvr_dvec3_make(fmin(lo->x, pos[0]), fmin(lo->y, pos[1]), fmin(lo->z, pos[2]));
                *hi = mvr_dvec3_make(fmax(hi->x, pos[0]), fmax(hi->y, pos[1]), fmax(hi->z, pos[2]));
            }
    }
    return MVR_OK;
}

static mvr_result copy_targets(mvr_scene *s, scene_primitive *p, const mvr_primitive_desc *d, const char *mesh,
                               uint32_t k)
{
    if (d->target_count == 0)
        return MVR_OK;
    if (!d->targets)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_mesh(%s): primitive %u: %u targets, NULL array", mesh, k, d->target_count);
    size_t per_target = (size_t)p->vertex_count * 3, total;
    if (!mvr_size_mul(per_target, d->target_count, &total))
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_mesh(%s): primitive %u: too many targets",
                              mesh, k);
    bool any[3] = {false, false, false};
    for (uint32_t t = 0; t < d->target_count; ++t) {
        const mvr_morph_target_desc *td = &d->targets[t];
        const float *attr[3] = {td->positions, td->normals, td->tangents};
        for (int a = 0; a < 3; ++a) {
            if (!attr[a])
                continue;
            any[a] = true;
            if (!mvr_finite_floats(attr[a], per_target))
                return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                      "mvr_scene_add_mesh(%s): primitive %u: target %u has NaN or infinite %s deltas",
                                      mesh, k, t,
                                      a == 0   ? "position"
                                      : a == 1 ? "normal"
                                               : "tangent");
        }
    }
    if ((any[1] && !p->normals) || (any[2] && !p->tangents))
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_mesh(%s): primitive %u: a target moves %s the primitive does not have",
                              mesh, k, any[1] && !p->normals ? "normals" : "tangents");
    bool oom = false;
    float **dst[3] = {&p->target_positions, &p->target_normals, &p->target_tangents};
    for (int a = 0; a < 3; ++a) {
        if (!any[a])
            continue;
        *dst[a] = alloc_array(total, sizeof(float), &oom);
        if (oom)
            return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_mesh(%s): out of memory (targets)", mesh);
        for (uint32_t t = 0; t < d->target_count; ++t) {
            const mvr_morph_target_desc *td = &d->targets[t];
            const float *src = a == 0 ? td->positions : a == 1 ? td->normals : td->tangents;
            float *out = *dst[a] + (size_t)t * per_target;
            if (src)
                memcpy(out, src, per_target * sizeof(float));
            else
                memset(out, 0, per_target * sizeof(float));
        }
    }
    p->target_extent = alloc_array(d->target_count, sizeof *p->target_extent, &oom);
    if (oom)
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_mesh(%s): out of memory (targets)", mesh);
    for (uint32_t t = 0; t < d->target_count; ++t) {
        /* the largest |delta| per axis, in float (exact: |x| of a float is
         * one), kept scalar: GCC 12's aarch64 vectorizer crashes (internal
         * compiler error in vect_transform_reduction) on this max reduction
         * over a small array */
        float ex = 0.0f, ey = 0.0f, ez = 0.0f;
        const float *pd = p->target_positions ? p->target_positions + (size_t)t * per_target : NULL;
        for (uint32_t v = 0; pd && v < p->vertex_count; ++v) {
            const float *dv = pd + (size_t)v * 3;
            ex = fabsf(dv[0]) > ex ? fabsf(dv[0]) : ex;
            ey = fabsf(dv[1]) > ey ? fabsf(dv[1]) : ey;
            ez = fabsf(dv[2]) > ez ? fabsf(dv[2]) : ez;
        }
        p->target_extent[t] = mvr_dvec3_make(ex, ey, ez);
    }
    p->target_count = d->target_count;
    return MVR_OK;
}

mvr_result mvr_scene_primitive_deformers(mvr_scene *s, scene_primitive *p, const mvr_primitive_desc *d,
                                         const char *mesh, uint32_t k)
{
    mvr_result r = copy_skinning(s, p, d, mesh, k);
    return r == MVR_OK ? copy_targets(s, p, d, mesh, k) : r;
}

void mvr_scene_free_skins_and_animations(mvr_scene *s)
{
    for (uint32_t i = 0; i < s->skin_count; ++i) {
        free(s->skins[i].joints);
        free(s->skins[i].inverse_bind);
    }
    free(s->skins);
    for (uint32_t i = 0; i < s->animation_count; ++i) {
        scene_animation *a = &s->animations[i];
        for (uint32_t k = 0; k < a->sampler_count; ++k) {
            free(a->samplers[k].times);
            free(a->samplers[k].values);
        }
        free(a->samplers);
        free(a->channels);
    }
    free(s->animations);
    s->skins = NULL;
    s->animations = NULL;
    s->skin_count = s->animation_count = 0;
}

/* ---- skins */

mvr_result mvr_scene_add_skin(mvr_scene *s, const mvr_skin_desc *d, mvr_skin_id *out)
{
    if (!s || !d || !out)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_skin: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    out->id = 0;
    const char *name = d->name ? d->name : "";
    if (d->joint_count == 0 || d->joint_count > 65536 || !d->joints)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_skin(%s): %u joints (1 .. 65536, array given)", name, d->joint_count);
    if (d->skeleton.id > s->node_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_skin(%s): skeleton node %u out of range (%u nodes)", name, d->skeleton.id,
                              s->node_count);
    bool oom = false;
    uint8_t *seen = calloc(s->node_count ? s->node_count : 1, 1);
    uint32_t *joints = alloc_array(d->joint_count, sizeof *joints, &oom);
    mvr_dmat4 *ibm = alloc_array(d->joint_count, sizeof *ibm, &oom);
    if (!seen || oom || !GROW(s, skins, skin_count, skin_cap)) {
        free(seen);
        free(joints);
        free(ibm);
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_skin(%s): out of memory", name);
    }
    const char *why = NULL;
    uint32_t bad = 0;
    for (uint32_t i = 0; i < d->joint_count && !why; ++i) {
        uint32_t id = d->joints[i].id;
        if (id == 0 || id > s->node_count)
            why = "is not a node of the scene", bad = i;
        else if (seen[id - 1])
            why = "names a node already a joint of this skin", bad = i;
        else {
            seen[id - 1] = 1;
            joints[i] = id - 1;
            if (d->inverse_bind_matrices) {
                memcpy(ibm[i].m, d->inverse_bind_matrices + (size_t)i * 16, sizeof ibm[i].m);
                for (int c = 0; c < 16; ++c)
                    if (!isfinite(ibm[i].m[c]))
                        why = "has a NaN or infinite inverse bind matrix", bad = i;
            } else {
                ibm[i] = mvr_dmat4_identity();
            }
        }
    }
    free(seen);
    if (why) {
        free(joints);
        free(ibm);
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_skin(%s): joint %u (node %u) %s", name, bad,
                              d->joints[bad].id, why);
    }
    scene_skin *sk = &s->skins[s->skin_count];
    memset(sk, 0, sizeof *sk);
    sk->joints = joints;
    sk->inverse_bind = ibm;
    sk->joint_count = d->joint_count;
    sk->skeleton = d->skeleton.id ? d->skeleton.id - 1 : MVR_NO_INDEX;
    mvr_str_copy(sk->name, sizeof sk->name, name);
    s->skin_count++;
    out->id = s->skin_count;
    return MVR_OK;
}

mvr_result mvr_scene_set_node_skin(mvr_scene *s, mvr_node_id node, mvr_skin_id skin)
{
    if (!s)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (node.id == 0 || node.id > s->node_count || skin.id > s->skin_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_set_node_skin: node %u / skin %u out of range "
                              "(%u nodes, %u skins)",
                              node.id, skin.id, s->node_count, s->skin_count);
    scene_node *n = &s->nodes[node.id - 1];
    if (skin.id && n->mesh == MVR_NO_INDEX)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_set_node_skin: node %u '%s' has no mesh to skin", node.id, n->name);
    if (skin.id) {
        const scene_skin *sk = &s->skins[skin.id - 1];
        const scene_mesh *m = &s->meshes[n->mesh];
        for (uint32_t k = 0; k < m->primitive_count; ++k) {
            const scene_primitive *p = &s->primitives[m->first_primitive + k];
            if (p->influence_sets && p->max_joint >= sk->joint_count)
                return mvr_scene_fail(
                    s, MVR_ERROR_INVALID_ARGUMENT,
                    "mvr_scene_set_node_skin: node %u '%s': mesh '%s' primitive %u uses joint %u; skin %u "
                    "'%s' has %u joints",
                    node.id, n->name, m->name, k, p->max_joint, skin.id, sk->name, sk->joint_count);
        }
    }
    n->skin = skin.id ? skin.id - 1 : MVR_NO_INDEX;
    s->transform_version++;
    return MVR_OK;
}

mvr_result mvr_scene_set_node_weights(mvr_scene *s, mvr_node_id node, const float *weights, uint32_t count)
{
    if (!s)
        return MVR_ERROR_INVALID_ARGUMENT;
    if (node.id == 0 || node.id > s->node_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_set_node_weights: node %u out of range",
                              node.id);
    scene_node *n = &s->nodes[node.id - 1];
    if (count == 0) {
        free(n->weights);
        free(n->rest_weights);
        n->weights = n->rest_weights = NULL;
        s->transform_version++;
        return MVR_OK;
    }
    uint32_t targets = n->mesh == MVR_NO_INDEX ? 0 : s->meshes[n->mesh].target_count;
    if (!weights || count != targets || !mvr_finite_floats(weights, count))
        return mvr_scene_fail(
            s, MVR_ERROR_INVALID_ARGUMENT,
            "mvr_scene_set_node_weights: node %u '%s': %u weights given, its mesh has %u morph targets "
            "(finite weights, one per target)",
            node.id, n->name, count, targets);
    if (!n->weights)
        n->weights = malloc((size_t)count * sizeof *n->weights);
    if (!n->rest_weights)
        n->rest_weights = malloc((size_t)count * sizeof *n->rest_weights);
    if (!n->weights || !n->rest_weights)
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_set_node_weights: out of memory");
    memcpy(n->weights, weights, (size_t)count * sizeof *weights);
    memcpy(n->rest_weights, weights, (size_t)count * sizeof *weights);
    s->transform_version++;
    return MVR_OK;
}

const float *mvr_scene_node_weights(const mvr_scene *s, const scene_node *n)
{
    if (n->mesh == MVR_NO_INDEX || s->meshes[n->mesh].target_count == 0)
        return NULL;
    return n->weights ? n->weights : s->meshes[n->mesh].weights;
}

void mvr_scene_skin_matrices(const mvr_scene *s, uint32_t skin, const mvr_dmat4 *world, mvr_dmat4 *out)
{
    const scene_skin *sk = &s->skins[skin];
    for (uint32_t j = 0; j < sk->joint_count; ++j)
        out[j] = mvr_dmat4_mul(&world[sk->joints[j]], &sk->inverse_bind[j]);
}

static void grow_box(const mvr_dmat4 *m, mvr_dvec3 lo, mvr_dvec3 hi, mvr_dvec3 *out_lo, mvr_dvec3 *out_hi)
{
    for (int c = 0; c < 8; ++c) {
        mvr_dvec3 corner = mvr_dvec3_make(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
        mvr_dvec3 w = mvr_dmat4_transform_point(m, corner);
        *out_lo = mvr_dvec3_make(fmin(out_lo->x, w.x), fmin(out_lo->y, w.y), fmin(out_lo->z, w.z));
        *out_hi = mvr_dvec3_make(fmax(out_hi->x, w.x), fmax(out_hi->y, w.y), fmax(out_hi->z, w.z));
    }
}

void mvr_scene_posed_bounds(const mvr_scene *s, const scene_node *n, const scene_primitive *p, const mvr_dmat4 *world,
                            const mvr_dmat4 *joint_matrices, mvr_dvec3 *lo, mvr_dvec3 *hi)
{
    /* morphing moves a vertex by sum_t w_t d_t: at most sum_t |w_t| times
     * each target's largest delta per axis */
    mvr_dvec3 grow = mvr_dvec3_make(0, 0, 0);
    const float *w = p->target_count ? mvr_scene_node_weights(s, n) : NULL;
    for (uint32_t t = 0; w && t < p->target_count; ++t)
        grow = mvr_dvec3_add(grow, mvr_dvec3_scale(p->target_extent[t], fabs((double)w[t])));
    *lo = mvr_dvec3_make(INFINITY, INFINITY, INFINITY);
    *hi = mvr_dvec3_make(-INFINITY, -INFINITY, -INFINITY);
    if (joint_matrices && mvr_scene_draw_skinned(s, n, p)) {
        /* a skinned vertex is a convex combination of its joints' transforms
         * of it, each inside that joint's transformed box: inside the union */
        for (uint32_t j = 0; j <= p->max_joint; ++j)
            if (p->joint_min[j].x <= p->joint_max[j].x)
                grow_box(&joint_matrices[j], mvr_dvec3_sub(p->joint_min[j], grow), mvr_dvec3_add(p->joint_max[j], grow),
                         lo, hi);
        if (lo->x <= hi->x)
            return;
    }
    grow_box(world, mvr_dvec3_sub(p->bounds_min, grow), mvr_dvec3_add(p->bounds_max, grow), lo, hi);
}

/* The CPU reference of deform.glsl for one attribute: positions (points
 * through the joint matrices) or normals (directions through their normal
 * matrices). */
static bool posed_attribute(const mvr_scene *s, uint32_t node, uint32_t primitive, bool normals, double *out)
{
    const scene_node *n = &s->nodes[node];
    const scene_primitive *p = &s->primitives[primitive];
    const float *base = normals ? p->normals : p->positions;
    const float *deltas = normals ? p->target_normals : p->target_positions;
    if (!base)
        return false;
    mvr_dmat4 *world = malloc((s->node_count ? s->node_count : 1) * sizeof *world);
    bool skinned = mvr_scene_draw_skinned(s, n, p);
    mvr_dmat4 *joints = skinned ? malloc(s->skins[n->skin].joint_count * sizeof *joints) : NULL;
    if (!world || (skinned && !joints)) {
        free(world);
        free(joints);
        return false;
    }
    mvr_scene_world_matrices(s, world);
    if (skinned) {
        mvr_scene_skin_matrices(s, n->skin, world, joints);
        for (uint32_t j = 0; normals && j < s->skins[n->skin].joint_count; ++j)
            joints[j] = mvr_dmat4_normal_matrix(&joints[j]);
    }
    mvr_dmat4 place = normals ? mvr_dmat4_normal_matrix(&world[node]) : world[node];
    const float *w = p->target_count ? mvr_scene_node_weights(s, n) : NULL;
    size_t per_target = (size_t)p->vertex_count * 3;
    for (uint32_t v = 0; v < p->vertex_count; ++v) {
        double a[3];
        for (size_t c = 0; c < 3; ++c)
            a[c] = base[(size_t)v * 3 + c];
        for (uint32_t t = 0; w && deltas && t < p->target_count; ++t)
            for (size_t c = 0; c < 3; ++c)
                a[c] += (double)w[t] * deltas[t * per_target + (size_t)v * 3 + c];
        mvr_dvec3 local = mvr_dvec3_make(a[0], a[1], a[2]), at = mvr_dvec3_make(0, 0, 0);
        if (skinned) {
            for (uint32_t set = 0; set < p->influence_sets; ++set)
                for (size_t c = 0; c < 4; ++c) {
                    double wt = p->weights[set][(size_t)v * 4 + c];
                    const mvr_dmat4 *m = &joints[p->joints[set][(size_t)v * 4 + c]];
                    if (wt != 0.0)
                        at = mvr_dvec3_add(at, mvr_dvec3_scale(normals ? mvr_dmat4_transform_dir(m, local)
                                                                       : mvr_dmat4_transform_point(m, local),
                                                               wt));
                }
        } else {
            at = normals ? mvr_dmat4_transform_dir(&place, local) : mvr_dmat4_transform_point(&place, local);
        }
        out[(size_t)v * 3] = at.x;
        out[(size_t)v * 3 + 1] = at.y;
        out[(size_t)v * 3 + 2] = at.z;
    }
    free(world);
    free(joints);
    return true;
}

bool mvr_scene_posed_positions(const mvr_scene *s, uint32_t node, uint32_t primitive, double *out)
{
    return posed_attribute(s, node, primitive, false, out);
}

bool mvr_scene_posed_normals(const mvr_scene *s, uint32_t node, uint32_t primitive, double *out)
{
    return posed_attribute(s, node, primitive, true, out);
}

/* ---- animations */

const char *mvr_animation_path_name(mvr_animation_path path)
{
    switch (path) {
    case MVR_ANIMATION_PATH_TRANSLATION: return "translation";
    case MVR_ANIMATION_PATH_ROTATION: return "rotation";
    case MVR_ANIMATION_PATH_SCALE: return "scale";
    case MVR_ANIMATION_PATH_WEIGHTS: return "weights";
    }
    return NULL;
}

static void free_animation(scene_animation *a)
{
    for (uint32_t k = 0; a->samplers && k < a->sampler_count; ++k) {
        free(a->samplers[k].times);
        free(a->samplers[k].values);
    }
    free(a->samplers);
    free(a->channels);
}

mvr_result mvr_scene_add_animation(mvr_scene *s, const mvr_animation_desc *d, uint32_t *out_index)
{
    if (!s || !d)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_animation: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    const char *name = d->name ? d->name : "";
    if ((d->sampler_count && !d->samplers) || (d->channel_count && !d->channels))
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_animation(%s): NULL samplers or channels",
                              name);
    /* channels first: they say how many components each sampler holds */
    for (uint32_t c = 0; c < d->channel_count; ++c) {
        const mvr_animation_channel_desc *ch = &d->channels[c];
        if (ch->sampler >= d->sampler_count || ch->node.id == 0 || ch->node.id > s->node_count ||
            !mvr_animation_path_name(ch->path))
            return mvr_scene_fail(
                s, MVR_ERROR_INVALID_ARGUMENT,
                "mvr_scene_add_animation(%s): channel %u: sampler %u / node %u / path %d out of range "
                "(%u samplers, %u nodes)",
                name, c, ch->sampler, ch->node.id, (int)ch->path, d->sampler_count, s->node_count);
        const scene_node *n = &s->nodes[ch->node.id - 1];
        uint32_t comps = ch->path == MVR_ANIMATION_PATH_ROTATION ? 4u : 3u;
        if (ch->path == MVR_ANIMATION_PATH_WEIGHTS) {
            comps = n->mesh == MVR_NO_INDEX ? 0 : s->meshes[n->mesh].target_count;
            if (comps == 0)
                return mvr_scene_fail(
                    s, MVR_ERROR_INVALID_ARGUMENT,
                    "mvr_scene_add_animation(%s): channel %u animates the weights of node %u '%s', whose "
                    "mesh has no morph targets",
                    name, c, ch->node.id, n->name);
        } else if (n->use_matrix) {
            return mvr_scene_fail(
                s, MVR_ERROR_INVALID_ARGUMENT,
                "mvr_scene_add_animation(%s): channel %u animates the %s of node %u '%s', which has a "
                "matrix (glTF 3.5.2: animated nodes use TRS)",
                name, c, mvr_animation_path_name(ch->path), ch->node.id, n->name);
        }
        const mvr_animation_sampler_desc *sd = &d->samplers[ch->sampler];
        size_t need = 0;
        if ((unsigned)sd->interpolation > MVR_INTERPOLATION_CUBICSPLINE)
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_scene_add_animation(%s): sampler %u has interpolation %d (not an "
                                  "mvr_interpolation)",
                                  name, ch->sampler, (int)sd->interpolation);
        if (!mvr_anim_sampler_value_count(sd->key_count, comps, sd->interpolation, &need) || need != sd->value_count)
            return mvr_scene_fail(
                s, MVR_ERROR_INVALID_ARGUMENT,
                "mvr_scene_add_animation(%s): sampler %u has %u values for %u keys; channel %u (%s of node "
                "%u) needs %zu",
                name, ch->sampler, sd->value_count, sd->key_count, c, mvr_animation_path_name(ch->path), ch->node.id,
                need);
    }
    if (!GROW(s, animations, animation_count, animation_cap))
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_animation: out of memory");
    scene_animation a;
    memset(&a, 0, sizeof a);
    bool oom = false;
    a.samplers = calloc(d->sampler_count ? d->sampler_count : 1, sizeof *a.samplers);
    a.channels = alloc_array(d->channel_count, sizeof *a.channels, &oom);
    if (!a.samplers || oom) {
        free_animation(&a);
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_animation(%s): out of memory", name);
    }
    a.sampler_count = d->sampler_count;
    a.start = INFINITY;
    a.end = -INFINITY;
    for (uint32_t k = 0; k < d->sampler_count; ++k) {
        const mvr_animation_sampler_desc *sd = &d->samplers[k];
        scene_anim_sampler *sa = &a.samplers[k];
        if (sd->key_count == 0 || !sd->times || (sd->value_count && !sd->values)) {
            free_animation(&a);
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_scene_add_animation(%s): sampler %u has no keys or values", name, k);
        }
        sa->times = alloc_array(sd->key_count, sizeof(double), &oom);
        sa->values = alloc_array(sd->value_count, sizeof(double), &oom);
        if (oom) {
            free_animation(&a);
            return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_animation(%s): out of memory", name);
        }
        for (uint32_t i = 0; i < sd->key_count; ++i)
            sa->times[i] = sd->times[i];
        for (uint32_t i = 0; i < sd->value_count; ++i)
            sa->values[i] = sd->values[i];
        sa->key_count = sd->key_count;
        sa->value_count = sd->value_count;
        sa->interpolation = sd->interpolation;
        /* times and values: the sampler module's own check (components 1:
         * the channels checked the count) */
        mvr_anim_sampler as = {sa->times,
                               sa->values,
                               sa->key_count,
                               sa->value_count,
                               1,
                               (unsigned)sd->interpolation <= MVR_INTERPOLATION_CUBICSPLINE ? sd->interpolation
                                                                                            : MVR_INTERPOLATION_LINEAR,
                               false};
        size_t ones;
        if (mvr_anim_sampler_value_count(sa->key_count, 1, as.interpolation, &ones) && ones <= sa->value_count)
            as.value_count = sa->value_count;
        char why[160];
        if (!mvr_anim_sampler_valid(&as, why, sizeof why)) {
            free_animation(&a);
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_animation(%s): sampler %u: %s", name, k,
                                  why);
        }
        a.start = fmin(a.start, sa->times[0]);
        a.end = fmax(a.end, sa->times[sa->key_count - 1]);
    }
    if (!(a.start <= a.end))
        a.start = a.end = 0.0;
    for (uint32_t c = 0; c < d->channel_count; ++c) {
        const mvr_animation_channel_desc *ch = &d->channels[c];
        const scene_node *n = &s->nodes[ch->node.id - 1];
        a.channels[c].sampler = ch->sampler;
        a.channels[c].node = ch->node.id - 1;
        a.channels[c].path = ch->path;
        a.channels[c].components = ch->path == MVR_ANIMATION_PATH_ROTATION  ? 4u
                                   : ch->path == MVR_ANIMATION_PATH_WEIGHTS ? s->meshes[n->mesh].target_count
                                                                            : 3u;
    }
    a.channel_count = d->channel_count;
    mvr_str_copy(a.name, sizeof a.name, name);
    s->animations[s->animation_count] = a;
    if (out_index)
        *out_index = s->animation_count;
    s->animation_count++;
    return MVR_OK;
}

uint32_t mvr_scene_animation_count(const mvr_scene *s)
{
    return s ? s->animation_count : 0;
}

mvr_result mvr_scene_get_animation_info(const mvr_scene *s, uint32_t index, mvr_animation_info *out)
{
    if (!s || !out)
        return MVR_ERROR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    if (index >= s->animation_count)
        return mvr_scene_fail((mvr_scene *)s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_get_animation_info: animation %u out of range (%u)", index,
                              s->animation_count);
    const scene_animation *a = &s->animations[index];
    out->name = a->name;
    out->start = a->start;
    out->end = a->end;
    out->channels = a->channel_count;
    out->samplers = a->sampler_count;
    return MVR_OK;
}

mvr_result mvr_scene_find_animation(const mvr_scene *s, const char *name, uint32_t *out_index)
{
    if (!s || !name || !out_index)
        return MVR_ERROR_INVALID_ARGUMENT;
    for (uint32_t i = 0; i < s->animation_count; ++i)
        if (strcmp(s->animations[i].name, name) == 0) {
            *out_index = i;
            return MVR_OK;
        }
    char names[256] = "";
    for (uint32_t i = 0; i < s->animation_count; ++i) {
        size_t used = strlen(names);
        mvr_str_format(names + used, sizeof names - used, "%s'%s'", i ? ", " : "", s->animations[i].name);
    }
    return mvr_scene_fail((mvr_scene *)s, MVR_ERROR_INVALID_ARGUMENT, "no animation named '%s' (%u animations%s%s)",
                          name, s->animation_count, s->animation_count ? ": " : "", names);
}

static bool same3(mvr_dvec3 a, const double *b)
{
    return a.x == b[0] && a.y == b[1] && a.z == b[2];
}

/* Poses the nodes of one animation; true when a value changed. */
static bool apply_one(mvr_scene *s, const scene_animation *a, double time, mvr_animation_wrap wrap)
{
    bool changed = false;
    double t = mvr_anim_time(time, a->start, a->end, wrap == MVR_ANIMATION_LOOP);
    double value[64];
    double *big = NULL;
    for (uint32_t c = 0; c < a->channel_count; ++c) {
        const scene_anim_channel *ch = &a->channels[c];
        const scene_anim_sampler *sa = &a->samplers[ch->sampler];
        scene_node *n = &s->nodes[ch->node];
        mvr_anim_sampler as = {sa->times,
                               sa->values,
                               sa->key_count,
                               sa->value_count,
                               ch->components,
                               sa->interpolation,
                               ch->path == MVR_ANIMATION_PATH_ROTATION};
        double *out = value;
        if (ch->components > MVR_ARRAY_COUNT(value)) {
            double *p = realloc(big, ch->components * sizeof *p);
            if (!p)
                continue; /* that channel keeps its pose */
            big = p;
            out = big;
        }
        mvr_anim_sample(&as, t, out);
        switch (ch->path) {
        case MVR_ANIMATION_PATH_TRANSLATION:
            changed |= !same3(n->translation, out);
            n->translation = mvr_dvec3_make(out[0], out[1], out[2]);
            break;
        case MVR_ANIMATION_PATH_ROTATION: {
            mvr_dquat q = mvr_dquat_normalize((mvr_dquat){out[0], out[1], out[2], out[3]});
            changed |= q.x != n->rotation.x || q.y != n->rotation.y || q.z != n->rotation.z || q.w != n->rotation.w;
            n->rotation = q;
            break;
        }
        case MVR_ANIMATION_PATH_SCALE:
            changed |= !same3(n->scale, out);
            n->scale = mvr_dvec3_make(out[0], out[1], out[2]);
            break;
        case MVR_ANIMATION_PATH_WEIGHTS:
            if (!n->weights) {
                /* from the weights drawn so far (the node's or the mesh's) */
                const float *before = mvr_scene_node_weights(s, n);
                n->weights = malloc(ch->components * sizeof *n->weights);
                if (n->weights && before)
                    memcpy(n->weights, before, ch->components * sizeof *n->weights);
            }
            for (uint32_t k = 0; n->weights && k < ch->components; ++k) {
                changed |= n->weights[k] != (float)out[k];
                n->weights[k] = (float)out[k];
            }
            break;
        }
    }
    free(big);
    return changed;
}

mvr_result mvr_scene_apply_animation(mvr_scene *s, uint32_t index, double time, mvr_animation_wrap wrap)
{
    if (!s)
        return MVR_ERROR_INVALID_ARGUMENT;
    if ((unsigned)wrap > MVR_ANIMATION_LOOP || isnan(time))
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_apply_animation: wrap %d / time %g invalid",
                              (int)wrap, time);
    if (index != MVR_ANIMATION_ALL && index >= s->animation_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_apply_animation: animation %u out of range (%u)", index, s->animation_count);
    bool changed = false;
    for (uint32_t i = 0; i < s->animation_count; ++i)
        if (index == MVR_ANIMATION_ALL || index == i)
            changed |= apply_one(s, &s->animations[i], time, wrap);
    /* the same pose again (a paused player) sends and captures nothing */
    if (changed)
        s->transform_version++;
    return MVR_OK;
}

void mvr_scene_reset_pose(mvr_scene *s)
{
    if (!s)
        return;
    for (uint32_t i = 0; i < s->node_count; ++i) {
        scene_node *n = &s->nodes[i];
        if (!n->use_matrix) {
            n->translation = n->rest_translation;
            n->rotation = n->rest_rotation;
            n->scale = n->rest_scale;
        }
        if (n->rest_weights && n->weights)
            memcpy(n->weights, n->rest_weights, s->meshes[n->mesh].target_count * sizeof *n->weights);
        else {
            free(n->weights);
            n->weights = NULL;
        }
    }
    s->transform_version++;
}
