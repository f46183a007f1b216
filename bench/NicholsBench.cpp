// Nichols (2010) Ch. 4 results as ratios measured in one run (docs/techniques/isr.md "Measured"):
//   BM_NicholsGather   rsm (full-resolution gather) vs isr (regular VPLs: the stencilled gather of
//                      Table 4.1; clusters: §4.2.2) vs hisr at the same VPL budget (256), with the
//                      relative RMS error against the every-texel gather of a 128^2 RSM (R6).
//   BM_NicholsGather   also multires-splat (Ch. 3, mode B) and full-screen rsm-splat at 256 VPLs (R1).
//   BM_NicholsFill     multires-splat subsplats per VPL as a fraction of full fill (R2).
//   BM_NicholsAtrium   isr frame time at 256^2 against atrium's triangle count (R3).
// llvmpipe (CPU rasteriser) sizes: images 32^2..256^2, not the thesis's 1024^2.
#include "gpu/Context.h"
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

gl::Context* context() {
    static std::unique_ptr<gl::Context> c = [] {
        auto made = gl::Context::createHeadless();
        return made.ok() ? std::move(*made) : std::unique_ptr<gl::Context>();
    }();
    if (c) c->makeCurrent();
    return c.get();
}

std::unique_ptr<Pipeline> pipeline(const Scene& scene, const std::string& technique,
                                   const std::map<std::string, std::string>& settings, int size) {
    auto t = createTechnique(technique);
    if (!t.ok() || !applySettings(**t, settings, technique).ok()) return nullptr;
    render::RenderSettings rs;
    rs.shadowMapSize = 512;
    auto p = Pipeline::create(scene, std::move(*t), {size, size}, rs);
    return p.ok() ? std::move(*p) : nullptr;
}

double relativeRms(const Image& test, const Image& reference) {
    double num = 0.0, den = 0.0;
    for (int y = 0; y < test.height(); ++y)
        for (int x = 0; x < test.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                const double d = double(test.at(x, y)[c]) - reference.at(x, y)[c];
                num += d * d;
                den += double(reference.at(x, y)[c]) * reference.at(x, y)[c];
            }
    return den > 0.0 ? std::sqrt(num / den) : 0.0;
}

const Scene& cornellBox() {
    static Scene scene = *loadScene("cornell-box");
    return scene;
}

// The every-texel gather of a 128^2 RSM (16k VPLs), per image size (the thesis's 1M-VPL reference
// does not finish in reasonable time on llvmpipe).
const Image& limitImage(int size) {
    static std::map<int, Image> cache;
    auto it = cache.find(size);
    if (it != cache.end()) return it->second;
    auto p = pipeline(cornellBox(), "rsm", {{"rsmSize", "128"}, {"vplGrid", "128"}}, size);
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

void BM_NicholsGather(benchmark::State& state, std::string technique, std::map<std::string, std::string> settings) {
    if (!context()) {
        state.SkipWithError("no GL context");
        return;
    }
    const int size = static_cast<int>(state.range(0));
    settings["rsmSize"] = "128";
    auto p = pipeline(cornellBox(), technique, settings, size);
    if (!p) {
        state.SkipWithError("pipeline");
        return;
    }
    runFrames(state, *p);
    state.counters["relRms"] = relativeRms(p->readback(Component::Indirect), limitImage(size));
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

const std::map<std::string, std::string> kRegular256{{"vplMode", "regular"}, {"vplGrid", "16"}};

BENCHMARK_CAPTURE(BM_NicholsGather, rsm_256vpl, std::string("rsm"), std::map<std::string, std::string>{{"vplGrid", "16"}})
    ->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK_CAPTURE(BM_NicholsGather, isr_regular_256vpl, std::string("isr"), kRegular256)
    ->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK_CAPTURE(BM_NicholsGather, multires_splat_256vpl, std::string("multires-splat"), std::map<std::string, std::string>{{"vplGrid", "16"}})
    ->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK_CAPTURE(BM_NicholsGather, rsm_splat_full_256vpl, std::string("rsm-splat"), std::map<std::string, std::string>{{"vplGrid", "16"}})
    ->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK_CAPTURE(BM_NicholsGather, isr_clusters, std::string("isr"), std::map<std::string, std::string>{{"lightFinest", "64"}})
    ->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK_CAPTURE(BM_NicholsGather, hisr, std::string("hisr"), std::map<std::string, std::string>{})
    ->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK(BM_NicholsFill)->Arg(32)->Arg(64)->Arg(128)->Arg(256)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.2);
BENCHMARK(BM_NicholsAtrium)->Arg(25000)->Arg(100000)->Arg(400000)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);

}  // namespace
