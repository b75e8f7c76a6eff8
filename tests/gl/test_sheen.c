/* gl: KHR_materials_sheen.
 * - no SHEEN bit (no sheen code) for a sheen-less material or any demo; a
 *   black sheen color is no sheen; overrides.disable_features = SHEEN draws
 *   the sheen material as the bare one (same bytes, no SHEEN program);
 * - the formulas, on the face of a box seen head-on (n = v = +z at the
 *   centre pixel of an odd-sized float target): under one directional light
 *   at 60 degrees, the centre is the bare material's pixel times the albedo
 *   scaling min(1 - max(c) E(n.v), 1 - max(c) E(n.l)) plus the light times
 *   c D_Charlie(n.h) V_sheen (n.l), evaluated here in double
 *   (core/sheen_lut.c's functions; E read from the same table the GPU
 *   samples, bilinearly, as it does); under a uniform environment of
 *   radiance 1, the bare pixel times 1 - max(c) E(1) plus c times the
 *   table's split-sum factor (the Charlie prefilter of a uniform
 *   environment is 1). Tolerance 2e-3 absolute (half-float table and maps);
 * - the sheen color and roughness textures change pixels as their texels
 *   say (black color texels give the bare material's pixels, white ones the
 *   factor's; roughness A = 255 gives the factor's pixels, A = 0 others);
 * - multiview and loop, texture arrays and per-material textures: the same
 *   bytes;
 * - the environment's Charlie chain is prefiltered only for a frame with
 *   sheen, once per environment (the prefilter's pass counts).
 * The comparison with the Khronos glTF Sample Renderer is io_peers' (the
 * sheen.gltf asset, Blender's export). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "demo_builder.h"
#include "environment.h"
#include "material.h"
#include "gl_test_util.h"
#include "mvr/mvr.h"
#include "shader_gen.h"
#include "skin_render.h"

#define W 65
#define PI 3.14159265358979323846
#define H 65

typedef struct view_shot {
    bool environment;            /* a uniform environment of radiance 1 */
    bool light;                  /* one directional light, intensity 2, towards l = (sin 60, 0, cos 60) */
    bool box;                    /* the box's face (else a sphere) */
} view_shot;

static mvr_scene *scene_of(mvr_test_state *t, const mvr_material_desc *md, const mvr_image_desc *images,
                           uint32_t image_count, view_shot sh)
{
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    for (uint32_t i = 0; i < image_count; ++i) {
        mvr_image_id id;
        CHECK(t, mvr_scene_add_image(s, &images[i], &id) == MVR_OK);
    }
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, md, &mat) == MVR_OK);
    /* a second material sharing the program, without textures */
    mvr_material_desc plain = *md;
    memset(&plain.sheen.color_texture, 0, sizeof plain.sheen.color_texture);
    memset(&plain.sheen.roughness_texture, 0, sizeof plain.sheen.roughness_texture);
    mvr_material_id other;
    CHECK(t, mvr_scene_add_material(s, &plain, &other) == MVR_OK);
    demo_mesh m;
    memset(&m, 0, sizeof m);
    if (sh.box)
        demo_box(&m, 3.0f, 3.0f, 0.1f, 1.0f);
    else
        demo_sphere(&m, 1.0f, 48, 24);
    mvr_mesh_id mesh = {0};
    CHECK(t, demo_mesh_add(s, &m, mat, false, "shape", &mesh) == MVR_OK);
    demo_mesh_free(&m);
    mvr_node_desc nd = {.mesh = mesh};
    mvr_node_id n;
    CHECK(t, mvr_scene_add_node(s, &nd, &n) == MVR_OK);
    if (sh.light) {
        mvr_light_desc ld = {.type = MVR_LIGHT_DIRECTIONAL, .color = {1, 1, 1}, .intensity = 2.0f};
        mvr_light_id lid;
        CHECK(t, mvr_scene_add_light(s, &ld, &lid) == MVR_OK);
        /* -Z turned 60 degrees about +Y: the light travels along -(sin 60, 0, cos 60) */
        mvr_node_desc ln = {.light = lid, .rotation = {0.0, sin(PI / 6.0), 0.0, cos(PI / 6.0)}};
        CHECK(t, mvr_scene_add_node(s, &ln, &n) == MVR_OK);
    }
    return s;
}

