/* Uploads of a scene: geometry once per geometry change, textures once per
 * image (and color space), the material table once per material change.
 * Nothing here depends on the views. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "errors.h"
#include "gpu_scene.h"
#include "renderer.h"
#include "skinning.h"

#ifndef GL_TEXTURE_MAX_ANISOTROPY_EXT
#define GL_TEXTURE_MAX_ANISOTROPY_EXT 0x84FE
#endif

static GLenum gl_filter(mvr_filter f, bool min)
{
    switch (f) {
    case MVR_FILTER_DEFAULT: return min ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR;
    case MVR_FILTER_NEAREST: return GL_NEAREST;
    case MVR_FILTER_LINEAR: return GL_LINEAR;
    case MVR_FILTER_NEAREST_MIPMAP_NEAREST: return min ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST;
    case MVR_FILTER_LINEAR_MIPMAP_NEAREST: return min ? GL_LINEAR_MIPMAP_NEAREST : GL_LINEAR;
    case MVR_FILTER_NEAREST_MIPMAP_LINEAR: return min ? GL_NEAREST_MIPMAP_LINEAR : GL_NEAREST;
    case MVR_FILTER_LINEAR_MIPMAP_LINEAR: return min ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR;
    }
    return GL_LINEAR;
}

static GLenum gl_wrap(mvr_wrap w)
{
    switch (w) {
    case MVR_WRAP_DEFAULT:
    case MVR_WRAP_REPEAT: return GL_REPEAT;
    case MVR_WRAP_CLAMP_TO_EDGE: return GL_CLAMP_TO_EDGE;
    case MVR_WRAP_MIRRORED_REPEAT: return GL_MIRRORED_REPEAT;
    }
    return GL_REPEAT;
}

static bool same_sampler(const mvr_sampler_desc *a, const mvr_sampler_desc *b)
{
    return gl_filter(a->mag_filter, false) == gl_filter(b->mag_filter, false) &&
           gl_filter(a->min_filter, true) == gl_filter(b->min_filter, true) &&
           gl_wrap(a->wrap_s) == gl_wrap(b->wrap_s) && gl_wrap(a->wrap_t) == gl_wrap(b->wrap_t);
}

static GLuint sampler_for(mvr_renderer *r, const mvr_sampler_desc *d)
{
    mvr_gpu_scene *g = &r->gpu;
    for (uint32_t i = 0; i < g->sampler_count; ++i)
        if (same_sampler(&g->samplers[i].desc, d))
            return g->samplers[i].sampler;
    if (g->sampler_count == g->sampler_cap) {
        uint32_t cap = g->sampler_cap ? g->sampler_cap * 2 : 8;
        mvr_gpu_sampler *p = realloc(g->samplers, cap * sizeof *p);
        if (!p)
            return 0;
        g->samplers = p;
        g->sampler_cap = cap;
    }
    const mvr_gl_api_table *gl = r->gl;
    GLuint s = 0;
    gl->GenSamplers(1, &s);
    gl->SamplerParameteri(s, GL_TEXTURE_MAG_FILTER, (GLint)gl_filter(d->mag_filter, false));
    gl->SamplerParameteri(s, GL_TEXTURE_MIN_FILTER, (GLint)gl_filter(d->min_filter, true));
    gl->SamplerParameteri(s, GL_TEXTURE_WRAP_S, (GLint)gl_wrap(d->wrap_s));
    gl->SamplerParameteri(s, GL_TEXTURE_WRAP_T, (GLint)gl_wrap(d->wrap_t));
    /* overrides.anisotropic on: anisotropic filtering (up to 16x) on linear,
     * mipmapped samplers, as the Khronos glTF Sample Renderer sets: at grazing
     * angles (rims, creases) trilinear filtering picks the mip of the
     * footprint's long axis and blurs across the short one. Not the default:
     * llvmpipe (Mesa 25) samples black where the UV derivatives are zero */
    if (r->anisotropic_on && r->ctx->caps.ext.ext_texture_filter_anisotropic &&
        r->ctx->caps.limits.max_anisotropy > 1.0f &&
        gl_filter(d->mag_filter, false) == GL_LINEAR && mvr_sampler_uses_mipmaps(d))
        gl->SamplerParameterf(s, GL_TEXTURE_MAX_ANISOTROPY_EXT, fminf(16.0f, r->ctx->caps.limits.max_anisotropy));
    g->samplers[g->sampler_count].desc = *d;
    g->samplers[g->sampler_count++].sampler = s;
    return s;
}

