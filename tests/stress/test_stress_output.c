/* Stress suite, output: the sRGB round trip, many views, determinism across
 * processes and the mediump trap. Thresholds are written next to their
 * checks with the reason; measured values are recorded (stress_record).
 * usage: stress_output            (the tests)
 *        stress_output --child F  (renders the determinism frame into F) */
#include <sys/wait.h>
#include <unistd.h>

#include "shader_gen.h"
#include "stress_util.h"

static mvr_context *stress_context(mvr_test_state *t)
{
    return create_or_report(t, MVR_CONTEXT_PROVIDER_SURFACELESS, MVR_GL_API_DEFAULT, NULL);
}

/* All 256 sRGB values through a base-color texture (decoded by the sampler
 * of an sRGB format), an unlit material and both 8-bit targets: an sRGB one
 * (encoded by the GL) and a UNORM one (encoded by the shader's exact
 * piecewise function). */
static void srgb_round_trip(mvr_test_state *t)
{
    mvr_context *ctx = stress_context(t);
    if (!ctx)
        return;
    mvr_scene *s = stress_scene();
    uint8_t ramp[256 * 4];
    for (int i = 0; i < 256; ++i) {
        ramp[i * 4] = (uint8_t)i;
        ramp[i * 4 + 1] = (uint8_t)(255 - i);
        ramp[i * 4 + 2] = (uint8_t)((i * 7) & 255);
        ramp[i * 4 + 3] = 255;
    }
    mvr_image_desc id = {.width = 256, .height = 1, .rgba8 = ramp, .name = "ramp"};
    mvr_image_id img;
    CHECK(t, mvr_scene_add_image(s, &id, &img) == MVR_OK);
    mvr_material_desc m = mvr_material_defaults();
    m.unlit = true;
    m.base_color.image = img;
    m.base_color.sampler.mag_filter = MVR_FILTER_NEAREST;
    m.base_color.sampler.min_filter = MVR_FILTER_NEAREST;
    mvr_material_id mat;
    CHECK(t, mvr_scene_add_material(s, &m, &mat) == MVR_OK);
    stress_node(t, s, stress_add_quad(t, s, mat), 0, 0, -1, 1.0);
    /* orthographic over the quad: pixel i's center samples texel i's center */
    double eye[3] = {0, 0, 0}, target[3] = {0, 0, -1};
    mvr_projection proj = {.type = MVR_PROJECTION_ORTHOGRAPHIC, .xmag = 1, .ymag = 1, .znear = 0.1, .zfar = 10};
    mvr_view_desc v = stress_view(eye, target, proj);
    mvr_view_set *vs = stress_view_set(t, &v, 1, NULL);
    const mvr_color_format formats[2] = {MVR_COLOR_FORMAT_DEFAULT, MVR_COLOR_FORMAT_RGBA8};
    unsigned worst[2] = {0, 0};
    for (int f = 0; f < 2 && vs; ++f) {
        stress_options o = {.width = 256, .height = 2, .format = formats[f], .clear = {0, 0, 0, 1}};
        uint8_t *px = stress_render(t, ctx, s, vs, &o, NULL);
        if (!px)
            continue;
        for (int row = 0; row < 2; ++row)
            for (int i = 0; i < 256; ++i)
                for (int c = 0; c < 3; ++c) {
                    int got = px[(row * 256 + i) * 4 + c], want = ramp[i * 4 + c];
                    unsigned d = (unsigned)abs(got - want);
                    worst[f] = d > worst[f] ? d : worst[f];
                }
        /* threshold 1 LSB: decode and encode each round once in 8 bits */
        CHECK_MSG(t, worst[f] <= 1, "%s target: sRGB round trip off by %u", mvr_color_format_name(formats[f]),
                  worst[f]);
        free(px);
    }
    char measured[96];
    snprintf(measured, sizeof measured, "%u LSB (sRGB target), %u LSB (UNORM target, shader encode)", worst[0],
             worst[1]);
    stress_record("sRGB round trip: 256 values through an sRGB texture and the target, max error", "<= 1 LSB",
                  measured, "one rounding on the way in and one on the way out");
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
}

