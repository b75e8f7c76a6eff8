/* Materials: texture roles, validation on the way into a scene, the std140 block. */
#include <math.h>
#include <string.h>

#include "frame.h"
#include "material.h"
#include "scene_internal.h"
#include "shader_gen.h"

/* ---- texture roles */

typedef struct role_info {
    const char *name;
    const char *sampler;         /* shaders/surface.glsl, material_*.glsl */
    bool srgb;
    uint32_t feature;
} role_info;

static const role_info roles[MVR_ROLE_COUNT] = {
    [MVR_ROLE_BASE_COLOR] = {"base color", "mvr_base_color_tex", true, MVR_FEATURE_BASE_COLOR_TEX},
    [MVR_ROLE_METAL_ROUGH] = {"metallic-roughness", "mvr_metal_rough_tex", false, MVR_FEATURE_METAL_ROUGH_TEX},
    [MVR_ROLE_NORMAL] = {"normal", "mvr_normal_tex", false, MVR_FEATURE_NORMAL_TEX},
    [MVR_ROLE_OCCLUSION] = {"occlusion", "mvr_occlusion_tex", false, MVR_FEATURE_OCCLUSION_TEX},
    [MVR_ROLE_EMISSIVE] = {"emissive", "mvr_emissive_tex", true, MVR_FEATURE_EMISSIVE_TEX},
    [MVR_ROLE_CLEARCOAT] = {"clearcoat", "mvr_clearcoat_tex", false, MVR_FEATURE_CLEARCOAT},
    [MVR_ROLE_CLEARCOAT_ROUGHNESS] = {"clearcoat roughness", "mvr_clearcoat_roughness_tex", false,
                                      MVR_FEATURE_CLEARCOAT},
    [MVR_ROLE_CLEARCOAT_NORMAL] = {"clearcoat normal", "mvr_clearcoat_normal_tex", false, MVR_FEATURE_CLEARCOAT},
    [MVR_ROLE_SHEEN_COLOR] = {"sheen color", "mvr_sheen_color_tex", true, MVR_FEATURE_SHEEN},
    [MVR_ROLE_SHEEN_ROUGHNESS] = {"sheen roughness", "mvr_sheen_roughness_tex", false, MVR_FEATURE_SHEEN},
    [MVR_ROLE_SPECULAR] = {"specular", "mvr_specular_tex", false, MVR_FEATURE_SPECULAR},
    [MVR_ROLE_SPECULAR_COLOR] = {"specular color", "mvr_specular_color_tex", true, MVR_FEATURE_SPECULAR},
    [MVR_ROLE_TRANSMISSION] = {"transmission", "mvr_transmission_tex", false, MVR_FEATURE_TRANSMISSION},
    [MVR_ROLE_THICKNESS] = {"thickness", "mvr_thickness_tex", false, MVR_FEATURE_TRANSMISSION},
    [MVR_ROLE_IRIDESCENCE] = {"iridescence", "mvr_iridescence_tex", false, MVR_FEATURE_IRIDESCENCE},
    [MVR_ROLE_IRIDESCENCE_THICKNESS] = {"iridescence thickness", "mvr_iridescence_thickness_tex", false,
                                        MVR_FEATURE_IRIDESCENCE},
    [MVR_ROLE_ANISOTROPY] = {"anisotropy", "mvr_anisotropy_tex", false, MVR_FEATURE_ANISOTROPY},
    /* RGB specular color (sRGB), A glossiness: an sRGB format leaves alpha linear */
    [MVR_ROLE_SPEC_GLOSS] = {"specular-glossiness", "mvr_spec_gloss_tex", true, MVR_FEATURE_SPEC_GLOSS},
};

