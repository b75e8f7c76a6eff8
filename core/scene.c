/* mvr_scene: owns copies of everything; validates before it accepts. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scene_internal.h"

mvr_result mvr_scene_fail(mvr_scene *s, mvr_result r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    mvr_error_record(s->last_error, sizeof s->last_error, &s->logger, r, fmt, ap);
    va_end(ap);
    return r;
}


static void *copy_floats(const float *src, uint32_t count, uint32_t per, bool *oom)
{
    if (!src)
        return NULL;
    size_t n, bytes;
    if (!mvr_size_mul(count, per, &n) || !mvr_size_mul(n, sizeof(float), &bytes)) {
        *oom = true;
        return NULL;
    }
    float *p = malloc(bytes ? bytes : 1);
    if (!p) {
        *oom = true;
        return NULL;
    }
    memcpy(p, src, bytes);
    return p;
}

/* FNV-1a, 64-bit: identifies identical pixel data. */
static uint64_t hash_bytes(const uint8_t *p, size_t n, uint64_t h)
{
    for (size_t i = 0; i < n; ++i) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

mvr_result mvr_scene_create(const mvr_scene_desc *desc, mvr_scene **out, mvr_error *error)
{
    if (!out)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_create: out_scene is NULL");
    *out = NULL;
    mvr_scene *s = calloc(1, sizeof *s);
    if (!s)
        return mvr_error_set(error, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_create: out of memory");
    if (desc)
        s->logger = desc->logger;
    s->geometry_version = s->material_version = s->transform_version = 1;
    s->selected_variant = MVR_VARIANT_DEFAULT;
    /* address and creation time (C11 timespec_get), mixed */
    struct timespec ts = {0, 0};
    timespec_get(&ts, TIME_UTC);
    uint64_t t = (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
    s->serial = hash_bytes((const uint8_t *)&t, sizeof t, (uint64_t)(uintptr_t)s * 0x9E3779B97F4A7C15ull);
    *out = s;
    if (error) {
        error->result = MVR_OK;
        error->message[0] = '\0';
    }
    return MVR_OK;
}

static void free_primitive(scene_primitive *p)
{
    free(p->positions);
    free(p->normals);
    free(p->tangents);
    free(p->uv0);
    free(p->uv1);
    free(p->colors);
    free(p->indices);
    free(p->variant_maps);
    mvr_scene_free_deformers(p);
}

void mvr_scene_destroy(mvr_scene *s)
{
    if (!s)
        return;
    for (uint32_t i = 0; i < s->image_count; ++i) {
        free(s->images[i].rgba);
        free(s->images[i].blocks);
    }
    for (uint32_t i = 0; i < s->primitive_count; ++i)
        free_primitive(&s->primitives[i]);
    for (uint32_t i = 0; i < s->mesh_count; ++i)
        free(s->meshes[i].weights);
    for (uint32_t i = 0; i < s->node_count; ++i) {
        free(s->nodes[i].weights);
        free(s->nodes[i].rest_weights);
    }
    mvr_scene_free_skins_and_animations(s);
    mvr_scene_free_variants(s);
    free(s->images);
    free(s->materials);
    free(s->primitives);
    free(s->meshes);
    free(s->nodes);
    free(s->lights);
    free(s->cameras);
    free(s);
}

uint64_t mvr_scene_serial(const mvr_scene *s)
{
    return s->serial;
}

const char *mvr_scene_last_error(const mvr_scene *s)
{
    return s ? s->last_error : "mvr_scene_last_error: scene is NULL";
}

static const struct {
    const char *name;
    uint8_t bw, bh, bytes;
} image_formats[MVR_IMAGE_FORMAT_COUNT] = {
    [MVR_IMAGE_FORMAT_RGBA8] = {"rgba8", 1, 1, 4},
    [MVR_IMAGE_FORMAT_ETC2_RGB8] = {"etc2_rgb8", 4, 4, 8},
    [MVR_IMAGE_FORMAT_ETC2_RGB8_A1] = {"etc2_rgb8_a1", 4, 4, 8},
    [MVR_IMAGE_FORMAT_ETC2_RGBA8] = {"etc2_rgba8", 4, 4, 16},
    [MVR_IMAGE_FORMAT_EAC_R11] = {"eac_r11", 4, 4, 8},
    [MVR_IMAGE_FORMAT_EAC_RG11] = {"eac_rg11", 4, 4, 16},
    [MVR_IMAGE_FORMAT_ASTC_4x4] = {"astc_4x4", 4, 4, 16},
    [MVR_IMAGE_FORMAT_ASTC_5x4] = {"astc_5x4", 5, 4, 16},
    [MVR_IMAGE_FORMAT_ASTC_5x5] = {"astc_5x5", 5, 5, 16},
    [MVR_IMAGE_FORMAT_ASTC_6x5] = {"astc_6x5", 6, 5, 16},
    [MVR_IMAGE_FORMAT_ASTC_6x6] = {"astc_6x6", 6, 6, 16},
    [MVR_IMAGE_FORMAT_ASTC_8x5] = {"astc_8x5", 8, 5, 16},
    [MVR_IMAGE_FORMAT_ASTC_8x6] = {"astc_8x6", 8, 6, 16},
    [MVR_IMAGE_FORMAT_ASTC_8x8] = {"astc_8x8", 8, 8, 16},
    [MVR_IMAGE_FORMAT_ASTC_10x5] = {"astc_10x5", 10, 5, 16},
    [MVR_IMAGE_FORMAT_ASTC_10x6] = {"astc_10x6", 10, 6, 16},
    [MVR_IMAGE_FORMAT_ASTC_10x8] = {"astc_10x8", 10, 8, 16},
    [MVR_IMAGE_FORMAT_ASTC_10x10] = {"astc_10x10", 10, 10, 16},
    [MVR_IMAGE_FORMAT_ASTC_12x10] = {"astc_12x10", 12, 10, 16},
    [MVR_IMAGE_FORMAT_ASTC_12x12] = {"astc_12x12", 12, 12, 16},
};

const char *mvr_image_format_name(mvr_image_format f)
{
    return (unsigned)f < MVR_IMAGE_FORMAT_COUNT ? image_formats[f].name : "unknown";
}

bool mvr_image_format_block(mvr_image_format f, uint32_t *bw, uint32_t *bh, uint32_t *bytes)
{
    if ((unsigned)f >= MVR_IMAGE_FORMAT_COUNT)
        return false;
    if (bw)
        *bw = image_formats[f].bw;
    if (bh)
        *bh = image_formats[f].bh;
    if (bytes)
        *bytes = image_formats[f].bytes;
    return true;
}

/* floor(log2(max(w, h))) + 1: the levels of a full chain */
static uint32_t chain_levels(uint32_t w, uint32_t h)
{
    uint32_t n = 1, m = w > h ? w : h;
    while (m > 1) {
        m >>= 1;
        n++;
    }
    return n;
}

bool mvr_image_level_size(mvr_image_format f, uint32_t w, uint32_t h, uint32_t level, uint64_t *out)
{
    *out = 0;
    if ((unsigned)f >= MVR_IMAGE_FORMAT_COUNT || w == 0 || h == 0 || level >= chain_levels(w, h))
        return false;
    uint64_t lw = w >> level ? w >> level : 1, lh = h >> level ? h >> level : 1;
    uint64_t bx = (lw + image_formats[f].bw - 1) / image_formats[f].bw;
    uint64_t by = (lh + image_formats[f].bh - 1) / image_formats[f].bh;
    uint64_t n;
    if (__builtin_mul_overflow(bx, by, &n) || __builtin_mul_overflow(n, (uint64_t)image_formats[f].bytes, &n))
        return false;
    *out = n;
    return true;
}

void mvr_scene_image_rehash(scene_image *img)
{
    img->hash = hash_bytes(mvr_scene_image_bytes(img), img->bytes,
                           (14695981039346656037ull ^ ((uint64_t)img->width << 32 | img->height)) +
                               ((uint64_t)img->format << 8 | img->levels));
}

mvr_result mvr_scene_add_image(mvr_scene *s, const mvr_image_desc *d, mvr_image_id *out)
{
    if (!s || !d || !out)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_image: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    out->id = 0;
    const char *name = d->name ? d->name : "";
    if (d->width == 0 || d->height == 0 || d->width > 16384 || d->height > 16384)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_image(%s): size %ux%u is not within 1..16384", name, d->width, d->height);
    if ((unsigned)d->format >= MVR_IMAGE_FORMAT_COUNT)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_image(%s): format %d is not an mvr_image_format",
                              name, (int)d->format);
    bool blocks = d->format != MVR_IMAGE_FORMAT_RGBA8;
    size_t bytes = 0;
    uint32_t levels = 1;
    size_t offset[MVR_IMAGE_MAX_LEVELS] = {0}, size[MVR_IMAGE_MAX_LEVELS] = {0};
    if (!blocks) {
        if (!d->rgba8)
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_image(%s): no pixels", name);
        if (d->level_count > 1)
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_scene_add_image(%s): %u levels of RGBA8 pixels (RGBA8 images give level 0; "
                                  "mips are generated)", name, d->level_count);
        if (!mvr_size_mul((size_t)d->width * d->height, 4, &bytes))
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_image: size overflows");
    } else {
        const char *fname = mvr_image_format_name(d->format);
        uint32_t chain = chain_levels(d->width, d->height);
        levels = d->level_count;
        if (levels == 0 || levels > chain)
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_scene_add_image(%s): %u levels; a %ux%u image has 1..%u", name, levels,
                                  d->width, d->height, chain);
        if (d->rgba8)
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_scene_add_image(%s): RGBA8 pixels given for a %s image", name, fname);
        for (uint32_t k = 0; k < levels; ++k) {
            uint64_t want = 0;
            if (!mvr_image_level_size(d->format, d->width, d->height, k, &want) || want > SIZE_MAX)
                return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_image(%s): level %u overflows",
                                      name, k);
            if (!d->levels[k].data || d->levels[k].size != want)
                return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                      "mvr_scene_add_image(%s): level %u of %s %ux%u %s %zu bytes; it needs %llu",
                                      name, k, fname, d->width >> k ? d->width >> k : 1,
                                      d->height >> k ? d->height >> k : 1, d->levels[k].data ? "has" : "has no data, size",
                                      d->levels[k].size, (unsigned long long)want);
            offset[k] = bytes;
            size[k] = (size_t)want;
            if (bytes > SIZE_MAX - (size_t)want)
                return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_image(%s): size overflows", name);
            bytes += (size_t)want;
        }
    }
    if (!GROW(s, images, image_count, image_cap))
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_image: out of memory");
    scene_image *img = &s->images[s->image_count];
    memset(img, 0, sizeof *img);
    uint8_t *data = malloc(bytes);
    if (!data)
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_image(%s): out of memory (%zu bytes)", name,
                              bytes);
    if (blocks) {
        for (uint32_t k = 0; k < levels; ++k)
            memcpy(data + offset[k], d->levels[k].data, size[k]);
        img->blocks = data;
        memcpy(img->level_offset, offset, sizeof offset);
        memcpy(img->level_size, size, sizeof size);
    } else {
        memcpy(data, d->rgba8, bytes);
        img->rgba = data;
    }
    img->format = d->format;
    img->levels = levels;
    img->bytes = bytes;
    img->width = d->width;
    img->height = d->height;
    mvr_scene_image_rehash(img);
    mvr_str_copy(img->name, sizeof img->name, d->name);
    s->image_count++;
    s->geometry_version++;
    out->id = s->image_count;
    return MVR_OK;
}

