// Incremental instant radiosity (Laine et al. 2007) on the GPU: the VPL budget under light motion,
// flux conservation, comparison mode, the indirect image against the one-bounce path-traced
// reference, temporal flicker, and every built-in scene.
#include "GpuTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/FlickerMeter.h"
#include "reference/PathTracer.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/iir/IirTechnique.h"

#include <cmath>
#include <map>
#include <string>

using namespace bounce;

namespace {

class IirGpuTest : public gputest::GpuTest {};

struct IirRun {
    std::unique_ptr<Pipeline> pipeline;
    IirTechnique* iir = nullptr;
};

// Tiny images and maps keep each test at a few seconds on llvmpipe.
IirRun makeRun(const Scene& scene, int size, std::map<std::string, std::string> settings) {
    auto technique = std::make_unique<IirTechnique>();
    settings.emplace("shadowMapSize", "64");
    auto applied = applySettings(*technique, settings, "technique 'iir'");
    EXPECT_TRUE(applied.ok()) << applied.error().message;
    IirTechnique* raw = technique.get();
    render::RenderSettings rs;
    rs.shadowMapSize = 256;
    auto pipeline = Pipeline::create(scene, std::move(technique), {size, size}, rs);
    EXPECT_TRUE(pipeline.ok()) << pipeline.error().message;
    return {pipeline.ok() ? std::move(*pipeline) : nullptr, raw};
}

Scene load(const std::string& name) {
    auto scene = loadScene(name);
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : Scene{};
}

glm::dvec3 totalFlux(const IirTechnique& iir) {
    glm::dvec3 sum(0.0);
    for (const glm::vec3& f : iir.sampleFlux()) sum += glm::dvec3(f);
    return sum;
}

double luminanceMean(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
    return sum / static_cast<double>(image.pixelCount());
}

}  // namespace

TEST_F(IirGpuTest, BudgetIsKeptAndFluxConservedWhileTheLightMoves) {
    const Scene scene = load("cornell-box-dynamic");
    constexpr uint32_t kMaxLights = 48;
    IirRun run = makeRun(scene, 32, {{"maxLights", std::to_string(kMaxLights)}});
    ASSERT_TRUE(run.pipeline);
    // Frames 3 apart: the spot moves by a few centimetres per step, enough to invalidate VPLs.
    for (uint32_t frame = 0; frame < 30; frame += 3) {
        const FrameStats stats = run.pipeline->renderFrame(frame);
        const VplDistribution* dist = run.iir->distribution();
        ASSERT_NE(dist, nullptr);
        const uint32_t invalid = static_cast<uint32_t>(stats.counters.at("vplsInvalidated"));
        // §4.2: every frame frees recalcMin slots and refills up to recalcMax, so the budget stays
        // full unless more than recalcMax - recalcMin = 4 samples went invalid at once.
        if (frame == 0 || invalid <= 4) {
            EXPECT_EQ(dist->sampleCount(), kMaxLights) << "frame " << frame;
        } else {
            EXPECT_GE(dist->sampleCount() + invalid, kMaxLights) << "frame " << frame;
        }
        if (frame > 0) {
            EXPECT_LE(stats.counters.at("vplShadowMaps"), 8.0) << "only new VPLs get maps";
        }
        // Cell areas sum to pi within 1e-9 (core tests); the float fluxes add ~1e-7 each.
        const glm::dvec3 flux = totalFlux(*run.iir);
        const glm::vec3 expected = scene.lights[0].at(scene.timeOfFrame(frame)).flux();
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(flux[c], expected[c], 1e-5 * expected[c]) << "frame " << frame;
    }
}

TEST_F(IirGpuTest, FluxIsConservedForPointAreaAndDirectionalLights) {
    for (const std::string name : {"two-rooms", "cornell-box-area", "atrium"}) {
        const Scene scene = load(name);
        IirRun run = makeRun(scene, 16, {{"maxLights", "32"}});
        ASSERT_TRUE(run.pipeline);
        run.pipeline->renderFrame(0);
        const glm::vec3 expected = IirTechnique::primaryLight(scene, 0.0f).flux;
        const glm::dvec3 flux = totalFlux(*run.iir);
        ASSERT_GT(expected.r + expected.g + expected.b, 0.0f) << name;
        // As above: float fluxes summed over 32 samples.
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(flux[c], expected[c], 1e-5 * expected[c]) << name;
    }
}