const mvr_texture_ref *mvr_material_role(const mvr_material_desc *m, uint32_t role)
{
    switch ((mvr_texture_role)role) {
    case MVR_ROLE_BASE_COLOR: return &m->base_color;
    case MVR_ROLE_METAL_ROUGH: return &m->metallic_roughness;
    case MVR_ROLE_NORMAL: return &m->normal;
    case MVR_ROLE_OCCLUSION: return &m->occlusion;
    case MVR_ROLE_EMISSIVE: return &m->emissive;
    case MVR_ROLE_CLEARCOAT: return &m->clearcoat.texture;
    case MVR_ROLE_CLEARCOAT_ROUGHNESS: return &m->clearcoat.roughness_texture;
    case MVR_ROLE_CLEARCOAT_NORMAL: return &m->clearcoat.normal_texture;
    case MVR_ROLE_SHEEN_COLOR: return &m->sheen.color_texture;
    case MVR_ROLE_SHEEN_ROUGHNESS: return &m->sheen.roughness_texture;
    case MVR_ROLE_SPECULAR: return &m->specular.texture;
    case MVR_ROLE_SPECULAR_COLOR: return &m->specular.color_texture;
    case MVR_ROLE_TRANSMISSION: return &m->transmission.texture;
    case MVR_ROLE_THICKNESS: return &m->volume.thickness_texture;
    case MVR_ROLE_IRIDESCENCE: return &m->iridescence.texture;
    case MVR_ROLE_IRIDESCENCE_THICKNESS: return &m->iridescence.thickness_texture;
    case MVR_ROLE_ANISOTROPY: return &m->anisotropy.texture;
    case MVR_ROLE_SPEC_GLOSS: return &m->spec_gloss.texture;
    case MVR_ROLE_COUNT: break;
    }
    return &m->base_color;
}

const char *mvr_role_name(uint32_t role)
{
    return role < MVR_ROLE_COUNT ? roles[role].name : "?";
}

const char *mvr_role_sampler(uint32_t role)
{
    return role < MVR_ROLE_COUNT ? roles[role].sampler : NULL;
}

bool mvr_role_is_srgb(uint32_t role)
{
    return role < MVR_ROLE_COUNT && roles[role].srgb;
}

uint32_t mvr_role_feature(uint32_t role)
{
    return role < MVR_ROLE_COUNT ? roles[role].feature : 0u;
}

uint32_t mvr_material_extension_features(const mvr_material_desc *m)
{
    uint32_t f = 0;
    /* the extensions' code only where a material departs from glTF's core
     * values (ior 1.5, no specular extension, no clearcoat) */
    if ((m->ior != 1.5f && m->ior != 0.0f) || m->specular.enabled) /* 0: not given, 1.5 */
        f |= MVR_FEATURE_SPECULAR;
    if (m->clearcoat.factor > 0.0f)
        f |= MVR_FEATURE_CLEARCOAT;
    /* spec-gloss is the specular extension's dielectric with F0 from its
     * specular color, no metal and its own texture */
    if (m->spec_gloss.enabled)
        f |= MVR_FEATURE_SPEC_GLOSS | MVR_FEATURE_SPECULAR;
    /* transmission (with its volume and dispersion) replaces the
     * dielectric's diffuse lobe, which the specular extension's code draws */
    if (m->transmission.factor > 0.0f)
        f |= MVR_FEATURE_TRANSMISSION | MVR_FEATURE_SPECULAR;
    /* a stretched specular lobe (strength 0 is the isotropic one) */
    if (m->anisotropy.strength > 0.0f)
        f |= MVR_FEATURE_ANISOTROPY | MVR_FEATURE_SPECULAR;
    /* a thin film over the dielectric and the metal (a film of thickness 0
     * at most, without a texture to thicken it, is none) */
    if (m->iridescence.factor > 0.0f &&
        (m->iridescence.thickness_maximum > 0.0f || m->iridescence.thickness_texture.image.id))
        f |= MVR_FEATURE_IRIDESCENCE | MVR_FEATURE_SPECULAR;
    /* KHR_materials_sheen: a black sheen color is no sheen (the extension's
     * default), whatever its textures say (they multiply the factor) */
    if (m->sheen.color_factor[0] > 0.0f || m->sheen.color_factor[1] > 0.0f || m->sheen.color_factor[2] > 0.0f)
        f |= MVR_FEATURE_SHEEN;
    return f;
}

_Static_assert(MVR_ROLE_COUNT <= MVR_MATERIAL_OCCLUSION_IN_METAL_ROUGH_BIT,
               "the roles' has-a-texture bits of uv.w stay below the occlusion-in-metal-rough bit");

