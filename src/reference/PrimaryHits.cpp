#include "reference/PrimaryHits.h"

#include "reference/CameraRays.h"
#include "reference/RayCaster.h"

namespace bounce {

Expected<PrimaryHits> primaryHits(const Scene& scene, float time, int width, int height) {
    BOUNCE_TRY(const RayCaster caster, RayCaster::create(scene, time, GeometryFilter::All));
    const CameraRays camera(scene.camera.at(time), width, height);
    std::vector<CastRay> rays;
    rays.reserve(static_cast<size_t>(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // The pixel's centre: where the rasteriser samples its G-buffer fragment.
            const CameraRay r = camera.generate(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
            rays.push_back({r.origin, r.direction, 0.0f, r.tMax});
        }
    std::vector<std::optional<RayHit>> hits(rays.size());
    caster.closestHits(rays, hits);
    PrimaryHits out{Image(width, height), std::vector<uint8_t>(rays.size(), 0)};
    for (size_t i = 0; i < hits.size(); ++i)
        if (hits[i]) {
            out.positions.data()[i] = hits[i]->position;
            out.covered[i] = 1;
        }
    return out;
}

}  // namespace bounce
