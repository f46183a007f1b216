#include "reference/RayCaster.h"

#include "core/Check.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>

namespace bounce {

namespace {

// Rays per Embree stream call: large enough to amortise the call, small enough for the stack.
constexpr size_t kStreamChunk = 64;
// Batches above this size are split across threads in pieces of kParallelGrain rays.
constexpr size_t kParallelThreshold = 4096;
constexpr size_t kParallelGrain = 1024;

// Closest hits of `rays` in Embree streams of kStreamChunk on the calling thread; visit(i, hit) gets ray
// i's result.
template <typename Visit>
void intersectStreams(RTCScene scene, std::span<const CastRay> rays, Visit&& visit) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    std::array<RTCRayHit, kStreamChunk> stream;
    for (size_t base = 0; base < rays.size(); base += kStreamChunk) {
        const size_t n = std::min(kStreamChunk, rays.size() - base);
        for (size_t i = 0; i < n; ++i) {
            const CastRay& r = rays[base + i];
            setRay(stream[i].ray, r.origin, r.direction, r.tMin, r.tMax);
            stream[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
            stream[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect1M(scene, &context, stream.data(), static_cast<unsigned>(n), sizeof(RTCRayHit));
        for (size_t i = 0; i < n; ++i) visit(base + i, stream[i]);
    }
}

}  // namespace

Expected<RayCaster> RayCaster::create(const Scene& scene, float time, GeometryFilter filter) {
    EmbreeSceneOptions options;
    options.time = time;
    options.filter = filter;
    options.includeAreaLights = false;
    BOUNCE_TRY(EmbreeScene embree, EmbreeScene::build(scene, options));
    return RayCaster(std::move(embree));
}

RayCaster::RayCaster(EmbreeScene embree) : m_embree(std::move(embree)) {
    for (const SceneGeometry& g : m_embree.geometries()) m_triangleCount += g.triangles.size();
}

RayHit RayCaster::makeHit(uint32_t geomId, uint32_t primId, float u, float v, float t, glm::vec3 direction) const {
    const SceneGeometry& g = m_embree.geometry(geomId);
    const SurfacePoint sp = m_embree.surface(geomId, primId, u, v);
    RayHit hit;
    hit.t = t;
    hit.position = sp.position;
    hit.geometricNormal = sp.geometricNormal;
    hit.shadingNormal = sp.shadingNormal;
    hit.uv = sp.uv;
    hit.frontFacing = glm::dot(direction, sp.geometricNormal) < 0.0f;
    hit.objectIndex = g.objectIndex;
    hit.triangleIndex = primId;
    hit.materialIndex = g.materialIndex;
    return hit;
}

std::optional<RayHit> RayCaster::closestHit(glm::vec3 origin, glm::vec3 direction, float tMin, float tMax) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    setRay(rh.ray, origin, direction, tMin, tMax);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_embree.handle(), &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return makeHit(rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, direction);
}

bool RayCaster::occluded(glm::vec3 from, glm::vec3 to) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    setRay(ray, from, to - from, kSegmentEpsilon, 1.0f - kSegmentEpsilon);
    rtcOccluded1(m_embree.handle(), &context, &ray);
    return ray.tfar < 0.0f;
}

void RayCaster::closestHitsChunk(std::span<const CastRay> rays, std::span<std::optional<RayHit>> results) const {
    intersectStreams(m_embree.handle(), rays, [&](size_t i, const RTCRayHit& rh) {
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            results[i].reset();
        else
            results[i] = makeHit(rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, rays[i].direction);
    });
}

void RayCaster::closestDistances(std::span<const CastRay> rays, std::span<float> distances) const {
    BOUNCE_CHECK(rays.size() == distances.size(), "closestDistances: {} rays but {} results", rays.size(), distances.size());
    intersectStreams(m_embree.handle(), rays, [&](size_t i, const RTCRayHit& rh) {
        distances[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<float>::infinity() : rh.ray.tfar;
    });
}

void RayCaster::occludedChunk(std::span<const Segment> segments, std::span<uint8_t> results) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    std::array<RTCRay, kStreamChunk> stream;
    for (size_t base = 0; base < segments.size(); base += kStreamChunk) {
        const size_t n = std::min(kStreamChunk, segments.size() - base);
        for (size_t i = 0; i < n; ++i) {
            const Segment& s = segments[base + i];
            setRay(stream[i], s.from, s.to - s.from, kSegmentEpsilon, 1.0f - kSegmentEpsilon);
        }
        rtcOccluded1M(m_embree.handle(), &context, stream.data(), static_cast<unsigned>(n), sizeof(RTCRay));
        for (size_t i = 0; i < n; ++i) results[base + i] = stream[i].tfar < 0.0f ? 1 : 0;
    }
}

void RayCaster::closestHits(std::span<const CastRay> rays, std::span<std::optional<RayHit>> results) const {
    BOUNCE_CHECK(rays.size() == results.size(), "closestHits: {} rays but {} results", rays.size(), results.size());
    if (rays.size() < kParallelThreshold) return closestHitsChunk(rays, results);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), kParallelGrain), [&](const tbb::blocked_range<size_t>& r) {
        closestHitsChunk(rays.subspan(r.begin(), r.size()), results.subspan(r.begin(), r.size()));
    });
}

void RayCaster::occluded(std::span<const Segment> segments, std::span<uint8_t> results) const {
    BOUNCE_CHECK(segments.size() == results.size(), "occluded: {} segments but {} results", segments.size(),
                 results.size());
    if (segments.size() < kParallelThreshold) return occludedChunk(segments, results);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, segments.size(), kParallelGrain),
                      [&](const tbb::blocked_range<size_t>& r) {
                          occludedChunk(segments.subspan(r.begin(), r.size()), results.subspan(r.begin(), r.size()));
                      });
}

}  // namespace bounce
