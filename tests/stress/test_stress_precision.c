/* Stress suite, precision: large world offsets, depth ordering, extreme
 * projections and degenerate input. Each threshold is written next to its
 * check with the reason for it; measured values are recorded
 * (stress_record) for the README's accuracy section. */
#include "stress_util.h"

#define OFFSET_SIZE 128u

static mvr_context *stress_context(mvr_test_state *t)
{
    return create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
}

/* A checkered image: a texture makes sub-pixel shifts visible. */
static mvr_image_id checker_image(mvr_test_state *t, mvr_scene *s)
{
    uint8_t px[16 * 16 * 4];
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            bool on = ((x / 2) ^ (y / 2)) & 1;
            uint8_t *p = px + (y * 16 + x) * 4;
            p[0] = on ? 230 : 40;
            p[1] = on ? 180 : 90;
            p[2] = on ? 60 : 200;
            p[3] = 255;
        }
    mvr_image_desc d = {.width = 16, .height = 16, .rgba8 = px, .name = "checker"};
    mvr_image_id id = {0};
    CHECK(t, mvr_scene_add_image(s, &d, &id) == MVR_OK);
    return id;
}

/* The textured, lit 1 m cube at `offset` seen from 5 m away. The view
 * set's origin is the view's position (its default: the views' centroid),
 * or `origin` when given: the world origin is what a renderer without
 * camera-relative transforms does. */
static uint8_t *render_offset_cube(mvr_test_state *t, mvr_context *ctx, double offset, const double *origin)
{
    mvr_scene *s = stress_scene();
    mvr_material_desc m = mvr_material_defaults();
    m.base_color = (mvr_texture_ref){.image = checker_image(t, s)};
    m.metallic_factor = 0.0f;
    m.roughness_factor = 0.4f;
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, &m, &mat) == MVR_OK);
    stress_node(t, s, stress_add_box(t, s, 0.5f, mat), offset, offset, offset, 1.0);
    mvr_light_desc ld = {.type = MVR_LIGHT_POINT, .intensity = 30.0f};
    mvr_light_id light;
    CHECK(t, mvr_scene_add_light(s, &ld, &light) == MVR_OK);
    mvr_node_desc ln = {.light = light, .translation = {offset + 2.0, offset + 3.0, offset + 2.5}};
    mvr_node_id lnode;
    CHECK(t, mvr_scene_add_node(s, &ln, &lnode) == MVR_OK);
    const float ambient[3] = {0.05f, 0.05f, 0.05f};
    mvr_scene_set_ambient(s, ambient);
    /* 5 m away along (3, 2, 4) / |(3, 2, 4)| */
    double k = 5.0 / sqrt(29.0);
    double eye[3] = {offset + 3 * k, offset + 2 * k, offset + 4 * k}, target[3] = {offset, offset, offset};
    mvr_projection proj = {.yfov = 0.5, .znear = 0.1};
    mvr_view_desc v = stress_view(eye, target, proj);
    mvr_view_set *vs = stress_view_set(t, &v, 1, origin);
    stress_options o = {.width = OFFSET_SIZE, .height = OFFSET_SIZE, .clear = {0, 0, 0, 1}};
    uint8_t *px = vs ? stress_render(t, ctx, s, vs, &o, NULL) : NULL;
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    return px;
}

/* Large offsets: camera-relative transforms (composed in double, narrowed
 * after subtracting the view set's origin) keep a cube at 1e7 units as
 * sharp as at the origin. */
