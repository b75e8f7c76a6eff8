/* core: materials (core/material.c): the extensions' feature bits, the
 * texture roles' fields of the std140 block, transform slots. */
#include <math.h>
#include <string.h>

#include "frame.h"
#include "material.h"
#include "mvr_test.h"
#include "scene_internal.h"
#include "shader_gen.h"

static int32_t block_int(const uint8_t *b, uint32_t offset)
{
    int32_t v;
    memcpy(&v, b + offset, sizeof v);
    return v;
}

static float block_float(const uint8_t *b, uint32_t offset)
{
    float v;
    memcpy(&v, b + offset, sizeof v);
    return v;
}

/* Each extension sets its bit only where the material departs from glTF
 * 2.0's core values; the ones drawn by the specular extension's code set
 * SPECULAR with theirs. */
static void extension_bits_follow_departures(mvr_test_state *t)
{
    mvr_material_desc m = mvr_material_defaults();
    CHECK_EQ_INT(t, mvr_material_extension_features(&m), 0);
    m.iridescence.factor = 1.0f; /* the defaults' 400 nm film */
    CHECK_EQ_INT(t, mvr_material_extension_features(&m), MVR_FEATURE_IRIDESCENCE | MVR_FEATURE_SPECULAR);
    m.iridescence.thickness_maximum = 0.0f; /* no film */
    CHECK_EQ_INT(t, mvr_material_extension_features(&m), 0);
    m = mvr_material_defaults();
    m.sheen.roughness_factor = 0.5f; /* black sheen: none */
    m.clearcoat.roughness_factor = 0.5f;
    m.volume.thickness_factor = 1.0f; /* a volume without transmission shows nothing */
    CHECK_EQ_INT(t, mvr_material_extension_features(&m), 0);
    m.sheen.color_factor[1] = 0.1f;
    m.transmission.factor = 0.5f;
    m.anisotropy.strength = 0.2f;
    CHECK_EQ_INT(t, mvr_material_extension_features(&m),
                 MVR_FEATURE_SHEEN | MVR_FEATURE_TRANSMISSION | MVR_FEATURE_ANISOTROPY | MVR_FEATURE_SPECULAR);
    m = mvr_material_defaults();
    m.spec_gloss.enabled = true;
    m.metallic_roughness.image.id = 1;
    CHECK_EQ_INT(t, mvr_material_extension_features(&m), MVR_FEATURE_SPEC_GLOSS | MVR_FEATURE_SPECULAR);
    CHECK(t, !mvr_material_samples_role(&m, MVR_ROLE_METAL_ROUGH)); /* spec-gloss has its own roughness */
    /* unlit draws none of them */
    float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    scene_primitive p;
    memset(&p, 0, sizeof p);
    p.positions = tri;
    p.normals = tri;
    m.unlit = true;
    CHECK_EQ_INT(t, mvr_draw_features(&p, &m) & (MVR_FEATURE_SPEC_GLOSS | MVR_FEATURE_SPECULAR), 0);
}

/* The block: per role a 16-bit layer, 4 uv bits (TEXCOORD_1, transform
 * slot) and a has-texture bit, only for roles the material samples;
 * identical transforms share a slot. */
