// Screen-space binary voxelization of the view frustum (Nichols 2010 §5.3.3 after Eisemann & Décoret
// 2006/2008): the uniform block shared by C++ and GLSL. vec4/mat4 members only (std140 = C++ layout).
#ifndef BOUNCE_SCREEN_VOXELS_SHARED_H
#define BOUNCE_SCREEN_VOXELS_SHARED_H

#include "common/shared.h"

#ifdef __cplusplus
namespace bounce::gpu {
#endif

#define SV_BITS_PER_LAYER 128  // one RGBA32UI texel: 4 x 32 bits
#define SV_MAX_LAYERS 8        // GL 4.5 guarantees 8 draw buffers: up to 1024 bits per column

struct ScreenVoxelsGpu {
    mat4 clipFromWorld;  // the camera's (x, y of the grid)
    mat4 viewFromWorld;  // depth of the grid: linear in view-space distance -z
    vec4 grid;           // x, y: columns (texels), z: bits per column, w: layers (bits / 128)
    vec4 depth;          // x: near (m), y: far (m), z: bits / (far - near) (slices per metre), w: slice depth (m)
};

#ifdef __cplusplus
static_assert(sizeof(ScreenVoxelsGpu) == 160);
}  // namespace bounce::gpu
#endif

#endif
