// The shared reflective shadow map and the `rsm` baseline gather (Nichols 2010 §3.2.1, §4.3):
// closed-form RSM fluxes for spot, point and directional lights over a grey plane, flux-preserving
// VPL extraction, the batched gather, and the gather's convergence towards the every-texel limit.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "techniques/rsm/RsmTechnique.h"

#include <glm/gtc/constants.hpp>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class RsmGpuTest : public gputest::GpuTest {};

glm::vec3 rsmFlux(const Scene& scene, int rsmSize, glm::vec3* vplFlux = nullptr) {
    auto p = makePipeline(scene, "rsm", {{"rsmSize", std::to_string(rsmSize)}, {"vplGrid", "16"}}, 16);
    p->renderFrame(0);
    auto& rsm = dynamic_cast<RsmTechnique&>(p->technique());
    if (vplFlux) {
        *vplFlux = glm::vec3(0.0f);
        for (const nichols::VplRecord& v : rsm.vpls().download()) *vplFlux += glm::vec3(v.flux);
    }
    return rsm.rsm().totalFlux();
}

}  // namespace

TEST_F(RsmGpuTest, SpotLightRsmReflectsAlbedoTimesEmittedFlux) {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 1.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.intensity = glm::vec3(10.0f);
    spot.cutoffAngle = glm::radians(30.0f);
    spot.falloffExponent = 1.0f;
    // The whole cone (radius tan 30 deg = 0.58 m) lands on the plane, so the RSM holds rho * flux.
    const glm::vec3 expected = kPlaneAlbedo * spot.flux();
    glm::vec3 vpl;
    const glm::vec3 got = rsmFlux(planeScene(spot), 128, &vpl);
    // 3 %: the cone's rim crosses ~400 of the 128^2 texels, each counted whole or not at all.
    EXPECT_NEAR(got.r, expected.r, 0.03f * expected.r);
    // Extraction moves flux between VPLs but never creates or loses it (float sums).
    EXPECT_NEAR(vpl.r, got.r, 1e-4f * got.r);
}

TEST_F(RsmGpuTest, PointLightCubeRsmMatchesTheSolidAngleOfThePlane) {
    Light point;
    point.type = LightType::Point;
    point.position = {0.0f, 1.0f, 0.0f};
    point.intensity = glm::vec3(5.0f);
    // Solid angle of a centred square of half-side a at distance h: 4 asin(a^2 / (a^2 + h^2)).
    const float a = kPlaneHalf, h = 1.0f;
    const float solidAngle = 4.0f * std::asin(a * a / (a * a + h * h));
    const float expected = kPlaneAlbedo * 5.0f * solidAngle;
    const glm::vec3 got = rsmFlux(planeScene(point), 64);
    // 2 %: the plane's square outline crosses the cube faces' texel grid (64^2 per face).
    EXPECT_NEAR(got.g, expected, 0.02f * expected);
}

TEST_F(RsmGpuTest, DirectionalRsmMatchesIrradianceTimesArea) {
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.irradiance = glm::vec3(3.0f);
    const float expected = kPlaneAlbedo * 3.0f * (2.0f * kPlaneHalf) * (2.0f * kPlaneHalf);
    const glm::vec3 got = rsmFlux(planeScene(sun), 128);
    // 3 %: the plane's edges fall across orthographic texels (about 4 texel rows of 90).
    EXPECT_NEAR(got.b, expected, 0.03f * expected);
}

TEST_F(RsmGpuTest, FlatPlaneReceivesNoIndirectLightFromItself) {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 1.0f, 0.0f};
    spot.intensity = glm::vec3(10.0f);
    spot.cutoffAngle = glm::radians(40.0f);
    const Image indirect = renderIndirect(planeScene(spot), "rsm", {{"rsmSize", "64"}, {"vplGrid", "16"}}, 32);
    // Sender and receiver are coplanar: both cosines are 0 (up to float rounding of positions).
    EXPECT_LT(totalRadiance(indirect), 1e-6);
}

TEST_F(RsmGpuTest, BatchedGatherEqualsTheOnePassGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 32;
    // 32^2 = 1024 VPLs: one draw (one uniform-block window, nichols/VplWindow.h), or batches of 200, rounded
    // down to 192 (a multiple of 16 VPLs): six draws, the last one partial and in a window of its own.
    const std::map<std::string, std::string> vpls = {{"rsmSize", "64"}, {"vplGrid", "32"}};
    auto one = makePipeline(*scene, "rsm", vpls, kSize);
    auto settings = vpls;
    settings["vplBatch"] = "200";
    auto batched = makePipeline(*scene, "rsm", settings, kSize);
    EXPECT_EQ(one->renderFrame(0).counters.at("gatherDraws"), 1.0);
    EXPECT_EQ(batched->renderFrame(0).counters.at("gatherDraws"), 6.0);
    const Image a = one->readback(Component::Indirect), b = batched->readback(Component::Indirect);
    ASSERT_GT(totalRadiance(a), 0.0);
    // The same terms, summed per batch and then added by blending: float rounding only (1024 terms of
    // one sign, relative rounding ~1e-7 each).
    EXPECT_LT(relativeRmsError(b, a), 1e-5);
}

