#include <math.h>
#include <string.h>

#include "shadow_plan.h"

#define DEFAULT_ZNEAR 0.05
#define PI 3.14159265358979323846

mvr_shadow_desc mvr_shadow_desc_resolve(const mvr_shadow_desc *d)
{
    mvr_shadow_desc s = *d;
    if (s.map_size == 0)
        s.map_size = 1024;
    if (s.cascades == 0)
        s.cascades = 3;
    if (s.cascades > MVR_SHADOW_MAX_CASCADES)
        s.cascades = MVR_SHADOW_MAX_CASCADES;
    if (!(s.distance > 0.0) || !isfinite(s.distance))
        s.distance = 0.0;
    if (s.slope_bias == 0.0f || !isfinite(s.slope_bias))
        s.slope_bias = 2.0f;
    if (s.constant_bias == 0.0f || !isfinite(s.constant_bias))
        s.constant_bias = 2.0f;
    if (s.normal_bias == 0.0f || !isfinite(s.normal_bias))
        s.normal_bias = 1.5f;
    return s;
}

uint32_t mvr_view_light_mask(const mvr_frame *f, const mvr_view_desc *v)
{
    uint32_t view_layers = v->light_layers ? v->light_layers : 0xffffffffu;
    uint32_t n = f->light_counts[0] + f->light_counts[1] + f->light_counts[2], mask = 0;
    for (uint32_t i = 0; i < n; ++i)
        if (f->lights[i].layers & view_layers)
            mask |= 1u << i;
    return mask;
}

static bool view_enabled(const mvr_view_desc *v, uint32_t width, uint32_t height)
{
    mvr_viewport vp = mvr_view_viewport(v, width, height);
    return !v->disabled && vp.width > 0 && vp.height > 0;
}

/* (m * (p, 1)) with the homogeneous divide. */
static mvr_dvec3 project(const mvr_dmat4 *m, mvr_dvec3 p)
{
    const double *a = m->m;
    double x = a[0] * p.x + a[4] * p.y + a[8] * p.z + a[12];
    double y = a[1] * p.x + a[5] * p.y + a[9] * p.z + a[13];
    double z = a[2] * p.x + a[6] * p.y + a[10] * p.z + a[14];
    double w = a[3] * p.x + a[7] * p.y + a[11] * p.z + a[15];
    if (w == 0.0)
        w = 1e-300;
    return mvr_dvec3_make(x / w, y / w, z / w);
}

typedef struct view_geometry {
    mvr_dmat4 inv_proj, inv_view; /* standard-depth projection; view relative to the origin */
    double znear, zfar;           /* zfar 0 = infinite */
} view_geometry;

static bool view_geometry_of(const mvr_view_desc *v, mvr_dvec3 origin, uint32_t width, uint32_t height,
                             view_geometry *out)
{
    mvr_viewport vp = mvr_view_viewport(v, width, height);
    mvr_dmat4 proj = mvr_view_projection(v, vp, false);
    mvr_dvec3 rel = mvr_dvec3_sub(mvr_dvec3_make(v->position[0], v->position[1], v->position[2]), origin);
    mvr_dquat q = {v->orientation[0], v->orientation[1], v->orientation[2], v->orientation[3]};
    if (q.x == 0 && q.y == 0 && q.z == 0 && q.w == 0)
        q.w = 1;
    mvr_dmat4 view = mvr_dmat4_view(rel, q);
    out->znear = v->projection.znear > 0 ? v->projection.znear : DEFAULT_ZNEAR;
    out->zfar = v->projection.zfar;
    return mvr_dmat4_invert(&proj, &out->inv_proj) && mvr_dmat4_invert(&view, &out->inv_view);
}

/* The four corners of a view's frustum at view depth d (world, relative to
 * the origin): along the line through the near-plane corner and the corner
 * at NDC z = 0 (finite even with an infinite far plane), so perspective,
 * asymmetric, orthographic and explicit projections all work. */
