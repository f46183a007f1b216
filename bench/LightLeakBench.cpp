// The `two-rooms` light-leak score (metrics/LightLeak.h) of techniques and settings, a number that
// needs the library rather than the CLI: bench/vct/run.py and bench/photon-splat/run.py run this
// and store its JSON in their raw records. vct: the thesis claims SH mixes and leaks less than
// isotropic voxels (5.3.1/5.3.3); photon-splat: the document reports leaks with 3x larger maps (5.3.1).
#include "BenchSupport.h"
#include "metrics/LightLeak.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <benchmark/benchmark.h>

#include <array>
#include <map>
#include <string>

namespace {

using namespace bounce;

constexpr int kImageSize = 128;              // pixels per side
constexpr float kWallHalfThickness = 0.01f;  // two-rooms' default 2 cm wall (metres)
constexpr std::array<const char*, 4> kStorages = {"iso", "aniso", "sh-f32", "sh-u8"};

double leakOf(benchmark::State& state, const std::string& technique, const std::map<std::string, std::string>& settings) {
    auto scene = loadScene("two-rooms");
    auto t = createTechnique(technique);
    if (!scene.ok() || !t.ok() || !applySettings(**t, settings, technique).ok()) {
        state.SkipWithError("set-up failed");
        return -1.0;
    }
    auto p = Pipeline::create(*scene, std::move(*t), {kImageSize, kImageSize}, render::RenderSettings{});
    if (!p.ok()) {
        state.SkipWithError(p.error().message.c_str());
        return -1.0;
    }
    double leak = 0.0;
    for (auto _ : state) {
        (*p)->renderFrame(0);
        const TwoRoomsMasks masks = twoRoomsMasks(readTexture((*p)->gbuffer().position()), kWallHalfThickness);
        auto score = lightLeakScore((*p)->readback(Component::Full), masks.dark, masks.lit);
        leak = score.ok() ? *score : -1.0;
    }
    return leak;
}

// photon-splat (flux estimate, 4096 photons) with the automatic bundle width times range(0) / 2.
void BM_PhotonSplatLightLeak(benchmark::State& state) {
    if (!bench::context()) {
        state.SkipWithError("no GL context");
        return;
    }
    // The automatic width is a twentieth of two-rooms' bounds diagonal (4.60 m): 0.230 m.
    const double width = 0.230 * static_cast<double>(state.range(0)) / 2.0;
    state.SetLabel("photon-splat@" + std::to_string(state.range(0) / 2.0).substr(0, 3) + "x");
    state.counters["leak"] = leakOf(state, "photon-splat", {{"estimate", "flux"}, {"photons", "4096"}, {"mapSize", std::to_string(width)}});
}

void BM_RsmLightLeak(benchmark::State& state) {
    if (!bench::context()) {
        state.SkipWithError("no GL context");
        return;
    }
    state.SetLabel("rsm");
    state.counters["leak"] = leakOf(state, "rsm", {});
}

void BM_VctLightLeak(benchmark::State& state) {
    if (!bench::context()) {
        state.SkipWithError("no GL context");
        return;
    }
    const std::string storage = kStorages.at(static_cast<size_t>(state.range(0)));
    const std::string resolution = std::to_string(state.range(1));
    const double leak = leakOf(state, "vct", {{"storage", storage}, {"resolution", resolution}});
    state.SetLabel(storage + "@" + resolution);
    state.counters["leak"] = leak;
}

}  // namespace

BENCHMARK(BM_VctLightLeak)->ArgsProduct({{0, 1, 2, 3}, {64, 128}})->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PhotonSplatLightLeak)->Arg(2)->Arg(6)->Iterations(1)->Unit(benchmark::kMillisecond);  // 1x and 3x maps
BENCHMARK(BM_RsmLightLeak)->Iterations(1)->Unit(benchmark::kMillisecond);