/* 16 views: multiview (three chunks of at most GL_MAX_VIEWS_OVR = 6 here)
 * equals 16 loop passes byte for byte, on the city and cube demos. */
static void many_views(mvr_test_state *t)
{
    mvr_context *ctx = stress_context(t);
    if (!ctx)
        return;
    const mvr_caps *caps = mvr_context_caps(ctx);
    if (!caps->ext.ovr_multiview2) {
        CHECK_MSG(t, !mvr_test_in_ci(), "CI requires GL_OVR_multiview2");
        mvr_context_destroy(ctx);
        SKIP(t, "no GL_OVR_multiview2");
    }
    const char *demos[2] = {"city", "cube"};
    size_t differing = 0;
    for (int d = 0; d < 2; ++d) {
        mvr_scene *s = NULL;
        mvr_view_set *vs = NULL;
        mvr_error err;
        mvr_demo_desc dd = {16, 64, 64, {0}};
        CHECK_MSG(t, mvr_demo_create(demos[d], &dd, &s, &vs, &err) == MVR_OK, "%s", err.message);
        if (!s)
            continue;
        stress_options o = {.width = 64, .height = 64, .path = MVR_VIEW_PATH_MULTIVIEW, .clear = {0.1f, 0.2f, 0.3f, 1}};
        mvr_frame_stats mv_st, loop_st;
        uint8_t *mv = stress_render(t, ctx, s, vs, &o, &mv_st);
        o.path = MVR_VIEW_PATH_LOOP;
        uint8_t *loop = stress_render(t, ctx, s, vs, &o, &loop_st);
        if (mv && loop) {
            uint32_t max_views = (uint32_t)caps->limits.max_views_ovr;
            CHECK_EQ_INT(t, mv_st.passes, (16 + max_views - 1) / max_views);
            CHECK_EQ_INT(t, loop_st.passes, 16);
            size_t n = 0;
            for (size_t i = 0; i < (size_t)16 * 64 * 64 * 4; ++i)
                n += mv[i] != loop[i];
            /* threshold 0: both paths run the same shader code per view */
            CHECK_MSG(t, n == 0, "%s, 16 views: %zu bytes differ between multiview and loop", demos[d], n);
            differing += n;
        }
        free(mv);
        free(loop);
        mvr_view_set_destroy(vs);
        mvr_scene_destroy(s);
    }
    char measured[64];
    snprintf(measured, sizeof measured, "%zu bytes differ", differing);
    stress_record("many views: 16 views by multiview (chunks of 6) against 16 loop passes, city and cube", "0 bytes",
                  measured, "both paths run the same shader code per view");
    mvr_context_destroy(ctx);
}

#define CHILD_VIEWS 4u
#define CHILD_SIZE 96u

/* The determinism frame: city, 4 views, read back raw. */
static int child_render(const char *path)
{
    mvr_test_state t = {0, 0};
    mvr_context *ctx = stress_context(&t);
    if (!ctx)
        return 1;
    mvr_scene *s = NULL;
    mvr_view_set *vs = NULL;
    mvr_demo_desc dd = {CHILD_VIEWS, CHILD_SIZE, CHILD_SIZE, {0}};
    int rc = 1;
    if (mvr_demo_create("city", &dd, &s, &vs, NULL) == MVR_OK) {
        stress_options o = {.width = CHILD_SIZE, .height = CHILD_SIZE, .clear = {0.1f, 0.2f, 0.3f, 1}};
        uint8_t *px = stress_render(&t, ctx, s, vs, &o, NULL);
        FILE *f = px ? fopen(path, "wb") : NULL;
        if (f) {
            size_t bytes = (size_t)CHILD_VIEWS * CHILD_SIZE * CHILD_SIZE * 4;
            rc = fwrite(px, 1, bytes, f) == bytes ? 0 : 1;
            rc |= fclose(f) != 0;
        }
        free(px);
    }
    mvr_view_set_destroy(vs);
    mvr_scene_destroy(s);
    mvr_context_destroy(ctx);
    return rc;
}

