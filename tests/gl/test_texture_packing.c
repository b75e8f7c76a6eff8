/* gl: the load-time texture packing (core/texture_packing.c) gives the same
 * pixels for fewer fetches and varyings.
 * - A sphere whose material samples separate metallic-roughness and
 *   occlusion images, the occlusion by texture coordinate set 1 (a copy of
 *   set 0, as DamagedHelmet's): after mvr_scene_fold_texcoords and
 *   mvr_scene_pack_occlusion the programs lose the occlusion texture and the
 *   second coordinate set, and every path (arrays, per material; multiview,
 *   loop) gives the unpacked scene's bytes. Under a uniform environment, so
 *   that occlusion darkens the picture: the same scene with occlusion
 *   strength 0 must differ (the comparison can fail).
 * - A material whose occlusion is its metallic-roughness texture (ORM, as
 *   exporters pack it) samples it once and gives the bytes of the same
 *   texels sampled twice (from a copy of the image). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "demo_builder.h"
#include "gl_test_util.h"
#include "mvr/mvr.h"
#include "render_views.h"
#include "skin_render.h"
#include "scene_internal.h"
#include "shader_gen.h"

#define W 64
#define H 64
#define TS 32

/* Noise in every channel, a different pattern per seed. */
static void noise(uint8_t *px, uint32_t seed)
{
    uint32_t x = seed * 2654435761u + 1u;
    for (size_t i = 0; i < (size_t)TS * TS * 4; ++i) {
        x ^= x << 13, x ^= x >> 17, x ^= x << 5;
        px[i] = (uint8_t)(x >> 24);
    }
}

typedef enum occlusion_image {
    OCCLUSION_IS_METAL_ROUGH, /* the metallic-roughness image, the same ref */
    OCCLUSION_NOISE,          /* an image of its own */
    OCCLUSION_COPY            /* an image of its own with the metallic-roughness image's texels */
} occlusion_image;

/* A sphere with texture coordinate set 1 a copy of set 0, material md, lit
 * by one directional light. */
static mvr_scene *sphere(mvr_test_state *t, mvr_material_desc md, occlusion_image occlusion)
{
    static uint8_t mr[TS * TS * 4], ao[TS * TS * 4];
    noise(mr, 1);
    noise(ao, 2);
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    mvr_image_desc dm = {.width = TS, .height = TS, .rgba8 = mr, .name = "mr"};
    mvr_image_desc da = {.width = TS, .height = TS, .rgba8 = ao, .name = "ao"};
    CHECK(t, mvr_scene_add_image(s, &dm, &md.metallic_roughness.image) == MVR_OK);
    if (occlusion == OCCLUSION_COPY)
        da.rgba8 = mr;
    if (occlusion == OCCLUSION_IS_METAL_ROUGH)
        md.occlusion = md.metallic_roughness;
    else
        CHECK(t, mvr_scene_add_image(s, &da, &md.occlusion.image) == MVR_OK);
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, &md, &mat) == MVR_OK);
    demo_mesh m;
    memset(&m, 0, sizeof m);
    demo_sphere(&m, 1.0f, 48, 24);
    mvr_primitive_desc p = {.vertex_count = m.vertex_count, .positions = m.positions, .normals = m.normals,
                            .tangents = m.tangents, .texcoords0 = m.uv0, .texcoords1 = m.uv0,
                            .index_count = m.index_count, .indices32 = m.indices, .material = mat};
    mvr_mesh_desc mesh = {.primitives = &p, .primitive_count = 1, .name = "sphere"};
    mvr_mesh_id mid;
    CHECK(t, mvr_scene_add_mesh(s, &mesh, &mid) == MVR_OK);
    demo_mesh_free(&m);
    mvr_node_desc nd = {.mesh = mid};
    mvr_node_id n;
    CHECK(t, mvr_scene_add_node(s, &nd, &n) == MVR_OK);
    render_views_add_sun(t, s);
    return s;
}

static mvr_view_set *two_views(mvr_test_state *t)
{
    mvr_view_desc v[2];
    memset(v, 0, sizeof v);
    for (uint32_t i = 0; i < 2; ++i) {
        double eye[3] = {0.4 * i, 0.2, 3.0}, at[3] = {0, 0, 0}, up[3] = {0, 1, 0};
        mvr_view_look_at(&v[i], eye, at, up);
        v[i].projection.yfov = 0.8;
    }
    mvr_view_set_desc vd = {.view_count = 2, .views = v};
    mvr_view_set *vs = NULL;
    CHECK(t, mvr_view_set_create(&vd, &vs, NULL) == MVR_OK);
    return vs;
}

