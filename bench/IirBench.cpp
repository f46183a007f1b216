// Incremental instant radiosity (Laine et al. 2007): the paper's headline results as ratios measured
// in one run on this machine (docs/techniques/iir.md "Measured results"):
//   R1  VPL shadow-map time, comparison method over incremental (paper: 41-45x)
//   R2  frame speed-up over the comparison method, cornell-box-dynamic (paper, CORNELL: 1.9x)
//   R3  the same on atrium, a bigger scene (paper: grows with complexity, 3.9x MAZE, 6.8x SIBENIK)
//   R5  VPL management CPU time, omni over spot light (paper: 16.0-16.2 / 3.6-5.0 ms = 3-4.5x)
//   R6  frame speed-up with 1024 VPLs (paper: 31 vs 2 fps on SIBENIK = 15x)
// Every benchmark renders one warm-up frame (the first frame fills the VPL budget in both modes),
// then times kFrames frames of the animation. Images are 256^2 (the paper: 1024x768); llvmpipe
// absolute times are indicative only.
#include "gpu/Context.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/iir/IirTechnique.h"

#include <benchmark/benchmark.h>

#include <map>
#include <string>

namespace {

using namespace bounce;

constexpr int kImageSize = 256;          // pixels per side
constexpr uint32_t kFrames = 4;          // timed frames per configuration
constexpr uint32_t kFrameStep = 3;       // frames apart: the light moves a few cm per step
constexpr double kAtriumTriangles = 20000;  // atrium detail; 100K makes the comparison run minutes long

gl::Context* context() {
    static std::unique_ptr<gl::Context> c;
    if (!c) {
        gl::ContextConfig config;
        config.debugOutput = false;
        auto made = gl::Context::createHeadless(config);
        if (!made.ok()) return nullptr;
        c = std::move(*made);
    }
    c->makeCurrent();
    return c.get();
}

struct Measured {
    double frameMs = 0.0;        // wall time of a frame, GPU wait included
    double shadowMapMs = 0.0;    // "iir/sm-rendering"
    double indirectMs = 0.0;     // "iir" (everything the technique does, CPU included)
    double managementMs = 0.0;   // VPL management on the CPU (counter vplManagementMs)
};

Measured measure(const Scene& scene, bool incremental, int maxLights) {
    auto technique = std::make_unique<IirTechnique>();
    const std::map<std::string, std::string> settings = {{"incremental", incremental ? "true" : "false"},
                                                         {"maxLights", std::to_string(maxLights)}};
    if (!applySettings(*technique, settings, "technique 'iir'").ok()) return {};
    render::RenderSettings rs;
    auto pipeline = Pipeline::create(scene, std::move(technique), {kImageSize, kImageSize}, rs);
    if (!pipeline.ok()) return {};
    (*pipeline)->renderFrame(0);
    Measured m;
    for (uint32_t k = 1; k <= kFrames; ++k) {
        const FrameStats s = (*pipeline)->renderFrame(k * kFrameStep);
        m.frameMs += s.cpuMilliseconds / kFrames;
        m.managementMs += s.counters.at("vplManagementMs") / kFrames;
        for (const gl::PassTime& p : s.passes) {
            if (p.name == "iir/sm-rendering") m.shadowMapMs += p.milliseconds / kFrames;
            if (p.name == "iir") m.indirectMs += p.milliseconds / kFrames;
        }
    }
    return m;
}

Scene loadOrEmpty(const std::string& name, const SceneParams& params = {}) {
    auto s = loadScene(name, params);
    return s.ok() ? std::move(*s) : Scene{};
}

void compareModes(benchmark::State& state, const Scene& scene, int maxLights) {
    if (!context()) {
        state.SkipWithError("no GL context");
        return;
    }
    Measured inc, comp;
    for (auto _ : state) {
        inc = measure(scene, true, maxLights);
        comp = measure(scene, false, maxLights);
    }
    state.counters["incFrameMs"] = inc.frameMs;
    state.counters["compFrameMs"] = comp.frameMs;
    state.counters["incSmMs"] = inc.shadowMapMs;
    state.counters["compSmMs"] = comp.shadowMapMs;
    state.counters["incMgmtMs"] = inc.managementMs;
    state.counters["compMgmtMs"] = comp.managementMs;
    state.counters["R1_smRatio"] = inc.shadowMapMs > 0.0 ? comp.shadowMapMs / inc.shadowMapMs : 0.0;
    state.counters["frameSpeedup"] = inc.frameMs > 0.0 ? comp.frameMs / inc.frameMs : 0.0;
    state.counters["indirectSpeedup"] = inc.indirectMs > 0.0 ? comp.indirectMs / inc.indirectMs : 0.0;
    state.counters["triangles"] = static_cast<double>(scene.triangleCount());
}

// R1, R2: cornell-box-dynamic, 256 VPLs.
void BM_IirCornellDynamic(benchmark::State& state) {
    static const Scene scene = loadOrEmpty("cornell-box-dynamic");
    compareModes(state, scene, 256);
}
BENCHMARK(BM_IirCornellDynamic)->Iterations(1)->Unit(benchmark::kMillisecond);

// R3: atrium (directional sun as a distant spot), 256 VPLs.
void BM_IirAtrium(benchmark::State& state) {
    static const Scene scene = loadOrEmpty("atrium", {{"triangles", std::to_string(kAtriumTriangles)}});
    compareModes(state, scene, 256);
}
BENCHMARK(BM_IirAtrium)->Iterations(1)->Unit(benchmark::kMillisecond);

// R6: 1024 VPLs on cornell-box-dynamic.
void BM_IirCornell1024(benchmark::State& state) {
    static const Scene scene = loadOrEmpty("cornell-box-dynamic");
    compareModes(state, scene, 1024);
}
BENCHMARK(BM_IirCornell1024)->Iterations(1)->Unit(benchmark::kMillisecond);

// R5: the same moving light as an omni (sphere domain) and as the scene's spot (disc domain).
void BM_IirOmniVsSpot(benchmark::State& state) {
    if (!context()) {
        state.SkipWithError("no GL context");
        return;
    }
    static const Scene spot = loadOrEmpty("cornell-box-dynamic");
    static const Scene omni = [] {
        Scene s = loadOrEmpty("cornell-box-dynamic");
        if (!s.lights.empty()) {
            // Same position and path; I0 / 4 keeps the flux in the same range as the spot's pi*I0.
            s.lights[0].type = LightType::Point;
            s.lights[0].intensity *= 0.25f;
        }
        return s;
    }();
    Measured sm, om;
    for (auto _ : state) {
        sm = measure(spot, true, 256);
        om = measure(omni, true, 256);
    }
    state.counters["spotMgmtMs"] = sm.managementMs;
    state.counters["omniMgmtMs"] = om.managementMs;
    state.counters["R5_omniOverSpot"] = sm.managementMs > 0.0 ? om.managementMs / sm.managementMs : 0.0;
}
BENCHMARK(BM_IirOmniVsSpot)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
