// vct quality numbers that need the library rather than the CLI (bench/vct/run.py runs this and
// stores its JSON in the vct raw record): the `two-rooms` light-leak score per storage format (the
// thesis claims SH mixes and leaks less than isotropic voxels, 5.3.1/5.3.3).
#include "BenchSupport.h"
#include "metrics/LightLeak.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <benchmark/benchmark.h>

#include <array>
#include <string>

namespace {

using namespace bounce;

constexpr int kImageSize = 128;              // pixels per side
constexpr float kWallHalfThickness = 0.01f;  // two-rooms' default 2 cm wall (metres)
constexpr std::array<const char*, 4> kStorages = {"iso", "aniso", "sh-f32", "sh-u8"};

void BM_VctLightLeak(benchmark::State& state) {
    if (!bench::context()) {
        state.SkipWithError("no GL context");
        return;
    }
    const std::string storage = kStorages.at(static_cast<size_t>(state.range(0)));
    const std::string resolution = std::to_string(state.range(1));
    auto scene = loadScene("two-rooms");
    auto t = createTechnique("vct");
    if (!scene.ok() || !t.ok() || !applySettings(**t, {{"storage", storage}, {"resolution", resolution}}, "vct").ok()) {
        state.SkipWithError("set-up failed");
        return;
    }
    auto p = Pipeline::create(*scene, std::move(*t), {kImageSize, kImageSize}, render::RenderSettings{});
    if (!p.ok()) {
        state.SkipWithError(p.error().message.c_str());
        return;
    }
    double leak = 0.0;
    for (auto _ : state) {
        (*p)->renderFrame(0);
        const TwoRoomsMasks masks = twoRoomsMasks(readTexture((*p)->gbuffer().position()), kWallHalfThickness);
        auto score = lightLeakScore((*p)->readback(Component::Full), masks.dark, masks.lit);
        leak = score.ok() ? *score : -1.0;
    }
    state.SetLabel(storage + "@" + resolution);
    state.counters["leak"] = leak;
}

}  // namespace

BENCHMARK(BM_VctLightLeak)->ArgsProduct({{0, 1, 2, 3}, {64, 128}})->Iterations(1)->Unit(benchmark::kMillisecond);
