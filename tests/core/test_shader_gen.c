/* core: shader variants become source text; every variant is well-formed. */
#include "mvr_test.h"
#include "block_layout.h"
#include "shader_files.h"
#include "shader_gen.h"

static char *source_of(const mvr_shader_variant *v, mvr_shader_stage stage)
{
    mvr_str_builder sb = {0};
    char why[256];
    if (!mvr_shader_source(v, stage, &sb, why, sizeof why)) {
        printf("  source failed: %s\n", why);
        mvr_sb_free(&sb);
        return NULL;
    }
    return sb.data;
}

static void every_embedded_file_is_nonempty(mvr_test_state *t)
{
    CHECK(t, mvr_shader_file_count >= 6);
    for (unsigned i = 0; i < mvr_shader_file_count; ++i) {
        CHECK(t, mvr_shader_files[i].length > 0);
        CHECK(t, strlen(mvr_shader_files[i].text) == mvr_shader_files[i].length);
    }
    CHECK(t, mvr_shader_file_find("mesh.frag.glsl") != NULL);
    CHECK(t, mvr_shader_file_find("no-such.glsl") == NULL);
}

static void version_comes_first_and_defines_follow_features(mvr_test_state *t)
{
    mvr_shader_variant v = {MVR_PROGRAM_MESH, MVR_FEATURE_UV0 | MVR_FEATURE_BASE_COLOR_TEX, 0, 1, 0, 0, 0, 0, 0, 0};
    char *vs = source_of(&v, MVR_SHADER_STAGE_VERTEX);
    char *fs = source_of(&v, MVR_SHADER_STAGE_FRAGMENT);
    CHECK(t, vs && fs);
    if (vs && fs) {
        CHECK(t, strncmp(vs, "#version 300 es\n", 16) == 0);
        CHECK(t, strncmp(fs, "#version 300 es\n", 16) == 0);
        CHECK(t, strstr(fs, "#define MVR_UV0 1\n") && strstr(fs, "#define MVR_BASE_COLOR_TEX 1\n"));
        CHECK(t, !strstr(fs, "#define MVR_NORMAL_TEX"));
        CHECK(t, strstr(fs, "#define MVR_DIRECTIONAL_LIGHTS 1\n"));
        CHECK(t, !strstr(vs, "GL_OVR_multiview"));
        CHECK(t, !strstr(vs, "#define MVR_MULTIVIEW"));
        CHECK(t, strstr(vs, "precision highp float;"));
        CHECK(t, !strstr(vs, "mediump") && !strstr(fs, "mediump"));
    }
    free(vs);
    free(fs);
}

static void multiview_layout_only_in_vertex_stage(mvr_test_state *t)
{
    mvr_shader_variant v = {MVR_PROGRAM_MESH, 0, 6, 0, 0, 0, 0, 0, 0, 0};
    char *vs = source_of(&v, MVR_SHADER_STAGE_VERTEX);
    char *fs = source_of(&v, MVR_SHADER_STAGE_FRAGMENT);
    CHECK(t, vs && fs);
    if (vs && fs) {
        CHECK(t, strstr(vs, "#extension GL_OVR_multiview2 : require\n"));
        CHECK(t, strstr(vs, "layout(num_views = 6) in;\n"));
        CHECK(t, strstr(fs, "#extension GL_OVR_multiview2 : require\n"));
        CHECK(t, !strstr(fs, "num_views"));
        CHECK(t, strstr(vs, "#define MVR_NUM_VIEWS 6\n"));
        /* the #extension must precede any non-preprocessor token */
        CHECK(t, strstr(vs, "#extension") < strstr(vs, "precision"));
    }
    free(vs);
    free(fs);
}

