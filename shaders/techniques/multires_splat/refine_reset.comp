// refinePass=compute: empties the destination side of the refinement's control block before a pass
// (refine.comp): every region's count 0, its first entry at region * u_regionStride, the instance count
// the final list is drawn with (mode B's splat: one instance per VPL; mode A and the stencil marks: 1),
// and the next dispatch's groups (0 x regions x 1, x and z grown by refine.comp).
// Host uniforms: u_side, u_regions, u_regionStride, u_instances. Output: BINDING_SSBO_TECH3.
layout(local_size_x = 64) in;
#include "techniques/multires_splat/refine_control.glsl"
uniform int u_side;
uniform int u_regions;
uniform uint u_regionStride;
uniform uint u_instances;

void main() {
    uint region = gl_GlobalInvocationID.x;
    if (region == 0u) u_groups[u_side] = uvec4(0u, uint(u_regions), 1u, 0u);
    if (region >= uint(u_regions)) return;
    u_commands[uint(u_side) * uint(u_regions) + region] = DrawCommand(0u, u_instances, region * u_regionStride, 0u);
}
