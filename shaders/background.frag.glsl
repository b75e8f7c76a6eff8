// background.frag.glsl: the environment seen through each pixel no geometry
// covers (depth test at the far plane): the source cube map (sharp) or a
// prefiltered level (blurred), exposed and encoded as the mesh's colors.
in vec3 v_dir;
layout(location = 0) out vec4 o_color;

uniform samplerCube mvr_env_background;
uniform mat3 mvr_env_rotation;   // world direction -> environment direction
uniform float mvr_env_intensity;
uniform float mvr_background_lod;

void main()
{
    vec3 e = mvr_env_rotation * mvr_safe_normalize(v_dir, vec3(0.0, 0.0, -1.0));
    o_color = mvr_output(vec4(textureLod(mvr_env_background, e, mvr_background_lod).rgb * mvr_env_intensity, 1.0));
}