static void invalid_variants_are_refused(mvr_test_state *t)
{
    char why[256];
    mvr_shader_variant v = {MVR_PROGRAM_MESH, MVR_FEATURE_ALPHA_MASK | MVR_FEATURE_ALPHA_BLEND, 0, 0, 0, 0, 0, 0, 0, 0};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    CHECK(t, strstr(why, "alpha") != NULL);
    uint32_t unknown = ~mvr_shader_feature_mask(MVR_PROGRAM_MESH);
    if (unknown) { /* a bit no feature has */
        v.features = unknown & (0u - unknown);
        CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    }
    /* a bit the composite program has no feature for (NORMAL_TEX's bit is POST_MSAA's there) */
    uint32_t none_of_composite = ~mvr_shader_feature_mask(MVR_PROGRAM_COMPOSITE);
    v = (mvr_shader_variant){MVR_PROGRAM_COMPOSITE, none_of_composite & (0u - none_of_composite), 0, 0, 0, 0, 0, 0, 0, 0};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    v = (mvr_shader_variant){MVR_PROGRAM_COMPOSITE, 0, 0, 1, 0, 0, 0, 0, 0, 0};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    v = (mvr_shader_variant){MVR_PROGRAM_MESH, 0, 1000, 0, 0, 0, 0, 0, 0, 0};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    v = (mvr_shader_variant){MVR_PROGRAM_MESH, 0, 0, MVR_SHADER_MAX_LIGHTS_PER_TYPE + 1, 0, 0, 0, 0, 0, 0};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    v = (mvr_shader_variant){MVR_PROGRAM_MESH, 0, 0, 0, 0, 0, 0, MVR_SHADER_MAX_DRAW_CAPACITY + 1, 0, 0};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    CHECK(t, strstr(why, "draw capacity") != NULL);
    v = (mvr_shader_variant){MVR_PROGRAM_COMPOSITE, 0, 0, 0, 0, 0, 0, 2, 0, 0};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    /* extra outputs: mesh only, camera space needs normals, outputs-only needs an output */
    v = (mvr_shader_variant){MVR_PROGRAM_COMPOSITE, 0, 0, 0, 0, 0, 0, 0, 0, MVR_SHADER_OUT_IDS};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    v = (mvr_shader_variant){MVR_PROGRAM_MESH, 0, 0, 0, 0, 0, 0, 0, 0, MVR_SHADER_OUT_NORMAL_CAMERA};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    v = (mvr_shader_variant){MVR_PROGRAM_MESH, 0, 0, 0, 0, 0, 0, 0, 0, MVR_SHADER_OUT_ONLY};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    CHECK(t, strstr(why, "outputs") != NULL);
    v = (mvr_shader_variant){MVR_PROGRAM_MESH, 0, 0, 0, 0, 0, 0, 0, 0, MVR_SHADER_OUT_IDS | MVR_SHADER_OUT_ONLY};
    CHECK(t, mvr_shader_variant_valid(&v, why, sizeof why));
    v = (mvr_shader_variant){(mvr_program_kind)42, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    CHECK(t, !mvr_shader_variant_valid(&v, why, sizeof why));
    mvr_str_builder sb = {0};
    CHECK(t, !mvr_shader_source(&v, MVR_SHADER_STAGE_VERTEX, &sb, why, sizeof why));
    mvr_sb_free(&sb);
    CHECK(t, !mvr_shader_variant_valid(NULL, why, sizeof why));
}

static void enumeration_covers_each_feature_and_view_path(mvr_test_state *t)
{
    mvr_shader_variant v;
    unsigned n = 0;
    uint32_t seen_bits[MVR_PROGRAM_KIND_COUNT] = {0};
    int seen_loop = 0, seen_mv6 = 0, seen_lights = 0;
    char names[400][96];
    while (mvr_shader_variant_enumerate(n, 6, &v)) {
        char why[256];
        CHECK_MSG(t, mvr_shader_variant_valid(&v, why, sizeof why), "variant %u: %s", n, why);
        seen_bits[v.program] |= v.features;
        seen_loop |= v.num_views == 0;
        seen_mv6 |= v.num_views == 6;
        seen_lights |= v.point_lights > 0;
        if (n < 400) {
            mvr_shader_variant_name(&v, names[n], sizeof names[n]);
            for (unsigned j = 0; j < n; ++j)
                CHECK_MSG(t, strcmp(names[j], names[n]) != 0, "duplicate variant %s", names[n]);
        }
        ++n;
    }
    CHECK(t, n > 20 && n < 400);
    for (int p = 0; p < MVR_PROGRAM_KIND_COUNT; ++p)
        CHECK_MSG(t, seen_bits[p] == mvr_shader_feature_mask((mvr_program_kind)p), "%s: features 0x%x of 0x%x seen",
                  mvr_program_kind_name((mvr_program_kind)p), seen_bits[p],
                  mvr_shader_feature_mask((mvr_program_kind)p));
    CHECK(t, seen_loop && seen_mv6 && seen_lights);
    /* with max_views 2 the list is shorter, never longer */
    unsigned n2 = 0;
    while (mvr_shader_variant_enumerate(n2, 2, &v))
        ++n2;
    CHECK(t, n2 < n);
}

static void every_feature_has_a_define(mvr_test_state *t)
{
    for (int p = 0; p < MVR_PROGRAM_KIND_COUNT; ++p) {
        uint32_t mask = mvr_shader_feature_mask((mvr_program_kind)p);
        CHECK(t, mask != 0);
        for (int b = 0; b < 32; ++b) {
            uint32_t bit = 1u << b;
            const char *name = mvr_shader_feature_define((mvr_program_kind)p, bit);
            CHECK(t, (name != NULL) == ((mask & bit) != 0));
            if (name) {
                /* the define is used by some shader file */
                int used = 0;
                for (unsigned i = 0; i < mvr_shader_file_count; ++i)
                    used |= strstr(mvr_shader_files[i].text, name) != NULL;
                CHECK_MSG(t, used, "%s is defined but no shader reads it", name);
            }
        }
    }
}

/* The uniform blocks' declarations are generated from the std140 table
 * (block_layout.h): a variant with every block declares each with all its
 * members, and no "#mvr_block" line is left in any variant's source. */
static void blocks_are_declared_from_the_layout_table(mvr_test_state *t)
{
    mvr_shader_variant v = {.program = MVR_PROGRAM_MESH, .features = MVR_FEATURE_SHADOWS, .point_lights = 2};
    char *vs = source_of(&v, MVR_SHADER_STAGE_VERTEX);
    char *fs = source_of(&v, MVR_SHADER_STAGE_FRAGMENT);
    CHECK(t, vs && fs);
    uint32_t count = 0;
    const mvr_block_layout *layouts = mvr_block_layouts(&count);
    for (uint32_t k = 0; vs && fs && k < count; ++k) {
        const mvr_block_layout *b = &layouts[k];
        char decl[128];
        snprintf(decl, sizeof decl, "layout(std140) uniform %s {\n", b->block);
        const char *at = strstr(vs, decl) ? strstr(vs, decl) : strstr(fs, decl);
        CHECK_MSG(t, at != NULL, "no declaration of %s", b->block);
        if (!at)
            continue;
        if (b->element) {
            snprintf(decl, sizeof decl, "    %s %s[%s];\n", b->struct_name, b->element, b->element_count);
            CHECK_MSG(t, strstr(at, decl) != NULL, "%s: no %s", b->block, decl);
            snprintf(decl, sizeof decl, "struct %s {\n", b->struct_name);
            at = strstr(vs, decl) ? strstr(vs, decl) : strstr(fs, decl);
            CHECK_MSG(t, at != NULL, "%s: no struct %s", b->block, b->struct_name);
            if (!at)
                continue;
        }
        for (uint32_t m = 0; m < b->member_count; ++m) {
            const char *name = b->members[m].name;
            CHECK_MSG(t, strstr(at, name) != NULL, "%s: no member %s", b->block, name);
        }
    }
    free(vs);
    free(fs);
    unsigned left = 0;
    for (unsigned i = 0; mvr_shader_variant_enumerate(i, 4, &v); ++i) {
        for (int s = 0; s < MVR_SHADER_STAGE_COUNT; ++s) {
            char *src = source_of(&v, (mvr_shader_stage)s);
            CHECK(t, src != NULL);
            left += src && strstr(src, "#mvr_block") ? 1u : 0u;
            free(src);
        }
    }
    CHECK_EQ_INT(t, (int)left, 0);
}

MVR_TEST_MAIN(TEST(every_embedded_file_is_nonempty),
              TEST(version_comes_first_and_defines_follow_features),
              TEST(multiview_layout_only_in_vertex_stage), TEST(invalid_variants_are_refused),
              TEST(enumeration_covers_each_feature_and_view_path),
              TEST(every_feature_has_a_define), TEST(blocks_are_declared_from_the_layout_table))
