// `isr` (Nichols 2010 Ch. 4): the stencil set-up marks each covered pixel at exactly one level, the
// indirect image stays close to the every-texel gather limit, and energy does not grow with the
// refinement depth of the multiresolution buffer.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "techniques/isr/IsrTechnique.h"

#include <glm/vec4.hpp>

#include <algorithm>
#include <vector>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class IsrGpuTest : public gputest::GpuTest {};

}  // namespace

// gatherPass=compute (the cell list and a compute dispatch, StencilledGather.h) against the thesis's
// stencilled draws: the same cells and sums, so the same image (float rounding) and per-level counts. Light
// clusters use four 1024-VPL windows, so three dispatches accumulate; regular VPLs one.
TEST_F(IsrGpuTest, ComputeGatherEqualsTheStencilledGather) {
    for (const char* sceneName : {"cornell-box", "cornell-box-dynamic"}) {
        auto scene = loadScene(sceneName);
        ASSERT_TRUE(scene.ok());
        for (const char* mode : {"clusters", "regular"}) {
            SCOPED_TRACE(std::string(sceneName) + ", " + mode);
            std::map<std::string, std::string> settings = {{"vplMode", mode}, {"gatherPass", "stencil"}};
            auto stencil = makePipeline(*scene, "isr", settings, 48);
            settings["gatherPass"] = "compute";
            auto compute = makePipeline(*scene, "isr", settings, 48);
            const Counters a = stencil->renderFrame(1).counters, b = compute->renderFrame(1).counters;
            const Image x = stencil->readback(Component::Indirect), y = compute->readback(Component::Indirect);
            ASSERT_GT(totalRadiance(x), 0.0);
            EXPECT_LT(relativeRmsError(y, x), 1e-6);
            for (const auto& [name, value] : a) {
                if (name.rfind("fragments/level-", 0) == 0 || name == "gatherFragments" || name == "vpls") {
                    EXPECT_EQ(b.at(name), value) << name;
                }
            }
        }
    }
}

TEST_F(IsrGpuTest, StencilMarksEachCoveredPixelAtExactlyOneLevel) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    // A low coarsest level (4^2) gives five levels, so the chain rule is exercised at every depth.
    auto p = makePipeline(*scene, "isr", {{"rsmSize", "64"}, {"lightFinest", "32"}, {"eyeCoarsest", "4"}}, kSize);
    p->renderFrame(0);
    auto& isr = dynamic_cast<IsrTechnique&>(p->technique());
    const nichols::MultiresBuffer& buffer = isr.buffer();
    ASSERT_GE(buffer.levels(), 4);
    const glm::ivec2 atlasSize(buffer.atlas().width(), buffer.atlas().height());
    const std::vector<glm::vec4> atlas = readLevel(buffer.atlas(), 0, atlasSize);
    const std::vector<glm::vec4> base = readLevel(isr.eyePyramid().geometry(), 0, {kSize, kSize});
    int covered = 0, levelsUsed = 0;
    std::vector<bool> levelSeen(static_cast<size_t>(buffer.levels()), false);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            int marks = 0;
            for (int k = 0; k < buffer.levels(); ++k) {
                const glm::ivec2 cell = glm::min(glm::ivec2(x, y) >> k, buffer.levelSize(k) - 1);
                const glm::ivec2 t = buffer.levelOrigin(k) + cell;
                if (atlas[static_cast<size_t>(t.y) * atlasSize.x + t.x].a > 0.5f) {
                    ++marks;
                    levelSeen[static_cast<size_t>(k)] = true;
                }
            }
            const bool isCovered = base[static_cast<size_t>(y) * kSize + x].w > 0.0f;
            covered += isCovered ? 1 : 0;
            ASSERT_EQ(marks, isCovered ? 1 : 0) << "pixel " << x << "," << y;
        }
    for (bool seen : levelSeen) levelsUsed += seen ? 1 : 0;
    EXPECT_GT(covered, kSize * kSize / 2) << "the box fills most of the view";
    EXPECT_GE(levelsUsed, 3) << "the Cornell box refines at several levels";
}

