/* core: the scene validates every count, index and reference, owns copies,
 * and the frame prep packs what the shaders read. */
#include <math.h>

#include "frame.h"
#include "mvr_test.h"
#include "scene_internal.h"

static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};

static mvr_scene *new_scene(void)
{
    mvr_scene *s = NULL;
    mvr_scene_create(NULL, &s, NULL);
    return s;
}

static void bad_meshes_are_refused(mvr_test_state *t)
{
    mvr_scene *s = new_scene();
    mvr_mesh_id id;
    mvr_primitive_desc p = {0};
    p.vertex_count = 3;
    p.positions = tri;
    mvr_mesh_desc m = {.primitives = &p, .primitive_count = 1, .name = "tri"};
    CHECK(t, mvr_scene_add_mesh(s, &m, &id) == MVR_OK && id.id == 1);

    uint16_t idx[3] = {0, 1, 3};
    p.index_count = 3;
    p.indices16 = idx;
    CHECK(t, mvr_scene_add_mesh(s, &m, &id) == MVR_ERROR_INVALID_ARGUMENT && id.id == 0);
    CHECK_MSG(t, strstr(mvr_scene_last_error(s), "index 3 at 2 is out of range") != NULL, "%s",
              mvr_scene_last_error(s));
    idx[2] = 2;
    p.index_count = 2;
    CHECK(t, mvr_scene_add_mesh(s, &m, &id) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "multiple of 3") != NULL);
    p.index_count = 3;
    uint32_t idx32[3] = {0, 1, 2};
    p.indices32 = idx32;
    CHECK(t, mvr_scene_add_mesh(s, &m, &id) == MVR_ERROR_INVALID_ARGUMENT); /* both index arrays */
    p.indices32 = NULL;
    p.material.id = 5;
    CHECK(t, mvr_scene_add_mesh(s, &m, &id) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "material 5") != NULL);
    p.material.id = 0;
    float nan_tri[9] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
    p.positions = nan_tri;
    CHECK(t, mvr_scene_add_mesh(s, &m, &id) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "NaN") != NULL);
    p.positions = NULL;
    CHECK(t, mvr_scene_add_mesh(s, &m, &id) == MVR_ERROR_INVALID_ARGUMENT);
    m.primitive_count = 0;
    CHECK(t, mvr_scene_add_mesh(s, &m, &id) == MVR_ERROR_INVALID_ARGUMENT);
    /* nothing half-added by the failures */
    mvr_scene_info info;
    mvr_scene_get_info(s, &info);
    CHECK_EQ_INT(t, info.meshes, 1);
    CHECK_EQ_INT(t, info.primitives, 1);
    mvr_scene_destroy(s);
}

static void references_are_checked(mvr_test_state *t)
{
    mvr_scene *s = new_scene();
    mvr_node_id n;
    mvr_node_desc d = {0};
    d.parent.id = 1;
    CHECK(t, mvr_scene_add_node(s, &d, &n) == MVR_ERROR_INVALID_ARGUMENT); /* no node 1 yet */
    d.parent.id = 0;
    d.translation[0] = INFINITY;
    CHECK(t, mvr_scene_add_node(s, &d, &n) == MVR_ERROR_INVALID_ARGUMENT);
    d.translation[0] = 0;
    CHECK(t, mvr_scene_add_node(s, &d, &n) == MVR_OK && n.id == 1);
    mvr_material_desc md = mvr_material_defaults();
    md.base_color.image.id = 1;
    mvr_material_id mid;
    CHECK(t, mvr_scene_add_material(s, &md, &mid) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "base color texture names image 1") != NULL);
    md.base_color.image.id = 0;
    md.normal.texcoord = 2;
    md.normal.image.id = 0;
    CHECK(t, mvr_scene_add_material(s, &md, &mid) == MVR_ERROR_INVALID_ARGUMENT);
    mvr_light_desc l = {MVR_LIGHT_POINT, {1, 1, 1}, -1.0f, 0, 0, 0, false, 0};
    mvr_light_id lid;
    CHECK(t, mvr_scene_add_light(s, &l, &lid) == MVR_ERROR_INVALID_ARGUMENT);
    mvr_image_desc img = {.width = 0, .height = 4, .rgba8 = NULL, .name = "empty"};
    mvr_image_id iid;
    CHECK(t, mvr_scene_add_image(s, &img, &iid) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_scene_add_image(NULL, &img, &iid) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_scene_set_node_transform(s, (mvr_node_id){7}, d.translation, d.rotation, d.scale) ==
                 MVR_ERROR_INVALID_ARGUMENT);
    mvr_scene_destroy(s);
    mvr_scene_destroy(NULL);
}

