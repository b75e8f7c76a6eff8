/* Extra outputs per view (mvr_target_desc.outputs): depth, distance, normals,
 * IDs and coverage, drawn in the colour's passes. What a dataset user relies
 * on: a plane's depth to float precision, a sphere's normals, exact IDs that
 * follow the transparency rule, the same bytes on every view path, colour
 * unchanged by asking for outputs, and the reprojection of surface points
 * through the exported cameras onto pixels whose depth and ID are theirs. */
#include <math.h>
#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#include <stdlib.h>
#include <string.h>

#include "demo_builder.h"
#include "mvr/mvr.h"
#include "gl_test_util.h"
#include "mvr_test.h"

#define ALL_OUTPUTS                                                                                                   \
    (MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH) | MVR_OUTPUT_BIT(MVR_OUTPUT_DISTANCE) | MVR_OUTPUT_BIT(MVR_OUTPUT_NORMAL) |       \
     MVR_OUTPUT_BIT(MVR_OUTPUT_IDS) | MVR_OUTPUT_BIT(MVR_OUTPUT_COVERAGE))

/* Every output of every layer, read back. */
typedef struct outputs {
    uint32_t w, h, n;
    uint8_t *color;
    float *depth, *distance, *normal, *coverage;
    uint32_t *ids;
    mvr_frame_stats stats;
} outputs;

static void outputs_free(outputs *o)
{
    free(o->color);
    free(o->depth);
    free(o->distance);
    free(o->normal);
    free(o->coverage);
    free(o->ids);
    memset(o, 0, sizeof *o);
}

typedef struct render_opts {
    uint32_t w, h;
    mvr_view_path path;
    uint32_t outputs;            /* target outputs (0: colour alone) */
    mvr_normal_space normal_space;
    float cutoff;
} render_opts;

static bool render(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, const mvr_view_set *vs, const render_opts *ro,
                   outputs *o)
{
    memset(o, 0, sizeof *o);
    uint32_t n = mvr_view_set_count(vs);
    mvr_renderer_desc rd = {.context = ctx, .view_path = ro->path};
    mvr_renderer *r = NULL;
    mvr_target *tg = NULL;
    mvr_target_desc td = {.width = ro->w, .height = ro->h, .layers = n, .anti_aliasing = MVR_ANTI_ALIASING_NONE,
                          .outputs = ro->outputs};
    bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK;
    mvr_render_desc desc = {.exposure = 1.0f, .normal_space = ro->normal_space, .output_alpha_cutoff = ro->cutoff,
                            .clear_color = {0.1f, 0.2f, 0.3f, 1.0f}};
    ok = ok && mvr_renderer_render(r, s, vs, tg, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "render: %s", r ? mvr_renderer_last_error(r) : "no renderer");
    size_t px = (size_t)ro->w * ro->h;
    o->w = ro->w, o->h = ro->h, o->n = n;
    o->color = malloc(px * 4 * n);
    bool want[MVR_OUTPUT_COUNT] = {false};
    for (int k = 1; k < MVR_OUTPUT_COUNT; ++k)
        want[k] = (ro->outputs & MVR_OUTPUT_BIT(k)) != 0;
    void **dst[MVR_OUTPUT_COUNT] = {NULL, (void **)&o->depth, (void **)&o->distance, (void **)&o->normal,
                                    (void **)&o->ids, (void **)&o->coverage};
    for (int k = 1; k < MVR_OUTPUT_COUNT; ++k)
        if (want[k])
            *dst[k] = malloc(px * mvr_output_pixel_size((mvr_output)k) * n);
    for (uint32_t l = 0; ok && l < n; ++l) {
        ok = mvr_renderer_read_output(r, tg, l, MVR_OUTPUT_COLOR, o->color + l * px * 4, px * 4) == MVR_OK;
        for (int k = 1; ok && k < MVR_OUTPUT_COUNT; ++k) {
            if (!want[k])
                continue;
            size_t bytes = px * mvr_output_pixel_size((mvr_output)k);
            ok = mvr_renderer_read_output(r, tg, l, (mvr_output)k, (uint8_t *)*dst[k] + l * bytes, bytes) == MVR_OK;
        }
        CHECK_MSG(t, ok, "read back layer %u: %s", l, mvr_renderer_last_error(r));
    }
    if (r)
        mvr_renderer_get_stats(r, &o->stats);
    mvr_target_destroy(tg);
    mvr_renderer_destroy(r);
    return ok;
}