/* Whether any material samples the image with a mipmapped minification filter. */
static bool image_needs_mipmaps(const mvr_scene *s, uint32_t image)
{
    for (uint32_t i = 0; i < s->material_count; ++i) {
        const mvr_material_desc *m = &s->materials[i].desc;
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
            const mvr_texture_ref *t = mvr_material_role(m, role);
            if (t->image.id == image + 1 && mvr_sampler_uses_mipmaps(&t->sampler))
                return true;
        }
    }
    return false;
}

/* ---- images too large for the GL (mvr_oversized_image) */

/* Box filter of an RGBA8 image into dw x dh (each side at most the
 * source's): each output texel averages the source texels it covers. sRGB
 * color channels are averaged in linear light (as the GL filters sRGB
 * mips), alpha and linear roles as stored. NULL when out of memory. */
static uint8_t *downscale_rgba8(const uint8_t *src, uint32_t sw, uint32_t sh, uint32_t dw, uint32_t dh, bool srgb)
{
    uint8_t *dst = malloc((size_t)dw * dh * 4);
    if (!dst)
        return NULL;
    float lut[256], mid[255];
    for (int i = 0; i < 256; ++i) {
        float c = (float)i / 255.0f;
        lut[i] = !srgb ? c : c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
    }
    for (int i = 0; i < 255; ++i)
        mid[i] = 0.5f * (lut[i] + lut[i + 1]);
    for (uint32_t y = 0; y < dh; ++y) {
        uint32_t y0 = (uint32_t)((uint64_t)y * sh / dh), y1 = (uint32_t)((uint64_t)(y + 1) * sh / dh);
        for (uint32_t x = 0; x < dw; ++x) {
            uint32_t x0 = (uint32_t)((uint64_t)x * sw / dw), x1 = (uint32_t)((uint64_t)(x + 1) * sw / dw);
            float sum[4] = {0, 0, 0, 0};
            for (uint32_t yy = y0; yy < y1; ++yy) {
                const uint8_t *row = src + ((size_t)yy * sw + x0) * 4;
                for (uint32_t xx = x0; xx < x1; ++xx, row += 4) {
                    for (int c = 0; c < 3; ++c)
                        sum[c] += lut[row[c]];
                    sum[3] += (float)row[3];
                }
            }
            float n = (float)((y1 - y0) * (x1 - x0));
            uint8_t *out = dst + ((size_t)y * dw + x) * 4;
            for (int c = 0; c < 3; ++c) {
                /* the nearest byte: how many midpoints lie below the mean */
                float v = sum[c] / n;
                int lo = 0, hi = 255;
                while (lo < hi) {
                    int m = (lo + hi) / 2;
                    if (mid[m] < v)
                        lo = m + 1;
                    else
                        hi = m;
                }
                out[c] = (uint8_t)lo;
            }
            out[3] = (uint8_t)(sum[3] / n + 0.5f);
        }
    }
    return dst;
}

/* Sets a scene image's flag in one of the per-image flag arrays (counted
 * once however many textures hold the image). */
static void mark_image(uint8_t **flags, uint32_t *cap, uint32_t *count, uint32_t image, uint32_t image_count)
{
    if (image >= *cap) {
        uint8_t *p = realloc(*flags, image_count);
        if (!p)
            return; /* only the count suffers */
        memset(p + *cap, 0, image_count - *cap);
        *flags = p;
        *cap = image_count;
    }
    if (!(*flags)[image]) {
        (*flags)[image] = 1;
        (*count)++;
    }
}

/* Marks a scene image as stored downscaled. */
static void mark_downscaled(mvr_gpu_scene *g, uint32_t image, uint32_t image_count)
{
    mark_image(&g->downscaled, &g->downscaled_cap, &g->downscaled_count, image, image_count);
}

static void forget_downscaled(mvr_gpu_scene *g)
{
    if (g->downscaled)
        memset(g->downscaled, 0, g->downscaled_cap);
    g->downscaled_count = 0;
}

/* The GL's internal format of a block format in a color space. EAC R11 /
 * RG11 have no sRGB form: sampled as stored. The ASTC enums of both spaces
 * run in mvr_image_format's order of block sizes (KHR_texture_compression_astc_ldr). */
