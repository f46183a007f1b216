#include "techniques/iir/VplDistribution.h"

#include "core/Check.h"
#include "techniques/iir/DiscTriangulation.h"
#include "techniques/iir/LightBasis.h"
#include "techniques/iir/SphereTriangulation.h"
#include "techniques/iir/SpotDiscMap.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <chrono>

namespace bounce {

namespace {

// Below this largest-empty-circle radius a new point would land within CGAL's sphere tolerance
// (2^-23 = 1.2e-7) of an existing one, or be indistinguishable in float world directions (2^-24);
// the domain counts as full. 256-1024 samples keep the radius near 0.1.
constexpr double kMinInsertionRadius = 1e-6;

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

SamplingDomain SamplingDomain::spot(double falloffExponent, double cutoffAngle) {
    return SamplingDomain{SamplingDomainKind::Disc, falloffExponent, cutoffAngle};
}

SamplingDomain SamplingDomain::omni() { return SamplingDomain{SamplingDomainKind::Sphere, 0.0, glm::pi<double>()}; }

Expected<SamplingDomain> SamplingDomain::forLight(const Light& light) {
    switch (light.type) {
        case LightType::Spot:
            if (!(light.falloffExponent >= 0.0f))
                return makeError("light '{}': spot falloff exponent {} must be >= 0 for incremental instant radiosity",
                                 light.name, light.falloffExponent);
            if (!(light.cutoffAngle > 0.0f))
                return makeError("light '{}': spot cutoff angle {} rad must be positive", light.name,
                                 light.cutoffAngle);
            return spot(light.falloffExponent, light.cutoffAngle);
        case LightType::Point: return omni();
        case LightType::Directional:
        case LightType::Area: break;
    }
    return makeError("light '{}': incremental instant radiosity needs a point or spot light (Laine et al. 2007 "
                     "sample the directions of a point-like light)",
                     light.name);
}

Expected<void> VplDistributionParams::validate() const {
    if (maxLights < 1) return makeError("iir: maxLights {} must be at least 1", maxLights);
    if (recalcMax < 1 || recalcMax > maxLights)
        return makeError("iir: recalcMax {} must be in [1, maxLights = {}]", recalcMax, maxLights);
    if (recalcMin > recalcMax)
        return makeError("iir: recalcMin {} must not exceed recalcMax {}", recalcMin, recalcMax);
    return {};
}

struct VplDistribution::Impl {
    SamplingDomain domain;
    VplDistributionParams params;
    SpotDiscMap discMap{1.0, glm::half_pi<double>()};
    std::unique_ptr<DomainTriangulation> triangulation;
    std::vector<VplSample> samples;
    std::vector<double> areas;
    uint32_t used = 0;
    uint64_t nextSerial = 0;
    VplFrameStats stats;
    bool havePose = false;
    LightPose pose;
    LightBasis basis;

    bool isDisc() const { return domain.kind == SamplingDomainKind::Disc; }

    bool samePose(const LightPose& other) const {
        if (!havePose || other.position != pose.position) return false;
        return !isDisc() || other.axis == pose.axis;  // an omni light has no orientation
    }

    std::optional<glm::dvec3> toDomain(const glm::dvec3& directionWorld) const {
        if (!isDisc()) return glm::normalize(directionWorld);
        const std::optional<glm::dvec2> disc = discMap.toDisc(basis.toLocal(directionWorld));
        if (!disc) return std::nullopt;
        return glm::dvec3(*disc, 0.0);
    }

    glm::dvec3 toWorldDirection(const glm::dvec3& domainPoint) const {
        if (!isDisc()) return glm::normalize(domainPoint);
        return glm::normalize(basis.toWorld(discMap.toDirection(glm::dvec2(domainPoint))));
    }

    void freeSlot(SlotId slot) {
        samples[slot] = VplSample{};
        --used;
    }

    std::optional<SlotId> firstFreeSlot() const {
        for (SlotId slot = 0; slot < samples.size(); ++slot)
            if (samples[slot].kind == SampleKind::Empty) return slot;
        return std::nullopt;
    }

