/* core: load-time texture packing (core/texture_packing.c) and the
 * material's occlusion-in-metallic-roughness test (core/material.c): what
 * is packed, what is left alone because it would change pixels. The pixels
 * themselves: tests/gl/test_texture_packing.c. */
#include <string.h>

#include "block_layout.h"
#include "material.h"
#include "mvr_test.h"
#include "scene_internal.h"

#define TS 8

static uint8_t mr_px[TS * TS * 4], ao_px[TS * TS * 4], small_px[4 * 4 * 4];

static void fill(void)
{
    for (size_t i = 0; i < sizeof mr_px; ++i) {
        mr_px[i] = (uint8_t)(i * 7 + 3);
        ao_px[i] = (uint8_t)(255 - i * 5);
    }
    memset(small_px, 90, sizeof small_px);
}

static mvr_image_id image(mvr_test_state *t, mvr_scene *s, const uint8_t *px, uint32_t size)
{
    mvr_image_desc d = {.width = size, .height = size, .rgba8 = px};
    mvr_image_id id = {0};
    CHECK(t, mvr_scene_add_image(s, &d, &id) == MVR_OK);
    return id;
}

/* One triangle with material `mat`; uv1 NULL for none. */
static void triangle(mvr_test_state *t, mvr_scene *s, mvr_material_id mat, const float *uv1)
{
    static const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, uv0[6] = {0, 0, 1, 0, 0, 1};
    mvr_primitive_desc p = {.vertex_count = 3, .positions = pos, .texcoords0 = uv0, .texcoords1 = uv1,
                            .material = mat};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1};
    mvr_mesh_id id;
    CHECK(t, mvr_scene_add_mesh(s, &md, &id) == MVR_OK);
}

static const mvr_material_desc *material(const mvr_scene *s, mvr_material_id id)
{
    return &s->materials[id.id - 1].desc;
}

static void occlusion_in_metal_rough_needs_the_same_fetch(mvr_test_state *t)
{
    mvr_material_desc m = mvr_material_defaults();
    m.metallic_roughness.image.id = 1;
    CHECK(t, !mvr_material_occlusion_in_metal_rough(&m)); /* no occlusion */
    m.occlusion = m.metallic_roughness;
    CHECK(t, mvr_material_occlusion_in_metal_rough(&m));
    CHECK(t, !mvr_material_samples_role(&m, MVR_ROLE_OCCLUSION));
    CHECK(t, mvr_material_samples_role(&m, MVR_ROLE_METAL_ROUGH));
    uint8_t block[MVR_MATERIAL_BLOCK_SIZE];
    mvr_material_pack(&m, NULL, block);
    int32_t has;
    memcpy(&has, block + MVR_MATERIAL_UV_OFFSET + 12, sizeof has);
    CHECK(t, ((uint32_t)has >> MVR_MATERIAL_OCCLUSION_IN_METAL_ROUGH_BIT) & 1u);
    CHECK(t, !(((uint32_t)has >> MVR_ROLE_OCCLUSION) & 1u) && (((uint32_t)has >> MVR_ROLE_METAL_ROUGH) & 1u));

    /* anything that fetches other texels keeps its own fetch */
    mvr_material_desc other[4] = {m, m, m, m};
    other[0].occlusion.texcoord = 1;
    other[1].occlusion.sampler.wrap_s = MVR_WRAP_CLAMP_TO_EDGE;
    other[2].occlusion.transform.enabled = true;
    other[3].spec_gloss.enabled = true; /* no metallic-roughness fetch */
    for (int k = 0; k < 4; ++k) {
        CHECK(t, !mvr_material_occlusion_in_metal_rough(&other[k]));
        CHECK(t, mvr_material_samples_role(&other[k], MVR_ROLE_OCCLUSION));
        mvr_material_pack(&other[k], NULL, block);
        memcpy(&has, block + MVR_MATERIAL_UV_OFFSET + 12, sizeof has);
        CHECK(t, !(((uint32_t)has >> MVR_MATERIAL_OCCLUSION_IN_METAL_ROUGH_BIT) & 1u));
    }
}

