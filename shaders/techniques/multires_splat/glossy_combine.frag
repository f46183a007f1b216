// Mode A's glossy shading (Nichols 2010 §3.2.3.1): adds the upsampled glossy radiance (level 0 of the
// second multiresolution buffer) to the indirect target, blended ONE, ONE after combine.frag wrote
// the Lambert part; Eq. 3.3's detail factor scales it as it scales the Lambert part.
// With the indirect-resolution cap (u_scale > 1), upsampled as the Lambert part (output_upsample.glsl).
// Host uniforms: u_detailAlpha, u_scale. Inputs: G-buffer, u_frame, glossy result (BINDING_TEX_TECH0).
// Output: indirect radiance W/(m^2 sr) (added).
#include "common/gbuffer.glsl"
#include "common/frame.glsl"
#include "techniques/nichols/output_upsample.glsl"
uniform float u_detailAlpha;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_glossy;
layout(location = 0) out vec4 o_radiance;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    Surface s = readSurface(p);
    vec3 view = normalize(u_frame.eyePosition.xyz - s.position);
    float detail = u_detailAlpha * max(dot(view, s.normal), 0.0) + (1.0 - u_detailAlpha);
    o_radiance = vec4(s.covered ? upsampledIrradiance(s_glossy, p) * detail : vec3(0.0), 0.0);
}
