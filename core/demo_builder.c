#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "demo_builder.h"

#define PI_F 3.14159265358979323846f

void demo_mesh_free(demo_mesh *m)
{
    free(m->positions);
    free(m->normals);
    free(m->tangents);
    free(m->uv0);
    free(m->colors);
    free(m->indices);
    memset(m, 0, sizeof *m);
}

static bool grow_floats(float **p, uint32_t count, uint32_t per)
{
    float *n = realloc(*p, (size_t)count * per * sizeof *n);
    if (!n)
        return false;
    *p = n;
    return true;
}

static uint32_t add_vertex(demo_mesh *m, const float p[3], const float n[3], const float t[4], float u,
                           float v)
{
    if (m->failed)
        return 0;
    if (m->vertex_count == m->vertex_cap) {
        uint32_t cap = m->vertex_cap ? m->vertex_cap * 2 : 64;
        if (!grow_floats(&m->positions, cap, 3) || !grow_floats(&m->normals, cap, 3) ||
            !grow_floats(&m->tangents, cap, 4) || !grow_floats(&m->uv0, cap, 2) ||
            !grow_floats(&m->colors, cap, 4)) {
            m->failed = true;
            return 0;
        }
        m->vertex_cap = cap;
    }
    uint32_t i = m->vertex_count++;
    memcpy(m->positions + i * 3, p, 3 * sizeof *p);
    memcpy(m->normals + i * 3, n, 3 * sizeof *n);
    memcpy(m->tangents + i * 4, t, 4 * sizeof *t);
    m->uv0[i * 2] = u;
    m->uv0[i * 2 + 1] = v;
    float white[4] = {1, 1, 1, 1};
    memcpy(m->colors + i * 4, white, sizeof white);
    return i;
}

static void add_triangle(demo_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    if (m->failed)
        return;
    if (m->index_count + 3 > m->index_cap) {
        uint32_t cap = m->index_cap ? m->index_cap * 2 : 192;
        uint32_t *n = realloc(m->indices, (size_t)cap * sizeof *n);
        if (!n) {
            m->failed = true;
            return;
        }
        m->indices = n;
        m->index_cap = cap;
    }
    m->indices[m->index_count++] = a;
    m->indices[m->index_count++] = b;
    m->indices[m->index_count++] = c;
}

mvr_result demo_mesh_add(mvr_scene *scene, demo_mesh *m, mvr_material_id material, bool with_colors,
                         const char *name, mvr_mesh_id *out)
{
    if (m->failed)
        return MVR_ERROR_OUT_OF_MEMORY;
    mvr_primitive_desc p;
    memset(&p, 0, sizeof p);
    p.vertex_count = m->vertex_count;
    p.positions = m->positions;
    p.normals = m->normals;
    p.tangents = m->tangents;
    p.texcoords0 = m->uv0;
    p.colors = with_colors ? m->colors : NULL;
    p.index_count = m->index_count;
    p.indices32 = m->indices;
    p.material = material;
    mvr_mesh_desc md = {.primitives = &p, .primitive_count = 1, .name = name};
    return mvr_scene_add_mesh(scene, &md, out);
}

/* One face of a box: normal n, tangent t (along +u), bitangent b = n x t (along +v). */
static void box_face(demo_mesh *m, const float c[3], const float n[3], const float t[3], const float b[3],
                     float ht, float hb, float uv_scale)
{
    float tan4[4] = {t[0], t[1], t[2], 1.0f};
    uint32_t idx[4];
    static const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; ++k) {
        float p[3];
        for (int i = 0; i < 3; ++i)
            p[i] = c[i] + t[i] * ht * corners[k][0] + b[i] * hb * corners[k][1];
        /* v grows downwards in image space: uv (0,0) is the image's top-left */
        idx[k] = add_vertex(m, p, n, tan4, (corners[k][0] * 0.5f + 0.5f) * uv_scale,
                            (0.5f - corners[k][1] * 0.5f) * uv_scale);
    }
    add_triangle(m, idx[0], idx[1], idx[2]);
    add_triangle(m, idx[0], idx[2], idx[3]);
}

void demo_box(demo_mesh *m, float hx, float hy, float hz, float uv_scale)
{
    /* per face: normal, tangent (+u, image right), bitangent (image up) with
     * tangent x bitangent = normal, so faces wind counter-clockwise outside
     * and side faces have +Y up */
    static const float frames[6][3][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}};
    const float h[3] = {hx, hy, hz};
    for (int f = 0; f < 6; ++f) {
        const float *n = frames[f][0], *t = frames[f][1], *b = frames[f][2];
        float c[3], ht = 0, hb = 0;
        for (int i = 0; i < 3; ++i) {
            c[i] = n[i] * h[i];
            ht += t[i] != 0 ? h[i] : 0;
            hb += b[i] != 0 ? h[i] : 0;
        }
        box_face(m, c, n, t, b, ht, hb, uv_scale);
    }
}