static GLenum block_internal_format(mvr_image_format f, bool srgb)
{
    switch (f) {
    case MVR_IMAGE_FORMAT_RGBA8: return srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8;
    case MVR_IMAGE_FORMAT_ETC2_RGB8: return srgb ? GL_COMPRESSED_SRGB8_ETC2 : GL_COMPRESSED_RGB8_ETC2;
    case MVR_IMAGE_FORMAT_ETC2_RGB8_A1:
        return srgb ? GL_COMPRESSED_SRGB8_PUNCHTHROUGH_ALPHA1_ETC2 : GL_COMPRESSED_RGB8_PUNCHTHROUGH_ALPHA1_ETC2;
    case MVR_IMAGE_FORMAT_ETC2_RGBA8: return srgb ? GL_COMPRESSED_SRGB8_ALPHA8_ETC2_EAC : GL_COMPRESSED_RGBA8_ETC2_EAC;
    case MVR_IMAGE_FORMAT_EAC_R11: return GL_COMPRESSED_R11_EAC;
    case MVR_IMAGE_FORMAT_EAC_RG11: return GL_COMPRESSED_RG11_EAC;
    default: break;
    }
    GLenum astc = (GLenum)(f - MVR_IMAGE_FORMAT_ASTC_4x4);
    return (srgb ? GL_COMPRESSED_SRGB8_ALPHA8_ASTC_4x4_KHR : GL_COMPRESSED_RGBA_ASTC_4x4_KHR) + astc;
}

/* Whether a renderer's GL samples a format, and why not (for messages). */
static const char *unsampleable_reason(const mvr_renderer *r, mvr_image_format f)
{
    if (r->sampleable_formats & (1u << f))
        return NULL;
    bool astc = f >= MVR_IMAGE_FORMAT_ASTC_4x4;
    bool has = astc ? r->ctx->caps.ext.astc_ldr : r->ctx->caps.ext.etc2;
    if (has)
        return "disabled by the renderer's overrides.disable_image_formats";
    return astc ? "no GL_KHR_texture_compression_astc_ldr"
                : "no ETC2 / EAC (OpenGL ES 3.0, desktop GL 4.3 or GL_ARB_ES3_compatibility)";
}

/* The images the materials sample in block formats: counted (the stats)
 * where the GL samples them (uploaded as blocks on either material path,
 * also where identical blocks share one array layer); where it cannot, one
 * warning per image naming it and why, counted too: the batch plan and
 * texture_for give their roles the neutral value. */
static void note_formats(mvr_renderer *r, const mvr_scene *s)
{
    mvr_gpu_scene *g = &r->gpu;
    if (g->unsampleable)
        memset(g->unsampleable, 0, g->unsampleable_cap);
    g->unsampleable_count = 0;
    if (g->compressed)
        memset(g->compressed, 0, g->compressed_cap);
    g->compressed_count = 0;
    for (uint32_t m = 0; m < s->material_count; ++m) {
        const mvr_material_desc *md = &s->materials[m].desc;
        for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
            if (!mvr_material_samples_role(md, role))
                continue;
            uint32_t image = mvr_material_role(md, role)->image.id - 1;
            const scene_image *img = &s->images[image];
            const char *why = unsampleable_reason(r, img->format);
            if (!why && img->format != MVR_IMAGE_FORMAT_RGBA8)
                mark_image(&g->compressed, &g->compressed_cap, &g->compressed_count, image, s->image_count);
            if (!why || (image < g->unsampleable_cap && g->unsampleable[image]))
                continue;
            mark_image(&g->unsampleable, &g->unsampleable_cap, &g->unsampleable_count, image, s->image_count);
            mvr_log(&r->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                    "mvr: image %u%s%s%s (%ux%u %s) cannot be sampled by this GL (%s): its textures (the %s "
                    "texture of material %u, and any other) use the role's neutral value",
                    image + 1, img->name[0] ? " '" : "", img->name, img->name[0] ? "'" : "", img->width, img->height,
                    mvr_image_format_name(img->format), why, mvr_role_name(role), m);
        }
    }
}

/* One texture to make: a 2D texture of one image (the per-material path),
 * or a 2D array of a batch plan group (the array path; MVR_NO_INDEX layers
 * are white). Every layer has the size width x height. */
typedef struct texture_job {
    GLenum target;               /* GL_TEXTURE_2D or GL_TEXTURE_2D_ARRAY */
    bool srgb, mips;             /* mips: RGBA8, a generated full chain */
    mvr_image_format format;     /* RGBA8, or the block format of every layer */
    uint32_t levels;             /* block formats: the levels uploaded (the images' first ones) */
    uint32_t role;               /* the neutral value of MVR_NO_INDEX layers (mvr_role_neutral) */
    uint32_t width, height;
    const uint32_t *layer_images;
    uint32_t layer_count;
    char what[200];              /* "texture array of image 3 'wall', ..." for messages */
} texture_job;

