/* mvr bench --env-axes: the environment prefilter's axes (specular map
 * size x GGX samples per texel) on a grid of spheres (or a file) under an
 * environment, each timed by its prefilter and compared with the
 * environment integrated per pixel and with converged maps. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "cli_common.h"
#include "cli_env.h"
#include "cli_scene.h"
#include "commands.h"
#include "mvr/mvr_image.h"

/* The sphere grid's roughnesses: rows 0 (dielectric) and 1 (metal) take the
 * first four, rows 2 and 3 the last four, so each roughness is seen on both
 * materials, and most fall between the levels of any map size (a map of
 * face size S has log2(S / 16) + 1 levels, roughness k / (levels - 1)). */
static const float sphere_roughness[8] = {0.0f, 0.15f, 0.3f, 0.45f, 0.6f, 0.75f, 0.9f, 1.0f};

/* A UV sphere of radius 1 (normals = positions), 64 x 32 quads. */
static bool add_sphere(mvr_scene *s, mvr_material_id material, mvr_mesh_id *out)
{
    enum { SEG = 64, RINGS = 32, NV = (SEG + 1) * (RINGS + 1), NI = SEG * RINGS * 6 };
    float *pos = malloc(sizeof(float) * NV * 3);
    uint16_t *idx = malloc(sizeof(uint16_t) * NI);
    bool ok = pos && idx;
    const double pi = 3.14159265358979323846;
    for (int j = 0; ok && j <= RINGS; ++j)
        for (int i = 0; i <= SEG; ++i) {
            double th = pi * j / RINGS, ph = 2.0 * pi * i / SEG;
            float *p = pos + (j * (SEG + 1) + i) * 3;
            p[0] = (float)(sin(th) * cos(ph));
            p[1] = (float)cos(th);
            p[2] = (float)(-sin(th) * sin(ph));
        }
    for (int j = 0, k = 0; ok && j < RINGS; ++j)
        for (int i = 0; i < SEG; ++i) {
            uint16_t a = (uint16_t)(j * (SEG + 1) + i), b = (uint16_t)(a + SEG + 1);
            const uint16_t q[6] = {a, b, (uint16_t)(a + 1), (uint16_t)(a + 1), b, (uint16_t)(b + 1)};
            for (int c = 0; c < 6; ++c)
                idx[k++] = q[c];
        }
    mvr_primitive_desc p = {.vertex_count = NV, .positions = pos, .normals = pos, .index_count = NI,
                            .indices16 = idx, .material = material};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "sphere"};
    ok = ok && mvr_scene_add_mesh(s, &md, out) == MVR_OK;
    free(pos);
    free(idx);
    return ok;
}

/* 16 spheres 2.4 apart in the XY plane, facing +Z (where the neutral
 * studio's key and fill are): blue dielectric and gold metal, 8 roughnesses
 * each; the views: the stereo framing of the grid. */
static int make_spheres(const bench_options *o, mvr_scene **scene, mvr_view_set **vs)
{
    mvr_error err;
    mvr_scene_desc sd = {o->context.logger};
    if (mvr_scene_create(&sd, scene, &err) != MVR_OK) {
        fprintf(stderr, "mvr bench: %s\n", err.message);
        return MVR_EXIT_FAILURE;
    }
    const float dielectric[3] = {0.25f, 0.45f, 0.75f}, gold[3] = {0.95f, 0.75f, 0.35f};
    for (uint32_t i = 0; i < 16; ++i) {
        uint32_t row = i / 4, col = i % 4;
        bool metal = row & 1u;
        mvr_material_desc m = mvr_material_defaults();
        memcpy(m.base_color_factor, metal ? gold : dielectric, sizeof dielectric);
        m.metallic_factor = metal ? 1.0f : 0.0f;
        m.roughness_factor = sphere_roughness[(row / 2) * 4 + col];
        mvr_material_id mat = {0};
        mvr_node_desc nd = {.translation = {((double)col - 1.5) * 2.4, (1.5 - (double)row) * 2.4, 0.0}};
        mvr_node_id node;
        if (mvr_scene_add_material(*scene, &m, &mat) != MVR_OK || !add_sphere(*scene, mat, &nd.mesh) ||
            mvr_scene_add_node(*scene, &nd, &node) != MVR_OK) {
            fprintf(stderr, "mvr bench: the sphere grid: %s\n", mvr_scene_last_error(*scene));
            return MVR_EXIT_FAILURE;
        }
    }
    mvr_framing_desc fd = {.layout = MVR_LAYOUT_STEREO, .views = o->scene.views,
                           .aspect = (double)o->scene.width / o->scene.height};
    if (mvr_view_set_frame_scene(*scene, &fd, vs, &err) != MVR_OK) {
        fprintf(stderr, "mvr bench: the sphere grid's views: %s\n", err.message);
        return MVR_EXIT_FAILURE;
    }
    return MVR_EXIT_OK;
}