bool mvr_texture_refs_fetch_alike(const mvr_texture_ref *a, const mvr_texture_ref *b)
{
    const mvr_texture_transform *ta = &a->transform, *tb = &b->transform;
    bool same_transform = ta->enabled == tb->enabled &&
                          (!ta->enabled || (ta->offset[0] == tb->offset[0] && ta->offset[1] == tb->offset[1] &&
                                            ta->rotation == tb->rotation && ta->scale[0] == tb->scale[0] &&
                                            ta->scale[1] == tb->scale[1]));
    return a->image.id == b->image.id && a->texcoord == b->texcoord && same_transform &&
           a->sampler.mag_filter == b->sampler.mag_filter && a->sampler.min_filter == b->sampler.min_filter &&
           a->sampler.wrap_s == b->sampler.wrap_s && a->sampler.wrap_t == b->sampler.wrap_t;
}

bool mvr_material_occlusion_in_metal_rough(const mvr_material_desc *m)
{
    return m->occlusion.image.id && !m->spec_gloss.enabled &&
           mvr_texture_refs_fetch_alike(&m->occlusion, &m->metallic_roughness);
}

bool mvr_material_samples_role(const mvr_material_desc *m, uint32_t role)
{
    if (role >= MVR_ROLE_COUNT || !mvr_material_role(m, role)->image.id)
        return false;
    if (role == MVR_ROLE_METAL_ROUGH && m->spec_gloss.enabled)
        return false; /* spec-gloss has no metal and its own roughness */
    if (role == MVR_ROLE_OCCLUSION && mvr_material_occlusion_in_metal_rough(m))
        return false; /* read from the metallic-roughness fetch's red channel */
    return role < MVR_CORE_ROLE_COUNT || (mvr_material_extension_features(m) & roles[role].feature) != 0;
}

float mvr_material_ior_f0(float ior)
{
    float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

/* ---- into the scene */

mvr_material_desc mvr_material_defaults(void)
{
    mvr_material_desc m;
    memset(&m, 0, sizeof m);
    for (int i = 0; i < 4; ++i)
        m.base_color_factor[i] = 1.0f;
    m.metallic_factor = 1.0f;
    m.roughness_factor = 1.0f;
    for (int i = 0; i < 3; ++i) {
        m.volume.attenuation_color[i] = 1.0f;
        m.spec_gloss.specular_factor[i] = 1.0f;
    }
    m.spec_gloss.glossiness_factor = 1.0f;
    m.iridescence.ior = 1.3f;
    m.iridescence.thickness_minimum = 100.0f;
    m.iridescence.thickness_maximum = 400.0f;
    return m;
}

static bool same_transform(const mvr_texture_transform *a, const mvr_texture_transform *b)
{
    if (!a->enabled || !b->enabled)
        return a->enabled == b->enabled;
    return a->offset[0] == b->offset[0] && a->offset[1] == b->offset[1] && a->rotation == b->rotation &&
           a->scale[0] == b->scale[0] && a->scale[1] == b->scale[1];
}

/* The transform slot of each role with a texture (the block's uv fields):
 * identical transforms share one. Returns the slots used, or more than
 * MVR_MATERIAL_TRANSFORM_SLOTS when they do not fit. */
static uint32_t transform_slots(const mvr_material_desc *m, uint8_t slot_of[MVR_ROLE_COUNT],
                                const mvr_texture_transform *slots[MVR_MATERIAL_TRANSFORM_SLOTS])
{
    uint32_t used = 0;
    for (uint32_t r = 0; r < MVR_ROLE_COUNT; ++r) {
        const mvr_texture_ref *t = mvr_material_role(m, r);
        slot_of[r] = 0;
        if (!t->image.id)
            continue;
        uint32_t k = 0;
        while (k < used && k < MVR_MATERIAL_TRANSFORM_SLOTS && !same_transform(slots[k], &t->transform))
            k++;
        if (k == used) {
            if (used < MVR_MATERIAL_TRANSFORM_SLOTS)
                slots[used] = &t->transform;
            used++;
        }
        slot_of[r] = (uint8_t)(k < MVR_MATERIAL_TRANSFORM_SLOTS ? k : 0);
    }
    return used;
}

static mvr_result check_texture(mvr_scene *s, const mvr_texture_ref *t, const char *role,
                                const char *material)
{
    if (t->image.id > s->image_count)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_material(%s): %s texture names image %u; the scene has %u",
                              material, role, t->image.id, s->image_count);
    if (t->texcoord > 1)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_material(%s): %s texture uses TEXCOORD_%u; 0 and 1 are supported",
                              material, role, t->texcoord);
    if ((unsigned)t->sampler.mag_filter > MVR_FILTER_LINEAR_MIPMAP_LINEAR ||
        (unsigned)t->sampler.min_filter > MVR_FILTER_LINEAR_MIPMAP_LINEAR ||
        (unsigned)t->sampler.wrap_s > MVR_WRAP_MIRRORED_REPEAT ||
        (unsigned)t->sampler.wrap_t > MVR_WRAP_MIRRORED_REPEAT)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_material(%s): %s sampler has an unknown enum",
                              material, role);
    if (!mvr_finite_floats(t->transform.offset, 2) || !mvr_finite_floats(t->transform.scale, 2) ||
        !isfinite(t->transform.rotation))
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_material(%s): %s texture transform is not finite", material, role);
    return MVR_OK;
}

