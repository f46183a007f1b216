#include "techniques/photon_splat/DepthRays.h"

#include "core/Check.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>

namespace bounce::photonsplat {

namespace {

// Bundles per TBB task: 16 maps of 8 x 8 texels are 1,024 rays, Embree's streams' worth of work.
constexpr size_t kBundlesPerTask = 16;
// Rays traced per Embree call from one tile (the largest map, 32 x 32, takes 16 calls).
constexpr size_t kRaysPerCall = 64;

}  // namespace

glm::vec2 texelRayInterval(const BundleVolume& v, float s, float t) {
    const glm::vec3 base = v.origin + s * v.right + t * v.up;
    // Past the near plane: dot(base + z w, m) <= nearOffset, with dot(w, m) < 0.
    const float zNearPlane = (v.nearOffset - glm::dot(base, v.nearNormal)) / glm::dot(v.direction, v.nearNormal);
    float a = std::max(zNearPlane, v.zNear), b = std::min(zNearPlane + v.length, v.zFar);
    if (std::isfinite(v.emitterOffset)) {
        // In front of the photon's surface: dot(base + z w, n_P) >= emitterOffset.
        const float along = glm::dot(v.direction, v.emitterNormal), at = glm::dot(base, v.emitterNormal) - v.emitterOffset;
        if (along > 0.0f) a = std::max(a, -at / along);
        else if (along < 0.0f) b = std::min(b, -at / along);
        else if (at < 0.0f) b = -std::numeric_limits<float>::infinity();
    }
    return {a, b};
}

size_t traceDepthMaps(const RayCaster& caster, std::span<const BundleVolume> volumes, int resolution, int tilesPerRow,
                    std::span<float> atlas) {
    const size_t r = static_cast<size_t>(resolution), row = static_cast<size_t>(tilesPerRow) * r;
    const size_t tileRows = (volumes.size() + static_cast<size_t>(tilesPerRow) - 1) / static_cast<size_t>(tilesPerRow);
    BOUNCE_CHECK(atlas.size() >= tileRows * r * row, "traceDepthMaps: {} floats for {} rows of tiles", atlas.size(), tileRows);
    // The last row's tiles past the last bundle hold no map.
    for (size_t k = volumes.size(); k < tileRows * static_cast<size_t>(tilesPerRow); ++k)
        for (size_t j = 0; j < r; ++j) {
            float* texel = atlas.data() + (k / static_cast<size_t>(tilesPerRow) * r + j) * row + k % static_cast<size_t>(tilesPerRow) * r;
            std::fill(texel, texel + r, 1.0f);
        }
    std::atomic<size_t> traced{0};
    auto traceTile = [&](size_t k) {
        const BundleVolume& v = volumes[k];
        const float range = std::max(v.zFar - v.zNear, std::numeric_limits<float>::min());  // a zero-depth map stores 0 or 1
        float* tile = atlas.data() + k / static_cast<size_t>(tilesPerRow) * r * row + k % static_cast<size_t>(tilesPerRow) * r;
        std::array<CastRay, kRaysPerCall> rays;
        std::array<float, kRaysPerCall> start, hits;  // local depth where each ray starts; its hit distance
        std::array<size_t, kRaysPerCall> texels;      // the ray's texel, as an offset from the tile's corner
        size_t count = 0, tracedHere = 0;
        auto trace = [&] {
            tracedHere += count;
            caster.closestDistances(std::span(rays.data(), count), std::span(hits.data(), count));
            for (size_t q = 0; q < count; ++q)
                if (std::isfinite(hits[q])) tile[texels[q]] = std::clamp((start[q] + hits[q] - v.zNear) / range, 0.0f, 1.0f);
            count = 0;
        };
        for (size_t j = 0; j < r; ++j)
            for (size_t i = 0; i < r; ++i) {
                tile[j * row + i] = 1.0f;
                // The texel centre's offset over the square [-h, h]^2: where the rasteriser samples.
                const float s = ((static_cast<float>(i) + 0.5f) / static_cast<float>(r) * 2.0f - 1.0f) * v.half;
                const float t = ((static_cast<float>(j) + 0.5f) / static_cast<float>(r) * 2.0f - 1.0f) * v.half;
                const glm::vec2 ab = texelRayInterval(v, s, t);
                if (!(ab.x <= ab.y)) continue;
                rays[count] = CastRay{v.origin + s * v.right + t * v.up + ab.x * v.direction, v.direction, 0.0f, ab.y - ab.x};
                start[count] = ab.x;
                texels[count++] = j * row + i;
                if (count == kRaysPerCall) trace();
            }
        if (count > 0) trace();
        traced.fetch_add(tracedHere, std::memory_order_relaxed);
    };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, volumes.size(), kBundlesPerTask), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t k = range.begin(); k < range.end(); ++k) traceTile(k);
    });
    return traced.load();
}

}  // namespace bounce::photonsplat