/* One environment configuration on a fresh renderer: `warmup` untimed and
 * `repeats` timed first frames, each with a fresh environment made from ed
 * (so the prefilter runs every time; programs and the DFG table are made by
 * the warm-up), or one frame with `given`. The reference (loop path,
 * environment_samples) integrates the environment per pixel instead of
 * reading the maps. The last frame is read back. */
static bool run_env_config(const bench_options *o, mvr_context *ctx, mvr_scene *scene, mvr_view_set *vs,
                           const mvr_render_desc *base, const mvr_environment_desc *ed,
                           const mvr_environment *given, bool reference, uint32_t warmup, uint32_t repeats,
                           const char *name, bench_result *res, double *ev100)
{
    uint32_t n = mvr_view_set_count(vs), w = o->scene.width, h = o->scene.height;
    /* per-view transparency order on both sides: a file's blended
     * surfaces add no sorting error to the prefilter's */
    mvr_renderer_desc rd = {.context = ctx, .view_path = reference ? MVR_VIEW_PATH_LOOP : MVR_VIEW_PATH_AUTO,
                            .transparency_order = MVR_TRANSPARENCY_ORDER_PER_VIEW, .logger = o->context.logger,
                            .overrides = o->overrides};
    mvr_renderer *r = NULL;
    mvr_target *t = NULL;
    mvr_error err;
    if (mvr_renderer_create(&rd, &r, &err) != MVR_OK) {
        fprintf(stderr, "mvr bench: %s: %s\n", name, err.message);
        return false;
    }
    mvr_target_desc td = {w, h, n, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_DEFAULT, 0};
    mvr_render_desc desc = *base;
    desc.environment_samples = reference ? o->reference_samples : 0;
    if (given) {
        warmup = 0;
        repeats = 1;
    }
    double *times = calloc((size_t)repeats * 4, sizeof *times);
    double *wall = times, *cpu = times + repeats, *gpu = times + 2 * repeats, *pre = times + 3 * repeats;
    bool ok = times && mvr_target_create(r, &td, &t) == MVR_OK;
    bool lib_error = !ok;
    mvr_environment *env = NULL;
    for (uint32_t k = 0; ok && k < warmup + repeats; ++k) {
        mvr_environment *fresh = NULL;
        if (!given) {
            if (mvr_environment_create(ed, &fresh, &err) != MVR_OK) {
                fprintf(stderr, "mvr bench: %s: %s\n", name, err.message);
                ok = false;
                break;
            }
            desc.environment = fresh;
        } else {
            desc.environment = given;
        }
        double w0 = bench_now_ms(CLOCK_MONOTONIC), c0 = bench_now_ms(CLOCK_THREAD_CPUTIME_ID);
        ok = mvr_renderer_render(r, scene, vs, t, &desc) == MVR_OK && mvr_renderer_finish(r) == MVR_OK;
        double w1 = bench_now_ms(CLOCK_MONOTONIC), c1 = bench_now_ms(CLOCK_THREAD_CPUTIME_ID);
        /* the renderer keeps its maps when their environment goes */
        mvr_environment_destroy(env);
        env = fresh;
        lib_error = !ok;
        if (!ok || k < warmup)
            continue;
        mvr_frame_stats st;
        mvr_renderer_get_stats(r, &st);
        uint32_t i = k - warmup;
        wall[i] = w1 - w0;
        cpu[i] = c1 - c0;
        gpu[i] = st.gpu_ms;
        pre[i] = st.env_prefilter_ms;
        res->prefilter_passes = st.env_prefilter_passes;
        if (ev100)
            *ev100 = st.exposure_ev100;
        bench_take_stats(res, &st);
        if (st.env_prefilter_passes == 0) {
            fprintf(stderr, "mvr bench: %s: the first frame with a fresh environment ran no prefilter\n", name);
            ok = false;
        }
    }
    if (ok) {
        res->wall_min = res->wall_max = wall[0];
        res->prefilter_min = res->prefilter_max = pre[0];
        for (uint32_t f = 1; f < repeats; ++f) {
            res->wall_min = fmin(res->wall_min, wall[f]);
            res->wall_max = fmax(res->wall_max, wall[f]);
            res->prefilter_min = fmin(res->prefilter_min, pre[f]);
            res->prefilter_max = fmax(res->prefilter_max, pre[f]);
        }
        res->wall_median = bench_median(wall, repeats);
        res->cpu_median = bench_median(cpu, repeats);
        res->gpu_median = gpu[0] < 0 ? -1.0 : bench_median(gpu, repeats);
        res->prefilter_median = bench_median(pre, repeats);
        size_t layer = (size_t)w * h * 4;
        res->display = malloc(layer * n);
        ok = res->display != NULL;
        for (uint32_t k = 0; ok && k < n; ++k)
            ok = cli_read_display_layer(r, t, k, w, h, 1, res->display + layer * k, NULL);
        lib_error = !ok;
        res->ran = ok;
    }
    if (!ok && lib_error)
        fprintf(stderr, "mvr bench: %s: %s\n", name, mvr_renderer_last_error(r));
    free(times);
    mvr_target_destroy(t);
    mvr_renderer_destroy(r);
    mvr_environment_destroy(env);
    return ok;
}