mvr_result mvr_scene_add_material(mvr_scene *s, const mvr_material_desc *d, mvr_material_id *out)
{
    if (!s || !d || !out)
        return s ? mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_material: NULL argument")
                 : MVR_ERROR_INVALID_ARGUMENT;
    out->id = 0;
    const char *name = d->name ? d->name : "";
    if ((unsigned)d->alpha_mode > MVR_ALPHA_BLEND)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT, "mvr_scene_add_material(%s): unknown alpha mode %d",
                              name, (int)d->alpha_mode);
    for (uint32_t role = 0; role < MVR_ROLE_COUNT; ++role) {
        mvr_result r = check_texture(s, mvr_material_role(d, role), mvr_role_name(role), name);
        if (r != MVR_OK)
            return r;
    }
    uint8_t slot_of[MVR_ROLE_COUNT];
    const mvr_texture_transform *slots[MVR_MATERIAL_TRANSFORM_SLOTS];
    uint32_t transforms = transform_slots(d, slot_of, slots);
    if (transforms > MVR_MATERIAL_TRANSFORM_SLOTS)
        return mvr_scene_fail(s, MVR_ERROR_INVALID_ARGUMENT,
                              "mvr_scene_add_material(%s): %u distinct texture transforms; a material holds %u",
                              name, transforms, MVR_MATERIAL_TRANSFORM_SLOTS);
    if (!GROW(s, materials, material_count, material_cap))
        return mvr_scene_fail(s, MVR_ERROR_OUT_OF_MEMORY, "mvr_scene_add_material: out of memory");
    scene_material *m = &s->materials[s->material_count];
    m->desc = *d;
    m->desc.name = NULL;
    mvr_str_copy(m->name, sizeof m->name, name);
    /* Factors: NaN or infinite becomes glTF's default, a denormal 0 (some
     * GPUs flush them, others take slow paths), and each is clamped to its
     * glTF range; each change is counted and logged. */
    mvr_material_desc defaults = mvr_material_defaults();
    struct { float *v; float fallback, lo, hi; } factors[] = {
        {&m->desc.base_color_factor[0], 1, 0, 1}, {&m->desc.base_color_factor[1], 1, 0, 1},
        {&m->desc.base_color_factor[2], 1, 0, 1}, {&m->desc.base_color_factor[3], 1, 0, 1},
        {&m->desc.metallic_factor, defaults.metallic_factor, 0, 1},
        {&m->desc.roughness_factor, defaults.roughness_factor, 0, 1},
        {&m->desc.emissive_factor[0], 0, 0, 1}, {&m->desc.emissive_factor[1], 0, 0, 1},
        {&m->desc.emissive_factor[2], 0, 0, 1}, {&m->desc.emissive_strength, 0, 0, 1e30f},
        {&m->desc.normal_scale, 0, -1e30f, 1e30f}, {&m->desc.occlusion_strength, 0, 0, 1},
        {&m->desc.alpha_cutoff, 0, 0, 1e30f}, {&m->desc.ior, 0, 0, 1e30f},
        {&m->desc.specular.factor, 1, 0, 1}, {&m->desc.specular.color_factor[0], 1, 0, 1e30f},
        {&m->desc.specular.color_factor[1], 1, 0, 1e30f}, {&m->desc.specular.color_factor[2], 1, 0, 1e30f},
        {&m->desc.clearcoat.factor, 0, 0, 1}, {&m->desc.clearcoat.roughness_factor, 0, 0, 1},
        {&m->desc.clearcoat.normal_scale, 0, -1e30f, 1e30f},
        {&m->desc.sheen.color_factor[0], 0, 0, 1}, {&m->desc.sheen.color_factor[1], 0, 0, 1},
        {&m->desc.sheen.color_factor[2], 0, 0, 1}, {&m->desc.sheen.roughness_factor, 0, 0, 1},
        {&m->desc.transmission.factor, 0, 0, 1}, {&m->desc.volume.thickness_factor, 0, 0, 1e30f},
        {&m->desc.volume.attenuation_distance, 0, 0, 1e30f},
        {&m->desc.volume.attenuation_color[0], 1, 0, 1}, {&m->desc.volume.attenuation_color[1], 1, 0, 1},
        {&m->desc.volume.attenuation_color[2], 1, 0, 1}, {&m->desc.dispersion, 0, 0, 1e30f},
        {&m->desc.iridescence.factor, 0, 0, 1}, {&m->desc.iridescence.ior, 0, 0, 1e30f},
        {&m->desc.iridescence.thickness_minimum, defaults.iridescence.thickness_minimum, 0, 1e30f},
        {&m->desc.iridescence.thickness_maximum, defaults.iridescence.thickness_maximum, 0, 1e30f},
        {&m->desc.anisotropy.strength, 0, 0, 1}, {&m->desc.anisotropy.rotation, 0, -1e30f, 1e30f},
        {&m->desc.spec_gloss.specular_factor[0], 1, 0, 1}, {&m->desc.spec_gloss.specular_factor[1], 1, 0, 1},
        {&m->desc.spec_gloss.specular_factor[2], 1, 0, 1}, {&m->desc.spec_gloss.glossiness_factor, 1, 0, 1}};
    uint32_t repaired = 0;
    for (size_t i = 0; i < MVR_ARRAY_COUNT(factors); ++i) {
        float v = *factors[i].v;
        if (!isfinite(v))
            v = factors[i].fallback;
        else if (fpclassify(v) == FP_SUBNORMAL)
            v = 0.0f;
        v = v < factors[i].lo ? factors[i].lo : v > factors[i].hi ? factors[i].hi : v;
        repaired += v != *factors[i].v || isnan(*factors[i].v);
        *factors[i].v = v;
    }
    if (repaired) {
        s->sanitized += repaired;
        mvr_log(&s->logger, MVR_LOG_WARNING, MVR_LOG_ID_GENERAL,
                "mvr_scene_add_material(%s): %u factors were NaN, infinite, denormal or out of range (repaired)",
                name, repaired);
    }
    /* Zero means default for these (a factor of 0 would be meaningless). */
    if (m->desc.emissive_strength == 0.0f)
        m->desc.emissive_strength = 1.0f;
    if (m->desc.normal_scale == 0.0f)
        m->desc.normal_scale = 1.0f;
    if (m->desc.occlusion_strength == 0.0f)
        m->desc.occlusion_strength = 1.0f;
    if (m->desc.alpha_cutoff == 0.0f)
        m->desc.alpha_cutoff = 0.5f;
    /* KHR_materials_ior: 0 is "not given" (1.5); below 1 is no index of
     * refraction (F0 would rise again): 1, no reflection */
    if (m->desc.ior == 0.0f)
        m->desc.ior = 1.5f;
    else if (m->desc.ior < 1.0f)
        m->desc.ior = 1.0f;
    if (!m->desc.specular.enabled) {
        m->desc.specular.factor = 1.0f;
        m->desc.specular.color_factor[0] = m->desc.specular.color_factor[1] = m->desc.specular.color_factor[2] = 1.0f;
    }
    if (m->desc.clearcoat.normal_scale == 0.0f)
        m->desc.clearcoat.normal_scale = 1.0f;
    /* an iridescence ior of 0 is "not given" (1.3); below 1, as the base's */
    if (m->desc.iridescence.ior == 0.0f)
        m->desc.iridescence.ior = defaults.iridescence.ior;
    else if (m->desc.iridescence.ior < 1.0f)
        m->desc.iridescence.ior = 1.0f;
    s->material_count++;
    s->material_version++;
    out->id = s->material_count;
    return MVR_OK;
}

