// Incremental instant radiosity (Laine et al. 2007): the paper's headline results as ratios measured
// in one run on this machine (docs/techniques/iir.md "Measured results"):
//   R1  VPL shadow-map time, comparison method over incremental (paper: 41-45x)
//   R2  frame speed-up over the comparison method, cornell-box-dynamic (paper, CORNELL: 1.9x)
//   R3  the same on atrium, a bigger scene (paper: grows with complexity, 3.9x MAZE, 6.8x SIBENIK)
//   R5  VPL management CPU time, omni over spot light (paper: 16.0-16.2 / 3.6-5.0 ms = 3-4.5x)
//   R6  frame speed-up with 1024 VPLs (paper: 31 vs 2 fps on SIBENIK = 15x)
// and the indirect image against the one-bounce path-traced reference over an animation
// (BM_IirQuality: relMSE and FLIP averaged over frames; the paper has no ground truth).
// Every benchmark renders one warm-up frame (the first frame fills the VPL budget in both modes),
// then times kFrames frames of the animation. Images are 256^2 (the paper: 1024x768); llvmpipe
// absolute times are indicative only.
#include "BenchSupport.h"
#include "gpu/Context.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/FlickerMeter.h"
#include "reference/PathTracer.h"
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
constexpr uint32_t kFrames = 8;          // timed frames per configuration
constexpr uint32_t kFrameStep = 3;       // frames apart: the light moves a few cm per step
constexpr uint32_t kManagementFrames = 16;  // R5 compares CPU times of ~1 ms: more frames
constexpr double kAtriumTriangles = 20000;  // atrium detail; 100K makes the comparison run minutes long

gl::Context* context() { return bench::context(); }

struct Measured {
    double frameMs = 0.0;        // wall time of a frame, GPU wait included
    double shadowMapMs = 0.0;    // "iir/sm-rendering"
    double indirectMs = 0.0;     // "iir" (everything the technique does, CPU included)
    double managementMs = 0.0;   // VPL management on the CPU (counter vplManagementMs)
    std::map<std::string, double> passMs;  // every timed pass (Table 1 and 2 rows), mean per frame
};