bool mvr_finite_floats(const float *v, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(v[i]))
            return false;
    return true;
}


/* Degenerate vertex data is repaired, never refused (only NaN or infinite
 * positions are): a NaN or zero-length normal becomes (0, 0, 0), which the
 * fragment shader replaces by the face normal from position derivatives;
 * a bad tangent becomes (0, 0, 0, 1), which drops the normal map's tangent
 * plane for that vertex (shading keeps the interpolated normal); a NaN or
 * infinite UV becomes 0 and a NaN color 1 (COLOR_0's neutral value), and
 * colors are clamped to [0, 1] as glTF requires. Returns the number of
 * vertex attributes changed. */
static uint32_t sanitize_vertices(scene_primitive *p)
{
    uint32_t changed = 0;
    for (uint32_t i = 0; i < p->vertex_count; ++i) {
        if (p->normals) {
            float *n = p->normals + (size_t)i * 3;
            float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            if (!(len2 > 1e-24f) || !isfinite(len2)) { /* !(x > e) is also true for NaN */
                n[0] = n[1] = n[2] = 0.0f;
                changed++;
            }
        }
        if (p->tangents) {
            float *t = p->tangents + (size_t)i * 4;
            float len2 = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
            bool bad = !(len2 > 1e-24f) || !isfinite(len2);
            if (bad)
                t[0] = t[1] = t[2] = 0.0f;
            if (t[3] != 1.0f && t[3] != -1.0f) { /* the bitangent sign is +-1 */
                t[3] = t[3] < 0.0f ? -1.0f : 1.0f;
                bad = true;
            }
            changed += bad;
        }
        float *uvs[2] = {p->uv0 ? p->uv0 + (size_t)i * 2 : NULL, p->uv1 ? p->uv1 + (size_t)i * 2 : NULL};
        for (int u = 0; u < 2; ++u)
            if (uvs[u] && (!isfinite(uvs[u][0]) || !isfinite(uvs[u][1]))) {
                uvs[u][0] = isfinite(uvs[u][0]) ? uvs[u][0] : 0.0f;
                uvs[u][1] = isfinite(uvs[u][1]) ? uvs[u][1] : 0.0f;
                changed++;
            }
        if (p->colors) {
            float *c = p->colors + (size_t)i * 4;
            bool bad = false;
            for (int j = 0; j < 4; ++j) {
                float v = isnan(c[j]) ? 1.0f : c[j] < 0.0f ? 0.0f : c[j] > 1.0f ? 1.0f : c[j];
                bad |= v != c[j];
                c[j] = v;
            }
            changed += bad;
        }
    }
    return changed;
}

