/* core: material variants (scene_variants.c). A scene of two meshes, three
 * primitives and four materials: selecting a variant switches the mapped
 * primitives' materials (and only theirs), the frame's draws follow (a
 * variant mapping a blended material moves the draw to the blend pass),
 * MVR_VARIANT_DEFAULT restores every primitive's own material, selecting the
 * selected variant again (or a variant that changes no material) moves no
 * version, names are found (the first of two equal ones), and bad ids,
 * duplicate variants in one primitive and NULLs are refused with a message
 * naming the mesh, primitive and mapping. */
#include <stdlib.h>
#include <string.h>

#include "frame.h"
#include "mvr_test.h"
#include "scene_internal.h"

typedef struct fixture {
    mvr_scene *s;
    mvr_material_id white, grey, red, glass; /* glass: blended */
    mvr_mesh_id board, ball;                 /* board: 2 primitives (paint, frame); ball: 1 */
    uint32_t v_red, v_blue, v_glass;
} fixture;

static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};

static bool build(mvr_test_state *t, fixture *f)
{
    memset(f, 0, sizeof *f);
    CHECK(t, mvr_scene_create(NULL, &f->s, NULL) == MVR_OK);
    if (!f->s)
        return false;
    mvr_scene *s = f->s;
    mvr_material_desc md = mvr_material_defaults();
    md.name = "white";
    CHECK(t, mvr_scene_add_material(s, &md, &f->white) == MVR_OK);
    md.name = "grey";
    md.base_color_factor[0] = md.base_color_factor[1] = md.base_color_factor[2] = 0.3f;
    CHECK(t, mvr_scene_add_material(s, &md, &f->grey) == MVR_OK);
    md.name = "red";
    md.base_color_factor[0] = 0.8f;
    md.base_color_factor[1] = md.base_color_factor[2] = 0.05f;
    CHECK(t, mvr_scene_add_material(s, &md, &f->red) == MVR_OK);
    md.name = "glass";
    md.alpha_mode = MVR_ALPHA_BLEND;
    md.base_color_factor[3] = 0.5f;
    CHECK(t, mvr_scene_add_material(s, &md, &f->glass) == MVR_OK);
    mvr_primitive_desc pd[2] = {{.vertex_count = 3, .positions = tri, .material = f->white},
                                {.vertex_count = 3, .positions = tri, .material = f->grey}};
    mvr_mesh_desc mesh = {.primitives = pd, .primitive_count = 2, .name = "board"};
    CHECK(t, mvr_scene_add_mesh(s, &mesh, &f->board) == MVR_OK);
    pd[0].material = (mvr_material_id){0}; /* the ball: the default material */
    mesh = (mvr_mesh_desc){.primitives = pd, .primitive_count = 1, .name = "ball"};
    CHECK(t, mvr_scene_add_mesh(s, &mesh, &f->ball) == MVR_OK);
    mvr_node_desc nd = {.mesh = f->board, .name = "board"};
    mvr_node_id node;
    CHECK(t, mvr_scene_add_node(s, &nd, &node) == MVR_OK);
    nd = (mvr_node_desc){.mesh = f->ball, .name = "ball", .translation = {0, 0, -3}};
    CHECK(t, mvr_scene_add_node(s, &nd, &node) == MVR_OK);
    CHECK(t, mvr_scene_add_variant(s, "red", &f->v_red) == MVR_OK);
    CHECK(t, mvr_scene_add_variant(s, "blue", &f->v_blue) == MVR_OK);
    CHECK(t, mvr_scene_add_variant(s, "glass", &f->v_glass) == MVR_OK);
    CHECK(t, f->v_red == 0 && f->v_blue == 1 && f->v_glass == 2);
    /* the board's paint: red in "red", the glass in "glass" ("blue" has no
     * blue material here: it maps the ball only); its frame: no mappings */
    mvr_variant_mapping paint[2] = {{f->v_red, f->red}, {f->v_glass, f->glass}};
    CHECK_MSG(t, mvr_scene_set_primitive_variants(s, f->board, 0, paint, 2) == MVR_OK, "%s",
              mvr_scene_last_error(s));
    /* the ball: the red material in "blue" (any material will do), the
     * default material in "glass" (material 0) */
    mvr_variant_mapping ball[2] = {{f->v_blue, f->red}, {f->v_glass, {0}}};
    CHECK_MSG(t, mvr_scene_set_primitive_variants(s, f->ball, 0, ball, 2) == MVR_OK, "%s", mvr_scene_last_error(s));
    return true;
}

