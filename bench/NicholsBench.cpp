// Nichols (2010) Ch. 4 results as ratios measured in one run (docs/techniques/isr.md "Measured"):
//   BM_NicholsR1       R1 at the thesis's 1024^2 image, RSM 256^2, 256 VPLs: frame and per-pass times of
//                      isr (regular VPLs: the stencilled gather of Table 4.1), multires-splat (Ch. 3,
//                      mode B), the full-resolution rsm gather, hisr and isr's light clusters; one
//                      timed frame each (llvmpipe needs seconds per frame at 1024^2).
//   BM_NicholsError    the same techniques at 64^2 with the relative RMS error of the indirect image
//                      against the million-VPL gather (rsm, rsmSize = vplGrid = 1024: Figs. 4.9/4.13),
//                      and the every-texel gathers of 128^2 and 256^2 RSMs (the tests' limit).
//   BM_NicholsFill     multires-splat subsplats per VPL as a fraction of full fill (R2).
//   BM_NicholsAtrium   isr frame time at 256^2 against atrium's triangle count (R3).
// Run R1 and the errors with --benchmark_filter='NicholsR1|NicholsError' (a few minutes: the
// million-VPL gather alone takes about two minutes at 64^2 on llvmpipe).
#include "BenchSupport.h"
#include "gpu/Context.h"
#include "metrics/ErrorMetrics.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>

namespace {

using namespace bounce;

gl::Context* context() { return bench::context(); }

std::unique_ptr<Pipeline> pipeline(const Scene& scene, const std::string& technique,
                                   const std::map<std::string, std::string>& settings, int size) {
    auto t = createTechnique(technique);
    if (!t.ok() || !applySettings(**t, settings, technique).ok()) return nullptr;
    render::RenderSettings rs;
    rs.shadowMapSize = 512;
    auto p = Pipeline::create(scene, std::move(*t), {size, size}, rs);
    return p.ok() ? std::move(*p) : nullptr;
}

const Scene& cornellBox() {
    static Scene scene = *loadScene("cornell-box");
    return scene;
}

// The million-VPL gather (every texel of a 1024^2 RSM is a VPL; cornell-box's spot has one map), per
// image size: the converged limit of Figs. 4.9/4.13.
constexpr int kLimitRsmSize = 1024;
const Image& limitImage(int size) {
    static std::map<int, Image> cache;
    auto it = cache.find(size);
    if (it != cache.end()) return it->second;
    const std::string rsm = std::to_string(kLimitRsmSize);
    auto p = pipeline(cornellBox(), "rsm", {{"rsmSize", rsm}, {"vplGrid", rsm}}, size);
    p->renderFrame(0);
    return cache[size] = p->readback(Component::Indirect);
}

void runFrames(benchmark::State& state, Pipeline& p) {
    p.renderFrame(0);  // warm-up: programs linked, static shadow maps rendered
    std::map<std::string, double> passes;
    FrameStats last;
    uint32_t frame = 1;
    for (auto _ : state) {
        last = p.renderFrame(frame++);
        state.SetIterationTime(last.cpuMilliseconds * 1e-3);
        for (const gl::PassTime& t : last.passes) passes[t.name] += t.milliseconds;
    }
    const double n = static_cast<double>(state.iterations());
    for (const auto& [name, ms] : passes)
        if (name.find('/') != std::string::npos || name == "frame") state.counters[name + "_ms"] = ms / n;
    for (const auto& [name, value] : last.counters) state.counters[name] = value;
}

// R1 and the speed-ups are measured at the thesis's RSM (256^2) and VPL count (256).
constexpr const char* kRsmSize = "256";

void BM_NicholsR1(benchmark::State& state, std::string technique, std::map<std::string, std::string> settings) {
    if (!context()) {
        state.SkipWithError("no GL context");
        return;
    }
    settings.emplace("rsmSize", kRsmSize);
    auto p = pipeline(cornellBox(), technique, settings, static_cast<int>(state.range(0)));
    if (!p) {
        state.SkipWithError("pipeline");
        return;
    }
    runFrames(state, *p);
}

void BM_NicholsError(benchmark::State& state, std::string technique, std::map<std::string, std::string> settings) {
    if (!context()) {
        state.SkipWithError("no GL context");
        return;
    }
    const int size = static_cast<int>(state.range(0));
    const Image& limit = limitImage(size);
    settings.emplace("rsmSize", kRsmSize);
    auto p = pipeline(cornellBox(), technique, settings, size);
    if (!p) {
        state.SkipWithError("pipeline");
        return;
    }
    runFrames(state, *p);
    state.counters["relRms"] = relativeRmsError(p->readback(Component::Indirect), limit);
}

void BM_NicholsFill(benchmark::State& state) {
    if (!context()) {
        state.SkipWithError("no GL context");
        return;
    }
    const int size = static_cast<int>(state.range(0));
    auto p = pipeline(cornellBox(), "multires-splat", {{"rsmSize", "64"}, {"vplGrid", "16"}}, size);
    runFrames(state, *p);
}

void BM_NicholsAtrium(benchmark::State& state) {
    if (!context()) {
        state.SkipWithError("no GL context");
        return;
    }
    static std::map<int64_t, Scene> scenes;
    if (!scenes.count(state.range(0))) scenes[state.range(0)] = *loadScene("atrium", {{"triangles", std::to_string(state.range(0))}});
    auto p = pipeline(scenes[state.range(0)], "isr", {{"rsmSize", "128"}, {"vplMode", "regular"}, {"vplGrid", "16"}}, 256);
    runFrames(state, *p);
}

using Settings = std::map<std::string, std::string>;
const Settings kGrid256{{"vplGrid", "16"}};
const Settings kRegular256{{"vplMode", "regular"}, {"vplGrid", "16"}};
const Settings kClusters{{"lightFinest", "64"}};

// One timed frame after the warm-up frame: at 1024^2 a frame takes seconds to tens of seconds on llvmpipe.
#define NICHOLS_R1(name, technique, settings) \
    BENCHMARK_CAPTURE(BM_NicholsR1, name, std::string(technique), settings) \
        ->Arg(1024)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1)
#define NICHOLS_ERROR(name, technique, settings) \
    BENCHMARK_CAPTURE(BM_NicholsError, name, std::string(technique), settings) \
        ->Arg(64)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1)

NICHOLS_R1(isr_regular_256vpl, "isr", kRegular256);
NICHOLS_R1(multires_splat_256vpl, "multires-splat", kGrid256);
NICHOLS_R1(rsm_256vpl, "rsm", kGrid256);
NICHOLS_R1(hisr, "hisr", Settings{});
NICHOLS_R1(isr_clusters, "isr", kClusters);
NICHOLS_ERROR(isr_regular_256vpl, "isr", kRegular256);
NICHOLS_ERROR(multires_splat_256vpl, "multires-splat", kGrid256);
NICHOLS_ERROR(rsm_256vpl, "rsm", kGrid256);
NICHOLS_ERROR(hisr, "hisr", Settings{});
NICHOLS_ERROR(isr_clusters, "isr", kClusters);
NICHOLS_ERROR(rsm_every_texel_128, "rsm", (Settings{{"rsmSize", "128"}, {"vplGrid", "128"}}));
NICHOLS_ERROR(rsm_every_texel_256, "rsm", (Settings{{"rsmSize", "256"}, {"vplGrid", "256"}}));
BENCHMARK(BM_NicholsFill)->Arg(32)->Arg(64)->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.2);
BENCHMARK(BM_NicholsAtrium)->Arg(25000)->Arg(100000)->Arg(400000)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);

}  // namespace
