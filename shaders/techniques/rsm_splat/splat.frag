// One VPL's splat: radiance rho_s / pi * Phi_j <N_j,-l><N_s,l> / (pi r^2 + A_j) (Eq. 4.1, as the
// gather), additively blended; with u_radius > 0 pixels farther than u_radius from the VPL get nothing
// (the reduced-overdraw splat, which darkens the image as the radius shrinks, §2.10.1).
// Host uniforms: u_radius. Inputs: G-buffer, Vpl[] (BINDING_SSBO_TECH0). Output: radiance (blend ONE, ONE).
#include "common/gbuffer.glsl"
#include "techniques/nichols/vpl.glsl"
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer VplBlock { Vpl u_vpls[]; };
uniform float u_radius;
flat in int v_vpl;
layout(location = 0) out vec4 o_radiance;

void main() {
    Surface s = readSurface(ivec2(gl_FragCoord.xy));
    Vpl v = u_vpls[v_vpl];
    vec3 d = v.position.xyz - s.position;
    if (!s.covered || (u_radius > 0.0 && dot(d, d) > u_radius * u_radius)) discard;
    o_radiance = vec4((1.0 - s.metallic) * s.albedo / 3.14159265358979 * vplIrradiance(v, s.position, s.normal, true, 0.0), 0.0);
}
