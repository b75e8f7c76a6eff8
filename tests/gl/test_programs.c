/* gl: every shader variant of the validation set compiles and links on the
 * real driver: GLES through EGL, and desktop GL core (OSMesa, and desktop GL
 * through EGL) running the same "#version 300 es" sources. */
#include "gl_test_util.h"
#include "program.h"

static void build_all(mvr_test_state *t, mvr_context *ctx)
{
    const mvr_caps *c = mvr_context_caps(ctx);
    uint32_t max_views = c->ext.ovr_multiview2 ? (uint32_t)c->limits.max_views_ovr : 0;
    mvr_shader_variant v;
    unsigned built = 0, skipped = 0;
    for (unsigned i = 0; mvr_shader_variant_enumerate(i, max_views ? max_views : 1, &v); ++i) {
        if (v.num_views > max_views) {
            skipped++; /* multiview variant on a GL without it */
            continue;
        }
        char name[96];
        mvr_shader_variant_name(&v, name, sizeof name);
        mvr_result r = mvr_context_check_shader_variant(ctx, &v);
        CHECK_MSG(t, r == MVR_OK, "%s on %s: %s", name, c->version, mvr_context_last_error(ctx));
        built++;
    }
    printf("  %s: %u variants built, %u multiview variants not applicable\n", c->version, built,
           skipped);
    CHECK(t, built > 20);
    CHECK(t, !mvr_test_in_ci() || skipped == 0);
}

static void variants_on_gles(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_GLES, NULL);
    if (ctx)
        build_all(t, ctx);
    mvr_context_destroy(ctx);
}

static void variants_on_osmesa_desktop(mvr_test_state *t)
{
    if (!mvr_context_provider_built(MVR_CONTEXT_PROVIDER_OSMESA))
        SKIP(t, "this build has no OSMesa provider");
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_OSMESA, MVR_GL_API_DEFAULT, NULL);
    if (ctx)
        build_all(t, ctx);
    mvr_context_destroy(ctx);
}

static void a_broken_variant_reports_the_log(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_GLES, NULL);
    if (!ctx)
        return;
    /* more views than the GL allows: refused before compiling, with the limit named */
    mvr_shader_variant v = {MVR_PROGRAM_MESH, 0, (uint32_t)mvr_context_caps(ctx)->limits.max_views_ovr + 1, 0, 0, 0, 0, 0, 0, 0};
    CHECK(t, mvr_context_check_shader_variant(ctx, &v) == MVR_ERROR_UNSUPPORTED);
    CHECK(t, strstr(mvr_context_last_error(ctx), "GL_MAX_VIEWS_OVR") != NULL);
    /* feature bits that do not exist: refused, named */
    v = (mvr_shader_variant){MVR_PROGRAM_COMPOSITE, 1u << 20, 0, 0, 0, 0, 0, 0, 0, 0};
    CHECK(t, mvr_context_check_shader_variant(ctx, &v) == MVR_ERROR_INVALID_ARGUMENT);
    CHECK(t, strstr(mvr_context_last_error(ctx), "composite") != NULL);
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(variants_on_gles), TEST(variants_on_osmesa_desktop),
              TEST(a_broken_variant_reports_the_log))
