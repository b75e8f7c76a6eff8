/* core: the frame plan, without GL: chunking, path choices, MSAA fallbacks,
 * resolves, post, sub-pass records and their reasons, and its text. */
#include <string.h>

#include "frame_plan.h"
#include "mvr_test.h"

#define MAX_TEST_VIEWS 80

typedef struct fixture {
    mvr_view_desc views[MAX_TEST_VIEWS];
    mvr_view_set set;
    mvr_frame_plan_input in;
    mvr_frame_plan plan;
} fixture;

/* n full-layer views, 64x64, multiview with 6 views a pass, one draw of each kind */
static void setup(fixture *f, uint32_t n)
{
    memset(f, 0, sizeof *f);
    f->set.views = f->views;
    f->set.count = n;
    f->in.views = &f->set;
    f->in.width = f->in.height = 64;
    f->in.samples = 1;
    f->in.factor = 1;
    f->in.unorm8 = true;
    f->in.max_views = 6;
    f->in.path = MVR_VIEW_PATH_MULTIVIEW;
    f->in.blend_policy = MVR_TRANSPARENCY_ORDER_CENTROID;
    for (int k = 0; k < MVR_PASS_KIND_COUNT; ++k)
        f->in.draws[k] = 1;
}

static uint32_t count_kind(const mvr_frame_plan *p, mvr_plan_kind kind, mvr_plan_when when)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < p->count; ++i)
        n += p->records[i].kind == kind && p->records[i].when == when;
    return n;
}

static const mvr_plan_record *find(const mvr_frame_plan *p, mvr_plan_kind kind, uint32_t nth)
{
    for (uint32_t i = 0; i < p->count; ++i)
        if (p->records[i].kind == kind && nth-- == 0)
            return &p->records[i];
    return NULL;
}

static void sixteen_views_by_six(mvr_test_state *t)
{
    fixture f;
    setup(&f, 16);
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, f.plan.multiview && f.plan.path == MVR_VIEW_PATH_MULTIVIEW);
    CHECK_EQ_INT(t, f.plan.chunk_count, 3);
    CHECK_EQ_INT(t, f.plan.chunks[0].base, 0);
    CHECK_EQ_INT(t, f.plan.chunks[0].count, 6);
    CHECK_EQ_INT(t, f.plan.chunks[1].base, 6);
    CHECK_EQ_INT(t, f.plan.chunks[1].count, 6);
    CHECK_EQ_INT(t, f.plan.chunks[2].base, 12);
    CHECK_EQ_INT(t, f.plan.chunks[2].count, 4);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_VIEW_PASS, MVR_PLAN_RUN), 3);
    /* the order: uploads, shadows, then per chunk view pass, opaque, mask,
     * background, transmission copy, blend */
    static const mvr_plan_kind order[] = {MVR_PLAN_UPLOAD,     MVR_PLAN_SHADOW_MAPS,  MVR_PLAN_VIEW_PASS,
                                          MVR_PLAN_OPAQUE,     MVR_PLAN_MASK,         MVR_PLAN_BACKGROUND,
                                          MVR_PLAN_TRANSMISSION, MVR_PLAN_BLEND,      MVR_PLAN_VIEW_PASS};
    for (size_t i = 0; i < sizeof order / sizeof order[0]; ++i)
        CHECK_EQ_INT(t, f.plan.records[i].kind, order[i]);
    const mvr_plan_record *vp = find(&f.plan, MVR_PLAN_VIEW_PASS, 2);
    CHECK(t, vp && vp->first_view == 12 && vp->views == 4 && vp->multiview && vp->chunk == 2);
    /* each chunk's last record closes it */
    uint32_t ends = 0;
    for (uint32_t i = 0; i < f.plan.count; ++i)
        ends += f.plan.records[i].ends_chunk;
    CHECK_EQ_INT(t, ends, 3);
    CHECK(t, f.plan.records[f.plan.count - 1].kind == MVR_PLAN_POST);
    CHECK(t, f.plan.records[f.plan.count - 1].when == MVR_PLAN_SKIP);
    /* more views than the block holds: chunks never cross a block of 64 */
    f.in.max_views = 1000;
    f.set.count = 80;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, f.plan.chunk_count, 2);
    CHECK_EQ_INT(t, f.plan.chunks[0].count, 64);
    CHECK_EQ_INT(t, f.plan.chunks[1].base, 64);
    mvr_frame_plan_free(&f.plan);
}