static void describe_images(char *dst, size_t size, const char *prefix, const mvr_scene *s, const uint32_t *images,
                            uint32_t count)
{
    mvr_str_copy(dst, size, prefix);
    uint32_t named = 0;
    for (uint32_t k = 0; k < count; ++k) {
        if (images[k] == MVR_NO_INDEX)
            continue;
        size_t used = strlen(dst);
        if (named == 4) {
            mvr_str_format(dst + used, size - used, ", ...");
            break;
        }
        const scene_image *img = &s->images[images[k]];
        /* image ids as mvr_scene_add_image returned them (index + 1) */
        mvr_str_format(dst + used, size - used, "%s%u%s%s%s", named ? ", " : " ", images[k] + 1,
                       img->name[0] ? " '" : "", img->name, img->name[0] ? "'" : "");
        named++;
    }
}

/* Drains GL errors; true when there were any (oom: one was GL_OUT_OF_MEMORY). */
static bool take_errors(const mvr_gl_api_table *gl, char *names, size_t size, bool *oom)
{
    size_t used = 0;
    int count = 0;
    names[0] = '\0';
    *oom = false;
    for (GLenum e; count < 16 && (e = gl->GetError()) != GL_NO_ERROR; ++count) {
        mvr_str_format(names + used, size - used, "%s%s", count ? ", " : "", mvr_gl_error_name(e));
        used = strlen(names);
        *oom |= e == GL_OUT_OF_MEMORY;
    }
    return count > 0;
}

/* Storage and pixels of one size; false (with the GL's errors in why) when
 * the GL refused. Out of host memory is an error of its own (*res). Block
 * formats start at their level `base` (w x h, the image's size at that
 * level); RGBA8 at w x h (downscaled when smaller than the job's). */
static bool try_texture(mvr_renderer *r, const mvr_scene *s, const texture_job *job, uint32_t base, uint32_t w,
                        uint32_t h, GLuint *out, char *why, size_t why_size, bool *oom, mvr_result *res)
{
    const mvr_gl_api_table *gl = r->gl;
    bool blocks = job->format != MVR_IMAGE_FORMAT_RGBA8;
    GLenum format = block_internal_format(job->format, job->srgb);
    GLsizei levels = blocks ? (GLsizei)(job->levels - base) : job->mips ? (GLsizei)mvr_mip_levels(w, h) : 1;
    bool array = job->target == GL_TEXTURE_2D_ARRAY;
    *res = MVR_OK;
    gl->GenTextures(1, out);
    mvr_state_texture(&r->state, 0, job->target, *out);
    if (array)
        gl->TexStorage3D(job->target, levels, format, (GLsizei)w, (GLsizei)h, (GLsizei)job->layer_count);
    else
        gl->TexStorage2D(job->target, levels, format, (GLsizei)w, (GLsizei)h);
    if (take_errors(gl, why, why_size, oom))
        return false;
    if (blocks) {
        /* The blocks as given, level by level: never decoded, never
         * mip-generated (the GL cannot encode blocks). A sampler that reads
         * mips on an image with fewer levels than the full chain reads those
         * it has: the storage holds exactly them (an immutable texture is
         * complete with its own levels), and GL_TEXTURE_MAX_LEVEL says so
         * too, levels - 1. */
        for (uint32_t layer = 0; layer < job->layer_count; ++layer) {
            const scene_image *img = &s->images[job->layer_images[layer]];
            for (GLsizei k = 0; k < levels; ++k) {
                uint32_t lv = base + (uint32_t)k;
                GLsizei lw = (GLsizei)(img->width >> lv ? img->width >> lv : 1);
                GLsizei lh = (GLsizei)(img->height >> lv ? img->height >> lv : 1);
                const uint8_t *data = img->blocks + img->level_offset[lv];
                GLsizei size = (GLsizei)img->level_size[lv];
                if (array)
                    gl->CompressedTexSubImage3D(job->target, k, 0, 0, (GLint)layer, lw, lh, 1, format, size, data);
                else
                    gl->CompressedTexSubImage2D(job->target, k, 0, 0, lw, lh, format, size, data);
                r->upload_bytes += (uint64_t)size;
            }
        }
        gl->TexParameteri(job->target, GL_TEXTURE_MAX_LEVEL, levels - 1);
        return !take_errors(gl, why, why_size, oom);
    }
    bool scaled = w != job->width || h != job->height;
    uint8_t *neutral = NULL;
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (uint32_t layer = 0; layer < job->layer_count && *res == MVR_OK; ++layer) {
        uint32_t image = job->layer_images[layer];
        const uint8_t *pixels = NULL;
        uint8_t *scratch = NULL;
        if (image == MVR_NO_INDEX) {
            if (!neutral && (neutral = malloc((size_t)w * h * 4)) != NULL) {
                uint8_t texel[4];
                mvr_role_neutral(job->role, texel);
                for (size_t i = 0; i < (size_t)w * h; ++i)
                    memcpy(neutral + i * 4, texel, 4);
            }
            pixels = neutral;
        } else if (scaled) {
            const scene_image *img = &s->images[image];
            pixels = scratch = downscale_rgba8(img->rgba, img->width, img->height, w, h, job->srgb);
        } else {
            pixels = s->images[image].rgba;
        }
        if (!pixels) {
            *res = mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "%s: out of memory (%ux%u pixels)", job->what, w, h);
            break;
        }
        /* rows as stored, top first: glTF's uv (0, 0) is the image's top-left */
        if (array)
            gl->TexSubImage3D(job->target, 0, 0, 0, (GLint)layer, (GLsizei)w, (GLsizei)h, 1, GL_RGBA,
                              GL_UNSIGNED_BYTE, pixels);
        else
            gl->TexSubImage2D(job->target, 0, 0, 0, (GLsizei)w, (GLsizei)h, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
        free(scratch);
        r->upload_bytes += (uint64_t)w * h * 4;
    }
    free(neutral);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (*res == MVR_OK && levels > 1)
        gl->GenerateMipmap(job->target);
    /* a GL may allocate lazily: uploads and mips can fail too */
    return !take_errors(gl, why, why_size, oom) && *res == MVR_OK;
}