static void frame_packs_draws_relative_to_origin(mvr_test_state *t)
{
    mvr_scene *s = new_scene();
    mvr_material_desc blend = mvr_material_defaults();
    blend.alpha_mode = MVR_ALPHA_BLEND;
    mvr_material_id opaque_m, blend_m;
    mvr_material_desc opaque = mvr_material_defaults();
    CHECK(t, mvr_scene_add_material(s, &opaque, &opaque_m) == MVR_OK);
    CHECK(t, mvr_scene_add_material(s, &blend, &blend_m) == MVR_OK);
    mvr_primitive_desc p = {0};
    p.vertex_count = 3;
    p.positions = tri;
    p.material = opaque_m;
    mvr_mesh_desc m = {.primitives = &p, .primitive_count = 1, .name = "a"};
    mvr_mesh_id a, b;
    CHECK(t, mvr_scene_add_mesh(s, &m, &a) == MVR_OK);
    p.material = blend_m;
    CHECK(t, mvr_scene_add_mesh(s, &m, &b) == MVR_OK);
    /* parent far away, children near it, one mirrored */
    mvr_node_desc nd = {0};
    nd.translation[0] = 1e7;
    mvr_node_id parent;
    CHECK(t, mvr_scene_add_node(s, &nd, &parent) == MVR_OK);
    memset(&nd, 0, sizeof nd);
    nd.parent = parent;
    nd.mesh = a;
    nd.translation[2] = -2;
    nd.scale[0] = -1, nd.scale[1] = 1, nd.scale[2] = 1;
    mvr_node_id child;
    CHECK(t, mvr_scene_add_node(s, &nd, &child) == MVR_OK);
    nd.mesh = b;
    nd.scale[0] = 0;
    nd.translation[2] = -5;
    CHECK(t, mvr_scene_add_node(s, &nd, &child) == MVR_OK);
    nd.translation[2] = -3;
    CHECK(t, mvr_scene_add_node(s, &nd, &child) == MVR_OK);

    mvr_frame f;
    memset(&f, 0, sizeof f);
    char why[128];
    CHECK(t, mvr_frame_build(&f, s, mvr_dvec3_make(1e7, 0, 0), 256, 64, NULL, why, sizeof why) == MVR_OK);
    CHECK_EQ_INT(t, f.draw_count, 3);
    CHECK_EQ_INT(t, f.pass_count[MVR_PASS_OPAQUE], 1);
    CHECK_EQ_INT(t, f.pass_count[MVR_PASS_BLEND], 2);
    const mvr_draw *o = &f.draws[f.pass_first[MVR_PASS_OPAQUE]];
    CHECK(t, o->mirrored);
    float model[16];
    memcpy(model, f.draw_blocks + (size_t)o->block * 256, sizeof model);
    CHECK_MSG(t, model[12] == 0.0f && model[14] == -2.0f, "relative translation %g %g", (double)model[12],
              (double)model[14]);
    /* blended draws back to front */
    const mvr_draw *b0 = &f.draws[f.pass_first[MVR_PASS_BLEND]], *b1 = b0 + 1;
    CHECK(t, b0->depth > b1->depth);
    CHECK(t, !b0->mirrored);
    int32_t info[4];
    memcpy(info, f.draw_blocks + (size_t)o->block * 256 + 128, sizeof info);
    CHECK_EQ_INT(t, info[0], 0); /* material slot 0 */
    CHECK(t, mvr_frame_build(&f, s, mvr_dvec3_make(0, 0, 0), 100, 64, NULL, why, sizeof why) != MVR_OK);
    mvr_frame_free(&f);
    mvr_scene_destroy(s);
}