static void chunks_split_at_viewports_and_disabled_views(mvr_test_state *t)
{
    fixture f;
    setup(&f, 8);
    f.views[3].disabled = true;
    f.views[5].viewport = (mvr_viewport){0, 0, 32, 32};
    f.views[6].viewport = (mvr_viewport){0, 0, 32, 32};
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    /* 0-2 | 4 | 5-6 (half viewport) | 7 */
    CHECK_EQ_INT(t, f.plan.chunk_count, 4);
    CHECK(t, f.plan.chunks[1].base == 4 && f.plan.chunks[1].count == 1);
    CHECK(t, f.plan.chunks[2].base == 5 && f.plan.chunks[2].count == 2 && f.plan.chunks[2].viewport.width == 32);
    /* a one-view chunk of the multiview path is a plain pass */
    const mvr_plan_record *vp = find(&f.plan, MVR_PLAN_VIEW_PASS, 1);
    CHECK(t, vp && !vp->multiview);
    mvr_frame_plan_free(&f.plan);
}

static void the_loop_path_passes_one_view_each(mvr_test_state *t)
{
    fixture f;
    setup(&f, 5);
    f.in.path = MVR_VIEW_PATH_LOOP;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, !f.plan.multiview);
    CHECK_EQ_INT(t, f.plan.chunk_count, 5);
    for (uint32_t c = 0; c < f.plan.chunk_count; ++c)
        CHECK(t, f.plan.chunks[c].base == c && f.plan.chunks[c].count == 1);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_VIEW_PASS, MVR_PLAN_RUN), 5);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BLEND_VIEW, MVR_PLAN_RUN), 0);
    CHECK(t, f.plan.encode_in_mesh);
    mvr_frame_plan_free(&f.plan);
}

static void msaa_falls_back_to_the_loop(mvr_test_state *t)
{
    fixture f;
    setup(&f, 4);
    f.in.samples = 4;
    /* no multisampled multiview */
    f.in.msaa_multiview = MVR_MSAA_MV_NONE;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, f.plan.path == MVR_VIEW_PATH_LOOP && !f.plan.msaa_multiview);
    CHECK_EQ_INT(t, f.plan.chunk_count, 4);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_MSAA_RESOLVE, MVR_PLAN_RUN), 4);
    const mvr_plan_record *rs = find(&f.plan, MVR_PLAN_MSAA_RESOLVE, 0);
    CHECK(t, rs && rs->views == 1 && !rs->msaa && !rs->depth && rs->ends_chunk);
    /* multisampled multiview, but a post pass: the loop, resolving depth too */
    f.in.msaa_multiview = MVR_MSAA_MV_ARRAY;
    f.in.post = true;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, f.plan.path == MVR_VIEW_PATH_LOOP && f.plan.hdr_frame);
    rs = find(&f.plan, MVR_PLAN_MSAA_RESOLVE, 0);
    CHECK(t, rs && rs->depth);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_POST, MVR_PLAN_RUN), 1);
    /* multisampled multiview: array mode resolves layer by layer */
    f.in.post = false;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, f.plan.path == MVR_VIEW_PATH_MULTIVIEW && f.plan.msaa_multiview);
    CHECK_EQ_INT(t, f.plan.chunk_count, 1);
    rs = find(&f.plan, MVR_PLAN_MSAA_RESOLVE, 0);
    CHECK(t, rs && rs->when == MVR_PLAN_RUN && rs->views == 4 && rs->msaa);
    /* render to texture: the GL resolves */
    f.in.msaa_multiview = MVR_MSAA_MV_RENDER_TO_TEXTURE;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_MSAA_RESOLVE, MVR_PLAN_SKIP), 1);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_MSAA_RESOLVE, MVR_PLAN_RUN), 0);
    /* multisampled multiview blends in the shared order, whatever the policy */
    f.in.blend_policy = MVR_TRANSPARENCY_ORDER_PER_VIEW;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BLEND, MVR_PLAN_RUN), 1);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BLEND_VIEW, MVR_PLAN_RUN), 0);
    mvr_frame_plan_free(&f.plan);
}

static void supersampling_resolves_unless_post(mvr_test_state *t)
{
    fixture f;
    setup(&f, 2);
    f.in.factor = 3;
    f.in.supersampled = true;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, !f.plan.encode_in_mesh);
    const mvr_plan_record *ss = find(&f.plan, MVR_PLAN_SUPERSAMPLE_RESOLVE, 0);
    CHECK(t, ss && ss->when == MVR_PLAN_RUN && ss->views == 2 && ss->multiview);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_POST, MVR_PLAN_SKIP), 1);
    /* a post pass reads the supersampled views itself; they are float already */
    f.in.post = true;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, f.plan.post && !f.plan.hdr_frame);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_SUPERSAMPLE_RESOLVE, MVR_PLAN_SKIP), 1);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_POST, MVR_PLAN_RUN), 1);
    /* no supersampling: no resolve record; post makes an HDR frame */
    f.in.factor = 1;
    f.in.supersampled = false;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, find(&f.plan, MVR_PLAN_SUPERSAMPLE_RESOLVE, 0) == NULL);
    CHECK(t, f.plan.hdr_frame && !f.plan.encode_in_mesh);
    mvr_frame_plan_free(&f.plan);
}

