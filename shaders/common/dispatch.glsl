// Indices of a 1D compute job dispatched as a 2D grid of work groups (gl::dispatchLinear,
// src/gpu/DispatchGrid.h: rows of at most GL_MAX_COMPUTE_WORK_GROUP_COUNT[0] groups, which GL 4.5
// guarantees only 65,535 of; issue 29 #5). The last row may hold groups past the job: callers
// bounds-check the index against their count. Include it after the layout(local_size_x = ...) declaration
// (gl_WorkGroupSize is declared by it).
uint linearGroup() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }
uint linearInvocation() { return linearGroup() * gl_WorkGroupSize.x + gl_LocalInvocationID.x; }
