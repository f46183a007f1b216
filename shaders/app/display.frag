// Viewer output: shows one image or debug view in the current viewport (the viewer letterboxes it to
// the image's aspect). The default framebuffer is not sRGB, so encoding happens here.
// Inputs: s_image (BINDING_TEX_INPUT0, 2D views) or s_layers (BINDING_TEX_INPUT1, one layer of a 2D
// array such as the RSM), u_array/u_layer choosing; u_encoding (techniques/Technique.h DebugEncoding:
// 0 radiance, 1 normal, 2 position, 3 colour, 4 scalar), u_scale, u_exposure (EV), u_curve;
// s_overlay (BINDING_TEX_INPUT2), the FLIP heat map as display colours, mixed in by u_overlay.
// Output: display colour.
#include "common/tonemap.glsl"
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_image;
layout(binding = BINDING_TEX_INPUT1) uniform sampler2DArray s_layers;
layout(binding = BINDING_TEX_INPUT2) uniform sampler2D s_overlay;
uniform float u_exposure;
uniform int u_curve;
uniform int u_encoding;
uniform float u_scale;
uniform int u_array;
uniform float u_layer;
uniform float u_overlay;
in vec2 v_uv;
layout(location = 0) out vec4 o_color;

// Scalar ramp for debug views: blue (0) through green to red (1), the colours photon-splat's overlap
// view uses; not the error heat map's (that one comes precomputed from metrics/Heatmap.h).
vec3 ramp(float t) {
    t = clamp(t, 0.0, 1.0);
    return clamp(vec3(2.0 * t - 0.5, 1.0 - abs(2.0 * t - 1.0), 1.5 - 2.0 * t), 0.0, 1.0);
}

void main() {
    vec4 t = u_array != 0 ? texture(s_layers, vec3(v_uv, u_layer)) : texture(s_image, v_uv);
    vec3 c;
    if (u_encoding == 1) c = 0.5 + 0.5 * t.xyz;
    else if (u_encoding == 2) c = fract(t.xyz);
    else if (u_encoding == 3) c = srgbEncode(t.rgb);
    else if (u_encoding == 4) c = ramp(t.r / u_scale);
    else c = toDisplay(t.rgb * u_scale, u_exposure, u_curve);
    if (u_overlay > 0.0) c = mix(c, texture(s_overlay, v_uv).rgb, u_overlay);
    o_color = vec4(c, 1.0);
}
