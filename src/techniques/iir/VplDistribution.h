#pragma once
// Incremental maintenance of the VPL distribution of Laine et al. 2007, "Incremental Instant
// Radiosity for Real-Time Indirect Illumination" (§3 steps 1-4, §4). GL-free: the caller supplies the
// two ray queries against the static scene and renders shadow maps for the VPLs this creates.
//
// Each VPL's direction from the light is a sampling point in a 2D domain (§4.1): the unit disc for a
// spot light (SpotDiscMap: Nusselt analog, radially stretched for cos^n falloff and a cutoff) or the
// unit sphere for an omni light. Every frame, in the paper's order:
//   1. removeInvalid   map every sample with the new light pose; drop those outside the spot cone and
//                      those the caller's test rejects (§4.4: shadow ray against the static scene).
//   2. deleteForBudget drop valid samples by the shortest-Delaunay-edge rule until recalcMin slots
//                      are free (§4.5).
//   3. createSamples   insert points at the centre of the largest empty circle, cast a ray for each,
//                      up to recalcMax per frame or until maxLights (§4.6).
//   4. computeWeights  each sample's Voronoi cell area in the domain (§4.7).
// update() runs the four in order.
//
// Rays that leave the scene (the paper: "no VPL is created", its sampling point having been added)
// become Miss samples here: they keep their slot and their point, fixed as a world direction, and are
// revalidated like VPLs (the caller checks the ray still escapes). Without them an open scene would
// pull the largest empty circle back into the same escaping directions every frame and spend the
// whole budget there; with them the escaping flux keeps its own cells (docs/techniques/iir.md).
#include "core/Error.h"
#include "scene/Scene.h"
#include "techniques/iir/DomainTriangulation.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace bounce {

enum class SamplingDomainKind { Disc, Sphere };

struct SamplingDomain {
    SamplingDomainKind kind = SamplingDomainKind::Disc;
    double falloffExponent = 1.0;          // disc: spot intensity cos^n(alpha)
    double cutoffAngle = 1.5707963267948966;  // disc: spot half-angle, radians (clamped to pi/2)

    static SamplingDomain spot(double falloffExponent, double cutoffAngle);
    static SamplingDomain omni();
    // A spot light maps to the disc, a point light to the sphere; other lights are an error.
    static Expected<SamplingDomain> forLight(const Light& light);
};

struct VplDistributionParams {
    uint32_t maxLights = 256;  // §4.2 maxLights; 256 in all of the paper's measurements
    uint32_t recalcMin = 4;    // §4.2 recalcMin: new samples forced per frame ("4-8 VPLs per frame", §6)
    uint32_t recalcMax = 8;    // §4.2 recalcMax: cap on new samples (rays, shadow maps) per frame
    uint64_t seed = 0;         // breaks the exact ties of nearly empty domains (see the triangulations)

    // 1 <= maxLights, 1 <= recalcMax <= maxLights, recalcMin <= recalcMax. recalcMin = recalcMax =
    // maxLights regenerates every sample every frame (the paper's comparison method, with this
    // sampling pattern).
    Expected<void> validate() const;
};

// The light at this frame: position (world, metres) and, for spot lights, the axis it points along.
struct LightPose {
    glm::vec3 position{0.0f};
    glm::vec3 axis{0.0f, -1.0f, 0.0f};
};

enum class SampleKind : uint8_t {
    Empty,  // free slot
    Vpl,    // a virtual point light at positionWorld
    Miss,   // a sampling point whose ray left the scene; carries the escaping flux of its cell
};

struct VplSample {
    SampleKind kind = SampleKind::Empty;
    glm::vec3 positionWorld{0.0f};    // Vpl: the ray's hit point
    glm::dvec3 directionWorld{0.0};   // unit, from the light; Vpl: towards positionWorld at the last
                                      // mapped pose; Miss: the fixed escaping direction
    glm::dvec3 domainPoint{0.0};      // sampling point: (x, y, 0) on the disc, unit vector on the sphere
    double cellArea = 0.0;            // Voronoi cell area in the domain (computeWeights)
    double fluxFraction = 0.0;        // cellArea / domain area: share of the light's total flux
    double weight = 0.0;              // Vpl: cellArea / (sum over VPLs), the paper's normalisation; Miss: 0
    uint32_t createdFrame = 0;
    uint64_t serial = 0;              // creation order over the distribution's lifetime
};

