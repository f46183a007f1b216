// Voxel cone tracing (Rauwendaal 2013): the per-frame parameter block shared by C++ and GLSL, and the
// enumerations of its settings. Members are vec4/mat4 only (std140 = std430 = C++ layout).
#ifndef BOUNCE_VCT_SHARED_H
#define BOUNCE_VCT_SHARED_H

#include "common/shared.h"

#ifdef __cplusplus
namespace bounce::gpu {
#endif

#define VCT_MAX_LIGHTS 4  // lights injected at voxelization (one shadow-map unit pair each, Bindings.h)

#define VCT_STORAGE_ISO 0     // RGBA8 (thesis 5.1.1)
#define VCT_STORAGE_ANISO 1   // 6 x RGBA8 (5.1.2)
#define VCT_STORAGE_SH_F32 2  // 12 x R32F, float atomic add + normalisation (5.1.3)
#define VCT_STORAGE_SH_U8 3   // 3 x RGBA8 from the isotropic result, range-scaled (5.1.3)

#define VCT_ATOMIC_MAX 0      // imageAtomicMax on the packed RGBA8
#define VCT_ATOMIC_AVERAGE 1  // compare-and-swap running average (Fig. B.1)

#define VCT_DEBUG_NONE 0
#define VCT_DEBUG_OCCUPANCY 1  // camera rays marched through level debugLevel: first occupied voxel
#define VCT_DEBUG_RADIANCE 2   // the same, showing the voxel's stored radiance
#define VCT_DEBUG_AO 3         // ambient accessibility of the six diffuse cones (Eq. 6.7)
#define VCT_DEBUG_SLICE 4      // the radiance of one z slice of level debugLevel over the whole image

struct VctUniforms {
    mat4 voxelFromWorld;  // world -> voxel space, the grid spans [0, N]^3 (unit voxels)
    mat4 worldFromVoxel;
    vec4 grid;      // x: N, y: 1 / N, z: voxel edge (metres), w: mip levels
    vec4 voxelize;  // x: separability (0 thin 6-sep, 1 conservative 26-sep), y: hybrid cutoff (voxels^2),
                    // z: storage (VCT_STORAGE_*), w: atomic mode (VCT_ATOMIC_*)
    vec4 range;     // x: radiance mapped to 1.0 in the 8-bit formats (W/(m^2 sr)), y: SH-U8 coefficient
                    // range, z: lights injected, w: 1 = binary (occupancy only)
    vec4 cone;      // x: f (start offset, voxels), y: fMax (voxels), z: maxDist (metres), w: aoDist (metres)
    vec4 cone2;     // x: specular cone on, y: specular aperture scale, z: diffuse tracer (0 generic,
                    // 1 60-degree), w: shadow cone aperture (radians)
    vec4 debug;     // x: view (VCT_DEBUG_*), y: level, z: slice (0..1), w: 1 = write active-voxel lists
    vec4 trace;     // x: 1 = tangent cap of the generic tracer's sample levels (cone.glsl), y: 1 = opacity
                    // correction of iso/SH samples for the step length, z: |v| of Eq. 6.2 in voxels
                    // (diagonal or side), w: 1 = anisotropic opacity blended as transmittance (cone.glsl)
    LightGpu lights[VCT_MAX_LIGHTS];
};

#ifdef __cplusplus
static_assert(sizeof(VctUniforms) == 128 + 7 * 16 + VCT_MAX_LIGHTS * sizeof(LightGpu));
}  // namespace bounce::gpu
#endif

#endif
