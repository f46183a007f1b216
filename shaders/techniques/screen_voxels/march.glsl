// Voxel ray marching through the screen-space binary voxelization (Nichols 2010 §5.3.3.1, checklist
// item 19). The thesis found a 3D DDA slow on its GPU ("varying numbers of loop iterations") and
// samples the segment uniformly instead; thin occluders a sample skips are partly caught "by checking
// multiple bits in texels fetched from the voxel buffer. This essentially thickens the ray": each of
// the `steps` segments tests every bit between the slices of its two ends, widened by `thickness`
// bits on each side, in the column under its midpoint. Points outside the camera frustum or the grid's
// depth range are empty: the voxelization only knows what the camera sees (a limitation the thesis
// does not discuss). The caller applies the origin bias.
// Include after defining nothing; needs u_voxels (screen_voxels_shared.h) and s_voxels at
// BINDING_TEX_VOXELS (usampler2DArray, one layer per 128 bits).
#include "techniques/screen_voxels/screen_voxels_shared.h"
layout(std140, binding = BINDING_UBO_VOXELS) uniform VoxelBlock { ScreenVoxelsGpu u_voxels; };
layout(binding = BINDING_TEX_VOXELS) uniform usampler2DArray s_voxels;

// Any bit of slices [s0, s1] set in column `texel`?
bool voxelBitsSet(ivec2 texel, int s0, int s1) {
    for (int w = s0 / 32; w <= s1 / 32; ++w) {
        int lo = max(s0 - 32 * w, 0), hi = min(s1 - 32 * w, 31);
        uint mask = (hi == 31 ? 0xFFFFFFFFu : ((1u << uint(hi + 1)) - 1u)) & ~((1u << uint(lo)) - 1u);
        uvec4 t = texelFetch(s_voxels, ivec3(texel, w / 4), 0);
        if ((t[w % 4] & mask) != 0u) return true;
    }
    return false;
}

// Fraction of the segment a -> b (world) before its first occupied sample, 1.0 when it is free.
float voxelMarch(vec3 a, vec3 b, int steps, int thickness) {
    vec4 ca = u_voxels.clipFromWorld * vec4(a, 1.0), cb = u_voxels.clipFromWorld * vec4(b, 1.0);
    float za = -(u_voxels.viewFromWorld * vec4(a, 1.0)).z, zb = -(u_voxels.viewFromWorld * vec4(b, 1.0)).z;
    int bits = int(u_voxels.grid.z);
    vec2 res = u_voxels.grid.xy;
    float prevSlice = (za - u_voxels.depth.x) * u_voxels.depth.z;
    for (int i = 1; i <= steps; ++i) {
        float t = float(i) / float(steps), tm = (float(i) - 0.5) / float(steps);
        float slice = (mix(za, zb, t) - u_voxels.depth.x) * u_voxels.depth.z;
        vec4 cm = mix(ca, cb, tm);
        vec2 ndc = cm.xy / cm.w;
        float s0f = min(prevSlice, slice), s1f = max(prevSlice, slice);
        prevSlice = slice;
        if (cm.w <= 0.0 || any(greaterThan(abs(ndc), vec2(1.0)))) continue;
        int s0 = max(int(floor(s0f)) - thickness, 0), s1 = min(int(floor(s1f)) + thickness, bits - 1);
        if (s0 > s1) continue;
        ivec2 texel = clamp(ivec2((ndc * 0.5 + 0.5) * res), ivec2(0), ivec2(res) - 1);
        if (voxelBitsSet(texel, s0, s1)) return (float(i) - 1.0) / float(steps);
    }
    return 1.0;
}