/* Two renders of every output (same size and views): the same bytes in each. */
static void check_same_outputs(mvr_test_state *t, const outputs *a, const outputs *b)
{
    size_t px = (size_t)a->w * a->h * a->n;
    CHECK(t, b->w == a->w && b->h == a->h && b->n == a->n);
    CHECK(t, memcmp(a->color, b->color, px * 4) == 0);
    CHECK(t, memcmp(a->depth, b->depth, px * 4) == 0);
    CHECK(t, memcmp(a->distance, b->distance, px * 4) == 0);
    CHECK(t, memcmp(a->normal, b->normal, px * 12) == 0);
    CHECK(t, memcmp(a->ids, b->ids, px * 16) == 0);
    CHECK(t, memcmp(a->coverage, b->coverage, px * 4) == 0);
}

static mvr_node_id add_shape(mvr_test_state *t, mvr_scene *s, demo_mesh *m, const mvr_material_desc *md,
                             const double at[3], const char *name)
{
    mvr_material_id mat = {0};
    mvr_mesh_id mesh = {0};
    mvr_node_id node = {0};
    CHECK(t, mvr_scene_add_material(s, md, &mat) == MVR_OK);
    CHECK(t, demo_mesh_add(s, m, mat, false, name, &mesh) == MVR_OK);
    demo_mesh_free(m);
    mvr_node_desc nd = {.mesh = mesh, .name = name, .translation = {at[0], at[1], at[2]}};
    CHECK(t, mvr_scene_add_node(s, &nd, &node) == MVR_OK);
    return node;
}

static mvr_material_desc plain_material(float r, float g, float b, float a, mvr_alpha_mode mode)
{
    mvr_material_desc md = {0};
    md.base_color_factor[0] = r;
    md.base_color_factor[1] = g;
    md.base_color_factor[2] = b;
    md.base_color_factor[3] = a;
    md.alpha_mode = mode;
    md.roughness_factor = 0.6f;
    return md;
}

/* Unprojects pixel (x, y_top) at view depth z through a camera: the world point. */
static void unproject(const mvr_view_camera *c, double x, double y_top, double z, double out[3])
{
    double cam[3] = {(x - c->cx) / c->fx * z, -(y_top - c->cy) / c->fy * z, -z}; /* OpenGL camera */
    const double *m = c->camera_to_world;
    for (int i = 0; i < 3; ++i)
        out[i] = m[i] * cam[0] + m[4 + i] * cam[1] + m[8 + i] * cam[2] + m[12 + i];
}

/* A plane 3.7 below eight views looking straight down: every covered pixel
 * reads depth 3.7 to float precision, its ray length from the intrinsics,
 * coverage 1 and the plane's IDs, on both paths. */