/* The maps the prefilter converges to, as far as the axes go: the largest
 * size with the API's most samples per texel. */
#define BENCH_CONVERGED_SAMPLES 4096u

static void env_config(bench_config *c, uint32_t size, uint32_t samples, bool reference, bool converged)
{
    memset(c, 0, sizeof *c);
    c->view_path = reference ? MVR_VIEW_PATH_LOOP : MVR_VIEW_PATH_AUTO;
    c->supersample = 1;
    c->order = MVR_TRANSPARENCY_ORDER_PER_VIEW;
    c->reference = reference;
    c->converged = converged;
    c->specular_size = size;
    c->specular_samples = samples;
    if (reference || converged)
        snprintf(c->name, sizeof c->name, reference ? "reference" : "converged");
    else
        snprintf(c->name, sizeof c->name, "size%u/samples%u", size, samples);
    snprintf(c->group, sizeof c->group, reference ? "reference" : converged ? "converged" : "environment");
}

/* Pareto fronts over (median prefilter time, error) among the axes'
 * configurations (from index 2: the reference's time is a frame's, and the
 * converged maps are the limit, not a choice). */
static void env_fronts(bench_result *results, uint32_t count)
{
    for (uint32_t k = 2; k < count; ++k) {
        bool dominated = false, maps_dominated = false;
        const bench_result *a = &results[k];
        for (uint32_t j = 2; j < count; ++j) {
            const bench_result *b = &results[j];
            if (j == k)
                continue;
            bool faster = b->prefilter_median <= a->prefilter_median;
            dominated |= faster && b->rmse <= a->rmse &&
                         (b->prefilter_median < a->prefilter_median || b->rmse < a->rmse);
            maps_dominated |= faster && b->maps_rmse <= a->maps_rmse &&
                              (b->prefilter_median < a->prefilter_median || b->maps_rmse < a->maps_rmse);
        }
        results[k].pareto = !dominated;
        results[k].maps_pareto = !maps_dominated;
    }
}

/* Auto exposure (a file with physical lights) would follow each
 * configuration's own pixels: one frame with the default maps fixes the
 * EV100 for every configuration and the reference. */
static bool fix_exposure(const bench_options *o, mvr_context *ctx, mvr_scene *scene, mvr_view_set *vs,
                         mvr_render_desc *base, const mvr_environment *lib_env)
{
    if (base->exposure_mode != MVR_EXPOSURE_AUTO)
        return true;
    bench_result probe;
    memset(&probe, 0, sizeof probe);
    double ev100 = 0.0;
    bool probed = run_env_config(o, ctx, scene, vs, base, NULL, lib_env, false, 0, 1, "exposure", &probe, &ev100);
    free(probe.display);
    if (!probed)
        return false;
    base->exposure_mode = MVR_EXPOSURE_EV100;
    base->ev100 = ev100;
    return true;
}

