#pragma once
// depthMaps=rays (the llvmpipe profile's default): the bundles' orthographic depth maps traced on the
// CPU instead of rasterised. A depth map holds, per texel, the first surface its centre's ray meets
// inside the volume (seed 004, §4.3); a ray per texel centre through the ray-casting scene finds the
// same surface, clipped to the same interval (past the near plane, before the far plane, in front of
// the photon's surface, within the map's depth range) and with the same alpha masks (the scene's
// intersection filter). On llvmpipe the GPU's rasteriser is the CPU too; tracing skips the clusters'
// culling and llvmpipe's set-up of every (bundle, triangle) pair. GL-free: the technique uploads the
// atlas rows it fills.
#include "reference/RayCaster.h"
#include "techniques/photon_splat/BundleVolume.h"

#include <span>

namespace bounce::photonsplat {

// The interval [a, b] of local depth along w (from the photon) in which the ray through the texel
// centre at cross-section offset (s, t) metres may find its surface; a > b when it may find none.
glm::vec2 texelRayInterval(const BundleVolume& volume, float s, float t);

// Bundles [0, volumes.size()) into an atlas of `tilesPerRow` tiles of r x r texels per row, row-major,
// `atlas` holding whole rows of tiles (tilesPerRow * r floats per texel row): per texel the first hit's
// depth as a [0, 1] fraction of [zNear, zFar], 1 where none. Tiles past the last bundle are set to 1.
// Parallel over bundles (TBB). Returns the rays traced (texels whose interval is not empty).
size_t traceDepthMaps(const RayCaster& caster, std::span<const BundleVolume> volumes, int resolution, int tilesPerRow,
                    std::span<float> atlas);

}  // namespace bounce::photonsplat
