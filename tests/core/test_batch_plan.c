/* core: the batch plan groups images into texture arrays by compatibility,
 * records why images split off, respects the layer limit, shares layers of
 * duplicate images, and fills roles a material lacks with a white layer. */
#include "batch_plan.h"
#include "shader_gen.h"
#include "mvr_test.h"

static mvr_image_id add_image(mvr_scene *s, uint32_t w, uint32_t h, uint8_t value)
{
    uint8_t *px = malloc((size_t)w * h * 4);
    memset(px, value, (size_t)w * h * 4);
    mvr_image_desc d = {.width = w, .height = h, .rgba8 = px, .name = "test"};
    mvr_image_id id = {0};
    mvr_scene_add_image(s, &d, &id);
    free(px);
    return id;
}

static mvr_material_id add_material(mvr_scene *s, mvr_image_id base, mvr_sampler_desc sampler)
{
    mvr_material_desc m = mvr_material_defaults();
    m.base_color.image = base;
    m.base_color.sampler = sampler;
    mvr_material_id id = {0};
    mvr_scene_add_material(s, &m, &id);
    return id;
}

static const mvr_sampler_desc DEFAULT_SAMPLER = {0};

static bool has_note(const mvr_batch_plan *p, const char *part)
{
    for (uint32_t i = 0; i < p->note_count; ++i)
        if (strstr(p->notes[i], part))
            return true;
    return false;
}

/* A 16x16 ETC2 RGB8 image of `levels` levels, every block byte `value`. */
static mvr_image_id add_etc2(mvr_scene *s, uint32_t levels, uint8_t value)
{
    static uint8_t blocks[16 * 8];
    memset(blocks, value, sizeof blocks);
    mvr_image_desc d = {.width = 16, .height = 16, .name = "etc2", .format = MVR_IMAGE_FORMAT_ETC2_RGB8,
                        .level_count = levels};
    for (uint32_t k = 0; k < levels; ++k) {
        uint64_t n = 0;
        mvr_image_level_size(MVR_IMAGE_FORMAT_ETC2_RGB8, 16, 16, k, &n);
        d.levels[k].data = blocks;
        d.levels[k].size = (size_t)n;
    }
    mvr_image_id id = {0};
    mvr_scene_add_image(s, &d, &id);
    return id;
}

/* Block images group by (format, size, levels) apart from RGBA8 ones; the
 * same blocks share a layer; a mipmapped sampler keeps the file's levels,
 * a plain one level 0 alone; a format the GL cannot sample reads the neutral
 * layer of a 1 x 1 RGBA8 group, with a note. */