static mvr_view_set *front_views(mvr_test_state *t, uint32_t n)
{
    mvr_view_desc v[2];
    memset(v, 0, sizeof v);
    for (uint32_t i = 0; i < n; ++i) {
        double eye[3] = {0.3 * i, 0, 3.2}, at[3] = {0.3 * i, 0, 0}, up[3] = {0, 1, 0};
        if (i == 0)
            at[0] = 0.0;
        mvr_view_look_at(&v[i], eye, at, up);
        v[i].projection.yfov = 0.8;
    }
    mvr_view_set_desc vd = {.view_count = n, .views = v};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_create(&vd, &vs, NULL) == MVR_OK);
    return vs;
}

typedef struct pass_opts {
    mvr_view_path path;
    mvr_material_path material_path;
    uint32_t disable;
    bool f32;
    bool environment;
} pass_opts;

/* The layers' floats (RGBA32F) or bytes; *features: the mesh programs' bits. */
static void *render(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, mvr_view_set *vs, pass_opts o,
                    uint32_t *features)
{
    uint32_t n = mvr_view_set_count(vs);
    mvr_renderer_desc rd = {.context = ctx, .view_path = o.path, .material_path = o.material_path,
                            .overrides = {.disable_features = o.disable}};
    mvr_renderer *r = NULL;
    mvr_target *tg = NULL;
    mvr_environment *env = NULL;
    mvr_environment_desc ed = {.source = MVR_ENVIRONMENT_UNIFORM};
    mvr_target_desc td = {.width = W, .height = H, .layers = n, .anti_aliasing = MVR_ANTI_ALIASING_NONE,
                          .color_format = o.f32 ? MVR_COLOR_FORMAT_RGBA32F : MVR_COLOR_FORMAT_DEFAULT};
    bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK &&
              (!o.environment || mvr_environment_create(&ed, &env, NULL) == MVR_OK);
    CHECK(t, ok);
    mvr_render_desc desc = {.exposure = 1.0f, .environment = env};
    ok = ok && mvr_renderer_render(r, s, vs, tg, &desc) == MVR_OK;
    CHECK_MSG(t, ok, "render: %s", r ? mvr_renderer_last_error(r) : "");
    size_t layer = (size_t)W * H * 4 * (o.f32 ? sizeof(float) : 1);
    uint8_t *out = ok ? malloc(layer * n) : NULL;
    for (uint32_t k = 0; out && k < n; ++k)
        CHECK(t, mvr_renderer_read_layer(r, tg, k, o.f32 ? MVR_READBACK_RGBA32F : MVR_READBACK_RGBA8,
                                         out + k * layer, layer) == MVR_OK);
    if (features) {
        *features = 0;
        for (uint32_t i = 0; r && i < mvr_renderer_program_count(r); ++i) {
            mvr_program_info info;
            if (mvr_renderer_get_program_info(r, i, &info) && info.mesh)
                *features |= info.features;
        }
    }
    mvr_environment_destroy(env);
    mvr_target_destroy(tg);
    mvr_renderer_destroy(r);
    return out;
}

static mvr_material_desc bare_material(void)
{
    mvr_material_desc m = mvr_material_defaults();
    m.base_color_factor[0] = 0.2f;
    m.base_color_factor[1] = 0.3f;
    m.base_color_factor[2] = 0.6f;
    m.metallic_factor = 0.0f;
    m.roughness_factor = 0.6f;
    return m;
}

static mvr_material_desc sheen_material(void)
{
    mvr_material_desc m = bare_material();
    m.sheen.color_factor[0] = 0.9f;
    m.sheen.color_factor[1] = 0.5f;
    m.sheen.color_factor[2] = 0.2f;
    m.sheen.roughness_factor = 0.5f;
    return m;
}