/* The environment's source as each configuration makes it again (an
 * image file read into image, freed by the caller). */
static bool source_desc(const bench_options *o, const cli_env_used *used, mvr_environment_desc *ed,
                        mvr_image_data *image)
{
    memset(ed, 0, sizeof *ed);
    ed->source = used->source;
    memcpy(ed->color, used->color, sizeof ed->color);
    ed->intensity = used->intensity;
    ed->rotation = used->rotation;
    ed->logger = o->context.logger;
    if (used->source == MVR_ENVIRONMENT_PIXELS) {
        mvr_error err;
        if (mvr_image_read(used->file, MVR_PIXEL_F32, image, &err) != MVR_OK) {
            fprintf(stderr, "mvr bench: --env %s: %s\n", used->file, err.message);
            return false;
        }
        ed->pixels = image->pixels;
        ed->width = image->width;
        ed->height = image->height;
    }
    return true;
}

/* The reference, the converged maps, then every size x samples; returns
 * the count. */
static uint32_t make_env_configs(const bench_options *o, bench_config *configs)
{
    uint32_t count = 0;
    /* the reference reads the source cube, which follows the specular size
     * (at least a face of a quarter of the image's width): the largest
     * size gives it the finest source any configuration has */
    uint32_t max_size = 0, max_samples = 0;
    for (uint32_t i = 0; i < o->n_sizes; ++i)
        max_size = o->sizes[i] > max_size ? o->sizes[i] : max_size;
    for (uint32_t j = 0; j < o->n_samples; ++j)
        max_samples = o->samples[j] > max_samples ? o->samples[j] : max_samples;
    env_config(&configs[count++], max_size, max_samples, true, false);
    env_config(&configs[count++], max_size, BENCH_CONVERGED_SAMPLES, false, true);
    for (uint32_t i = 0; i < o->n_sizes; ++i)
        for (uint32_t j = 0; j < o->n_samples; ++j)
            env_config(&configs[count++], o->sizes[i], o->samples[j], false, false);
    return count;
}

/* What the configurations run on and what they give. */
typedef struct env_run {
    mvr_context *ctx;
    mvr_scene *scene;
    mvr_view_set *vs;
    const mvr_render_desc *base;
    const mvr_environment_desc *ed;
    const bench_config *configs;
    bench_result *results;
    uint32_t count;
    size_t pixels;
    uint64_t compared;           /* pixels the scene covers */
} env_run;

/* Each configuration's prefilter timed and its pixels compared with the
 * reference's and with the converged maps'. */
static bool run_env_configs(const bench_options *o, env_run *e)
{
    bench_result *results = e->results;
    for (uint32_t k = 0; k < e->count; ++k) {
        const bench_config *c = &e->configs[k];
        bench_result *res = &results[k];
        res->group_diff = -1;
        bench_progress(o, k, e->count + 1, c->name);
        mvr_environment_desc d = *e->ed;
        d.specular_size = c->specular_size;
        d.specular_samples = c->specular_samples;
        /* the reference and the converged maps: one frame each (they are
         * slow), their programs compiled in it */
        bool once = c->reference || c->converged;
        if (!run_env_config(o, e->ctx, e->scene, e->vs, e->base, &d, NULL, c->reference, once ? 0 : o->warmup,
                            once ? 1 : o->frames, c->name, res, NULL))
            return false;
        e->compared = bench_compare(results[0].display, res->display, e->pixels, true, res);
    }
    for (uint32_t k = 0; k < e->count; ++k) {
        bench_result maps;
        bench_compare(results[1].display, results[k].display, e->pixels, true, &maps);
        results[k].maps_rmse = maps.rmse;
        results[k].maps_psnr_db = maps.psnr_db;
        results[k].maps_max_abs = maps.max_abs;
    }
    return true;
}