static mvr_result add_primitive(mvr_scene *s, const mvr_primitive_desc *d, const char *mesh, uint32_t k)
{
    if (d->vertex_count == 0 || !d->positions)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_mesh(%s): primitive %u has no positions", mesh, k);
    if ((unsigned)d->mode > MVR_PRIMITIVE_POINTS)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_mesh(%s): primitive %u: unknown mode",
                              mesh, k);
    if (d->material.id > s->material_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_mesh(%s): primitive %u names material %u; the scene has %u",
                              mesh, k, d->material.id, s->material_count);
    if (!mvr_finite_floats(d->positions, (size_t)d->vertex_count * 3))
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_mesh(%s): primitive %u has NaN or infinite positions", mesh, k);
    uint32_t count = d->index_count ? d->index_count : d->vertex_count;
    uint32_t per = d->mode == MVR_PRIMITIVE_TRIANGLES ? 3u : d->mode == MVR_PRIMITIVE_LINES ? 2u : 1u;
    if (count % per != 0)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_mesh(%s): primitive %u: %u %s is not a multiple of %u",
                              mesh, k, count, d->index_count ? "indices" : "vertices", per);
    if (d->index_count && !d->indices16 == !d->indices32)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_mesh(%s): primitive %u: give exactly one of indices16 / indices32",
                              mesh, k);
    for (uint32_t i = 0; i < d->index_count; ++i) {
        uint32_t v = d->indices16 ? d->indices16[i] : d->indices32[i];
        if (v >= d->vertex_count)
            return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                                  "mvr_scene_add_mesh(%s): primitive %u: index %u at %u is out of range (%u vertices)",
                                  mesh, k, v, i, d->vertex_count);
    }
    if (!GROW(s, primitives, primitive_count, primitive_cap))
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_mesh: out of memory");
    scene_primitive *p = &s->primitives[s->primitive_count];
    memset(p, 0, sizeof *p);
    bool oom = false;
    p->vertex_count = d->vertex_count;
    p->positions = copy_floats(d->positions, d->vertex_count, 3, &oom);
    p->normals = copy_floats(d->normals, d->vertex_count, 3, &oom);
    p->tangents = copy_floats(d->tangents, d->vertex_count, 4, &oom);
    p->uv0 = copy_floats(d->texcoords0, d->vertex_count, 2, &oom);
    p->uv1 = copy_floats(d->texcoords1, d->vertex_count, 2, &oom);
    p->colors = copy_floats(d->colors, d->vertex_count, 4, &oom);
    if (d->index_count && !oom) {
        p->indices = malloc((size_t)d->index_count * sizeof *p->indices);
        if (!p->indices)
            oom = true;
        else {
            p->small_indices = true;
            for (uint32_t i = 0; i < d->index_count; ++i) {
                p->indices[i] = d->indices16 ? d->indices16[i] : d->indices32[i];
                if (p->indices[i] > 0xFFFEu)
                    p->small_indices = false;
            }
        }
    }
    if (oom) {
        free_primitive(p);
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_mesh(%s): out of memory", mesh);
    }
    mvr_result dr = mvr_scene_primitive_deformers(s, p, d, mesh, k);
    if (dr != MVR_OK) {
        free_primitive(p);
        return dr;
    }
    uint32_t repaired = sanitize_vertices(p);
    if (repaired) {
        s->sanitized += repaired;
        mvr_log(&s->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                "mvr_scene_add_mesh(%s): primitive %u: %u vertex attributes were NaN, infinite or zero-length "
                "(repaired: normals from the face, tangents dropped, UVs 0, colors clamped)",
                mesh, k, repaired);
    }
    p->index_count = d->index_count;
    p->mode = d->mode;
    p->material = d->material.id ? d->material.id - 1 : MVR_NO_INDEX;
    p->own_material = p->material;
    p->bounds_min = mvr_dvec3_make(INFINITY, INFINITY, INFINITY);
    p->bounds_max = mvr_dvec3_make(-INFINITY, -INFINITY, -INFINITY);
    for (uint32_t i = 0; i < d->vertex_count; ++i) {
        const float *v = d->positions + (size_t)i * 3;
        p->bounds_min = mvr_dvec3_make(fmin(p->bounds_min.x, v[0]), fmin(p->bounds_min.y, v[1]),
                                       fmin(p->bounds_min.z, v[2]));
        p->bounds_max = mvr_dvec3_make(fmax(p->bounds_max.x, v[0]), fmax(p->bounds_max.y, v[1]),
                                       fmax(p->bounds_max.z, v[2]));
    }
    s->primitive_count++;
    return MVR_OK;
}

