/* The renderer's overrides (mvr_renderer_overrides): read from MVR_*
 * variables on request, checked at create. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core_util.h"
#include "overrides.h"
#include "shader_gen.h"

/* value among choices: *out = its index + 1 (the override enums' order);
 * else the failure, naming the variable and what it takes */
static mvr_result parse_choice(const char *name, const char *value, const char *const *choices, int count, int *out,
                               mvr_error *error)
{
    char list[128] = "";
    for (int k = 0; k < count; ++k) {
        if (strcmp(value, choices[k]) == 0) {
            *out = k + 1;
            return MVR_OK;
        }
        size_t used = strlen(list);
        snprintf(list + used, sizeof list - used, "%s%s", k == 0 ? "" : k == count - 1 ? " or " : ", ", choices[k]);
    }
    return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "%s=%s is not %s", name, value, list);
}

static bool valid_ubo_alignment(unsigned long a)
{
    return a >= 1 && a <= 4096 && (a & (a - 1)) == 0;
}

/* The mesh feature bits an override may take out: material extensions,
 * whose absence is a valid (if different) look, never what a draw needs. */
#define DISABLEABLE_FEATURES                                                                                \
    (MVR_FEATURE_SPECULAR | MVR_FEATURE_CLEARCOAT | MVR_FEATURE_TRANSMISSION | MVR_FEATURE_SHEEN |              \
     MVR_FEATURE_IRIDESCENCE | MVR_FEATURE_ANISOTROPY)

/* "SPECULAR,CLEARCOAT" -> feature bits; names as mvr_program_feature_name. */
static mvr_result parse_feature_list(const char *var, const char *value, uint32_t *out, mvr_error *error)
{
    *out = 0;
    const char *p = value;
    for (;;) {
        size_t n = strcspn(p, ",");
        uint32_t bit = 0;
        for (uint32_t b = 1; b && !bit; b <<= 1) {
            const char *name = (b & DISABLEABLE_FEATURES) ? mvr_program_feature_name(b) : NULL;
            if (name && strlen(name) == n && strncmp(name, p, n) == 0)
                bit = b;
        }
        if (!bit)
            return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                                 "%s=%s: '%.*s' is not a feature that can be disabled (SPECULAR, CLEARCOAT, "
                                 "TRANSMISSION, SHEEN, IRIDESCENCE, ANISOTROPY)",
                                 var,
                                 value, (int)n, p);
        *out |= bit;
        p += n;
        if (*p != ',')
            return MVR_OK;
        ++p; /* a name must follow: "CLEARCOAT," is refused as '' */
    }
}

