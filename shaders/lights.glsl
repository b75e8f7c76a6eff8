// lights.glsl: the punctual lights (KHR_lights_punctual) and the uniform
// ambient of the mesh program's fragment stage.

#define MVR_LIGHT_COUNT (MVR_DIRECTIONAL_LIGHTS + MVR_POINT_LIGHTS + MVR_SPOT_LIGHTS)
#if MVR_LIGHT_COUNT > 0
// struct mvr_light and the mvr_lights block of MVR_LIGHT_COUNT of them
// (directional, then point, then spot), from core/block_layout.c
#mvr_block mvr_lights
#endif
uniform vec3 mvr_ambient;    // rgb radiance of a uniform environment

// KHR_lights_punctual range attenuation: smooth window to zero at range,
// inverse square inside; distance clamped so a light at the surface is finite.
float mvr_range_attenuation(float range, float dist)
{
    float d2 = max(dist * dist, 1e-8);
    if (range <= 0.0)
        return 1.0 / d2;
    float r = clamp(1.0 - pow(dist / range, 4.0), 0.0, 1.0);
    return r * r / d2;
}
