// `rsm-splat` (Nichols 2010 §4.3, Fig. 4.8 baselines): full-screen splats equal the rsm gather and stay
// close to the converged every-texel gather,
// radius-limited splats only remove light (§2.10.1: they darken), the matched radius converges to the
// target fragments per splat, and every built-in scene renders.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"

using namespace bounce;
using namespace bounce::nicholstest;

namespace {
class RsmSplatGpuTest : public gputest::GpuTest {};
}  // namespace

TEST_F(RsmSplatGpuTest, FullScreenSplatsEqualTheGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    const std::map<std::string, std::string> vpls = {{"rsmSize", "64"}, {"vplGrid", "8"}};
    const Image splat = renderIndirect(*scene, "rsm-splat", vpls, 32);
    const Image gather = renderIndirect(*scene, "rsm", vpls, 32);
    ASSERT_GT(totalRadiance(gather), 0.0);
    // Same terms summed in a different order (blending vs a loop): float rounding only.
    EXPECT_LT(relativeRmsError(splat, gather), 1e-5);
}

TEST_F(RsmSplatGpuTest, FullScreenSplatsAreCloseToTheEveryTexelGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const Image& limit = convergedLimit("cornell-box", kSize);
    const Image splat = renderIndirect(*scene, "rsm-splat", {{"rsmSize", "128"}, {"vplGrid", "32"}}, kSize);
    const double error = relativeRmsError(splat, limit);
    RecordProperty("rsmSplatRelRms", std::to_string(error));
    // Full-screen splats are the rsm gather of the same 1024 VPLs (test above), so the error is the
    // regular VPL grid's and the 128^2 RSM's: measured 16.7 % at 64^2 (as rsm's); bound with ~20 % margin.
    EXPECT_LT(error, 0.20);
}

TEST_F(RsmSplatGpuTest, LimitedRadiusOnlyDarkens) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    const Image full = renderIndirect(*scene, "rsm-splat", {{"rsmSize", "64"}, {"vplGrid", "8"}}, 32);
    const Image limited = renderIndirect(*scene, "rsm-splat", {{"rsmSize", "64"}, {"vplGrid", "8"}, {"mode", "fixed"}, {"radius", "0.2"}}, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_LE(limited.at(x, y)[c], full.at(x, y)[c] * (1.0f + 1e-5f) + 1e-9f);
    EXPECT_LT(totalRadiance(limited), 0.9 * totalRadiance(full)) << "a 0.2 m radius drops light in a 0.55 m box";
}

TEST_F(RsmSplatGpuTest, MatchedRadiusConvergesToTheTargetFragments) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr double kTarget = 200.0;  // of 64^2 = 4096 pixels per splat
    auto p = makePipeline(*scene, "rsm-splat", {{"rsmSize", "64"}, {"vplGrid", "8"}, {"mode", "matched"}, {"targetFragments", "200"}}, 64);
    FrameStats stats;
    for (uint32_t f = 0; f < 6; ++f) stats = p->renderFrame(f);
    // Fragments grow roughly with the splat's screen area (radius^2); clipping and the rectangle's
    // corners make it approximate, so 25 % after six frames.
    EXPECT_NEAR(stats.counters.at("fragmentsPerSplat"), kTarget, 0.25 * kTarget);
}

TEST_F(RsmSplatGpuTest, EveryBuiltinSceneRendersFiniteIndirectLight) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        auto scene = loadScene(info.name);
        ASSERT_TRUE(scene.ok()) << info.name;
        if (scene->hasEmissiveMaterials()) {  // furnace: lit by emission only
            expectRefusesEmissiveScene(*scene, "rsm-splat");
            continue;
        }
        const Image indirect = renderIndirect(*scene, "rsm-splat", {{"rsmSize", "32"}, {"vplGrid", "8"}, {"mode", "matched"}}, 16);
        EXPECT_TRUE(finiteAndNonNegative(indirect)) << info.name;
    }
}
