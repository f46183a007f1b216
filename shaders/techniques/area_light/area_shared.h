// Multiresolution textured area lights (Nichols 2010 ch. 5; Nichols, Penmatsa & Wyman, UICS-10-01):
// the records shared by C++ and GLSL. vec4/mat4/uvec4 members only (std140/std430 = C++ layout).
#ifndef BOUNCE_AREA_SHARED_H
#define BOUNCE_AREA_SHARED_H

#include "common/shared.h"

#ifdef __cplusplus
namespace bounce::gpu {
#endif

#define AL_MAX_LIGHTS 4   // area lights one frame shades (their VPL grids are concatenated)

// Flags of a multiresolution cell (the flags atlas, R32UI, one texel per cell at its level's place).
#define AL_CELL_TREE 1u      // in the refinement tree: visibility computed here (parent refined or lit discontinuously)
#define AL_CELL_RENDERED 2u  // illumination gathered at this level
#define AL_CELL_REFINE 4u    // children must be rendered: illumination or visibility discontinuity (§5.3.4)

// Counters the gather passes add to (std430 SSBO, uint each).
#define AL_STAT_RAYS_CAST 0
#define AL_STAT_RAYS_REUSED 1
#define AL_STAT_RAYS_CULLED 2   // VPLs facing away from the receiver or the receiver behind them: no ray
#define AL_STAT_LOBE_SAMPLED 3  // specular cells that used the 5x5 lobe-centred texture samples
#define AL_STAT_PARTIAL_VPLS 4  // sum over tree cells of VPLs whose bits disagree in their subset's 3x3 region
#define AL_STAT_TREE_CELLS 5    // cells that computed that sum
#define AL_STAT_EXAMINED_VPLS 6 // sum over tree cells of the VPLs whose subset has two or more cells in the region
#define AL_STAT_COUNT 8

struct AreaLightGpu {
    vec4 centre;    // xyz: centre (m); w: 1 if two-sided
    vec4 edgeU;     // xyz: full edge (m); w: |edgeU|
    vec4 edgeV;     // xyz: full edge (m); w: |edgeV|
    vec4 normal;    // xyz: emitting-side unit normal; w: area (m^2)
    vec4 radiance;  // rgb: radiance before the texture, W/(m^2 sr); w: 1 if textured
    vec4 texture;   // x: texture width, y: height (texels), z: first VPL index, w: VPLs per side
};

struct AreaPassUniforms {
    AreaLightGpu lights[AL_MAX_LIGHTS];
    vec4 counts;      // x: lights, y: VPLs in all, z: VPLs per pixel (VPLs / subsets), w: subsets (1 or 4)
    vec4 march;       // x: steps, y: thickness (bits), z: origin bias (m), w: visibility (AL_VIS_*)
    vec4 refine;      // x: colour threshold (a white receiver's radiance, W/(m^2 sr)), y: bit-count threshold
                      // (VPLs), z: 1 = incremental stencil (§5.3.4), w: unused
    vec4 lobe;        // x: lobe threshold (fraction of the lobe's peak), y: VPLs in a lobe below which the
                      // 5x5 samples are used (9), z: sample-spacing factor, w: camera pixel angle (rad)
    vec4 geometry;    // x: normal-similarity cosine for interleave resolve, y: relative depth tolerance,
                      // z: 1 = specular pass, w: bitstream layers (128 bits each)
    vec4 shadow;      // shadow-map baseline: x depth bias (fraction of far), yz unused, w: far (m)
};

#define AL_VIS_NONE 0         // V = 1 (§5.3.2)
#define AL_VIS_BRUTE 1        // every VPL ray-marched at every cell (§5.3.3.1)
#define AL_VIS_INCREMENTAL 2  // bitstream reuse from the coarser level (§5.3.3.2)
#define AL_VIS_SHADOW_MAPS 3  // one rasterized paraboloid shadow map per VPL (the §5.4.6 baseline)

// One VPL on a light (§5.3.2.1): a 16 x 16 grid cell's centre, its area and its prefiltered radiance.
struct AreaVplGpu {
    vec4 position;  // xyz (m); w: light index
    vec4 radiance;  // rgb: W/(m^2 sr) (texture block average times the light's radiance); w: cell area (m^2)
};

#ifdef __cplusplus
static_assert(sizeof(AreaLightGpu) == 96);
static_assert(sizeof(AreaPassUniforms) == AL_MAX_LIGHTS * 96 + 6 * 16);
static_assert(sizeof(AreaVplGpu) == 32);
}  // namespace bounce::gpu
#endif

#endif
