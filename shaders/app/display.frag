// Viewer output: shows one image or debug view in the current viewport (the viewer letterboxes it to
// the image's aspect). The default framebuffer is not sRGB, so encoding happens here.
// Inputs: s_image (BINDING_TEX_INPUT0, 2D views) or s_layers (BINDING_TEX_INPUT1, one layer of a 2D
// array such as the RSM), u_array/u_layer choosing, u_level the mip level; u_encoding
// (techniques/Technique.h DebugEncoding: 0 radiance, 1 normal, 2 position, 3 colour, 4 scalar, 7 ids),
// u_scale, u_exposure (EV), u_curve. Built three times: plain; DISPLAY_IDS, where s_layers is an
// unsigned-integer array (radiosity's ID hemicubes); DISPLAY_MS, where it is a multisampled array
// (the gather's radiosity hemicubes) whose u_samples samples are averaged. One program per sampler
// type, since two sampler types may not share a texture unit in one draw.
// s_overlay (BINDING_TEX_INPUT2), the FLIP heat map as display colours, mixed in by u_overlay.
// Output: display colour.
#include "common/tonemap.glsl"
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_image;
#if defined(DISPLAY_IDS)
layout(binding = BINDING_TEX_INPUT1) uniform usampler2DArray s_layers;
#elif defined(DISPLAY_MS)
layout(binding = BINDING_TEX_INPUT1) uniform sampler2DMSArray s_layers;
uniform int u_samples;
#else
layout(binding = BINDING_TEX_INPUT1) uniform sampler2DArray s_layers;
#endif
layout(binding = BINDING_TEX_INPUT2) uniform sampler2D s_overlay;
uniform float u_exposure;
uniform int u_curve;
uniform int u_encoding;
uniform float u_scale;
uniform int u_array;
uniform float u_layer;
uniform int u_level;
uniform float u_overlay;
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

// Scalar ramp for debug views: blue (0) through green to red (1), the colours photon-splat's overlap
// view uses; not the error heat map's (that one comes precomputed from metrics/Heatmap.h).
vec3 ramp(float t) {
    t = clamp(t, 0.0, 1.0);
    return clamp(vec3(2.0 * t - 0.5, 1.0 - abs(2.0 * t - 1.0), 1.5 - 2.0 * t), 0.0, 1.0);
}

// A distinct, saturated colour per ID (a hash of it); 0 (nothing seen) stays black.
vec3 idColour(uint id) {
    if (id == 0u) return vec3(0.0);
    uint h = id * 2654435761u;  // Knuth's multiplicative hash: neighbouring IDs get unrelated hues
    h ^= h >> 15;
    return 0.25 + 0.75 * vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0;
}

void main() {
#if defined(DISPLAY_IDS)
    const ivec3 size = textureSize(s_layers, u_level);
    const ivec2 texel = min(ivec2(v_uv * vec2(size.xy)), size.xy - 1);
    // Colours, not values: shown as they are whatever u_encoding says.
    vec4 t = vec4(idColour(texelFetch(s_layers, ivec3(texel, int(u_layer)), u_level).r), 1.0);
#elif defined(DISPLAY_MS)
    const ivec2 size = textureSize(s_layers).xy;
    const ivec3 texel = ivec3(min(ivec2(v_uv * vec2(size)), size - 1), int(u_layer));
    vec4 t = vec4(0.0);
    for (int i = 0; i < u_samples; ++i) t += texelFetch(s_layers, texel, i);
    t /= float(max(u_samples, 1));
#else
    vec4 t = u_array != 0 ? textureLod(s_layers, vec3(v_uv, u_layer), float(u_level)) : textureLod(s_image, v_uv, float(u_level));
#endif
    vec3 c;
#if defined(DISPLAY_IDS)
    c = t.rgb;
#else
    if (u_encoding == 1) c = 0.5 + 0.5 * t.xyz;
    else if (u_encoding == 2) c = fract(t.xyz);
    else if (u_encoding == 3) c = srgbEncode(t.rgb);
    else if (u_encoding == 4) c = ramp(t.r / u_scale);
    else c = toDisplay(t.rgb * u_scale, u_exposure, u_curve);
#endif
    if (u_overlay > 0.0) c = mix(c, texture(s_overlay, v_uv).rgb, u_overlay);
    o_color = vec4(c, 1.0);
}
