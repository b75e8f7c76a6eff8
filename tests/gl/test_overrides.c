#define _POSIX_C_SOURCE 200809L
/* gl: the renderer's overrides. The library reads no environment variable
 * by itself: a renderer made with zero overrides ignores MVR_* variables.
 * mvr_renderer_overrides_from_env (the one opt-in, which the CLI and the
 * viewer call) parses each of its eight variables, and refuses a bad value
 * with a message naming the variable. Each override wins over the
 * descriptor field it names; out-of-range overrides are refused.
 * (This test's process is its own: the setenv here touches no other test.) */
#include <stdlib.h>
#include <string.h>

#include "gl_test_util.h"
#include "renderer.h"
#include "shader_gen.h"
#include "targets.h"

static const char *const variables[] = {"MVR_VIEW_PATH",   "MVR_MATERIAL_PATH",  "MVR_DEPTH",
                                        "MVR_CULLING",     "MVR_INSTANCING",     "MVR_MSAA_MULTIVIEW",
                                        "MVR_FORCE_FEATURES", "MVR_UBO_ALIGNMENT", "MVR_SKINNING_PATH",
                                        "MVR_DISABLE_FEATURES", "MVR_ANISOTROPIC"};

static void clear_variables(void)
{
    for (size_t i = 0; i < sizeof variables / sizeof variables[0]; ++i)
        unsetenv(variables[i]);
}

static bool all_zero(const mvr_renderer_overrides *o)
{
    static const mvr_renderer_overrides zero;
    return memcmp(o, &zero, sizeof zero) == 0;
}

/* Every variable and value it takes, and what it fills. */
static void from_env_parses_every_variable(mvr_test_state *t)
{
    clear_variables();
    mvr_renderer_overrides o;
    mvr_error err;
    memset(&o, 0xff, sizeof o);
    CHECK(t, mvr_renderer_overrides_from_env(&o, &err) == MVR_OK && all_zero(&o));
    setenv("MVR_VIEW_PATH", "", 1); /* empty = unset */
    CHECK(t, mvr_renderer_overrides_from_env(&o, &err) == MVR_OK && all_zero(&o));
    setenv("MVR_VIEW_PATH", "loop", 1);
    setenv("MVR_MATERIAL_PATH", "per_material", 1);
    setenv("MVR_DEPTH", "standard", 1);
    setenv("MVR_CULLING", "off", 1);
    setenv("MVR_INSTANCING", "on", 1);
    setenv("MVR_MSAA_MULTIVIEW", "off", 1);
    setenv("MVR_FORCE_FEATURES", "inert", 1);
    setenv("MVR_UBO_ALIGNMENT", "256", 1);
    setenv("MVR_SKINNING_PATH", "preskin", 1);
    setenv("MVR_DISABLE_FEATURES", "CLEARCOAT,SPECULAR", 1);
    setenv("MVR_ANISOTROPIC", "off", 1);
    CHECK(t, mvr_renderer_overrides_from_env(&o, &err) == MVR_OK);
    CHECK_EQ_INT(t, o.anisotropic, MVR_OVERRIDE_OFF);
    CHECK_EQ_INT(t, o.skinning_path, MVR_SKINNING_PATH_OVERRIDE_PRESKIN);
    CHECK_EQ_INT(t, o.disable_features, MVR_FEATURE_CLEARCOAT | MVR_FEATURE_SPECULAR);
    CHECK_EQ_INT(t, o.view_path, MVR_VIEW_PATH_OVERRIDE_LOOP);
    CHECK_EQ_INT(t, o.material_path, MVR_MATERIAL_PATH_OVERRIDE_PER_MATERIAL);
    CHECK_EQ_INT(t, o.depth_mode, MVR_DEPTH_MODE_OVERRIDE_STANDARD);
    CHECK_EQ_INT(t, o.culling, MVR_OVERRIDE_OFF);
    CHECK_EQ_INT(t, o.instancing, MVR_OVERRIDE_ON);
    CHECK_EQ_INT(t, o.msaa_multiview, MVR_OVERRIDE_OFF);
    CHECK(t, o.force_inert_features);
    CHECK_EQ_INT(t, o.ubo_alignment, 256);
    setenv("MVR_VIEW_PATH", "auto", 1);
    setenv("MVR_MATERIAL_PATH", "per_draw", 1);
    setenv("MVR_DEPTH", "reversed_z", 1);
    setenv("MVR_CULLING", "on", 1);
    setenv("MVR_INSTANCING", "off", 1);
    setenv("MVR_MSAA_MULTIVIEW", "on", 1);
    setenv("MVR_UBO_ALIGNMENT", "4096", 1);
    setenv("MVR_SKINNING_PATH", "vertex", 1);
    setenv("MVR_DISABLE_FEATURES", "CLEARCOAT", 1);
    setenv("MVR_ANISOTROPIC", "on", 1);
    CHECK(t, mvr_renderer_overrides_from_env(&o, &err) == MVR_OK);
    CHECK_EQ_INT(t, o.anisotropic, MVR_OVERRIDE_ON);
    CHECK_EQ_INT(t, o.skinning_path, MVR_SKINNING_PATH_OVERRIDE_VERTEX);
    CHECK_EQ_INT(t, o.disable_features, MVR_FEATURE_CLEARCOAT);
    CHECK_EQ_INT(t, o.view_path, MVR_VIEW_PATH_OVERRIDE_AUTO);
    CHECK_EQ_INT(t, o.material_path, MVR_MATERIAL_PATH_OVERRIDE_PER_DRAW);
    CHECK_EQ_INT(t, o.depth_mode, MVR_DEPTH_MODE_OVERRIDE_REVERSED_Z);
    CHECK_EQ_INT(t, o.culling, MVR_OVERRIDE_ON);
    CHECK_EQ_INT(t, o.instancing, MVR_OVERRIDE_OFF);
    CHECK_EQ_INT(t, o.msaa_multiview, MVR_OVERRIDE_ON);
    CHECK_EQ_INT(t, o.ubo_alignment, 4096);
    CHECK(t, mvr_renderer_overrides_from_env(NULL, &err) == MVR_ERROR_INVALID_ARGUMENT);
    clear_variables();
}