mvr_result mvr_scene_add_mesh(mvr_scene *s, const mvr_mesh_desc *d, mvr_mesh_id *out)
{
    if (!s || !d || !out)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_mesh: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    out->id = 0;
    const char *name = d->name ? d->name : "";
    if (d->primitive_count == 0 || !d->primitives)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_mesh(%s): no primitives", name);
    if (!GROW(s, meshes, mesh_count, mesh_cap))
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_mesh: out of memory");
    uint32_t first = s->primitive_count;
    for (uint32_t k = 0; k < d->primitive_count; ++k) {
        mvr_result r = add_primitive(s, &d->primitives[k], name, k);
        if (r != MVR_OK) {
            while (s->primitive_count > first)
                free_primitive(&s->primitives[--s->primitive_count]);
            return r;
        }
    }
    /* glTF 3.7.2.2: every primitive of a mesh has the same number of targets */
    uint32_t targets = s->primitives[first].target_count;
    const char *bad = NULL;
    for (uint32_t k = 1; k < d->primitive_count && !bad; ++k)
        if (s->primitives[first + k].target_count != targets)
            bad = "its primitives have different numbers of morph targets";
    if (!bad && d->weight_count && (d->weight_count != targets || !d->weights))
        bad = "its default weights are not one per morph target";
    if (!bad && d->weight_count && !mvr_finite_floats(d->weights, d->weight_count))
        bad = "its default weights are not finite";
    float *weights = NULL;
    if (!bad && targets) {
        weights = calloc(targets, sizeof *weights);
        if (!weights)
            bad = "out of memory";
        else if (d->weight_count)
            memcpy(weights, d->weights, targets * sizeof *weights);
    }
    if (bad) {
        while (s->primitive_count > first)
            free_primitive(&s->primitives[--s->primitive_count]);
        return mvr_scene_fail(s, strcmp(bad, "out of memory") ? MVR_ERROR_INVALID_ARGUMENT : MVR_ERROR_OUT_OF_MEMORY,
                              "mvr_scene_add_mesh(%s): %s (%u targets, %u weights)", name, bad, targets,
                              d->weight_count);
    }
    for (uint32_t k = 0; k < d->primitive_count; ++k) {
        scene_primitive *p = &s->primitives[first + k];
        if (!p->target_count)
            continue;
        uint32_t slot = 0, slots = 0;
        const float *attr[3] = {p->target_positions, p->target_normals, p->target_tangents};
        for (uint32_t a = 0; a < 3; ++a)
            slots |= (attr[a] ? slot++ : 3u) << (2 * a);
        p->morph_attributes = slot;
        p->morph_slots = slots;
        p->morph_base = s->morph_texels;
        s->morph_texels += (uint64_t)p->target_count * slot * p->vertex_count;
    }
    scene_mesh *m = &s->meshes[s->mesh_count];
    m->first_primitive = first;
    m->primitive_count = d->primitive_count;
    m->target_count = targets;
    m->weights = weights;
    mvr_str_copy(m->name, sizeof m->name, name);
    s->mesh_count++;
    s->geometry_version++;
    out->id = s->mesh_count;
    return MVR_OK;
}