struct VplFrameStats {
    uint32_t frame = 0;
    uint32_t samplesAtStart = 0;       // samples carried over from the previous frame
    uint32_t invalidOutsideCone = 0;   // mapped outside the spot cone (or onto the light itself)
    uint32_t invalidRejected = 0;      // the caller's validity test failed
    uint32_t invalidCoincident = 0;    // mapped onto another sample's point (one of the two is kept)
    uint32_t valid = 0;                // samplesAtStart minus the three kinds of invalid
    uint32_t deleted = 0;              // valid samples removed by the shortest-edge rule
    uint32_t createdVpls = 0;
    uint32_t createdMisses = 0;
    uint32_t vplCount = 0;             // at the end of the frame
    uint32_t missCount = 0;
    double dispersionBeforeCreation = 0.0;  // Eq. (1) after deletion (chordal on the sphere)
    double dispersion = 0.0;                // Eq. (1) at the end of the frame
    double validityMs = 0.0;           // CPU time of each step, including the caller's callbacks
    double deletionMs = 0.0;
    double creationMs = 0.0;
    double weightsMs = 0.0;
};

class VplDistribution {
public:
    // Called once per carried-over sample with its state for the new pose (directionWorld and
    // domainPoint already updated). Return false to drop it: for a Vpl when the segment from the light
    // to positionWorld is blocked by static geometry; for a Miss when the ray from the light along
    // directionWorld now hits static geometry.
    using ValidityTest = std::function<bool(SlotId slot, const VplSample& sample)>;
    // Casts a ray from the light along a unit world direction against the static scene; returns the
    // closest hit, or nothing when the ray leaves the scene. `slot` is where the result will live (to
    // store the hit's normal and colour alongside).
    using RayCaster = std::function<std::optional<glm::vec3>(SlotId slot, const glm::dvec3& directionWorld)>;

    VplDistribution(const SamplingDomain& domain, const VplDistributionParams& params);
    ~VplDistribution();
    VplDistribution(VplDistribution&&) noexcept;
    VplDistribution& operator=(VplDistribution&&) noexcept;

    // Steps 1-4 in the paper's order; returns this frame's statistics.
    const VplFrameStats& update(const LightPose& pose, const ValidityTest& isValid, const RayCaster& castRay);

    // Step 1. Starts a new frame. When the pose changed, every sample is re-mapped and the
    // triangulation rebuilt from the valid ones (all sampling points move with the light, Fig. 3);
    // when it did not, invalid samples are removed one by one.
    void removeInvalid(const LightPose& pose, const ValidityTest& isValid);
    // Step 2. Returns the number of samples deleted.
    uint32_t deleteForBudget();
    // Step 3. Returns the slots created this call (Vpl and Miss), in creation order.
    std::vector<SlotId> createSamples(const RayCaster& castRay);
    // Step 4.
    void computeWeights();

    // Drops every sample (scene change).
    void clear();

    const SamplingDomain& domain() const;
    const VplDistributionParams& params() const;
    std::span<const VplSample> samples() const;  // maxLights entries, indexed by slot
    const VplSample& sample(SlotId slot) const;
    uint32_t sampleCount() const;
    uint32_t vplCount() const;
    const VplFrameStats& frameStats() const;
    // Eq. (1) for the current samples.
    double dispersion();
    const DomainTriangulation& triangulation() const;

    // The domain mappings at the current pose (the pose of the last removeInvalid).
    std::optional<glm::dvec3> toDomain(const glm::dvec3& directionWorld) const;
    glm::dvec3 toWorldDirection(const glm::dvec3& domainPoint) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace bounce