static void slice_corners(const view_geometry *g, double d, mvr_dvec3 out[4])
{
    for (int k = 0; k < 4; ++k) {
        double x = (k & 1) ? 1.0 : -1.0, y = (k & 2) ? 1.0 : -1.0;
        mvr_dvec3 a = project(&g->inv_proj, mvr_dvec3_make(x, y, -1.0));
        mvr_dvec3 b = project(&g->inv_proj, mvr_dvec3_make(x, y, 0.0));
        double da = -a.z, db = -b.z;
        double t = fabs(db - da) > 1e-12 ? (d - da) / (db - da) : 0.0;
        mvr_dvec3 p = mvr_dvec3_add(a, mvr_dvec3_scale(mvr_dvec3_sub(b, a), t));
        out[k] = mvr_dmat4_transform_point(&g->inv_view, p);
    }
}

typedef struct scene_extent {
    mvr_dvec3 center;            /* bounding sphere of every draw */
    double radius;
    bool any;
} scene_extent;

static scene_extent scene_extent_of(const mvr_frame *f)
{
    scene_extent e = {{0, 0, 0}, 0, false};
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < f->draw_count; ++i) {
        const mvr_draw *d = &f->draws[i];
        for (int c = 0; c < 3; ++c) {
            lo[c] = fmin(lo[c], d->center[c] - d->radius);
            hi[c] = fmax(hi[c], d->center[c] + d->radius);
        }
        e.any = true;
    }
    if (!e.any)
        return e;
    e.center = mvr_dvec3_make(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]));
    e.radius = 0.5 * sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                          (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return e;
}

/* Range of dot(p, axis) over the casters' spheres. */
static void caster_range(const mvr_frame *f, mvr_dvec3 axis, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (uint32_t i = 0; i < f->draw_count; ++i) {
        const mvr_draw *d = &f->draws[i];
        if (d->pass == MVR_PASS_BLEND)
            continue;
        double c = d->center[0] * axis.x + d->center[1] * axis.y + d->center[2] * axis.z;
        *lo = fmin(*lo, c - d->radius);
        *hi = fmax(*hi, c + d->radius);
    }
}

static mvr_dvec3 any_up(mvr_dvec3 forward)
{
    return fabs(forward.y) > 0.99 ? mvr_dvec3_make(1, 0, 0) : mvr_dvec3_make(0, 1, 0);
}

/* One cascade: the bounding sphere of the slices [d0, d1] of the views,
 * an orthographic box around it along the light, its centre snapped to whole
 * texels in light space so the map does not shimmer as views move, and its
 * depth range stretched towards the light to take every caster in. */
static void fit_cascade(mvr_shadow_layer *layer, const mvr_frame *f, const mvr_frame_light *light,
                        const view_geometry *geoms, uint32_t geom_count, double d0, double d1, uint32_t size,
                        bool reversed)
{
    mvr_dvec3 corners[2 * 4 * 64];
    uint32_t n = 0;
    mvr_dvec3 sum = {0, 0, 0};
    for (uint32_t g = 0; g < geom_count && n + 8 <= MVR_ARRAY_COUNT(corners); ++g) {
        slice_corners(&geoms[g], d0, &corners[n]);
        slice_corners(&geoms[g], d1, &corners[n + 4]);
        n += 8;
    }
    for (uint32_t i = 0; i < n; ++i)
        sum = mvr_dvec3_add(sum, corners[i]);
    mvr_dvec3 center = mvr_dvec3_scale(sum, 1.0 / (n ? n : 1));
    double radius = 0.0;
    for (uint32_t i = 0; i < n; ++i)
        radius = fmax(radius, mvr_dvec3_length(mvr_dvec3_sub(corners[i], center)));
    radius = fmax(radius * 1.01, 1e-3);

    mvr_dvec3 L = light->direction;
    mvr_dquat q = mvr_dquat_look_rotation(L, any_up(L));
    mvr_dvec3 right = mvr_dquat_rotate(q, mvr_dvec3_make(1, 0, 0));
    mvr_dvec3 up = mvr_dquat_rotate(q, mvr_dvec3_make(0, 1, 0));
    double texel = 2.0 * radius / size;
    double cx = floor(mvr_dvec3_dot(center, right) / texel) * texel;
    double cy = floor(mvr_dvec3_dot(center, up) / texel) * texel;
    double cz = mvr_dvec3_dot(center, L);
    double lo, hi;
    caster_range(f, L, &lo, &hi);
    double zmin = fmin(lo, cz - radius), zmax = cz + radius;
    double margin = 0.01 * (zmax - zmin) + 1e-3;
    mvr_dvec3 eye = mvr_dvec3_add(mvr_dvec3_add(mvr_dvec3_scale(right, cx), mvr_dvec3_scale(up, cy)),
                                  mvr_dvec3_scale(L, zmin - 2.0 * margin));
    mvr_dmat4 view = mvr_dmat4_view(eye, q);
    mvr_dmat4 proj = mvr_dmat4_orthographic(radius, radius, margin, zmax - zmin + 3.0 * margin, reversed);
    layer->view_proj = mvr_dmat4_mul(&proj, &view);
    layer->texel = texel;
    layer->perspective = false;
}

