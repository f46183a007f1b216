// refinePass=compute's control block (BINDING_SSBO_TECH3), shared by refine.comp and refine_reset.comp:
// per ping-pong side the next pass's dispatch size (groups x, regions, rows z of x groups), then per side and region (list)
// a DrawArraysIndirectCommand whose count is the list's length, which the splat draws indirectly.
struct DrawCommand {
    uint count;
    uint instanceCount;
    uint first;
    uint baseInstance;
};
layout(std430, binding = BINDING_SSBO_TECH3) buffer ControlBlock {
    uvec4 u_groups[2];
    DrawCommand u_commands[];  // [side * u_regions + region]
};
