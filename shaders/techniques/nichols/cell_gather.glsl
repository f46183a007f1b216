// gatherPass=compute's gather main (include after a technique's gather.glsl, which defines
// vec3 gatherCell(ivec2 cell, int level, inout uvec2 rays)): one invocation per listed cell
// (cell_list.comp), the sum stored in the cell's atlas texel with alpha 1, as the stencilled draw's
// fragment writes it. With u_accumulate (a later batch of the same gather) the sum adds to the texel:
// each texel belongs to one invocation per dispatch, and the host puts a barrier between dispatches.
// Host uniforms: u_levelOrigins (atlas texel of each level's (0,0)), u_accumulate. Inputs: the list
// (BINDING_SSBO_TECH2). Output: the atlas (BINDING_IMG0, RGBA32F).
layout(local_size_x = 64) in;
layout(std430, binding = BINDING_SSBO_TECH2) readonly buffer CellListBlock {
    uint u_cellCount;
    uint u_levelCells[16];
    uint u_cells[];
};
layout(rgba32f, binding = BINDING_IMG0) uniform image2D i_atlas;
uniform ivec2 u_levelOrigins[16];
uniform bool u_accumulate;

void main() {
    // Groups in rows of gl_NumWorkGroups.x (list_args.comp's 2D grid past the x group limit).
    uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
    if (i >= u_cellCount) return;
    uint entry = u_cells[i];
    ivec2 cell = ivec2(entry & 0x3FFFu, (entry >> 14) & 0x3FFFu);
    int level = int(entry >> 28);
    uvec2 rays = uvec2(0u);
    vec3 irradiance = gatherCell(cell, level, rays);
    countVplRays(rays);
    ivec2 texel = u_levelOrigins[level] + cell;
    if (u_accumulate) irradiance += imageLoad(i_atlas, texel).rgb;
    imageStore(i_atlas, texel, vec4(irradiance, 1.0));
}