TEST_F(IsrGpuTest, OneLevelWithRegularVplsEqualsTheRsmGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 32;
    // eyeCoarsest = image size: a single level, every pixel gathers the same VPL cache as rsm.
    const Image isr = renderIndirect(*scene, "isr", {{"rsmSize", "64"}, {"vplMode", "regular"}, {"vplGrid", "16"}, {"eyeCoarsest", "32"}}, kSize);
    const Image rsm = renderIndirect(*scene, "rsm", {{"rsmSize", "64"}, {"vplGrid", "16"}}, kSize);
    ASSERT_GT(totalRadiance(rsm), 0.0);
    // Same sum in the same order: only float rounding of the mean position (g.xyz / 1) differs.
    EXPECT_LT(relativeRmsError(isr, rsm), 1e-5);
}

TEST_F(IsrGpuTest, IndirectLightIsCloseToTheEveryTexelGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const Image& limit = convergedLimit("cornell-box", kSize);
    // Eye-space clustering alone (same VPLs as a 32^2 regular grid).
    const Image regular = renderIndirect(*scene, "isr", {{"rsmSize", "128"}, {"vplMode", "regular"}, {"vplGrid", "32"}}, kSize);
    const Image rsm32 = renderIndirect(*scene, "rsm", {{"rsmSize", "128"}, {"vplGrid", "32"}}, kSize);
    // Eye- and light-space clustering combined.
    const Image clusters = renderIndirect(*scene, "isr", {{"rsmSize", "128"}, {"lightFinest", "64"}}, kSize);
    const double eyeOnly = relativeRmsError(regular, rsm32);
    const double combined = relativeRmsError(clusters, limit);
    RecordProperty("eyeClusteringRelRms", std::to_string(eyeOnly));
    RecordProperty("combinedRelRms", std::to_string(combined));
    // Thesis R6: 2-3 % RMS from eye-space clustering, 5-6 % combined (1024^2 image, 1024^2 RSM). Measured
    // here (64^2 image): eye clustering 3.0 % (against the same 1024 VPLs); clusters over a 128^2 RSM
    // against the 256^2 every-texel limit 10.6 % (13.0 % before clusters were shot from their centre
    // sample instead of their mean point), of which 5.5 % is the RSM resolution alone (rsm test);
    // at 64^2 the 16^2 coarsest level covers 16x more of the image than at 1024^2, so the combined bound
    // is wider than the thesis's figure. Bounds: measured plus ~20-60 % for other drivers.
    EXPECT_LT(eyeOnly, 0.05);
    EXPECT_LT(combined, 0.13);
}

// §3.2.5's reason for the empty-aware filter: against the same VPLs gathered at every pixel (rsm, 32^2
// regular VPLs), the thesis's reconstruction is closer than copying the parent cell (nearest, blocky)
// and than naive bilinear interpolation with empty cells as black (light bleeds out of the covered
// cells). Measured at 128^2 with 128^2 VPLs: 0.041 / 0.076 / 0.109 relative RMS; here (64^2, 32^2
// VPLs) see the recorded properties. The ordering is the claim; each step needs a 10 % margin so that a
// filter that silently fell back to another could not pass.
TEST_F(IsrGpuTest, EmptyAwareUpsamplingBeatsNearestAndNaiveBilinear) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const Image rsm32 = renderIndirect(*scene, "rsm", {{"rsmSize", "128"}, {"vplGrid", "32"}}, kSize);
    std::map<std::string, double> error;
    for (const char* filter : {"empty-aware", "nearest", "bilinear"}) {
        const Image isr = renderIndirect(
            *scene, "isr", {{"rsmSize", "128"}, {"vplMode", "regular"}, {"vplGrid", "32"}, {"upsampling", filter}}, kSize);
        error[filter] = relativeRmsError(isr, rsm32);
        RecordProperty(std::string("relRms-") + filter, std::to_string(error[filter]));
    }
    EXPECT_LT(1.1 * error["empty-aware"], error["nearest"]);
    EXPECT_LT(1.1 * error["empty-aware"], error["bilinear"]);
}

TEST_F(IsrGpuTest, EnergyDoesNotGrowWithRefinementDepth) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const std::map<std::string, std::string> common = {{"rsmSize", "64"}, {"vplMode", "regular"}, {"vplGrid", "16"}};
    double fullResolution = 0.0;
    for (int coarsest : {64, 32, 16, 8, 4}) {
        auto settings = common;
        settings["eyeCoarsest"] = std::to_string(coarsest);
        const double energy = totalRadiance(renderIndirect(*scene, "isr", settings, kSize));
        if (coarsest == kSize) {
            fullResolution = energy;  // one level: every pixel gathers, the reference depth
            ASSERT_GT(energy, 0.0);
            continue;
        }
        // Empty-aware upsampling only redistributes: 3 % for the irradiance a coarse patch's mean
        // position and normal assign to the pixels below it.
        EXPECT_LE(energy, fullResolution * 1.03) << "coarsest " << coarsest;
        EXPECT_GE(energy, fullResolution * 0.97) << "coarsest " << coarsest;
    }
}