mvr_result mvr_scene_add_light(mvr_scene *s, const mvr_light_desc *d, mvr_light_id *out)
{
    if (!s || !d || !out)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_light: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    out->id = 0;
    if ((unsigned)d->type > MVR_LIGHT_SPOT)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_light: unknown type %d", (int)d->type);
    if (!mvr_finite_floats(d->color, 3) || !isfinite(d->intensity) || d->intensity < 0 ||
        !isfinite(d->range) || d->range < 0)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_light: color, intensity and range must be finite and >= 0");
    if (!GROW(s, lights, light_count, light_cap))
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_light: out of memory");
    mvr_light_desc l = *d;
    if (l.color[0] == 0 && l.color[1] == 0 && l.color[2] == 0)
        l.color[0] = l.color[1] = l.color[2] = 1.0f;
    if (l.outer_cone_angle <= 0.0f)
        l.outer_cone_angle = (float)(3.14159265358979323846 / 4.0);
    if (l.inner_cone_angle >= l.outer_cone_angle)
        l.inner_cone_angle = 0.999f * l.outer_cone_angle;
    s->lights[s->light_count++] = l;
    s->transform_version++;
    out->id = s->light_count;
    return MVR_OK;
}

mvr_result mvr_scene_add_camera(mvr_scene *s, const mvr_projection *p, mvr_camera_id *out)
{
    if (!s || !p || !out)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_camera: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    out->id = 0;
    if ((unsigned)p->type > MVR_PROJECTION_MATRIX)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_camera: unknown projection %d",
                              (int)p->type);
    if (!GROW(s, cameras, camera_count, camera_cap))
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_camera: out of memory");
    s->cameras[s->camera_count++] = *p;
    out->id = s->camera_count;
    return MVR_OK;
}