/* "srgb8_alpha8", "rgba8", "etc2_rgb8 (sRGB)", ... */
static void describe_format(char *dst, size_t size, const texture_job *job)
{
    if (job->format == MVR_IMAGE_FORMAT_RGBA8)
        mvr_str_copy(dst, size, job->srgb ? "srgb8_alpha8" : "rgba8");
    else
        mvr_str_format(dst, size, "%s%s", mvr_image_format_name(job->format), job->srgb ? " sRGB" : "");
}

/* Makes a job's texture: at its size, or, where the GL cannot hold that
 * (over GL_MAX_TEXTURE_SIZE, or GL_OUT_OF_MEMORY), smaller until it can when
 * the renderer's policy is to downscale: RGBA8 halved, block formats started
 * at their next level (blocks cannot be resampled without decoding them; an
 * image without a smaller level is refused). One function for both material
 * paths, so they decide alike. */
static mvr_result make_texture(mvr_renderer *r, const mvr_scene *s, const texture_job *job, GLuint *out)
{
    uint32_t max = (uint32_t)r->ctx->caps.limits.max_texture_size;
    bool blocks = job->format != MVR_IMAGE_FORMAT_RGBA8;
    uint32_t w = job->width, h = job->height, base = 0;
    char first_why[128] = "", fmt[48];
    describe_format(fmt, sizeof fmt, job);
    *out = 0;
    for (;;) {
        char why[128] = "";
        bool oom = false;
        mvr_result res = MVR_OK;
        if (w > max || h > max) {
            mvr_str_format(why, sizeof why, "over GL_MAX_TEXTURE_SIZE %u", max);
            res = MVR_ERROR_UNSUPPORTED;
        } else if (try_texture(r, s, job, base, w, h, out, why, sizeof why, &oom, &res)) {
            break;
        } else {
            mvr_gl_delete(r, MVR_GL_TEXTURE, out);
            if (res != MVR_OK) /* out of host memory: recorded */
                return res;
            res = oom ? MVR_ERROR_OUT_OF_MEMORY : MVR_ERROR_GL;
        }
        if (!first_why[0])
            mvr_str_copy(first_why, sizeof first_why, why);
        /* other GL errors are not about size: shrinking would not help */
        bool smaller = blocks ? base + 1 < job->levels : (w > 1 || h > 1);
        bool halve = res != MVR_ERROR_GL && r->oversized_images == MVR_OVERSIZED_IMAGE_DOWNSCALE && smaller;
        if (!halve)
            return mvr_gl_fail(r, res, "%s (%ux%u %s, %u mips): %s%s", job->what, w, h, fmt,
                               blocks ? job->levels - base : job->mips ? mvr_mip_levels(w, h) : 1u, why,
                               res == MVR_ERROR_GL ? ""
                               : r->oversized_images == MVR_OVERSIZED_IMAGE_REFUSE
                                   ? " (the renderer's oversized_images is refuse)"
                               : blocks ? " (block-compressed: no smaller mip level to start from)"
                                        : " (even at 1x1)");
        if (blocks) {
            base++;
            w = job->width >> base ? job->width >> base : 1;
            h = job->height >> base ? job->height >> base : 1;
        } else {
            w = w > 1 ? w / 2 : 1;
            h = h > 1 ? h / 2 : 1;
        }
    }
    if (w != job->width || h != job->height) {
        mvr_log(&r->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                "mvr: %s: %ux%u (%s, %u mips, %u layers) does not fit this GL (%s): %s %ux%u", job->what,
                job->width, job->height, fmt, blocks ? job->levels : job->mips ? mvr_mip_levels(job->width, job->height) : 1u,
                job->layer_count, first_why, blocks ? "starts at its smaller level" : "downscaled to", w, h);
        for (uint32_t k = 0; k < job->layer_count; ++k)
            if (job->layer_images[k] != MVR_NO_INDEX)
                mark_downscaled(&r->gpu, job->layer_images[k], s->image_count);
    }
    return MVR_OK;
}

