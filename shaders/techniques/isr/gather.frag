// Stencilled multiresolution gather (Nichols 2010 §4.2.1.2, checklist item 12): a fragment of level
// k that passed the stencil set-up represents the eye-space patch of its cell (mean position and
// normal of the covered pixels below it, an assumption: the thesis does not say) and sums every VPL
// of the cache with the disk-to-point form factor (Eq. 4.1) and Eq. 4.5:
//   E_i = sum_j Phi_j <N_i, V_ij> <N_j, V_ji> / (pi ||V_ij||^2 + A_j)
// where Phi_j = rho_j I omega_j (Eqs. 4.2-4.4 with the exact texel solid angle). The atlas stores the
// irradiance E_i (W/m^2, alpha 1 = rendered here); the pixel's own albedo multiplies it at the end,
// which keeps texture detail under coarse patches.
// One draw sums the VPLs [u_vplFirst, min(u_vplEnd, count)); the host adds the draws (blending) so that
// no invocation loops past the shader loop budget (gpu/ShaderLimits.h).
// VPL_VISIBILITY (host define; beyond the thesis, off by default): each VPL's term times the voxel-march visibility
// of the segment from the cell's patch to the VPL (screen_voxels/vpl_visibility.glsl).
// Host uniforms: u_level, u_levelOrigin, u_vplFirst, u_vplEnd, u_windowFirst, vpl_visibility.glsl's. Inputs: eye pyramid
// (BINDING_TEX_TECH0, TECH1), the window of VPLs from u_windowFirst (vpl_window.glsl)
// and the VPL count (BINDING_SSBO_TECH1), the voxel grid when
// visibility is on. Output: atlas RGBA32F; ray counters.
#include "techniques/nichols/atlas.glsl"
#include "techniques/nichols/vpl.glsl"
#include "techniques/nichols/vpl_window.glsl"
#include "techniques/screen_voxels/vpl_visibility.glsl"
// Only the stencilled cells of the level rectangle may run the loop. This shader has no side effects,
// so GL already allows the stencil test before it (llvmpipe does it: same frame time with and without
// the qualifier); the qualifier makes it required, so a counter added here later cannot silently turn
// the culling off as it did in hisr's gather (see that file). Safe: no discard, no gl_FragDepth, KEEP.
layout(early_fragment_tests) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_normal;
layout(std430, binding = BINDING_SSBO_TECH1) readonly buffer VplCountBlock { uint u_vplCount; };
uniform uint u_vplFirst;
uniform uint u_windowFirst;  // the record u_vplWindow[0] holds
uniform uint u_vplEnd;
layout(location = 0) out vec4 o_irradiance;

void main() {
    ivec3 cell = ivec3(ivec2(gl_FragCoord.xy) - u_levelOrigin, 0);
    vec4 g = texelFetch(s_geometry, cell, u_level);
    vec3 x = g.xyz / g.w;
    vec3 n = normalize(texelFetch(s_normal, cell, u_level).xyz + vec3(0.0, 0.0, 1e-12));
    vec3 irradiance = vec3(0.0);
    uvec2 rays = uvec2(0u);
    uint end = min(u_vplEnd, u_vplCount);
    for (uint j = u_vplFirst; j < end; ++j) {
        Vpl v = u_vplWindow[j - u_windowFirst];
        if (v.position.w < 0.5) continue;
        vec3 e = vplIrradiance(v, x, n, true, 0.0);
        if (kVplVisibility && any(greaterThan(e, vec3(0.0)))) e *= vplVisible(x, n, v.position.xyz, v.normal.xyz, rays);
        irradiance += e;
    }
    countVplRays(rays);
    o_irradiance = vec4(irradiance, 1.0);
}
