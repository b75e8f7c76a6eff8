#define _POSIX_C_SOURCE 200809L
/* gl: shader variants follow the scene's features (a scene without textures
 * compiles no texturing code; one normal-mapped material adds exactly one
 * variant), and the program binary cache lets a restart compile nothing,
 * while damaged or refused entries are rebuilt, never trusted. Pixels are
 * the same whichever way a program was made. */
#include <dirent.h>
#include <stdlib.h>
#include <unistd.h>

#include "gl_test_util.h"
#include "program_cache_files.h"
#include "program_binary_file.h"
#include "shader_gen.h"

#define W 48
#define H 32

/* A quad of two triangles facing +Z, with normals, tangents and UVs. */
static mvr_mesh_id add_quad(mvr_test_state *t, mvr_scene *s, mvr_material_id material)
{
    static const float pos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    static const float nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    static const float tan[16] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
    static const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    static const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    mvr_primitive_desc p = {.vertex_count = 4, .positions = pos, .normals = nrm, .tangents = tan,
                            .texcoords0 = uv, .index_count = 6, .indices16 = idx, .material = material};
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = "quad"};
    mvr_mesh_id mesh = {0};
    CHECK(t, mvr_scene_add_mesh(s, &md, &mesh) == MVR_OK);
    return mesh;
}

static void add_node(mvr_test_state *t, mvr_scene *s, mvr_mesh_id mesh, double x)
{
    mvr_node_desc nd = {.mesh = mesh, .translation = {x, 0, -4}};
    mvr_node_id id;
    CHECK(t, mvr_scene_add_node(s, &nd, &id) == MVR_OK);
}

static uint32_t variants_with(const mvr_renderer *r, uint32_t bits)
{
    uint32_t n = 0;
    mvr_program_info info;
    for (uint32_t i = 0; mvr_renderer_get_program_info(r, i, &info); ++i)
        n += (info.features & bits) != 0;
    return n;
}

