// gatherPass=compute: the gather's indirect dispatch size from the cell count (one invocation per
// cell, cell_gather.glsl's 64-wide groups), so the count never comes back to the CPU (issue 18).
layout(local_size_x = 1) in;
layout(std430, binding = BINDING_SSBO_TECH2) readonly buffer CellListBlock { uint u_cellCount; };
layout(std430, binding = BINDING_SSBO_TECH3) writeonly buffer DispatchBlock { uvec3 u_groups; };
void main() {
    u_groups = uvec3((u_cellCount + 63u) / 64u, 1u, 1u);
}