Measured measure(const Scene& scene, bool incremental, int maxLights, uint32_t frames = kFrames) {
    auto technique = std::make_unique<IirTechnique>();
    const std::map<std::string, std::string> settings = {{"incremental", incremental ? "true" : "false"},
                                                         {"maxLights", std::to_string(maxLights)}};
    if (!applySettings(*technique, settings, "technique 'iir'").ok()) return {};
    render::RenderSettings rs;
    auto pipeline = Pipeline::create(scene, std::move(technique), {kImageSize, kImageSize}, rs);
    if (!pipeline.ok()) return {};
    (*pipeline)->renderFrame(0);
    Measured m;
    for (uint32_t k = 1; k <= frames; ++k) {
        const FrameStats s = (*pipeline)->renderFrame(k * kFrameStep);
        m.frameMs += s.cpuMilliseconds / frames;
        m.managementMs += s.counters.at("vplManagementMs") / frames;
        for (const gl::PassTime& p : s.passes) {
            m.passMs[p.name] += p.milliseconds / frames;
            if (p.name == "iir/sm-rendering") m.shadowMapMs += p.milliseconds / frames;
            if (p.name == "iir") m.indirectMs += p.milliseconds / frames;
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
    // Table 1 and 2 rows of the incremental run: G-buffer, direct (shadow maps + shading), split,
    // accumulation, combine, filter.
    for (const char* name : {"gbuffer", "shadow-maps", "direct", "iir/split", "iir/accum", "iir/combine", "iir/filter"}) {
        const auto it = inc.passMs.find(name);
        if (it != inc.passMs.end()) state.counters[std::string("inc:") + name] = it->second;
    }
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

// R6: 1024 VPLs, on cornell-box-dynamic and on atrium (the paper's figure is SIBENIK's).
void BM_IirCornell1024(benchmark::State& state) {
    static const Scene scene = loadOrEmpty("cornell-box-dynamic");
    compareModes(state, scene, 1024);
}
BENCHMARK(BM_IirCornell1024)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_IirAtrium1024(benchmark::State& state) {
    static const Scene scene = loadOrEmpty("atrium", {{"triangles", std::to_string(kAtriumTriangles)}});
    compareModes(state, scene, 1024);
}
BENCHMARK(BM_IirAtrium1024)->Iterations(1)->Unit(benchmark::kMillisecond);

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
        sm = measure(spot, true, 256, kManagementFrames);
        om = measure(omni, true, 256, kManagementFrames);
    }
    state.counters["spotMgmtMs"] = sm.managementMs;
    state.counters["omniMgmtMs"] = om.managementMs;
    state.counters["R5_omniOverSpot"] = sm.managementMs > 0.0 ? om.managementMs / sm.managementMs : 0.0;
}
BENCHMARK(BM_IirOmniVsSpot)->Iterations(1)->Unit(benchmark::kMillisecond);

// Indirect light against `bounce reference --bounces 1 --indirect-only` (diffuse-only paths, as the
// VPLs are diffuse), frame by frame over the animation.
constexpr int kQualitySize = 128;            // pixels per side
constexpr uint32_t kQualityFrames = 6;       // frames 0, 10, ..., 50 of the animation
constexpr uint32_t kQualityFrameStep = 10;
constexpr uint32_t kReferenceSamples = 128;  // per pixel; leaves ~3 % noise in the reference

void quality(benchmark::State& state, const std::string& sceneName) {
    if (!context()) {
        state.SkipWithError("no GL context");
        return;
    }
    const Scene scene = loadOrEmpty(sceneName);
    double relMse = 0.0, flip = 0.0, meanRatio = 0.0;
    for (auto _ : state) {
        auto technique = std::make_unique<IirTechnique>();
        auto pipeline = Pipeline::create(scene, std::move(technique), {kQualitySize, kQualitySize}, {});
        if (!pipeline.ok()) {
            state.SkipWithError(pipeline.error().message.c_str());
            return;
        }
        // Frames are rendered in order so that the incremental state evolves as in an animation.
        for (uint32_t f = 0; f <= (kQualityFrames - 1) * kQualityFrameStep; ++f) {
            (*pipeline)->renderFrame(f);
            if (f % kQualityFrameStep != 0) continue;
            const Image iir = (*pipeline)->readback(Component::Indirect);
            PathTracerSettings pts;
            pts.width = pts.height = kQualitySize;
            pts.samplesPerPixel = kReferenceSamples;
            pts.bounces = 1;
            pts.indirectOnly = true;
            pts.diffuseOnly = true;
            pts.frame = f;
            auto tracer = PathTracer::create(scene, pts);
            if (!tracer.ok()) {
                state.SkipWithError(tracer.error().message.c_str());
                return;
            }
            const Image reference = tracer->render().radiance;
            auto m = compareImages(iir, reference);
            if (!m.ok()) {
                state.SkipWithError(m.error().message.c_str());
                return;
            }
            double a = 0.0, b = 0.0;
            for (const glm::vec3& p : iir.pixels()) a += p.r + p.g + p.b;
            for (const glm::vec3& p : reference.pixels()) b += p.r + p.g + p.b;
            relMse += m->relMse / kQualityFrames;
            flip += m->flipLdr / kQualityFrames;
            meanRatio += (b > 0.0 ? a / b : 0.0) / kQualityFrames;
        }
    }
    state.counters["relMSE"] = relMse;
    state.counters["FLIP"] = flip;
    state.counters["meanRatio"] = meanRatio;
}

void BM_IirQualityCornell(benchmark::State& state) { quality(state, "cornell-box"); }
BENCHMARK(BM_IirQualityCornell)->Iterations(1)->Unit(benchmark::kMillisecond);
void BM_IirQualityCornellDynamic(benchmark::State& state) { quality(state, "cornell-box-dynamic"); }
BENCHMARK(BM_IirQualityCornellDynamic)->Iterations(1)->Unit(benchmark::kMillisecond);

// Temporal stability with a still camera (cornell-box-dynamic's camera does not move): flicker of the
// indirect image, incremental against the comparison method at the same VPL count (paper: "less
// flickering"). metrics/FlickerMeter: mean |dY| between frames over mean Y.
void BM_IirFlicker(benchmark::State& state) {
    if (!context()) {
        state.SkipWithError("no GL context");
        return;
    }
    static const Scene scene = loadOrEmpty("cornell-box-dynamic");
    double flicker[2] = {0.0, 0.0};
    for (auto _ : state) {
        for (int mode = 0; mode < 2; ++mode) {
            auto technique = std::make_unique<IirTechnique>();
            const std::map<std::string, std::string> settings = {{"incremental", mode == 0 ? "true" : "false"}};
            if (!applySettings(*technique, settings, "technique 'iir'").ok()) return;
            auto pipeline = Pipeline::create(scene, std::move(technique), {kQualitySize, kQualitySize}, {});
            if (!pipeline.ok()) return;
            FlickerMeter meter;
            for (uint32_t f = 0; f < 30; ++f) {
                (*pipeline)->renderFrame(f);
                if (!meter.addFrame((*pipeline)->readback(Component::Indirect)).ok()) return;
            }
            auto v = meter.flicker();
            flicker[mode] = v.ok() ? *v : 0.0;
        }
    }
    state.counters["incFlicker"] = flicker[0];
    state.counters["compFlicker"] = flicker[1];
    state.counters["compOverInc"] = flicker[0] > 0.0 ? flicker[1] / flicker[0] : 0.0;
}
BENCHMARK(BM_IirFlicker)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