static bool all_zero(const double *v, int n)
{
    for (int i = 0; i < n; ++i)
        if (v[i] != 0.0)
            return false;
    return true;
}

static bool finite_doubles(const double *v, int n)
{
    for (int i = 0; i < n; ++i)
        if (!isfinite(v[i]))
            return false;
    return true;
}

/* Sets a node's TRS. A rotation that is not a unit quaternion (glTF
 * requires one) is normalized, counted and logged; all zero is the API's
 * "identity" default and no repair. */
static void set_trs(mvr_scene *s, scene_node *n, const char *where, const double t[3], const double r[4],
                    const double sc[3])
{
    n->translation = mvr_dvec3_make(t[0], t[1], t[2]);
    mvr_dquat q = {r[0], r[1], r[2], r[3]};
    if (all_zero(r, 4))
        q.w = 1.0;
    double len2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
    if (fabs(len2 - 1.0) > 1e-6) {
        s->sanitized++;
        mvr_log(&s->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                "%s: rotation (%g, %g, %g, %g) is not a unit quaternion (normalized)", where, q.x, q.y, q.z, q.w);
    }
    n->rotation = mvr_dquat_normalize(q);
    n->scale = all_zero(sc, 3) ? mvr_dvec3_make(1, 1, 1) : mvr_dvec3_make(sc[0], sc[1], sc[2]);
}

