// Screen-space binary voxelization (Nichols 2010 §5.3.3, checklist item 18; Eisemann & Décoret,
// "Fast scene voxelization and applications", 2006): every fragment of every triangle, without depth
// test or culling, sets bits of its pixel's column; the framebuffer ORs them together (glLogicOp(GL_OR)
// on RGBA32UI targets). Slices are linear in view depth between the grid's near and far (Eisemann &
// Décoret's uniform slicing). Output target k holds bits 128k .. 128k + 127 (component c, bit b =
// slice 128k + 32c + b).
// u_footprint = false is the thesis's voxel: the one slice holding the fragment's depth at the pixel
// centre. A surface at a grazing angle to the camera then leaves holes: neighbouring columns hold it
// many slices apart, and a visibility ray crossing it between two centres passes through (on
// cornell-box-area at 16 steps most rays through the short block got through). u_footprint = true
// (bounce's default, a deviation) sets every slice the triangle spans within the pixel, estimated from
// the depth's screen derivatives, so that each surface is a connected shell in the grid.
// Inputs: scene.vert's world position, u_voxels (BINDING_UBO_VOXELS), u_footprint.
// Outputs: up to SV_MAX_LAYERS uvec4.
#include "techniques/screen_voxels/screen_voxels_shared.h"
layout(std140, binding = BINDING_UBO_VOXELS) uniform VoxelBlock { ScreenVoxelsGpu u_voxels; };
uniform bool u_footprint;
in vec3 v_posWorld;
layout(location = 0) out uvec4 o_bits[SV_MAX_LAYERS];

void main() {
    float z = -(u_voxels.viewFromWorld * vec4(v_posWorld, 1.0)).z;
    int bits = int(u_voxels.grid.z);
    // Half the depth change across the pixel (the derivatives are per column of the grid's viewport).
    float halfSpan = u_footprint ? 0.5 * (abs(dFdx(z)) + abs(dFdy(z))) : 0.0;
    int s0 = int(floor((z - halfSpan - u_voxels.depth.x) * u_voxels.depth.z));
    int s1 = int(floor((z + halfSpan - u_voxels.depth.x) * u_voxels.depth.z));
    s0 = max(s0, 0);
    s1 = min(s1, bits - 1);
    for (int k = 0; k < SV_MAX_LAYERS; ++k) {
        uvec4 word = uvec4(0u);
        for (int c = 0; c < 4; ++c) {
            int first = SV_BITS_PER_LAYER * k + 32 * c;  // slice of bit 0 of this word
            int lo = max(s0 - first, 0), hi = min(s1 - first, 31);
            if (lo > hi) continue;  // also when the fragment lies outside the depth range (s0 > s1)
            word[c] = (hi == 31 ? 0xFFFFFFFFu : ((1u << uint(hi + 1)) - 1u)) & ~((1u << uint(lo)) - 1u);
        }
        o_bits[k] = word;
    }
}
