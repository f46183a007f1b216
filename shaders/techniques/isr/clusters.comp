// Multiresolution VPL clusters of basic image-space radiosity (Nichols 2010 §4.2.2, checklist item
// 13): one invocation per cell of the finest light level f (a dense sampling of the RSM); each finds
// the level k >= f at which its light-space patch is valid (no refinement at k, refined parent, as
// the eye-space stencil rule), and only the first cell of each valid patch writes one VPL (vpl.glsl
// patchVpl: on the RSM sample at the patch's centre, with the patch's summed flux and area, so omega_j
// grows with the patch, Eqs. 4.2-4.3).
// Appends to the VPL cache with an atomic counter.
// Host uniforms: u_finest (level f), u_coarsest, u_levelSize[level] (the pyramid's level sizes: the walk's
// level differs between invocations, and textureSize with such a level returns the first SIMD lane's
// size on llvmpipe, stale when that lane has left the loop). Inputs: light pyramid (BINDING_TEX_TECH0..3).
// Outputs: Vpl[] (BINDING_SSBO_TECH0), count (BINDING_SSBO_TECH1).
#include "techniques/nichols/vpl.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_normal;
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_flux;
layout(binding = BINDING_TEX_TECH3) uniform sampler2DArray s_refine;
layout(std430, binding = BINDING_SSBO_TECH0) writeonly buffer VplBlock { Vpl u_vpls[]; };
layout(std430, binding = BINDING_SSBO_TECH1) buffer VplCountBlock { uint u_vplCount; };
uniform int u_finest;
uniform int u_coarsest;
uniform ivec2 u_levelSize[16];

bool refined(ivec2 cell, int level, int layer) {
    return texelFetch(s_refine, ivec3(cell, layer), level).r > 0.5;
}

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID.xyz);
    ivec2 size = u_levelSize[u_finest];
    if (any(greaterThanEqual(id.xy, size))) return;
    ivec2 cell = id.xy;
    int level = u_finest;
    // Walk up while the parent is not refined: the valid level is the coarsest unrefined ancestor.
    while (level < u_coarsest) {
        ivec2 parentSize = u_levelSize[level + 1];
        ivec2 parent = min(cell / 2, parentSize - 1);
        if (refined(parent, level + 1, id.z)) break;
        cell = parent;
        level += 1;
    }
    // The first fine cell under the patch writes it (odd-sized levels give the last cell 3 children).
    ivec2 first = cell;
    for (int k = level; k > u_finest; --k) first *= 2;
    if (first != id.xy) return;
    vec4 g = texelFetch(s_geometry, ivec3(cell, id.z), level);
    vec4 f = texelFetch(s_flux, ivec3(cell, id.z), level);
    if (g.w <= 0.0 || max(f.r, max(f.g, f.b)) <= 0.0) return;
    Vpl v = patchVpl(s_geometry, s_normal, ivec3(cell, id.z), level, g, f);
    uint index = atomicAdd(u_vplCount, 1u);
    u_vpls[index] = v;
}
