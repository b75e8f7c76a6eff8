/* gl: KHR_materials_transmission and _volume across views (gl/transmission.c).
 * A striped, unlit wall behind a transmissive quad, no lights and no
 * environment (the transmitted light is then exactly what lies behind, times
 * the base color):
 * - a thin-walled quad of transmission 1 disappears: every pixel is the
 *   wall-only render's (within 1/255);
 * - transmission 0.5 halves the wall's linear radiance behind it;
 * - a volume of thickness 1, ior 1 and attenuation color (0.25, 1, 1) at
 *   distance 1 scales the red of what is behind by 0.25 (linear);
 * - with lights, an environment, a transmission texture, dispersion and a
 *   rough surface: multiview and loop, arrays and per-material give the
 *   same bytes; the stats count one copy per view;
 * - a scene without transmission copies nothing and compiles no
 *   transmission code. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "demo_builder.h"
#include "gl_test_util.h"
#include "mvr/mvr.h"
#include "shader_gen.h"
#include "render_views.h"
#include "skin_render.h"

#define W 64
#define H 64
#define TW 16

static uint8_t stripes[TW * TW * 4];

typedef struct glass {
    bool present;
    float transmission, roughness, thickness, ior, dispersion;
    float attenuation_distance, attenuation_color[3];
    bool texture;
} glass;

/* The wall (unlit, striped, 4 x 4 at z = -2) and the glass quad (2 x 2 at z = 0). */
static mvr_scene *make_scene(mvr_test_state *t, const glass *g, bool light)
{
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    mvr_image_desc id = {.width = TW, .height = TW, .rgba8 = stripes, .name = "stripes"};
    mvr_image_id img;
    CHECK(t, mvr_scene_add_image(s, &id, &img) == MVR_OK);
    mvr_material_desc wall = mvr_material_defaults();
    wall.unlit = true;
    wall.base_color.image = img;
    wall.base_color.sampler = (mvr_sampler_desc){MVR_FILTER_NEAREST, MVR_FILTER_NEAREST, MVR_WRAP_REPEAT,
                                                 MVR_WRAP_REPEAT};
    mvr_material_id wall_mat;
    CHECK(t, mvr_scene_add_material(s, &wall, &wall_mat) == MVR_OK);
    const double rot[4] = {0.70710678118654752, 0, 0, 0.70710678118654752}; /* +Y to +Z */
    demo_mesh m;
    memset(&m, 0, sizeof m);
    demo_plane(&m, 2.0f, 2.0f, 1.0f);
    mvr_mesh_id mesh = {0};
    CHECK(t, demo_mesh_add(s, &m, wall_mat, false, "wall", &mesh) == MVR_OK);
    demo_mesh_free(&m);
    mvr_node_desc nd = {.mesh = mesh, .translation = {0, 0, -2}};
    memcpy(nd.rotation, rot, sizeof rot);
    mvr_node_id n;
    CHECK(t, mvr_scene_add_node(s, &nd, &n) == MVR_OK);
    if (g->present) {
        mvr_material_desc md = mvr_material_defaults();
        md.metallic_factor = 0.0f;
        md.roughness_factor = g->roughness;
        md.transmission.factor = g->transmission;
        md.volume.thickness_factor = g->thickness;
        md.volume.attenuation_distance = g->attenuation_distance;
        memcpy(md.volume.attenuation_color, g->attenuation_color, sizeof md.volume.attenuation_color);
        md.ior = g->ior;
        md.dispersion = g->dispersion;
        if (g->texture)
            md.transmission.texture.image = img;
        mvr_material_id gm;
        CHECK(t, mvr_scene_add_material(s, &md, &gm) == MVR_OK);
        memset(&m, 0, sizeof m);
        demo_plane(&m, 1.0f, 1.0f, 1.0f);
        CHECK(t, demo_mesh_add(s, &m, gm, false, "glass", &mesh) == MVR_OK);
        demo_mesh_free(&m);
        mvr_node_desc gd = {.mesh = mesh};
        memcpy(gd.rotation, rot, sizeof rot);
        CHECK(t, mvr_scene_add_node(s, &gd, &n) == MVR_OK);
    }
    if (light) {
        mvr_light_desc ld = {.type = MVR_LIGHT_POINT, .color = {1, 0.9f, 0.8f}, .intensity = 8.0f};
        mvr_light_id lid;
        CHECK(t, mvr_scene_add_light(s, &ld, &lid) == MVR_OK);
        mvr_node_desc ln = {.light = lid, .translation = {0.5, 0.8, -1.0}};
        CHECK(t, mvr_scene_add_node(s, &ln, &n) == MVR_OK);
    }
    return s;
}

