/* gl: the PBR extensions KHR_materials_ior, _specular, _clearcoat,
 * _pbrSpecularGlossiness, _iridescence and _anisotropy (sheen and
 * transmission have their own tests).
 * - a scene without them compiles none of their code (no extension's
 *   feature bit on any demo);
 * - the extensions at glTF's core values (ior 1.5, specular factor 1 and
 *   colour 1, clearcoat 0) give the core BRDF's pixels (within 1/255: the
 *   formulas are the same, the arithmetic is ordered differently);
 * - a clearcoat over a sphere under a uniform environment: the centre pixel
 *   (n.v = 1, the coat's Fresnel is its F0 = 0.04) is the bare sphere's
 *   value mixed with the coat's reflection of radiance 1 by 0.04 (float
 *   target; tolerance 2e-3 for the half-float environment maps);
 * - the multiview and loop paths give the same bytes with both extensions.
 * The comparison with the Khronos glTF Sample Renderer is io_peers' (the
 * coated.gltf asset). */
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

/* A lit (or unlit) sphere of material md in scene s (NULL: a new scene). */
static mvr_scene *sphere_in(mvr_test_state *t, mvr_scene *s, const mvr_material_desc *md, bool light)
{
    if (!s)
        CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, md, &mat) == MVR_OK);
    demo_mesh m;
    memset(&m, 0, sizeof m);
    demo_sphere(&m, 1.0f, 48, 24);
    mvr_mesh_id mesh = {0};
    CHECK(t, demo_mesh_add(s, &m, mat, false, "sphere", &mesh) == MVR_OK);
    demo_mesh_free(&m);
    mvr_node_desc nd = {.mesh = mesh};
    mvr_node_id n;
    CHECK(t, mvr_scene_add_node(s, &nd, &n) == MVR_OK);
    if (light)
        render_views_add_sun(t, s);
    return s;
}

static mvr_scene *sphere_scene(mvr_test_state *t, const mvr_material_desc *md, bool light)
{
    return sphere_in(t, NULL, md, light);
}

/* core/material.c's F0 of an ior, as the library computes it (float) */
static float mvr_material_ior_f0_for_test(float ior)
{
    float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

static mvr_view_set *front_views(mvr_test_state *t, uint32_t n)
{
    mvr_view_desc v[2];
    memset(v, 0, sizeof v);
    for (uint32_t i = 0; i < n; ++i) {
        double eye[3] = {0.3 * i, 0, 3.2}, at[3] = {0, 0, 0}, up[3] = {0, 1, 0};
        mvr_view_look_at(&v[i], eye, at, up);
        v[i].projection.yfov = 0.8;
    }
    mvr_view_set_desc vd = {.view_count = n, .views = v};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_create(&vd, &vs, NULL) == MVR_OK);
    return vs;
}

/* Renders with an environment (uniform radiance 1) into a target of the
 * format; returns the layers' floats (RGBA32F) or bytes (default). */
static void *render_with(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, mvr_view_set *vs, mvr_view_path path,
                         mvr_material_path material_path, mvr_color_format format, uint32_t *features)
{
    render_views_opts o = {.width = W, .height = H, .path = path, .material_path = material_path, .format = format,
                           .environment = true, .environment_source = MVR_ENVIRONMENT_UNIFORM};
    render_views_out r = render_views(t, ctx, s, vs, &o);
    *features = r.features;
    return r.pixels;
}

static void *render(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, mvr_view_set *vs, mvr_view_path path,
                    mvr_color_format format, uint32_t *features)
{
    return render_with(t, ctx, s, vs, path, MVR_MATERIAL_PATH_AUTO, format, features);
}

static void demos_compile_no_extension_code(mvr_test_state *t)
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
        free(render(t, ctx, s, vs, MVR_VIEW_PATH_AUTO, MVR_COLOR_FORMAT_DEFAULT, &features));
        const uint32_t extensions = MVR_FEATURE_SPECULAR | MVR_FEATURE_CLEARCOAT | MVR_FEATURE_SHEEN |
                                    MVR_FEATURE_TRANSMISSION | MVR_FEATURE_IRIDESCENCE | MVR_FEATURE_ANISOTROPY |
                                    MVR_FEATURE_SPEC_GLOSS;
        CHECK_MSG(t, !(features & extensions), "%s: features %x", mvr_demo_name(d), features);
        mvr_view_set_destroy(vs);
        mvr_scene_destroy(s);
    }
    mvr_context_destroy(ctx);
}