/* A node drawing `mesh` at distance `distance` down -Z from the origin. */
static void add_node_at(mvr_test_state *t, mvr_scene *s, mvr_mesh_id mesh, float distance)
{
    mvr_node_desc nd = {0};
    nd.scale[0] = nd.scale[1] = nd.scale[2] = 1;
    nd.translation[2] = -distance;
    nd.mesh = mesh;
    mvr_node_id id;
    CHECK(t, mvr_scene_add_node(s, &nd, &id) == MVR_OK);
}

/* Opaque draws without textures go front to back whatever their
 * materials (switching costs nothing: the draw block names the material),
 * so early depth rejects what nearer draws hide; textured materials keep
 * their draws together (their textures are bound once), front to back
 * within. */
static void opaque_draws_go_front_to_back_across_untextured_materials(mvr_test_state *t)
{
    mvr_scene *s = new_scene();
    static const uint8_t white[16] = {255, 255, 255, 255, 255, 255, 255, 255,
                                      255, 255, 255, 255, 255, 255, 255, 255};
    mvr_image_desc img = {.width = 2, .height = 2, .rgba8 = white, .name = "white"};
    mvr_image_id image;
    CHECK(t, mvr_scene_add_image(s, &img, &image) == MVR_OK);
    mvr_material_id plain[3], textured[2];
    for (int k = 0; k < 3; ++k) {
        mvr_material_desc m = mvr_material_defaults();
        m.base_color_factor[0] = 0.25f * (float)k;
        CHECK(t, mvr_scene_add_material(s, &m, &plain[k]) == MVR_OK);
    }
    for (int k = 0; k < 2; ++k) {
        mvr_material_desc m = mvr_material_defaults();
        m.base_color.image = image;
        m.base_color_factor[1] = 0.5f * (float)k;
        CHECK(t, mvr_scene_add_material(s, &m, &textured[k]) == MVR_OK);
    }
    static const float uv[6] = {0, 0, 1, 0, 0, 1};
    mvr_primitive_desc p = {0};
    p.vertex_count = 3;
    p.positions = tri;
    p.texcoords0 = uv;
    mvr_mesh_id meshes[5];
    for (int k = 0; k < 5; ++k) {
        p.material = k < 3 ? plain[k] : textured[k - 3];
        mvr_mesh_desc m = {.primitives = &p, .primitive_count = 1, .name = "m"};
        CHECK(t, mvr_scene_add_mesh(s, &m, &meshes[k]) == MVR_OK);
    }
    /* nine untextured draws whose materials interleave with distance, and
     * six textured ones of two materials, also interleaved */
    for (int k = 0; k < 15; ++k)
        add_node_at(t, s, k < 9 ? meshes[k % 3] : meshes[3 + k % 2], (float)((k * 7) % 15) + 1.0f);
    mvr_frame f;
    memset(&f, 0, sizeof f);
    char why[128];
    CHECK(t, mvr_frame_build(&f, s, mvr_dvec3_make(0, 0, 0), 256, 64, NULL, why, sizeof why) == MVR_OK);
    CHECK_EQ_INT(t, f.pass_count[MVR_PASS_OPAQUE], 15);
    uint32_t untextured = 0, materials_seen = 0, switches = 0;
    uint32_t keys = 0; /* runs of one binding key */
    for (uint32_t i = 0; i < f.pass_count[MVR_PASS_OPAQUE]; ++i) {
        const mvr_draw *d = &f.draws[f.pass_first[MVR_PASS_OPAQUE] + i];
        bool has_texture = (d->features & MVR_FEATURE_BASE_COLOR_TEX) != 0;
        CHECK_MSG(t, has_texture == (d->group_key != 0), "draw %u: group key %llu, textured %d", i,
                  (unsigned long long)d->group_key, has_texture);
        keys += i == 0 || d->group_key != d[-1].group_key;
        if (i > 0) {
            const mvr_draw *prev = d - 1;
            /* within a program and a binding, strictly nearer first */
            if (prev->features == d->features && prev->group_key == d->group_key)
                CHECK_MSG(t, prev->depth <= d->depth, "draw %u at %g after %g", i, (double)d->depth,
                          (double)prev->depth);
            switches += prev->material != d->material;
        }
        untextured += !has_texture;
        materials_seen |= 1u << (d->material & 31u);
    }
    CHECK_EQ_INT(t, untextured, 9);
    /* each binding one run: the two textured materials are not interleaved */
    CHECK_EQ_INT(t, keys, 3);
    /* the untextured ones are: nine draws of three materials, front to back */
    CHECK_MSG(t, switches >= 8, "%u material switches", switches);
    CHECK_EQ_INT(t, materials_seen, 31);
    mvr_frame_free(&f);
    mvr_scene_destroy(s);
}