    void countKinds() {
        stats.vplCount = stats.missCount = 0;
        for (const VplSample& s : samples) {
            if (s.kind == SampleKind::Vpl) ++stats.vplCount;
            if (s.kind == SampleKind::Miss) ++stats.missCount;
        }
    }
};

VplDistribution::VplDistribution(const SamplingDomain& domain, const VplDistributionParams& params)
    : m_impl(std::make_unique<Impl>()) {
    const Expected<void> valid = params.validate();
    BOUNCE_CHECK(valid.ok(), "{}", valid.ok() ? std::string() : valid.error().message);
    Impl& m = *m_impl;
    m.domain = domain;
    m.params = params;
    if (m.isDisc()) {
        m.discMap = SpotDiscMap(domain.falloffExponent, domain.cutoffAngle);
        m.triangulation = std::make_unique<DiscTriangulation>(params.maxLights, params.seed);
    } else {
        m.triangulation = std::make_unique<SphereTriangulation>(params.maxLights, params.seed);
    }
    m.samples.assign(params.maxLights, VplSample{});
    m.areas.assign(params.maxLights, 0.0);
}

VplDistribution::~VplDistribution() = default;
VplDistribution::VplDistribution(VplDistribution&&) noexcept = default;
VplDistribution& VplDistribution::operator=(VplDistribution&&) noexcept = default;

const VplFrameStats& VplDistribution::update(const LightPose& pose, const ValidityTest& isValid,
                                             const RayCaster& castRay) {
    removeInvalid(pose, isValid);
    deleteForBudget();
    createSamples(castRay);
    computeWeights();
    return m_impl->stats;
}

void VplDistribution::removeInvalid(const LightPose& pose, const ValidityTest& isValid) {
    Impl& m = *m_impl;
    const auto start = std::chrono::steady_clock::now();
    const uint32_t frame = m.stats.frame + (m.havePose ? 1u : 0u);
    m.stats = VplFrameStats{};
    m.stats.frame = frame;
    m.stats.samplesAtStart = m.used;

    const bool moved = !m.samePose(pose);
    m.pose = pose;
    m.havePose = true;
    if (m.isDisc()) m.basis = LightBasis::fromAxis(glm::dvec3(pose.axis));

    if (!moved) {
        // Same pose: every sampling point is where it was, so the triangulation stays.
        for (SlotId slot = 0; slot < m.samples.size(); ++slot) {
            if (m.samples[slot].kind == SampleKind::Empty || isValid(slot, m.samples[slot])) continue;
            m.triangulation->remove(slot);
            m.freeSlot(slot);
            ++m.stats.invalidRejected;
        }
    } else {
        std::vector<DomainTriangulation::Site> sites;
        sites.reserve(m.used);
        for (SlotId slot = 0; slot < m.samples.size(); ++slot) {
            VplSample& s = m.samples[slot];
            if (s.kind == SampleKind::Empty) continue;
            if (s.kind == SampleKind::Vpl) {
                const glm::dvec3 offset = glm::dvec3(s.positionWorld) - glm::dvec3(pose.position);
                const double distance = glm::length(offset);
                if (!(distance > 0.0)) {
                    m.freeSlot(slot);
                    ++m.stats.invalidOutsideCone;
                    continue;
                }
                s.directionWorld = offset / distance;
            }
            const std::optional<glm::dvec3> point = m.toDomain(s.directionWorld);
            if (!point) {
                m.freeSlot(slot);
                ++m.stats.invalidOutsideCone;
                continue;
            }
            s.domainPoint = *point;
            if (!isValid(slot, s)) {
                m.freeSlot(slot);
                ++m.stats.invalidRejected;
                continue;
            }
            sites.push_back({slot, s.domainPoint});
        }
        for (SlotId slot : m.triangulation->rebuild(sites)) {
            m.freeSlot(slot);
            ++m.stats.invalidCoincident;
        }
    }
    m.stats.valid = m.used;
    m.stats.validityMs = millisecondsSince(start);
}

uint32_t VplDistribution::deleteForBudget() {
    Impl& m = *m_impl;
    const auto start = std::chrono::steady_clock::now();
    uint32_t deleted = 0;
    while (m.params.maxLights - m.used < m.params.recalcMin && m.used > 0) {
        std::optional<SlotId> victim = m.triangulation->shortestEdgeVictim();
        if (!victim) {  // a single sample left and recalcMin = maxLights: it goes too
            for (SlotId slot = 0; slot < m.samples.size() && !victim; ++slot)
                if (m.samples[slot].kind != SampleKind::Empty) victim = slot;
        }
        m.triangulation->remove(*victim);
        m.freeSlot(*victim);
        ++deleted;
    }
    m.stats.deleted += deleted;
    m.stats.deletionMs += millisecondsSince(start);
    return deleted;
}

std::vector<SlotId> VplDistribution::createSamples(const RayCaster& castRay) {
    Impl& m = *m_impl;
    BOUNCE_CHECK(m.havePose, "createSamples before the first removeInvalid: the light pose is unknown");
    const auto start = std::chrono::steady_clock::now();
    std::vector<SlotId> created;
    DomainTriangulation::EmptyCircle circle = m.triangulation->largestEmptyCircle();
    m.stats.dispersionBeforeCreation = circle.radius;
    while (created.size() < m.params.recalcMax && m.used < m.params.maxLights) {
        if (circle.radius < kMinInsertionRadius) break;
        const SlotId slot = *m.firstFreeSlot();
        glm::dvec3 point = circle.centre;
        if (m.isDisc() && glm::length(point) > 1.0) point /= glm::length(point);
        if (!m.triangulation->insert({slot, point})) break;  // numerically on top of a sample

        VplSample& s = m.samples[slot];
        s.domainPoint = point;
        s.directionWorld = m.toWorldDirection(point);
        s.createdFrame = m.stats.frame;
        s.serial = m.nextSerial++;
        ++m.used;
        if (const std::optional<glm::vec3> hit = castRay(slot, s.directionWorld)) {
            s.kind = SampleKind::Vpl;
            s.positionWorld = *hit;
            ++m.stats.createdVpls;
        } else {
            s.kind = SampleKind::Miss;
            ++m.stats.createdMisses;
        }
        created.push_back(slot);
        circle = m.triangulation->largestEmptyCircle();
    }
    m.stats.dispersion = circle.radius;
    m.stats.creationMs += millisecondsSince(start);
    return created;
}

void VplDistribution::computeWeights() {
    Impl& m = *m_impl;
    const auto start = std::chrono::steady_clock::now();
    m.triangulation->cellAreas(m.areas);
    double vplArea = 0.0;
    for (SlotId slot = 0; slot < m.samples.size(); ++slot)
        if (m.samples[slot].kind == SampleKind::Vpl) vplArea += m.areas[slot];
    const double domainArea = m.triangulation->domainArea();
    for (SlotId slot = 0; slot < m.samples.size(); ++slot) {
        VplSample& s = m.samples[slot];
        s.cellArea = m.areas[slot];
        s.fluxFraction = s.cellArea / domainArea;
        s.weight = s.kind == SampleKind::Vpl && vplArea > 0.0 ? s.cellArea / vplArea : 0.0;
    }
    m.countKinds();
    m.stats.weightsMs += millisecondsSince(start);
}

void VplDistribution::clear() {
    Impl& m = *m_impl;
    m.triangulation->clear();
    std::fill(m.samples.begin(), m.samples.end(), VplSample{});
    std::fill(m.areas.begin(), m.areas.end(), 0.0);
    m.used = 0;
}

const SamplingDomain& VplDistribution::domain() const { return m_impl->domain; }
const VplDistributionParams& VplDistribution::params() const { return m_impl->params; }
std::span<const VplSample> VplDistribution::samples() const { return m_impl->samples; }

const VplSample& VplDistribution::sample(SlotId slot) const {
    BOUNCE_CHECK(slot < m_impl->samples.size(), "slot {} out of range (maxLights {})", slot,
                 m_impl->samples.size());
    return m_impl->samples[slot];
}

uint32_t VplDistribution::sampleCount() const { return m_impl->used; }

uint32_t VplDistribution::vplCount() const {
    uint32_t count = 0;
    for (const VplSample& s : m_impl->samples)
        if (s.kind == SampleKind::Vpl) ++count;
    return count;
}

const VplFrameStats& VplDistribution::frameStats() const { return m_impl->stats; }
double VplDistribution::dispersion() { return m_impl->triangulation->largestEmptyCircle().radius; }
const DomainTriangulation& VplDistribution::triangulation() const { return *m_impl->triangulation; }

std::optional<glm::dvec3> VplDistribution::toDomain(const glm::dvec3& directionWorld) const {
    return m_impl->toDomain(directionWorld);
}

glm::dvec3 VplDistribution::toWorldDirection(const glm::dvec3& domainPoint) const {
    return m_impl->toWorldDirection(domainPoint);
}

}  // namespace bounce
