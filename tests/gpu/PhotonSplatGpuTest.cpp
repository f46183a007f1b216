// Photon splatting (seed 004) on the GPU: one photon over a plane splats its footprint (the box
// filter's square at the calibrated level, each filter's integral), a bundle's depth map shadows the
// receiver behind an occluder, the calibrated estimate against the one-bounce reference (still and
// animated), the document's normalisation, debug views and settings errors.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "techniques/Registry.h"
#include "techniques/photon_splat/PhotonSplatTechnique.h"

#include <glm/gtc/constants.hpp>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class PhotonSplatGpuTest : public gputest::GpuTest {};

PhotonSplatTechnique& splatOf(Pipeline& p) { return dynamic_cast<PhotonSplatTechnique&>(p.technique()); }


double meanOf(const Image& image) { return totalRadiance(image) / (3.0 * image.width() * image.height()); }

// The plane scene seen orthographically (pixel (x, y) -> plane point), no light: photons are given.
Scene litPlane() {
    Light off;
    off.type = LightType::Point;
    off.position = {0.0f, 3.0f, 0.0f};
    off.intensity = glm::vec3(1e-6f);
    return gputest::planeScene(off, Projection::Orthographic);
}

}  // namespace

TEST_F(PhotonSplatGpuTest, OnePhotonSplatsItsFootprint) {
    constexpr int kSize = 128;
    const Scene scene = litPlane();
    const float pixel = 2.0f * gputest::kPlaneHalf / kSize;  // metres per pixel
    const photonsplat::Photon photon{{0.0f, 0.5f, 0.0f}, glm::vec3(2.0f), {0.0f, -1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}};
    for (const char* filter : {"box", "tent", "gaussian"}) {
        auto p = makePipeline(scene, "photon-splat", {{"estimate", "flux"}, {"filter", filter}, {"mapSize", "1.0"}, {"stepBack", "0.1"}}, kSize);
        splatOf(*p).setFixedPhotons({photon});
        p->renderFrame(0);
        ASSERT_EQ(splatOf(*p).bundles().size(), 1u);
        const Image img = p->readback(Component::Indirect);
        // rho / pi * Phi * w_n integrates over the plane to rho Phi / pi (the kernel has unit
        // integral; the beam meets the plane head on). Measured 1.0000 (box, tent), 1.0003
        // (Gaussian): the square's edges fall on pixel boundaries here; 1 % leaves room for the
        // pixel-centre sampling of an edge that does not.
        double integral = 0.0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) integral += double(img.at(x, y).r) * pixel * pixel;
        const double expected = gputest::kPlaneAlbedo * 2.0 / glm::pi<double>();
        RecordProperty(std::string(filter) + "_integralRatio", std::to_string(integral / expected));
        EXPECT_NEAR(integral, expected, 0.01 * expected) << filter;
        if (std::string(filter) == "box") {
            // Inside the square the level is rho / pi * Phi / (2h)^2 exactly; outside it is zero.
            const float level = gputest::kPlaneAlbedo / glm::pi<float>() * 2.0f / 1.0f;
            EXPECT_NEAR(img.at(kSize / 2, kSize / 2).r, level, 1e-4f * level);
            EXPECT_NEAR(img.at(kSize / 2 + 10, kSize / 2 - 12).r, level, 1e-4f * level);
            EXPECT_EQ(img.at(kSize / 2 + 20, kSize / 2).r, 0.0f);  // 0.63 m from the axis, outside
            EXPECT_EQ(img.at(5, 5).r, 0.0f);
        }
    }
}