static void variants_follow_the_scene(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_material_path paths[2] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL};
    for (int pi = 0; pi < 2; ++pi) {
        mvr_scene *scene = NULL;
        mvr_scene_create(NULL, &scene, NULL);
        mvr_material_desc plain = mvr_material_defaults();
        plain.base_color_factor[0] = 0.8f;
        plain.roughness_factor = 0.5f;
        mvr_material_id plain_id;
        CHECK(t, mvr_scene_add_material(scene, &plain, &plain_id) == MVR_OK);
        add_node(t, scene, add_quad(t, scene, plain_id), -1.2);
        mvr_light_desc ld = {.type = MVR_LIGHT_DIRECTIONAL, .intensity = 3.0f};
        mvr_light_id light;
        CHECK(t, mvr_scene_add_light(scene, &ld, &light) == MVR_OK);
        mvr_node_desc ln = {.light = light, .rotation = {-0.3826834, 0, 0, 0.9238795}};
        mvr_node_id lnode;
        CHECK(t, mvr_scene_add_node(scene, &ln, &lnode) == MVR_OK);

        mvr_view_desc vds[2] = {{.position = {-0.03, 0, 0}, .projection = {.yfov = 1.0}},
                                {.position = {0.03, 0, 0}, .projection = {.yfov = 1.0}}};
        mvr_view_set_desc vsd = {2, vds, false, {0, 0, 0}};
        mvr_view_set *vs = NULL;
        CHECK(t, mvr_view_set_create(&vsd, &vs, NULL) == MVR_OK);
        /* tuning off: auto's tuner would compile the other view path's variants in its warm-up frame */
        mvr_renderer_desc rd = {.context = ctx, .material_path = paths[pi], .tuning = {.mode = MVR_TUNING_OFF}};
        mvr_renderer *r = NULL;
        mvr_target *target = NULL;
        mvr_target_desc td = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
        bool ok = mvr_renderer_create(&rd, &r, NULL) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
                  mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK;
        CHECK_MSG(t, ok, "%s", r ? mvr_renderer_last_error(r) : "no renderer");
        if (!ok) {
            mvr_context_destroy(ctx);
            return;
        }
        const char *path = mvr_material_path_name(paths[pi]);
        /* no textures: no sampler, no UVs, no tangents, no array indexing */
        uint32_t before = mvr_renderer_program_count(r);
        CHECK_MSG(t, before == 1, "%s: %u variants for one plain material", path, before);
        uint32_t texturing = MVR_TEXTURE_FEATURES | MVR_FEATURE_MATERIAL_ARRAYS | MVR_FEATURE_UV0 |
                             MVR_FEATURE_UV1 | MVR_FEATURE_TANGENTS | MVR_FEATURE_TEXTURE_TRANSFORM;
        CHECK_MSG(t, variants_with(r, texturing) == 0, "%s: texturing code in a scene without textures", path);
        mvr_frame_stats st;
        mvr_renderer_get_stats(r, &st);
        CHECK_EQ_INT(t, st.programs_compiled, 1);
        CHECK(t, mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK);
        mvr_renderer_get_stats(r, &st);
        CHECK_EQ_INT(t, st.programs_compiled, 0);
        CHECK(t, st.program_cache_hits >= 1);

        /* one normal-mapped material: exactly one more variant, with the normal map */
        uint8_t texels[4 * 4 * 4];
        for (int i = 0; i < 16; ++i) {
            texels[i * 4 + 0] = (uint8_t)(100 + i * 8);
            texels[i * 4 + 1] = 128;
            texels[i * 4 + 2] = 240;
            texels[i * 4 + 3] = 255;
        }
        mvr_image_desc id = {.width = 4, .height = 4, .rgba8 = texels, .name = "bumps"};
        mvr_image_id image;
        CHECK(t, mvr_scene_add_image(scene, &id, &image) == MVR_OK);
        mvr_material_desc bumpy = plain;
        bumpy.normal.image = image;
        mvr_material_id bumpy_id;
        CHECK(t, mvr_scene_add_material(scene, &bumpy, &bumpy_id) == MVR_OK);
        add_node(t, scene, add_quad(t, scene, bumpy_id), 1.2);
        CHECK_MSG(t, mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK, "%s", mvr_renderer_last_error(r));
        mvr_renderer_get_stats(r, &st);
        CHECK_EQ_INT(t, mvr_renderer_program_count(r), before + 1);
        CHECK_EQ_INT(t, st.programs_compiled, 1);
        mvr_program_info info;
        CHECK(t, mvr_renderer_get_program_info(r, before, &info));
        CHECK_MSG(t, (info.features & MVR_FEATURE_NORMAL_TEX) && (info.features & MVR_FEATURE_TANGENTS),
                  "%s: new variant %s lacks the normal map", path, info.name);
        CHECK(t, !(info.features & (MVR_TEXTURE_FEATURES & ~(uint32_t)MVR_FEATURE_NORMAL_TEX)));
        CHECK(t, strcmp(mvr_program_feature_name(MVR_FEATURE_NORMAL_TEX), "NORMAL_TEX") == 0);
        CHECK(t, mvr_program_feature_name(MVR_FEATURE_NORMAL_TEX | MVR_FEATURE_UV0) == NULL); /* not one bit */
        mvr_program_info first;
        CHECK(t, mvr_renderer_get_program_info(r, 0, &first));
        printf("  %s: %s, then + %s\n", path, first.name, info.name);
        mvr_target_destroy(target);
        mvr_renderer_destroy(r);
        mvr_view_set_destroy(vs);
        mvr_scene_destroy(scene);
    }
    mvr_context_destroy(ctx);
}

/* ---- binary cache */

/* One render of a demo's two views: stats, the variants built (how many came
 * from the binary cache, how many carry every bit of `bits`), and the pixels. */