static void background_only_with_a_background(mvr_test_state *t)
{
    fixture f;
    setup(&f, 6);
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BACKGROUND, MVR_PLAN_SKIP), 1);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BACKGROUND, MVR_PLAN_RUN), 0);
    CHECK(t, find(&f.plan, MVR_PLAN_ENV_PREFILTER, 0) == NULL);
    f.in.background = true;
    f.in.environment = true;
    f.in.environment_new = true;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BACKGROUND, MVR_PLAN_RUN), 1);
    /* after opaque and mask, before blend */
    const mvr_plan_record *bg = find(&f.plan, MVR_PLAN_BACKGROUND, 0);
    CHECK(t, bg && bg[-1].kind == MVR_PLAN_MASK && bg[2].kind == MVR_PLAN_BLEND && bg->multiview);
    /* the environment prefilter first, once; not again for the same environment */
    CHECK(t, f.plan.records[0].kind == MVR_PLAN_ENV_PREFILTER && f.plan.records[0].when == MVR_PLAN_RUN);
    f.in.environment_new = false;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, f.plan.records[0].kind == MVR_PLAN_ENV_PREFILTER && f.plan.records[0].when == MVR_PLAN_SKIP);
    mvr_frame_plan_free(&f.plan);
}

/* Transmissive draws: a copy record per chunk, run only when there are
 * some; storage the GL resolves at the pass's end (multisampled render to
 * texture) cannot be read mid-pass: such frames take the loop path. */
static void transmission_records(mvr_test_state *t)
{
    fixture f;
    setup(&f, 8);
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_TRANSMISSION, MVR_PLAN_SKIP), 2);
    f.in.transmissive = 2;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_TRANSMISSION, MVR_PLAN_RUN), 2);
    const mvr_plan_record *tr = find(&f.plan, MVR_PLAN_TRANSMISSION, 1);
    CHECK(t, tr && tr->first_view == 6 && tr->views == 2 && tr->multiview && tr[1].kind == MVR_PLAN_BLEND &&
                 tr->draws == 2);
    f.in.samples = 4;
    f.in.msaa_multiview = MVR_MSAA_MV_RENDER_TO_TEXTURE;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, !f.plan.msaa_multiview && f.plan.path == MVR_VIEW_PATH_LOOP);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_TRANSMISSION, MVR_PLAN_RUN), 8);
    f.in.msaa_multiview = MVR_MSAA_MV_ARRAY;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, f.plan.msaa_multiview && f.plan.path == MVR_VIEW_PATH_MULTIVIEW);
    mvr_frame_plan_free(&f.plan);
}

static void blend_fallback_records(mvr_test_state *t)
{
    fixture f;
    setup(&f, 8);
    /* auto: the shared order unless the views diverge, then one pass per view */
    f.in.blend_policy = MVR_TRANSPARENCY_ORDER_AUTO;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, f.plan.chunk_count, 2);
    const mvr_plan_record *vp = find(&f.plan, MVR_PLAN_VIEW_PASS, 0);
    CHECK(t, vp && vp->blend == MVR_PLAN_BLEND_SPLIT_IF_DIVERGED);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BLEND, MVR_PLAN_IF_ORDERS_AGREE), 2);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BLEND_VIEW, MVR_PLAN_IF_ORDERS_DIVERGE), 8);
    const mvr_plan_record *bv = find(&f.plan, MVR_PLAN_BLEND_VIEW, 7);
    CHECK(t, bv && bv->first_view == 7 && bv->views == 1 && bv->chunk == 1 && bv->ends_chunk);
    /* per view: always split; the shared blend is skipped */
    f.in.blend_policy = MVR_TRANSPARENCY_ORDER_PER_VIEW;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BLEND, MVR_PLAN_SKIP), 2);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BLEND_VIEW, MVR_PLAN_RUN), 8);
    /* no blended draws: no fallback, a skipped blend */
    f.in.draws[MVR_PASS_BLEND] = 0;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BLEND, MVR_PLAN_SKIP), 2);
    CHECK(t, find(&f.plan, MVR_PLAN_BLEND_VIEW, 0) == NULL);
    /* centroid: never split */
    f.in.draws[MVR_PASS_BLEND] = 3;
    f.in.blend_policy = MVR_TRANSPARENCY_ORDER_CENTROID;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_BLEND, MVR_PLAN_RUN), 2);
    CHECK(t, find(&f.plan, MVR_PLAN_BLEND_VIEW, 0) == NULL);
    /* empty lists skip their sub-pass */
    f.in.draws[MVR_PASS_MASK] = 0;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_MASK, MVR_PLAN_SKIP), 2);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_OPAQUE, MVR_PLAN_RUN), 2);
    mvr_frame_plan_free(&f.plan);
}