TEST_F(PhotonSplatGpuTest, TheBundleDepthMapShadowsAReceiverBehindAnOccluder) {
    constexpr int kSize = 96;
    Scene scene = litPlane();
    // A small square 0.3 m above the plane, 0.4 m wide, on the +z side of the photon's 1.6 m bundle
    // only: a depth map mirrored across the bundle's axis would shadow the -z side instead.
    Mesh blocker;
    blocker.name = "blocker";
    blocker.positions = {{-0.2f, 0.3f, 0.0f}, {0.2f, 0.3f, 0.0f}, {0.2f, 0.3f, 0.4f}, {-0.2f, 0.3f, 0.4f}};
    blocker.normals.assign(4, glm::vec3(0, 1, 0));
    blocker.indices = {0, 2, 1, 0, 3, 2};
    scene.meshes.push_back(blocker);
    Object o;
    o.name = "blocker";
    o.mesh = 1;
    scene.objects.push_back(o);
    ASSERT_TRUE(finalizeScene(scene).ok());
    // A photon high on the -x side sends its bundle diagonally down along (1, -1, 0)/sqrt(2): its own
    // ray passes beside the blocker (x = 0.3 at the blocker's height) and hits the plane at x = 0.6;
    // the blocker's shadow along the bundle falls on the plane at x in [0.1, 0.5], z in [0, 0.4],
    // where the camera (straight above) sees the plane.
    const glm::vec3 w = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
    const photonsplat::Photon photon{{-0.9f, 1.5f, 0.0f}, glm::vec3(1.0f), w, {0.0f, 1.0f, 0.0f}};
    auto p = makePipeline(scene, "photon-splat", {{"estimate", "flux"}, {"filter", "box"}, {"mapSize", "1.6"}, {"stepBack", "1.0"},
                                                  {"mapResolution", "32"}}, kSize);
    splatOf(*p).setFixedPhotons({photon});
    p->renderFrame(0);
    ASSERT_EQ(splatOf(*p).bundles().size(), 1u);
    const Image img = p->readback(Component::Indirect);
    auto at = [&](float wx, float wz) {
        const int x = static_cast<int>((wx + gputest::kPlaneHalf) / (2.0f * gputest::kPlaneHalf) * kSize);
        const int y = static_cast<int>((wz + gputest::kPlaneHalf) / (2.0f * gputest::kPlaneHalf) * kSize);
        return img.at(x, y).r;
    };
    // Lit plane: rho / pi * Phi / (2h)^2 * cos 45 degrees.
    const float level = gputest::kPlaneAlbedo / glm::pi<float>() / (1.6f * 1.6f) * 0.70710678f;
    EXPECT_NEAR(at(0.3f, 0.6f), level, 1e-3f * level);   // beside the shadow, inside the bundle
    EXPECT_NEAR(at(0.3f, -0.2f), level, 1e-3f * level);  // the mirror image of the shadow: lit
    EXPECT_NEAR(at(1.0f, 0.0f), level, 1e-3f * level);   // past the shadow
    EXPECT_EQ(at(0.3f, 0.2f), 0.0f);                      // in the blocker's shadow
    EXPECT_EQ(at(0.4f, 0.3f), 0.0f);
}

TEST_F(PhotonSplatGpuTest, FluxEstimateAgainstTheOneBounceReference) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const Image ref = oneBounceReference(*scene, kSize, 0, 256);
    const Image img = renderIndirect(*scene, "photon-splat", {{"estimate", "flux"}, {"photons", "4096"}}, kSize);
    auto m = compareImages(img, ref);
    ASSERT_TRUE(m.ok());
    const double ratio = meanOf(img) / meanOf(ref);
    RecordProperty("relMse", std::to_string(m->relMse));
    RecordProperty("meanRatio", std::to_string(ratio));
    // Measured on llvmpipe (4096 photons, 64^2): relMSE 0.028, mean 0.81 of the reference. The
    // calibrated estimate loses the light of beam cross-sections that miss the receivers' depth
    // range (corners, the open front), so it stays below the reference. Bounds: 1.45x the relMSE
    // (the reference's 256-spp noise), mean within [0.7, 1.0] (halving the photons' power fails).
    EXPECT_LT(m->relMse, 0.04);
    EXPECT_GT(ratio, 0.7);
    EXPECT_LT(ratio, 1.0);
}

TEST_F(PhotonSplatGpuTest, FollowsTheMovingSpotOfCornellBoxDynamic) {
    auto scene = loadScene("cornell-box-dynamic");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 48;
    auto p = makePipeline(*scene, "photon-splat", {{"estimate", "flux"}, {"photons", "4096"}}, kSize);
    Image first, last;
    double worst = 0.0;
    for (uint32_t frame : {0u, 30u}) {
        p->renderFrame(frame);
        const Image img = p->readback(Component::Indirect);
        auto m = compareImages(img, oneBounceReference(*scene, kSize, frame, 256));
        ASSERT_TRUE(m.ok());
        worst = std::max(worst, m->relMse);
        RecordProperty("relMse_frame" + std::to_string(frame), std::to_string(m->relMse));
        (frame == 0 ? first : last) = img;
    }
    // Photons are shot anew for the moving light and block every frame (frozen photons keep
    // frame 0's light and fail at frame 30). Measured relMSE 0.028 / 0.022 at 48^2; bound 1.8x.
    EXPECT_LT(worst, 0.05);
    EXPECT_GT(relativeRmsError(last, first), 0.05);
}

TEST_F(PhotonSplatGpuTest, NormalisationIsTheWeightedMeanWithAnAmbientFallback) {
    constexpr int kSize = 64;
    const Scene scene = litPlane();
    const photonsplat::Photon photon{{0.0f, 0.5f, 0.0f}, glm::vec3(2.0f), {0.0f, -1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}};
    auto p = makePipeline(scene, "photon-splat", {{"estimate", "normalized"}, {"filter", "gaussian"}, {"mapSize", "1.0"},
                                                  {"ambient", "0.01"}, {"exposure", "2"}}, kSize);
    splatOf(*p).setFixedPhotons({photon, photon});
    p->renderFrame(0);
    const Image img = p->readback(Component::Indirect);
    // Inside the footprint: exposure * (w S) / w = 2 * C A with C = Phi / (pi (2h)^2), whatever the
    // weight (two identical photons average to one); outside: ambient * albedo.
    const float inside = 2.0f * 2.0f / (glm::pi<float>() * 1.0f) * gputest::kPlaneAlbedo;
    EXPECT_NEAR(img.at(kSize / 2, kSize / 2).r, inside, 1e-4f * inside);
    EXPECT_NEAR(img.at(kSize / 2 + 6, kSize / 2 + 5).r, inside, 1e-4f * inside);
    EXPECT_NEAR(img.at(2, 2).r, 0.01f * gputest::kPlaneAlbedo, 1e-6f);
}