typedef struct demo_run {
    mvr_frame_stats stats;
    uint32_t programs, from_binary, with_bits;
    uint8_t pixels[2 * W * H * 4];
} demo_run;

static bool render_demo_run(mvr_test_state *t, mvr_context *ctx, const char *demo, mvr_renderer_desc rd,
                            uint32_t bits, demo_run *out)
{
    mvr_scene *scene = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {2, W, H, {0}};
    mvr_error err;
    if (mvr_demo_create(demo, &dd, &scene, &vs, &err) != MVR_OK) {
        CHECK_MSG(t, 0, "%s", err.message);
        return false;
    }
    rd.context = ctx;
    mvr_renderer *r = NULL;
    mvr_target *target = NULL;
    mvr_target_desc td = {W, H, 2, MVR_COLOR_FORMAT_DEFAULT, 0, 0, 0, 0, 0, MVR_ANTI_ALIASING_NONE, 0};
    bool ok = mvr_renderer_create(&rd, &r, &err) == MVR_OK && mvr_target_create(r, &td, &target) == MVR_OK &&
              mvr_renderer_render(r, scene, vs, target, NULL) == MVR_OK;
    CHECK_MSG(t, ok, "%s: %s", demo, r ? mvr_renderer_last_error(r) : err.message);
    if (ok) {
        mvr_renderer_get_stats(r, &out->stats);
        out->programs = mvr_renderer_program_count(r);
        out->from_binary = out->with_bits = 0;
        mvr_program_info info;
        for (uint32_t i = 0; mvr_renderer_get_program_info(r, i, &info); ++i) {
            out->from_binary += info.from_binary_cache;
            out->with_bits += (info.features & bits) == bits;
        }
        for (uint32_t k = 0; ok && k < 2; ++k)
            ok = mvr_renderer_read_layer(r, target, k, MVR_READBACK_RGBA8, out->pixels + (size_t)k * W * H * 4,
                                         (size_t)W * H * 4) == MVR_OK;
        CHECK(t, ok);
    }
    mvr_target_destroy(target);
    mvr_renderer_destroy(r);
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(scene);
    return ok;
}

/* The stereo demo with a binary cache in dir (NULL: none), logging into sink. */
static bool render_with_cache(mvr_test_state *t, mvr_context *ctx, const char *dir, log_sink *sink, demo_run *out)
{
    mvr_renderer_desc rd = {.program_cache_dir = dir};
    if (sink) {
        rd.logger.fn = log_sink_fn;
        rd.logger.user_data = sink;
    }
    return render_demo_run(t, ctx, "stereo", rd, 0, out);
}

static void flip_byte(const char *path, long from_end)
{
    FILE *f = fopen(path, "r+b");
    if (!f)
        return;
    fseek(f, -from_end, SEEK_END);
    int c = fgetc(f);
    fseek(f, -from_end, SEEK_END);
    fputc(c ^ 0x5a, f);
    fclose(f);
}

/* Rewrites a file as an authentic entry (right driver, key and the user's
 * tag) whose payload the driver cannot use: only the driver can refuse it. */
static bool replace_payload_with_garbage(const char *dir, const char *path)
{
    mvr_program_cache_key mac;
    char why[512];
    FILE *f = fopen(path, "rb");
    if (!f || !mvr_program_cache_key_load(dir, &mac, why, sizeof why)) {
        if (f)
            fclose(f);
        return false;
    }
    unsigned char header[32];
    char driver[MVR_PROGRAM_BINARY_MAX_DRIVER + 1] = "";
    bool ok = fread(header, 1, sizeof header, f) == sizeof header;
    uint32_t format = 0, driver_len = 0;
    uint64_t key = 0;
    for (int i = 3; i >= 0; --i) {
        format = format << 8 | header[8 + i];
        driver_len = driver_len << 8 | header[12 + i];
    }
    for (int i = 7; i >= 0; --i)
        key = key << 8 | header[16 + i];
    ok = ok && driver_len <= MVR_PROGRAM_BINARY_MAX_DRIVER && fread(driver, 1, driver_len, f) == driver_len;
    fclose(f);
    if (!ok)
        return false;
    driver[driver_len] = '\0';
    unsigned char garbage[512];
    for (size_t i = 0; i < sizeof garbage; ++i)
        garbage[i] = (unsigned char)(i * 31 + 7);
    return mvr_program_binary_write(path, &mac, driver, key, format, garbage, sizeof garbage, why, sizeof why) != 0;
}

