// Full-resolution RSM gather (the baseline of Nichols 2010 §4.3 / Fig. 4.8; Dachsbacher & Stamminger
// 2005): every pixel sums every VPL of the cache, without visibility.
//   L_indirect = rho_s / pi * sum_j Phi_j <N_j, -l> <N_s, l> / D_j
// with D_j = pi * max(r^2, r_min^2) (Eq. 3.2) or pi * r^2 + A_j (Eq. 4.1, disk-to-point).
// Host uniforms: u_vplCount, u_diskForm, u_minDistance2 (m^2). Inputs: G-buffer, Vpl[] (BINDING_SSBO_TECH0).
// Output: indirect radiance W/(m^2 sr), RGBA32F.
#include "common/gbuffer.glsl"
#include "techniques/nichols/vpl.glsl"
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer VplBlock { Vpl u_vpls[]; };
uniform int u_vplCount;
uniform bool u_diskForm;
uniform float u_minDistance2;
layout(location = 0) out vec4 o_radiance;

void main() {
    Surface s = readSurface(ivec2(gl_FragCoord.xy));
    if (!s.covered) {
        o_radiance = vec4(0.0);
        return;
    }
    vec3 irradiance = vec3(0.0);
    for (int j = 0; j < u_vplCount; ++j) {
        Vpl v = u_vpls[j];
        if (v.position.w < 0.5) continue;
        irradiance += vplIrradiance(v, s.position, s.normal, u_diskForm, u_minDistance2);
    }
    o_radiance = vec4((1.0 - s.metallic) * s.albedo / 3.14159265358979 * irradiance, 1.0);
}