static void large_offsets(mvr_test_state *t)
{
    mvr_context *ctx = stress_context(t);
    if (!ctx)
        return;
    const size_t bytes = (size_t)OFFSET_SIZE * OFFSET_SIZE * 4;
    uint8_t *ref = render_offset_cube(t, ctx, 0.0, NULL);
    const double offsets[4] = {1e4, 1e5, 1e6, 1e7};
    unsigned worst = 0;
    char measured[256] = "";
    for (int i = 0; ref && i < 4; ++i) {
        uint8_t *img = render_offset_cube(t, ctx, offsets[i], NULL);
        if (!img)
            continue;
        unsigned d = max_abs_diff8(ref, img, bytes);
        /* threshold 1/255: one 8-bit step, the encoding's own rounding */
        CHECK_MSG(t, d <= 1, "cube at %g: max difference %u/255 to the origin image", offsets[i], d);
        worst = d > worst ? d : worst;
        free(img);
    }
    /* for the record: the same cube without a camera-relative origin */
    const double zero[3] = {0, 0, 0};
    uint8_t *naive = ref ? render_offset_cube(t, ctx, 1e5, zero) : NULL;
    unsigned naive_d = naive ? max_abs_diff8(ref, naive, bytes) : 0;
    /* and with the origin where a ring of cameras 1 km across would put it:
     * its centre, 500 m from this camera (docs/guide.md, "The origin") */
    unsigned ring_d[2] = {0, 0};
    for (int i = 0; i < 2 && ref; ++i) {
        double far_origin[3] = {1e5 + 500.0, 1e5, 1e5}, near_origin[3] = {1e5 + 50.0, 1e5, 1e5};
        uint8_t *img = render_offset_cube(t, ctx, 1e5, i ? near_origin : far_origin);
        ring_d[i] = img ? max_abs_diff8(ref, img, bytes) : 0;
        free(img);
    }
    /* that naive render really is broken at 1e5, so this test can fail */
    CHECK_MSG(t, naive_d > 1, "without a camera-relative origin the cube at 1e5 still matches (%u)", naive_d);
    snprintf(measured, sizeof measured,
             "%u/255 (origin 500 m / 50 m from the camera: %u/255 / %u/255; at world 0: %u/255 at 1e5)", worst,
             ring_d[0], ring_d[1], naive_d);
    stress_record("large offsets: 1 m cube at 1e4..1e7, max difference to the cube at 0", "<= 1/255", measured,
                  "one 8-bit step: the output encoding's own rounding");
    free(naive);
    free(ref);
    mvr_context_destroy(ctx);
}

/* Two parallel screen-filling quads at d and d * (1 + gap): whether every
 * pixel shows the front one, with the front quad's material drawn first
 * and then last (the opaque sort orders by material). Where the depth
 * buffer cannot tell the two apart, the outcome is the rounding's coin
 * flip, so the pair is tried at four distances around d and counts as
 * ordered only when all four are. */
static bool quads_ordered(mvr_test_state *t, mvr_context *ctx, mvr_depth_mode depth, double d0, double gap)
{
    bool all = true;
    for (int trial = 0; trial < 8 && all; ++trial) {
        int order = trial & 1;
        double d = d0 * (1.0 + 0.0137 * (trial >> 1));
        mvr_scene *s = stress_scene();
        mvr_material_id first = stress_unlit(t, s, 1, 0, 0), second = stress_unlit(t, s, 0, 1, 0);
        mvr_material_id front = order == 0 ? first : second, back = order == 0 ? second : first;
        double half = d * 2.0; /* covers the 60 degree view at d */
        stress_node(t, s, stress_add_quad(t, s, front), 0, 0, -d, half);
        stress_node(t, s, stress_add_quad(t, s, back), 0, 0, -d * (1.0 + gap), half);
        double eye[3] = {0, 0, 0}, target[3] = {0, 0, -1};
        /* standard depth needs a finite far plane: 1e6 holds every pair */
        mvr_projection proj = {.yfov = 1.0471975511965976, .znear = 0.1,
                               .zfar = depth == MVR_DEPTH_MODE_STANDARD ? 1e6 : 0.0};
        mvr_view_desc v = stress_view(eye, target, proj);
        mvr_view_set *vs = stress_view_set(t, &v, 1, NULL);
        stress_options o = {.width = 32, .height = 32, .depth = depth, .clear = {0, 0, 1, 1}};
        mvr_frame_stats st;
        uint8_t *px = vs ? stress_render(t, ctx, s, vs, &o, &st) : NULL;
        if (px) {
            CHECK_EQ_INT(t, st.depth_mode, depth);
            /* the front quad's color, sRGB-encoded: red for order 0, green for 1 */
            for (size_t i = 0; i < 32u * 32u; ++i) {
                bool red = px[i * 4] == 255 && px[i * 4 + 1] == 0 && px[i * 4 + 2] == 0;
                bool green = px[i * 4] == 0 && px[i * 4 + 1] == 255 && px[i * 4 + 2] == 0;
                if (!(order == 0 ? red : green))
                    all = false;
            }
        } else {
            all = false;
        }
        free(px);
        mvr_view_set_destroy(vs);
        mvr_scene_destroy(s);
    }
    return all;
}

