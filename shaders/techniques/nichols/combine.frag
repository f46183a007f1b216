// Final indirect radiance of the multiresolution techniques: the upsampled irradiance of level 0 times
// the pixel's diffuse albedo / pi (Lambertian receivers, Eq. 4.5's rho_i).
// Inputs: G-buffer, level-0 result (BINDING_TEX_TECH0). Output: indirect radiance W/(m^2 sr).
#include "common/gbuffer.glsl"
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_result;
layout(location = 0) out vec4 o_radiance;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    Surface s = readSurface(p);
    vec4 e = texelFetch(s_result, ivec3(p, 0), 0);
    o_radiance = vec4(s.covered ? (1.0 - s.metallic) * s.albedo / 3.14159265358979 * e.rgb : vec3(0.0), 1.0);
}