static bool run_child(mvr_test_state *t, const char *out)
{
    pid_t pid = fork();
    if (pid == 0) {
        execl("/proc/self/exe", "stress_output", "--child", out, (char *)NULL);
        _exit(127);
    }
    int status = 0;
    bool ok = pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    CHECK_MSG(t, ok, "child render into %s failed (status %d)", out, status);
    return ok;
}

static uint8_t *read_all(const char *path, size_t bytes)
{
    FILE *f = fopen(path, "rb");
    uint8_t *p = f ? malloc(bytes) : NULL;
    if (p && fread(p, 1, bytes, f) != bytes) {
        free(p);
        p = NULL;
    }
    if (f)
        fclose(f);
    return p;
}

/* Determinism: the same frame rendered by two separate processes is
 * byte-identical (no uninitialized memory, time or address dependence). */
static void determinism(mvr_test_state *t)
{
    char a[64], b[64];
    snprintf(a, sizeof a, "stress_determinism_%d_a.raw", (int)getpid());
    snprintf(b, sizeof b, "stress_determinism_%d_b.raw", (int)getpid());
    size_t bytes = (size_t)CHILD_VIEWS * CHILD_SIZE * CHILD_SIZE * 4;
    if (run_child(t, a) && run_child(t, b)) {
        uint8_t *pa = read_all(a, bytes), *pb = read_all(b, bytes);
        CHECK(t, pa && pb);
        size_t n = 0;
        for (size_t i = 0; pa && pb && i < bytes; ++i)
            n += pa[i] != pb[i];
        /* threshold 0: a renderer's output must be a function of its input */
        CHECK_MSG(t, n == 0, "%zu bytes differ between two processes", n);
        char measured[64];
        snprintf(measured, sizeof measured, "%zu bytes differ", n);
        stress_record("determinism: city, 4 views, rendered by two processes", "0 bytes", measured,
                      "a renderer's output must be a function of its input");
        free(pa);
        free(pb);
    }
    remove(a);
    remove(b);
}

/* Compiles and runs a one-pixel program computing u + 1.0 for u = 2049 at
 * the given precision into an RGBA32F texture; returns the result. fp16
 * holds integers exactly only to 2048, so 2049 + 1 is 2050 in fp32 and
 * 2048 in fp16 (2049 rounds to 2048, then 2049 rounds to 2048 again). */
static float run_precision_probe(mvr_test_state *t, mvr_context *ctx, const char *precision)
{
    const mvr_gl_api_table *gl = &ctx->gl;
    bool gles = mvr_context_caps(ctx)->api == MVR_GL_API_GLES;
    const char *version = gles ? "#version 300 es\n" : "#version 330 core\n";
    char fs[512];
    snprintf(fs, sizeof fs,
             "%sprecision %s float;\nuniform float u;\nout vec4 o;\n"
             "void main() { %s float x = u; x = x + 1.0; o = vec4(x, 0.0, 0.0, 1.0); }\n",
             version, precision, gles ? precision : "");
    char vs[256];
    snprintf(vs, sizeof vs,
             "%svoid main() { gl_Position = vec4(vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0, 0.0, 1.0); }\n",
             version);
    const char *srcs[2] = {vs, fs};
    GLenum kinds[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    GLuint prog = gl->CreateProgram();
    for (int i = 0; i < 2; ++i) {
        GLuint sh = gl->CreateShader(kinds[i]);
        gl->ShaderSource(sh, 1, &srcs[i], NULL);
        gl->CompileShader(sh);
        GLint ok = 0;
        gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        CHECK_MSG(t, ok, "probe shader (%s) did not compile", precision);
        gl->AttachShader(prog, sh);
        gl->DeleteShader(sh);
    }
    gl->LinkProgram(prog);
    GLint linked = 0;
    gl->GetProgramiv(prog, GL_LINK_STATUS, &linked);
    CHECK(t, linked);
    GLuint tex, fbo, vao;
    gl->GenTextures(1, &tex);
    gl->BindTexture(GL_TEXTURE_2D, tex);
    gl->TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, 1, 1);
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    gl->GenVertexArrays(1, &vao);
    gl->BindVertexArray(vao);
    gl->Viewport(0, 0, 1, 1);
    gl->UseProgram(prog);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u"), 2049.0f);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    float px[4] = {0, 0, 0, 0};
    gl->ReadPixels(0, 0, 1, 1, GL_RGBA, GL_FLOAT, px);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteTextures(1, &tex);
    gl->DeleteVertexArrays(1, &vao);
    gl->DeleteProgram(prog);
    return px[0];
}

