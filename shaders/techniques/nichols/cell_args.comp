// gatherPass=compute: the gather's indirect dispatch size from the cell count (one invocation per
// cell, cell_gather.glsl's 64-wide groups), so the count never comes back to the CPU (issue 18). The
// groups form a 2D grid of at most u_maxGroupsX columns (GL_MAX_COMPUTE_WORK_GROUP_COUNT[0]: 65,535 in
// GL 4.5 and on llvmpipe; a list of 4.19M cells, a 4K output, passed it: issue 29 #5); cell_gather.glsl
// numbers the groups row by row and its bounds check drops the last row's extra invocations.
// Host uniforms: u_maxGroupsX.
layout(local_size_x = 1) in;
layout(std430, binding = BINDING_SSBO_TECH2) readonly buffer CellListBlock { uint u_cellCount; };
layout(std430, binding = BINDING_SSBO_TECH3) writeonly buffer DispatchBlock { uvec3 u_groups; };
uniform uint u_maxGroupsX;
void main() {
    uint groups = (u_cellCount + 63u) / 64u;
    u_groups = uvec3(min(groups, u_maxGroupsX), (groups + u_maxGroupsX - 1u) / u_maxGroupsX, 1u);
}