/* Where front to back would cost many more calls than instancing the draws
 * of each primitive (many small draws of few meshes), the draws of a
 * primitive stay together, front to back among them. */
static void many_draws_of_few_meshes_stay_instanced(mvr_test_state *t)
{
    mvr_scene *s = new_scene();
    mvr_material_id mats[2];
    mvr_mesh_id meshes[2];
    for (int k = 0; k < 2; ++k) {
        mvr_material_desc m = mvr_material_defaults();
        m.roughness_factor = 0.25f + 0.5f * (float)k;
        CHECK(t, mvr_scene_add_material(s, &m, &mats[k]) == MVR_OK);
        mvr_primitive_desc p = {0};
        p.vertex_count = 3;
        p.positions = tri;
        p.material = mats[k];
        mvr_mesh_desc m2 = {.primitives = &p, .primitive_count = 1, .name = "m"};
        CHECK(t, mvr_scene_add_mesh(s, &m2, &meshes[k]) == MVR_OK);
    }
    enum { N = 200 };
    for (int k = 0; k < N; ++k) /* the two meshes alternate with distance */
        add_node_at(t, s, meshes[k % 2], (float)k + 1.0f);
    mvr_frame f;
    memset(&f, 0, sizeof f);
    char why[128];
    CHECK(t, mvr_frame_build(&f, s, mvr_dvec3_make(0, 0, 0), 256, 64, NULL, why, sizeof why) == MVR_OK);
    CHECK_EQ_INT(t, f.pass_count[MVR_PASS_OPAQUE], N);
    uint32_t primitive_changes = 0;
    for (uint32_t i = 1; i < N; ++i) {
        const mvr_draw *d = &f.draws[f.pass_first[MVR_PASS_OPAQUE] + i], *prev = d - 1;
        if (prev->primitive != d->primitive)
            primitive_changes++;
        else
            CHECK_MSG(t, prev->depth <= d->depth, "draw %u at %g after %g", i, (double)d->depth, (double)prev->depth);
    }
    CHECK_EQ_INT(t, primitive_changes, 1);
    mvr_frame_free(&f);
    mvr_scene_destroy(s);
}

