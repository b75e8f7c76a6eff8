/* The names of the renderer's enums (mvr.h): what messages, stats and the
 * CLI print, and what the create and render checks test a value against. */
#include <string.h>

#include "mvr/mvr.h"
#include "shader_gen.h"

const char *mvr_view_path_name(mvr_view_path path)
{
    switch (path) {
    case MVR_VIEW_PATH_AUTO: return "auto";
    case MVR_VIEW_PATH_MULTIVIEW: return "multiview";
    case MVR_VIEW_PATH_LOOP: return "loop";
    }
    return NULL;
}

const char *mvr_material_path_name(mvr_material_path path)
{
    switch (path) {
    case MVR_MATERIAL_PATH_AUTO: return "auto";
    case MVR_MATERIAL_PATH_ARRAYS: return "arrays";
    case MVR_MATERIAL_PATH_PER_MATERIAL: return "per_material";
    case MVR_MATERIAL_PATH_PER_DRAW: return "per_draw";
    }
    return NULL;
}

const char *mvr_transparency_order_name(mvr_transparency_order order)
{
    switch (order) {
    case MVR_TRANSPARENCY_ORDER_AUTO: return "auto";
    case MVR_TRANSPARENCY_ORDER_CENTROID: return "centroid";
    case MVR_TRANSPARENCY_ORDER_PER_VIEW: return "per_view";
    }
    return NULL;
}

const char *mvr_depth_mode_name(mvr_depth_mode mode)
{
    switch (mode) {
    case MVR_DEPTH_MODE_AUTO: return "auto";
    case MVR_DEPTH_MODE_REVERSED_Z: return "reversed_z";
    case MVR_DEPTH_MODE_STANDARD: return "standard";
    }
    return NULL;
}

const char *mvr_color_format_name(mvr_color_format format)
{
    switch (format) {
    case MVR_COLOR_FORMAT_DEFAULT: return "srgb8_alpha8";
    case MVR_COLOR_FORMAT_RGBA8: return "rgba8";
    case MVR_COLOR_FORMAT_RGBA16F: return "rgba16f";
    case MVR_COLOR_FORMAT_RGBA32F: return "rgba32f";
    }
    return NULL;
}

const char *mvr_oversized_image_name(mvr_oversized_image policy)
{
    switch (policy) {
    case MVR_OVERSIZED_IMAGE_DEFAULT: return "default";
    case MVR_OVERSIZED_IMAGE_DOWNSCALE: return "downscale";
    case MVR_OVERSIZED_IMAGE_REFUSE: return "refuse";
    }
    return NULL;
}

const char *mvr_program_feature_name(uint32_t bit)
{
    const char *define = mvr_shader_feature_define(MVR_PROGRAM_MESH, bit);
    /* the #define without its MVR_ prefix */
    return define && strncmp(define, "MVR_", 4) == 0 ? define + 4 : define;
}