static void separate_occlusion_moves_into_the_red_channel(mvr_test_state *t)
{
    fill();
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    mvr_material_desc m = mvr_material_defaults();
    m.metallic_roughness.image = image(t, s, mr_px, TS);
    m.occlusion.image = image(t, s, ao_px, TS);
    mvr_material_id a, b;
    CHECK(t, mvr_scene_add_material(s, &m, &a) == MVR_OK);
    mvr_material_desc mr_only = mvr_material_defaults(); /* reads no red: may share the image */
    mr_only.metallic_roughness.image = m.metallic_roughness.image;
    CHECK(t, mvr_scene_add_material(s, &mr_only, &b) == MVR_OK);
    uint64_t hash = s->images[0].hash;
    CHECK_EQ_INT(t, mvr_scene_pack_occlusion(s), 1);
    const uint8_t *px = s->images[0].rgba;
    uint32_t wrong = 0;
    for (size_t i = 0; i < (size_t)TS * TS; ++i)
        wrong += px[4 * i] != ao_px[4 * i] || memcmp(px + 4 * i + 1, mr_px + 4 * i + 1, 3) != 0;
    CHECK_EQ_INT(t, wrong, 0);
    CHECK(t, s->images[0].hash != hash);
    CHECK_EQ_INT(t, material(s, a)->occlusion.image.id, m.metallic_roughness.image.id);
    CHECK(t, mvr_material_occlusion_in_metal_rough(material(s, a)));
    CHECK_EQ_INT(t, material(s, b)->occlusion.image.id, 0);
    CHECK_EQ_INT(t, mvr_scene_pack_occlusion(s), 0); /* done: nothing left apart */
    mvr_scene_destroy(s);
}

/* Cases the packing must leave alone (each would change some pixel). */
static void packing_leaves_alone_what_would_change(mvr_test_state *t)
{
    fill();
    for (int k = 0; k < 5; ++k) {
        mvr_scene *s = NULL;
        CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
        mvr_material_desc m = mvr_material_defaults();
        m.metallic_roughness.image = image(t, s, mr_px, TS);
        m.occlusion.image = image(t, s, k == 0 ? small_px : ao_px, k == 0 ? 4 : TS);
        mvr_material_desc other = mvr_material_defaults();
        const char *why = "";
        switch (k) {
        case 0: why = "sizes differ"; break;
        case 1:
            why = "the image is also another material's base color";
            other.base_color.image = m.metallic_roughness.image;
            break;
        case 2:
            why = "another material pairs the image with another occlusion image";
            other.metallic_roughness.image = m.metallic_roughness.image;
            other.occlusion.image = image(t, s, small_px, 4);
            break;
        case 3:
            why = "the occlusion is fetched with another sampler";
            m.occlusion.sampler.min_filter = MVR_FILTER_NEAREST;
            break;
        case 4:
            why = "another material reads the image's red as its occlusion";
            other.metallic_roughness.image = m.metallic_roughness.image;
            other.occlusion.image = m.metallic_roughness.image;
            break;
        }
        mvr_material_id a, b;
        CHECK(t, mvr_scene_add_material(s, &m, &a) == MVR_OK && mvr_scene_add_material(s, &other, &b) == MVR_OK);
        uint32_t packed = mvr_scene_pack_occlusion(s);
        CHECK_MSG(t, packed == 0, "packed although %s", why);
        CHECK_MSG(t, memcmp(s->images[0].rgba, mr_px, sizeof mr_px) == 0, "pixels changed although %s", why);
        CHECK_EQ_INT(t, material(s, a)->occlusion.image.id, m.occlusion.image.id);
        mvr_scene_destroy(s);
    }
}

static void texcoords_fold_where_every_primitive_repeats_them(mvr_test_state *t)
{
    static const float same[6] = {0, 0, 1, 0, 0, 1}, other[6] = {0, 0, 0.5f, 0, 0, 0.5f};
    for (int k = 0; k < 3; ++k) {
        mvr_scene *s = NULL;
        CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
        mvr_material_desc m = mvr_material_defaults();
        m.occlusion.image = image(t, s, ao_px, TS);
        m.occlusion.texcoord = 1;
        mvr_material_id mat;
        CHECK(t, mvr_scene_add_material(s, &m, &mat) == MVR_OK);
        triangle(t, s, mat, same);
        if (k == 1)
            triangle(t, s, mat, other); /* a second primitive whose set 1 differs */
        if (k == 2)
            triangle(t, s, mat, NULL);  /* one without set 1: its occlusion is not sampled */
        CHECK_EQ_INT(t, mvr_scene_fold_texcoords(s), k == 0 ? 1 : 0);
        CHECK_EQ_INT(t, material(s, mat)->occlusion.texcoord, k == 0 ? 0 : 1);
        mvr_scene_destroy(s);
    }
}

MVR_TEST_MAIN(TEST(occlusion_in_metal_rough_needs_the_same_fetch), TEST(separate_occlusion_moves_into_the_red_channel),
              TEST(packing_leaves_alone_what_would_change), TEST(texcoords_fold_where_every_primitive_repeats_them))
