// splatPrimitive=stencil (mode B): one subsplat-VPL pair per fragment, as splat.frag, but the subsplat
// is the stencilled atlas texel under the fragment and the VPL the instance's (splat_stencil.vert):
//   E_i += Phi_j <N_i, V_ij> <N_j, V_ji> / D   (D = pi r^2 + A_j, Eq. 4.1, or pi max(r^2, r_min^2), Eq. 3.2; additive)
// The stencil test runs before the shader (layout below; no side effect but the ray counters, which must
// not turn the culling off: see hisr/gather.frag). VPL_VISIBILITY: the pair's term times the voxel march.
// Host uniforms: u_level, u_levelOrigin (atlas.glsl), u_windowFirst, u_minDistance2, u_diskForm, vpl_visibility.glsl's.
// Inputs: eye pyramid (BINDING_TEX_TECH0, TECH2), the VPL window (vpl_window.glsl). Output: atlas RGBA32F.
#include "techniques/multires_splat/subsplat.glsl"
#include "techniques/nichols/vpl_window.glsl"
#include "techniques/nichols/atlas.glsl"
#include "techniques/screen_voxels/vpl_visibility.glsl"
layout(early_fragment_tests) in;
uniform uint u_windowFirst;  // the record u_vplWindow[0] holds
flat in uint v_vpl;
layout(location = 0) out vec4 o_irradiance;
void main() {
    Patch p = subsplatGeometry(u_level, ivec2(gl_FragCoord.xy) - u_levelOrigin);
    Vpl v = u_vplWindow[v_vpl - u_windowFirst];
    vec3 e = patchIrradiance(p, v);
    if (kVplVisibility && any(greaterThan(e, vec3(0.0)))) {
        uvec2 rays = uvec2(0u);
        e *= vplVisible(p.position, p.normal, v.position.xyz, v.normal.xyz, rays);
        countVplRays(rays);
    }
    o_irradiance = vec4(e, 1.0);
}