static void binary_cache_restart_compiles_nothing(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    const mvr_caps *caps = mvr_context_caps(ctx);
    if (!caps->ext.program_binary) {
        mvr_context_destroy(ctx);
        SKIP(t, "%s offers no program binary format", caps->renderer);
    }
    char dir[] = "/tmp/mvr-programs-XXXXXX";
    CHECK(t, mkdtemp(dir) != NULL);
    static demo_run cold, warm, damaged, healed, none;
    char files[16][512];

    bool ok = render_with_cache(t, ctx, NULL, NULL, &none) && render_with_cache(t, ctx, dir, NULL, &cold);
    uint32_t n = program_cache_entries(dir, files, 16);
    if (ok) {
        printf("  cold start: %u compiled, %u files\n", cold.stats.programs_compiled, n);
        CHECK(t, cold.stats.programs_compiled > 0);
        CHECK_EQ_INT(t, cold.stats.program_binary_loads, 0);
        CHECK_EQ_INT(t, n, cold.stats.programs_compiled);
        CHECK_MSG(t, memcmp(none.pixels, cold.pixels, sizeof none.pixels) == 0, "the cache changed pixels");
    }
    /* a restart: every variant linked from the cache, same pixels */
    ok = ok && render_with_cache(t, ctx, dir, NULL, &warm);
    if (ok) {
        CHECK_EQ_INT(t, warm.stats.programs_compiled, 0);
        CHECK_EQ_INT(t, warm.stats.program_binary_loads, cold.stats.programs_compiled);
        CHECK_EQ_INT(t, warm.stats.program_binary_rejects, 0);
        CHECK_EQ_INT(t, warm.from_binary, warm.programs);
        CHECK_MSG(t, memcmp(cold.pixels, warm.pixels, sizeof cold.pixels) == 0, "binaries changed pixels");
    }
    /* damage: a flipped byte, a cut file and a payload the driver refuses */
    uint32_t damaged_count = n < 3 ? n : 3;
    if (ok && n >= 1) {
        flip_byte(files[0], 10);
        if (n >= 2) {
            long size = 0;
            FILE *f = fopen(files[1], "rb");
            if (f) {
                fseek(f, 0, SEEK_END);
                size = ftell(f);
                fclose(f);
            }
            CHECK(t, truncate(files[1], size / 2) == 0);
        }
        if (n >= 3)
            CHECK(t, replace_payload_with_garbage(dir, files[2]));
        ok = render_with_cache(t, ctx, dir, NULL, &damaged);
    }
    if (ok && n >= 1) {
        CHECK_EQ_INT(t, damaged.stats.program_binary_rejects, damaged_count);
        CHECK_EQ_INT(t, damaged.stats.programs_compiled, damaged_count);
        CHECK_EQ_INT(t, damaged.stats.program_binary_loads, n - damaged_count);
        CHECK_MSG(t, memcmp(cold.pixels, damaged.pixels, sizeof cold.pixels) == 0, "damaged cache changed pixels");
        /* the rebuilt entries were rewritten: the next start loads them all */
        ok = render_with_cache(t, ctx, dir, NULL, &healed);
        CHECK_EQ_INT(t, healed.stats.programs_compiled, 0);
        CHECK_EQ_INT(t, healed.stats.program_binary_rejects, 0);
        CHECK_EQ_INT(t, healed.stats.program_binary_loads, n);
    }
    n = program_cache_entries(dir, files, 16);
    for (uint32_t i = 0; i < n; ++i)
        remove(files[i]);
    char key_file[512];
    CHECK(t, mvr_program_cache_key_path(dir, key_file, sizeof key_file) && remove(key_file) == 0);
    CHECK_MSG(t, rmdir(dir) == 0, "%s holds more than the cache's files and key", dir);

    /* a directory that does not exist: a warning, and the frame still renders */
    log_sink sink = {0};
    static demo_run nowhere;
    CHECK(t, render_with_cache(t, ctx, "/nonexistent-mvr-cache-dir", &sink, &nowhere));
    CHECK(t, nowhere.stats.programs_compiled > 0);
    CHECK(t, sink.warnings >= 1);
    CHECK_EQ_INT(t, sink.errors, 0);
    mvr_context_destroy(ctx);
}