void demo_sphere(demo_mesh *m, float r, uint32_t slices, uint32_t stacks)
{
    uint32_t first = m->vertex_count;
    for (uint32_t i = 0; i <= stacks; ++i) {
        float v = (float)i / (float)stacks;
        float theta = v * PI_F;
        for (uint32_t j = 0; j <= slices; ++j) {
            float u = (float)j / (float)slices;
            float phi = u * 2.0f * PI_F;
            float n[3] = {sinf(theta) * cosf(phi), cosf(theta), -sinf(theta) * sinf(phi)};
            float p[3] = {n[0] * r, n[1] * r, n[2] * r};
            float t[4] = {-sinf(phi), 0.0f, -cosf(phi), 1.0f};
            add_vertex(m, p, n, t, u * 2.0f, v);
        }
    }
    for (uint32_t i = 0; i < stacks; ++i)
        for (uint32_t j = 0; j < slices; ++j) {
            uint32_t a = first + i * (slices + 1) + j, b = a + slices + 1;
            add_triangle(m, a, b, a + 1);
            add_triangle(m, a + 1, b, b + 1);
        }
}

void demo_torus(demo_mesh *m, float R, float r, uint32_t segments, uint32_t sides)
{
    uint32_t first = m->vertex_count;
    for (uint32_t i = 0; i <= segments; ++i) {
        float u = (float)i / (float)segments;
        float a = u * 2.0f * PI_F;
        for (uint32_t j = 0; j <= sides; ++j) {
            float v = (float)j / (float)sides;
            float b = v * 2.0f * PI_F;
            float n[3] = {cosf(b) * cosf(a), sinf(b), -cosf(b) * sinf(a)};
            float p[3] = {(R + r * cosf(b)) * cosf(a), r * sinf(b), -(R + r * cosf(b)) * sinf(a)};
            float t[4] = {-sinf(a), 0.0f, -cosf(a), 1.0f};
            add_vertex(m, p, n, t, u * 4.0f, v);
        }
    }
    for (uint32_t i = 0; i < segments; ++i)
        for (uint32_t j = 0; j < sides; ++j) {
            uint32_t a = first + i * (sides + 1) + j, b = a + sides + 1;
            add_triangle(m, a, b, a + 1);
            add_triangle(m, a + 1, b, b + 1);
        }
}

void demo_plane(demo_mesh *m, float hx, float hz, float uv_scale)
{
    float c[3] = {0, 0, 0}, n[3] = {0, 1, 0}, t[3] = {1, 0, 0}, b[3] = {0, 0, -1};
    box_face(m, c, n, t, b, hx, hz, uv_scale);
}

void demo_color_by_position(demo_mesh *m)
{
    for (uint32_t i = 0; i < m->vertex_count; ++i) {
        const float *p = m->positions + i * 3;
        float *c = m->colors + i * 4;
        c[0] = 0.5f + 0.5f * sinf(p[0] * 3.0f);
        c[1] = 0.5f + 0.5f * sinf(p[1] * 3.0f + 2.0f);
        c[2] = 0.5f + 0.5f * sinf(p[2] * 3.0f + 4.0f);
        c[3] = 1.0f;
    }
}

/* Integer hash (deterministic across machines): no rand(). */
static uint32_t hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

static float value_noise(uint32_t seed, float x, float y)
{
    int xi = (int)floorf(x), yi = (int)floorf(y);
    float fx = x - (float)xi, fy = y - (float)yi;
    float c[4];
    for (int k = 0; k < 4; ++k) {
        uint32_t h = hash32(seed ^ hash32((uint32_t)(xi + (k & 1)) * 73856093u ^ (uint32_t)(yi + (k >> 1)) * 19349663u));
        c[k] = (float)(h & 0xFFFF) / 65535.0f;
    }
    float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
    return (c[0] * (1 - sx) + c[1] * sx) * (1 - sy) + (c[2] * (1 - sx) + c[3] * sx) * sy;
}