static bool contains_word(const char *text, size_t length, const char *word)
{
    size_t n = strlen(word);
    for (size_t i = 0; i + n <= length; ++i)
        if (memcmp(text + i, word, n) == 0)
            return true;
    return false;
}

/* The mediump trap: llvmpipe computes mediump in fp16 (shown by the probe,
 * so this test can fail), and every shader variant mvr can generate
 * declares highp for floats, ints and samplers and never names a lower
 * precision. */
static void mediump_trap(mvr_test_state *t)
{
    mvr_context *ctx = stress_context(t);
    if (!ctx)
        return;
    float high = run_precision_probe(t, ctx, "highp");
    float medium = run_precision_probe(t, ctx, "mediump");
    CHECK_MSG(t, high == 2050.0f, "highp probe: 2049 + 1 = %g", high);
    bool trap = medium != 2050.0f;
    printf("  mediump probe: 2049 + 1 = %g (%s)\n", medium,
           trap ? "this driver computes mediump below fp32" : "this driver computes mediump at fp32");
    /* caps detect the quirk (gl/caps.c); the probe must agree with them */
    CHECK_MSG(t, trap == mvr_context_caps(ctx)->bugs.mediump_is_fp16,
              "mediump probe %s fp16, caps say mediump_is_fp16 = %d", trap ? "shows" : "does not show",
              mvr_context_caps(ctx)->bugs.mediump_is_fp16);
    mvr_context_destroy(ctx);

    mvr_shader_variant v;
    unsigned n = 0, bad = 0;
    for (; mvr_shader_variant_enumerate(n, 16, &v); ++n)
        for (int stage = 0; stage < 2; ++stage) {
            mvr_str_builder sb = {0};
            char why[256];
            mvr_shader_stage st = stage ? MVR_SHADER_STAGE_FRAGMENT : MVR_SHADER_STAGE_VERTEX;
            if (!mvr_shader_source(&v, st, &sb, why, sizeof why)) {
                CHECK_MSG(t, 0, "variant %u: %s", n, why);
                bad++;
                mvr_sb_free(&sb);
                continue;
            }
            bool ok = contains_word(sb.data, sb.length, "precision highp float;") &&
                      contains_word(sb.data, sb.length, "precision highp int;") &&
                      contains_word(sb.data, sb.length, "precision highp sampler2DArray;") &&
                      !contains_word(sb.data, sb.length, "mediump") && !contains_word(sb.data, sb.length, "lowp");
            if (!ok) {
                char name[96];
                mvr_shader_variant_name(&v, name, sizeof name);
                CHECK_MSG(t, 0, "%s (%s) does not declare highp everywhere", name, mvr_shader_stage_name(st));
                bad++;
            }
            mvr_sb_free(&sb);
        }
    char measured[128];
    snprintf(measured, sizeof measured, "%u of %u sources without highp; mediump probe gave %g (highp %g)", bad, 2 * n,
             medium, high);
    stress_record("mediump trap: every generated shader declares highp", "0 sources", measured,
                  "llvmpipe computes mediump in fp16 (2049 + 1 = 2048 there)");
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--child") == 0)
        return child_render(argv[2]);
    static const mvr_test_case cases[] = {TEST(srgb_round_trip), TEST(many_views), TEST(determinism),
                                          TEST(mediump_trap)};
    return mvr_test_run(cases, sizeof cases / sizeof cases[0]);
}
