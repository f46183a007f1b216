// Per-frame cost of the incremental VPL distribution (Laine et al. 2007 §4, steps 1-4) without the
// scene's rays: the light moves inside an empty unit box, every VPL stays visible, so each frame
// re-maps and re-triangulates all samples, deletes recalcMin by the shortest-edge rule, creates as
// many at largest empty circles and recomputes every cell area. The paper: 3.6-5.0 ms (spot) and
// 16 ms (omni, 3D tetrahedralisation) for 256 VPLs on one 2.2 GHz Athlon 64 core, including rays.
#include "techniques/iir/VplDistribution.h"

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {

using namespace bounce;

// Exit point of a ray from inside the box [-1, 1]^3.
std::optional<glm::vec3> castInUnitBox(const glm::vec3& origin, const glm::dvec3& direction) {
    double t = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] > 0.0) t = std::min(t, (1.0 - origin[axis]) / direction[axis]);
        if (direction[axis] < 0.0) t = std::min(t, (-1.0 - origin[axis]) / direction[axis]);
    }
    return glm::vec3(glm::dvec3(origin) + t * direction);
}

LightPose poseAt(int frame, bool moving) {
    const float t = moving ? 0.02f * static_cast<float>(frame) : 0.0f;
    return LightPose{{0.3f * std::sin(t), 0.6f, 0.3f * std::cos(0.7f * t)},
                     glm::normalize(glm::vec3(0.2f * std::sin(1.3f * t), -1.0f, 0.1f))};
}

void runFrames(benchmark::State& state, const SamplingDomain& domain, bool moving) {
    const auto maxLights = static_cast<uint32_t>(state.range(0));
    VplDistribution distribution(domain, VplDistributionParams{maxLights, 4, 8, 1});
    int frame = 0;
    auto step = [&] {
        const LightPose pose = poseAt(frame++, moving);
        return distribution.update(
            pose, [](SlotId, const VplSample&) { return true; },
            [&](SlotId, const glm::dvec3& direction) { return castInUnitBox(pose.position, direction); });
    };
    while (distribution.sampleCount() < maxLights) step();  // fill before timing
    double validity = 0.0, deletion = 0.0, creation = 0.0, weights = 0.0;
    for (auto _ : state) {
        const VplFrameStats& stats = step();
        validity += stats.validityMs;
        deletion += stats.deletionMs;
        creation += stats.creationMs;
        weights += stats.weightsMs;
    }
    const double frames = static_cast<double>(state.iterations());
    state.counters["validity_ms"] = validity / frames;
    state.counters["deletion_ms"] = deletion / frames;
    state.counters["creation_ms"] = creation / frames;
    state.counters["weights_ms"] = weights / frames;
    state.counters["samples"] = distribution.sampleCount();
}

void BM_IirSpotMoving(benchmark::State& state) { runFrames(state, SamplingDomain::spot(1.0, 1.5707963267948966), true); }
void BM_IirSpotStatic(benchmark::State& state) { runFrames(state, SamplingDomain::spot(1.0, 1.5707963267948966), false); }
void BM_IirOmniMoving(benchmark::State& state) { runFrames(state, SamplingDomain::omni(), true); }
void BM_IirOmniStatic(benchmark::State& state) { runFrames(state, SamplingDomain::omni(), false); }

BENCHMARK(BM_IirSpotMoving)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IirSpotStatic)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IirOmniMoving)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IirOmniStatic)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);

}  // namespace