static void block_formats_group_apart(mvr_test_state *t)
{
    mvr_scene *s = NULL;
    mvr_scene_create(NULL, &s, NULL);
    mvr_image_id a = add_etc2(s, 3, 1), b = add_etc2(s, 3, 1), c = add_etc2(s, 5, 2);
    CHECK(t, a.id && b.id && c.id);
    add_material(s, a, DEFAULT_SAMPLER);
    add_material(s, b, DEFAULT_SAMPLER);
    add_material(s, c, DEFAULT_SAMPLER);
    add_material(s, add_image(s, 16, 16, 7), DEFAULT_SAMPLER);
    mvr_sampler_desc linear = {.min_filter = MVR_FILTER_LINEAR};
    add_material(s, c, linear);
    mvr_batch_plan p = {0};
    CHECK(t, mvr_batch_plan_build(&p, s, 2048) == MVR_OK);
    /* etc2 3 levels (a, b share a layer), etc2 5 levels, rgba8 (+ white), etc2 1 level */
    CHECK_EQ_INT(t, p.group_count, 4);
    CHECK_EQ_INT(t, p.materials[0].group[0], p.materials[1].group[0]);
    CHECK_EQ_INT(t, p.materials[0].layer[0], p.materials[1].layer[0]);
    const mvr_texture_group *g0 = &p.groups[p.materials[0].group[0]], *g2 = &p.groups[p.materials[2].group[0]];
    const mvr_texture_group *g3 = &p.groups[p.materials[3].group[0]], *g4 = &p.groups[p.materials[4].group[0]];
    CHECK(t, g0->format == MVR_IMAGE_FORMAT_ETC2_RGB8 && g0->levels == 3 && g0->layer_count == 1);
    CHECK(t, g2->format == MVR_IMAGE_FORMAT_ETC2_RGB8 && g2->levels == 5 && g2 != g0);
    CHECK(t, g3->format == MVR_IMAGE_FORMAT_RGBA8 && g3->neutral_layer != MVR_NO_INDEX);
    CHECK(t, g4->format == MVR_IMAGE_FORMAT_ETC2_RGB8 && g4->levels == 1);
    CHECK(t, g0->neutral_layer == MVR_NO_INDEX && g2->neutral_layer == MVR_NO_INDEX);
    CHECK(t, has_note(&p, "mip count 5 differs"));
    CHECK(t, has_note(&p, "format rgba8 differs"));
    /* the GL samples no ETC2: every block image reads the neutral layer of one 1 x 1 group */
    CHECK(t, mvr_batch_plan_build_for(&p, s, 2048, 1u << MVR_IMAGE_FORMAT_RGBA8) == MVR_OK);
    const mvr_texture_group *n = &p.groups[p.materials[0].group[0]];
    CHECK(t, n->format == MVR_IMAGE_FORMAT_RGBA8 && n->width == 1 && n->height == 1);
    CHECK_EQ_INT(t, p.materials[0].layer[0], n->neutral_layer);
    CHECK(t, has_note(&p, "etc2_rgb8 cannot be sampled"));
    mvr_batch_plan_free(&p);
    mvr_scene_destroy(s);
}


static void one_material(mvr_test_state *t)
{
    mvr_scene *s = NULL;
    mvr_scene_create(NULL, &s, NULL);
    add_material(s, add_image(s, 16, 16, 10), DEFAULT_SAMPLER);
    mvr_batch_plan p = {0};
    CHECK(t, mvr_batch_plan_build(&p, s, 2048) == MVR_OK);
    CHECK_EQ_INT(t, p.group_count, 1);
    CHECK_EQ_INT(t, p.groups[0].layer_count, 2); /* the image + a white layer for the default material */
    CHECK(t, p.groups[0].srgb && p.groups[0].levels == 5);
    CHECK_EQ_INT(t, p.materials[0].group[0], 0);
    CHECK_EQ_INT(t, p.materials[0].layer[0], 0);
    CHECK_EQ_INT(t, p.materials[1].layer[0], p.groups[0].neutral_layer); /* default material */
    CHECK_EQ_INT(t, p.materials[0].group[2], MVR_NO_GROUP);             /* no normal maps anywhere */
    CHECK_EQ_INT(t, mvr_batch_plan_neutral_features(&p, 0), 0);
    CHECK_EQ_INT(t, mvr_batch_plan_neutral_features(&p, 1), MVR_FEATURE_BASE_COLOR_TEX);
    CHECK_EQ_INT(t, p.note_count, 0);
    mvr_batch_plan_free(&p);
    mvr_scene_destroy(s);
}