mvr_result mvr_scene_add_node(mvr_scene *s, const mvr_node_desc *d, mvr_node_id *out)
{
    if (!s || !d || !out)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_node: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    out->id = 0;
    const char *name = d->name ? d->name : "";
    if (d->parent.id > s->node_count || d->mesh.id > s->mesh_count ||
        d->light.id > s->light_count || d->camera.id > s->camera_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_node(%s): parent %u / mesh %u / light %u / camera %u out of range "
                              "(%u nodes, %u meshes, %u lights, %u cameras)",
                              name, d->parent.id, d->mesh.id, d->light.id, d->camera.id, s->node_count,
                              s->mesh_count, s->light_count, s->camera_count);
    if (d->use_matrix ? !finite_doubles(d->matrix, 16)
                      : !(finite_doubles(d->translation, 3) && finite_doubles(d->rotation, 4) &&
                          finite_doubles(d->scale, 3)))
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_node(%s): transform is not finite", name);
    if (!GROW(s, nodes, node_count, node_cap))
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_node: out of memory");
    scene_node *n = &s->nodes[s->node_count];
    memset(n, 0, sizeof *n);
    n->parent = d->parent.id ? d->parent.id - 1 : MVR_NO_INDEX;
    n->use_matrix = d->use_matrix;
    if (d->use_matrix)
        memcpy(n->matrix.m, d->matrix, sizeof n->matrix.m);
    else
        set_trs(s, n, "mvr_scene_add_node", d->translation, d->rotation, d->scale);
    n->mesh = d->mesh.id ? d->mesh.id - 1 : MVR_NO_INDEX;
    n->light = d->light.id ? d->light.id - 1 : MVR_NO_INDEX;
    n->camera = d->camera.id ? d->camera.id - 1 : MVR_NO_INDEX;
    n->skin = MVR_NO_INDEX;
    n->rest_translation = n->translation;
    n->rest_rotation = n->rotation;
    n->rest_scale = n->scale;
    mvr_str_copy(n->name, sizeof n->name, name);
    s->node_count++;
    s->transform_version++;
    out->id = s->node_count;
    return MVR_OK;
}

mvr_result mvr_scene_set_node_transform(mvr_scene *s, mvr_node_id node, const double t[3],
                                        const double r[4], const double sc[3])
{
    if (!s || !t || !r || !sc)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_set_node_transform: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    if (node.id == 0 || node.id > s->node_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_set_node_transform: node %u out of range",
                              node.id);
    if (!finite_doubles(t, 3) || !finite_doubles(r, 4) || !finite_doubles(sc, 3))
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_set_node_transform: not finite");
    scene_node *n = &s->nodes[node.id - 1];
    n->use_matrix = false;
    set_trs(s, n, "mvr_scene_set_node_transform", t, r, sc);
    n->rest_translation = n->translation;
    n->rest_rotation = n->rotation;
    n->rest_scale = n->scale;
    s->transform_version++;
    return MVR_OK;
}

void mvr_scene_set_ambient(mvr_scene *s, const float rgb[3])
{
    if (!s || !rgb || !mvr_finite_floats(rgb, 3))
        return;
    memcpy(s->ambient, rgb, sizeof s->ambient);
    s->transform_version++;
}

void mvr_scene_world_matrices(const mvr_scene *s, mvr_dmat4 *out)
{
    for (uint32_t i = 0; i < s->node_count; ++i) {
        const scene_node *n = &s->nodes[i];
        mvr_dmat4 local = n->use_matrix ? n->matrix : mvr_dmat4_trs(n->translation, n->rotation, n->scale);
        out[i] = n->parent == MVR_NO_INDEX ? local : mvr_dmat4_mul(&out[n->parent], &local);
    }
}