static void shadow_pass_only_when_planned(mvr_test_state *t)
{
    fixture f;
    setup(&f, 3);
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_SHADOW_MAPS, MVR_PLAN_SKIP), 1);
    f.in.shadow_layers = 4;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    const mvr_plan_record *s = find(&f.plan, MVR_PLAN_SHADOW_MAPS, 0);
    CHECK(t, s && s->when == MVR_PLAN_RUN && s->draws == 4 && s->chunk == MVR_PLAN_NO_CHUNK);
    /* before every view pass */
    CHECK(t, s < find(&f.plan, MVR_PLAN_VIEW_PASS, 0));
    mvr_frame_plan_free(&f.plan);
}

static void the_plan_prints(mvr_test_state *t)
{
    fixture f;
    setup(&f, 16);
    f.in.shadow_layers = 2;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    size_t need = mvr_frame_plan_format(&f.plan, NULL, 0);
    CHECK(t, need > 0);
    char small[32];
    CHECK(t, mvr_frame_plan_format(&f.plan, small, sizeof small) == need);
    CHECK(t, strlen(small) == sizeof small - 1);
    char text[8192];
    CHECK(t, need < sizeof text);
    CHECK(t, mvr_frame_plan_format(&f.plan, text, sizeof text) == need && strlen(text) == need);
    CHECK(t, strstr(text, "16 views in 3 passes, multiview path") != NULL);
    CHECK(t, strstr(text, "shadow-maps") && strstr(text, "views 12-15") && strstr(text, "2 layers"));
    uint32_t lines = 0;
    for (const char *c = text; *c; ++c)
        lines += *c == '\n';
    CHECK_EQ_INT(t, lines, f.plan.count + 1);
    mvr_frame_plan_free(&f.plan);
}

/* Pre-skinning: a record only when something is skinned or morphed; it
 * runs once, before the shadow maps and every view, on the pre-skinning
 * path when joints or weights moved. */
static void preskin_once_before_the_views(mvr_test_state *t)
{
    fixture f;
    setup(&f, 16);
    f.in.shadow_layers = 2;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    CHECK(t, find(&f.plan, MVR_PLAN_PRESKIN, 0) == NULL);
    f.in.deforms = 3;
    f.in.preskin = true;
    f.in.deforms_moved = true;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    const mvr_plan_record *p = find(&f.plan, MVR_PLAN_PRESKIN, 0);
    CHECK(t, p && p->when == MVR_PLAN_RUN && p->draws == 3 && p->views == 16);
    CHECK_EQ_INT(t, count_kind(&f.plan, MVR_PLAN_PRESKIN, MVR_PLAN_RUN), 1);
    CHECK(t, p < find(&f.plan, MVR_PLAN_SHADOW_MAPS, 0) && p < find(&f.plan, MVR_PLAN_VIEW_PASS, 0));
    f.in.deforms_moved = false;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    p = find(&f.plan, MVR_PLAN_PRESKIN, 0);
    CHECK(t, p && p->when == MVR_PLAN_SKIP && strstr(p->why, "reused"));
    f.in.preskin = false;
    f.in.deforms_moved = true;
    CHECK(t, mvr_frame_plan_build(&f.plan, &f.in) == MVR_OK);
    p = find(&f.plan, MVR_PLAN_PRESKIN, 0);
    CHECK(t, p && p->when == MVR_PLAN_SKIP && strstr(p->why, "vertex path"));
    mvr_frame_plan_free(&f.plan);
}

MVR_TEST_MAIN(TEST(preskin_once_before_the_views), TEST(sixteen_views_by_six), TEST(transmission_records), TEST(chunks_split_at_viewports_and_disabled_views),
              TEST(the_loop_path_passes_one_view_each), TEST(msaa_falls_back_to_the_loop),
              TEST(supersampling_resolves_unless_post), TEST(background_only_with_a_background),
              TEST(blend_fallback_records), TEST(shadow_pass_only_when_planned), TEST(the_plan_prints))
