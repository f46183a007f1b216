// One VPL's splat: radiance rho_s / pi * Phi_j <N_j,-l><N_s,l> / (pi r^2 + A_j) (Eq. 4.1, as the
// gather), additively blended; with u_radius > 0 pixels farther than u_radius from the VPL get nothing
// (the reduced-overdraw splat, which darkens the image as the radius shrinks, §2.10.1).
// Host uniforms: u_radius, u_windowFirst. Inputs: G-buffer, the VPL window (nichols/vpl_window.glsl: a
// uniform block, read per fragment; an SSBO read is a per-lane loop on llvmpipe). Output: radiance (blend ONE, ONE).
#include "common/gbuffer.glsl"
#include "techniques/nichols/vpl.glsl"
#include "techniques/nichols/vpl_window.glsl"
uniform uint u_windowFirst;  // the record u_vplWindow[0] holds
uniform float u_radius;
flat in int v_vpl;
layout(location = 0) out vec4 o_radiance;

void main() {
    Surface s = readSurface(ivec2(gl_FragCoord.xy));
    Vpl v = u_vplWindow[uint(v_vpl) - u_windowFirst];
    vec3 d = v.position.xyz - s.position;
    if (!s.covered || (u_radius > 0.0 && dot(d, d) > u_radius * u_radius)) discard;
    o_radiance = vec4((1.0 - s.metallic) * s.albedo / 3.14159265358979 * vplIrradiance(v, s.position, s.normal, true, 0.0), 0.0);
}
