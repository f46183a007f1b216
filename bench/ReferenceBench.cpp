// The reference path tracer and the ray-casting service on cornell-box-area.
//   build/bench/bounce_bench --benchmark_filter=Reference --benchmark_repetitions=3
// Counters: paths/s (camera paths, one per pixel sample) and rays/s (camera, continuation and
// shadow rays given to Embree), both per second of wall-clock time on every core.
#include "reference/PathTracer.h"
#include "reference/RayCaster.h"
#include "reference/Rng.h"
#include "scene/SceneLoader.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using namespace bounce;

constexpr int kImageSide = 512;       // pixels
constexpr int kMaxReflections = 64;   // "max depth 64": 63 indirect bounces after the direct one
constexpr uint32_t kSamplesPerPixel = 4;  // one pass of 2^20 paths per iteration

const Scene& cornellBoxArea() {
    static const Scene scene = [] {
        auto loaded = loadScene("cornell-box-area");
        if (!loaded) {
            std::fprintf(stderr, "ReferenceBench: %s\n", loaded.error().message.c_str());
            std::exit(1);
        }
        return std::move(loaded).value();
    }();
    return scene;
}

void BM_ReferencePathTracerCornellBoxArea(benchmark::State& state) {
    PathTracerSettings settings;
    settings.width = settings.height = kImageSide;
    settings.samplesPerPixel = kSamplesPerPixel;
    settings.bounces = kMaxReflections - 1;
    settings.threads = static_cast<int>(state.range(0));
    settings.vectorized = state.range(1) != 0;
    auto tracer = PathTracer::create(cornellBoxArea(), settings);
    if (!tracer) {
        state.SkipWithError(tracer.error().message.c_str());
        return;
    }
    uint64_t paths = 0, rays = 0;
    for (auto _ : state) {
        const PathTracerResult result = tracer->render();
        benchmark::DoNotOptimize(result.radiance.data());
        paths += result.paths;
        rays += result.rays;
    }
    state.counters["paths/s"] = benchmark::Counter(static_cast<double>(paths), benchmark::Counter::kIsRate);
    state.counters["rays/s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
    state.counters["rays/path"] = static_cast<double>(rays) / static_cast<double>(paths);
}
// Arguments: worker threads (0 = every core), vectorised kernel (1) or scalar code only (0).
BENCHMARK(BM_ReferencePathTracerCornellBoxArea)
    ->ArgNames({"threads", "vectorized"})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The other light kinds and smooth normals: cornell-box (a spot light), two-rooms (a point light,
// two rooms joined by a door) and atrium at its default 100K triangles (a directional sun, smooth
// columns); 256 x 256, 16 spp, unbounded paths, with and without the vectorised kernel.
void BM_ReferencePathTracerScenes(benchmark::State& state) {
    static const char* const kScenes[] = {"cornell-box", "two-rooms", "atrium"};
    const char* name = kScenes[state.range(0)];
    auto scene = loadScene(name);
    if (!scene) {
        state.SkipWithError(scene.error().message.c_str());
        return;
    }
    PathTracerSettings settings;
    settings.width = settings.height = 256;
    settings.samplesPerPixel = 16;
    settings.vectorized = state.range(1) != 0;
    auto tracer = PathTracer::create(*scene, settings);
    if (!tracer) {
        state.SkipWithError(tracer.error().message.c_str());
        return;
    }
    uint64_t paths = 0;
    for (auto _ : state) {
        const PathTracerResult result = tracer->render();
        benchmark::DoNotOptimize(result.radiance.data());
        paths += result.paths;
    }
    state.SetLabel(name);
    state.counters["paths/s"] = benchmark::Counter(static_cast<double>(paths), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReferencePathTracerScenes)
    ->ArgNames({"scene", "vectorized"})
    ->ArgsProduct({{0, 1, 2}, {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Incoherent rays from random points inside the box in random directions: the raw Embree rate
// through the ray-casting service, single rays and batches.
std::vector<CastRay> randomRaysInBox(size_t count) {
    std::vector<CastRay> rays(count);
    for (size_t i = 0; i < count; ++i) {
        Rng rng(1, i, 0);
        // The box spans about 0..0.556 m in x and z and 0..0.549 m in y (Cornell data, metres).
        rays[i].origin = {0.05f + 0.45f * rng.next(), 0.01f + 0.5f * rng.next(), 0.05f + 0.45f * rng.next()};
        rays[i].direction = {rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f};
    }
    return rays;
}

constexpr size_t kRayBatch = 1 << 16;

void BM_ReferenceRayCasterClosestHitSingle(benchmark::State& state) {
    auto caster = RayCaster::create(cornellBoxArea(), 0.0f, GeometryFilter::All);
    const std::vector<CastRay> rays = randomRaysInBox(kRayBatch);
    for (auto _ : state)
        for (const CastRay& r : rays) benchmark::DoNotOptimize(caster->closestHit(r.origin, r.direction));
    state.counters["rays/s"] = benchmark::Counter(static_cast<double>(state.iterations() * kRayBatch),
                                                  benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReferenceRayCasterClosestHitSingle)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReferenceRayCasterClosestHitBatch(benchmark::State& state) {
    auto caster = RayCaster::create(cornellBoxArea(), 0.0f, GeometryFilter::All);
    const std::vector<CastRay> rays = randomRaysInBox(kRayBatch);
    std::vector<std::optional<RayHit>> hits(rays.size());
    for (auto _ : state) {
        caster->closestHits(rays, hits);
        benchmark::DoNotOptimize(hits.data());
    }
    state.counters["rays/s"] = benchmark::Counter(static_cast<double>(state.iterations() * kRayBatch),
                                                  benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReferenceRayCasterClosestHitBatch)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReferenceRayCasterOccludedBatch(benchmark::State& state) {
    auto caster = RayCaster::create(cornellBoxArea(), 0.0f, GeometryFilter::All);
    const std::vector<CastRay> rays = randomRaysInBox(kRayBatch);
    std::vector<Segment> segments(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) segments[i] = {rays[i].origin, rays[i].origin + rays[i].direction};
    std::vector<uint8_t> blocked(rays.size());
    for (auto _ : state) {
        caster->occluded(segments, blocked);
        benchmark::DoNotOptimize(blocked.data());
    }
    state.counters["rays/s"] = benchmark::Counter(static_cast<double>(state.iterations() * kRayBatch),
                                                  benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReferenceRayCasterOccludedBatch)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