void mvr_scene_get_info(const mvr_scene *s, mvr_scene_info *out)
{
    memset(out, 0, sizeof *out);
    if (!s)
        return;
    out->images = s->image_count;
    out->materials = s->material_count;
    out->meshes = s->mesh_count;
    out->primitives = s->primitive_count;
    out->nodes = s->node_count;
    out->lights = s->light_count;
    out->cameras = s->camera_count;
    out->skins = s->skin_count;
    for (uint32_t i = 0; i < s->skin_count; ++i)
        out->joints += s->skins[i].joint_count;
    out->animations = s->animation_count;
    for (uint32_t i = 0; i < s->primitive_count; ++i)
        out->morph_targets += s->primitives[i].target_count;
    for (uint32_t i = 0; i < s->light_count; ++i) {
        const mvr_light_desc *l = &s->lights[i];
        float c = fmaxf(l->color[0], fmaxf(l->color[1], l->color[2])) * l->intensity;
        if (c > out->max_light_intensity[l->type])
            out->max_light_intensity[l->type] = c;
    }
    mvr_dvec3 lo = mvr_dvec3_make(INFINITY, INFINITY, INFINITY);
    mvr_dvec3 hi = mvr_dvec3_make(-INFINITY, -INFINITY, -INFINITY);
    uint32_t most_joints = 0;
    for (uint32_t i = 0; i < s->skin_count; ++i)
        if (s->skins[i].joint_count > most_joints)
            most_joints = s->skins[i].joint_count;
    mvr_dmat4 *world = s->node_count ? malloc(s->node_count * sizeof *world) : NULL;
    mvr_dmat4 *joints = most_joints ? malloc(most_joints * sizeof *joints) : NULL;
    if (world) {
        mvr_scene_world_matrices(s, world);
        for (uint32_t i = 0; i < s->node_count; ++i) {
            const scene_node *n = &s->nodes[i];
            if (n->mesh == MVR_NO_INDEX)
                continue;
            /* as posed now: skinned by its joints, morphed by its weights */
            if (n->skin != MVR_NO_INDEX && joints)
                mvr_scene_skin_matrices(s, n->skin, world, joints);
            const scene_mesh *m = &s->meshes[n->mesh];
            for (uint32_t k = 0; k < m->primitive_count; ++k) {
                mvr_dvec3 plo, phi;
                mvr_scene_posed_bounds(s, n, &s->primitives[m->first_primitive + k], &world[i],
                                       n->skin != MVR_NO_INDEX ? joints : NULL, &plo, &phi);
                lo = mvr_dvec3_make(fmin(lo.x, plo.x), fmin(lo.y, plo.y), fmin(lo.z, plo.z));
                hi = mvr_dvec3_make(fmax(hi.x, phi.x), fmax(hi.y, phi.y), fmax(hi.z, phi.z));
            }
        }
    }
    free(world);
    free(joints);
    out->bounds_min[0] = lo.x; out->bounds_min[1] = lo.y; out->bounds_min[2] = lo.z;
    out->bounds_max[0] = hi.x; out->bounds_max[1] = hi.y; out->bounds_max[2] = hi.z;
}

uint32_t mvr_scene_sanitized_count(const mvr_scene *s)
{
    return s ? s->sanitized : 0;
}

uint32_t mvr_scene_camera_node_count(const mvr_scene *s)
{
    uint32_t n = 0;
    for (uint32_t i = 0; s && i < s->node_count; ++i)
        n += s->nodes[i].camera != MVR_NO_INDEX;
    return n;
}

mvr_node_id mvr_scene_camera_node(const mvr_scene *s, uint32_t index)
{
    for (uint32_t i = 0; s && i < s->node_count; ++i)
        if (s->nodes[i].camera != MVR_NO_INDEX && index-- == 0)
            return (mvr_node_id){i + 1};
    return (mvr_node_id){0};
}

bool mvr_scene_lights_physical(const mvr_scene *s)
{
    mvr_scene_info info;
    mvr_scene_get_info(s, &info);
    return info.max_light_intensity[MVR_LIGHT_DIRECTIONAL] > 20.0f ||
           info.max_light_intensity[MVR_LIGHT_POINT] > 100.0f || info.max_light_intensity[MVR_LIGHT_SPOT] > 100.0f;
}

const char *mvr_scene_node_name(const mvr_scene *s, mvr_node_id node)
{
    return s && node.id >= 1 && node.id <= s->node_count ? s->nodes[node.id - 1].name : NULL;
}

const char *mvr_scene_mesh_name(const mvr_scene *s, mvr_mesh_id mesh)
{
    return s && mesh.id >= 1 && mesh.id <= s->mesh_count ? s->meshes[mesh.id - 1].name : NULL;
}

const char *mvr_scene_material_name(const mvr_scene *s, mvr_material_id material)
{
    return s && material.id >= 1 && material.id <= s->material_count ? s->materials[material.id - 1].name : NULL;
}

mvr_mesh_id mvr_scene_node_mesh(const mvr_scene *s, mvr_node_id node)
{
    mvr_mesh_id id = {0};
    if (s && node.id >= 1 && node.id <= s->node_count && s->nodes[node.id - 1].mesh != MVR_NO_INDEX)
        id.id = s->nodes[node.id - 1].mesh + 1;
    return id;
}