const mvr_material_desc *mvr_scene_material(const mvr_scene *s, uint32_t index)
{
    static const mvr_material_desc fallback = {.base_color_factor = {1.0f, 1.0f, 1.0f, 1.0f},
                                               .metallic_factor = 1.0f,
                                               .roughness_factor = 1.0f,
                                               .emissive_strength = 1.0f,
                                               .normal_scale = 1.0f,
                                               .occlusion_strength = 1.0f,
                                               .alpha_cutoff = 0.5f,
                                               .ior = 1.5f,
                                               .specular = {.factor = 1.0f, .color_factor = {1.0f, 1.0f, 1.0f}},
                                               .clearcoat = {.normal_scale = 1.0f},
                                               .volume = {.attenuation_color = {1.0f, 1.0f, 1.0f}},
                                               .iridescence = {.ior = 1.3f,
                                                               .thickness_minimum = 100.0f,
                                                               .thickness_maximum = 400.0f},
                                               .spec_gloss = {.specular_factor = {1.0f, 1.0f, 1.0f},
                                                              .glossiness_factor = 1.0f}};
    return index < s->material_count ? &s->materials[index].desc : &fallback;
}


/* ---- the std140 block */

/* Two rows of the 2x3 affine of KHR_texture_transform: uv' = T * R * S * uv
 * with R = mat3(cos, sin, 0, -sin, cos, 0, 0, 0, 1) in column-major GLSL, as
 * the ratified extension text writes it. */