/* Depth ordering: reversed-Z with a float depth buffer orders surfaces
 * a relative gap of 1e-5 apart anywhere from 1 to 1e5 units (near 0.1);
 * standard depth's smallest resolved gap is recorded for comparison. */
static void depth_ordering(mvr_test_state *t)
{
    mvr_context *ctx = stress_context(t);
    if (!ctx)
        return;
    bool reversed = mvr_context_caps(ctx)->ext.ext_clip_control;
    if (!reversed && mvr_test_in_ci()) {
        CHECK_MSG(t, 0, "no GL_EXT_clip_control: reversed-Z cannot be tested");
    }
    const double distances[6] = {1, 10, 100, 1e3, 1e4, 1e5};
    char rev_line[512] = "", std_line[512] = "";
    size_t rl = 0, sl = 0;
    for (int i = 0; i < 6; ++i) {
        double d = distances[i];
        if (reversed) {
            /* threshold: relative gap 1e-5 (the precision mvr promises) at every distance */
            CHECK_MSG(t, quads_ordered(t, ctx, MVR_DEPTH_MODE_REVERSED_Z, d, 1e-5),
                      "reversed-Z: quads at %g and %g are not ordered", d, d * (1 + 1e-5));
            double smallest = 1e-5;
            while (smallest > 1e-8 && quads_ordered(t, ctx, MVR_DEPTH_MODE_REVERSED_Z, d, smallest / 10))
                smallest /= 10;
            rl += (size_t)snprintf(rev_line + rl, sizeof rev_line - rl, "%s%g: %g", i ? ", " : "", d, smallest);
        }
        /* standard depth: the smallest of 1e-1 .. 1e-7 it still orders (for the record) */
        double smallest = 0;
        for (double g = 1e-1; g >= 1e-7; g /= 10) {
            if (!quads_ordered(t, ctx, MVR_DEPTH_MODE_STANDARD, d, g))
                break;
            smallest = g;
        }
        if (smallest > 0)
            sl += (size_t)snprintf(std_line + sl, sizeof std_line - sl, "%s%g: %g", i ? ", " : "", d, smallest);
        else
            sl += (size_t)snprintf(std_line + sl, sizeof std_line - sl, "%s%g: > 0.1", i ? ", " : "", d);
    }
    if (reversed)
        stress_record("depth ordering, reversed-Z (float depth, infinite far): smallest relative gap ordered, by distance",
                      "<= 1e-5 at 1 .. 1e5", rev_line,
                      "the precision mvr promises; float depth keeps about 24 bits of relative precision at any distance");
    stress_record("depth ordering, standard depth (near 0.1, far 1e6): smallest relative gap ordered, by distance",
                  "(for the record)", std_line, "what conventional Z resolves where clip control is missing");
    mvr_context_destroy(ctx);
}

static size_t count_nonfinite(const float *px, size_t floats)
{
    size_t n = 0;
    for (size_t i = 0; i < floats; ++i)
        n += isfinite(px[i]) ? 0u : 1u;
    return n;
}

/* Extreme projections: fov 1 and 170 degrees, near 1e-4, aspect 1:20 and
 * orthographic. A 1-unit-wide unlit quad is placed so that it covers a known
 * share of the view; its pixel count must match the projection's own
 * prediction within a pixel of its outline, with no NaN anywhere. */