static void plane_depth_is_exact(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    demo_mesh m = {0};
    demo_plane(&m, 200.0f, 200.0f, 1.0f);
    mvr_material_desc md = plain_material(0.8f, 0.8f, 0.8f, 1.0f, MVR_ALPHA_OPAQUE);
    const double at[3] = {0, 0, 0};
    mvr_node_id plane = add_shape(t, s, &m, &md, at, "plane");
    const double d = 3.7;
    mvr_view_desc views[8];
    memset(views, 0, sizeof views);
    for (int i = 0; i < 8; ++i) {
        double eye[3] = {-2.0 + 0.6 * i, d, 1.5 - 0.4 * i}, target[3] = {eye[0], 0.0, eye[2]}, up[3] = {0, 0, -1};
        mvr_view_look_at(&views[i], eye, target, up);
        views[i].projection.yfov = 0.9 + 0.05 * i;
    }
    mvr_view_set *vs = NULL;
    mvr_view_set_desc vd = {.view_count = 8, .views = views};
    CHECK(t, mvr_view_set_create(&vd, &vs, NULL) == MVR_OK);
    outputs mv, loop;
    render_opts ro = {.w = 64, .h = 48, .path = MVR_VIEW_PATH_MULTIVIEW, .outputs = ALL_OUTPUTS};
    bool ok = render(t, ctx, s, vs, &ro, &mv);
    ro.path = MVR_VIEW_PATH_LOOP;
    ok = render(t, ctx, s, vs, &ro, &loop) && ok;
    if (ok) {
        size_t px = (size_t)64 * 48;
        double worst_depth = 0, worst_distance = 0;
        uint32_t bad_ids = 0, bad_coverage = 0;
        for (uint32_t v = 0; v < 8; ++v) {
            mvr_view_camera cam;
            CHECK(t, mvr_view_set_get_camera(vs, v, 64, 48, &cam) == MVR_OK);
            for (uint32_t y = 0; y < 48; ++y)
                for (uint32_t x = 0; x < 64; ++x) {
                    size_t i = v * px + (size_t)y * 64 + x;
                    double e = fabs(mv.depth[i] - d) / d;
                    worst_depth = e > worst_depth ? e : worst_depth;
                    /* the ray through the pixel centre (rows read bottom to top) */
                    double xn = (x + 0.5 - cam.cx) / cam.fx, yn = ((47 - y) + 0.5 - cam.cy) / cam.fy;
                    double ray = d * sqrt(1.0 + xn * xn + yn * yn);
                    e = fabs(mv.distance[i] - ray) / ray;
                    worst_distance = e > worst_distance ? e : worst_distance;
                    const uint32_t *id = mv.ids + i * 4;
                    bad_ids += id[0] != plane.id || id[1] != 1 || id[2] != 1 || id[3] != 1;
                    bad_coverage += mv.coverage[i] != 1.0f;
                }
        }
        printf("  plane: depth within %.3g, distance within %.3g (relative)\n", worst_depth, worst_distance);
        /* float precision: a few units in the last place of 3.7 */
        CHECK_MSG(t, worst_depth < 1e-6, "depth off by %.3g relative", worst_depth);
        /* the ray is interpolated per pixel, not at its exact centre in a
         * float: a few ulps too on llvmpipe; a GPU's length() is an
         * approximation (NVIDIA H100, driver 580: 2.05e-5) */
        const double distance_tolerance = mvr_context_caps(ctx)->is_software ? 4e-6 : 5e-5;
        CHECK_MSG(t, worst_distance < distance_tolerance, "distance off by %.3g relative (tolerance %.3g)",
                  worst_distance, distance_tolerance);
        CHECK_MSG(t, bad_ids == 0 && bad_coverage == 0, "%u pixels with other IDs, %u without coverage", bad_ids,
                  bad_coverage);
        /* the plane faces +Y: its world normal, everywhere */
        double worst_normal = 0;
        for (size_t i = 0; i < px * 8; ++i) {
            double dx = mv.normal[3 * i], dy = mv.normal[3 * i + 1] - 1.0, dz = mv.normal[3 * i + 2];
            double e = sqrt(dx * dx + dy * dy + dz * dz);
            worst_normal = e > worst_normal ? e : worst_normal;
        }
        CHECK_MSG(t, worst_normal < 1e-6, "normal off by %.3g", worst_normal);
        /* multiview and loop: the same bytes for every output */
        check_same_outputs(t, &mv, &loop);
        /* 8 views: one multiview pass per GL_MAX_VIEWS_OVR of them (6 on llvmpipe, 32 on NVIDIA) */
        const uint32_t max_views = (uint32_t)mvr_context_caps(ctx)->limits.max_views_ovr;
        const uint32_t passes = max_views ? (8 + max_views - 1) / max_views : 0;
        CHECK_MSG(t, mv.stats.view_path == MVR_VIEW_PATH_MULTIVIEW && mv.stats.multiview_passes == passes,
                  "%u multiview passes for 8 views, %u expected", mv.stats.multiview_passes, passes);
        CHECK(t, mv.stats.outputs == ALL_OUTPUTS && mv.stats.output_blend_passes == 0);
    }
    outputs_free(&mv);
    outputs_free(&loop);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* A tessellated unit sphere seen by a ring of views: each covered pixel,
 * unprojected with its depth through the view's camera, has the analytic
 * normal of its point, in world and in camera space. */
static void sphere_normals_match_the_analytic_normal(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    demo_mesh m = {0};
    demo_sphere(&m, 1.0f, 96, 48);
    mvr_material_desc md = plain_material(0.7f, 0.5f, 0.3f, 1.0f, MVR_ALPHA_OPAQUE);
    const double center[3] = {0.25, -0.5, 0.125};
    add_shape(t, s, &m, &md, center, "sphere");
    mvr_framing_desc fd = {.layout = MVR_LAYOUT_RING, .views = 6};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_frame_scene(s, &fd, &vs, NULL) == MVR_OK);
    outputs world, camera;
    render_opts ro = {.w = 80, .h = 80, .outputs = ALL_OUTPUTS};
    bool ok = vs && render(t, ctx, s, vs, &ro, &world);
    ro.normal_space = MVR_NORMAL_SPACE_CAMERA;
    ok = ok && render(t, ctx, s, vs, &ro, &camera);
    if (ok) {
        double worst = 0, worst_camera = 0;
        uint32_t covered = 0;
        for (uint32_t v = 0; v < 6; ++v) {
            mvr_view_camera cam;
            CHECK(t, mvr_view_set_get_camera(vs, v, 80, 80, &cam) == MVR_OK);
            for (uint32_t y = 0; y < 80; ++y)
                for (uint32_t x = 0; x < 80; ++x) {
                    size_t i = (size_t)v * 6400 + (size_t)y * 80 + x;
                    if (world.coverage[i] == 0.0f)
                        continue;
                    covered++;
                    double p[3];
                    unproject(&cam, x + 0.5, (79 - y) + 0.5, world.depth[i], p);
                    double nx = p[0] - center[0], ny = p[1] - center[1], nz = p[2] - center[2];
                    double len = sqrt(nx * nx + ny * ny + nz * nz);
                    nx /= len, ny /= len, nz /= len;
                    const float *n = world.normal + 3 * i;
                    double c = nx * n[0] + ny * n[1] + nz * n[2];
                    double a = acos(c > 1.0 ? 1.0 : c);
                    worst = a > worst ? a : worst;
                    /* camera space: the world normal turned by world_to_camera */
                    const double *w2c = cam.world_to_camera;
                    double cn[3];
                    for (int k = 0; k < 3; ++k)
                        cn[k] = w2c[k] * nx + w2c[4 + k] * ny + w2c[8 + k] * nz;
                    const float *m3 = camera.normal + 3 * i;
                    c = cn[0] * m3[0] + cn[1] * m3[1] + cn[2] * m3[2];
                    a = acos(c > 1.0 ? 1.0 : c);
                    worst_camera = a > worst_camera ? a : worst_camera;
                }
        }
        CHECK_MSG(t, covered > 6 * 800, "%u pixels covered", covered);
        printf("  sphere: normals within %.4f deg (world), %.4f deg (camera) over %u pixels\n", worst * 180.0 / M_PI,
               worst_camera * 180.0 / M_PI, covered);
        /* interpolated vertex normals of a sphere are radial at every point
         * of the facet: what remains is float precision (measured: 0.03 deg) */
        const double bound = 0.1 * M_PI / 180.0;
        CHECK_MSG(t, worst < bound, "world normals off by up to %.4f deg", worst * 180.0 / M_PI);
        CHECK_MSG(t, worst_camera < bound, "camera normals off by up to %.4f deg", worst_camera * 180.0 / M_PI);
        CHECK(t, memcmp(world.color, camera.color, (size_t)6400 * 4 * 6) == 0);
    }
    outputs_free(&world);
    outputs_free(&camera);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* The transparency rule: an opaque sphere behind two blended quads, one of
 * alpha 0.8 (recorded: above the cutoff) on the left, one of 0.2 (seen
 * through) on the right. Colour is the same bytes with and without
 * outputs; every output is the same on both paths. */
static void transparent_surfaces_follow_the_cutoff(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    demo_mesh m = {0};
    demo_sphere(&m, 1.0f, 48, 24);
    mvr_material_desc opaque = plain_material(0.7f, 0.5f, 0.3f, 1.0f, MVR_ALPHA_OPAQUE);
    const double origin[3] = {0, 0, 0};
    mvr_node_id sphere = add_shape(t, s, &m, &opaque, origin, "sphere");
    /* quads facing +Z (the plane is XZ facing +Y: turned by the node) in front of the sphere */
    mvr_node_id quads[2] = {{0}, {0}};
    const float alphas[2] = {0.8f, 0.2f};
    for (int q = 0; q < 2; ++q) {
        demo_plane(&m, 0.6f, 1.5f, 1.0f);
        mvr_material_desc md = plain_material(q ? 0.1f : 0.9f, 0.9f, q ? 0.9f : 0.1f, alphas[q], MVR_ALPHA_BLEND);
        md.double_sided = true;
        mvr_material_id mat = {0};
        mvr_mesh_id mesh = {0};
        CHECK(t, mvr_scene_add_material(s, &md, &mat) == MVR_OK);
        CHECK(t, demo_mesh_add(s, &m, mat, false, q ? "faint" : "strong", &mesh) == MVR_OK);
        demo_mesh_free(&m);
        mvr_node_desc nd = {.mesh = mesh, .translation = {q ? 0.65 : -0.65, 0.0, 1.6},
                            .rotation = {0.70710678118654752, 0, 0, 0.70710678118654752}};
        CHECK(t, mvr_scene_add_node(s, &nd, &quads[q]) == MVR_OK);
    }
    mvr_framing_desc fd = {.layout = MVR_LAYOUT_STEREO, .views = 6};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_frame_scene(s, &fd, &vs, NULL) == MVR_OK);
    outputs mv, loop, plain;
    render_opts ro = {.w = 96, .h = 64, .path = MVR_VIEW_PATH_MULTIVIEW, .outputs = ALL_OUTPUTS};
    bool ok = vs && render(t, ctx, s, vs, &ro, &mv);
    ro.path = MVR_VIEW_PATH_LOOP;
    ok = ok && render(t, ctx, s, vs, &ro, &loop);
    ro.path = MVR_VIEW_PATH_MULTIVIEW;
    ro.outputs = 0;
    ok = ok && render(t, ctx, s, vs, &ro, &plain);
    if (ok) {
        size_t px = (size_t)96 * 64 * 6;
        uint32_t strong = 0, faint = 0, on_sphere = 0, background_faint = 0;
        CHECK(t, mv.ids[0] == 0); /* a corner: the background */
        for (size_t i = 0; i < px; ++i) {
            uint32_t node = mv.ids[4 * i];
            strong += node == quads[0].id;
            faint += node == quads[1].id;
            on_sphere += node == sphere.id;
            /* the faint quad over the background: its colour shows, nothing is recorded */
            bool tinted = memcmp(mv.color + 4 * i, mv.color, 4) != 0; /* pixel 0: the clear colour */
            background_faint += node == 0 && tinted;
            CHECK(t, (node != 0) == (mv.coverage[i] == 1.0f));
            CHECK(t, node != 0 || (mv.depth[i] == 0.0f && mv.distance[i] == 0.0f));
        }
        CHECK_MSG(t, strong > 500 && faint == 0 && on_sphere > 500, "strong %u, faint %u, sphere %u", strong, faint,
                  on_sphere);
        CHECK_MSG(t, background_faint > 100, "%u background pixels tinted by the faint quad", background_faint);
        /* what the IDs name */
        CHECK(t, strcmp(mvr_scene_mesh_name(s, (mvr_mesh_id){2}), "strong") == 0);
        CHECK(t, mvr_scene_node_mesh(s, quads[1]).id == 3 && !mvr_scene_mesh_name(s, (mvr_mesh_id){4}));
        CHECK(t, mvr_scene_node_name(s, sphere) && !mvr_scene_node_name(s, (mvr_node_id){0}));
        /* the strong quad's IDs: its node, mesh 2, material 2, primitive 1 */
        for (size_t i = 0; i < px; ++i)
            if (mv.ids[4 * i] == quads[0].id)
                CHECK(t, mv.ids[4 * i + 1] == 2 && mv.ids[4 * i + 2] == 2 && mv.ids[4 * i + 3] == 1);
        CHECK(t, mv.stats.output_blend_passes == 1 && loop.stats.output_blend_passes == 6);
        CHECK(t, memcmp(mv.color, plain.color, px * 4) == 0);
        check_same_outputs(t, &mv, &loop);
    }
    /* a cutoff above 0.8 sees through both quads */
    outputs high;
    ro.outputs = MVR_OUTPUT_BIT(MVR_OUTPUT_IDS);
    ro.cutoff = 0.9f;
    if (ok && render(t, ctx, s, vs, &ro, &high)) {
        uint32_t quad_pixels = 0;
        for (size_t i = 0; i < (size_t)96 * 64 * 6; ++i)
            quad_pixels += high.ids[4 * i] == quads[0].id || high.ids[4 * i] == quads[1].id;
        CHECK_MSG(t, quad_pixels == 0, "%u quad pixels above a 0.9 cutoff", quad_pixels);
        CHECK(t, memcmp(high.color, plain.color, (size_t)96 * 64 * 6 * 4) == 0);
    }
    outputs_free(&high);
    outputs_free(&mv);
    outputs_free(&loop);
    outputs_free(&plain);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* Deterministic points on a sphere (a small LCG: the test must not vary). */
static double lcg(uint64_t *state)
{
    *state = *state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*state >> 11) / 9007199254740992.0;
}

