// Screen-space binary voxelization (Nichols 2010 §5.3.3, checklist item 18; Eisemann & Décoret,
// "Single-pass GPU solid voxelization", 2006): every fragment of every triangle, without depth test or
// culling, sets the bits of its pixel's column that hold the view depths the triangle spans over that
// column (one bit for a surface facing the camera, several at grazing angles); the framebuffer ORs the
// bits together (glLogicOp(GL_OR) on RGBA32UI targets). Slices are linear in view depth between the
// grid's near and far (as Eisemann & Décoret's uniform slicing). Output target k holds bits
// 128k .. 128k + 127 (component c, bit b = slice 128k + 32c + b).
// Inputs: voxelize.geom's world position and triangle depth range, u_voxels (BINDING_UBO_VOXELS),
// u_footprint.
// Outputs: up to SV_MAX_LAYERS uvec4.
#include "techniques/screen_voxels/screen_voxels_shared.h"
layout(std140, binding = BINDING_UBO_VOXELS) uniform VoxelBlock { ScreenVoxelsGpu u_voxels; };
in vec3 g_posWorld;
flat in vec2 g_depthRange;
uniform bool u_footprint;
layout(location = 0) out uvec4 o_bits[SV_MAX_LAYERS];

void main() {
    float z = -(u_voxels.viewFromWorld * vec4(g_posWorld, 1.0)).z;
    // The depth the surface spans over this column: a planar triangle's depth changes by dFdx(z),
    // dFdy(z) from column to column, so its footprint is z +- half their sum. Setting only the bit of
    // the centre's depth left a surface seen at a grazing angle (a floor, a table top at eye level)
    // with empty slices between its columns' bits, through which rays passed undetected
    // (ScreenVoxelsGpuTest.GrazingSurfacesHaveNoDepthGaps).
    // The footprint is kept within the triangle's own depth range (voxelize.geom): half a column past
    // its edge it would claim depths the surface does not reach.
    // u_footprint = false is the thesis's voxel (area-light's voxelFootprint=false): one bit, the slice
    // at the column centre.
    float halfFootprint = u_footprint ? 0.5 * (abs(dFdx(z)) + abs(dFdy(z))) : 0.0;
    float zLo = max(z - halfFootprint, g_depthRange.x), zHi = min(z + halfFootprint, g_depthRange.y);
    int bits = int(u_voxels.grid.z);
    float u0 = (min(zLo, z) - u_voxels.depth.x) * u_voxels.depth.z;
    float u1 = (max(zHi, z) - u_voxels.depth.x) * u_voxels.depth.z;
    uvec4 words[SV_MAX_LAYERS];
    for (int k = 0; k < SV_MAX_LAYERS; ++k) words[k] = uvec4(0u);
    if (u1 >= 0.0 && u0 < float(bits)) {  // else outside the grid's depth range: not represented
        int s0 = max(int(floor(u0)), 0), s1 = min(int(floor(u1)), bits - 1);
        for (int w = s0 / 32; w <= s1 / 32; ++w) {
            int lo = max(s0 - 32 * w, 0), hi = min(s1 - 32 * w, 31);
            words[w / 4][w % 4] = (hi == 31 ? 0xFFFFFFFFu : ((1u << uint(hi + 1)) - 1u)) & ~((1u << uint(lo)) - 1u);
        }
    }
    for (int k = 0; k < SV_MAX_LAYERS; ++k) o_bits[k] = words[k];
}