static mvr_view_set *views(mvr_test_state *t, uint32_t n)
{
    mvr_view_desc v[3];
    memset(v, 0, sizeof v);
    for (uint32_t i = 0; i < n; ++i) {
        double eye[3] = {0.25 * i, 0.1 * i, 2.5}, at[3] = {0, 0, 0}, up[3] = {0, 1, 0};
        mvr_view_look_at(&v[i], eye, at, up);
        v[i].projection.yfov = 0.9;
    }
    mvr_view_set_desc vd = {.view_count = n, .views = v};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_create(&vd, &vs, NULL) == MVR_OK);
    return vs;
}

typedef struct result {
    uint8_t *px;
    mvr_frame_stats stats;
    uint32_t features;
} result;

static result render(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, mvr_view_set *vs, mvr_view_path path,
                     mvr_material_path mpath, bool environment)
{
    render_views_opts o = {.width = W, .height = H, .path = path, .material_path = mpath, .environment = environment,
                           .environment_source = MVR_ENVIRONMENT_NEUTRAL, .clear = {0, 0, 0, 1}};
    render_views_out r = render_views(t, ctx, s, vs, &o);
    return (result){r.pixels, r.stats, r.features};
}

static double to_linear(uint8_t c)
{
    double x = c / 255.0;
    return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4);
}

static void fill_stripes(void)
{
    for (int y = 0; y < TW; ++y)
        for (int x = 0; x < TW; ++x) {
            uint8_t *p = &stripes[(y * TW + x) * 4];
            bool a = (x / 4) % 2 == 0;
            p[0] = a ? 230 : 40;
            p[1] = a ? 180 : 90;
            p[2] = a ? 60 : 200;
            p[3] = 255;
        }
}

/* Pixels where a and b differ by more than tol/255 in any channel. */
static uint32_t differing(const uint8_t *a, const uint8_t *b, size_t pixels, int tol)
{
    return count_diff(a, b, pixels, tol);
}

