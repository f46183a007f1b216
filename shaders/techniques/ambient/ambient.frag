// Constant ambient term: reflected radiance = diffuse albedo * L_a (uniform incident radiance L_a
// integrated against the Lambert BRDF over the hemisphere). Inputs: G-buffer, u_ambientRadiance.
// Output: indirect radiance, RGBA32F.
#include "common/gbuffer.glsl"
uniform float u_ambientRadiance;
layout(location = 0) out vec4 o_radiance;
void main() {
    Surface s = readSurface(ivec2(gl_FragCoord.xy));
    vec3 radiance = s.covered ? (1.0 - s.metallic) * s.albedo * u_ambientRadiance : vec3(0.0);
    o_radiance = vec4(radiance, 1.0);
}