/* the library's default prefilter: which configuration has its pixels */
static bool mark_library_default(const bench_options *o, env_run *e, const mvr_environment *lib_env,
                                 bench_result *lib_default)
{
    bench_progress(o, e->count, e->count + 1, "library default");
    if (!run_env_config(o, e->ctx, e->scene, e->vs, e->base, NULL, lib_env, false, 0, 1, "library default",
                        lib_default, NULL))
        return false;
    /* the same pixels and the same passes (one per level: the same size;
     * under a uniform environment every prefilter gives the same pixels) */
    for (uint32_t k = 2; k < e->count; ++k)
        e->results[k].library_default = e->results[k].prefilter_passes == lib_default->prefilter_passes &&
                                        memcmp(e->results[k].display, lib_default->display, e->pixels * 4) == 0;
    return true;
}

static int write_env_reports(int argc, char **argv, const bench_options *o, const env_run *e,
                             const cli_env_used *used, bench_config *configs)
{
    char cmdline[1024];
    bench_command_line(argc, argv, cmdline, sizeof cmdline);
    const char *scene_name = o->scene.scene_file ? o->scene.scene_file : o->demo_set ? o->scene.demo : "spheres";
    const char *env_name = used->source == MVR_ENVIRONMENT_PIXELS ? used->file
                                                                   : mvr_environment_source_name(used->source);
    bench_run run = {scene_name, o->out_dir, cmdline, mvr_context_caps(e->ctx)->renderer, mvr_view_set_count(e->vs),
                     o->scene.width, o->scene.height, o->frames, e->count, configs, e->results, 0, "", true, env_name,
                     o->reference_samples, e->compared, 0};
    return bench_write_reports(&run) ? MVR_EXIT_OK : MVR_EXIT_FAILURE;
}

int bench_run_env_axes(int argc, char **argv, const bench_options *o, mvr_context *ctx)
{
    mvr_scene *scene = NULL;
    mvr_view_set *vs = NULL;
    mvr_environment *lib_env = NULL;
    mvr_image_data image;
    memset(&image, 0, sizeof image);
    bench_config configs[BENCH_MAX_CONFIGS];
    bench_result results[BENCH_MAX_CONFIGS];
    memset(results, 0, sizeof results);
    bench_result lib_default;
    memset(&lib_default, 0, sizeof lib_default);
    uint32_t count = 0;
    /* the scene: the sphere grid, unless a file or a demo was named */
    bool scene_file = o->scene.scene_file != NULL || !o->demo_set;
    int rc = o->scene.scene_file || o->demo_set ? cli_load_scene("mvr bench", &o->scene, &scene, &vs)
                                                : make_spheres(o, &scene, &vs);
    if (rc != MVR_EXIT_OK)
        goto done;
    /* the environment as mvr render makes it (the library's default
     * prefilter: its pixels mark the default configuration), then the same
     * source again with each configuration's prefilter */
    mvr_render_desc base;
    cli_render_desc_defaults(&base);
    memset(base.clear_color, 0, sizeof base.clear_color); /* alpha 0: what the scene does not cover */
    mvr_render_desc_choose_exposure(scene, &base);
    cli_env_used used;
    rc = cli_env_create("mvr bench", &o->env, scene_file, &base, &lib_env, &used);
    if (rc != MVR_EXIT_OK)
        goto done;
    rc = MVR_EXIT_USAGE;
    if (!used.present) {
        fprintf(stderr, "mvr bench: --env-axes needs an environment (--env FILE|neutral|uniform; the demos have "
                        "none of their own)\n");
        goto done;
    }
    rc = MVR_EXIT_FAILURE;
    mvr_environment_desc ed;
    if (!fix_exposure(o, ctx, scene, vs, &base, lib_env) || !source_desc(o, &used, &ed, &image))
        goto done;
    count = make_env_configs(o, configs);
    env_run e = {ctx, scene, vs, &base, &ed, configs, results, count,
                 (size_t)mvr_view_set_count(vs) * o->scene.width * o->scene.height, 0};
    if (!run_env_configs(o, &e) || !mark_library_default(o, &e, lib_env, &lib_default))
        goto done;
    bench_progress(o, count + 1, count + 1, "done");
    env_fronts(results, count);
    rc = write_env_reports(argc, argv, o, &e, &used, configs);
done:
    for (uint32_t k = 0; k < count; ++k)
        free(results[k].display);
    free(lib_default.display);
    mvr_image_free(&image);
    mvr_environment_destroy(lib_env);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    return rc;
}