TEST_F(IsrGpuTest, EveryBuiltinSceneRendersFiniteIndirectLight) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        auto scene = loadScene(info.name);
        ASSERT_TRUE(scene.ok()) << info.name;
        if (scene->hasEmissiveMaterials()) {  // furnace: lit by emission only
            expectRefusesEmissiveScene(*scene, "isr");
            continue;
        }
        const Image indirect = renderIndirect(*scene, "isr", {{"rsmSize", "32"}, {"lightFinest", "32"}}, 32);
        EXPECT_TRUE(finiteAndNonNegative(indirect)) << info.name;
    }
}

// A light cluster (isr) or tree node (hisr) of the finest level can still span a discontinuity (the
// Cornell short block's top face and the floor below its front edge); shot from its texels' mean point,
// its VPL floated 1 cm in front of the block and lit two hot spots on its front face. Shot from the
// patch's centre sample, no pixel exceeds the every-texel limit by that much any more.
// Light clusters partition the RSM (§4.2.2): each texel's flux lands in exactly one cluster VPL, so the
// VPLs' flux adds up to the light pyramid's coarsest level (the whole RSM's flux), at power-of-two and
// odd-sized RSMs (whose pyramid levels halve with floor, so a level's last row and column take three
// children). The walk up the pyramid differs per invocation: a level's size must not come from
// textureSize with that level (llvmpipe answers with the first SIMD lane's level). two-rooms' point light:
// six cube faces whose borders see walls, so the odd levels' last rows and columns carry flux.
TEST_F(IsrGpuTest, LightClustersConserveTheRsmFlux) {
    auto scene = loadScene("two-rooms");
    ASSERT_TRUE(scene.ok());
    for (const char* rsmSize : {"64", "100", "75"}) {
        SCOPED_TRACE(rsmSize);
        auto p = makePipeline(*scene, "isr", {{"rsmSize", rsmSize}, {"vplGrid", "1"}, {"lightFinest", "64"}, {"vplMode", "clusters"}}, 32);
        p->renderFrame(0);
        const auto& isr = dynamic_cast<const IsrTechnique&>(p->technique());
        const nichols::MinMaxPyramid& light = isr.lightPyramid();
        const int top = light.levels() - 1;
        const glm::ivec2 topSize = light.levelSize(top);
        glm::dvec3 rsmFlux(0.0);
        for (const glm::vec4& f : readLevel(light.flux(), top, topSize, light.layers())) rsmFlux += glm::dvec3(f);
        uint32_t count = 0;
        isr.clusterCount().download(0, sizeof(count), &count);
        ASSERT_GT(count, 0u);
        std::vector<nichols::VplRecord> vpls(count);
        isr.clusterVpls().download(0, count * sizeof(nichols::VplRecord), vpls.data());
        glm::dvec3 vplFlux(0.0);
        for (const nichols::VplRecord& v : vpls) vplFlux += glm::dvec3(v.flux);
        ASSERT_GT(rsmFlux.g, 0.0);
        // float sums of the same texels in different orders: 1e-4 relative
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(vplFlux[c], rsmFlux[c], 1e-4 * rsmFlux[c]) << "channel " << c;
    }
}

TEST_F(IsrGpuTest, LightClustersLeaveNoHotSpots) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const Image& limit = convergedLimit("cornell-box", kSize);
    double peak = 0.0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) peak = std::max(peak, double(limit.at(x, y).g));
    for (const char* technique : {"isr", "hisr"}) {
        // eyeCoarsest = image size: every pixel gathers for itself, so only the light side is tested.
        const Image image = renderIndirect(*scene, technique, {{"eyeCoarsest", "64"}}, kSize);
        double worst = 0.0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const double reference = limit.at(x, y).g;
                if (reference < 0.05 * peak) continue;  // dark pixels: ratios of tiny numbers
                worst = std::max(worst, image.at(x, y).g / reference);
            }
        RecordProperty(std::string(technique) + "WorstRatio", std::to_string(worst));
        // Measured: 1.95 (isr) and 2.2 (hisr) at near-field corners; 4.6 for both with mean points.
        EXPECT_LT(worst, 3.0) << technique;
    }
}