/* A bad value fails naming the variable and the value; *out stays all zero. */
static void from_env_refuses_bad_values(mvr_test_state *t)
{
    static const struct {
        const char *name, *value;
    } bad[] = {{"MVR_VIEW_PATH", "bogus"},       {"MVR_MATERIAL_PATH", "bogus"}, {"MVR_DEPTH", "reversed"},
               {"MVR_CULLING", "0"},             {"MVR_INSTANCING", "OFF"},      {"MVR_MSAA_MULTIVIEW", "no"}, {"MVR_ANISOTROPIC", "16"},
               {"MVR_FORCE_FEATURES", "all"},    {"MVR_UBO_ALIGNMENT", "100"},   {"MVR_UBO_ALIGNMENT", "8192"},
               {"MVR_UBO_ALIGNMENT", "256x"},    {"MVR_UBO_ALIGNMENT", "-256"},  {"MVR_UBO_ALIGNMENT", "0"},
               {"MVR_SKINNING_PATH", "gpu"},     {"MVR_DISABLE_FEATURES", "NORMALS"},
               {"MVR_DISABLE_FEATURES", "CLEARCOAT,"}, {"MVR_DISABLE_FEATURES", "clearcoat"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        clear_variables();
        setenv("MVR_VIEW_PATH", "loop", 1); /* a good one beside it */
        setenv(bad[i].name, bad[i].value, 1);
        mvr_renderer_overrides o;
        mvr_error err;
        memset(&o, 0xff, sizeof o);
        CHECK_MSG(t, mvr_renderer_overrides_from_env(&o, &err) == MVR_ERROR_INVALID_ARGUMENT, "%s=%s accepted",
                  bad[i].name, bad[i].value);
        CHECK_MSG(t, strstr(err.message, bad[i].name) && strstr(err.message, bad[i].value), "%s=%s: \"%s\"",
                  bad[i].name, bad[i].value, err.message);
        CHECK(t, all_zero(&o));
        printf("  %s\n", err.message);
    }
    clear_variables();
}

/* Variables set, no opt-in: the renderer follows its descriptor alone. */
static void library_reads_no_environment(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    setenv("MVR_VIEW_PATH", "loop", 1);
    setenv("MVR_MATERIAL_PATH", "per_draw", 1);
    setenv("MVR_DEPTH", "standard", 1);
    setenv("MVR_CULLING", "off", 1);
    setenv("MVR_INSTANCING", "off", 1);
    setenv("MVR_FORCE_FEATURES", "inert", 1);
    setenv("MVR_UBO_ALIGNMENT", "4096", 1);
    mvr_renderer_desc rd = {.context = ctx, .view_path = MVR_VIEW_PATH_MULTIVIEW};
    mvr_renderer *r = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_renderer_create(&rd, &r, &err) == MVR_OK, "%s", err.message);
    if (r) {
        bool clip_control = mvr_context_caps(ctx)->ext.ext_clip_control && ctx->gl.ClipControl;
        CHECK_EQ_INT(t, r->requested_path, MVR_VIEW_PATH_MULTIVIEW);
        CHECK_EQ_INT(t, r->material_path, MVR_MATERIAL_PATH_ARRAYS);
        CHECK(t, r->reversed_z == clip_control);
        CHECK(t, r->culling && !r->force_inert_features && !r->msaa_multiview_off);
        CHECK(t, r->ubo_alignment < 4096);
    }
    mvr_renderer_destroy(r);
    clear_variables();
    mvr_context_destroy(ctx);
}

