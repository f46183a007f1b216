// Diffuse gather from the VPLs on the area lights with incremental voxel visibility (Nichols 2010
// §5.3.2 Eq. 5.2 with V, §5.3.3.2; checklist items 19-20). A stencilled cell of level k represents the
// eye-space patch of its covered pixels (mean position and normal, as isr) and sums its VPLs:
//   E = sum_j L_j A_j V(x -> y_j) cos(x->y_j, N_x) cos(y_j->x, N_y) / |x - y_j|^2
// (the irradiance: Eq. 5.2's diffuse form without rho / pi, which the final pass applies per pixel),
// with r^2 kept at or above A / pi near the light (alNearFieldR2: no VPL gives more than pi L).
// Interleaved sampling (Keller & Heidrich 2001, §5.3.3.2 on 2x2 blocks): with 4 subsets the cell of
// parity s = (x & 1) + 2 (y & 1) at its level takes VPLs s, s + 4, s + 8, ... and writes their sum;
// resolve.comp adds the four subsets of a neighbourhood. Visibility per VPL is a bit of the cell's
// bitstream (one bit per VPL of its subset, 128 per layer of an RGBA32UI atlas array): at the coarsest
// level every VPL is ray-marched; at finer levels a VPL's bit is reused when the parent level's tree
// cells of the subset's 3x3 region around the parent (area_common.glsl alWindowRadius: the subset's
// cells within two cells, 4 to 9 of them) agree on it, and re-cast where they disagree or fewer than
// two of them have bits. A VPL the receiver faces away from, or that emits away from it, is not traced
// (bit 0).
// One draw handles VPLs [u_vplBegin, u_vplEnd) of the cell's subset, within bitstream layer u_batch
// (128 VPLs; a draw of part of a layer adds its bits to the earlier draws'), so that any VPL count stays within the shader
// loop budget, gpu/ShaderLimits.h); the host adds the draws (blending).
// visibility=shadow-maps replaces the march by a lookup in the VPL's paraboloid shadow map (the
// baseline of §5.4.6: 1024 rasterized 64^2 maps).
// Host uniforms: u_level, u_levelOrigin, u_parentOrigin, u_parentSize, u_coarsest, u_batch, u_vplBegin,
// u_vplEnd, u_shade.
// Inputs: eye pyramid geometry and normal (BINDING_TEX_TECH0, TECH1), cell flags (TECH2), VPLs
// (BINDING_SSBO_TECH0), the voxel grid (march.glsl). In/out: bitstreams (image BINDING_IMG0),
// counters (BINDING_SSBO_TECH1). Output: subset irradiance W/m^2 (alpha 1 = rendered here).
#include "techniques/nichols/atlas.glsl"
#include "techniques/area_light/area_common.glsl"
#define SV_OUTER_GRID  // rays beyond the camera's frustum are tested in the grid along the lights (voxelOutside)
#include "techniques/screen_voxels/march.glsl"
#include "techniques/paraboloid/paraboloid.glsl"
// The stencil must cull before this shader runs although it stores to images and buffers (GL would
// otherwise run it on every fragment and test afterwards). Safe: no discard, no depth output.
layout(early_fragment_tests) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_normal;
layout(binding = BINDING_TEX_TECH2) uniform usampler2D s_flags;
layout(std430, binding = BINDING_SSBO_TECH0) readonly buffer VplBlock { AreaVplGpu u_vpls[]; };
layout(std430, binding = BINDING_SSBO_TECH1) buffer StatsBlock { uint u_stats[AL_STAT_COUNT]; };
layout(rgba32ui, binding = BINDING_IMG0) uniform uimage2DArray i_bits;
// visibility=shadow-maps: VPL j's paraboloid map is layer j (one-sided lights; normal = the light's).
layout(binding = BINDING_TEX_TECH3) uniform sampler2DArrayShadow s_vplMaps;
uniform ivec2 u_parentOrigin;
uniform ivec2 u_parentSize;
uniform int u_coarsest;
uniform int u_batch;
uniform int u_vplBegin;
uniform int u_vplEnd;
uniform bool u_shade;
layout(location = 0) out vec4 o_irradiance;

