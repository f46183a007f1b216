#pragma once
// Ray casting against a Scene at one instant, for techniques that need CPU visibility: incremental
// instant radiosity places and validates VPLs with it, photon splatting traces photons. Backed by
// Embree 3; const methods are thread-safe.
//
// Only objects are geometry here: area lights are not rectangles in this world (the path tracer
// adds them for itself). Hits report the triangle's front side as defined by counter-clockwise
// winding (OpenGL's default), whichever side the ray came from.
#include "core/Error.h"
#include "reference/EmbreeScene.h"
#include "scene/Scene.h"

#include <limits>
#include <optional>
#include <span>

namespace bounce {

struct RayHit {
    float t = 0.0f;                // ray parameter: the distance when the direction is unit
    glm::vec3 position{0.0f};      // world space
    glm::vec3 geometricNormal{0.0f};  // unit, the triangle's front side
    glm::vec3 shadingNormal{0.0f};    // unit, interpolated vertex normal on the front side
    glm::vec2 uv{0.0f};            // interpolated; (0, 0) unless the material has a base-colour texture
    bool frontFacing = false;      // the ray arrived on the front side
    uint32_t objectIndex = 0;      // Scene::objects
    uint32_t triangleIndex = 0;    // triangle of the object's mesh (indices[3 * triangleIndex])
    uint32_t materialIndex = 0;    // Scene::materials
};

struct CastRay {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, 1.0f};  // need not be unit; t is then in units of its length
    float tMin = 0.0f;
    float tMax = std::numeric_limits<float>::infinity();
};

struct Segment {
    glm::vec3 from{0.0f};
    glm::vec3 to{0.0f};
};

class RayCaster {
public:
    // The geometry of `scene` at `time` seconds; StaticOnly leaves animated objects out (e.g. for
    // VPLs that must stay valid while objects move).
    static Expected<RayCaster> create(const Scene& scene, float time, GeometryFilter filter);

    std::optional<RayHit> closestHit(glm::vec3 origin, glm::vec3 direction, float tMin = 0.0f,
                                     float tMax = std::numeric_limits<float>::infinity()) const;

    // True when a triangle lies between the two points. The first and last kSegmentEpsilon of the
    // segment are ignored, so that surface points do not occlude themselves.
    bool occluded(glm::vec3 from, glm::vec3 to) const;

    // Batch versions: results[i] belongs to rays[i] / segments[i]; spans must have equal sizes.
    // Rays go to Embree as streams (rtcIntersect1M / rtcOccluded1M); big batches use every core.
    void closestHits(std::span<const CastRay> rays, std::span<std::optional<RayHit>> results) const;
    void occluded(std::span<const Segment> segments, std::span<uint8_t> results) const;
    // The distance t to each ray's closest hit (infinity where it hits nothing), on the calling thread
    // (a caller that parallelises over its own batches): no hit record is made.
    void closestDistances(std::span<const CastRay> rays, std::span<float> distances) const;

    size_t triangleCount() const noexcept { return m_triangleCount; }

    // Fraction of a segment's length ignored at each end by occluded(): 1e-4 is 0.1 mm on a 1 m
    // segment, well above float rounding of positions (~1e-7 relative) and below any scene detail.
    static constexpr float kSegmentEpsilon = 1e-4f;

private:
    explicit RayCaster(EmbreeScene embree);
    RayHit makeHit(uint32_t geomId, uint32_t primId, float u, float v, float t, glm::vec3 direction) const;
    void closestHitsChunk(std::span<const CastRay> rays, std::span<std::optional<RayHit>> results) const;
    void occludedChunk(std::span<const Segment> segments, std::span<uint8_t> results) const;

    EmbreeScene m_embree;
    size_t m_triangleCount = 0;
};

}  // namespace bounce