TEST_F(IirGpuTest, ComparisonModeRegeneratesEveryVplAndMapEachFrame) {
    const Scene scene = load("cornell-box-dynamic");
    IirRun run = makeRun(scene, 16, {{"maxLights", "32"}, {"incremental", "false"}});
    ASSERT_TRUE(run.pipeline);
    for (uint32_t frame = 0; frame < 4; ++frame) {
        const FrameStats stats = run.pipeline->renderFrame(frame);
        EXPECT_EQ(stats.counters.at("vplSamplesCreated"), 32.0);
        EXPECT_EQ(stats.counters.at("vplShadowMaps"), stats.counters.at("vpls"));
    }
}

TEST_F(IirGpuTest, IndirectImageIsCloseToTheOneBounceReference) {
    const Scene scene = load("cornell-box");
    constexpr int kSize = 48;
    IirRun run = makeRun(scene, kSize, {{"maxLights", "64"}});
    ASSERT_TRUE(run.pipeline);
    run.pipeline->renderFrame(0);
    const Image iir = run.pipeline->readback(Component::Indirect);

    PathTracerSettings pts;
    pts.width = pts.height = kSize;
    pts.samplesPerPixel = 256;
    pts.bounces = 1;
    pts.indirectOnly = true;
    pts.diffuseOnly = true;
    auto tracer = PathTracer::create(scene, pts);
    ASSERT_TRUE(tracer.ok()) << tracer.error().message;
    const Image reference = tracer->render().radiance;

    auto metrics = compareImages(iir, reference);
    ASSERT_TRUE(metrics.ok()) << metrics.error().message;
    const double meanRatio = luminanceMean(iir) / luminanceMean(reference);
    std::printf("iir vs reference (cornell-box, 48^2, 64 VPLs): relMSE %.4f, FLIP %.4f, mean ratio %.4f\n",
                metrics->relMse, metrics->flipLdr, meanRatio);
    // The mean indirect radiance: 64 VPLs estimate the one-bounce integral without bias except for the
    // irradiance clamp (removes energy near VPLs) and the 256-spp reference's noise: 15 %.
    EXPECT_NEAR(meanRatio, 1.0, 0.15);
    // Per pixel: VPL noise at 64 VPLs, the clamp in the corners and blocky paraboloid edges: 0.1.
    EXPECT_LT(metrics->relMse, 0.1);
}

TEST_F(IirGpuTest, FlickerOfIncrementalAndComparisonModes) {
    const Scene scene = load("cornell-box-dynamic");
    double flicker[2] = {0.0, 0.0};
    for (int mode = 0; mode < 2; ++mode) {
        IirRun run = makeRun(scene, 32, {{"maxLights", "48"}, {"incremental", mode == 0 ? "true" : "false"}});
        ASSERT_TRUE(run.pipeline);
        FlickerMeter meter;
        for (uint32_t frame = 0; frame < 12; ++frame) {
            run.pipeline->renderFrame(frame);
            ASSERT_TRUE(meter.addFrame(run.pipeline->readback(Component::Indirect)).ok());
        }
        auto f = meter.flicker();
        ASSERT_TRUE(f.ok()) << f.error().message;
        flicker[mode] = *f;
    }
    std::printf("flicker (cornell-box-dynamic, 32^2, 48 VPLs, 12 frames): incremental %.5f, comparison %.5f\n",
                flicker[0], flicker[1]);
    ASSERT_TRUE(std::isfinite(flicker[0]) && std::isfinite(flicker[1]));
    // The paper's claim (§6: "less flickering artifacts than the comparison method using the same
    // number of VPLs"). Both runs are deterministic; measured 0.23 against 0.41, so the margin is wide.
    EXPECT_LT(flicker[0], flicker[1]);
}

TEST_F(IirGpuTest, RendersEveryBuiltinScene) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        const std::string& name = info.name;
        const Scene scene = load(name);
        // 18 is not a multiple of the 4x4 tiling: the atlas has empty pixels at the tile ends.
        IirRun run = makeRun(scene, 18, {{"maxLights", "16"}});
        ASSERT_TRUE(run.pipeline) << name;
        run.pipeline->renderFrame(0);
        run.pipeline->renderFrame(1);
        const Image indirect = run.pipeline->readback(Component::Indirect);
        for (const glm::vec3& p : indirect.pixels()) {
            ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b)) << name;
            ASSERT_GE(std::min({p.r, p.g, p.b}), 0.0f) << name;
        }
    }
}