static void features_follow_attributes_and_material(mvr_test_state *t)
{
    float uv[6] = {0, 0, 1, 0, 0, 1};
    scene_primitive p;
    memset(&p, 0, sizeof p);
    p.positions = (float *)tri;
    p.normals = (float *)tri;
    mvr_material_desc m = mvr_material_defaults();
    m.base_color.image.id = 1;
    /* no UVs: the texture cannot be sampled, so no texture feature */
    CHECK_EQ_INT(t, mvr_draw_features(&p, &m) & MVR_FEATURE_BASE_COLOR_TEX, 0);
    p.uv0 = uv;
    uint32_t f = mvr_draw_features(&p, &m);
    CHECK(t, (f & MVR_FEATURE_BASE_COLOR_TEX) && (f & MVR_FEATURE_UV0) && (f & MVR_FEATURE_NORMALS));
    CHECK(t, !(f & MVR_FEATURE_UV1));
    m.unlit = true;
    f = mvr_draw_features(&p, &m);
    CHECK(t, (f & MVR_FEATURE_UNLIT) && !(f & MVR_FEATURE_NORMALS));
    m.unlit = false;
    m.normal.image.id = 1;
    CHECK(t, !(mvr_draw_features(&p, &m) & MVR_FEATURE_TANGENTS)); /* no tangents given */
    p.tangents = uv;
    CHECK(t, mvr_draw_features(&p, &m) & MVR_FEATURE_TANGENTS);
}


/* Degenerate values are repaired (and counted), never passed on: the GPU
 * sees no NaN from a normal, tangent, UV, color or factor. */
static void degenerate_values_are_repaired(mvr_test_state *t)
{
    mvr_scene *s = new_scene();
    const float nan = NAN, inf = INFINITY;
    float normals[9] = {nan, 0, 1, 0, 0, 0, 0, 0, 2};            /* NaN, zero, fine (unnormalized) */
    float tangents[12] = {1, 0, 0, 1, inf, 0, 0, 1, 1, 0, 0, 0.5f}; /* fine, infinite, bad sign */
    float uv[6] = {0, 0, nan, 1, 1, 1};                          /* one NaN */
    float colors[12] = {1, 1, 1, 1, 2, 0, 0, 1, nan, 0, 0, 1};   /* fine, > 1, NaN */
    mvr_primitive_desc p = {.vertex_count = 3, .positions = tri, .normals = normals, .tangents = tangents,
                            .texcoords0 = uv, .colors = colors};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "bad"};
    mvr_mesh_id mesh;
    CHECK(t, mvr_scene_add_mesh(s, &md, &mesh) == MVR_OK);
    CHECK_EQ_INT(t, mvr_scene_sanitized_count(s), 2 + 2 + 1 + 2);
    const scene_primitive *sp = &s->primitives[0];
    for (int i = 0; i < 9; ++i)
        CHECK(t, isfinite(sp->normals[i]) && isfinite(sp->tangents[i]));
    CHECK(t, sp->normals[0] == 0 && sp->normals[1] == 0 && sp->normals[2] == 0);
    CHECK(t, sp->normals[8] == 2.0f); /* a valid normal is left alone (the shader normalizes) */
    CHECK(t, sp->tangents[4] == 0 && sp->tangents[11] == 1.0f);
    CHECK(t, sp->uv0[2] == 0.0f && sp->uv0[3] == 1.0f);
    CHECK(t, sp->colors[4] == 1.0f && sp->colors[8] == 1.0f);

    mvr_material_desc m = mvr_material_defaults();
    m.metallic_factor = nan;                 /* -> glTF default 1 */
    m.roughness_factor = 1e-40f;             /* denormal -> 0 */
    m.base_color_factor[0] = 1.5f;           /* -> 1 */
    m.emissive_factor[1] = -inf;             /* -> 0 */
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, &m, &mat) == MVR_OK);
    CHECK_EQ_INT(t, mvr_scene_sanitized_count(s), 7 + 4);
    const mvr_material_desc *got = mvr_scene_material(s, 0);
    CHECK(t, got->metallic_factor == 1.0f && got->roughness_factor == 0.0f && got->base_color_factor[0] == 1.0f &&
             got->emissive_factor[1] == 0.0f);

    /* a quaternion of length 2 is normalized and counted; all zero is the default */
    mvr_node_desc nd = {.mesh = mesh, .rotation = {0, 0, 0, 2}};
    mvr_node_id node;
    CHECK(t, mvr_scene_add_node(s, &nd, &node) == MVR_OK);
    mvr_node_desc nd0 = {.mesh = mesh};
    CHECK(t, mvr_scene_add_node(s, &nd0, &node) == MVR_OK);
    CHECK_EQ_INT(t, mvr_scene_sanitized_count(s), 12);
    CHECK(t, s->nodes[0].rotation.w == 1.0);
    mvr_scene_destroy(s);
}