/* Brick relief height in [0, 1] at texel (x, y) of a size-texel image. */
static float brick_height(uint32_t x, uint32_t y, uint32_t size)
{
    uint32_t bh = size / 8, bw = size / 4;
    uint32_t row = y / bh;
    uint32_t xo = (x + (row & 1) * bw / 2) % size;
    uint32_t mx = xo % bw, my = y % bh;
    uint32_t mortar = size / 64 ? size / 64 : 1;
    uint32_t dx = mx < bw - mx ? mx : bw - mx;
    uint32_t dy = my < bh - my ? my : bh - my;
    uint32_t d = dx < dy ? dx : dy;
    if (d < mortar)
        return 0.0f;
    float e = (float)(d - mortar) / (float)(mortar * 2);
    return e > 1.0f ? 1.0f : e;
}

static void mix_rgba(uint8_t *px, const uint8_t a[4], const uint8_t b[4], float t)
{
    for (int c = 0; c < 4; ++c)
        px[c] = (uint8_t)lroundf((float)a[c] + ((float)b[c] - (float)a[c]) * t);
}

mvr_result demo_image(mvr_scene *scene, demo_pattern pattern, uint32_t size, const uint8_t a[4],
                      const uint8_t b[4], uint32_t seed, mvr_image_id *out)
{
    uint8_t *rgba = malloc((size_t)size * size * 4);
    if (!rgba)
        return MVR_ERROR_OUT_OF_MEMORY;
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
            uint8_t *px = rgba + ((size_t)y * size + x) * 4;
            float fx = (float)x / (float)size, fy = (float)y / (float)size;
            switch (pattern) {
            case DEMO_CHECKER: {
                uint32_t cell = size / 8 ? size / 8 : 1;
                mix_rgba(px, a, b, ((x / cell + y / cell) & 1) ? 1.0f : 0.0f);
                break;
            }
            case DEMO_BRICKS: {
                float h = brick_height(x, y, size);
                uint32_t row = y / (size / 8);
                uint32_t col = (x + (row & 1) * size / 8) / (size / 4);
                float tint = (float)(hash32(seed ^ (row * 131u + col)) % 100) / 400.0f;
                mix_rgba(px, b, a, h > 0.0f ? 0.85f + tint : 0.0f);
                break;
            }
            case DEMO_BRICKS_NORMAL: {
                /* central differences of the relief -> tangent-space normal (+Z out) */
                float hl = brick_height((x + size - 1) % size, y, size);
                float hr = brick_height((x + 1) % size, y, size);
                float hu = brick_height(x, (y + size - 1) % size, size);
                float hd = brick_height(x, (y + 1) % size, size);
                float nx = (hl - hr) * 2.0f, ny = (hd - hu) * 2.0f, nz = 1.0f;
                float len = sqrtf(nx * nx + ny * ny + nz * nz);
                px[0] = (uint8_t)lroundf((nx / len * 0.5f + 0.5f) * 255.0f);
                px[1] = (uint8_t)lroundf((ny / len * 0.5f + 0.5f) * 255.0f);
                px[2] = (uint8_t)lroundf((nz / len * 0.5f + 0.5f) * 255.0f);
                px[3] = 255;
                break;
            }
            case DEMO_NOISE: {
                float n = 0.5f * value_noise(seed, fx * 8, fy * 8) + 0.3f * value_noise(seed + 1, fx * 16, fy * 16) +
                          0.2f * value_noise(seed + 2, fx * 32, fy * 32);
                mix_rgba(px, a, b, n);
                break;
            }
            case DEMO_WINDOWS: {
                uint32_t cols = 4, rows = 8;
                float cx = fx * (float)cols - floorf(fx * (float)cols);
                float cy = fy * (float)rows - floorf(fy * (float)rows);
                bool window = cx > 0.2f && cx < 0.8f && cy > 0.25f && cy < 0.75f;
                uint32_t lit = hash32(seed ^ ((uint32_t)(fx * (float)cols) * 7u + (uint32_t)(fy * (float)rows) * 131u)) % 3;
                mix_rgba(px, a, b, window ? (lit == 0 ? 1.0f : 0.6f) : 0.0f);
                break;
            }
            case DEMO_LEAF_MASK: {
                float lx = fx * 2.0f - 1.0f, ly = fy * 2.0f - 1.0f;
                float d = lx * lx / 0.3f + ly * ly;
                float vein = fabsf(lx) < 0.03f ? 0.6f : 1.0f;
                mix_rgba(px, a, b, 0.5f + 0.5f * value_noise(seed, fx * 6, fy * 6));
                for (int c = 0; c < 3; ++c)
                    px[c] = (uint8_t)((float)px[c] * vein);
                px[3] = d < 1.0f ? 255 : 0;
                break;
            }
            }
        }
    }
    mvr_image_desc d = {.width = size, .height = size, .rgba8 = rgba, .name = "demo"};
    mvr_result r = mvr_scene_add_image(scene, &d, out);
    free(rgba);
    return r;
}
