/* gl: the HDR frame's post pass. Auto-exposure puts a 100,000 lux sun in a
 * sane band; the multiview post pass and the loop's give the same bytes on
 * every demo (one pass for 6 views); each tone mapper matches its formula
 * (a CPU reference here, written from the published curves). */
#include <math.h>

#include "stress/stress_util.h"

static double srgb_decode(double e)
{
    return e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4);
}

static double srgb_encode_d(double c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return c <= 0.0031308 ? c * 12.92 : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

/* A grey floor with boxes under a 100,000 lux sun (noon in summer). */
static mvr_scene *sunny_scene(mvr_test_state *t)
{
    mvr_scene *s = stress_scene();
    mvr_material_desc m = mvr_material_defaults();
    m.metallic_factor = 0.0f;
    m.roughness_factor = 0.7f;
    m.base_color_factor[0] = m.base_color_factor[1] = m.base_color_factor[2] = 0.5f;
    mvr_material_id grey;
    CHECK(t, mvr_scene_add_material(s, &m, &grey) == MVR_OK);
    m.base_color_factor[0] = 0.7f, m.base_color_factor[1] = 0.2f, m.base_color_factor[2] = 0.1f;
    mvr_material_id red;
    CHECK(t, mvr_scene_add_material(s, &m, &red) == MVR_OK);
    const double h = 0.70710678118654752;
    mvr_node_desc floor = {.mesh = stress_add_quad(t, s, grey), .rotation = {-h, 0, 0, h}, .scale = {10, 10, 10}};
    mvr_node_id id;
    CHECK(t, mvr_scene_add_node(s, &floor, &id) == MVR_OK);
    mvr_mesh_id box = stress_add_box(t, s, 0.5f, red);
    for (int i = 0; i < 5; ++i)
        stress_node(t, s, box, -3.0 + 1.5 * i, 0.5, -1.0 - (i % 2), 1.0);
    double a = -0.9; /* the sun high, from the front */
    mvr_light_desc sun = {.type = MVR_LIGHT_DIRECTIONAL, .intensity = 100000.0f};
    mvr_light_id lid;
    CHECK(t, mvr_scene_add_light(s, &sun, &lid) == MVR_OK);
    mvr_node_desc sn = {.light = lid, .rotation = {sin(a / 2), 0, 0, cos(a / 2)}};
    CHECK(t, mvr_scene_add_node(s, &sn, &id) == MVR_OK);
    /* skylight: a fifth of the sun's illuminance, as radiance (E / pi) */
    float sky[3] = {20000.0f / 3.14159265f * 0.6f, 20000.0f / 3.14159265f * 0.7f, 20000.0f / 3.14159265f};
    mvr_scene_set_ambient(s, sky);
    return s;
}

static uint8_t *render_desc(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, const mvr_view_set *vs,
                            mvr_view_path path, mvr_color_format format, uint32_t w, uint32_t h,
                            const mvr_render_desc *rd, mvr_frame_stats *st)
{
    stress_options o = {.path = path, .format = format, .width = w, .height = h, .render = rd};
    return stress_render(t, ctx, s, vs, &o, st);
}

static void auto_exposure_tames_the_sun(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = sunny_scene(t);
    const double eye[3] = {0, 2.5, 6}, target[3] = {0, 0.3, -1};
    mvr_projection proj = {.yfov = 0.9, .znear = 0.1};
    mvr_view_desc v[2] = {stress_view(eye, target, proj), stress_view(eye, target, proj)};
    v[1].position[0] += 0.064;
    mvr_view_set *vs = stress_view_set(t, v, 2, NULL);
    const uint32_t W = 96, H = 64;
    /* the clear color is a display colour (never exposed): a pale blue sky */
    mvr_render_desc linear = {.clear_color = {0.3f, 0.45f, 0.8f, 1}};
    mvr_render_desc autod = {.clear_color = {0.3f, 0.45f, 0.8f, 1}, .exposure_mode = MVR_EXPOSURE_AUTO,
                             .tone_map = MVR_TONE_MAP_KHR_PBR_NEUTRAL};
    mvr_frame_stats st_lin, st_auto;
    uint8_t *white = render_desc(t, ctx, s, vs, MVR_VIEW_PATH_AUTO, MVR_COLOR_FORMAT_DEFAULT, W, H, &linear, &st_lin);
    uint8_t *img = render_desc(t, ctx, s, vs, MVR_VIEW_PATH_AUTO, MVR_COLOR_FORMAT_DEFAULT, W, H, &autod, &st_auto);
    if (white && img) {
        for (int k = 0; k < 2; ++k) {
            const uint8_t *im = k ? img : white;
            double sum = 0;
            size_t clipped = 0, n = (size_t)W * H * 2;
            for (size_t i = 0; i < n; ++i) {
                const uint8_t *p = im + i * 4;
                double y = 0.2126 * srgb_decode(p[0] / 255.0) + 0.7152 * srgb_decode(p[1] / 255.0) +
                           0.0722 * srgb_decode(p[2] / 255.0);
                sum += y;
                clipped += p[0] >= 254 || p[1] >= 254 || p[2] >= 254;
            }
            double mean = sum / n, clip = (double)clipped / n;
            printf("  %s: mean luminance %.3f, %.1f%% clipped, EV100 %.2f\n", k ? "auto" : "exposure 1", mean,
                   100.0 * clip, k ? st_auto.exposure_ev100 : st_lin.exposure_ev100);
            if (k) {
                CHECK_MSG(t, mean >= 0.1 && mean <= 0.6, "auto-exposed mean luminance %.3f", mean);
                CHECK_MSG(t, clip <= 0.03, "auto-exposed: %.1f%% clipped", 100.0 * clip);
                /* about sunny 16: EV100 15 for sunlit scenes */
                CHECK_MSG(t, st_auto.exposure_ev100 > 12.0 && st_auto.exposure_ev100 < 18.0, "EV100 %.2f",
                          st_auto.exposure_ev100);
                CHECK_EQ_INT(t, st_auto.exposure_mode, MVR_EXPOSURE_AUTO);
                CHECK_EQ_INT(t, st_auto.tone_mapper, MVR_TONE_MAP_KHR_PBR_NEUTRAL);
                CHECK_EQ_INT(t, st_auto.luminance_passes, st_auto.passes);
            } else {
                CHECK_MSG(t, clip > 0.5, "exposure 1 should blow the sun out: %.1f%% clipped", 100.0 * clip);
                CHECK_EQ_INT(t, st_lin.post_passes, 0); /* the default: no HDR frame */
            }
        }
        /* shared exposure: the two eyes agree (nearly the same picture) */
        size_t layer = (size_t)W * H * 4;
        double d = 0;
        for (size_t i = 0; i < layer; ++i)
            d += fabs((double)img[i] - img[layer + i]);
        CHECK_MSG(t, d / layer < 6.0, "the eyes differ by %.2f on average", d / layer);
    }
    free(white);
    free(img);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

static void post_pass_is_the_same_on_both_paths(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const uint32_t W = 64, H = 48;
    const mvr_render_desc descs[3] = {
        {.clear_color = {0.02f, 0.02f, 0.03f, 1}, .exposure_mode = MVR_EXPOSURE_AUTO, .tone_map = MVR_TONE_MAP_ACES},
        {.clear_color = {0.02f, 0.02f, 0.03f, 1}, .exposure_mode = MVR_EXPOSURE_AUTO, .exposure_per_view = true,
         .tone_map = MVR_TONE_MAP_KHR_PBR_NEUTRAL},
        {.clear_color = {0.02f, 0.02f, 0.03f, 1}, .exposure_mode = MVR_EXPOSURE_EV100, .ev100 = -1.0,
         .dither = true},
    };
    for (uint32_t d = 0; mvr_demo_name(d); ++d) {
        const char *demo = mvr_demo_name(d);
        uint32_t views = strcmp(demo, "cube") == 0 ? 6 : 2;
        mvr_scene *s = NULL;
        mvr_view_set *vs = NULL;
        mvr_demo_desc dd = {views, W, H, {0}};
        CHECK(t, mvr_demo_create(demo, &dd, &s, &vs, NULL) == MVR_OK);
        for (int k = 0; k < 3 && s; ++k) {
            mvr_frame_stats mv, loop;
            uint8_t *a = render_desc(t, ctx, s, vs, MVR_VIEW_PATH_MULTIVIEW, MVR_COLOR_FORMAT_DEFAULT, W, H, &descs[k], &mv);
            uint8_t *b = render_desc(t, ctx, s, vs, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_DEFAULT, W, H, &descs[k], &loop);
            if (a && b) {
                size_t bytes = (size_t)W * H * 4 * views;
                unsigned diff = max_abs_diff8(a, b, bytes);
                CHECK_MSG(t, diff == 0, "%s, post %d: multiview and loop differ by %u", demo, k, diff);
                report_image_diff("post: multiview vs loop", a, b, W, H, views);
                CHECK_EQ_INT(t, mv.post_passes, 1); /* one multiview pass, whatever N (<= 6 here) */
                CHECK_EQ_INT(t, loop.post_passes, views);
                CHECK_MSG(t, mv.exposure_ev100 == loop.exposure_ev100, "%s: EV100 %g vs %g", demo, mv.exposure_ev100,
                          loop.exposure_ev100);
                if (k == 0 && d == 0)
                    printf("  %s: EV100 %.3f, %u post pass(es) for %u views\n", demo, mv.exposure_ev100,
                           mv.post_passes, views);
            }
            free(a);
            free(b);
        }
        mvr_view_set_destroy(vs);
        mvr_scene_destroy(s);
    }
    mvr_context_destroy(ctx);
}

/* The Khronos glTF Sample Renderer's curves, in double. */
static void ref_aces(const double in[3], double out[3])
{
    static const double mi[3][3] = {{0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}};
    static const double mo[3][3] = {{1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}};
    double c[3], f[3];
    for (int i = 0; i < 3; ++i)
        c[i] = mi[i][0] * in[0] + mi[i][1] * in[1] + mi[i][2] * in[2];
    for (int i = 0; i < 3; ++i) {
        double a = c[i] * (c[i] + 0.0245786) - 0.000090537;
        double b = c[i] * (0.983729 * c[i] + 0.4329510) + 0.238081;
        f[i] = a / b;
    }
    for (int i = 0; i < 3; ++i) {
        double v = mo[i][0] * f[0] + mo[i][1] * f[1] + mo[i][2] * f[2];
        out[i] = v < 0 ? 0 : v > 1 ? 1 : v;
    }
}

static void ref_pbr_neutral(const double in[3], double out[3])
{
    const double start = 0.8 - 0.04, desat = 0.15;
    double x = fmin(in[0], fmin(in[1], in[2]));
    double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    double c[3] = {in[0] - offset, in[1] - offset, in[2] - offset};
    double peak = fmax(c[0], fmax(c[1], c[2]));
    if (peak < start) {
        memcpy(out, c, sizeof c);
        return;
    }
    double d = 1.0 - start;
    double new_peak = 1.0 - d * d / (peak + d - start);
    double g = 1.0 - 1.0 / (desat * (peak - new_peak) + 1.0);
    for (int i = 0; i < 3; ++i)
        out[i] = c[i] * (new_peak / peak) * (1.0 - g) + new_peak * g;
}

static void tone_mappers_match_their_formulas(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    /* a ramp of emissive quads (base black, no lights): the HDR value of
     * quad i is emissive_i exactly, from 0.005 to 40, log-spaced */
    enum { N = 24 };
    mvr_scene *s = stress_scene();
    double value[N][3];
    mvr_mesh_id quads[N];
    for (int i = 0; i < N; ++i) {
        double v = 0.005 * pow(8000.0, i / (double)(N - 1));
        const double tint[3] = {1.0, 0.55, 0.2};
        mvr_material_desc m = mvr_material_defaults();
        m.base_color_factor[0] = m.base_color_factor[1] = m.base_color_factor[2] = 0.0f;
        m.metallic_factor = 0.0f;
        for (int c = 0; c < 3; ++c) {
            m.emissive_factor[c] = (float)tint[c];
            value[i][c] = (float)tint[c] * (float)v;
        }
        m.emissive_strength = (float)v;
        mvr_material_id mat;
        CHECK(t, mvr_scene_add_material(s, &m, &mat) == MVR_OK);
        quads[i] = stress_add_quad(t, s, mat);
        stress_node(t, s, quads[i], -(N - 1) / 2.0 + i, 0, 0, 0.45);
    }
    mvr_view_desc v;
    memset(&v, 0, sizeof v);
    v.position[2] = 5;
    v.projection.type = MVR_PROJECTION_ORTHOGRAPHIC;
    v.projection.xmag = N / 2.0;
    v.projection.ymag = 1;
    v.projection.zfar = 10;
    mvr_view_set *vs = stress_view_set(t, &v, 1, NULL);
    const uint32_t W = N * 4, H = 8;
    const mvr_tone_map maps[3] = {MVR_TONE_MAP_NONE, MVR_TONE_MAP_ACES, MVR_TONE_MAP_KHR_PBR_NEUTRAL};
    const mvr_color_format formats[2] = {MVR_COLOR_FORMAT_DEFAULT, MVR_COLOR_FORMAT_RGBA8};
    for (int k = 0; k < 3; ++k)
        for (int f = 0; f < 2; ++f) {
            /* EV100 mode with exposure exactly 1: 1 / (1.2 * 2^ev) = 1 */
            mvr_render_desc rd = {.exposure_mode = MVR_EXPOSURE_EV100, .ev100 = -log2(1.2), .tone_map = maps[k]};
            mvr_frame_stats st;
            uint8_t *img = render_desc(t, ctx, s, vs, MVR_VIEW_PATH_AUTO, formats[f], W, H, &rd, &st);
            if (!img)
                continue;
            CHECK_EQ_INT(t, st.post_passes, 1);
            double worst = 0;
            for (int i = 0; i < N; ++i) {
                const uint8_t *p = img + ((size_t)(H / 2) * W + (size_t)(i * 4 + 2)) * 4;
                double out[3];
                if (maps[k] == MVR_TONE_MAP_ACES)
                    ref_aces(value[i], out);
                else if (maps[k] == MVR_TONE_MAP_KHR_PBR_NEUTRAL)
                    ref_pbr_neutral(value[i], out);
                else
                    memcpy(out, value[i], sizeof out);
                for (int c = 0; c < 3; ++c) {
                    double e = fabs(p[c] / 255.0 - srgb_encode_d(out[c]));
                    worst = fmax(worst, e);
                }
            }
            printf("  %-11s %-12s worst %.2f/255 over %d values\n", mvr_tone_map_name(maps[k]),
                   mvr_color_format_name(formats[f]), worst * 255.0, N);
            CHECK_MSG(t, worst <= 1.0 / 255.0 + 1e-9, "%s on %s: %.2f/255 from the reference",
                      mvr_tone_map_name(maps[k]), mvr_color_format_name(formats[f]), worst * 255.0);
            free(img);
        }
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* A clear colour is a display colour: where nothing is drawn the output
 * holds the clear bytes of the plain frame (no post pass) whatever the
 * exposure and tone map, on both view paths and both 8-bit formats, with
 * and without anti-aliasing; the dark sky the CLI clears to stays itself
 * under auto exposure of a sunlit scene. */
static void clear_colour_is_display_referred(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = sunny_scene(t);
    const double eye[3] = {0, 2.5, 6}, target[3] = {0, 1.5, -1}; /* the horizon mid-view: sky above */
    mvr_projection proj = {.yfov = 0.9, .znear = 0.1};
    mvr_view_desc v[2] = {stress_view(eye, target, proj), stress_view(eye, target, proj)};
    v[1].position[0] += 0.064;
    mvr_view_set *vs = stress_view_set(t, v, 2, NULL);
    const uint32_t W = 48, H = 32;
    const size_t n = (size_t)W * H * 2;
    const float clears[3][4] = {{1, 0, 1, 1}, {0.02f, 0.025f, 0.035f, 1}, {0.5f, 0.2f, 0.05f, 0.5f}};
    const mvr_color_format formats[2] = {MVR_COLOR_FORMAT_DEFAULT, MVR_COLOR_FORMAT_RGBA8};
    const mvr_tone_map maps[3] = {MVR_TONE_MAP_NONE, MVR_TONE_MAP_ACES, MVR_TONE_MAP_KHR_PBR_NEUTRAL};
    const mvr_anti_aliasing aas[3] = {MVR_ANTI_ALIASING_NONE, MVR_ANTI_ALIASING_SUPERSAMPLE, MVR_ANTI_ALIASING_MSAA};
    for (int f = 0; f < 2; ++f)
        for (int c = 0; c < 3; ++c) {
            /* the plain frame: its clear pixels (those another clear changes) hold the clear bytes */
            mvr_render_desc plain = {.exposure = 1.0f};
            memcpy(plain.clear_color, clears[c], sizeof plain.clear_color);
            mvr_render_desc other = plain;
            other.clear_color[0] = 0.25f;
            stress_options o = {.format = formats[f], .width = W, .height = H, .render = &plain};
            uint8_t *ref = stress_render(t, ctx, s, vs, &o, NULL);
            o.render = &other;
            uint8_t *mask = stress_render(t, ctx, s, vs, &o, NULL);
            if (!ref || !mask) {
                free(ref);
                free(mask);
                continue;
            }
            /* sky: a clear pixel whose neighbours are clear too (an anti-aliased edge pixel is not) */
            size_t sky = 0;
            uint8_t *deep = calloc(n, 1);
            for (size_t i = 0; deep && i < n; ++i) {
                int x = (int)(i % W), y = (int)(i / W % H);
                deep[i] = 1;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        int nx = x + dx < 0 ? 0 : x + dx >= (int)W ? (int)W - 1 : x + dx;
                        int ny = y + dy < 0 ? 0 : y + dy >= (int)H ? (int)H - 1 : y + dy;
                        size_t j = i - (size_t)x - (size_t)y * W + (size_t)nx + (size_t)ny * W;
                        deep[i] &= ref[j * 4] != mask[j * 4];
                    }
                sky += deep[i];
            }
            CHECK_MSG(t, sky > n / 8 && sky < n * 7 / 8, "%zu of %zu pixels are sky", sky, n);
            /* each (exposure and tone map, AA) pair under one of the three clears, so every pair
             * is checked once per format: all 27 pairs under every clear made 336 renders, a few
             * seconds in a release build but over 300 s under ASan with Mesa's shader cache off
             * (every renderer compiles its programs) */
            for (int m = 0; m < 9; ++m)
                for (int a = 0; a < 3; ++a) {
                    if ((m + a) % 3 != c)
                        continue;
                    mvr_render_desc rd = plain;
                    rd.tone_map = maps[m % 3];
                    rd.exposure_mode = m < 3 ? MVR_EXPOSURE_LINEAR : m < 6 ? MVR_EXPOSURE_AUTO : MVR_EXPOSURE_EV100;
                    rd.exposure = 0.001f;
                    rd.ev100 = 16.0;
                    o.render = &rd;
                    o.aa = aas[a];
                    for (int p = 0; p < 2; ++p) {
                        o.path = p ? MVR_VIEW_PATH_LOOP : MVR_VIEW_PATH_MULTIVIEW;
                        uint8_t *img = stress_render(t, ctx, s, vs, &o, NULL);
                        size_t bad = 0, first = n;
                        for (size_t i = 0; img && i < n; ++i)
                            if (deep[i] && memcmp(img + i * 4, ref + i * 4, 4) != 0) {
                                bad++;
                                first = first < n ? first : i;
                            }
                        CHECK_MSG(t, img && bad == 0,
                                  "clear %d on %s, tone map %s, exposure %d, aa %s, %s path: %zu of %zu sky "
                                  "pixels differ (first %zu: %d,%d,%d,%d for %d,%d,%d,%d)",
                                  c, mvr_color_format_name(formats[f]), mvr_tone_map_name(rd.tone_map),
                                  (int)rd.exposure_mode, mvr_anti_aliasing_name(o.aa), p ? "loop" : "multiview",
                                  bad, sky, first, img && first < n ? img[first * 4] : -1,
                                  img && first < n ? img[first * 4 + 1] : -1, img && first < n ? img[first * 4 + 2] : -1,
                                  img && first < n ? img[first * 4 + 3] : -1, first < n ? ref[first * 4] : -1,
                                  first < n ? ref[first * 4 + 1] : -1, first < n ? ref[first * 4 + 2] : -1,
                                  first < n ? ref[first * 4 + 3] : -1);
                        free(img);
                    }
                }
            if (c == 1) /* the dark sky: its own bytes, not black */
                CHECK_MSG(t, ref[0] > 30 || ref[(n - 1) * 4] > 30, "dark sky %d,%d,%d", ref[0], ref[1], ref[2]);
            free(deep);
            free(ref);
            free(mask);
        }
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* A slanted quad of emissive `bright` over a dark one (emissive 0.05), no lights. */
static mvr_scene *edge_scene(mvr_test_state *t, float bright)
{
    mvr_scene *s = stress_scene();
    mvr_material_id mats[2];
    for (int k = 0; k < 2; ++k) {
        mvr_material_desc m = mvr_material_defaults();
        m.base_color_factor[0] = m.base_color_factor[1] = m.base_color_factor[2] = 0.0f;
        m.metallic_factor = 0.0f;
        m.emissive_factor[0] = m.emissive_factor[1] = m.emissive_factor[2] = 1.0f;
        m.emissive_strength = k ? bright : 0.05f;
        CHECK(t, mvr_scene_add_material(s, &m, &mats[k]) == MVR_OK);
    }
    stress_node(t, s, stress_add_quad(t, s, mats[0]), 0, 0, 0, 10.0);
    double a = 0.35; /* about 20 degrees: every edge pixel partly covered, at every coverage */
    mvr_node_desc nd = {.mesh = stress_add_quad(t, s, mats[1]), .translation = {0, 0, 0.5},
                        .rotation = {0, 0, sin(a / 2), cos(a / 2)}, .scale = {0.55, 0.55, 0.55}};
    mvr_node_id id;
    CHECK(t, mvr_scene_add_node(s, &nd, &id) == MVR_OK);
    return s;
}

/* The resolve respects HDR: the edge of a blown-out surface (emissive 1000,
 * tone mapped to white) against a dark one has as many partly covered
 * pixels as the edge of a surface exactly white (emissive 1, no tone map),
 * and their mean sits near the mean of the two display values, with MSAA
 * and with supersampling, the same bytes on both view paths. A resolve of
 * the HDR values before tone mapping turns most of those pixels white. */
static void resolve_tone_maps_each_sample(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *scenes[2] = {edge_scene(t, 1.0f), edge_scene(t, 1000.0f)};
    mvr_view_desc v;
    memset(&v, 0, sizeof v);
    v.position[2] = 5;
    v.projection.type = MVR_PROJECTION_ORTHOGRAPHIC;
    v.projection.xmag = v.projection.ymag = 1;
    v.projection.zfar = 10;
    mvr_view_desc vv[2] = {v, v};
    mvr_view_set *vs = stress_view_set(t, vv, 2, NULL);
    const uint32_t W = 64, H = 64;
    const mvr_anti_aliasing aas[2] = {MVR_ANTI_ALIASING_MSAA, MVR_ANTI_ALIASING_SUPERSAMPLE};
    for (int a = 0; a < 2; ++a) {
        size_t partial[2] = {0, 0};
        double mean[2] = {0, 0}, mid[2] = {0, 0};
        for (int k = 0; k < 2; ++k) {
            /* exposure 1; the blown-out scene tone mapped (PBR Neutral: 1000 -> white) */
            mvr_render_desc rd = {.exposure_mode = MVR_EXPOSURE_EV100, .ev100 = -log2(1.2),
                                  .tone_map = k ? MVR_TONE_MAP_KHR_PBR_NEUTRAL : MVR_TONE_MAP_NONE};
            stress_options o = {.format = MVR_COLOR_FORMAT_DEFAULT, .width = W, .height = H, .render = &rd,
                                .aa = aas[a], .path = MVR_VIEW_PATH_MULTIVIEW};
            uint8_t *mv = stress_render(t, ctx, scenes[k], vs, &o, NULL);
            o.path = MVR_VIEW_PATH_LOOP;
            uint8_t *loop = stress_render(t, ctx, scenes[k], vs, &o, NULL);
            if (mv && loop)
                CHECK_MSG(t, memcmp(mv, loop, (size_t)W * H * 8) == 0, "%s: the paths differ",
                          mvr_anti_aliasing_name(aas[a]));
            if (mv) {
                int dark = mv[1], bright = mv[((H / 2) * W + W / 2) * 4 + 1];
                mid[k] = (dark + bright) / 2.0;
                for (size_t i = 0; i < (size_t)W * H; ++i) {
                    int g = mv[i * 4 + 1];
                    if (abs(g - dark) > 2 && abs(g - bright) > 2) {
                        partial[k]++;
                        mean[k] += g;
                    }
                }
                mean[k] /= partial[k] ? (double)partial[k] : 1.0;
                printf("  %-11s %-10s dark %d, bright %d: %zu partly covered pixels, mean %.1f (midpoint %.1f)\n",
                       mvr_anti_aliasing_name(aas[a]), k ? "blown out" : "white", dark, bright, partial[k], mean[k],
                       mid[k]);
                CHECK_MSG(t, bright == 255, "%s: the bright surface is %d", mvr_anti_aliasing_name(aas[a]), bright);
            }
            free(mv);
            free(loop);
        }
        CHECK_MSG(t, partial[0] > 40, "%zu edge pixels", partial[0]);
        CHECK_MSG(t, partial[1] >= partial[0] * 8 / 10, "%s: %zu partly covered pixels blown out, %zu white",
                  mvr_anti_aliasing_name(aas[a]), partial[1], partial[0]);
        CHECK_MSG(t, fabs(mean[1] - mid[1]) <= 0.15 * 255, "%s: edge mean %.1f, the display values' mean %.1f",
                  mvr_anti_aliasing_name(aas[a]), mean[1], mid[1]);
    }
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scenes[0]);
    mvr_scene_destroy(scenes[1]);
    mvr_context_destroy(ctx);
}

/* The stats a caller pools to meter views rendered in parts (mvr render's
 * stream): 4 views, one looking at the black sky alone (not measured); the
 * measured luminances of parts of 2 views, weighted by their measured
 * views, give the EV100 of one render of the 4. */
static void auto_exposure_pools_over_parts(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_scene *s = sunny_scene(t);
    mvr_projection proj = {.yfov = 0.9, .znear = 0.1};
    const double eyes[4][3] = {{0, 2.5, 6}, {4, 1.5, 3}, {0, 30, 0.01}, {-3, 3, 4}};
    const double at[4][3] = {{0, 0.3, -1}, {0, 0, -1}, {0, 1000, 0}, {0, 0, 0}};
    mvr_view_desc v[4];
    for (int i = 0; i < 4; ++i)
        v[i] = stress_view(eyes[i], at[i], proj);
    mvr_view_set *all = stress_view_set(t, v, 4, NULL);
    double origin[3] = {0, 0, 0};
    CHECK(t, mvr_view_set_get_origin(all, origin) == MVR_OK);
    mvr_view_set *part[2] = {stress_view_set(t, v, 2, origin), stress_view_set(t, v + 2, 2, origin)};
    mvr_render_desc rd = {.clear_color = {0, 0, 0, 1}, .exposure_mode = MVR_EXPOSURE_AUTO, .exposure_compensation = 0.5f,
                          .tone_map = MVR_TONE_MAP_KHR_PBR_NEUTRAL};
    mvr_frame_stats st_all, st_part[2];
    uint8_t *img = render_desc(t, ctx, s, all, MVR_VIEW_PATH_AUTO, MVR_COLOR_FORMAT_DEFAULT, 48, 32, &rd, &st_all);
    free(img);
    double sum = 0.0;
    uint32_t measured = 0;
    for (int k = 0; k < 2; ++k) {
        img = render_desc(t, ctx, s, part[k], MVR_VIEW_PATH_AUTO, MVR_COLOR_FORMAT_DEFAULT, 48, 32, &rd, &st_part[k]);
        free(img);
        sum += st_part[k].exposure_log2_luminance * st_part[k].exposure_measured_views;
        measured += st_part[k].exposure_measured_views;
    }
    CHECK_EQ_INT(t, st_all.exposure_measured_views, 3);
    CHECK_EQ_INT(t, measured, 3);
    /* the EV100 the stats give: the average on the key (0.18), less the compensation */
    double key = log2(1.2 * (double)0.18f);
    double ev_all = st_all.exposure_log2_luminance - key - 0.5;
    double ev_pooled = sum / (measured ? measured : 1) - key - 0.5;
    /* weighted by views instead, the view that saw nothing would count */
    double ev_by_views = (st_part[0].exposure_log2_luminance + st_part[1].exposure_log2_luminance) / 2 - key - 0.5;
    printf("  EV100 %.4f (one render, stats %.4f), pooled over parts %.4f (parts alone %.4f, %.4f)\n",
           st_all.exposure_ev100, ev_all, ev_pooled, st_part[0].exposure_ev100, st_part[1].exposure_ev100);
    CHECK_MSG(t, fabs(ev_all - st_all.exposure_ev100) < 1e-9, "the stats give EV100 %.6f, the render ran %.6f", ev_all,
              st_all.exposure_ev100);
    CHECK_MSG(t, fabs(ev_pooled - st_all.exposure_ev100) < 1e-3, "pooled %.6f, one render %.6f", ev_pooled,
              st_all.exposure_ev100);
    /* the parts alone, or pooled by view count, miss it by more than that */
    CHECK_MSG(t, fabs(st_part[0].exposure_ev100 - st_all.exposure_ev100) > 1e-2, "part 0: %.4f",
              st_part[0].exposure_ev100);
    CHECK_MSG(t, fabs(ev_by_views - st_all.exposure_ev100) > 3e-3, "pooled by views: %.4f", ev_by_views);
    mvr_view_set_destroy(part[0]);
    mvr_view_set_destroy(part[1]);
    mvr_view_set_destroy(all);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(auto_exposure_tames_the_sun), TEST(post_pass_is_the_same_on_both_paths),
              TEST(tone_mappers_match_their_formulas), TEST(auto_exposure_pools_over_parts),
              TEST(clear_colour_is_display_referred), TEST(resolve_tone_maps_each_sample))