/* The materials of the board's paint, its frame and the ball, as the
 * scene's primitives hold them (index; MVR_NO_INDEX = default). */
static void expect(mvr_test_state *t, const fixture *f, int line, mvr_material_id paint, mvr_material_id frame,
                   mvr_material_id ball)
{
    const mvr_material_id want[3] = {paint, frame, ball};
    for (uint32_t i = 0; i < 3; ++i) {
        uint32_t w = want[i].id ? want[i].id - 1 : MVR_NO_INDEX;
        CHECK_MSG(t, f->s->primitives[i].material == w, "line %d: primitive %u has material %d, expected %d", line, i,
                  (int)f->s->primitives[i].material, (int)w);
    }
}
#define EXPECT(paint, frame, ball) expect(t, &f, __LINE__, paint, frame, ball)

static const mvr_material_id none = {0};

static void selection_switches_materials(mvr_test_state *t)
{
    fixture f;
    if (!build(t, &f))
        return;
    mvr_scene *s = f.s;
    CHECK_EQ_INT(t, mvr_scene_variant_count(s), 3);
    CHECK(t, mvr_scene_selected_variant(s) == MVR_VARIANT_DEFAULT);
    EXPECT(f.white, f.grey, none);
    /* setting mappings while the default is selected changes no material */
    uint64_t v0 = s->material_version, g0 = s->geometry_version, x0 = s->transform_version;
    CHECK(t, mvr_scene_select_variant(s, f.v_red) == MVR_OK);
    CHECK(t, mvr_scene_selected_variant(s) == f.v_red);
    EXPECT(f.red, f.grey, none);
    uint64_t v1 = s->material_version;
    CHECK(t, v1 != v0);
    /* only the material version moves: no geometry, no transforms */
    CHECK(t, s->geometry_version == g0 && s->transform_version == x0);
    /* the same variant again: nothing at all */
    CHECK(t, mvr_scene_select_variant(s, f.v_red) == MVR_OK);
    CHECK(t, s->material_version == v1);
    EXPECT(f.red, f.grey, none);
    /* "blue": the paint has no mapping for it (back to its own), the ball has */
    CHECK(t, mvr_scene_select_variant(s, f.v_blue) == MVR_OK);
    EXPECT(f.white, f.grey, f.red);
    CHECK(t, s->material_version != v1);
    CHECK(t, mvr_scene_select_variant(s, f.v_glass) == MVR_OK);
    EXPECT(f.glass, f.grey, none);
    /* the default restores every primitive's own material */
    CHECK(t, mvr_scene_select_variant(s, MVR_VARIANT_DEFAULT) == MVR_OK);
    CHECK(t, mvr_scene_selected_variant(s) == MVR_VARIANT_DEFAULT);
    EXPECT(f.white, f.grey, none);
    uint64_t v2 = s->material_version;
    CHECK(t, mvr_scene_select_variant(s, MVR_VARIANT_DEFAULT) == MVR_OK);
    CHECK(t, s->material_version == v2);
    mvr_scene_destroy(s);
}

static void a_variant_that_changes_nothing_moves_nothing(mvr_test_state *t)
{
    fixture f;
    if (!build(t, &f))
        return;
    mvr_scene *s = f.s;
    /* a fourth variant no primitive maps: selecting it (from the default)
     * changes no material */
    uint32_t v_none = 0;
    CHECK(t, mvr_scene_add_variant(s, "unused", &v_none) == MVR_OK);
    uint64_t v0 = s->material_version;
    CHECK(t, mvr_scene_select_variant(s, v_none) == MVR_OK);
    CHECK(t, mvr_scene_selected_variant(s) == v_none);
    CHECK(t, s->material_version == v0);
    EXPECT(f.white, f.grey, none);
    mvr_scene_destroy(s);
}