/* The GL texture of an image in a role's color space, uploaded on first
 * use: RGBA8 with a mip chain only where a sampler that reads it needs one;
 * block formats with their own levels (where a sampler reads mips; else
 * level 0); a format the GL cannot sample: a 1 x 1 texture of the role's
 * neutral value (note_formats warned). */
static mvr_result texture_for(mvr_renderer *r, const mvr_scene *s, uint32_t image, uint32_t role, GLuint *out)
{
    mvr_gpu_scene *g = &r->gpu;
    bool srgb = mvr_role_is_srgb(role);
    const scene_image *img = &s->images[image];
    bool neutral = !(r->sampleable_formats & (1u << img->format));
    uint8_t texel[4];
    mvr_role_neutral(role, texel);
    /* neutral textures are shared by the roles of one neutral value */
    uint32_t key = neutral ? MVR_NO_INDEX - (uint32_t)(texel[0] != 255 ? 1 : texel[1] != 255 ? 2 : 0) : image;
    for (uint32_t i = 0; i < g->texture_count; ++i)
        if (g->textures[i].image == key && g->textures[i].srgb == srgb) {
            *out = g->textures[i].texture;
            return MVR_OK;
        }
    if (g->texture_count == g->texture_cap) {
        uint32_t cap = g->texture_cap ? g->texture_cap * 2 : 16;
        mvr_gpu_texture *p = realloc(g->textures, cap * sizeof *p);
        if (!p)
            return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "textures: out of memory");
        g->textures = p;
        g->texture_cap = cap;
    }
    static const uint32_t none = MVR_NO_INDEX;
    bool mips = image_needs_mipmaps(s, image);
    texture_job job = {.target = GL_TEXTURE_2D, .srgb = srgb, .role = role, .layer_images = &image, .layer_count = 1};
    if (neutral) {
        job.width = job.height = 1;
        job.layer_images = &none;
        mvr_str_format(job.what, sizeof job.what, "neutral texture of the %s role", mvr_role_name(role));
    } else {
        job.format = img->format;
        job.mips = mips && img->format == MVR_IMAGE_FORMAT_RGBA8;
        job.levels = mips ? img->levels : 1;
        job.width = img->width;
        job.height = img->height;
        describe_images(job.what, sizeof job.what, srgb ? "texture (sRGB) of image" : "texture of image", s, &image, 1);
    }
    GLuint t = 0;
    mvr_result res = make_texture(r, s, &job, &t);
    if (res != MVR_OK)
        return res;
    g->textures[g->texture_count].image = key;
    g->textures[g->texture_count].srgb = srgb;
    g->textures[g->texture_count++].texture = t;
    *out = t;
    return MVR_OK;
}

/* Array path: one GL_TEXTURE_2D_ARRAY per plan group, layers in plan order,
 * white for a group's neutral layer; mips generated for the whole array. */
static mvr_result upload_arrays(mvr_renderer *r, const mvr_scene *s)
{
    mvr_gpu_scene *g = &r->gpu;
    mvr_result res = mvr_batch_plan_build_for(&g->plan, s, (uint32_t)r->ctx->caps.limits.max_array_texture_layers,
                                              r->sampleable_formats);
    if (res != MVR_OK)
        return mvr_gl_fail(r, res, "batch plan: out of memory");
    for (uint32_t n = 0; n < g->plan.note_count; ++n)
        mvr_log(&r->logger, MVR_LOG_DEBUG, MVR_LOG_ID_GENERAL, "mvr: batch plan: %s", g->plan.notes[n]);
    uint32_t count = g->plan.group_count;
    g->group_textures = calloc(count ? count : 1, sizeof *g->group_textures);
    g->group_samplers = calloc(count ? count : 1, sizeof *g->group_samplers);
    if (!g->group_textures || !g->group_samplers)
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "texture arrays: out of memory");
    for (uint32_t k = 0; k < count; ++k) {
        const mvr_texture_group *grp = &g->plan.groups[k];
        bool blocks = grp->format != MVR_IMAGE_FORMAT_RGBA8;
        texture_job job = {.target = GL_TEXTURE_2D_ARRAY, .srgb = grp->srgb, .mips = !blocks && grp->levels > 1,
                           .format = grp->format, .levels = grp->levels, .role = grp->role,
                           .width = grp->width, .height = grp->height, .layer_images = grp->layer_images,
                           .layer_count = grp->layer_count};
        char prefix[64];
        mvr_str_format(prefix, sizeof prefix, "%s texture array %u (%u layers) of image%s", mvr_role_name(grp->role), k,
                       grp->layer_count, grp->layer_count - (grp->neutral_layer != MVR_NO_INDEX) > 1 ? "s" : "");
        describe_images(job.what, sizeof job.what, prefix, s, grp->layer_images, grp->layer_count);
        res = make_texture(r, s, &job, &g->group_textures[k]);
        if (res != MVR_OK)
            return res;
        g->group_samplers[k] = sampler_for(r, &grp->sampler);
        if (!g->group_samplers[k])
            return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "samplers: out of memory");
    }
    return MVR_OK;
}