TEST_F(PhotonSplatGpuTest, StratificationAndDebugViewsRender) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    auto p = makePipeline(*scene, "photon-splat", {{"stratify", "true"}, {"gridSize", "16"}}, 32);
    const Counters c = p->renderFrame(0).counters;
    EXPECT_GT(c.at("mergedBlocks"), 0.0);
    EXPECT_LT(c.at("photonsStratified"), c.at("photonsStored"));
    EXPECT_EQ(c.at("gridBytes"), 16.0 * 16 * 16 * 40);  // the thesis's dense 40 B per cell (M1)
    for (const char* view : {"overlap", "accumulation", "grid"}) {
        const Image img = renderIndirect(*scene, "photon-splat", {{"debugView", view}}, 32);
        EXPECT_GT(meanOf(img), 0.0) << view;
    }
}

TEST_F(PhotonSplatGpuTest, BadSettingsAreOneLineErrors) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    for (const auto& [settings, needle] : std::vector<std::pair<std::map<std::string, std::string>, std::string>>{
             {{{"blur", "4"}}, "blur"}, {{{"gridSize", "15"}}, "gridSize"}}) {
        auto t = createTechnique("photon-splat");
        ASSERT_TRUE(t.ok());
        ASSERT_TRUE(applySettings(**t, settings, "photon-splat").ok());
        auto p = Pipeline::create(*scene, std::move(*t), {16, 16}, smallRenderSettings());
        ASSERT_FALSE(p.ok());
        EXPECT_NE(p.error().message.find(needle), std::string::npos) << p.error().message;
    }
}

TEST_F(PhotonSplatGpuTest, RsmInjectionCarriesTheSamePowerAsShotPhotons) {
    // Method B (the reflective shadow map's VPLs) and method A (rays) estimate the same reflected
    // flux: rho times the spot's flux, all of which lands on the plane.
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 1.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.intensity = glm::vec3(10.0f);
    spot.cutoffAngle = glm::radians(30.0f);
    const Scene scene = gputest::planeScene(spot);
    const float expected = gputest::kPlaneAlbedo * spot.flux().r;
    for (const char* injection : {"rays", "rsm"}) {
        auto p = makePipeline(scene, "photon-splat", {{"injection", injection}, {"photons", "8192"}, {"rsmSize", "128"}, {"vplGrid", "64"}}, 16);
        p->renderFrame(0);
        double sum = 0.0;
        for (const photonsplat::Photon& ph : splatOf(*p).photons()) sum += ph.power.r;
        // 3 %: the RSM's cone rim crosses ~400 of its 128^2 texels (RsmGpuTest); the rays' sum has
        // ~0.5 % Monte Carlo error at 8192 photons.
        EXPECT_NEAR(sum, expected, 0.03 * expected) << injection;
    }
}

TEST_F(PhotonSplatGpuTest, BlurSpreadsTheFootprintAndKeepsItsIntegral) {
    constexpr int kSize = 128;
    const Scene scene = litPlane();
    const photonsplat::Photon photon{{0.0f, 0.5f, 0.0f}, glm::vec3(2.0f), {0.0f, -1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}};
    auto render = [&](const char* blur) {
        auto p = makePipeline(scene, "photon-splat", {{"estimate", "flux"}, {"filter", "box"}, {"mapSize", "1.0"}, {"blur", blur}}, kSize);
        splatOf(*p).setFixedPhotons({photon});
        p->renderFrame(0);
        return p->readback(Component::Indirect);
    };
    const Image sharp = render("0"), blurred = render("9");
    // The box footprint spans pixels 48..79; one pixel outside is 0 sharp and lit after the blur, and
    // the normalised Gaussian (far from the image border) keeps the sum to float rounding.
    EXPECT_EQ(sharp.at(kSize / 2, 47).r, 0.0f);
    EXPECT_GT(blurred.at(kSize / 2, 47).r, 0.0f);
    EXPECT_LT(blurred.at(kSize / 2 + 16, kSize / 2 + 16).r, sharp.at(kSize / 2 + 15, kSize / 2 + 15).r);
    EXPECT_NEAR(totalRadiance(blurred), totalRadiance(sharp), 1e-4 * totalRadiance(sharp));
}