static void mappings_set_while_selected_apply_at_once(mvr_test_state *t)
{
    fixture f;
    if (!build(t, &f))
        return;
    mvr_scene *s = f.s;
    CHECK(t, mvr_scene_select_variant(s, f.v_red) == MVR_OK);
    EXPECT(f.red, f.grey, none);
    /* the frame gets "red" -> the glass while "red" is selected */
    uint64_t v0 = s->material_version;
    mvr_variant_mapping m = {f.v_red, f.glass};
    CHECK(t, mvr_scene_set_primitive_variants(s, f.board, 1, &m, 1) == MVR_OK);
    EXPECT(f.red, f.glass, none);
    CHECK(t, s->material_version != v0);
    /* removing the paint's mappings puts its own material back */
    uint64_t v1 = s->material_version;
    CHECK(t, mvr_scene_set_primitive_variants(s, f.board, 0, NULL, 0) == MVR_OK);
    EXPECT(f.white, f.glass, none);
    CHECK(t, s->material_version != v1);
    /* setting the ball's mappings again, unchanged for "red": no version */
    uint64_t v2 = s->material_version;
    mvr_variant_mapping ball = {f.v_blue, f.grey};
    CHECK(t, mvr_scene_set_primitive_variants(s, f.ball, 0, &ball, 1) == MVR_OK);
    CHECK(t, s->material_version == v2);
    CHECK(t, mvr_scene_select_variant(s, MVR_VARIANT_DEFAULT) == MVR_OK);
    EXPECT(f.white, f.grey, none);
    mvr_scene_destroy(s);
}

/* The frame (what a renderer draws) follows the selection. */
static void the_frame_draws_the_selected_materials(mvr_test_state *t)
{
    fixture f;
    if (!build(t, &f))
        return;
    mvr_scene *s = f.s;
    mvr_frame fr;
    memset(&fr, 0, sizeof fr);
    char why[128];
    uint32_t opaque[2], blend[2];
    for (int k = 0; k < 2; ++k) {
        CHECK(t, mvr_scene_select_variant(s, k ? f.v_glass : MVR_VARIANT_DEFAULT) == MVR_OK);
        CHECK(t, mvr_frame_build(&fr, s, mvr_dvec3_make(0, 0, 0), 256, 64, NULL, why, sizeof why) == MVR_OK);
        CHECK_EQ_INT(t, fr.draw_count, 3);
        opaque[k] = fr.pass_count[MVR_PASS_OPAQUE];
        blend[k] = fr.pass_count[MVR_PASS_BLEND];
        bool paint_seen = false;
        for (uint32_t i = 0; i < fr.draw_count; ++i)
            if (fr.draws[i].primitive == 0) {
                paint_seen = true;
                CHECK_EQ_INT(t, fr.draws[i].material, k ? f.glass.id - 1 : f.white.id - 1);
                CHECK(t, fr.draws[i].pass == (k ? MVR_PASS_BLEND : MVR_PASS_OPAQUE));
            }
        CHECK(t, paint_seen);
    }
    CHECK(t, opaque[0] == 3 && blend[0] == 0);
    CHECK(t, opaque[1] == 2 && blend[1] == 1);
    mvr_frame_free(&fr);
    mvr_scene_destroy(s);
}

static void names(mvr_test_state *t)
{
    fixture f;
    if (!build(t, &f))
        return;
    mvr_scene *s = f.s;
    CHECK(t, strcmp(mvr_scene_variant_name(s, 1), "blue") == 0);
    CHECK(t, mvr_scene_variant_name(s, 3) == NULL);
    CHECK(t, mvr_scene_variant_name(s, MVR_VARIANT_DEFAULT) == NULL);
    uint32_t i = 99;
    CHECK(t, mvr_scene_find_variant(s, "glass", &i) == MVR_OK && i == 2);
    /* glTF allows equal names: the first is found */
    uint32_t again = 0;
    CHECK(t, mvr_scene_add_variant(s, "blue", &again) == MVR_OK && again == 3);
    CHECK(t, mvr_scene_find_variant(s, "blue", &i) == MVR_OK && i == 1);
    /* an empty name is a name; a long one is kept whole */
    char long_name[300];
    memset(long_name, 'x', sizeof long_name - 1);
    long_name[sizeof long_name - 1] = '\0';
    CHECK(t, mvr_scene_add_variant(s, "", NULL) == MVR_OK);
    CHECK(t, mvr_scene_add_variant(s, long_name, NULL) == MVR_OK);
    CHECK(t, mvr_scene_find_variant(s, long_name, &i) == MVR_OK && i == 5);
    CHECK(t, mvr_scene_find_variant(s, "", &i) == MVR_OK && i == 4);
    /* unknown: refused, naming the variants there are */
    CHECK(t, mvr_scene_find_variant(s, "green", &i) == MVR_ERROR_INVALID_ARGUMENT);
    const char *e = mvr_scene_last_error(s);
    CHECK_MSG(t, strstr(e, "'green'") && strstr(e, "'red', 'blue', 'glass'"), "%s", e);
    mvr_scene_destroy(s);
    /* a scene without variants */
    CHECK(t, mvr_scene_create(NULL, &s, NULL) == MVR_OK);
    CHECK_EQ_INT(t, mvr_scene_variant_count(s), 0);
    CHECK(t, mvr_scene_find_variant(s, "red", &i) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "0 variants") != NULL);
    CHECK(t, mvr_scene_select_variant(s, MVR_VARIANT_DEFAULT) == MVR_OK);
    CHECK(t, mvr_scene_select_variant(s, 0) == MVR_ERROR_INVALID_ARGUMENT);
    mvr_scene_destroy(s);
}

