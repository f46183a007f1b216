// `hisr` (Nichols 2010 §4.2.4): with a zero-size threshold and full depth the traversal visits every
// RSM texel and the image equals the every-texel rsm gather; with the defaults it stays close to the
// converged limit; every built-in scene renders.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"

using namespace bounce;
using namespace bounce::nicholstest;

namespace {
class HisrGpuTest : public gputest::GpuTest {};
}  // namespace

TEST_F(HisrGpuTest, FullTraversalEqualsTheEveryTexelGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 32;
    // rsmSize 64, roots 16^2, depth 2: the leaves are the 64^2 texels. tau -> 0 makes T huge, so every
    // node refines; eyeCoarsest = image size keeps one level (every pixel gathers for itself).
    const Image hisr = renderIndirect(*scene, "hisr",
                                      {{"rsmSize", "64"}, {"rootGrid", "16"}, {"maxDepth", "2"}, {"tau", "1e-6"}, {"eyeCoarsest", "32"}},
                                      kSize);
    const Image rsm = renderIndirect(*scene, "rsm", {{"rsmSize", "64"}, {"vplGrid", "64"}}, kSize);
    ASSERT_GT(totalRadiance(rsm), 0.0);
    // Same VPLs, same form factor; only the summation order differs (float rounding).
    EXPECT_LT(relativeRmsError(hisr, rsm), 1e-4);
}

TEST_F(HisrGpuTest, DefaultsStayCloseToTheEveryTexelGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const Image& limit = convergedLimit("cornell-box", kSize);
    const Image hisr = renderIndirect(*scene, "hisr", {{"rsmSize", "128"}}, kSize);
    const double error = relativeRmsError(hisr, limit);
    RecordProperty("hisrRelRms", std::to_string(error));
    // Thesis R6: 5-6 % RMS at 1024^2. Measured here 10.9 % against the 256^2 every-texel limit (64^2
    // image: the coarse eye levels cover more of the screen; a 128^2 RSM alone is 5.5 % off the limit;
    // tau and maxDepth are this implementation's defaults). Bound: measured plus ~20 %.
    EXPECT_LT(error, 0.13);
}

TEST_F(HisrGpuTest, EnergyDoesNotGrowWithTreeDepth) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    // rsmSize 128 with 16^2 roots: depth 3 reaches the texels. eyeCoarsest = image size keeps the eye
    // side at full resolution, so only the light hierarchy changes.
    std::vector<double> energies;
    for (int depth : {0, 1, 2, 3}) {
        const double energy = totalRadiance(renderIndirect(
            *scene, "hisr", {{"rsmSize", "128"}, {"rootGrid", "16"}, {"maxDepth", std::to_string(depth)}, {"eyeCoarsest", "64"}},
            kSize));
        RecordProperty("energyDepth" + std::to_string(depth), std::to_string(energy));
        ASSERT_GT(energy, 0.0);
        energies.push_back(energy);
    }
    // A node carries the summed flux of its texels, so descending only changes where that flux is shot
    // from; it never adds any. Measured: 431.5, 449.2, 457.7, 458.7 for depths 0..3 — a coarse node
    // shot from one sample under-lights the receivers close to it (5.9 % at depth 0).
    const double deepest = energies.back();
    for (size_t d = 0; d < energies.size(); ++d) {
        // 0.5 %: float summation order between depths (measured 0.02 %); anything above is energy created.
        EXPECT_LE(energies[d], deepest * 1.005) << "depth " << d;
        // 8 %: the near-field loss of coarse nodes (measured 5.9 % at depth 0) with margin.
        EXPECT_GE(energies[d], deepest * 0.92) << "depth " << d;
    }
}

TEST_F(HisrGpuTest, EveryBuiltinSceneRendersFiniteIndirectLight) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        auto scene = loadScene(info.name);
        ASSERT_TRUE(scene.ok()) << info.name;
        const Image indirect = renderIndirect(*scene, "hisr", {{"rsmSize", "32"}, {"maxDepth", "1"}}, 32);
        EXPECT_TRUE(finiteAndNonNegative(indirect)) << info.name;
        if (info.name == "furnace") {
            EXPECT_EQ(totalRadiance(indirect), 0.0) << "no light, no indirect light";
        }
    }
}