static void roles_pack_into_the_block(mvr_test_state *t)
{
    mvr_material_desc m = mvr_material_defaults();
    mvr_texture_transform tr = {true, {0.5f, 0.25f}, 0.0f, {2.0f, 2.0f}};
    m.base_color.image.id = 1;
    m.emissive.image.id = 2;
    m.emissive.texcoord = 1;
    m.emissive.transform = tr;
    m.clearcoat.factor = 1.0f;
    m.clearcoat.normal_texture.image.id = 3;
    m.clearcoat.normal_texture.transform = tr; /* the emissive's slot */
    m.sheen.color_texture.image.id = 4;        /* sheen is black: not sampled */
    uint16_t layers[MVR_ROLE_COUNT];
    for (uint32_t r = 0; r < MVR_ROLE_COUNT; ++r)
        layers[r] = (uint16_t)(100 + r);
    layers[MVR_ROLE_METAL_ROUGH] = 7; /* a white layer the batch plan gave (no texture) */
    uint8_t b[MVR_MATERIAL_BLOCK_SIZE];
    mvr_material_pack(&m, layers, b);
    /* layers: role r in the 16-bit half (r % 2) of int r / 2 */
    int32_t w0 = block_int(b, MVR_MATERIAL_LAYERS_OFFSET);
    CHECK_EQ_INT(t, w0 & 0xFFFF, 100);
    CHECK_EQ_INT(t, (w0 >> 16) & 0xFFFF, 7);
    int32_t w3 = block_int(b, MVR_MATERIAL_LAYERS_OFFSET + 3 * 4); /* roles 6, 7 */
    CHECK_EQ_INT(t, (w3 >> 16) & 0xFFFF, 100 + MVR_ROLE_CLEARCOAT_NORMAL);
    /* uv fields */
    int32_t uv0 = block_int(b, MVR_MATERIAL_UV_OFFSET), has = block_int(b, MVR_MATERIAL_UV_OFFSET + 12);
    uint32_t base_field = (uint32_t)uv0 & 15u, emissive_field = ((uint32_t)uv0 >> 16) & 15u;
    uint32_t coat_field = ((uint32_t)uv0 >> 28) & 15u;
    CHECK_EQ_INT(t, base_field, 0);                          /* TEXCOORD_0, slot 0 (identity) */
    CHECK_EQ_INT(t, emissive_field, 1u | 1u << 1);           /* TEXCOORD_1, slot 1 */
    CHECK_EQ_INT(t, coat_field, 1u << 1);                    /* TEXCOORD_0, slot 1: shared */
    CHECK_EQ_INT(t, (uint32_t)has, 1u << MVR_ROLE_BASE_COLOR | 1u << MVR_ROLE_EMISSIVE | 1u << MVR_ROLE_CLEARCOAT_NORMAL);
    /* slot 1's rows: scale 2 and the offset */
    uint32_t row = MVR_MATERIAL_UV_TRANSFORM_OFFSET + 2 * MVR_MATERIAL_UV_TRANSFORM_STRIDE;
    CHECK(t, block_float(b, row) == 2.0f && block_float(b, row + 8) == 0.5f);
    CHECK(t, block_float(b, row + MVR_MATERIAL_UV_TRANSFORM_STRIDE + 8) == 0.25f);
    /* the per-material path: no layers */
    mvr_material_pack(&m, NULL, b);
    CHECK_EQ_INT(t, block_int(b, MVR_MATERIAL_LAYERS_OFFSET), 0);
}

/* Eight distinct transforms fit a material; a ninth is refused by name. */
static void transform_slots_are_bounded(mvr_test_state *t)
{
    mvr_scene *s = NULL;
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    uint8_t px[4] = {255, 255, 255, 255};
    mvr_image_desc id = {.width = 1, .height = 1, .rgba8 = px};
    mvr_image_id img;
    CHECK(t, mvr_scene_add_image(s, &id, &img) == MVR_OK);
    mvr_material_desc m = mvr_material_defaults();
    m.name = "many";
    for (uint32_t r = 0; r < 9; ++r) {
        mvr_texture_ref *ref = (mvr_texture_ref *)mvr_material_role(&m, r);
        ref->image = img;
        ref->transform = (mvr_texture_transform){true, {0.1f * (float)r, 0.0f}, 0.0f, {1.0f, 1.0f}};
    }
    mvr_material_id out;
    CHECK(t, mvr_scene_add_material(s, &m, &out) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "many") && strstr(mvr_scene_last_error(s), "9 distinct"));
    ((mvr_texture_ref *)mvr_material_role(&m, 8))->transform = m.base_color.transform; /* shares slot 0 */
    CHECK(t, mvr_scene_add_material(s, &m, &out) == MVR_OK);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(extension_bits_follow_departures), TEST(roles_pack_into_the_block),
              TEST(transform_slots_are_bounded))
