/* Photometric exposure (backend-free): Lagarde and de Rousiers, "Moving
 * Frostbite to Physically Based Rendering 3.0" (SIGGRAPH 2014 course notes),
 * section 4.4: saturation-based sensitivity (ISO 12232) with S = 100, a
 * lens and vignetting factor q = 0.65, so the luminance that saturates the
 * sensor is L_max = 78 / (S q) * 2^EV100 = 1.2 * 2^EV100 and
 * exposure = 1 / L_max. */
#include <math.h>

#include "mvr/mvr.h"

double mvr_exposure_from_ev100(double ev100)
{
    return 1.0 / (1.2 * exp2(ev100));
}

double mvr_ev100_from_camera(double aperture, double shutter, double iso)
{
    if (!(aperture > 0.0))
        aperture = 16.0;
    if (!(shutter > 0.0))
        shutter = 1.0 / 125.0;
    if (!(iso > 0.0))
        iso = 100.0;
    /* EV100 = log2(N^2 / t * 100 / S) */
    return log2(aperture * aperture / shutter * 100.0 / iso);
}

const char *mvr_exposure_mode_name(mvr_exposure_mode mode)
{
    switch (mode) {
    case MVR_EXPOSURE_LINEAR: return "linear";
    case MVR_EXPOSURE_EV100: return "ev100";
    case MVR_EXPOSURE_CAMERA: return "camera";
    case MVR_EXPOSURE_AUTO: return "auto";
    }
    return NULL;
}

const char *mvr_tone_map_name(mvr_tone_map tone_map)
{
    switch (tone_map) {
    case MVR_TONE_MAP_NONE: return "none";
    case MVR_TONE_MAP_ACES: return "aces";
    case MVR_TONE_MAP_KHR_PBR_NEUTRAL: return "pbr-neutral";
    }
    return NULL;
}

void mvr_render_desc_choose_exposure(const mvr_scene *scene, mvr_render_desc *desc)
{
    if (!desc)
        return;
    if (scene && mvr_scene_lights_physical(scene)) {
        /* a sun of thousands of lux is a white frame at exposure 1: expose
         * it as a camera would, and roll the highlights off */
        desc->exposure_mode = MVR_EXPOSURE_AUTO;
        desc->tone_map = MVR_TONE_MAP_KHR_PBR_NEUTRAL;
    } else {
        /* lights authored for a linear multiplier: the values as they are;
         * under an environment, whose light adds to theirs and whose
         * highlights reach far above 1, rolled off by Khronos PBR Neutral
         * (the identity below 0.76 (its start of compression), hue kept
         * above; the Khronos glTF Sample Viewer's default) instead of
         * clipped */
        desc->exposure_mode = MVR_EXPOSURE_LINEAR;
        desc->tone_map = desc->environment ? MVR_TONE_MAP_KHR_PBR_NEUTRAL : MVR_TONE_MAP_NONE;
    }
}