/* Every demo, both texture paths: the variants built from the scene's
 * features and variants with every inert feature forced on give the same
 * bytes, so skipping features changes cost, not pixels. */
static void forced_features_change_no_pixels(mvr_test_state *t)
{
    mvr_context *ctx = create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
    if (!ctx)
        return;
    static demo_run lean, forced;
    const uint32_t bits = MVR_FEATURE_TEXTURE_TRANSFORM | MVR_FEATURE_UV0 | MVR_FEATURE_UV1 | MVR_FEATURE_COLOR0;
    const mvr_material_path paths[2] = {MVR_MATERIAL_PATH_ARRAYS, MVR_MATERIAL_PATH_PER_MATERIAL};
    for (uint32_t d = 0; mvr_demo_name(d); ++d)
        for (int p = 0; p < 2; ++p) {
            const char *demo = mvr_demo_name(d);
            mvr_renderer_desc rd = {.material_path = paths[p]};
            bool ok = render_demo_run(t, ctx, demo, rd, bits, &lean);
            mvr_renderer_desc forced_rd = rd;
            forced_rd.overrides.force_inert_features = true;
            ok = ok && render_demo_run(t, ctx, demo, forced_rd, bits, &forced);
            if (!ok)
                continue;
            const char *mp = mvr_material_path_name(paths[p]);
            CHECK_MSG(t, forced.with_bits == forced.programs, "%s/%s: %u of %u variants forced", demo, mp,
                      forced.with_bits, forced.programs);
            CHECK_MSG(t, lean.with_bits == 0, "%s/%s: a lean variant has every inert feature", demo, mp);
            size_t diff = 0;
            unsigned worst = 0;
            for (size_t i = 0; i < sizeof lean.pixels; ++i) {
                unsigned delta = (unsigned)abs((int)lean.pixels[i] - (int)forced.pixels[i]);
                diff += delta != 0;
                worst = delta > worst ? delta : worst;
            }
            /* llvmpipe: the same bytes. A GPU's compiler schedules the forced
             * variant's (longer) code otherwise and may round a byte the other
             * way (NVIDIA H100: 1 byte of the ring's 24576, off by 1): at most
             * 1 off, in at most 1 byte in 1000 */
            if (mvr_context_caps(ctx)->is_software)
                CHECK_MSG(t, diff == 0, "%s/%s: %zu bytes differ with forced features", demo, mp, diff);
            else
                CHECK_MSG(t, worst <= 1 && diff * 1000 <= sizeof lean.pixels,
                          "%s/%s: %zu bytes differ with forced features, by up to %u", demo, mp, diff, worst);
            printf("  %-6s %-12s %u variants, forced %u: identical\n", demo, mp, lean.programs, forced.programs);
        }
    mvr_context_destroy(ctx);
}

MVR_TEST_MAIN(TEST(variants_follow_the_scene), TEST(binary_cache_restart_compiles_nothing),
              TEST(forced_features_change_no_pixels))