static void extreme_projections(mvr_test_state *t)
{
    mvr_context *ctx = stress_context(t);
    if (!ctx)
        return;
    typedef struct { const char *name; mvr_projection proj; uint32_t w, h; double dist; } config;
    const double deg = 3.14159265358979323846 / 180.0;
    const config cfgs[] = {
        {"fov 1 deg", {.yfov = 1 * deg, .znear = 0.1}, 64, 64, 0},
        {"fov 170 deg", {.yfov = 170 * deg, .znear = 0.1}, 64, 64, 0},
        {"near 1e-4", {.yfov = 60 * deg, .znear = 1e-4}, 64, 64, 0},
        {"aspect 1:20", {.yfov = 60 * deg, .znear = 0.1}, 8, 160, 0},
        {"orthographic", {.type = MVR_PROJECTION_ORTHOGRAPHIC, .xmag = 2, .ymag = 2, .znear = 0.1, .zfar = 100},
         64, 64, 0},
    };
    char measured[512] = "";
    size_t ml = 0;
    for (size_t c = 0; c < sizeof cfgs / sizeof cfgs[0]; ++c) {
        const config *cf = &cfgs[c];
        /* the quad (half size 0.5 * q) fills about half the view's height */
        double half_h;   /* visible half height at the quad's distance */
        double dist = 10.0;
        if (cf->proj.type == MVR_PROJECTION_ORTHOGRAPHIC) {
            half_h = cf->proj.ymag;
        } else {
            if (cf->proj.znear < 1e-3)
                dist = 0.01; /* close to the near plane */
            half_h = dist * tan(cf->proj.yfov * 0.5);
        }
        double half_w = half_h * (cf->proj.type == MVR_PROJECTION_ORTHOGRAPHIC ? cf->proj.xmag / cf->proj.ymag
                                                                                  : (double)cf->w / cf->h);
        double q = 0.5 * (half_h < half_w ? half_h : half_w); /* half size: half of the smaller extent */
        mvr_scene *s = stress_scene();
        stress_node(t, s, stress_add_quad(t, s, stress_unlit(t, s, 1, 1, 1)), 0, 0, -dist, q);
        double eye[3] = {0, 0, 0}, target[3] = {0, 0, -1};
        mvr_view_desc v = stress_view(eye, target, cf->proj);
        mvr_view_set *vs = stress_view_set(t, &v, 1, NULL);
        stress_options o = {.width = cf->w, .height = cf->h, .format = MVR_COLOR_FORMAT_RGBA32F,
                            .readback = MVR_READBACK_RGBA32F, .clear = {0, 0, 0, 1}};
        float *px = vs ? stress_render(t, ctx, s, vs, &o, NULL) : NULL;
        if (px) {
            size_t pixels = (size_t)cf->w * cf->h;
            size_t bad = count_nonfinite(px, pixels * 4), covered = 0;
            for (size_t i = 0; i < pixels; ++i)
                covered += px[i * 4] > 0.5f ? 1u : 0u;
            /* prediction: the quad spans q / half_w of the width and q / half_h of the height */
            double ew = cf->w * q / half_w, eh = cf->h * q / half_h;
            double expect = ew * eh;
            double slack = 2.0 * (ew + eh) + 4.0; /* a pixel of its outline either way */
            CHECK_MSG(t, bad == 0, "%s: %zu NaN/Inf values", cf->name, bad);
            CHECK_MSG(t, fabs((double)covered - expect) <= slack, "%s: the quad covers %zu pixels, expected %.1f +- %.1f",
                      cf->name, covered, expect, slack);
            ml += (size_t)snprintf(measured + ml, sizeof measured - ml, "%s%s %zu/%.0f px", c ? ", " : "", cf->name,
                                   covered, expect);
        }
        free(px);
        mvr_view_set_destroy(vs);
        mvr_scene_destroy(s);
    }
    stress_record("extreme projections: quad coverage (drawn / predicted pixels), NaN/Inf 0", "outline +-1 px, 0 NaN",
                  measured, "rasterization rounds edges to pixel centers; anything else is lost geometry");
    mvr_context_destroy(ctx);
}

