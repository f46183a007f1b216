// Viewer output: tone-maps a linear radiance texture to the window (the default framebuffer is
// not sRGB, so encoding happens here). Inputs: s_radiance (BINDING_TEX_INPUT0), u_exposure (EV),
// u_curve. Output: display colour.
#include "common/tonemap.glsl"
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_radiance;
uniform float u_exposure;
uniform int u_curve;
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(toDisplay(texture(s_radiance, v_uv).rgb, u_exposure, u_curve), 1.0); }
