// Optional VPL-to-receiver visibility of the RSM-family gathers (rsm, isr, hisr, multires-splat), beyond
// Nichols (2010) ch. 3-4, whose gathers have none: the segment from the receiver to the VPL, both ends
// moved off their surfaces along their normals by u_rayBias slice depths (the origin bias of §5.3.3.1),
// is tested in the screen-space voxelization of the view (ch. 5, §5.3.3; march.glsl) column by column
// (voxelTrace, the default) or at u_raySteps uniform samples (voxelMarch, the thesis's march), and the
// VPL counts only if the segment is free. Binary, as the thesis's per-VPL visibility bits.
// Host define VPL_VISIBILITY (VplVisibility::defines): 0 off, 1 column traversal, 2 uniform samples. A
// define, not a uniform: llvmpipe runs a branch's loops under an execution mask even when no lane takes
// it, so an unused march still spent loop iterations of the shader loop budget (gpu/ShaderLimits.h) and
// the every-texel gathers lost VPLs with visibility off; kVplVisibility is a constant the compiler
// removes the test with. Host uniforms (VplVisibility::setUniforms): u_raySteps, u_rayThickness,
// u_rayBias (slice depths). Inputs: the grid (march.glsl). Outputs: ray counters
// (BINDING_SSBO_VOXEL_RAYS) as 64-bit sums, added once per invocation by countVplRays.
#include "techniques/screen_voxels/march.glsl"
#ifndef VPL_VISIBILITY
#define VPL_VISIBILITY 0
#endif
const bool kVplVisibility = VPL_VISIBILITY != 0;
uniform int u_raySteps;
uniform int u_rayThickness;
uniform float u_rayBias;
layout(std430, binding = BINDING_SSBO_VOXEL_RAYS) buffer VoxelRayBlock {
    uint u_raysMarchedLow;
    uint u_raysMarchedHigh;
    uint u_raysBlockedLow;
    uint u_raysBlockedHigh;
};

// 1.0 if receiver x (unit normal n) sees the VPL at p (unit normal np) in the voxel grid, else 0.0;
// rays.x counts the segments marched, rays.y the blocked ones.
float vplVisible(vec3 x, vec3 n, vec3 p, vec3 np, inout uvec2 rays) {
    float bias = u_rayBias * u_voxels.depth.w;
    vec3 a = x + bias * n, b = p + bias * np;
#if VPL_VISIBILITY == 2
    bool free = voxelMarch(a, b, u_raySteps, u_rayThickness) >= 1.0;
#else
    bool free = voxelTrace(a, b, u_rayThickness, true) >= 1.0;
#endif
    rays += uvec2(1u, free ? 0u : 1u);
    return free ? 1.0 : 0.0;
}

// Adds an invocation's counts to the 64-bit sums (each adder detects its own wrap of the low word, as
// hisr's node counter).
void countVplRays(uvec2 rays) {
    if (!kVplVisibility || rays.x == 0u) return;
    uint before = atomicAdd(u_raysMarchedLow, rays.x);
    if (before > 0xFFFFFFFFu - rays.x) atomicAdd(u_raysMarchedHigh, 1u);
    if (rays.y == 0u) return;
    before = atomicAdd(u_raysBlockedLow, rays.y);
    if (before > 0xFFFFFFFFu - rays.y) atomicAdd(u_raysBlockedHigh, 1u);
}