/* Degenerate meshes: NaN and zero normals, bad tangents, a normal map
 * without tangents on degenerate UVs, zero-area triangles, a flattened and a
 * mirrored node, a non-unit quaternion, denormal and extreme factors, a
 * light on the surface; rendered lit into a float target from six sides:
 * no NaN or infinite value reaches a pixel. */
static void degenerate_meshes(mvr_test_state *t)
{
    mvr_context *ctx = stress_context(t);
    if (!ctx)
        return;
    mvr_scene *s = stress_scene();
    const float nan = NAN, inf = INFINITY;
    /* a bumpy normal map */
    uint8_t nm[8 * 8 * 4];
    for (int i = 0; i < 64; ++i) {
        nm[i * 4 + 0] = (uint8_t)(128 + 100 * ((i % 3) - 1));
        nm[i * 4 + 1] = (uint8_t)(128 + 100 * (((i / 8) % 3) - 1));
        nm[i * 4 + 2] = 200;
        nm[i * 4 + 3] = 255;
    }
    mvr_image_desc nd = {.width = 8, .height = 8, .rgba8 = nm, .name = "bumps"};
    mvr_image_id bumps;
    CHECK(t, mvr_scene_add_image(s, &nd, &bumps) == MVR_OK);
    mvr_material_desc m = mvr_material_defaults();
    m.normal = (mvr_texture_ref){.image = bumps};
    m.roughness_factor = 0.0f;          /* GGX at its sharpest */
    m.metallic_factor = 1e-40f;         /* denormal */
    m.base_color_factor[1] = 1e-39f;    /* denormal */
    m.emissive_factor[0] = 1e-42f;
    m.double_sided = true;
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, &m, &mat) == MVR_OK);

    /* triangles: fine, zero-area (collinear), zero-area (one point), sliver */
    const float pos[36] = {0, 0, 0, 1, 0, 0, 0, 1, 0, /* fine */
                           0, 0, 0, 1, 1, 0, 2, 2, 0, /* collinear */
                           .5f, .5f, 0, .5f, .5f, 0, .5f, .5f, 0,
                           0, 0, 0, 1, 1e-7f, 0, 1, 0, 0};
    const float nrm[36] = {nan, 0, 1, 0, 0, 0, 0, inf, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                           0, 0, 1, 0, 0, 1, 0, 0, 1, 1e-30f, 0, 0, 0, 0, 1, 0, 0, -1};
    const float tan4[48] = {nan, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1,
                            1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1};
    const float uv[24] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, /* degenerate UVs */
                          0, 0, 1, 1, 2, 2, nan, 0, 0, inf, 1, 1, 0, 0, 1, 0, 0, 1};
    mvr_primitive_desc prims[2] = {
        {.vertex_count = 12, .positions = pos, .normals = nrm, .texcoords0 = uv, .material = mat},
        {.vertex_count = 12, .positions = pos, .normals = nrm, .tangents = tan4, .texcoords0 = uv, .material = mat},
    };
    mvr_mesh_desc md = {.primitives = prims, .primitive_count = 2, .name = "degenerate"};
    mvr_mesh_id mesh;
    CHECK_MSG(t, mvr_scene_add_mesh(s, &md, &mesh) == MVR_OK, "%s", mvr_scene_last_error(s));
    mvr_mesh_id box = stress_add_box(t, s, 0.5f, mat);
    /* nodes: plain, flattened (zero scale on an axis), mirrored, a
     * quaternion of length 5, and a box with a zero-scale axis */
    mvr_node_desc nodes[5] = {
        {.mesh = mesh, .translation = {-1.5, 0, 0}},
        {.mesh = mesh, .translation = {0, 1.5, 0}, .scale = {1, 0, 1}},
        {.mesh = mesh, .translation = {1.5, 0, 0}, .scale = {-1, 1, 1}},
        {.mesh = mesh, .translation = {0, -1.5, 0}, .rotation = {0, 0, 3, 4}},
        {.mesh = box, .translation = {0, 0, 1}, .scale = {1, 1, 0}},
    };
    for (int i = 0; i < 5; ++i) {
        mvr_node_id id;
        CHECK(t, mvr_scene_add_node(s, &nodes[i], &id) == MVR_OK);
    }
    /* a point light on the surface of the plain triangle, and a spot */
    mvr_light_desc pl = {.type = MVR_LIGHT_POINT, .intensity = 5.0f};
    mvr_light_desc sp = {.type = MVR_LIGHT_SPOT, .intensity = 50.0f, .outer_cone_angle = 0.5f, .inner_cone_angle = 0.5f};
    mvr_light_id l1, l2;
    CHECK(t, mvr_scene_add_light(s, &pl, &l1) == MVR_OK && mvr_scene_add_light(s, &sp, &l2) == MVR_OK);
    mvr_node_desc ln1 = {.light = l1, .translation = {-1.25, 0.25, 0}};
    mvr_node_desc ln2 = {.light = l2, .translation = {0, 0, 3}};
    mvr_node_id id;
    CHECK(t, mvr_scene_add_node(s, &ln1, &id) == MVR_OK && mvr_scene_add_node(s, &ln2, &id) == MVR_OK);
    CHECK(t, mvr_scene_sanitized_count(s) > 0);

    /* six views around the scene, one looking straight along the flattened node */
    mvr_view_desc views[6];
    const double eyes[6][3] = {{0, 0, 5}, {0, 0, -5}, {5, 0, 0.01}, {-5, 0, 0}, {0, 5, 0}, {0, 1.5, 5}};
    for (int i = 0; i < 6; ++i) {
        const double target[3] = {0, i == 5 ? 1.5 : 0, 0};
        mvr_projection proj = {.yfov = 1.2, .znear = 0.05};
        views[i] = stress_view(eyes[i], target, proj);
    }
    mvr_view_set *vs = stress_view_set(t, views, 6, NULL);
    size_t worst = 0;
    for (int path = 0; path < 2 && vs; ++path) {
        stress_options o = {.width = 64, .height = 64, .format = MVR_COLOR_FORMAT_RGBA32F,
                            .readback = MVR_READBACK_RGBA32F, .clear = {0, 0, 0, 1},
                            .path = path ? MVR_VIEW_PATH_LOOP : MVR_VIEW_PATH_AUTO};
        mvr_frame_stats st;
        float *px = stress_render(t, ctx, s, vs, &o, &st);
        if (px) {
            size_t bad = count_nonfinite(px, (size_t)64 * 64 * 4 * 6), lit = 0;
            for (size_t i = 0; i < (size_t)64 * 64 * 6; ++i)
                lit += px[i * 4] + px[i * 4 + 1] + px[i * 4 + 2] > 0.0f ? 1u : 0u;
            /* threshold 0: one NaN poisons whatever filters or blends it later */
            CHECK_MSG(t, bad == 0, "%s: %zu NaN/Inf values", path ? "loop" : "auto", bad);
            CHECK_MSG(t, lit > 300, "only %zu pixels drawn: the scene is not in view", lit);
            CHECK_EQ_INT(t, st.sanitized, mvr_scene_sanitized_count(s));
            worst = bad > worst ? bad : worst;
        }
        free(px);
    }
    char measured[64];
    snprintf(measured, sizeof measured, "%zu (%u values repaired on input)", worst, mvr_scene_sanitized_count(s));
    stress_record("degenerate meshes: NaN/Inf values in a float target, 6 views", "0", measured,
                  "one NaN poisons whatever filters or blends it later");
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(large_offsets), TEST(depth_ordering), TEST(extreme_projections), TEST(degenerate_meshes))