/* A spot light's map: a perspective frustum around its outer cone, out to
 * its range (or the farthest caster). */
static void fit_spot(mvr_shadow_layer *layer, const mvr_frame *f, const mvr_frame_light *light, uint32_t size,
                     bool reversed)
{
    double far = light->range;
    if (!(far > 0.0)) {
        far = 0.0;
        for (uint32_t i = 0; i < f->draw_count; ++i) {
            const mvr_draw *d = &f->draws[i];
            mvr_dvec3 c = mvr_dvec3_make(d->center[0], d->center[1], d->center[2]);
            far = fmax(far, mvr_dvec3_length(mvr_dvec3_sub(c, light->position)) + d->radius);
        }
    }
    far = fmax(far, 1e-2);
    double near = fmax(far * 1e-4, 1e-3);
    double yfov = fmin(2.0 * light->outer_cone_angle * 1.05, 170.0 * PI / 180.0);
    mvr_dquat q = mvr_dquat_look_rotation(light->direction, any_up(light->direction));
    mvr_dmat4 view = mvr_dmat4_view(light->position, q);
    mvr_dmat4 proj = mvr_dmat4_perspective(yfov, 1.0, near, far, reversed);
    layer->view_proj = mvr_dmat4_mul(&proj, &view);
    layer->texel = 2.0 * tan(0.5 * yfov) / size;
    layer->perspective = true;
}

void mvr_shadow_plan_build(mvr_shadow_plan *plan, const mvr_frame *f, const mvr_view_set *views, uint32_t width,
                           uint32_t height, bool reversed, const mvr_shadow_desc *s)
{
    memset(plan, 0, sizeof *plan);
    uint32_t light_count = f->light_counts[0] + f->light_counts[1] + f->light_counts[2];
    for (uint32_t i = 0; i < MVR_FRAME_MAX_LIGHTS; ++i)
        plan->light_first[i] = -1;
    uint32_t all = light_count >= 32 ? 0xffffffffu : (1u << light_count) - 1u;
    uint32_t used = 0; /* lights shining in some enabled view */
    for (uint32_t v = 0; v < views->count; ++v) {
        if (!view_enabled(&views->views[v], width, height))
            continue;
        uint32_t m = mvr_view_light_mask(f, &views->views[v]);
        used |= m;
        if ((m & all) != all)
            plan->masked = true;
    }
    scene_extent scene = scene_extent_of(f);
    if (s->mode == MVR_SHADOWS_OFF || !scene.any)
        return;
    for (uint32_t i = 0; i < light_count; ++i) {
        const mvr_frame_light *l = &f->lights[i];
        bool wants = l->type != MVR_LIGHT_POINT && (s->mode == MVR_SHADOWS_ALL || l->cast_shadows);
        if (!wants || !(used & (1u << i)))
            continue;
        uint32_t need = l->type == MVR_LIGHT_DIRECTIONAL ? s->cascades : 1u;
        if (plan->layer_count + need > MVR_SHADOW_MAX_LAYERS) {
            plan->lights_unshadowed++;
            continue;
        }
        plan->light_first[i] = (int32_t)plan->layer_count;
        plan->light_layers[i] = need;
        if (l->type == MVR_LIGHT_SPOT) {
            mvr_shadow_layer *layer = &plan->layers[plan->layer_count++];
            layer->light = i;
            fit_spot(layer, f, l, s->map_size, reversed);
            mvr_frustum_planes(&layer->view_proj, reversed, &layer->frustum);
            continue;
        }
        /* the views this light shines in, and the depth range the cascades split */
        view_geometry geoms[64];
        uint32_t geom_count = 0;
        double znear = INFINITY, zfar = 0.0;
        for (uint32_t v = 0; v < views->count && geom_count < MVR_ARRAY_COUNT(geoms); ++v) {
            const mvr_view_desc *vd = &views->views[v];
            if (!view_enabled(vd, width, height) || !(mvr_view_light_mask(f, vd) & (1u << i)))
                continue;
            if (!view_geometry_of(vd, views->origin, width, height, &geoms[geom_count]))
                continue;
            const view_geometry *g = &geoms[geom_count++];
            mvr_dvec3 eye = mvr_dmat4_transform_point(&g->inv_view, mvr_dvec3_make(0, 0, 0));
            /* to the scene's far side, or the view's far plane, or the setting */
            double reach = mvr_dvec3_length(mvr_dvec3_sub(scene.center, eye)) + scene.radius;
            if (g->zfar > 0)
                reach = fmin(reach, g->zfar);
            if (s->distance > 0)
                reach = s->distance;
            znear = fmin(znear, g->znear);
            zfar = fmax(zfar, reach);
        }
        if (geom_count == 0 || !(zfar > znear)) {
            plan->light_first[i] = -1;
            plan->light_layers[i] = 0;
            continue;
        }
        /* the practical split scheme (Zhang et al., "Parallel-Split Shadow
         * Maps for Large-scale Virtual Environments", 2006): a blend of
         * logarithmic and uniform splits, lambda = 0.75 */
        double prev = znear;
        for (uint32_t c = 0; c < need; ++c) {
            double t = (double)(c + 1) / need;
            double split = 0.75 * znear * pow(zfar / znear, t) + 0.25 * (znear + (zfar - znear) * t);
            mvr_shadow_layer *layer = &plan->layers[plan->layer_count++];
            layer->light = i;
            layer->cascade = c;
            fit_cascade(layer, f, l, geoms, geom_count, prev, split, s->map_size, reversed);
            mvr_frustum_planes(&layer->view_proj, reversed, &layer->frustum);
            prev = split;
        }
    }
    for (uint32_t v = 0; v < views->count; ++v) {
        if (!view_enabled(&views->views[v], width, height))
            continue;
        uint32_t m = mvr_view_light_mask(f, &views->views[v]), layers = 0;
        for (uint32_t i = 0; i < light_count; ++i)
            if (m & (1u << i))
                layers += plan->light_layers[i];
        if (layers > plan->max_view_layers)
            plan->max_view_layers = layers;
    }
}

