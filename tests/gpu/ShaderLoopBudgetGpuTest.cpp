// llvmpipe cuts every loop of a shader invocation short once they have run 65535 iterations together
// (gpu/ShaderLimits.h), silently. The Nichols gathers split long loops into batches of draws; these
// tests run gathers well past the budget and check they still sum every VPL / tree node, by comparing
// two independent implementations of the same sum.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"

#include "gpu/ShaderLimits.h"

using namespace bounce;
using namespace bounce::nicholstest;

namespace {
class ShaderLoopBudgetGpuTest : public gputest::GpuTest {};
}  // namespace

TEST_F(ShaderLoopBudgetGpuTest, RsmAndIsrGatherEveryVplOfAQuarterMillion) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 16;
    // 512^2 = 262144 VPLs: four times the budget. The rsm gather walks texture rows in batches, isr
    // (one level: every pixel gathers for itself) walks the SSBO in batches; before batching, each
    // single loop stopped at 65535 VPLs and the two differed by 30 % relMSE.
    const std::map<std::string, std::string> rsmSettings = {{"rsmSize", "512"}, {"vplGrid", "512"}};
    auto rsm = makePipeline(*scene, "rsm", rsmSettings, kSize);
    const FrameStats rsmStats = rsm->renderFrame(0);
    const Image rsmImage = rsm->readback(Component::Indirect);
    EXPECT_GT(rsmStats.counters.at("gatherDraws"), 1.0);
    auto isr = makePipeline(*scene, "isr",
                            {{"rsmSize", "512"}, {"vplMode", "regular"}, {"vplGrid", "512"}, {"eyeCoarsest", "16"}}, kSize);
    const FrameStats isrStats = isr->renderFrame(0);
    const Image isrImage = isr->readback(Component::Indirect);
    EXPECT_GT(isrStats.counters.at("gatherDraws"), 1.0);
    ASSERT_GT(totalRadiance(rsmImage), 0.0);
    // Same VPLs, same form factor; float summation order differs.
    EXPECT_LT(relativeRmsError(isrImage, rsmImage), 1e-5);
    // Batch size does not matter: 8192-VPL batches give the same image as the default.
    auto small = rsmSettings;
    small["vplBatch"] = "8192";
    EXPECT_LT(relativeRmsError(renderIndirect(*scene, "rsm", small, kSize), rsmImage), 1e-5);
}

TEST_F(ShaderLoopBudgetGpuTest, HisrWalksDeepTreesWhole) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 16;
    // rsmSize 256 with 16^2 roots, depth 4: the leaves are the 65536 texels, 87296 nodes per fragment
    // (more than the budget); tau -> 0 refines every node, so the walk equals the every-texel gather.
    const Image hisr = renderIndirect(
        *scene, "hisr", {{"rsmSize", "256"}, {"rootGrid", "16"}, {"maxDepth", "4"}, {"tau", "1e-6"}, {"eyeCoarsest", "16"}},
        kSize);
    const Image rsm = renderIndirect(*scene, "rsm", {{"rsmSize", "256"}, {"vplGrid", "256"}}, kSize);
    ASSERT_GT(totalRadiance(rsm), 0.0);
    // Same texels as VPLs; only the summation order differs.
    EXPECT_LT(relativeRmsError(hisr, rsm), 1e-4);
}

TEST_F(ShaderLoopBudgetGpuTest, TooCoarseVplGridIsASettingsError) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    // 1024 / 4 = 256: one VPL's block of 256^2 texels is beyond what its extraction may loop over.
    auto t = createTechnique("rsm");
    ASSERT_TRUE(t.ok());
    ASSERT_TRUE(applySettings(**t, {{"rsmSize", "1024"}, {"vplGrid", "4"}}, "rsm").ok());
    auto p = Pipeline::create(*scene, std::move(*t), {16, 16}, smallRenderSettings());
    ASSERT_FALSE(p.ok());
    EXPECT_NE(p.error().message.find("vplGrid=4"), std::string::npos) << p.error().message;
    EXPECT_NE(p.error().message.find("vplGrid >= 8"), std::string::npos) << p.error().message;
}
