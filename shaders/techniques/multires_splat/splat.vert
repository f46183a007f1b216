// Subsplat splatting (Nichols 2010 §3.2.4): every subsplat of the shared list is drawn as a GL point
// once per VPL (instance; mode A: each subsplat once, its VPL in w), at its texel of the flattened
// multiresolution buffer.
// VPL_VISIBILITY (host define; beyond the thesis, off by default): the voxel-march visibility of the segment from the
// subsplat's patch to the VPL (screen_voxels/vpl_visibility.glsl), which splat.frag multiplies E by: each
// point is one subsplat-VPL pair, the per-receiver per-VPL evaluation the gathers have in their loops.
// Tested here, once per point, rather than in the fragment shader, where llvmpipe shades a point's
// pixel as a 2x2 quad and its three helper invocations marched too (measured per 128^2 frame on
// furnished-room: 9.7 s there, 3.2 s here, docs/techniques/multires-splat.md).
// Host uniforms: u_origins[level] (atlas texel of each level's origin), u_atlasSize, u_perVpl,
// u_minDistance2, u_diskForm and vpl_visibility.glsl's. Inputs: attribute 0 = ivec4 (level, x, y, VPL in mode A),
// gl_InstanceID = VPL index (mode B); subsplat.glsl's and, with visibility, the voxel grid.
// Outputs: point, level, cell, VPL, visibility; ray counters; subsplats per level (BINDING_SSBO_TECH1,
// Table 3.1's counts: one count per list entry, so mode B counts instance 0 only), read by the host
// after the frame is queued rather than by reading the list back on the frame's path (issue 18).
#include "techniques/multires_splat/subsplat.glsl"
#include "techniques/screen_voxels/vpl_visibility.glsl"
layout(location = 0) in ivec4 a_subsplat;
uniform ivec2 u_origins[16];
uniform ivec2 u_atlasSize;
uniform bool u_perVpl;
flat out ivec4 v_subsplat;
flat out int v_vpl;
flat out float v_visibility;
layout(std430, binding = BINDING_SSBO_TECH1) buffer LevelCountBlock { uint u_subsplatsPerLevel[]; };
void main() {
    if (u_perVpl || gl_InstanceID == 0) atomicAdd(u_subsplatsPerLevel[a_subsplat.x], 1u);
    v_subsplat = a_subsplat;
    v_vpl = u_perVpl ? a_subsplat.w : gl_InstanceID;
    v_visibility = 1.0;
    if (kVplVisibility) {
        Patch p = subsplatPatch(a_subsplat.x, a_subsplat.yz);
        Vpl v = u_vpls[v_vpl];
        if (any(greaterThan(patchIrradiance(p, v), vec3(0.0)))) {
            uvec2 rays = uvec2(0u);
            v_visibility = vplVisible(p.position, p.normal, v.position.xyz, v.normal.xyz, rays);
            countVplRays(rays);
        }
    }
    vec2 texel = vec2(u_origins[a_subsplat.x] + a_subsplat.yz) + 0.5;
    gl_Position = vec4(texel / vec2(u_atlasSize) * 2.0 - 1.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