static void same_size_shares_different_splits(mvr_test_state *t)
{
    mvr_scene *s = NULL;
    mvr_scene_create(NULL, &s, NULL);
    for (int i = 0; i < 4; ++i)
        add_material(s, add_image(s, 32, 32, (uint8_t)i), DEFAULT_SAMPLER);      /* one group, 4 layers */
    add_material(s, add_image(s, 64, 32, 9), DEFAULT_SAMPLER);                  /* size */
    mvr_sampler_desc clamp = {MVR_FILTER_NEAREST, MVR_FILTER_NEAREST, MVR_WRAP_CLAMP_TO_EDGE, MVR_WRAP_CLAMP_TO_EDGE};
    add_material(s, add_image(s, 32, 32, 20), clamp);                           /* sampler (and mip count) */
    mvr_sampler_desc mip_clamp = {0, 0, MVR_WRAP_CLAMP_TO_EDGE, 0};
    add_material(s, add_image(s, 32, 32, 21), mip_clamp);                       /* sampler only */
    mvr_material_desc lin = mvr_material_defaults();                            /* format: linear role */
    lin.metallic_roughness.image = add_image(s, 32, 32, 30);
    mvr_material_id mid;
    mvr_scene_add_material(s, &lin, &mid);
    mvr_batch_plan p = {0};
    CHECK(t, mvr_batch_plan_build(&p, s, 2048) == MVR_OK);
    /* base color: 32x32 default, 64x32, 32x32 nearest, 32x32 clamp; metal-rough: 1 */
    CHECK_EQ_INT(t, p.group_count, 5);
    for (int i = 1; i < 4; ++i)
        CHECK_EQ_INT(t, p.materials[i].group[0], p.materials[0].group[0]);
    CHECK(t, p.materials[4].group[0] != p.materials[0].group[0]);
    CHECK(t, p.materials[5].group[0] != p.materials[0].group[0]);
    CHECK(t, p.materials[6].group[0] != p.materials[5].group[0]);
    CHECK(t, has_note(&p, "size 64x32 differs from group 0 (32x32)"));
    CHECK(t, has_note(&p, "mip count 1 differs"));
    CHECK(t, has_note(&p, "sampler"));
    CHECK(t, !p.groups[p.materials[7].group[1]].srgb && p.groups[p.materials[0].group[0]].srgb);
    mvr_batch_plan_free(&p);
    mvr_scene_destroy(s);
}

static void layer_limit_splits(mvr_test_state *t)
{
    mvr_scene *s = NULL;
    mvr_scene_create(NULL, &s, NULL);
    for (int i = 0; i < 7; ++i)
        add_material(s, add_image(s, 8, 8, (uint8_t)(i * 10)), DEFAULT_SAMPLER);
    mvr_batch_plan p = {0};
    CHECK(t, mvr_batch_plan_build(&p, s, 4) == MVR_OK);
    CHECK_EQ_INT(t, p.group_count, 2); /* 4 + 3 (+ the white layer) */
    for (uint32_t g = 0; g < p.group_count; ++g)
        CHECK(t, p.groups[g].layer_count <= 4);
    CHECK(t, has_note(&p, "is full (GL_MAX_ARRAY_TEXTURE_LAYERS)"));
    mvr_batch_plan_free(&p);
    mvr_scene_destroy(s);
}

static void duplicate_images_share_a_layer(mvr_test_state *t)
{
    mvr_scene *s = NULL;
    mvr_scene_create(NULL, &s, NULL);
    mvr_image_id a = add_image(s, 16, 16, 7);
    mvr_image_id b = add_image(s, 16, 16, 7); /* the same pixels, another image */
    mvr_image_id c = add_image(s, 16, 16, 8);
    add_material(s, a, DEFAULT_SAMPLER);
    add_material(s, a, DEFAULT_SAMPLER); /* the same source */
    add_material(s, b, DEFAULT_SAMPLER);
    add_material(s, c, DEFAULT_SAMPLER);
    mvr_batch_plan p = {0};
    CHECK(t, mvr_batch_plan_build(&p, s, 2048) == MVR_OK);
    CHECK_EQ_INT(t, p.group_count, 1);
    CHECK_EQ_INT(t, p.materials[0].layer[0], p.materials[1].layer[0]);
    CHECK_EQ_INT(t, p.materials[0].layer[0], p.materials[2].layer[0]);
    CHECK(t, p.materials[3].layer[0] != p.materials[0].layer[0]);
    CHECK_EQ_INT(t, p.groups[0].layer_count, 3); /* a, c, white */
    CHECK(t, mvr_batch_plan_group_key(&p, 0) == mvr_batch_plan_group_key(&p, 3));
    mvr_batch_plan_free(&p);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(one_material), TEST(same_size_shares_different_splits), TEST(layer_limit_splits),
              TEST(duplicate_images_share_a_layer), TEST(block_formats_group_apart))
