// lights.glsl: the punctual lights (KHR_lights_punctual) and the uniform
// ambient of the mesh program's fragment stage.

struct mvr_light {
    vec4 position_range;     // xyz relative to the view origin; w: range (0 = infinite)
    vec4 direction;          // xyz: direction the light points to (unit)
    vec4 color;              // rgb: color * intensity
    vec4 spot;               // x: angle scale, y: angle offset (KHR_lights_punctual)
};

#define MVR_LIGHT_COUNT (MVR_DIRECTIONAL_LIGHTS + MVR_POINT_LIGHTS + MVR_SPOT_LIGHTS)
#if MVR_LIGHT_COUNT > 0
layout(std140) uniform mvr_lights {
    mvr_light mvr_light_list[MVR_LIGHT_COUNT]; // directional, then point, then spot
};
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