/* Random points on a known sphere, projected with each view's exported
 * intrinsics and extrinsics, land on pixels whose ID is the sphere's and
 * whose depth is the point's within what half a pixel's move changes. */
static uint32_t check_reprojection(mvr_test_state *t, const mvr_view_set *vs, const outputs *o, const double c[3],
                                   double radius, double sag, uint32_t node, const char *what)
{
    uint64_t seed = 12345;
    uint32_t checked = 0, failed = 0;
    for (uint32_t k = 0; k < 400; ++k) {
        double z = 2.0 * lcg(&seed) - 1.0, phi = 2.0 * M_PI * lcg(&seed), r = sqrt(1.0 - z * z);
        double n[3] = {r * cos(phi), r * sin(phi), z};
        double p[3] = {c[0] + radius * n[0], c[1] + radius * n[1], c[2] + radius * n[2]};
        for (uint32_t v = 0; v < o->n; ++v) {
            mvr_view_camera cam;
            if (mvr_view_set_get_camera(vs, v, o->w, o->h, &cam) != MVR_OK)
                continue;
            const double *m = cam.world_to_camera;
            double q[3];
            for (int i = 0; i < 3; ++i)
                q[i] = m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i];
            if (q[2] >= 0.0)
                continue; /* behind the camera (it looks along -Z) */
            /* OpenCV / COLMAP: x right, y down, z forward */
            double X = q[0], Y = -q[1], Z = -q[2];
            double u = cam.fx * X / Z + cam.cx, vv = cam.fy * Y / Z + cam.cy;
            if (u < 1.0 || vv < 1.0 || u >= cam.width - 1.0 || vv >= cam.height - 1.0)
                continue;
            /* facing the camera within 70 degrees (the sphere is convex: then visible) */
            double e[3] = {cam.camera_to_world[12] - p[0], cam.camera_to_world[13] - p[1],
                           cam.camera_to_world[14] - p[2]};
            double el = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
            double cosine = (n[0] * e[0] + n[1] * e[1] + n[2] * e[2]) / el;
            if (cosine < cos(70.0 * M_PI / 180.0))
                continue;
            uint32_t x = (uint32_t)u, y = (uint32_t)vv;
            size_t i = (size_t)v * o->w * o->h + (size_t)(o->h - 1 - y) * o->w + x;
            /* half a pixel's footprint at depth Z (to the corner: 0.71), stretched
             * by the slope, plus how far the tessellated mesh lies inside the
             * sphere (sag) along the ray */
            double pixel = Z / cam.fx;
            double tol = 0.75 * pixel * sqrt(1.0 - cosine * cosine) / cosine + sag / cosine + 1e-5 * Z;
            bool ok = o->ids[4 * i] == node && fabs(o->depth[i] - Z) <= tol;
            if (!ok && failed++ < 5)
                CHECK_MSG(t, ok, "%s: point %u in view %u at (%.2f, %.2f): id %u (want %u), depth %.6f (point %.6f, tol %.2g)",
                          what, k, v, u, vv, o->ids[4 * i], node, (double)o->depth[i], Z, tol);
            checked++;
        }
    }
    CHECK_MSG(t, failed == 0, "%s: %u of %u points off", what, failed, checked);
    printf("  %s: %u point projections on their pixels\n", what, checked);
    return checked;
}