void main() {
    ivec2 cell = ivec2(gl_FragCoord.xy) - u_levelOrigin;
    vec4 g = texelFetch(s_geometry, ivec3(cell, 0), u_level);
    vec3 x = g.xyz / g.w;
    vec3 n = normalize(texelFetch(s_normal, ivec3(cell, 0), u_level).xyz + vec3(0.0, 0.0, 1e-12));
    int subsets = int(u_pass.counts.w);
    int perCell = int(u_pass.counts.z);
    int s = alParity(cell, subsets);
    int visibility = int(u_pass.march.w);
    int layerStart = SV_BITS_PER_LAYER * u_batch;
    int first = u_vplBegin, end = min(perCell, min(u_vplEnd, layerStart + SV_BITS_PER_LAYER));

    // The parent level's verdicts on this layer's VPLs: AND and OR over the tree cells of this
    // subset's 3x3 region around the parent.
    uvec4 anyVisible = uvec4(0u), allVisible = uvec4(0xFFFFFFFFu);
    int samples = 0;
    if (visibility == AL_VIS_INCREMENTAL && u_level < u_coarsest) {
        ivec2 p = min(cell / 2, u_parentSize - 1);
        int r = alWindowRadius(subsets);
        for (int i = 0; i < alRegionCells(r); ++i) {
            ivec2 q;
            if (!alSubsetCell(p, r, u_parentSize, subsets, s, i, q)) continue;
            if ((texelFetch(s_flags, u_parentOrigin + q, 0).r & AL_CELL_TREE) == 0u) continue;
            uvec4 b = imageLoad(i_bits, ivec3(u_parentOrigin + q, u_batch));
            anyVisible |= b;
            allVisible &= b;
            ++samples;
        }
    }
    uvec4 agree = samples >= AL_MIN_REGION_SAMPLES ? ~(anyVisible ^ allVisible) : uvec4(0u);

    // Origin bias against self-occlusion ("shadow acne", Fig. 5.12): u_pass.march.z metres along the
    // normal, and the same distance off the emitter at the VPL's end (rayEnd).
    vec3 origin = x + n * u_pass.march.z;
    int steps = int(u_pass.march.x), thickness = int(u_pass.march.y);
    // The bits earlier draws of this layer found (this cell's own texel: no other fragment writes it).
    uvec4 bits = visibility == AL_VIS_INCREMENTAL && first > layerStart ? imageLoad(i_bits, ivec3(gl_FragCoord.xy, u_batch)) : uvec4(0u);
    vec3 irradiance = vec3(0.0);
    uint raysCast = 0u, reused = 0u, culled = 0u;
    for (int m = first; m < end; ++m) {
        AreaVplGpu v = u_vpls[s + subsets * m];
        AreaLightGpu L = u_pass.lights[int(v.position.w)];
        vec3 d = v.position.xyz - x;
        float r2 = max(dot(d, d), 1e-12);
        vec3 l = d * inversesqrt(r2);
        float cosX = dot(n, l), cosY = emitterCosine(L, l);
        float geometry = v.radiance.w * cosX * cosY / alNearFieldR2(r2, v.radiance.w);  // A cos cos / r^2, bounded
        if (cosX <= 0.0 || cosY <= 0.0) {
            ++culled;
            continue;
        }
        int word = (m - layerStart) / 32;
        uint bit = 1u << uint((m - layerStart) % 32);
        bool visible = true;
        if (visibility == AL_VIS_SHADOW_MAPS) {
            // The rasterized baseline: a filtered lookup, so V is fractional at shadow edges.
            float d = sqrt(r2);
            float vis = paraboloidVisibility(s_vplMaps, float(s + subsets * m), -l, d, L.normal.xyz, L.edgeU.xyz / L.edgeU.w,
                                             u_pass.shadow.w, u_pass.shadow.x);
            ++raysCast;
            irradiance += vis * v.radiance.rgb * geometry;
            continue;
        }
        if (visibility != AL_VIS_NONE) {
            if ((agree[word] & bit) != 0u) {
                visible = (anyVisible[word] & bit) != 0u;
                ++reused;
            } else {
                visible = voxelMarch(origin, rayEnd(L, v.position.xyz, x), steps, thickness) >= 1.0;
                ++raysCast;
            }
        }
        if (!visible) continue;
        bits[word] |= bit;
        irradiance += v.radiance.rgb * geometry;
    }
    if (visibility == AL_VIS_INCREMENTAL) imageStore(i_bits, ivec3(gl_FragCoord.xy, u_batch), bits);
    atomicAdd(u_stats[AL_STAT_RAYS_CAST], raysCast);
    atomicAdd(u_stats[AL_STAT_RAYS_REUSED], reused);
    atomicAdd(u_stats[AL_STAT_RAYS_CULLED], culled);
    o_irradiance = vec4(u_shade ? irradiance : vec3(0.0), 1.0);
}