/* Each override wins over its descriptor field; out-of-range values are refused. */
static void overrides_win_over_the_descriptor(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    mvr_renderer_desc rd = {.context = ctx, .view_path = MVR_VIEW_PATH_MULTIVIEW,
                            .material_path = MVR_MATERIAL_PATH_PER_DRAW, .disable_culling = true,
                            .disable_instancing = true, .depth_mode = MVR_DEPTH_MODE_STANDARD};
    rd.overrides = (mvr_renderer_overrides){.view_path = MVR_VIEW_PATH_OVERRIDE_LOOP,
                                            .material_path = MVR_MATERIAL_PATH_OVERRIDE_ARRAYS,
                                            .depth_mode = MVR_DEPTH_MODE_OVERRIDE_AUTO,
                                            .culling = MVR_OVERRIDE_ON,
                                            .instancing = MVR_OVERRIDE_ON,
                                            .msaa_multiview = MVR_OVERRIDE_OFF,
                                            .force_inert_features = true,
                                            .ubo_alignment = 2048};
    mvr_renderer *r = NULL;
    mvr_error err;
    CHECK_MSG(t, mvr_renderer_create(&rd, &r, &err) == MVR_OK, "%s", err.message);
    if (r) {
        bool clip_control = mvr_context_caps(ctx)->ext.ext_clip_control && ctx->gl.ClipControl;
        CHECK_EQ_INT(t, r->requested_path, MVR_VIEW_PATH_LOOP);
        CHECK_EQ_INT(t, r->material_path, MVR_MATERIAL_PATH_ARRAYS);
        CHECK(t, r->reversed_z == clip_control);
        CHECK(t, r->culling && r->force_inert_features && r->msaa_multiview_off);
        CHECK_EQ_INT(t, r->ubo_alignment, 2048);
        CHECK(t, r->draw_capacity >= 1);
        /* MSAA off multiview: the target keeps no multisampled multiview */
        mvr_target_desc td = {32, 32, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 4, 0, MVR_ANTI_ALIASING_DEFAULT, 0};
        mvr_target *target = NULL;
        if (mvr_target_create(r, &td, &target) == MVR_OK)
            CHECK_EQ_INT(t, target->msaa_multiview, MVR_MSAA_MV_NONE);
        mvr_target_destroy(target);
    }
    mvr_renderer_destroy(r);
    rd.overrides = (mvr_renderer_overrides){.culling = MVR_OVERRIDE_OFF, .instancing = MVR_OVERRIDE_OFF};
    rd.disable_culling = rd.disable_instancing = false;
    rd.material_path = MVR_MATERIAL_PATH_AUTO;
    CHECK_MSG(t, mvr_renderer_create(&rd, &r, &err) == MVR_OK, "%s", err.message);
    if (r)
        CHECK(t, !r->culling && r->draw_capacity == 1);
    mvr_renderer_destroy(r);
    static const struct {
        mvr_renderer_overrides o;
        const char *field;
    } bad[] = {{{.view_path = (mvr_view_path_override)4}, "overrides.view_path"},
               {{.material_path = (mvr_material_path_override)5}, "overrides.material_path"},
               {{.depth_mode = (mvr_depth_mode_override)4}, "overrides.depth_mode"},
               {{.culling = (mvr_override_switch)3}, "overrides.culling"},
               {{.instancing = (mvr_override_switch)3}, "overrides.instancing"},
               {{.msaa_multiview = (mvr_override_switch)3}, "overrides.msaa_multiview"},
               {{.ubo_alignment = 96}, "overrides.ubo_alignment"},
               {{.ubo_alignment = 8192}, "overrides.ubo_alignment"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        rd.overrides = bad[i].o;
        r = NULL;
        CHECK(t, mvr_renderer_create(&rd, &r, &err) == MVR_ERROR_INVALID_ARGUMENT && r == NULL);
        CHECK_MSG(t, strstr(err.message, bad[i].field) != NULL, "%s: \"%s\"", bad[i].field, err.message);
    }
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(from_env_parses_every_variable), TEST(from_env_refuses_bad_values),
              TEST(library_reads_no_environment), TEST(overrides_win_over_the_descriptor))
