// The indirect dispatch size of a 64-wide compute job over a list a shader appended to (an atomic
// count), so the count never comes back to the CPU (issue 18): gpu/ListDispatch.h. The groups form a
// 2D grid of at most u_maxGroupsX columns (GL_MAX_COMPUTE_WORK_GROUP_COUNT[0]: 65,535 in GL 4.5 and
// on llvmpipe; a 4K output's 4.19M-cell gather list passed it: issue 29 #5); the job numbers its
// groups row by row (dispatch.glsl's linearInvocation) and bounds-checks against min(count, capacity),
// which drops the last row's extra invocations.
// Users: the stencilled gather's cell list (isr, hisr: cell_gather.glsl) and vct's active-voxel lists
// (vct/pass_list.comp).
// Host uniforms: u_maxGroupsX, u_capacity (entries the list holds: appends past it were dropped).
layout(local_size_x = 1) in;
layout(std430, binding = BINDING_SSBO_TECH2) readonly buffer ListCountBlock { uint u_count; };
layout(std430, binding = BINDING_SSBO_TECH3) writeonly buffer DispatchBlock { uvec3 u_groups; };
uniform uint u_maxGroupsX;
uniform uint u_capacity;
void main() {
    uint groups = (min(u_count, u_capacity) + 63u) / 64u;
    u_groups = uvec3(min(groups, u_maxGroupsX), (groups + u_maxGroupsX - 1u) / u_maxGroupsX, 1u);
}