static void thin_glass_is_invisible(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    fill_stripes();
    mvr_view_set *vs = views(t, 1);
    glass none = {0};
    glass clear = {.present = true, .transmission = 1.0f, .ior = 1.5f};
    glass half = clear;
    half.transmission = 0.5f;
    glass tinted = {.present = true, .transmission = 1.0f, .ior = 1.0f, .thickness = 1.0f,
                    .attenuation_distance = 1.0f, .attenuation_color = {0.25f, 1.0f, 1.0f}};
    mvr_scene *s0 = make_scene(t, &none, false), *s1 = make_scene(t, &clear, false),
              *s2 = make_scene(t, &half, false), *s3 = make_scene(t, &tinted, false);
    result r0 = render(t, ctx, s0, vs, MVR_VIEW_PATH_LOOP, MVR_MATERIAL_PATH_AUTO, false);
    result r1 = render(t, ctx, s1, vs, MVR_VIEW_PATH_LOOP, MVR_MATERIAL_PATH_AUTO, false);
    result r2 = render(t, ctx, s2, vs, MVR_VIEW_PATH_LOOP, MVR_MATERIAL_PATH_AUTO, false);
    result r3 = render(t, ctx, s3, vs, MVR_VIEW_PATH_LOOP, MVR_MATERIAL_PATH_AUTO, false);
    CHECK(t, !(r0.features & MVR_FEATURE_TRANSMISSION) && r0.stats.transmission_copies == 0);
    CHECK(t, (r1.features & MVR_FEATURE_TRANSMISSION) && r1.stats.transmission_copies == 1);
    /* one sRGB8 layer of the loop path's one-view chunk, its mips a third more */
    CHECK_EQ_INT(t, r1.stats.transmission_bytes, (uint64_t)W * H * 4 * 4 / 3);
    CHECK_EQ_INT(t, r0.stats.transmission_bytes, 0);
    if (r0.px && r1.px && r2.px && r3.px) {
        uint32_t d = differing(r0.px, r1.px, (size_t)W * H, 1);
        printf("  thin glass: %u of %u pixels differ from the wall alone by more than 1/255\n", d, W * H);
        CHECK_EQ_INT(t, d, 0);
        /* the glass covers the centre: half the light there, a quarter of the red */
        uint32_t checked = 0, bad_half = 0, bad_tint = 0;
        for (size_t y = H / 2 - 8; y < H / 2 + 8; ++y)
            for (size_t x = W / 2 - 8; x < W / 2 + 8; ++x) {
                size_t i = (y * W + x) * 4;
                for (size_t c = 0; c < 3; ++c) {
                    double wall = to_linear(r0.px[i + c]);
                    double halfv = to_linear(r2.px[i + c]), tint = to_linear(r3.px[i + c]);
                    double expect_tint = c == 0 ? 0.25 * wall : wall;
                    /* one step of 8-bit sRGB near the value */
                    double step = 0.004 + 0.02 * wall;
                    bad_half += fabs(halfv - 0.5 * wall) > step;
                    bad_tint += fabs(tint - expect_tint) > step;
                }
                checked++;
            }
        printf("  transmission 0.5: %u, volume tint: %u channel(s) off of %u pixels\n", bad_half, bad_tint, checked);
        CHECK_EQ_INT(t, bad_half, 0);
        CHECK(t, bad_tint <= checked * 3 / 50); /* stripe edges: the refracted sample may land a texel over */
    }
    free(r0.px);
    free(r1.px);
    free(r2.px);
    free(r3.px);
    mvr_scene_destroy(s0);
    mvr_scene_destroy(s1);
    mvr_scene_destroy(s2);
    mvr_scene_destroy(s3);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

static void paths_agree(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    fill_stripes();
    mvr_view_set *vs = views(t, 3);
    glass g = {.present = true, .transmission = 0.9f, .roughness = 0.3f, .ior = 1.45f, .thickness = 0.4f,
               .dispersion = 2.0f, .attenuation_distance = 2.0f, .attenuation_color = {0.9f, 0.6f, 0.5f},
               .texture = true};
    mvr_scene *s = make_scene(t, &g, true);
    const mvr_view_path paths[2] = {MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_MULTIVIEW};
    const mvr_material_path mpaths[2] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL};
    result ref = {0};
    for (int p = 0; p < 2; ++p) {
        if (paths[p] == MVR_VIEW_PATH_MULTIVIEW && !mvr_context_caps(ctx)->ext.ovr_multiview2)
            continue;
        for (int m = 0; m < 2; ++m) {
            result o = render(t, ctx, s, vs, paths[p], mpaths[m], true);
            CHECK(t, (o.features & MVR_FEATURE_TRANSMISSION) && o.stats.transmission_copies == 3);
            if (!ref.px) {
                ref = o;
                continue;
            }
            if (o.px)
                CHECK_MSG(t, differing(ref.px, o.px, (size_t)3 * W * H, 0) == 0, "%s / %s differs",
                          mvr_view_path_name(paths[p]), m ? "per-material" : "arrays");
            free(o.px);
        }
    }
    /* the glass changes what the wall shows (so the comparison means something) */
    glass none = {0};
    mvr_scene *bare = make_scene(t, &none, true);
    result b = render(t, ctx, bare, vs, MVR_VIEW_PATH_LOOP, MVR_MATERIAL_PATH_AUTO, true);
    if (b.px && ref.px)
        CHECK(t, differing(b.px, ref.px, (size_t)3 * W * H, 2) > 100);
    free(b.px);
    free(ref.px);
    mvr_scene_destroy(bare);
    mvr_scene_destroy(s);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(thin_glass_is_invisible), TEST(paths_agree))
