// Temporal coherence (Nichols 2010, thesis Fig. 4.5 and §4.2.2-4.2.4; Laine et al. 2007 §6): with a
// still camera and a moving light, the flicker of the indirect image (metrics/FlickerMeter: mean
// |dY| between consecutive frames over mean Y) of the techniques built to be stable against those
// that are not:
//   - isr's light-space clusters and hisr's VPL tree against rsm's fixed 16x16 VPL grid (256 VPLs),
//   - iir's incremental VPL set against its comparison mode (every VPL regenerated every frame).
// cornell-box-dynamic: the camera does not move; the spot orbits and the tall block turns.
#include "NicholsTestSupport.h"
#include "metrics/FlickerMeter.h"

#include <cstdio>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class TemporalCoherenceGpuTest : public gputest::GpuTest {};

constexpr int kSize = 48;
constexpr uint32_t kFrames = 12;

double flickerOf(const Scene& scene, const std::string& technique, const std::map<std::string, std::string>& settings) {
    auto pipeline = makePipeline(scene, technique, settings, kSize);
    if (!pipeline) return -1.0;
    FlickerMeter meter;
    for (uint32_t frame = 0; frame < kFrames; ++frame) {
        pipeline->renderFrame(frame);
        auto added = meter.addFrame(pipeline->readback(Component::Indirect));
        EXPECT_TRUE(added.ok()) << technique;
    }
    auto f = meter.flicker();
    EXPECT_TRUE(f.ok()) << technique << ": " << (f.ok() ? "" : f.error().message);
    return f.ok() ? *f : -1.0;
}

Scene dynamicCornellBox() {
    auto scene = loadScene("cornell-box-dynamic");
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : Scene{};
}

}  // namespace

TEST_F(TemporalCoherenceGpuTest, NicholsClustersAndTreeAgainstTheVplGrid) {
    const Scene scene = dynamicCornellBox();
    // 256 VPLs each: a 16x16 grid over the 256^2 RSM (rsm), 16^2 coarsest clusters (isr), 16^2 tree
    // roots (hisr).
    const double rsm = flickerOf(scene, "rsm", {{"rsmSize", "256"}, {"vplGrid", "16"}});
    const double isr = flickerOf(scene, "isr", {{"rsmSize", "256"}, {"vplMode", "clusters"}, {"lightCoarsest", "16"}});
    const double hisr = flickerOf(scene, "hisr", {{"rsmSize", "256"}, {"rootGrid", "16"}});
    std::printf("flicker (cornell-box-dynamic, %d^2, %u frames): rsm %.5f, isr clusters %.5f, hisr %.5f\n", kSize,
                kFrames, rsm, isr, hisr);
    ASSERT_GT(rsm, 0.0);
    ASSERT_GT(isr, 0.0);
    ASSERT_GT(hisr, 0.0);
    // Measured (deterministic renders, llvmpipe): rsm 0.0662, isr clusters 0.0374 (0.56x rsm), hisr
    // 0.0551 (0.83x rsm); over 24 frames 0.0542, 0.0329 (0.61x), 0.0471 (0.87x). Both claims hold.
    // Part of every value is real change (the spot orbits, the tall block turns), which no technique
    // removes, so the ratios cannot approach 0. The bounds keep the measured ordering with its margin:
    // isr at most 0.7x rsm, hisr at most 0.95x rsm (hisr's margin is the thinner one).
    RecordProperty("rsmFlicker", std::to_string(rsm));
    RecordProperty("isrClustersFlicker", std::to_string(isr));
    RecordProperty("hisrFlicker", std::to_string(hisr));
    EXPECT_LT(isr, 0.7 * rsm);
    EXPECT_LT(hisr, 0.95 * rsm);
}

TEST_F(TemporalCoherenceGpuTest, IirIncrementalAgainstItsComparisonMode) {
    const Scene scene = dynamicCornellBox();
    const double incremental = flickerOf(scene, "iir", {{"maxLights", "256"}, {"shadowMapSize", "64"}});
    const double comparison =
        flickerOf(scene, "iir", {{"maxLights", "256"}, {"shadowMapSize", "64"}, {"incremental", "false"}});
    std::printf("flicker (cornell-box-dynamic, %d^2, %u frames, 256 VPLs): iir incremental %.5f, comparison %.5f\n",
                kSize, kFrames, incremental, comparison);
    ASSERT_GT(incremental, 0.0);
    ASSERT_GT(comparison, 0.0);
    // Laine et al. §6: "less flickering artifacts than the comparison method using the same number of
    // VPLs". Measured 0.0389 against 0.1974 (0.20x; 24 frames: 0.0390 against 0.1967). Before VPLs
    // kept their interleaving tile (tiles re-dealt every frame) incremental measured 0.0877 (0.44x).
    // At most half of the comparison mode's flicker.
    RecordProperty("iirIncrementalFlicker", std::to_string(incremental));
    RecordProperty("iirComparisonFlicker", std::to_string(comparison));
    EXPECT_LT(incremental, 0.5 * comparison);
}
