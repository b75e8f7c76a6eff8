/* core: generated tangents (core/tangents.c) on meshes whose answer is
 * known: glTF's frame (T = dP/du, cross(N, T) w = -dP/dv, v running down the
 * image), mirrored UVs, a curved strip, welded and degenerate vertices. */
#include <math.h>
#include <string.h>

#include "mvr_test.h"
#include "tangents.h"

static float dot3f(const float *a, const float *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* A unit quad in the XY plane facing +Z; u along +X (or -X when mirrored),
 * v down the image: along -Y. */
static void quad_frame(mvr_test_state *t, bool mirrored)
{
    const float p[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const float n[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    float s = mirrored ? -1.0f : 1.0f;
    const float uv[] = {0, 1, s, 1, s, 0, 0, 0};
    const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    float tan[16];
    CHECK(t, mvr_mesh_tangents(p, n, uv, 4, idx, 6, tan));
    for (int v = 0; v < 4; ++v) {
        const float want[3] = {s, 0, 0};
        CHECK_MSG(t, dot3f(tan + v * 4, want) > 0.9999f, "vertex %d: tangent (%g, %g, %g)", v, tan[v * 4],
                  tan[v * 4 + 1], tan[v * 4 + 2]);
        /* B = cross(N, T) w must be +Y (the image's up) either way */
        CHECK_MSG(t, tan[v * 4 + 3] == s, "vertex %d: w %g", v, tan[v * 4 + 3]);
    }
}

static void quad_gives_gltf_frame(mvr_test_state *t)
{
    quad_frame(t, false);
}

static void mirrored_uvs_flip_w(mvr_test_state *t)
{
    quad_frame(t, true);
}

/* A half cylinder about +Y (u around it, v down its height): each vertex's
 * tangent is the circle's direction, orthogonal to its normal. */
static void curved_strip_follows_the_circle(mvr_test_state *t)
{
    enum { SEG = 16, V = (SEG + 1) * 2 };
    float p[V * 3], n[V * 3], uv[V * 2], tan[V * 4];
    uint32_t idx[SEG * 6];
    for (int i = 0; i <= SEG; ++i) {
        float a = 3.14159265f * (float)i / SEG, c = cosf(a), s = sinf(a);
        for (int j = 0; j < 2; ++j) {
            int v = i * 2 + j;
            p[v * 3] = c, p[v * 3 + 1] = (float)j, p[v * 3 + 2] = s;
            n[v * 3] = c, n[v * 3 + 1] = 0, n[v * 3 + 2] = s;
            uv[v * 2] = (float)i / SEG, uv[v * 2 + 1] = 1.0f - (float)j;
        }
    }
    for (int i = 0; i < SEG; ++i) {
        uint32_t a = (uint32_t)i * 2, q[6] = {a, a + 2, a + 3, a, a + 3, a + 1};
        memcpy(idx + i * 6, q, sizeof q);
    }
    CHECK(t, mvr_mesh_tangents(p, n, uv, V, idx, SEG * 6, tan));
    for (int v = 0; v < V; ++v) {
        float a = 3.14159265f * (float)(v / 2) / SEG, want[3] = {-sinf(a), 0, cosf(a)};
        CHECK_MSG(t, dot3f(tan + v * 4, want) > 0.9999f, "vertex %d", v);
        CHECK_MSG(t, fabsf(dot3f(tan + v * 4, n + v * 3)) < 1e-5f, "vertex %d: not orthogonal", v);
    }
}

/* Two copies of a vertex (equal position, normal, UV) get one tangent, the
 * sum over both fans; a vertex with only degenerate UVs gets a unit vector
 * orthogonal to its normal. */
static void welded_and_degenerate(mvr_test_state *t)
{
    const float p[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 0, 0, 1, 0, 5, 5, 0, 6, 5, 0, 5, 6, 0};
    const float n[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const float uv[] = {0, 1, 1, 1, 1, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    const uint32_t idx[] = {0, 1, 2, 0, 3, 4, 5, 6, 7}; /* 2 and 3 are one vertex */
    float tan[32];
    CHECK(t, mvr_mesh_tangents(p, n, uv, 8, idx, 9, tan));
    CHECK(t, memcmp(tan + 2 * 4, tan + 3 * 4, 4 * sizeof(float)) == 0);
    for (int v = 5; v < 8; ++v) {
        float len = sqrtf(dot3f(tan + v * 4, tan + v * 4));
        CHECK_MSG(t, fabsf(len - 1.0f) < 1e-5f && fabsf(dot3f(tan + v * 4, n + v * 3)) < 1e-5f, "vertex %d", v);
    }
}

MVR_TEST_MAIN(TEST(quad_gives_gltf_frame), TEST(mirrored_uvs_flip_w), TEST(curved_strip_follows_the_circle),
              TEST(welded_and_degenerate))
