// full = direct + indirect (linear radiance). Inputs: s_direct (BINDING_TEX_INPUT0), s_indirect
// (BINDING_TEX_INPUT1). Output: RGBA32F radiance.
layout(binding = BINDING_TEX_INPUT0) uniform sampler2D s_direct;
layout(binding = BINDING_TEX_INPUT1) uniform sampler2D s_indirect;
layout(location = 0) out vec4 o_radiance;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    o_radiance = vec4(texelFetch(s_direct, p, 0).rgb + texelFetch(s_indirect, p, 0).rgb, 1.0);
}
