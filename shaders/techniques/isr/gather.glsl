// The stencilled multiresolution gather's per-cell sum (isr/gather.frag: stencilled draw; isr/gather.comp:
// gatherPass=compute, over the cell list). Stencilled multiresolution gather (Nichols 2010 §4.2.1.2, checklist item 12): a fragment of level
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
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_normal;
layout(std430, binding = BINDING_SSBO_TECH1) readonly buffer VplCountBlock { uint u_vplCount; };
uniform uint u_vplFirst;
uniform uint u_windowFirst;  // the record u_vplWindow[0] holds
uniform uint u_vplEnd;

// The irradiance gathered at `cell` of `level` (W/m^2), and the visibility rays it cast.
vec3 gatherCell(ivec2 cellXY, int level, inout uvec2 rays) {
    ivec3 cell = ivec3(cellXY, 0);
    vec4 g = texelFetch(s_geometry, cell, level);
    vec3 x = g.xyz / g.w;
    vec3 n = normalize(texelFetch(s_normal, cell, level).xyz + vec3(0.0, 0.0, 1e-12));
    vec3 irradiance = vec3(0.0);
    uint end = min(u_vplEnd, u_vplCount);
    for (uint j = u_vplFirst; j < end; ++j) {
        Vpl v = u_vplWindow[j - u_windowFirst];
        if (v.position.w < 0.5) continue;
        vec3 e = vplIrradiance(v, x, n, true, 0.0);
        if (kVplVisibility && any(greaterThan(e, vec3(0.0)))) e *= vplVisible(x, n, v.position.xyz, v.normal.xyz, rays);
        irradiance += e;
    }
    return irradiance;
}
