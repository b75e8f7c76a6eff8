// composite.frag.glsl: full-screen passes over a color array, each view
// reading its own layer (multiview: the layer follows gl_ViewID_OVR).
// - plain: a copy;
// - MVR_DOWNSAMPLE: the supersampling resolve, each pixel the mean of its
//   factor x factor source texels (linear values; summed in a fixed order,
//   so every path gives the same bytes);
// - MVR_POST: the final resolve of an HDR target: exposure, tone mapping,
//   dithering, then the sRGB encode (MVR_SRGB_ENCODE, for UNORM outputs).
//   Where no surface was drawn (the HDR alpha, cleared to 0, stays 0) the
//   pixel keeps the display clear colour the pass cleared the output to
//   (the GL's clear, as a plain frame's: the same bytes): a clear colour is
//   a display colour, never exposed. With MVR_DOWNSAMPLE each supersample is exposed,
//   tone mapped and composited over the clear first, and the display
//   (sRGB-encoded) values are averaged, as a GL resolve of the peers'
//   display-encoded framebuffers does: an edge against a blown-out surface
//   is the mean of what is seen, not the brightest sample's tone map.
//   MVR_POST_MSAA does the same over a multisampled frame's samples;
// - MVR_LOG_LUMINANCE: log2 of each texel's luminance and whether it has
//   any (auto-exposure; the GL's mipmap chain then averages both).
uniform sampler2DArray mvr_source;
#ifdef MVR_DOWNSAMPLE
uniform int mvr_factor;
#endif
#ifdef MVR_LOG_LUMINANCE
uniform sampler2DArray mvr_depth;  // the views' depth: where nothing was drawn is not metered
uniform float mvr_clear_depth;
#endif
#ifdef MVR_POST
#define MVR_POST_VIEWS 32
uniform float mvr_post_exposure[MVR_POST_VIEWS]; // per view of the pass: exposure / pre-exposure
uniform int mvr_layer_base;                      // the pass's first source layer (as the vertex stage's)
#endif
#if defined(MVR_POST) && defined(MVR_POST_MSAA)
uniform highp sampler2DMSArray mvr_source_ms; // every view's samples (a multisampled HDR frame)
uniform int mvr_samples;
#endif
#if defined(MVR_POST) || defined(MVR_DOWNSAMPLE)
uniform vec4 mvr_clear_out; // the clear colour as written (encoded for UNORM outputs)
#endif

flat in int v_layer;
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

#ifdef MVR_TONEMAP_ACES
// The fitted ACES curve the Khronos glTF Sample Renderer uses (its
// "ACES Filmic (Hill)": Stephen Hill's fit of the RRT + ODT): sRGB -> AP1
// with the RRT's saturation, the rational fit, back to sRGB, clamped.
const mat3 MVR_ACES_INPUT = mat3(0.59719, 0.07600, 0.02840,
                                 0.35458, 0.90834, 0.13383,
                                 0.04823, 0.01566, 0.83777);
const mat3 MVR_ACES_OUTPUT = mat3(1.60475, -0.10208, -0.00327,
                                  -0.53108, 1.10813, -0.07276,
                                  -0.07367, -0.00605, 1.07602);