static void put_f32(uint8_t *dst, const float *v, size_t n)
{
    memcpy(dst, v, n * sizeof *v);
}

void mvr_shadow_block_pack(const mvr_shadow_plan *plan, const mvr_shadow_desc *s, bool reversed,
                           uint8_t out[MVR_SHADOW_BLOCK_SIZE])
{
    memset(out, 0, MVR_SHADOW_BLOCK_SIZE);
    /* clip -> (u, v, depth) in [0, 1]: x and y always; z only for standard
     * depth (reversed-Z clip z is already in [0, 1]) */
    mvr_dmat4 bias = mvr_dmat4_identity();
    bias.m[0] = bias.m[5] = 0.5;
    bias.m[12] = bias.m[13] = 0.5;
    if (!reversed) {
        bias.m[10] = 0.5;
        bias.m[14] = 0.5;
    }
    for (uint32_t k = 0; k < plan->layer_count; ++k) {
        const mvr_shadow_layer *layer = &plan->layers[k];
        mvr_dmat4 m = mvr_dmat4_mul(&bias, &layer->view_proj);
        mvr_mat4f mf = mvr_dmat4_to_float(&m);
        put_f32(out + MVR_SHADOWS_MATRIX_OFFSET + k * MVR_SHADOWS_MATRIX_STRIDE, mf.m, 16);
        float params[4] = {(float)layer->texel, layer->perspective ? 1.0f : 0.0f, s->normal_bias,
                           1.0f / (float)s->map_size};
        put_f32(out + MVR_SHADOWS_PARAMS_OFFSET + k * MVR_SHADOWS_PARAMS_STRIDE, params, 4);
    }
    for (uint32_t i = 0; i < MVR_FRAME_MAX_LIGHTS; ++i) {
        int32_t info[4] = {plan->light_first[i], (int32_t)plan->light_layers[i], 0, 0};
        memcpy(out + MVR_SHADOWS_LIGHT_OFFSET + i * MVR_SHADOWS_LIGHT_STRIDE, info, sizeof info);
    }
}