static render_views_out draw(mvr_test_state *t, mvr_context *ctx, mvr_scene *s, mvr_view_set *vs, mvr_view_path vp,
                             mvr_material_path mp)
{
    render_views_opts o = {.width = W, .height = H, .path = vp, .material_path = mp, .environment = true,
                           .environment_source = MVR_ENVIRONMENT_UNIFORM};
    return render_views(t, ctx, s, vs, &o);
}

static mvr_material_desc rough_metal(void)
{
    mvr_material_desc md = mvr_material_defaults();
    md.base_color_factor[0] = 0.8f;
    md.base_color_factor[1] = 0.6f;
    md.base_color_factor[2] = 0.3f;
    md.occlusion_strength = 1.0f;
    return md;
}

static void packing_gives_the_same_pixels(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_view_set *vs = two_views(t);
    mvr_material_desc md = rough_metal();
    md.occlusion.texcoord = 1;
    mvr_scene *apart = sphere(t, md, OCCLUSION_NOISE), *packed = sphere(t, md, OCCLUSION_NOISE);
    mvr_material_desc none = md;
    none.occlusion_strength = 1e-6f; /* 0 means the default, 1 */
    mvr_scene *unoccluded = sphere(t, none, OCCLUSION_NOISE);
    CHECK_EQ_INT(t, mvr_scene_fold_texcoords(packed), 1);
    CHECK_EQ_INT(t, mvr_scene_pack_occlusion(packed), 1);
    static const mvr_view_path vps[2] = {MVR_VIEW_PATH_MULTIVIEW, MVR_VIEW_PATH_LOOP};
    static const mvr_material_path mps[2] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL};
    for (int v = 0; v < 2; ++v)
        for (int k = 0; k < 2; ++k) {
            render_views_out a = draw(t, ctx, apart, vs, vps[v], mps[k]);
            render_views_out b = draw(t, ctx, packed, vs, vps[v], mps[k]);
            render_views_out c = draw(t, ctx, unoccluded, vs, vps[v], mps[k]);
            if (a.pixels && b.pixels && c.pixels) {
                size_t n = (size_t)W * H * 2;
                uint32_t same = count_diff(a.pixels, b.pixels, n, 0) == 0;
                uint32_t occluded = count_diff(a.pixels, c.pixels, n, 0);
                printf("  %s/%s: packed %s; %u of %zu pixels differ without occlusion\n",
                       v ? "loop" : "multiview", k ? "per_material" : "arrays", same ? "same bytes" : "DIFFERS",
                       occluded, n);
                CHECK(t, same);
                CHECK(t, occluded > n / 10);
                /* the packed scene's programs sample no occlusion texture and read no second coordinate set */
                CHECK(t, (a.features & MVR_FEATURE_OCCLUSION_TEX) && (a.features & MVR_FEATURE_UV1));
                CHECK(t, !(b.features & (MVR_FEATURE_OCCLUSION_TEX | MVR_FEATURE_UV1)));
            }
            free(a.pixels);
            free(b.pixels);
            free(c.pixels);
        }
    mvr_scene_destroy(apart);
    mvr_scene_destroy(packed);
    mvr_scene_destroy(unoccluded);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

static void orm_texture_is_fetched_once(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_view_set *vs = two_views(t);
    mvr_material_desc md = rough_metal();
    mvr_scene *orm = sphere(t, md, OCCLUSION_IS_METAL_ROUGH), *twice = sphere(t, md, OCCLUSION_COPY);
    render_views_out a = draw(t, ctx, twice, vs, MVR_VIEW_PATH_MULTIVIEW, MVR_MATERIAL_PATH_PER_MATERIAL);
    render_views_out b = draw(t, ctx, orm, vs, MVR_VIEW_PATH_MULTIVIEW, MVR_MATERIAL_PATH_PER_MATERIAL);
    if (a.pixels && b.pixels) {
        uint32_t differ = count_diff(a.pixels, b.pixels, (size_t)W * H * 2, 0);
        printf("  ORM fetched once: %u pixels differ from fetched twice\n", differ);
        CHECK_EQ_INT(t, differ, 0);
        CHECK(t, (a.features & MVR_FEATURE_OCCLUSION_TEX) != 0);
        CHECK(t, !(b.features & MVR_FEATURE_OCCLUSION_TEX) && (b.features & MVR_FEATURE_METAL_ROUGH_TEX));
    }
    free(a.pixels);
    free(b.pixels);
    mvr_scene_destroy(orm);
    mvr_scene_destroy(twice);
    mvr_view_set_destroy(vs);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(packing_gives_the_same_pixels), TEST(orm_texture_is_fetched_once))