vec3 mvr_tone_map(vec3 c)
{
    c = MVR_ACES_INPUT * c;
    vec3 a = c * (c + 0.0245786) - 0.000090537;
    vec3 b = c * (0.983729 * c + 0.4329510) + 0.238081;
    return clamp(MVR_ACES_OUTPUT * (a / b), 0.0, 1.0);
}
#elif defined(MVR_TONEMAP_PBR_NEUTRAL)
// Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral; the Sample
// Renderer's "Khronos PBR Neutral").
vec3 mvr_tone_map(vec3 c)
{
    const float start_compression = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(c.r, min(c.g, c.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    c -= offset;
    float peak = max(c.r, max(c.g, c.b));
    if (peak < start_compression)
        return c;
    const float d = 1.0 - start_compression;
    float new_peak = 1.0 - d * d / (peak + d - start_compression);
    c *= new_peak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return mix(c, vec3(new_peak), g);
}
#else
// none: clamp
vec3 mvr_tone_map(vec3 c)
{
    return clamp(c, 0.0, 1.0);
}
#endif

#ifdef MVR_POST
// One HDR sample's display value (linear, before any encode): exposed and
// tone mapped; its alpha says how much surface covers it (0: the clear).
vec3 mvr_post_display(vec4 c)
{
    return mvr_tone_map(max(c.rgb, vec3(0.0)) * mvr_post_exposure[v_layer - mvr_layer_base]);
}

// The sRGB decode (the inverse of mvr_linear_to_srgb).
vec3 mvr_srgb_decode(vec3 e)
{
    return mix(pow((e + 0.055) / 1.055, vec3(2.4)), e / 12.92, vec3(lessThanEqual(e, vec3(0.04045))));
}

// The clear colour, linear (what an sRGB output encodes to its bytes).
vec3 mvr_clear_linear()
{
#ifdef MVR_SRGB_ENCODE
    return mvr_srgb_decode(mvr_clear_out.rgb);
#else
    return mvr_clear_out.rgb;
#endif
}
#endif

void main()
{
#if defined(MVR_POST) && (defined(MVR_DOWNSAMPLE) || defined(MVR_POST_MSAA))
    // per sample: exposure, tone map, composite over the clear, encode; then the mean
#ifdef MVR_POST_MSAA
    int n = mvr_samples;
#define MVR_SAMPLE(i) texelFetch(mvr_source_ms, ivec3(ivec2(gl_FragCoord.xy), v_layer), i)
#else
    ivec2 base = ivec2(gl_FragCoord.xy) * mvr_factor;
    int n = mvr_factor * mvr_factor;
#define MVR_SAMPLE(i) texelFetch(mvr_source, ivec3(base + ivec2((i) % mvr_factor, (i) / mvr_factor), v_layer), 0)
#endif
    vec3 clear_e = mvr_linear_to_srgb(mvr_clear_linear());
    vec4 sum = vec4(0.0);
    int covered = 0;
    for (int i = 0; i < n; ++i) {
        vec4 s = MVR_SAMPLE(i);
        float a = clamp(s.a, 0.0, 1.0);
        covered += a > 0.0 ? 1 : 0;
        sum += vec4(mix(clear_e, mvr_linear_to_srgb(mvr_post_display(s)), a), a + mvr_clear_out.a * (1.0 - a));
    }
    if (covered == 0)
        discard; // the clear the pass made before: the plain frame's bytes
    vec4 c = sum / float(n);
    c.rgb = mvr_srgb_decode(c.rgb); // back to linear (the output encodes again)
#elif defined(MVR_DOWNSAMPLE) && !defined(MVR_LOG_LUMINANCE)
    // a plain frame's resolve: the mean of linear light; the samples'
    // alpha says where a surface is (0: the clear, which the pass keeps)
    ivec2 base = ivec2(gl_FragCoord.xy) * mvr_factor;
    vec4 sum = vec4(0.0);
    int covered = 0;
    for (int y = 0; y < mvr_factor; ++y)
        for (int x = 0; x < mvr_factor; ++x) {
            vec4 s = texelFetch(mvr_source, ivec3(base + ivec2(x, y), v_layer), 0);
            float a = clamp(s.a, 0.0, 1.0);
            covered += a > 0.0 ? 1 : 0;
            sum += vec4(s.rgb, a + mvr_clear_out.a * (1.0 - a));
        }
    if (covered == 0)
        discard;
    vec4 c = sum / float(mvr_factor * mvr_factor);
#elif defined(MVR_DOWNSAMPLE) // metering: the mean of the linear samples
    ivec2 base = ivec2(gl_FragCoord.xy) * mvr_factor;
    vec4 sum = vec4(0.0);
    for (int y = 0; y < mvr_factor; ++y)
        for (int x = 0; x < mvr_factor; ++x)
            sum += texelFetch(mvr_source, ivec3(base + ivec2(x, y), v_layer), 0);
    vec4 c = sum / float(mvr_factor * mvr_factor);
#elif defined(MVR_POST) || defined(MVR_LOG_LUMINANCE)
    vec4 c = texelFetch(mvr_source, ivec3(ivec2(gl_FragCoord.xy), v_layer), 0);
#else
    vec4 c = textureLod(mvr_source, vec3(v_uv, float(v_layer)), 0.0);
#endif
#ifdef MVR_LOG_LUMINANCE
    // Rec. 709 luminance: r = log2 of it, g = 1 where a surface was drawn
    // and lit (the mean of r over the mean of g is the average over those:
    // the clear color and the environment background, which leave the
    // depth cleared, do not move the exposure)
    float l = dot(max(c.rgb, vec3(0.0)), vec3(0.2126, 0.7152, 0.0722));
#ifdef MVR_DOWNSAMPLE
    float depth = texelFetch(mvr_depth, ivec3(ivec2(gl_FragCoord.xy) * mvr_factor, v_layer), 0).r;
#else
    float depth = texelFetch(mvr_depth, ivec3(ivec2(gl_FragCoord.xy), v_layer), 0).r;
#endif
    bool drawn = depth != mvr_clear_depth;  // the background (clear color) is no subject
    o_color = l > 1e-6 && drawn ? vec4(log2(l), 1.0, 0.0, 1.0) : vec4(0.0, 0.0, 0.0, 1.0);
    return;
#endif
#if defined(MVR_POST) && !defined(MVR_DOWNSAMPLE) && !defined(MVR_POST_MSAA)
    {
        float a = clamp(c.a, 0.0, 1.0);
        if (a == 0.0)
            discard; // the clear the pass made before: exact, no exposure, tone map, encode or dither
        c.rgb = mvr_post_display(c);
        if (a < 1.0) // a translucent surface over the clear: composited in display values
            c.rgb = mvr_srgb_decode(mix(mvr_linear_to_srgb(mvr_clear_linear()), mvr_linear_to_srgb(c.rgb), a));
        c.a = a + mvr_clear_out.a * (1.0 - a);
    }
#endif
#ifdef MVR_SRGB_ENCODE
    c.rgb = mvr_linear_to_srgb(c.rgb);
#endif
#ifdef MVR_DITHER
    // +-1 8-bit step, triangular (two uniform hashes of the pixel), added to
    // the encoded value, so gradients do not band; off by default: it breaks
    // byte comparisons. An sRGB-format output encodes in the GL: the noise
    // goes through the encoding and back.
    vec2 p = gl_FragCoord.xy + float(v_layer) * vec2(17.0, 59.0);
    float n0 = fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453);
    float n1 = fract(sin(dot(p, vec2(39.3468, 11.135))) * 24634.6345);
    vec3 noise = vec3((n0 + n1 - 1.0) / 255.0);
#ifdef MVR_SRGB_ENCODE
    c.rgb = clamp(c.rgb + noise, 0.0, 1.0);
#else
    vec3 e = clamp(mvr_linear_to_srgb(c.rgb) + noise, 0.0, 1.0);
    c.rgb = mix(pow((e + 0.055) / 1.055, vec3(2.4)), e / 12.92, vec3(lessThanEqual(e, vec3(0.04045))));
#endif
#endif
    o_color = c;
}
