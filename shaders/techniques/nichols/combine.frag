// Final indirect radiance of the multiresolution techniques: the upsampled irradiance of level 0 times
// the pixel's diffuse albedo / pi (Lambertian receivers, Eq. 4.5's rho_i), optionally with Eq. 3.3's
// detail modulation c_out = c * (alpha <V, N> + (1 - alpha)) (§3.3.3; u_detailAlpha = 0 disables it).
// With the indirect-resolution cap (u_scale > 1) the result is upsampled to the output size first
// (output_upsample.glsl: empty-aware bilinear).
// Host uniforms: u_detailAlpha, u_scale. Inputs: G-buffer, u_frame, level-0 result (BINDING_TEX_TECH0).
// Output: indirect radiance W/(m^2 sr).
#include "common/gbuffer.glsl"
#include "common/frame.glsl"
#include "techniques/nichols/output_upsample.glsl"
uniform float u_detailAlpha;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_result;
layout(location = 0) out vec4 o_radiance;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    Surface s = readSurface(p);
    vec3 e = upsampledIrradiance(s_result, p);
    vec3 view = normalize(u_frame.eyePosition.xyz - s.position);
    float detail = u_detailAlpha * max(dot(view, s.normal), 0.0) + (1.0 - u_detailAlpha);
    o_radiance = vec4(s.covered ? (1.0 - s.metallic) * s.albedo / 3.14159265358979 * e * detail : vec3(0.0), 1.0);
}