TEST_F(RsmGpuTest, GatherConvergesToTheEveryTexelLimit) {
    constexpr int kSize = 64;
    // The converged limit: every texel of a kLimitRsmSize^2 RSM is a VPL (the cornell-box spot's single
    // 120-degree map; NicholsTestSupport.h says why not the thesis's 1024^2).
    const Image& limit = convergedLimit("cornell-box", kSize);
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    const Image coarse = renderIndirect(*scene, "rsm", {{"rsmSize", "128"}, {"vplGrid", "8"}}, kSize);
    const Image fine = renderIndirect(*scene, "rsm", {{"rsmSize", "128"}, {"vplGrid", "32"}}, kSize);
    const Image everyTexel = renderIndirect(*scene, "rsm", {{"rsmSize", "128"}, {"vplGrid", "128"}}, kSize);
    ASSERT_GT(totalRadiance(limit), 0.0);
    const double coarseError = relativeRmsError(coarse, limit), fineError = relativeRmsError(fine, limit);
    const double texelError = relativeRmsError(everyTexel, limit);
    RecordProperty("coarseRelRms", std::to_string(coarseError));
    RecordProperty("fineRelRms", std::to_string(fineError));
    RecordProperty("everyTexel128RelRms", std::to_string(texelError));
    // More VPLs approach the limit: a regular VPL sits at its block's centre texel, which errs most in
    // the box's corners. Measured on llvmpipe at 64^2: 64 VPLs 36.3 %, 1024 VPLs 16.7 %, every texel of
    // a 128^2 RSM (16k VPLs) 5.5 % (the RSM resolution alone: texels of 128^2 vs 256^2 in the corners).
    // Bounds: the measured values plus about 20 % for other drivers' rounding and rasterisation rules.
    EXPECT_LT(fineError, coarseError);
    EXPECT_LT(texelError, fineError);
    EXPECT_LT(fineError, 0.20);
    EXPECT_LT(texelError, 0.07);
    // The gather preserves energy: the totals agree within 5 % (regular sampling, not the flux).
    EXPECT_NEAR(totalRadiance(fine) / totalRadiance(limit), 1.0, 0.05);
}

TEST_F(RsmGpuTest, EveryBuiltinSceneRendersFiniteIndirectLight) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        auto scene = loadScene(info.name);
        ASSERT_TRUE(scene.ok()) << info.name;
        if (scene->hasEmissiveMaterials()) {  // furnace: lit by emission only
            expectRefusesEmissiveScene(*scene, "rsm");
            continue;
        }
        const Image indirect = renderIndirect(*scene, "rsm", {{"rsmSize", "32"}, {"vplGrid", "8"}}, 16);
        EXPECT_TRUE(finiteAndNonNegative(indirect)) << info.name;
    }
}

TEST_F(RsmGpuTest, EqualSolidAngleApproximationMatchesItsClosedForm) {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 1.0f, 0.0f};
    spot.intensity = glm::vec3(10.0f);
    spot.cutoffAngle = glm::radians(30.0f);
    spot.falloffExponent = 0.0f;
    const Scene scene = planeScene(spot);
    auto exact = makePipeline(scene, "rsm", {{"rsmSize", "128"}, {"vplGrid", "16"}}, 16);
    auto equal = makePipeline(scene, "rsm", {{"rsmSize", "128"}, {"vplGrid", "16"}, {"equalSolidAngle", "true"}}, 16);
    exact->renderFrame(0);
    equal->renderFrame(0);
    const float exactFlux = dynamic_cast<RsmTechnique&>(exact->technique()).rsm().totalFlux().r;
    const float equalFlux = dynamic_cast<RsmTechnique&>(equal->technique()).rsm().totalFlux().r;
    // Exact: rho * I * 2 pi (1 - cos a) (n = 0). Eq. 4.4 gives each texel the frustum's mean solid angle
    // 4 asin(sin^2 a) / N^2, and the cone covers pi/4 of the frustum's texels (a disc inscribed in the
    // square): rho * I * pi asin(sin^2 a), 6 % below the exact value at a = 30 degrees.
    const float a = spot.cutoffAngle;
    const float exactExpected = kPlaneAlbedo * 10.0f * glm::two_pi<float>() * (1.0f - std::cos(a));
    const float equalExpected = kPlaneAlbedo * 10.0f * glm::pi<float>() * std::asin(std::sin(a) * std::sin(a));
    // 2 %: rim texels counted whole (about 400 of 128^2).
    EXPECT_NEAR(exactFlux, exactExpected, 0.02f * exactExpected);
    EXPECT_NEAR(equalFlux, equalExpected, 0.02f * equalExpected);
}