static void no_sheen_no_code(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    for (uint32_t d = 0; mvr_demo_name(d); ++d) {
        mvr_scene *s = NULL;
        mvr_view_set *vs = NULL;
        mvr_demo_desc dd = {2, W, H, {0}};
        CHECK(t, mvr_demo_create(mvr_demo_name(d), &dd, &s, &vs, NULL) == MVR_OK);
        uint32_t features = 0;
        free(render(t, ctx, s, vs, (pass_opts){.environment = true}, &features));
        CHECK_MSG(t, !(features & MVR_FEATURE_SHEEN), "%s: features %x", mvr_demo_name(d), features);
        mvr_view_set_destroy(vs);
        mvr_scene_destroy(s);
    }
    mvr_material_desc bare = bare_material(), black = bare, sheen = sheen_material();
    black.sheen.roughness_factor = 0.7f; /* roughness alone: no sheen */
    CHECK(t, !(mvr_material_extension_features(&bare) & MVR_FEATURE_SHEEN));
    CHECK(t, !(mvr_material_extension_features(&black) & MVR_FEATURE_SHEEN));
    CHECK(t, (mvr_material_extension_features(&sheen) & MVR_FEATURE_SHEEN) != 0);
    CHECK(t, strcmp(mvr_program_feature_name(MVR_FEATURE_SHEEN), "SHEEN") == 0);

    /* disabled: the sheen material as the bare one, with no sheen program */
    mvr_view_set *vs = front_views(t, 1);
    view_shot sh = {.environment = true, .light = true};
    mvr_scene *a = scene_of(t, &bare, NULL, 0, sh), *b = scene_of(t, &sheen, NULL, 0, sh);
    uint32_t fa = 0, fb = 0, fs = 0;
    uint8_t *pa = render(t, ctx, a, vs, (pass_opts){.path = MVR_VIEW_PATH_LOOP, .environment = true}, &fa);
    uint8_t *pb = render(t, ctx, b, vs,
                         (pass_opts){.path = MVR_VIEW_PATH_LOOP, .environment = true, .disable = MVR_FEATURE_SHEEN},
                         &fb);
    uint8_t *ps = render(t, ctx, b, vs, (pass_opts){.path = MVR_VIEW_PATH_LOOP, .environment = true}, &fs);
    CHECK(t, !(fa & MVR_FEATURE_SHEEN) && !(fb & MVR_FEATURE_SHEEN) && (fs & MVR_FEATURE_SHEEN));
    if (pa && pb && ps) {
        CHECK_EQ_INT(t, count_diff(pa, pb, (size_t)W * H, 0), 0);
        uint32_t d = count_diff(pa, ps, (size_t)W * H, 2);
        printf("  sheen changes %u pixels by more than 2/255\n", d);
        CHECK(t, d > 500);
    }
    free(pa);
    free(pb);
    free(ps);
    mvr_scene_destroy(a);
    mvr_scene_destroy(b);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

/* The GPU's table read: bilinear between texel centres, clamped at the edges. */
static double table_at(const float *lut, uint32_t size, double x, double y, uint32_t channel)
{
    double fx = x * size - 0.5, fy = y * size - 0.5;
    fx = fx < 0 ? 0 : fx > size - 1 ? size - 1 : fx;
    fy = fy < 0 ? 0 : fy > size - 1 ? size - 1 : fy;
    uint32_t x0 = (uint32_t)fx, y0 = (uint32_t)fy;
    uint32_t x1 = x0 + 1 < size ? x0 + 1 : x0, y1 = y0 + 1 < size ? y0 + 1 : y0;
    double ax = fx - x0, ay = fy - y0;
#define AT(i, j) ((double)lut[((size_t)(j) * size + (i)) * 2u + channel])
    return (AT(x0, y0) * (1 - ax) + AT(x1, y0) * ax) * (1 - ay) + (AT(x0, y1) * (1 - ax) + AT(x1, y1) * ax) * ay;
#undef AT
}

static void centre_pixel_matches_the_formulas(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    enum { LUT = 32 };
    static float lut[LUT * LUT * 2];
    CHECK(t, mvr_sheen_lut(LUT, lut));
    mvr_view_set *vs = front_views(t, 1);
    mvr_material_desc bare = bare_material(), sheen = sheen_material();
    const double c[3] = {0.9, 0.5, 0.2}, cmax = 0.9, rough = 0.5;
    size_t centre = ((size_t)(H / 2) * W + W / 2) * 4u;
    for (int k = 0; k < 2; ++k) {
        bool light = k == 0;
        view_shot sh = {.environment = !light, .light = light, .box = true};
        mvr_scene *a = scene_of(t, &bare, NULL, 0, sh), *b = scene_of(t, &sheen, NULL, 0, sh);
        pass_opts o = {.path = MVR_VIEW_PATH_LOOP, .f32 = true, .environment = !light};
        float *pa = render(t, ctx, a, vs, o, NULL), *pb = render(t, ctx, b, vs, o, NULL);
        if (pa && pb) {
            double scale, sheen_term;
            if (light) {
                /* n = v = +z, l = (sin 60, 0, cos 60), h = (l + v) / |l + v| */
                double nl = 0.5, nv = 1.0, hx = sin(PI / 3.0), hz = 1.0 + cos(PI / 3.0);
                double nh = hz / sqrt(hx * hx + hz * hz);
                scale = fmin(1.0 - cmax * table_at(lut, LUT, nv, rough, 0), 1.0 - cmax * table_at(lut, LUT, nl, rough, 0));
                sheen_term = 2.0 * mvr_sheen_d_charlie(rough, nh) * mvr_sheen_visibility(rough, nl, nv) * nl;
            } else {
                scale = 1.0 - cmax * table_at(lut, LUT, 1.0, rough, 0);
                sheen_term = table_at(lut, LUT, 1.0, rough, 1);
            }
            for (int ch = 0; ch < 3; ++ch) { /* RGB */
                double expect = pa[centre + (size_t)ch] * scale + c[ch] * sheen_term;
                printf("  %s, channel %d: %.5f, expected %.5f (bare %.5f, scale %.4f, sheen %.5f)\n",
                       light ? "light" : "uniform environment", ch, pb[centre + (size_t)ch], expect, pa[centre + (size_t)ch], scale,
                       c[ch] * sheen_term);
                CHECK_MSG(t, fabs(pb[centre + (size_t)ch] - expect) < 2e-3, "channel %d: %g, expected %g", ch,
                          pb[centre + (size_t)ch], expect);
            }
            CHECK(t, c[0] * sheen_term > 0.01); /* the check has something to check */
        }
        free(pa);
        free(pb);
        mvr_scene_destroy(a);
        mvr_scene_destroy(b);
    }
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

static void textures_and_paths(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    enum { TW = 16, TH = 16 };
    /* half: left white, right black (RGB and A) */
    static uint8_t half[TW * TH * 4];
    for (int y = 0; y < TH; ++y)
        for (int x = 0; x < TW; ++x) {
            uint8_t *p = &half[(y * TW + x) * 4];
            p[0] = p[1] = p[2] = p[3] = x < TW / 2 ? 255 : 0;
        }
    mvr_image_desc images[1] = {{.width = TW, .height = TH, .rgba8 = half, .name = "half"}};
    mvr_sampler_desc nearest = {MVR_FILTER_NEAREST, MVR_FILTER_NEAREST, MVR_WRAP_REPEAT, MVR_WRAP_REPEAT};
    mvr_view_set *vs = front_views(t, 1);
    view_shot sh = {.environment = true, .light = true};
    pass_opts o = {.path = MVR_VIEW_PATH_LOOP, .environment = true};
    mvr_material_desc bare = bare_material(), full = sheen_material();
    mvr_material_desc colored = full, roughed = full;
    colored.sheen.color_texture.image.id = 1;
    colored.sheen.color_texture.sampler = nearest;
    roughed.sheen.roughness_texture.image.id = 1;
    roughed.sheen.roughness_texture.sampler = nearest;
    mvr_scene *scenes[4] = {scene_of(t, &bare, images, 1, sh), scene_of(t, &full, images, 1, sh),
                            scene_of(t, &colored, images, 1, sh), scene_of(t, &roughed, images, 1, sh)};
    uint8_t *px[4];
    for (int k = 0; k < 4; ++k)
        px[k] = render(t, ctx, scenes[k], vs, o, NULL);
    if (px[0] && px[1] && px[2] && px[3]) {
        /* color: each pixel the bare's or the full sheen's */
        uint32_t as_bare = 0, as_full = 0, neither = 0, differ = 0;
        /* roughness: A = 255 -> the factor's pixels; A = 0 -> others */
        uint32_t r_same = 0, r_other = 0;
        for (size_t i = 0; i < (size_t)W * H; ++i) {
            bool b = count_diff(px[2] + i * 4, px[0] + i * 4, 1, 1) == 0;
            bool f = count_diff(px[2] + i * 4, px[1] + i * 4, 1, 1) == 0;
            bool d = count_diff(px[0] + i * 4, px[1] + i * 4, 1, 1) != 0;
            differ += d;
            as_bare += d && b && !f;
            as_full += d && f && !b;
            neither += !b && !f;
            bool rs = count_diff(px[3] + i * 4, px[1] + i * 4, 1, 1) == 0;
            r_same += d && rs;
            r_other += !rs;
        }
        printf("  sheen color texture: %u pixels as the bare material, %u as the full sheen, %u neither (%u "
               "differ)\n  sheen roughness texture: %u as the factor's, %u not\n",
               as_bare, as_full, neither, differ, r_same, r_other);
        CHECK_EQ_INT(t, neither, 0);
        CHECK(t, as_bare > differ / 4 && as_full > differ / 4);
        CHECK(t, r_same > differ / 4 && r_other > differ / 4);
    }
    for (int k = 0; k < 4; ++k) {
        free(px[k]);
        mvr_scene_destroy(scenes[k]);
    }

    /* both textures (one with a transform), two views: every path the same bytes */
    mvr_material_desc both = full;
    both.sheen.color_texture.image.id = 1;
    both.sheen.roughness_texture.image.id = 1;
    both.sheen.roughness_texture.transform = (mvr_texture_transform){true, {0.25f, 0.0f}, 0.3f, {2.0f, 2.0f}};
    mvr_scene *s = scene_of(t, &both, images, 1, sh);
    mvr_view_set *two = front_views(t, 2);
    const mvr_view_path paths[2] = {MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_MULTIVIEW};
    const mvr_material_path mpaths[2] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL};
    uint8_t *ref = NULL;
    int compared = 0;
    for (int p = 0; p < 2; ++p) {
        if (paths[p] == MVR_VIEW_PATH_MULTIVIEW && !mvr_context_caps(ctx)->ext.ovr_multiview2)
            continue;
        for (int m = 0; m < 2; ++m) {
            uint32_t feat = 0;
            uint8_t *out = render(t, ctx, s, two,
                                  (pass_opts){.path = paths[p], .material_path = mpaths[m], .environment = true}, &feat);
            CHECK(t, (feat & MVR_FEATURE_SHEEN) && (feat & MVR_FEATURE_TEXTURE_TRANSFORM));
            if (!ref) {
                ref = out;
            } else {
                if (out) {
                    CHECK_MSG(t, count_diff(ref, out, (size_t)2 * W * H, 0) == 0, "path %d / %d differs", p, m);
                    compared++;
                }
                free(out);
            }
        }
    }
    printf("  %d path combinations compared with the loop + arrays render\n", compared);
    CHECK(t, compared >= 1);
    free(ref);
    mvr_view_set_destroy(two);
    mvr_scene_destroy(s);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

/* The Charlie chain is built only for a frame that draws sheen, once per
 * environment: a sheen-less frame prefilters the source and the GGX chain
 * (A passes); a sheen frame after it with the same environment only the
 * Charlie chain (B, 0 < B < A); the next sheen frame nothing; a fresh
 * renderer's first sheen frame A + B. */
static void charlie_chain_only_for_sheen(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_view_set *vs = front_views(t, 1);
    mvr_material_desc bare = bare_material(), sheen = sheen_material();
    view_shot sh = {.environment = true};
    mvr_scene *a = scene_of(t, &bare, NULL, 0, sh), *b = scene_of(t, &sheen, NULL, 0, sh);
    mvr_environment *env = NULL;
    mvr_environment_desc ed = {.source = MVR_ENVIRONMENT_UNIFORM};
    CHECK(t, mvr_environment_create(&ed, &env, NULL) == MVR_OK);
    uint32_t passes[4] = {0, 0, 0, 0};
    for (int k = 0; k < 2 && env; ++k) {
        mvr_renderer_desc rd = {.context = ctx, .view_path = MVR_VIEW_PATH_LOOP};
        mvr_renderer *r = NULL;
        mvr_target *tg = NULL;
        mvr_target_desc td = {.width = W, .height = H, .layers = 1, .anti_aliasing = MVR_ANTI_ALIASING_NONE};
        bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK;
        CHECK(t, ok);
        mvr_scene *order[2][3] = {{a, b, b}, {b, NULL, NULL}};
        for (int f = 0; ok && f < 3 && order[k][f]; ++f) {
            mvr_render_desc desc = {.exposure = 1.0f, .environment = env};
            ok = mvr_renderer_render(r, order[k][f], vs, tg, &desc) == MVR_OK;
            CHECK_MSG(t, ok, "render: %s", mvr_renderer_last_error(r));
            mvr_frame_stats st;
            mvr_renderer_get_stats(r, &st);
            passes[k == 0 ? f : 3] = st.env_prefilter_passes;
        }
        mvr_target_destroy(tg);
        mvr_renderer_destroy(r);
    }
    printf("  prefilter passes: sheen-less %u, then sheen %u, then %u; sheen first %u\n", passes[0], passes[1],
           passes[2], passes[3]);
    CHECK(t, passes[0] > 0 && passes[1] > 0 && passes[1] < passes[0] && passes[2] == 0);
    CHECK_EQ_INT(t, passes[3], passes[0] + passes[1]);
    mvr_environment_destroy(env);
    mvr_scene_destroy(a);
    mvr_scene_destroy(b);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(no_sheen_no_code), TEST(centre_pixel_matches_the_formulas), TEST(textures_and_paths),
              TEST(charlie_chain_only_for_sheen))
