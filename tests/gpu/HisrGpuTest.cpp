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
    // Thesis R6: 5-6 % RMS at 1024^2. Measured here 14.9 % against the 256^2 every-texel limit (64^2
    // image: the coarse eye levels cover more of the screen; a 128^2 RSM alone is 5.5 % off the limit;
    // tau and maxDepth are this implementation's defaults). Bound: measured plus ~20 %.
    EXPECT_LT(error, 0.18);
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
