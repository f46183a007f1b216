// One iterative refinement pass of multiresolution splatting in compute (refinePass=compute, bounce's
// default; Nichols 2010 §3.2.3, Fig. 3.3): the same decision as the thesis's geometry-shader pass
// (refine.glsl), with the list appended through an atomic counter instead of transform feedback.
// Why: llvmpipe runs vertex and geometry shaders and transform feedback on one thread at draw time,
// compute on all cores; the counts stay on the GPU either way (issue 18).
// One invocation per subsplat of the source list; workgroup row y = list (region) r: mode B has one
// list, mode A one per VPL of the batch, VPL first + r. A list's groups form rows of at most
// u_maxGroupsX (GL_MAX_COMPUTE_WORK_GROUP_COUNT[0], 65,535 in GL 4.5; a 4K output's list of 4.19M+
// subsplats passed it: issue 29 #5) stacked in z, numbered row by row. Region r's entries start at r * u_regionStride
// in both buffers, so each VPL's list is drawn by its own indirect command, in VPL order, and every
// atlas texel adds its VPLs' light in the same order as the transform-feedback lists do.
// Host uniforms: refine.glsl's; u_initial (this pass reads no list: the coarsest level's cells,
// u_coarsestSize), u_coarsest, u_firstVpl, u_regionStride, u_src, u_regions, u_maxGroupsX.
// Inputs: source list (BINDING_SSBO_TECH1), control (BINDING_SSBO_TECH3: per side the next dispatch's
// groups, then per side and region a DrawArraysIndirectCommand whose count is the list's length).
// Output: destination list (BINDING_SSBO_TECH2), the destination side's counts and dispatch groups.
#include "techniques/multires_splat/refine.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = BINDING_SSBO_TECH1) readonly buffer SourceBlock { ivec4 u_source[]; };
layout(std430, binding = BINDING_SSBO_TECH2) writeonly buffer DestinationBlock { ivec4 u_destination[]; };
#include "techniques/multires_splat/refine_control.glsl"
uniform bool u_initial;
uniform ivec2 u_coarsestSize;
uniform int u_coarsest;
uniform int u_firstVpl;
uniform uint u_regionStride;
uniform int u_src;
uniform int u_regions;
uniform uint u_maxGroupsX;

void append(uint region, ivec4 s) {
    uint dst = uint(1 - u_src) * uint(u_regions) + region;
    uint slot = atomicAdd(u_commands[dst].count, 1u);
    u_destination[region * u_regionStride + slot] = s;
    // The next pass's groups g = slot / 64 + 1 as a grid: both maxima are monotone in g, so the
    // largest slot sets both.
    uint g = slot / 64u + 1u;
    atomicMax(u_groups[1 - u_src].x, min(g, u_maxGroupsX));
    atomicMax(u_groups[1 - u_src].z, (g + u_maxGroupsX - 1u) / u_maxGroupsX);
}

void main() {
    uint region = gl_WorkGroupID.y;
    uint i = (gl_WorkGroupID.z * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
    int vpl = u_perVpl ? u_firstVpl + int(region) : 0;
    ivec4 s;
    if (u_initial) {
        if (i >= uint(u_coarsestSize.x * u_coarsestSize.y)) return;
        s = ivec4(u_coarsest, int(i) % u_coarsestSize.x, int(i) / u_coarsestSize.x, vpl);
    } else {
        DrawCommand c = u_commands[uint(u_src) * uint(u_regions) + region];
        if (i >= c.count) return;
        s = u_source[c.first + i];
    }
    int keep = refineStep(s);
    if ((keep & kKeepSelf) != 0) {
        append(region, s);
        return;
    }
    for (int k = 0; k < 4; ++k)
        if ((keep & (1 << k)) != 0) append(region, refineChild(s, k));
}