static void release_arrays(mvr_renderer *r)
{
    mvr_gpu_scene *g = &r->gpu;
    for (uint32_t k = 0; g->group_textures && k < g->plan.group_count; ++k)
        mvr_gl_delete(r, MVR_GL_TEXTURE, &g->group_textures[k]);
    free(g->group_textures);
    free(g->group_samplers);
    g->group_textures = g->group_samplers = NULL;
    mvr_batch_plan_free(&g->plan);
    /* the downscaled flags stay: the per-material textures may hold the
     * same images downscaled (forgotten with the geometry, where both go) */
}

static void release_geometry(mvr_renderer *r)
{
    mvr_gpu_scene *g = &r->gpu;
    mvr_gpu_primitives_release(r);
    release_arrays(r);
    for (uint32_t i = 0; i < g->texture_count; ++i)
        mvr_gl_delete(r, MVR_GL_TEXTURE, &g->textures[i].texture);
    g->texture_count = 0;
    forget_downscaled(g);
}


static mvr_result upload_geometry(mvr_renderer *r, const mvr_scene *s)
{
    release_geometry(r);
    return mvr_gpu_primitives_upload(r, s);
}

/* The material slots of a new material version: bindings (filled by the
 * per-material representation) and the page layout both representations share. */
static mvr_result layout_materials(mvr_renderer *r, const mvr_scene *s)
{
    mvr_gpu_scene *g = &r->gpu;
    uint32_t slots = s->material_count + 1; /* + the default material */
    free(g->materials);
    g->materials = calloc(slots, sizeof *g->materials);
    if (!g->materials)
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "materials: out of memory");
    g->material_count = slots;
    uint32_t cap = r->material_capacity;
    g->material_pages = (slots + cap - 1) / cap;
    GLsizeiptr page_bytes = (GLsizeiptr)cap * MVR_MATERIAL_BLOCK_SIZE;
    GLsizeiptr align = (GLsizeiptr)r->ubo_alignment;
    g->material_page_stride = (page_bytes + align - 1) / align * align;
    return MVR_OK;
}

/* One representation's material blocks (arrays: with each role's layer in
 * its group's array; else the per-material textures and samplers too). */
static mvr_result upload_materials(mvr_renderer *r, const mvr_scene *s, bool arrays)
{
    mvr_gpu_scene *g = &r->gpu;
    const mvr_gl_api_table *gl = r->gl;
    uint32_t slots = g->material_count, cap = r->material_capacity;
    size_t total = (size_t)g->material_page_stride * g->material_pages;
    uint8_t *data = calloc(1, total);
    if (!data)
        return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "materials: out of memory");
    for (uint32_t i = 0; i < slots; ++i) {
        const mvr_material_desc *m = mvr_scene_material(s, i < s->material_count ? i : MVR_NO_INDEX);
        size_t at = (size_t)(i / cap) * (size_t)g->material_page_stride + (size_t)(i % cap) * MVR_MATERIAL_BLOCK_SIZE;
        mvr_material_pack(m, arrays ? g->plan.materials[i].layer : NULL, data + at);
        if (arrays)
            continue;
        for (uint32_t k = 0; k < MVR_ROLE_COUNT; ++k) {
            if (!mvr_material_samples_role(m, k))
                continue;
            const mvr_texture_ref *t = mvr_material_role(m, k);
            mvr_result res = texture_for(r, s, t->image.id - 1, k, &g->materials[i].textures[k]);
            if (res != MVR_OK) {
                free(data);
                return res;
            }
            g->materials[i].samplers[k] = sampler_for(r, &t->sampler);
            if (!g->materials[i].samplers[k]) {
                free(data);
                return mvr_gl_fail(r, MVR_ERROR_OUT_OF_MEMORY, "samplers: out of memory");
            }
        }
    }
    GLuint *ubo = &g->material_ubos[arrays];
    if (!*ubo)
        gl->GenBuffers(1, ubo);
    gl->BindBuffer(GL_UNIFORM_BUFFER, *ubo);
    gl->BufferData(GL_UNIFORM_BUFFER, (GLsizeiptr)total, data, GL_STATIC_DRAW);
    /* BufferData gives the name new storage; a cached range of it is stale */
    mvr_state_forget_buffer(&r->state, *ubo);
    r->upload_bytes += total;
    free(data);
    mvr_result res = mvr_gl_check_alloc(r, "material buffer (%u materials, %zu bytes)", slots, total);
    if (res != MVR_OK)
        mvr_gl_delete(r, MVR_GL_BUFFER, ubo);
    return res;
}

