// Two per-level steps after the diffuse gather of level k (Nichols 2010 §5.3.3.2):
// 1. Interleaved-sampling reconstruction (Keller & Heidrich 2001, 2x2 blocks): a rendered cell's
//    irradiance is the sum over the 4 VPL subsets of each subset's value, taken as the mean over the
//    rendered cells of that parity in the cell's 3x3 neighbourhood that lie on the same surface (normal
//    cosine above u_pass.geometry.x, plane distance within u_pass.geometry.y of the eye distance). A
//    subset no such neighbour has is replaced by scaling the others by 4 / subsets found. The thesis
//    does not describe its reconstruction; this edge-aware one is an assumption.
// 2. The bit-count refinement metric: for each tree cell, the VPLs whose bits disagree among the
//    tree cells of their subset's 3x3 region around it (the subset's cells within two cells,
//    alWindowRadius; "partially visible"); at least u_pass.refine.y of them (thesis: 128 of 256,
//    "at least half the VPLs") flags the cell for refinement (AL_CELL_REFINE).
// Host uniforms: u_level, u_levelOrigin, u_size, u_resolve (interleaving on), u_bitCount (metric on).
// Inputs: subset sums (BINDING_TEX_TECH0, atlas copy), eye pyramid geometry and normal (TECH1, TECH2),
// bitstreams (image BINDING_IMG2), u_frame. In/out: atlas (image BINDING_IMG0), flags (image
// BINDING_IMG1), counters (BINDING_SSBO_TECH1).
#include "techniques/area_light/area_common.glsl"
#include "techniques/screen_voxels/screen_voxels_shared.h"
#include "common/frame.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = BINDING_TEX_TECH0) uniform sampler2D s_subsets;
layout(binding = BINDING_TEX_TECH1) uniform sampler2DArray s_geometry;
layout(binding = BINDING_TEX_TECH2) uniform sampler2DArray s_normal;
layout(rgba32f, binding = BINDING_IMG0) writeonly uniform image2D i_atlas;
layout(r32ui, binding = BINDING_IMG1) uniform uimage2D i_flags;
layout(rgba32ui, binding = BINDING_IMG2) readonly uniform uimage2DArray i_bits;
layout(std430, binding = BINDING_SSBO_TECH1) buffer StatsBlock { uint u_stats[AL_STAT_COUNT]; };
uniform int u_level;
uniform ivec2 u_levelOrigin;
uniform ivec2 u_size;
uniform bool u_resolve;
uniform bool u_bitCount;

void main() {
    ivec2 c = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(c, u_size))) return;
    uint flags = imageLoad(i_flags, u_levelOrigin + c).r;
    if ((flags & AL_CELL_TREE) == 0u) return;
    vec4 g = texelFetch(s_geometry, ivec3(c, 0), u_level);
    vec3 x = g.xyz / g.w;
    vec3 n = normalize(texelFetch(s_normal, ivec3(c, 0), u_level).xyz + vec3(0.0, 0.0, 1e-12));
    float tolerance = u_pass.geometry.y * length(u_frame.eyePosition.xyz - x);

    if (u_resolve && (flags & AL_CELL_RENDERED) != 0u) {
        vec3 sum[4] = vec3[4](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
        float count[4] = float[4](0.0, 0.0, 0.0, 0.0);
        for (int i = 0; i < alRegionCells(1); ++i) {
            ivec2 q;
            if (!alRegionCell(c, 1, u_size, i, q)) continue;
            if ((imageLoad(i_flags, u_levelOrigin + q).r & AL_CELL_RENDERED) == 0u) continue;
            vec4 gq = texelFetch(s_geometry, ivec3(q, 0), u_level);
            vec3 xq = gq.xyz / gq.w;
            vec3 nq = normalize(texelFetch(s_normal, ivec3(q, 0), u_level).xyz + vec3(0.0, 0.0, 1e-12));
            if (dot(n, nq) < u_pass.geometry.x || abs(dot(xq - x, n)) > tolerance) continue;
            int s = alParity(q, 4);
            sum[s] += texelFetch(s_subsets, u_levelOrigin + q, 0).rgb;
            count[s] += 1.0;
        }
        vec3 e = vec3(0.0);
        float found = 0.0;
        for (int s = 0; s < 4; ++s)
            if (count[s] > 0.0) {
                e += sum[s] / count[s];
                found += 1.0;
            }
        imageStore(i_atlas, u_levelOrigin + c, vec4(e * (4.0 / max(found, 1.0)), 1.0));
    }

    if (u_bitCount) {
        // Per subset, the VPLs whose bits differ among its tree cells of the cell's 3x3 region
        // (area_common.glsl alWindowRadius), over the subsets with at least two such cells: every VPL
        // of an interior cell is examined, so u_pass.refine.y (thesis: 128 of 256) is the fraction of
        // all VPLs it says.
        uint partial = 0u, examined = 0u;
        int subsets = int(u_pass.counts.w), perCell = int(u_pass.counts.z), r = alWindowRadius(subsets);
        for (int layer = 0; layer < int(u_pass.geometry.w); ++layer) {
            uvec4 anyBits[4], allBits[4];
            int samples[4];
            for (int s = 0; s < 4; ++s) {
                anyBits[s] = uvec4(0u);
                allBits[s] = uvec4(0xFFFFFFFFu);
                samples[s] = 0;
            }
            for (int i = 0; i < alRegionCells(r); ++i) {
                ivec2 q;
                if (!alRegionCell(c, r, u_size, i, q)) continue;
                if ((imageLoad(i_flags, u_levelOrigin + q).r & AL_CELL_TREE) == 0u) continue;
                int s = alParity(q, subsets);
                uvec4 b = imageLoad(i_bits, ivec3(u_levelOrigin + q, layer));
                anyBits[s] |= b;
                allBits[s] &= b;
                samples[s] += 1;
            }
            uint layerVpls = uint(min(perCell - SV_BITS_PER_LAYER * layer, SV_BITS_PER_LAYER));
            for (int s = 0; s < subsets; ++s) {
                if (samples[s] < AL_MIN_REGION_SAMPLES) continue;
                uvec4 differ = anyBits[s] & ~allBits[s];
                partial += uint(bitCount(differ.x) + bitCount(differ.y) + bitCount(differ.z) + bitCount(differ.w));
                examined += layerVpls;
            }
        }
        atomicAdd(u_stats[AL_STAT_PARTIAL_VPLS], partial);
        atomicAdd(u_stats[AL_STAT_EXAMINED_VPLS], examined);
        atomicAdd(u_stats[AL_STAT_TREE_CELLS], 1u);
        if (float(partial) >= u_pass.refine.y) imageStore(i_flags, u_levelOrigin + c, uvec4(flags | AL_CELL_REFINE));
    }
}
