// Eq. 3.2 for one subsplat and one VPL (Nichols 2010 §3.2.4), Lambertian receiver handled at the end:
//   E = Phi_l <V_ls, N_l> <V_sl, N_s> / (pi max(|V_ls|^2, r_min^2))
// at the subsplat's patch (mean position and normal of its covered pixels), added into the atlas
// (blend ONE, ONE; alpha counts the VPLs, so alpha > 0 marks a rendered texel for upsampling).
// Host uniforms: u_minDistance2 (m^2). Inputs: eye pyramid (BINDING_TEX_TECH0, TECH1), Vpl[]
// (BINDING_SSBO_TECH0). Output: irradiance W/m^2.
#include "techniques/nichols/vpl.glsl"
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_normal;
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer VplBlock { Vpl u_vpls[]; };
uniform float u_minDistance2;
flat in ivec4 v_subsplat;
flat in int v_vpl;
layout(location = 0) out vec4 o_irradiance;
void main() {
    ivec3 cell = ivec3(v_subsplat.yz, 0);
    int level = v_subsplat.x;
    vec4 g = texelFetch(s_geometry, cell, level);
    vec3 x = g.xyz / g.w;
    vec3 n = normalize(texelFetch(s_normal, cell, level).xyz + vec3(0.0, 0.0, 1e-12));
    Vpl v = u_vpls[v_vpl];
    vec3 e = v.position.w > 0.5 ? vplIrradiance(v, x, n, false, u_minDistance2) : vec3(0.0);
    o_irradiance = vec4(e, 1.0);
}
