// Screen-space binary voxelization (Nichols 2010 §5.3.3, checklist item 18; Eisemann & Décoret,
// "Single-pass GPU solid voxelization", 2006): every fragment of every triangle, without depth test or
// culling, sets the one bit of its pixel's column that holds its view depth; the framebuffer ORs the
// bits together (glLogicOp(GL_OR) on RGBA32UI targets). Slices are linear in view depth between the
// grid's near and far (as Eisemann & Décoret's uniform slicing). Output target k holds bits
// 128k .. 128k + 127 (component c, bit b = slice 128k + 32c + b).
// Inputs: scene.vert's world position, u_voxels (BINDING_UBO_VOXELS). Outputs: up to SV_MAX_LAYERS uvec4.
#include "techniques/screen_voxels/screen_voxels_shared.h"
layout(std140, binding = BINDING_UBO_VOXELS) uniform VoxelBlock { ScreenVoxelsGpu u_voxels; };
in vec3 v_posWorld;
layout(location = 0) out uvec4 o_bits[SV_MAX_LAYERS];

void main() {
    float z = -(u_voxels.viewFromWorld * vec4(v_posWorld, 1.0)).z;
    int bits = int(u_voxels.grid.z);
    int slice = int(floor((z - u_voxels.depth.x) * u_voxels.depth.z));
    for (int k = 0; k < SV_MAX_LAYERS; ++k) o_bits[k] = uvec4(0u);
    if (slice < 0 || slice >= bits) return;  // outside the grid's depth range: not represented
    uvec4 word = uvec4(0u);
    word[(slice % SV_BITS_PER_LAYER) / 32] = 1u << uint(slice % 32);
    o_bits[slice / SV_BITS_PER_LAYER] = word;
}
