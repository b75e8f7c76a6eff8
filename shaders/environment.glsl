// environment.glsl: directions of cube map texels and equirectangular
// images, and GGX importance sampling (the environment program).

// The direction of texel coordinates st in [-1, 1]^2 of cube face `face`
// (0..5: +X, -X, +Y, -Y, +Z, -Z): the inverse of the face selection table
// of the OpenGL ES 3.0 specification (Table 3.21: +X: sc = -rz, tc = -ry;
// -X: sc = rz, tc = -ry; +Y: sc = rx, tc = rz; -Y: sc = rx, tc = -rz;
// +Z: sc = rx, tc = -ry; -Z: sc = -rx, tc = -ry).
vec3 mvr_cube_direction(int face, vec2 st)
{
    if (face == 0)
        return vec3(1.0, -st.y, -st.x);
    if (face == 1)
        return vec3(-1.0, -st.y, st.x);
    if (face == 2)
        return vec3(st.x, 1.0, st.y);
    if (face == 3)
        return vec3(st.x, -1.0, -st.y);
    if (face == 4)
        return vec3(st.x, -st.y, 1.0);
    return vec3(-st.x, -st.y, -1.0);
}

// mvr.h's mapping: u = 0.5 + atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi
// (the image's top row, uploaded first, is v = 0).
vec2 mvr_equirect_uv(vec3 d)
{
    float u = 0.5 + atan(d.x, -d.z) / (2.0 * MVR_PI);
    float v = acos(clamp(d.y, -1.0, 1.0)) / MVR_PI;
    return vec2(u, v);
}

// Van der Corput radical inverse in base 2: the Hammersley point set.
vec2 mvr_hammersley(int i, int n)
{
    uint b = uint(i);
    b = (b << 16u) | (b >> 16u);
    b = ((b & 0x55555555u) << 1u) | ((b & 0xAAAAAAAAu) >> 1u);
    b = ((b & 0x33333333u) << 2u) | ((b & 0xCCCCCCCCu) >> 2u);
    b = ((b & 0x0F0F0F0Fu) << 4u) | ((b & 0xF0F0F0F0u) >> 4u);
    b = ((b & 0x00FF00FFu) << 8u) | ((b & 0xFF00FF00u) >> 8u);
    return vec2(float(i) / float(n), float(b) * 2.3283064365386963e-10);
}

// A GGX half vector around +Z for xi in [0, 1)^2 (Walter et al. 2007):
// pdf(h) = D(h) cos(theta_h).
vec3 mvr_ggx_half_vector(vec2 xi, float alpha)
{
    float phi = 2.0 * MVR_PI * xi.x;
    float cos_t = sqrt((1.0 - xi.y) / (1.0 + (alpha * alpha - 1.0) * xi.y));
    float sin_t = sqrt(max(1.0 - cos_t * cos_t, 0.0));
    return vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t);
}

float mvr_d_ggx(float n_dot_h, float alpha)
{
    float a2 = alpha * alpha;
    float f = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / max(MVR_PI * f * f, 1e-12);
}