/* Releases one representation of the materials (the GL objects; the
 * downscaled-image flags of the arrays go with them). */
static void release_representation(mvr_renderer *r, bool arrays)
{
    mvr_gpu_scene *g = &r->gpu;
    if (arrays) {
        release_arrays(r);
    } else {
        for (uint32_t i = 0; i < g->texture_count; ++i)
            mvr_gl_delete(r, MVR_GL_TEXTURE, &g->textures[i].texture);
        g->texture_count = 0;
        if (g->materials)
            memset(g->materials, 0, g->material_count * sizeof *g->materials);
    }
    mvr_gl_delete(r, MVR_GL_BUFFER, &g->material_ubos[arrays]);
    g->resident[arrays] = false;
}

mvr_result mvr_gpu_scene_sync(mvr_renderer *r, const mvr_scene *s, bool keep_both)
{
    mvr_gpu_scene *g = &r->gpu;
    bool same_scene = g->scene == s && g->scene_serial == mvr_scene_serial(s);
    if (!same_scene) {
        mvr_gpu_scene_release(r);
        g->scene = s;
        g->scene_serial = mvr_scene_serial(s);
    }
    mvr_result res = MVR_OK;
    bool arrays = r->material_path == MVR_MATERIAL_PATH_ARRAYS;
    bool geometry = !same_scene || g->geometry_version != s->geometry_version;
    bool materials = geometry || g->material_version != s->material_version;
    if (geometry) {
        res = upload_geometry(r, s);
        if (res == MVR_OK)
            res = mvr_skinning_sync_scene(r, s);
        if (res != MVR_OK)
            return res;
        g->geometry_version = s->geometry_version;
    }
    if (materials) {
        note_formats(r, s);
        /* both representations describe the old materials: the arrays
         * (their plan depends on the materials) are rebuilt; the
         * per-material textures are not (texture_for finds them again by
         * image), only their bindings and blocks */
        if (g->resident[1])
            release_representation(r, true);
        g->resident[0] = false;
        res = layout_materials(r, s);
        if (res != MVR_OK)
            return res;
        g->material_version = s->material_version;
    }
    if (!g->resident[arrays]) {
        /* the plan depends on images and materials: built with the arrays */
        if (arrays) {
            release_arrays(r);
            res = upload_arrays(r, s);
        }
        if (res == MVR_OK)
            res = upload_materials(r, s, arrays);
        if (res != MVR_OK)
            return res;
        g->resident[arrays] = true;
    }
    /* the other representation, unless auto's tuner is measuring both
     * (per-material textures may be held while not resident: see above) */
    if (!keep_both && (g->resident[!arrays] || (arrays && g->texture_count)))
        release_representation(r, !arrays);
    g->arrays = arrays;
    g->material_ubo = g->material_ubos[arrays];
    /* each allocation was checked; the rest (attribute setup) in debug builds */
    res = mvr_gl_check(r->ctx, "scene upload", false);
    return res == MVR_OK ? MVR_OK : mvr_gl_fail(r, res, "%s", mvr_context_last_error(r->ctx));
}

void mvr_gpu_scene_release(mvr_renderer *r)
{
    mvr_gpu_scene *g = &r->gpu;
    mvr_skinning_release(r);
    release_geometry(r);
    free(g->textures);
    for (uint32_t i = 0; i < g->sampler_count; ++i)
        mvr_gl_delete(r, MVR_GL_SAMPLER, &g->samplers[i].sampler);
    free(g->samplers);
    free(g->materials);
    mvr_gl_delete(r, MVR_GL_BUFFER, &g->material_ubos[0]);
    mvr_gl_delete(r, MVR_GL_BUFFER, &g->material_ubos[1]);
    free(g->downscaled);
    free(g->compressed);
    free(g->unsampleable);
    memset(g, 0, sizeof *g);
}