mvr_result mvr_renderer_overrides_from_env(mvr_renderer_overrides *out, mvr_error *error)
{
    if (!out)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT, "mvr_renderer_overrides_from_env: out is NULL");
    memset(out, 0, sizeof *out);
    /* the choices in the order of the override enums (after their NONE) */
    static const char *const view_paths[] = {"auto", "multiview", "loop"};
    static const char *const material_paths[] = {"auto", "arrays", "per_material", "per_draw"};
    static const char *const depth_modes[] = {"auto", "reversed_z", "standard"};
    static const char *const switches[] = {"off", "on"};
    static const char *const features[] = {"inert"};
    static const char *const skinning_paths[] = {"auto", "vertex", "preskin"};
    enum { VIEW_PATH, MATERIAL_PATH, DEPTH, CULLING, INSTANCING, MSAA_MULTIVIEW, FORCE_FEATURES, UBO_ALIGNMENT,
           SKINNING_PATH, DISABLE_FEATURES, TUNING, ANISOTROPIC, COUNT };
    static const char *const names[COUNT] = {"MVR_VIEW_PATH",      "MVR_MATERIAL_PATH", "MVR_DEPTH",
                                             "MVR_CULLING",        "MVR_INSTANCING",    "MVR_MSAA_MULTIVIEW",
                                             "MVR_FORCE_FEATURES", "MVR_UBO_ALIGNMENT", "MVR_SKINNING_PATH",
                                             "MVR_DISABLE_FEATURES", "MVR_TUNING", "MVR_ANISOTROPIC"};
    mvr_renderer_overrides o;
    memset(&o, 0, sizeof o);
    for (int v = 0; v < COUNT; ++v) {
        const char *value = getenv(names[v]);
        if (!value || !*value)
            continue;
        int k = 0;
        mvr_result res = MVR_OK;
        switch (v) {
        case VIEW_PATH:
            res = parse_choice(names[v], value, view_paths, 3, &k, error);
            o.view_path = (mvr_view_path_override)k;
            break;
        case MATERIAL_PATH:
            res = parse_choice(names[v], value, material_paths, 4, &k, error);
            o.material_path = (mvr_material_path_override)k;
            break;
        case DEPTH:
            res = parse_choice(names[v], value, depth_modes, 3, &k, error);
            o.depth_mode = (mvr_depth_mode_override)k;
            break;
        case CULLING:
        case INSTANCING:
        case MSAA_MULTIVIEW:
        case TUNING:
        case ANISOTROPIC:
            res = parse_choice(names[v], value, switches, 2, &k, error);
            *(v == CULLING       ? &o.culling
              : v == INSTANCING  ? &o.instancing
              : v == TUNING      ? &o.tuning
              : v == ANISOTROPIC ? &o.anisotropic
                                : &o.msaa_multiview) = (mvr_override_switch)k;
            break;
        case SKINNING_PATH:
            res = parse_choice(names[v], value, skinning_paths, 3, &k, error);
            o.skinning_path = (mvr_skinning_path_override)k;
            break;
        case DISABLE_FEATURES:
            res = parse_feature_list(names[v], value, &o.disable_features, error);
            break;
        case FORCE_FEATURES:
            res = parse_choice(names[v], value, features, 1, &k, error);
            o.force_inert_features = k == 1;
            break;
        case UBO_ALIGNMENT: {
            char *end = NULL;
            unsigned long a = strtoul(value, &end, 10);
            if (value[0] < '0' || value[0] > '9' || *end || !valid_ubo_alignment(a))
                res = mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                                    "%s=%s is not a power of two from 1 to 4096", names[v], value);
            o.ubo_alignment = (uint32_t)a;
            break;
        }
        }
        if (res != MVR_OK)
            return res;
    }
    *out = o;
    return MVR_OK;
}

mvr_result mvr_overrides_check(const mvr_renderer_overrides *o, mvr_error *error)
{
    const char *field = NULL;
    int value = 0;
    if ((unsigned)o->view_path > MVR_VIEW_PATH_OVERRIDE_LOOP)
        field = "view_path", value = (int)o->view_path;
    else if ((unsigned)o->material_path > MVR_MATERIAL_PATH_OVERRIDE_PER_DRAW)
        field = "material_path", value = (int)o->material_path;
    else if ((unsigned)o->depth_mode > MVR_DEPTH_MODE_OVERRIDE_STANDARD)
        field = "depth_mode", value = (int)o->depth_mode;
    else if ((unsigned)o->skinning_path > MVR_SKINNING_PATH_OVERRIDE_PRESKIN)
        field = "skinning_path", value = (int)o->skinning_path;
    else if (o->disable_features & ~(uint32_t)DISABLEABLE_FEATURES)
        field = "disable_features", value = (int)o->disable_features;
    else if ((unsigned)o->culling > MVR_OVERRIDE_ON)
        field = "culling", value = (int)o->culling;
    else if ((unsigned)o->instancing > MVR_OVERRIDE_ON)
        field = "instancing", value = (int)o->instancing;
    else if ((unsigned)o->msaa_multiview > MVR_OVERRIDE_ON)
        field = "msaa_multiview", value = (int)o->msaa_multiview;
    else if ((unsigned)o->tuning > MVR_OVERRIDE_ON)
        field = "tuning", value = (int)o->tuning;
    else if ((unsigned)o->anisotropic > MVR_OVERRIDE_ON)
        field = "anisotropic", value = (int)o->anisotropic;
    if (field)
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: overrides.%s %d is out of its enum's range", field, value);
    if (o->ubo_alignment != 0 && !valid_ubo_alignment(o->ubo_alignment))
        return mvr_error_set(error, MVR_ERROR_INVALID_ARGUMENT,
                             "mvr_renderer_create: overrides.ubo_alignment %u is not a power of two up to 4096",
                             (unsigned)o->ubo_alignment);
    return MVR_OK;
}