static void core_values_give_the_core_pixels(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_view_set *vs = front_views(t, 1);
    const float metals[2] = {0.0f, 1.0f};
    for (int k = 0; k < 2; ++k) {
        mvr_material_desc core = mvr_material_defaults();
        core.base_color_factor[0] = 0.8f;
        core.base_color_factor[1] = 0.4f;
        core.base_color_factor[2] = 0.2f;
        core.metallic_factor = metals[k];
        core.roughness_factor = 0.35f;
        mvr_material_desc ext = core;
        ext.specular.enabled = true;
        ext.specular.factor = 1.0f;
        ext.specular.color_factor[0] = ext.specular.color_factor[1] = ext.specular.color_factor[2] = 1.0f;
        ext.ior = 1.5f;
        mvr_scene *a = sphere_scene(t, &core, true), *b = sphere_scene(t, &ext, true);
        uint32_t fa = 0, fb = 0;
        uint8_t *pa = render(t, ctx, a, vs, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_DEFAULT, &fa);
        uint8_t *pb = render(t, ctx, b, vs, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_DEFAULT, &fb);
        CHECK(t, !(fa & MVR_FEATURE_SPECULAR) && (fb & MVR_FEATURE_SPECULAR));
        if (pa && pb) {
            uint32_t d = count_diff(pa, pb, (size_t)W * H, 1), d0 = count_diff(pa, pb, (size_t)W * H, 0);
            printf("  metallic %g: %u pixels differ at all, %u by more than 1/255\n", metals[k], d0, d);
            CHECK_EQ_INT(t, d, 0);
        }
        free(pa);
        free(pb);
        mvr_scene_destroy(a);
        mvr_scene_destroy(b);
    }
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

static void clearcoat_mixes_by_its_fresnel(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_view_set *vs = front_views(t, 1);
    mvr_material_desc bare = mvr_material_defaults();
    bare.base_color_factor[0] = 0.7f;
    bare.base_color_factor[1] = 0.1f;
    bare.base_color_factor[2] = 0.1f;
    bare.metallic_factor = 0.0f;
    bare.roughness_factor = 0.7f;
    mvr_material_desc coated = bare;
    coated.clearcoat.factor = 1.0f;
    coated.clearcoat.roughness_factor = 0.1f;
    mvr_scene *a = sphere_scene(t, &bare, false), *b = sphere_scene(t, &coated, false);
    uint32_t fa = 0, fb = 0;
    float *pa = render(t, ctx, a, vs, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_RGBA32F, &fa);
    float *pb = render(t, ctx, b, vs, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_RGBA32F, &fb);
    CHECK(t, !(fa & MVR_FEATURE_CLEARCOAT) && (fb & MVR_FEATURE_CLEARCOAT));
    if (pa && pb) {
        size_t c = ((size_t)(H / 2) * W + W / 2) * 4;
        for (size_t k = 0; k < 3; ++k) {
            double expect = 0.96 * pa[c + k] + 0.04 * 1.0;
            CHECK_MSG(t, fabs(pb[c + k] - expect) < 2e-3, "channel %zu: %g, expected %g (bare %g)", k, pb[c + k],
                      expect, pa[c + k]);
        }
    }
    free(pa);
    free(pb);
    /* multiview and loop, both extensions: the same bytes */
    coated.specular.enabled = true;
    coated.specular.factor = 0.6f;
    coated.ior = 1.9f;
    mvr_scene *c2 = sphere_scene(t, &coated, true);
    mvr_view_set *two = front_views(t, 2);
    if (mvr_context_caps(ctx)->ext.ovr_multiview2) {
        uint32_t f1, f2;
        uint8_t *loop = render(t, ctx, c2, two, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_DEFAULT, &f1);
        uint8_t *mv = render(t, ctx, c2, two, MVR_VIEW_PATH_MULTIVIEW, MVR_COLOR_FORMAT_DEFAULT, &f2);
        if (loop && mv)
            CHECK_EQ_INT(t, count_diff(loop, mv, (size_t)2 * W * H, 0), 0);
        free(loop);
        free(mv);
    }
    mvr_view_set_destroy(two);
    mvr_scene_destroy(c2);
    /* overrides.disable_features: the coated sphere drawn as the bare one,
     * with no clearcoat code (mvr bench's "extension off") */
    {
        mvr_renderer_desc rd = {.context = ctx, .view_path = MVR_VIEW_PATH_LOOP,
                                .overrides = {.disable_features = MVR_FEATURE_CLEARCOAT | MVR_FEATURE_SPECULAR}};
        mvr_renderer_desc plain = {.context = ctx, .view_path = MVR_VIEW_PATH_LOOP};
        const mvr_renderer_desc *descs[2] = {&rd, &plain};
        mvr_scene *scenes[2] = {b, a};
        uint8_t *px[2] = {NULL, NULL};
        for (int k = 0; k < 2; ++k) {
            mvr_renderer *r = NULL;
            mvr_target *tg = NULL;
            mvr_target_desc td = {.width = W, .height = H, .layers = 1};
            mvr_render_desc desc = {.exposure = 1.0f};
            bool ok = mvr_renderer_create(descs[k], &r, NULL) == MVR_OK && mvr_target_create(r, &td, &tg) == MVR_OK &&
                      mvr_renderer_render(r, scenes[k], vs, tg, &desc) == MVR_OK;
            CHECK(t, ok);
            px[k] = malloc((size_t)W * H * 4);
            CHECK(t, ok && mvr_renderer_read_layer(r, tg, 0, MVR_READBACK_RGBA8, px[k], (size_t)W * H * 4) == MVR_OK);
            for (uint32_t i = 0; r && i < mvr_renderer_program_count(r); ++i) {
                mvr_program_info info;
                if (mvr_renderer_get_program_info(r, i, &info))
                    CHECK(t, !(info.features & (MVR_FEATURE_CLEARCOAT | MVR_FEATURE_SPECULAR)));
            }
            mvr_target_destroy(tg);
            mvr_renderer_destroy(r);
        }
        CHECK_EQ_INT(t, count_diff(px[0], px[1], (size_t)W * H, 0), 0);
        free(px[0]);
        free(px[1]);
        mvr_renderer_desc bad = {.context = ctx, .overrides = {.disable_features = MVR_FEATURE_NORMALS}};
        mvr_renderer *r = NULL;
        CHECK(t, mvr_renderer_create(&bad, &r, NULL) == MVR_ERROR_INVALID_ARGUMENT && !r);
    }
    mvr_scene_destroy(a);
    mvr_scene_destroy(b);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

/* The extensions' textures (KHR_materials_clearcoat's three, _specular's
 * two), nearest-sampled: where the clearcoat texture is white a pixel is the
 * fully coated sphere's, where black the bare sphere's (within 1/255), and
 * both occur; a tilted coat normal map changes pixels; array and
 * per-material texture paths, multiview and loop give the same bytes. */
static void extension_textures_are_sampled(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    enum { TW = 16, TH = 16 };
    static uint8_t half[TW * TH * 4], tilt[TW * TH * 4], grey[TW * TH * 4];
    for (int y = 0; y < TH; ++y)
        for (int x = 0; x < TW; ++x) {
            uint8_t *p = &half[(y * TW + x) * 4], *q = &tilt[(y * TW + x) * 4], *g = &grey[(y * TW + x) * 4];
            uint8_t v = x < TW / 2 ? 255 : 0;
            p[0] = p[1] = p[2] = p[3] = v;
            q[0] = 200, q[1] = 128, q[2] = 200, q[3] = 255; /* a normal tilted towards +u */
            g[0] = 255, g[1] = 160, g[2] = 90, g[3] = 128;
        }
    mvr_sampler_desc nearest = {MVR_FILTER_NEAREST, MVR_FILTER_NEAREST, MVR_WRAP_REPEAT, MVR_WRAP_REPEAT};
    mvr_material_desc bare = mvr_material_defaults();
    bare.base_color_factor[0] = 0.6f;
    bare.base_color_factor[1] = 0.2f;
    bare.base_color_factor[2] = 0.1f;
    bare.metallic_factor = 0.0f;
    bare.roughness_factor = 0.8f;
    mvr_material_desc coated = bare;
    coated.clearcoat.factor = 1.0f;
    coated.clearcoat.roughness_factor = 0.05f;
    mvr_view_set *vs = front_views(t, 1);

    /* a scene of the three: bare, coated, coated where the texture is white */
    mvr_scene *scenes[3] = {NULL, NULL, NULL};
    for (int k = 0; k < 3; ++k) {
        CHECK(t, mvr_scene_create(NULL, &scenes[k], NULL) == MVR_OK);
        mvr_material_desc md = k == 0 ? bare : coated;
        if (k == 2) {
            mvr_image_desc id = {.width = TW, .height = TH, .rgba8 = half, .name = "half"};
            CHECK(t, mvr_scene_add_image(scenes[k], &id, &md.clearcoat.texture.image) == MVR_OK);
            md.clearcoat.texture.sampler = nearest;
        }
        sphere_in(t, scenes[k], &md, true);
    }
    uint32_t f[3];
    uint8_t *px[3];
    for (int k = 0; k < 3; ++k)
        px[k] = render(t, ctx, scenes[k], vs, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_DEFAULT, &f[k]);
    if (px[0] && px[1] && px[2]) {
        uint32_t as_bare = 0, as_coated = 0, neither = 0, differ = 0;
        for (size_t i = 0; i < (size_t)W * H; ++i) {
            bool b = count_diff(px[2] + i * 4, px[0] + i * 4, 1, 1) == 0;
            bool c = count_diff(px[2] + i * 4, px[1] + i * 4, 1, 1) == 0;
            differ += count_diff(px[0] + i * 4, px[1] + i * 4, 1, 1) != 0;
            as_bare += b && !c;
            as_coated += c && !b;
            neither += !b && !c;
        }
        printf("  clearcoat texture: %u pixels as the bare sphere, %u as the coated, %u neither (%u differ)\n",
               as_bare, as_coated, neither, differ);
        CHECK_EQ_INT(t, neither, 0);
        CHECK(t, as_bare > differ / 4 && as_coated > differ / 4);
    }
    for (int k = 0; k < 3; ++k) {
        free(px[k]);
        mvr_scene_destroy(scenes[k]);
    }

    /* every texture of both extensions, the coat's normal map tilted */
    mvr_scene *s = NULL, *flat = NULL;
    for (int k = 0; k < 2; ++k) {
        mvr_scene **sp = k ? &flat : &s;
        CHECK(t, mvr_scene_create(NULL, sp, NULL) == MVR_OK);
        mvr_image_id ih, it, ig;
        mvr_image_desc dh = {.width = TW, .height = TH, .rgba8 = half, .name = "half"}, dt = {.width = TW, .height = TH, .rgba8 = tilt, .name = "tilt"}, dg = {.width = TW, .height = TH, .rgba8 = grey, .name = "grey"};
        CHECK(t, mvr_scene_add_image(*sp, &dh, &ih) == MVR_OK && mvr_scene_add_image(*sp, &dt, &it) == MVR_OK &&
                     mvr_scene_add_image(*sp, &dg, &ig) == MVR_OK);
        mvr_material_desc md = coated;
        md.clearcoat.texture.image = ig;
        md.clearcoat.roughness_texture.image = ig;
        if (k == 0)
            md.clearcoat.normal_texture.image = it;
        md.specular.enabled = true;
        md.specular.factor = 0.8f;
        md.specular.color_factor[1] = 1.2f;
        md.specular.texture.image = ig;
        md.specular.color_texture.image = ig;
        md.specular.color_texture.transform = (mvr_texture_transform){true, {0.25f, 0.0f}, 0.3f, {2.0f, 2.0f}};
        sphere_in(t, *sp, &md, true);
        /* a second material sharing the program without the textures */
        mvr_material_desc plain = coated;
        plain.specular.enabled = true;
        plain.specular.factor = 0.5f;
        mvr_material_id pm;
        CHECK(t, mvr_scene_add_material(*sp, &plain, &pm) == MVR_OK);
    }
    mvr_view_set *two = front_views(t, 2);
    const mvr_view_path paths[2] = {MVR_VIEW_PATH_LOOP, MVR_VIEW_PATH_MULTIVIEW};
    const mvr_material_path mpaths[2] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL};
    uint8_t *ref = NULL;
    for (int p = 0; p < 2; ++p) {
        if (paths[p] == MVR_VIEW_PATH_MULTIVIEW && !mvr_context_caps(ctx)->ext.ovr_multiview2)
            continue;
        for (int m = 0; m < 2; ++m) {
            uint32_t feat;
            uint8_t *o = render_with(t, ctx, s, two, paths[p], mpaths[m], MVR_COLOR_FORMAT_DEFAULT, &feat);
            CHECK(t, (feat & MVR_FEATURE_CLEARCOAT) && (feat & MVR_FEATURE_SPECULAR) &&
                         (feat & MVR_FEATURE_TEXTURE_TRANSFORM));
            if (!ref)
                ref = o;
            else {
                if (o)
                    CHECK_MSG(t, count_diff(ref, o, (size_t)2 * W * H, 0) == 0, "path %d / %d differs", p, m);
                free(o);
            }
        }
    }
    uint32_t ff;
    uint8_t *o = render_with(t, ctx, flat, two, MVR_VIEW_PATH_LOOP, MVR_MATERIAL_PATH_ARRAYS,
                             MVR_COLOR_FORMAT_DEFAULT, &ff);
    if (ref && o) {
        uint32_t d = count_diff(ref, o, (size_t)2 * W * H, 2);
        printf("  the coat's normal map changes %u pixels\n", d);
        CHECK(t, d > 50);
    }
    free(o);
    free(ref);
    mvr_view_set_destroy(two);
    mvr_scene_destroy(s);
    mvr_scene_destroy(flat);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

/* KHR_materials_pbrSpecularGlossiness is the specular extension's
 * dielectric: a spec-gloss sphere gives the pixels (within 1/255) of a
 * metallic 0, roughness 1 - glossiness sphere whose KHR_materials_specular
 * color makes F0 the specular color; its texture's A scales glossiness (a
 * half-black A: each pixel is the glossy or the rough twin's). */
static void spec_gloss_is_a_dielectric(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    enum { TW = 16, TH = 16 };
    static uint8_t half[TW * TH * 4];
    for (int y = 0; y < TH; ++y)
        for (int x = 0; x < TW; ++x) {
            uint8_t *p = &half[(y * TW + x) * 4];
            p[0] = p[1] = p[2] = 255;
            p[3] = x < TW / 2 ? 255 : 0;
        }
    mvr_view_set *vs = front_views(t, 1);
    const float spec[3] = {0.2f, 0.1f, 0.05f}, gloss = 0.6f;
    float f0 = mvr_material_ior_f0_for_test(1.5f);
    mvr_material_desc sg = mvr_material_defaults();
    sg.base_color_factor[0] = 0.5f;
    sg.base_color_factor[1] = 0.3f;
    sg.base_color_factor[2] = 0.2f;
    sg.spec_gloss.enabled = true;
    memcpy(sg.spec_gloss.specular_factor, spec, sizeof spec);
    sg.spec_gloss.glossiness_factor = gloss;
    mvr_material_desc twin = mvr_material_defaults();
    memcpy(twin.base_color_factor, sg.base_color_factor, sizeof twin.base_color_factor);
    twin.metallic_factor = 0.0f;
    twin.roughness_factor = 1.0f - gloss;
    twin.specular.enabled = true;
    twin.specular.factor = 1.0f;
    for (int c = 0; c < 3; ++c)
        twin.specular.color_factor[c] = spec[c] / f0;
    mvr_material_desc rough = twin;
    rough.roughness_factor = 1.0f;
    mvr_material_desc textured = sg;
    mvr_scene *scenes[4] = {NULL, NULL, NULL, NULL};
    const mvr_material_desc *mats[4] = {&sg, &twin, &rough, &textured};
    for (int k = 0; k < 4; ++k) {
        CHECK(t, mvr_scene_create(NULL, &scenes[k], NULL) == MVR_OK);
        mvr_material_desc md = *mats[k];
        if (k == 3) {
            mvr_image_desc id = {.width = TW, .height = TH, .rgba8 = half, .name = "half"};
            CHECK(t, mvr_scene_add_image(scenes[k], &id, &md.spec_gloss.texture.image) == MVR_OK);
            md.spec_gloss.texture.sampler =
                (mvr_sampler_desc){MVR_FILTER_NEAREST, MVR_FILTER_NEAREST, MVR_WRAP_REPEAT, MVR_WRAP_REPEAT};
        }
        sphere_in(t, scenes[k], &md, true);
    }
    uint32_t f[4];
    uint8_t *px[4];
    for (int k = 0; k < 4; ++k)
        px[k] = render(t, ctx, scenes[k], vs, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_DEFAULT, &f[k]);
    CHECK(t, (f[0] & MVR_FEATURE_SPEC_GLOSS) && !(f[1] & MVR_FEATURE_SPEC_GLOSS));
    if (px[0] && px[1] && px[2] && px[3]) {
        uint32_t d = count_diff(px[0], px[1], (size_t)W * H, 1);
        printf("  spec-gloss vs its metal-rough twin: %u pixels over 1/255\n", d);
        CHECK_EQ_INT(t, d, 0);
        uint32_t glossy = 0, rough_px = 0, neither = 0;
        for (size_t i = 0; i < (size_t)W * H; ++i) {
            bool g = count_diff(px[3] + i * 4, px[1] + i * 4, 1, 1) == 0;
            bool r = count_diff(px[3] + i * 4, px[2] + i * 4, 1, 1) == 0;
            glossy += g && !r;
            rough_px += r && !g;
            neither += !g && !r;
        }
        printf("  spec-gloss texture: %u pixels glossy, %u rough, %u neither\n", glossy, rough_px, neither);
        CHECK_EQ_INT(t, neither, 0);
        CHECK(t, glossy > 100 && rough_px > 100);
    }
    for (int k = 0; k < 4; ++k) {
        free(px[k]);
        mvr_scene_destroy(scenes[k]);
    }
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

/* KHR_materials_pbrSpecularGlossiness: diffuseTexture and the RGB of
 * specularGlossinessTexture are sRGB-encoded (the extension's text), so a
 * texel of 128 is the factor 0.2158 (pixels within 1/255 of that twin's),
 * not 0.502. The Khronos glTF Sample Renderer 1.1.0 uploads both as linear
 * (docs/peers.md): its BoomBox is brighter than mvr's for that reason. */
static void spec_gloss_textures_are_srgb(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    enum { TW = 4, TH = 4 };
    static uint8_t diffuse[TW * TH * 4], specgloss[TW * TH * 4];
    for (int i = 0; i < TW * TH; ++i) {
        diffuse[i * 4] = diffuse[i * 4 + 1] = diffuse[i * 4 + 2] = 128;
        specgloss[i * 4] = specgloss[i * 4 + 1] = specgloss[i * 4 + 2] = 128;
        diffuse[i * 4 + 3] = specgloss[i * 4 + 3] = 255;
    }
    const float lin = 0.21586050f, raw = 128.0f / 255.0f; /* sRGB 128 decoded, and read as linear */
    mvr_view_set *vs = front_views(t, 1);
    mvr_material_desc textured = mvr_material_defaults();
    textured.spec_gloss.enabled = true;
    textured.spec_gloss.glossiness_factor = 0.5f;
    mvr_material_desc as_srgb = textured, as_linear = textured;
    for (int c = 0; c < 3; ++c) {
        as_srgb.base_color_factor[c] = as_srgb.spec_gloss.specular_factor[c] = lin;
        as_linear.base_color_factor[c] = as_linear.spec_gloss.specular_factor[c] = raw;
    }
    const mvr_material_desc *mats[3] = {&textured, &as_srgb, &as_linear};
    mvr_scene *scenes[3] = {NULL, NULL, NULL};
    uint8_t *px[3];
    for (int k = 0; k < 3; ++k) {
        CHECK(t, mvr_scene_create(NULL, &scenes[k], NULL) == MVR_OK);
        mvr_material_desc md = *mats[k];
        if (k == 0) {
            mvr_image_desc d = {.width = TW, .height = TH, .rgba8 = diffuse, .name = "diffuse"};
            mvr_image_desc g = {.width = TW, .height = TH, .rgba8 = specgloss, .name = "specular-glossiness"};
            CHECK(t, mvr_scene_add_image(scenes[k], &d, &md.base_color.image) == MVR_OK);
            CHECK(t, mvr_scene_add_image(scenes[k], &g, &md.spec_gloss.texture.image) == MVR_OK);
        }
        sphere_in(t, scenes[k], &md, true);
        uint32_t features = 0;
        px[k] = render(t, ctx, scenes[k], vs, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_DEFAULT, &features);
    }
    if (px[0] && px[1] && px[2]) {
        uint32_t srgb = count_diff(px[0], px[1], (size_t)W * H, 1), linear = count_diff(px[0], px[2], (size_t)W * H, 1);
        printf("  spec-gloss textures: %u pixels off the sRGB-decoded factors, %u off the raw ones\n", srgb, linear);
        CHECK_EQ_INT(t, srgb, 0);
        CHECK(t, linear > 1000);
    }
    for (int k = 0; k < 3; ++k) {
        free(px[k]);
        mvr_scene_destroy(scenes[k]);
    }
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

/* Multiview and loop give the same bytes for a lit sphere of material md. */
static void multiview_equals_loop(mvr_test_state *t, mvr_context *ctx, const mvr_material_desc *md)
{
    if (!mvr_context_caps(ctx)->ext.ovr_multiview2)
        return;
    mvr_scene *s = sphere_scene(t, md, true);
    mvr_view_set *two = front_views(t, 2);
    uint32_t f1, f2;
    uint8_t *loop = render(t, ctx, s, two, MVR_VIEW_PATH_LOOP, MVR_COLOR_FORMAT_DEFAULT, &f1);
    uint8_t *mv = render(t, ctx, s, two, MVR_VIEW_PATH_MULTIVIEW, MVR_COLOR_FORMAT_DEFAULT, &f2);
    if (loop && mv)
        CHECK_EQ_INT(t, count_diff(loop, mv, (size_t)2 * W * H, 0), 0);
    free(loop);
    free(mv);
    mvr_view_set_destroy(two);
    mvr_scene_destroy(s);
}

/* A lit sphere of material md in a scene of its own, rendered on the loop
 * path and the material path; with texels (size x size RGBA8), the image
 * goes into *slot (a texture ref of md). */
static uint8_t *render_lit_sphere(mvr_test_state *t, mvr_context *ctx, mvr_view_set *vs, mvr_material_desc *md,
                                  const uint8_t *texels, uint32_t size, mvr_texture_ref *slot,
                                  mvr_material_path path, uint32_t *features)
{
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    if (texels) {
        mvr_image_desc id = {.width = size, .height = size, .rgba8 = texels};
        CHECK(t, mvr_scene_add_image(s, &id, &slot->image) == MVR_OK);
    }
    sphere_in(t, s, md, true);
    uint8_t *px = render_with(t, ctx, s, vs, MVR_VIEW_PATH_LOOP, path, MVR_COLOR_FORMAT_DEFAULT, features);
    mvr_scene_destroy(s);
    return px;
}

/* KHR_materials_iridescence: no film (factor 0, or 0 nm) compiles none of
 * its code; a film changes the sphere; a thickness texture of G = 0 gives
 * the film of the minimum thickness (the bytes of a film whose maximum is
 * that minimum), G = 1 the maximum's (the bytes of no texture); multiview
 * and loop, arrays and per-material textures give the same bytes. */
static void iridescence_film(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    enum { TW = 8 };
    static uint8_t black[TW * TW * 4], white[TW * TW * 4];
    memset(white, 255, sizeof white);
    for (int i = 0; i < TW * TW; ++i)
        black[i * 4 + 3] = 255;
    mvr_view_set *vs = front_views(t, 1);
    mvr_material_desc plain = mvr_material_defaults();
    plain.base_color_factor[0] = 0.2f;
    plain.base_color_factor[1] = 0.2f;
    plain.base_color_factor[2] = 0.25f;
    plain.metallic_factor = 0.3f;
    plain.roughness_factor = 0.25f;
    mvr_material_desc film = plain;
    film.iridescence.factor = 1.0f;
    film.iridescence.thickness_minimum = 250.0f;
    film.iridescence.thickness_maximum = 600.0f;
    mvr_material_desc thin = film, none = film;
    thin.iridescence.thickness_maximum = 250.0f;
    none.iridescence.thickness_maximum = 0.0f;
    mvr_material_desc tex_black = film, tex_white = film;
    const mvr_material_desc *mats[6] = {&plain, &film, &thin, &none, &tex_black, &tex_white};
    uint8_t *px[6];
    uint32_t f[6];
    for (int k = 0; k < 6; ++k) {
        mvr_material_desc md = *mats[k];
        px[k] = render_lit_sphere(t, ctx, vs, &md, k >= 4 ? (k == 4 ? black : white) : NULL, TW,
                                  &md.iridescence.thickness_texture, MVR_MATERIAL_PATH_ARRAYS, &f[k]);
    }
    /* the texture from its own 2D texture: the array's bytes */
    mvr_material_desc md = tex_black;
    uint32_t fp;
    uint8_t *per = render_lit_sphere(t, ctx, vs, &md, black, TW, &md.iridescence.thickness_texture,
                                     MVR_MATERIAL_PATH_PER_MATERIAL, &fp);
    if (per && px[4])
        CHECK_EQ_INT(t, count_diff(per, px[4], (size_t)W * H, 0), 0);
    free(per);
    CHECK(t, !(f[0] & MVR_FEATURE_IRIDESCENCE) && (f[1] & MVR_FEATURE_IRIDESCENCE) &&
                 !(f[3] & MVR_FEATURE_IRIDESCENCE));
    if (px[0] && px[1] && px[2] && px[3] && px[4] && px[5]) {
        uint32_t changed = count_diff(px[0], px[1], (size_t)W * H, 2);
        printf("  a 600 nm film changes %u pixels; 0 nm changes %u\n", changed, count_diff(px[0], px[3], (size_t)W * H, 0));
        CHECK(t, changed > 500);
        CHECK_EQ_INT(t, count_diff(px[0], px[3], (size_t)W * H, 0), 0);
        CHECK_EQ_INT(t, count_diff(px[4], px[2], (size_t)W * H, 0), 0);
        CHECK_EQ_INT(t, count_diff(px[5], px[1], (size_t)W * H, 0), 0);
        CHECK(t, count_diff(px[2], px[1], (size_t)W * H, 2) > 100);
    }
    for (int k = 0; k < 6; ++k)
        free(px[k]);
    multiview_equals_loop(t, ctx, &film);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

/* KHR_materials_anisotropy: the stretched lobe changes the highlight; a
 * half turn of the direction changes nothing (the lobe is symmetric, within
 * 1/255), a quarter turn does; a texture direction (0, 1) is the quarter turn
 * (within 2/255: 128/255 is not exactly 0.5); multiview and loop, arrays and
 * per-material textures give the same bytes. */
static void anisotropy_direction(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    enum { TW = 8 };
    static uint8_t up[TW * TW * 4];
    for (int i = 0; i < TW * TW; ++i) {
        up[i * 4 + 0] = 128;
        up[i * 4 + 1] = up[i * 4 + 2] = up[i * 4 + 3] = 255;
    }
    mvr_view_set *vs = front_views(t, 1);
    mvr_material_desc iso = mvr_material_defaults();
    iso.base_color_factor[0] = 0.9f;
    iso.base_color_factor[1] = 0.7f;
    iso.base_color_factor[2] = 0.4f;
    iso.metallic_factor = 1.0f;
    iso.roughness_factor = 0.3f;
    mvr_material_desc a0 = iso, a_half = iso, a_quarter = iso, a_tex = iso;
    a0.anisotropy.strength = a_half.anisotropy.strength = a_quarter.anisotropy.strength = a_tex.anisotropy.strength =
        0.8f;
    a_half.anisotropy.rotation = 3.14159265f;
    a_quarter.anisotropy.rotation = 1.57079633f;
    const mvr_material_desc *mats[5] = {&iso, &a0, &a_half, &a_quarter, &a_tex};
    uint8_t *px[5];
    uint32_t f[5];
    for (int k = 0; k < 5; ++k) {
        mvr_material_desc md = *mats[k];
        px[k] = render_lit_sphere(t, ctx, vs, &md, k == 4 ? up : NULL, TW, &md.anisotropy.texture,
                                  MVR_MATERIAL_PATH_ARRAYS, &f[k]);
    }
    /* the texture from its own 2D texture: the array's bytes */
    mvr_material_desc md = a_tex;
    uint32_t fp;
    uint8_t *per = render_lit_sphere(t, ctx, vs, &md, up, TW, &md.anisotropy.texture, MVR_MATERIAL_PATH_PER_MATERIAL,
                                     &fp);
    if (per && px[4])
        CHECK_EQ_INT(t, count_diff(per, px[4], (size_t)W * H, 0), 0);
    free(per);
    CHECK(t, !(f[0] & MVR_FEATURE_ANISOTROPY) && (f[1] & MVR_FEATURE_ANISOTROPY));
    if (px[0] && px[1] && px[2] && px[3] && px[4]) {
        uint32_t stretched = count_diff(px[0], px[1], (size_t)W * H, 2);
        uint32_t half = count_diff(px[1], px[2], (size_t)W * H, 1);
        uint32_t quarter = count_diff(px[1], px[3], (size_t)W * H, 2);
        uint32_t tex = count_diff(px[3], px[4], (size_t)W * H, 2);
        printf("  anisotropy 0.8 changes %u pixels; a half turn %u, a quarter turn %u; texture vs quarter %u\n",
               stretched, half, quarter, tex);
        CHECK(t, stretched > 200);
        CHECK_EQ_INT(t, half, 0);
        CHECK(t, quarter > 200);
        CHECK(t, tex <= (uint32_t)(W * H / 100));
    }
    for (int k = 0; k < 5; ++k)
        free(px[k]);
    multiview_equals_loop(t, ctx, &a_quarter);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(demos_compile_no_extension_code), TEST(core_values_give_the_core_pixels),
              TEST(clearcoat_mixes_by_its_fresnel), TEST(extension_textures_are_sampled),
              TEST(spec_gloss_is_a_dielectric), TEST(spec_gloss_textures_are_srgb), TEST(iridescence_film), TEST(anisotropy_direction))