static void bad_input_is_refused(mvr_test_state *t)
{
    fixture f;
    if (!build(t, &f))
        return;
    mvr_scene *s = f.s;
    uint64_t v0 = s->material_version;
    CHECK(t, mvr_scene_select_variant(s, 3) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_scene_last_error(s), "variant 3 out of range (3 variants)") != NULL);
    CHECK(t, mvr_scene_selected_variant(s) == MVR_VARIANT_DEFAULT);
    struct {
        mvr_mesh_id mesh;
        uint32_t primitive;
        mvr_variant_mapping m[2];
        uint32_t count;
        const char *message;
    } bad[] = {
        {{0}, 0, {{0, {1}}}, 1, "mesh 0 out of range (2 meshes)"},
        {{3}, 0, {{0, {1}}}, 1, "mesh 3 out of range"},
        {f.board, 2, {{0, {1}}}, 1, "(board): primitive 2 out of range (2 primitives)"},
        {f.ball, 0, {{0, {1}}, {3, {1}}}, 2, "(ball): primitive 0, mapping 1 names variant 3; the scene has 3"},
        {f.board, 1, {{0, {5}}}, 1, "(board): primitive 1, mapping 0 names material 5; the scene has 4"},
        {f.board, 1, {{1, {1}}, {1, {2}}}, 2, "(board): primitive 1, mappings 0 and 1 both name variant 1"},
        {f.board, 1, {{0}}, 1, NULL}, /* mappings NULL with a count */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        mvr_result r = mvr_scene_set_primitive_variants(s, bad[i].mesh, bad[i].primitive,
                                                        bad[i].message ? bad[i].m : NULL, bad[i].count);
        CHECK_MSG(t, r == MVR_ERROR_INVALID_ARGUMENT, "case %zu: %d", i, (int)r);
        const char *want = bad[i].message ? bad[i].message : "NULL argument";
        CHECK_MSG(t, strstr(mvr_scene_last_error(s), want) != NULL, "case %zu: '%s', expected '%s'", i,
                  mvr_scene_last_error(s), want);
    }
    /* a refusal leaves the mappings as they were */
    CHECK(t, mvr_scene_select_variant(s, f.v_red) == MVR_OK);
    EXPECT(f.red, f.grey, none);
    CHECK(t, mvr_scene_select_variant(s, MVR_VARIANT_DEFAULT) == MVR_OK);
    CHECK(t, s->material_version != v0);
    CHECK(t, mvr_scene_add_variant(s, NULL, NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_scene_add_variant(NULL, "x", NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_scene_select_variant(NULL, 0) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_scene_set_primitive_variants(NULL, f.board, 0, NULL, 0) == MVR_ERROR_INVALID_ARGUMENT);
    uint32_t i;
    CHECK(t, mvr_scene_find_variant(s, NULL, &i) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, mvr_scene_find_variant(s, "red", NULL) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK_EQ_INT(t, mvr_scene_variant_count(NULL), 0);
    CHECK(t, mvr_scene_variant_name(NULL, 0) == NULL);
    CHECK(t, mvr_scene_selected_variant(NULL) == MVR_VARIANT_DEFAULT);
    mvr_scene_destroy(s);
}

MVR_TEST_MAIN(TEST(selection_switches_materials), TEST(a_variant_that_changes_nothing_moves_nothing),
              TEST(mappings_set_while_selected_apply_at_once), TEST(the_frame_draws_the_selected_materials),
              TEST(names), TEST(bad_input_is_refused))