static void uv_rows(const mvr_texture_transform *t, float out[8])
{
    float sx = t->scale[0] != 0.0f ? t->scale[0] : 1.0f;
    float sy = t->scale[1] != 0.0f ? t->scale[1] : 1.0f;
    float c = 1.0f, s = 0.0f, ox = 0.0f, oy = 0.0f;
    if (t->enabled) {
        c = cosf(t->rotation);
        s = sinf(t->rotation);
        ox = t->offset[0];
        oy = t->offset[1];
    } else {
        sx = sy = 1.0f;
    }
    float rows[8] = {c * sx, -s * sy, ox, 0.0f, s * sx, c * sy, oy, 0.0f};
    memcpy(out, rows, sizeof rows);
}

static void put_vec4(uint8_t *out, uint32_t offset, float x, float y, float z, float w)
{
    float v[4] = {x, y, z, w};
    memcpy(out + offset, v, sizeof v);
}

void mvr_material_pack(const mvr_material_desc *m, const uint16_t *layers, uint8_t *out)
{
    memset(out, 0, MVR_MATERIAL_BLOCK_SIZE);
    memcpy(out + MVR_MATERIAL_BASE_COLOR_OFFSET, m->base_color_factor, 4 * sizeof(float));
    put_vec4(out, MVR_MATERIAL_EMISSIVE_OFFSET, m->emissive_factor[0] * m->emissive_strength,
             m->emissive_factor[1] * m->emissive_strength, m->emissive_factor[2] * m->emissive_strength,
             m->alpha_cutoff);
    put_vec4(out, MVR_MATERIAL_PARAMS_OFFSET, m->metallic_factor, m->roughness_factor, m->normal_scale,
             m->occlusion_strength);

    /* per role: its layer, its uv set and transform slot, whether it has a texture */
    uint8_t slot_of[MVR_ROLE_COUNT];
    const mvr_texture_transform *slots[MVR_MATERIAL_TRANSFORM_SLOTS];
    uint32_t used = transform_slots(m, slot_of, slots);
    int32_t layer_words[4 * MVR_MATERIAL_LAYERS_COUNT] = {0};
    int32_t uv[4] = {0, 0, 0, 0};
    for (uint32_t r = 0; r < MVR_ROLE_COUNT; ++r) {
        /* a layer also where the batch plan gives a role without a texture
         * its group's white layer */
        uint32_t layer = layers && layers[r] != UINT16_MAX ? layers[r] : 0u;
        layer_words[r / 2] = (int32_t)((uint32_t)layer_words[r / 2] | layer << (16u * (r % 2)));
        if (!mvr_material_samples_role(m, r))
            continue;
        const mvr_texture_ref *t = mvr_material_role(m, r);
        uint32_t field = (t->texcoord == 1 ? 1u : 0u) | (uint32_t)slot_of[r] << 1;
        uv[r / 8] = (int32_t)((uint32_t)uv[r / 8] | field << (4u * (r % 8)));
        uv[3] = (int32_t)((uint32_t)uv[3] | 1u << r);
    }
    if (mvr_material_occlusion_in_metal_rough(m))
        uv[3] = (int32_t)((uint32_t)uv[3] | 1u << MVR_MATERIAL_OCCLUSION_IN_METAL_ROUGH_BIT);
    memcpy(out + MVR_MATERIAL_LAYERS_OFFSET, layer_words, sizeof layer_words);
    memcpy(out + MVR_MATERIAL_UV_OFFSET, uv, sizeof uv);
    for (uint32_t k = 0; k < used && k < MVR_MATERIAL_TRANSFORM_SLOTS; ++k) {
        float rows[8];
        uv_rows(slots[k], rows);
        memcpy(out + MVR_MATERIAL_UV_TRANSFORM_OFFSET + (size_t)k * 2 * MVR_MATERIAL_UV_TRANSFORM_STRIDE, rows,
               sizeof rows);
    }

    /* KHR_materials_ior / _specular, as the Khronos glTF Sample Renderer
     * takes them: F0 = min(((ior - 1) / (ior + 1))^2 * specular color, 1),
     * weight = specular factor (F90 of the dielectric, and its F0's scale) */
    float f0 = mvr_material_ior_f0(m->ior);
    float spec[4] = {f0, f0, f0, 1.0f};
    if (m->specular.enabled) {
        for (int c = 0; c < 3; ++c)
            spec[c] = fminf(f0 * m->specular.color_factor[c], 1.0f);
        spec[3] = m->specular.factor;
    }
    if (m->spec_gloss.enabled) {
        /* KHR_materials_pbrSpecularGlossiness: F0 is the specular color;
         * params.y carries the glossiness */
        for (int c = 0; c < 3; ++c)
            spec[c] = m->spec_gloss.specular_factor[c];
        spec[3] = 1.0f;
        put_vec4(out, MVR_MATERIAL_PARAMS_OFFSET, 0.0f, m->spec_gloss.glossiness_factor, m->normal_scale,
                 m->occlusion_strength);
    }
    memcpy(out + MVR_MATERIAL_SPECULAR_OFFSET, spec, sizeof spec);
    put_vec4(out, MVR_MATERIAL_CLEARCOAT_OFFSET, m->clearcoat.factor, m->clearcoat.roughness_factor, f0,
             m->clearcoat.normal_scale);
    put_vec4(out, MVR_MATERIAL_SHEEN_OFFSET, m->sheen.color_factor[0], m->sheen.color_factor[1],
             m->sheen.color_factor[2], m->sheen.roughness_factor);
    put_vec4(out, MVR_MATERIAL_TRANSMISSION_OFFSET, m->transmission.factor, m->volume.thickness_factor,
             m->volume.attenuation_distance, m->dispersion);
    put_vec4(out, MVR_MATERIAL_VOLUME_OFFSET, m->volume.attenuation_color[0], m->volume.attenuation_color[1],
             m->volume.attenuation_color[2], m->ior);
    put_vec4(out, MVR_MATERIAL_IRIDESCENCE_OFFSET, m->iridescence.factor, m->iridescence.ior,
             m->iridescence.thickness_minimum, m->iridescence.thickness_maximum);
    put_vec4(out, MVR_MATERIAL_ANISOTROPY_OFFSET, m->anisotropy.strength, cosf(m->anisotropy.rotation),
             sinf(m->anisotropy.rotation), 0.0f);
}