/* a 128 x 64 UV sphere of radius 1: a facet's centre lies at most about
 * 1 - cos(pi / 64) inside the sphere (the diagonal of a quad facet) */
#define SPHERE_SAG (1.0 - cos(M_PI / 64.0))

static void points_reproject_onto_their_pixels(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    demo_mesh m = {0};
    demo_sphere(&m, 1.0f, 128, 64);
    mvr_material_desc md = plain_material(0.6f, 0.6f, 0.6f, 1.0f, MVR_ALPHA_OPAQUE);
    const double center[3] = {1.5, 0.75, -2.0};
    mvr_node_id node = add_shape(t, s, &m, &md, center, "sphere");
    /* the cube layout's views stand at the scene's centre: a scene whose centre
     * is outside the sphere (a small ball 6 units away) gives them a view of it */
    mvr_scene *with_ball = NULL;
    CHECK(t, mvr_scene_create(NULL, &with_ball, NULL) == MVR_OK);
    demo_sphere(&m, 1.0f, 128, 64);
    mvr_node_id cube_node = add_shape(t, with_ball, &m, &md, center, "sphere");
    demo_sphere(&m, 0.1f, 16, 8);
    const double ball[3] = {center[0] - 6.0, center[1], center[2]};
    add_shape(t, with_ball, &m, &md, ball, "ball");
    static const mvr_view_layout layouts[] = {MVR_LAYOUT_STEREO, MVR_LAYOUT_CUBE, MVR_LAYOUT_RING,
                                              MVR_LAYOUT_GRID,   MVR_LAYOUT_SPHERE, MVR_LAYOUT_ORBIT};
    for (size_t l = 0; l < sizeof layouts / sizeof layouts[0]; ++l) {
        bool cube = layouts[l] == MVR_LAYOUT_CUBE;
        mvr_scene *scene = cube ? with_ball : s;
        mvr_framing_desc fd = {.layout = layouts[l], .views = layouts[l] == MVR_LAYOUT_SPHERE ? 12 : 0,
                               .aspect = cube ? 1.0 : 1.5};
        mvr_view_set *vs = NULL;
        CHECK(t, mvr_view_set_frame_scene(scene, &fd, &vs, NULL) == MVR_OK);
        if (!vs)
            continue;
        outputs o;
        render_opts ro = {.w = cube ? 64 : 96, .h = 64,
                          .outputs = MVR_OUTPUT_BIT(MVR_OUTPUT_DEPTH) | MVR_OUTPUT_BIT(MVR_OUTPUT_IDS)};
        if (render(t, ctx, scene, vs, &ro, &o)) {
            uint32_t checked = check_reprojection(t, vs, &o, center, 1.0, SPHERE_SAG, cube ? cube_node.id : node.id,
                                                  mvr_view_layout_name(layouts[l]));
            CHECK_MSG(t, checked > 50, "%s: only %u points checked", mvr_view_layout_name(layouts[l]), checked);
        }
        outputs_free(&o);
        mvr_view_set_destroy(vs);
    }
    mvr_scene_destroy(with_ball);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* What is refused, naming it. */
static void outputs_refusals_name_the_problem(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_renderer_desc rd = {.context = ctx};
    mvr_renderer *r = NULL;
    CHECK(t, mvr_renderer_create(&rd, &r, NULL) == MVR_OK);
    mvr_target *tg = NULL;
    mvr_target_desc msaa = {.width = 16, .height = 16, .samples = 4, .outputs = MVR_OUTPUT_BIT(MVR_OUTPUT_IDS)};
    CHECK(t, mvr_target_create(r, &msaa, &tg) == MVR_ERROR_INVALID_ARGUMENT && !tg);
    CHECK(t, strstr(mvr_renderer_last_error(r), "anti-aliasing") != NULL);
    mvr_target_desc bad = {.width = 16, .height = 16, .outputs = 1u << 20};
    CHECK(t, mvr_target_create(r, &bad, &tg) == MVR_ERROR_INVALID_ARGUMENT && !tg);
    CHECK(t, strstr(mvr_renderer_last_error(r), "output bits") != NULL);
    mvr_target_desc ids = {.width = 16, .height = 16, .layers = 2, .outputs = MVR_OUTPUT_BIT(MVR_OUTPUT_IDS)};
    CHECK(t, mvr_target_create(r, &ids, &tg) == MVR_OK);
    float depth[256];
    uint32_t id4[256 * 4];
    CHECK(t, mvr_renderer_read_output(r, tg, 0, MVR_OUTPUT_DEPTH, depth, sizeof depth) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_renderer_last_error(r), "depth output") != NULL);
    CHECK(t, mvr_renderer_read_output(r, tg, 0, MVR_OUTPUT_IDS, id4, sizeof id4 - 1) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_renderer_last_error(r), "needed") != NULL);
    CHECK(t, mvr_renderer_read_output(r, tg, 2, MVR_OUTPUT_IDS, id4, sizeof id4) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_renderer_read_output(r, tg, 0, (mvr_output)77, id4, sizeof id4) == MVR_ERROR_INVALID_ARGUMENT);
    /* a target never rendered reads its cleared state: nothing */
    CHECK(t, mvr_renderer_read_output(r, tg, 1, MVR_OUTPUT_IDS, id4, sizeof id4) == MVR_OK);
    CHECK(t, mvr_output_pixel_size(MVR_OUTPUT_NORMAL) == 12 && mvr_output_pixel_size(MVR_OUTPUT_IDS) == 16);
    CHECK(t, strcmp(mvr_output_name(MVR_OUTPUT_DISTANCE), "distance") == 0 && !mvr_output_name(MVR_OUTPUT_COUNT));
    mvr_target_destroy(tg);
    mvr_renderer_destroy(r);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(plane_depth_is_exact), TEST(sphere_normals_match_the_analytic_normal),
              TEST(transparent_surfaces_follow_the_cutoff), TEST(points_reproject_onto_their_pixels),
              TEST(outputs_refusals_name_the_problem))