/* Block-compressed images: each level exactly its blocks' bytes (rounded up
 * to whole blocks, down to 1 x 1), at most the full chain, no RGBA8 pixels
 * beside them, a known format; RGBA8 images give no levels. */
static void block_images_are_checked(mvr_test_state *t)
{
    mvr_scene *s = NULL;
    mvr_scene_create(NULL, &s, NULL);
    static uint8_t blocks[1024];
    uint64_t n = 0;
    CHECK(t, mvr_image_level_size(MVR_IMAGE_FORMAT_ETC2_RGBA8, 10, 6, 0, &n) && n == 3 * 2 * 16);
    CHECK(t, mvr_image_level_size(MVR_IMAGE_FORMAT_ETC2_RGBA8, 10, 6, 3, &n) && n == 16);   /* 1x1 */
    CHECK(t, !mvr_image_level_size(MVR_IMAGE_FORMAT_ETC2_RGBA8, 10, 6, 4, &n) && n == 0);   /* beyond the chain */
    CHECK(t, mvr_image_level_size(MVR_IMAGE_FORMAT_ASTC_12x10, 25, 11, 0, &n) && n == 3 * 2 * 16);
    CHECK(t, !mvr_image_level_size(MVR_IMAGE_FORMAT_COUNT, 4, 4, 0, &n));
    mvr_image_desc d = {.width = 10, .height = 6, .name = "blocks", .format = MVR_IMAGE_FORMAT_ETC2_RGBA8,
                        .level_count = 4};
    size_t sizes[4] = {96, 32, 16, 16};
    for (int k = 0; k < 4; ++k)
        d.levels[k] = (mvr_image_level){blocks, sizes[k]};
    mvr_image_id id = {0};
    CHECK(t, mvr_scene_add_image(s, &d, &id) == MVR_OK && id.id == 1);
    mvr_image_desc bad = d;
    bad.levels[1].size = 16;
    CHECK(t, mvr_scene_add_image(s, &bad, &id) == MVR_ERROR_INVALID_ARGUMENT && id.id == 0);
    CHECK(t, strstr(mvr_scene_last_error(s), "blocks") && strstr(mvr_scene_last_error(s), "level 1"));
    bad = d;
    bad.level_count = 5;
    bad.levels[4] = (mvr_image_level){blocks, 16};
    CHECK(t, mvr_scene_add_image(s, &bad, &id) == MVR_ERROR_INVALID_ARGUMENT);
    bad = d;
    bad.level_count = 0;
    CHECK(t, mvr_scene_add_image(s, &bad, &id) == MVR_ERROR_INVALID_ARGUMENT);
    bad = d;
    bad.levels[2].data = NULL;
    CHECK(t, mvr_scene_add_image(s, &bad, &id) == MVR_ERROR_INVALID_ARGUMENT);
    bad = d;
    bad.rgba8 = blocks;
    CHECK(t, mvr_scene_add_image(s, &bad, &id) == MVR_ERROR_INVALID_ARGUMENT);
    bad = d;
    bad.format = (mvr_image_format)99;
    CHECK(t, mvr_scene_add_image(s, &bad, &id) == MVR_ERROR_INVALID_ARGUMENT);
    mvr_image_desc rgba = {.width = 2, .height = 2, .rgba8 = blocks, .level_count = 2};
    CHECK(t, mvr_scene_add_image(s, &rgba, &id) == MVR_ERROR_INVALID_ARGUMENT);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(block_images_are_checked), TEST(opaque_draws_go_front_to_back_across_untextured_materials),
              TEST(many_draws_of_few_meshes_stay_instanced), TEST(degenerate_values_are_repaired), TEST(bad_meshes_are_refused), TEST(references_are_checked),
              TEST(frame_packs_draws_relative_to_origin), TEST(features_follow_attributes_and_material))
