// gatherPass=compute's set-up (the "stencil-setup" timer): instead of marking the atlas stencil, lists
// every cell that gathers (stencil_rule.glsl, the same rule as stencil_setup.frag), one dispatch per
// level, and counts them per level. Why: on llvmpipe a stencilled draw shades 4x4-pixel blocks, so the
// sparse cells of a level waste most SIMD lanes; a compute gather over the list runs full vectors.
// Entry: x | y << 14 | level << 28 (levels < 16, sides < 16384, checked by the host).
// Host uniforms: u_level, u_size (the level's size), u_coarsest. Inputs: eye pyramid geometry and refine
// flags (BINDING_TEX_TECH0, TECH1). Output: the list (BINDING_SSBO_TECH2).
#include "techniques/nichols/stencil_rule.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_refine;
layout(std430, binding = BINDING_SSBO_TECH2) buffer CellListBlock {
    uint u_cellCount;
    uint u_levelCells[16];
    uint u_cells[];
};
uniform int u_level;
uniform ivec2 u_size;
uniform int u_coarsest;

void main() {
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(cell, u_size))) return;
    if (!gathersHere(s_geometry, s_refine, cell, u_level, u_coarsest)) return;
    uint slot = atomicAdd(u_cellCount, 1u);
    atomicAdd(u_levelCells[u_level], 1u);
    u_cells[slot] = uint(cell.x) | (uint(cell.y) << 14) | (uint(u_level) << 28);
}
