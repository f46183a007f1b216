// hisr's per-cell walk, shared by the stencilled draw (hisr/gather.frag) and the compute gather over the
// cell list (hisr/gather.comp, gatherPass=compute). Hierarchical image-space radiosity gather (Nichols 2010 §4.2.4, checklist item 14): every stencilled
// fragment of the multiresolution atlas walks the VPL tree (the light-space min-max pyramid over the
// RSM) from its 16^2 roots, refining a node j while Eq. 4.8 holds,
//   ||V_ij||^2 <= T_l ||V_j||^2,   T_l = 2 (1 - tau) / (3 tau res_l^2),
// with ||V_j|| the node's maximum light distance (max-mipmap, §4.2.4.1), at most u_maxDepth levels
// below the roots, and gathers each accepted node as a VPL (mean position and normal, summed flux and
// area) with the disk-to-point form factor (Eqs. 4.1, 4.5). The light intensity I of Eq. 4.8 is taken
// as 1 (the thesis's normalised colours) and res_l is the node's level resolution (its solid angle).
// The tree is tree.comp's Morton-ordered records (the thesis's re-organised VPL tree).
// One draw walks the roots [u_rootFirst, u_rootEnd) (index = layer * roots per layer + Morton index); the
// host adds the draws (blending) so that no invocation loops past the shader loop budget
// (gpu/ShaderLimits.h) however deep the trees.
// VPL_VISIBILITY (host define; beyond the thesis, off by default): each accepted node's term times the voxel-march
// visibility of the segment from the cell's patch to the node's VPL (screen_voxels/vpl_visibility.glsl).
// Host uniforms: u_level, u_levelOrigin, u_rootLevel, u_maxDepth, u_rootsPerLayer, u_layers, u_levelOffset,
// u_levelSide, u_tau, u_rootFirst, u_rootEnd,
// vpl_visibility.glsl's (the voxel grid and ray counters when visibility is on).
// Inputs: eye pyramid (BINDING_TEX_TECH0, TECH1), the VPL tree (BINDING_TEX_INPUT0, a buffer texture). Outputs: atlas irradiance (alpha 1); counters (BINDING_SSBO_TECH0): visited
// nodes as a 64-bit sum (low word, carries into the high word: at 1024^2, up to 2^20 fragments x 5376
// nodes with the defaults, more than 2^32) and the invocations of this shader (one per fragment
// shaded, summed over the draws).
#include "techniques/nichols/atlas.glsl"
#include "techniques/nichols/vpl.glsl"
#include "techniques/screen_voxels/vpl_visibility.glsl"
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_normal;
layout(binding = BINDING_TEX_INPUT0) uniform samplerBuffer s_tree;  // tree.comp's records, four texels each
layout(std430, binding = BINDING_SSBO_TECH0) buffer GatherCountBlock {
    uint u_nodesLow;
    uint u_nodesHigh;
    uint u_invocations;
};
uniform int u_rootLevel;
uniform int u_maxDepth;
uniform int u_rootFirst;
uniform int u_rootEnd;
uniform int u_rootsPerLayer;  // roots of one layer (a power of four: Morton indices 0 .. u_rootsPerLayer - 1)
uniform int u_layers;
uniform int u_levelOffset[16];  // records before level l (tree.comp)
uniform int u_levelSide[16];    // res_l of Eq. 4.8: level l's side
uniform float u_tau;

// The irradiance gathered at `cell` of `level` (W/m^2), the rays it cast, and the counters above.
vec3 gatherCell(ivec2 cellXY, int level, inout uvec2 rays) {
    ivec3 cell = ivec3(cellXY, 0);
    vec4 g = texelFetch(s_geometry, cell, level);
    vec3 x = g.xyz / g.w;
    vec3 n = normalize(texelFetch(s_normal, cell, level).xyz + vec3(0.0, 0.0, 1e-12));
    vec3 irradiance = vec3(0.0);
    uint visited = 0u;
    int finest = max(u_rootLevel - u_maxDepth, 0);
    // Stackless depth-first walk of each root's quadtree in Morton order: descend to the first child
    // (4m) on refinement, otherwise move to the next sibling (m + 1), climbing (m / 4) while on a last child.
    int rootEnd = min(u_rootEnd, u_layers * u_rootsPerLayer);
    for (int root = u_rootFirst; root < rootEnd; ++root) {
        int layer = root / u_rootsPerLayer;
        int m = root - layer * u_rootsPerLayer;
        int level = u_rootLevel;
        while (true) {
            // The level's nodes per layer: the roots' count times 4 per level below them.
            int index = (u_levelOffset[level] + layer * (u_rootsPerLayer << (2 * (u_rootLevel - level))) + m) * 4;
            ++visited;
            vec4 head = texelFetch(s_tree, index);
            bool refine = false;
            if (head.w >= 0.0 && level > finest) {
                float res = float(u_levelSide[level]);
                float t = 2.0 * (1.0 - u_tau) / (3.0 * u_tau * res * res);
                vec3 d = head.xyz - x;
                refine = dot(d, d) <= t * head.w * head.w;
            }
            if (refine) {
                m *= 4;
                level -= 1;
                continue;
            }
            if (head.w >= 0.0) {
                Vpl v;
                v.position = texelFetch(s_tree, index + 1);
                v.normal = texelFetch(s_tree, index + 2);
                v.flux = texelFetch(s_tree, index + 3);
                vec3 e = vplIrradiance(v, x, n, true, 0.0);
                if (kVplVisibility && any(greaterThan(e, vec3(0.0)))) e *= vplVisible(x, n, v.position.xyz, v.normal.xyz, rays);
                irradiance += e;
            }
            while (level < u_rootLevel && (m & 3) == 3) {
                m >>= 2;
                level += 1;
            }
            if (level == u_rootLevel) break;
            m += 1;
        }
    }
    // Each adder detects its own wrap of the low word (old + visited >= 2^32), so the pair is exact.
    uint before = atomicAdd(u_nodesLow, visited);
    if (before > 0xFFFFFFFFu - visited) atomicAdd(u_nodesHigh, 1u);
    atomicAdd(u_invocations, 1u);
    return irradiance;
}
