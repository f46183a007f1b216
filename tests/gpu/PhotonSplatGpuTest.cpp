// Photon splatting (seed 004) on the GPU: one photon over a plane splats its footprint (the box
// filter's square at the calibrated level, each filter's integral), a bundle's depth map shadows the
// receiver behind an occluder, the calibrated estimate against the one-bounce reference (still and
// animated), the document's normalisation, debug views and settings errors.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "reference/Rng.h"
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
        auto p = makePipeline(scene, "photon-splat", {{"estimate", "flux"}, {"filter", filter}, {"mapSize", "1.0"}, {"stepBack", "0.1"}, {"blur", "0"}}, kSize);
        splatOf(*p).setFixedPhotons({photon});
        const Counters counters = p->renderFrame(0).counters;
        ASSERT_EQ(splatOf(*p).bundles().size(), 1u);
        // M6's overlap counters: one bundle over its 1 m square, 32 x 32 pixels of 3.125 cm.
        EXPECT_EQ(counters.at("overlapMax"), 1.0) << filter;
        if (std::string(filter) == "box") {
            EXPECT_EQ(counters.at("overlapPixels"), 1024.0);
        }
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
                                                  {"mapResolution", "32"}, {"blur", "0"}}, kSize);
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

TEST_F(PhotonSplatGpuTest, BundlesDepositTheirWholeFluxAcrossEdges) {
    // Unbiasedness of the flux estimate where bundles straddle geometry: every parallel ray of a
    // bundle must leave its share of the photon's power on the first surface it meets. A 0.6 m table
    // top 0.3 m above the plane, photons 1 m up aimed at its edges (their bundles fall partly on the
    // table, partly on the plane below it, where the table's side is not in the way), and photons
    // whose own ray passes the plane's edge (their bundles fall partly on the plane). Seen from
    // straight above, the image integrates to rho/pi times the power the parallel rays bring to the
    // table top or to the plane where the table does not hide it: a CPU integration over each
    // bundle's cross-section (its Gaussian weight, 400^2 rays against the two rectangles).
    constexpr int kSize = 128;
    constexpr float kTable = 0.3f, kTableHeight = 0.3f, kHalf = 0.5f;  // table half side, height; bundle half width h
    Scene scene = litPlane();
    Mesh table;
    table.name = "table";
    table.positions = {{-kTable, kTableHeight, -kTable}, {kTable, kTableHeight, -kTable}, {kTable, kTableHeight, kTable}, {-kTable, kTableHeight, kTable}};
    table.normals.assign(4, glm::vec3(0, 1, 0));
    table.indices = {0, 2, 1, 0, 3, 2};
    scene.meshes.push_back(table);
    Object o;
    o.name = "table";
    o.mesh = 1;
    scene.objects.push_back(o);
    ASSERT_TRUE(finalizeScene(scene).ok());
    std::vector<photonsplat::Photon> photons;
    Rng rng(11, 0, 0);
    for (int i = 0; i < 48; ++i) {
        // Above a point near the table's edges, aimed down within 40 degrees of the vertical.
        const float side = (i % 4 < 2 ? -1.0f : 1.0f) * kTable, along = -kTable + 2.0f * kTable * rng.next();
        const glm::vec3 target = i % 2 == 0 ? glm::vec3(side + 0.2f * (rng.next() - 0.5f), 0.0f, along) : glm::vec3(along, 0.0f, side + 0.2f * (rng.next() - 0.5f));
        const float theta = glm::radians(40.0f) * rng.next(), phi = 2.0f * glm::pi<float>() * rng.next();
        const glm::vec3 w(std::sin(theta) * std::cos(phi), -std::cos(theta), std::sin(theta) * std::sin(phi));
        photons.push_back({target - w / -w.y, glm::vec3(1.0f), w, {0.0f, -1.0f, 0.0f}});
    }
    for (int i = 0; i < 8; ++i) {
        // Own ray past the plane's +x edge (x = 2.1 at the plane): no hit, half its bundle lands.
        const glm::vec3 w = glm::normalize(glm::vec3(0.5f, -1.0f, 0.1f * static_cast<float>(i - 4)));
        photons.push_back({glm::vec3(2.1f, 0.0f, 0.2f * static_cast<float>(i - 4)) - w / -w.y, glm::vec3(1.0f), w, {0.0f, -1.0f, 0.0f}});
    }
    auto p = makePipeline(scene, "photon-splat", {{"mapSize", std::to_string(2.0f * kHalf)}, {"blur", "0"}}, kSize);
    splatOf(*p).setFixedPhotons(photons);
    p->renderFrame(0);
    ASSERT_EQ(splatOf(*p).bundles().size(), photons.size());  // the 8 without a hit keep their bundles
    const Image img = p->readback(Component::Indirect);
    const double pixel = 2.0 * gputest::kPlaneHalf / kSize;
    double integral = 0.0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) integral += double(img.at(x, y).r) * pixel * pixel;
    double landed = 0.0;
    constexpr int kRays = 400;
    for (const photonsplat::Photon& ph : photons) {
        glm::vec3 right, up;
        photonsplat::bundleAxes(ph.direction, right, up);
        double hit = 0.0, all = 0.0;
        for (int a = 0; a < kRays; ++a)
            for (int b = 0; b < kRays; ++b) {
                const float u = -1.0f + (a + 0.5f) * 2.0f / kRays, v = -1.0f + (b + 0.5f) * 2.0f / kRays;
                const double weight = std::exp(-2.0 * (u * u + v * v));  // Gaussian, sigma = h/2
                const glm::vec3 start = ph.position + kHalf * (u * right + v * up);
                all += weight;
                const glm::vec3 atTable = start + ph.direction * ((kTableHeight - start.y) / ph.direction.y);
                const glm::vec3 atPlane = start + ph.direction * (-start.y / ph.direction.y);
                const bool onTable = std::abs(atTable.x) <= kTable && std::abs(atTable.z) <= kTable;
                const bool underTable = std::abs(atPlane.x) <= kTable && std::abs(atPlane.z) <= kTable;  // hidden from above
                const bool onPlane = std::abs(atPlane.x) <= gputest::kPlaneHalf && std::abs(atPlane.z) <= gputest::kPlaneHalf;
                if (onTable || (onPlane && !underTable)) hit += weight;
            }
        landed += ph.power.r * hit / all;
    }
    const double expected = gputest::kPlaneAlbedo / glm::pi<double>() * landed;
    RecordProperty("integralRatio", std::to_string(integral / expected));
    RecordProperty("landedFraction", std::to_string(landed / static_cast<double>(photons.size())));
    // Measured 0.998 on llvmpipe (128^2; the footprints' edges are sampled at pixel centres, 3 cm
    // apart). 2 %: a bundle that drops the rays nearer than a small step back before its hit (the
    // table top under the edge bundles: 6 % of the total), the rays past a short depth (the plane
    // under the edge bundles) or those of a photon whose own ray misses (4 %) fails it.
    EXPECT_NEAR(integral, expected, 0.02 * expected);
}

TEST_F(PhotonSplatGpuTest, DefaultsAreWithinTheBoundsOfTheOneBounceReference) {
    // The defaults (flux estimate, 16384 photons, 2h = diagonal / 20, b = d, D past the scene, blur 5) against
    // the path tracer's one-bounce indirect light, and the no-GI image (black) against it: the
    // project's bounds are energy within 15 % and relMSE below the no-GI image's.
    constexpr int kSize = 64;
    for (const char* name : {"cornell-box", "cornell-box-area", "furnace", "two-rooms"}) {
        auto scene = loadScene(name);
        ASSERT_TRUE(scene.ok());
        const Image ref = oneBounceReference(*scene, kSize, 0, 256);
        const Image img = renderIndirect(*scene, "photon-splat", {}, kSize);
        auto m = compareImages(img, ref);
        auto noGi = compareImages(Image(kSize, kSize), ref);
        ASSERT_TRUE(m.ok() && noGi.ok());
        const double energy = meanOf(img) / meanOf(ref);
        RecordProperty(std::string(name) + "_relMse", std::to_string(m->relMse));
        RecordProperty(std::string(name) + "_energy", std::to_string(energy));
        RecordProperty(std::string(name) + "_noGiRelMse", std::to_string(noGi->relMse));
        // Measured on llvmpipe at 64^2 (energy / relMSE / no-GI relMSE): cornell-box 0.981 / 0.0147
        // / 0.133, cornell-box-area 0.997 / 0.0166 / 0.182, furnace 0.960 / 0.030 / 0.860,
        // two-rooms 0.970 / 0.0064 / 0.136. The energy bound is the project's (halved or doubled
        // light fails it; the furnace's 4 % is the bundles' corner bias, docs); the relMSE bounds are
        // the no-GI image's and 1.6x the measured relMSE (the reference's 256-spp noise and another
        // photon seed stay within it).
        EXPECT_NEAR(energy, 1.0, 0.15) << name;
        EXPECT_LT(m->relMse, noGi->relMse) << name;
        const double measured = std::string(name) == "cornell-box" ? 0.0147 : std::string(name) == "cornell-box-area" ? 0.0166
                              : std::string(name) == "furnace" ? 0.030 : 0.0064;
        EXPECT_LT(m->relMse, 1.6 * measured) << name;
    }
}

TEST_F(PhotonSplatGpuTest, FollowsTheMovingSpotOfCornellBoxDynamic) {
    auto scene = loadScene("cornell-box-dynamic");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 48;
    auto p = makePipeline(*scene, "photon-splat", {}, kSize);
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
    // frame 0's light and fail at frame 30 with relMSE 0.15). Measured relMSE 0.0156 / 0.0098 at
    // 48^2 (defaults); bound 1.6x the worse.
    EXPECT_LT(worst, 0.025);
    EXPECT_GT(relativeRmsError(last, first), 0.05);
}

TEST_F(PhotonSplatGpuTest, NormalisationIsTheWeightedMeanWithAnAmbientFallback) {
    constexpr int kSize = 64;
    const Scene scene = litPlane();
    const photonsplat::Photon photon{{0.0f, 0.5f, 0.0f}, glm::vec3(2.0f), {0.0f, -1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}};
    auto p = makePipeline(scene, "photon-splat", {{"estimate", "normalized"}, {"filter", "gaussian"}, {"mapSize", "1.0"},
                                                  {"ambient", "0.01"}, {"exposure", "2"}, {"blur", "0"}}, kSize);
    splatOf(*p).setFixedPhotons({photon, photon});
    const Counters counters = p->renderFrame(0).counters;
    EXPECT_EQ(counters.at("overlapMax"), 2.0);  // the two bundles cover the same pixels
    EXPECT_EQ(counters.at("overlapMean"), 2.0);
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
    // The grid's allocation: one 16-byte entry per photon (all of them lie in the scene's bounds),
    // not the thesis's dense 40 B per cell (16^3 x 40 = 164 KB here).
    EXPECT_EQ(c.at("gridBytes"), 16.0 * c.at("photonsStored"));
    for (const char* view : {"overlap", "accumulation", "grid"}) {
        const Image img = renderIndirect(*scene, "photon-splat", {{"debugView", view}}, 32);
        EXPECT_GT(meanOf(img), 0.0) << view;
    }
}

TEST_F(PhotonSplatGpuTest, ByteCountersReportWhatIsAllocated) {
    // photonBytes is the photon list's allocation (48-byte Photons, not Table 1's 36 B),
    // bundleBufferBytes the bundle buffer GL holds, depthAtlasBytes the depth atlas's storage: each
    // read back from what exists, at two photon counts.
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    for (int photons : {1000, 3000}) {
        auto p = makePipeline(*scene, "photon-splat", {{"photons", std::to_string(photons)}}, 32);
        const Counters c = p->renderFrame(0).counters;
        const PhotonSplatTechnique& t = splatOf(*p);
        EXPECT_EQ(c.at("photonBytes"), static_cast<double>(t.photons().capacity() * sizeof(photonsplat::Photon)));
        EXPECT_GE(c.at("photonBytes"), 48.0 * c.at("photonsStored"));
        GLint64 bufferSize = 0;
        glGetNamedBufferParameteri64v(t.bundleBuffer().id(), GL_BUFFER_SIZE, &bufferSize);
        EXPECT_EQ(c.at("bundleBufferBytes"), static_cast<double>(bufferSize));
        EXPECT_EQ(bufferSize, static_cast<GLint64>(photons) * 112);  // one BundleGpu per photon: the frame's most bundles
        GLint width = 0, height = 0, format = 0;
        glGetTextureLevelParameteriv(t.depthAtlas().id(), 0, GL_TEXTURE_WIDTH, &width);
        glGetTextureLevelParameteriv(t.depthAtlas().id(), 0, GL_TEXTURE_HEIGHT, &height);
        glGetTextureLevelParameteriv(t.depthAtlas().id(), 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
        EXPECT_TRUE(format == GL_R32F || format == GL_DEPTH_COMPONENT32F) << format;  // depthMaps=rays, compute / raster
        EXPECT_EQ(c.at("depthAtlasBytes"), 4.0 * width * height);
        EXPECT_GE(static_cast<double>(width) * height, 64.0 * photons);  // an 8 x 8 tile per bundle
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
    // The kernel is the Gaussian of sigma = 9/4 pixels, normalised, applied along x then y with the
    // edge pixels repeated: the CPU's blur of the sharp image, pixel by pixel (a box or tent of the
    // same width differs by up to a third of the level at the footprint's edges).
    constexpr int kRadius = 4;
    constexpr float kSigma = 9.0f / 4.0f;
    float weights[2 * kRadius + 1], total = 0.0f;
    for (int i = -kRadius; i <= kRadius; ++i) total += weights[i + kRadius] = std::exp(-0.5f * float(i * i) / (kSigma * kSigma));
    Image across(kSize, kSize), expected(kSize, kSize);
    for (int pass = 0; pass < 2; ++pass) {
        const Image& from = pass == 0 ? sharp : across;
        Image& to = pass == 0 ? across : expected;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                glm::vec3 sum(0.0f);
                for (int i = -kRadius; i <= kRadius; ++i)
                    sum += weights[i + kRadius] / total *
                           (pass == 0 ? from.at(std::clamp(x + i, 0, kSize - 1), y) : from.at(x, std::clamp(y + i, 0, kSize - 1)));
                to.at(x, y) = sum;
            }
    }
    const float level = sharp.at(kSize / 2, kSize / 2).r;
    float worst = 0.0f;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) worst = std::max(worst, std::abs(blurred.at(x, y).r - expected.at(x, y).r));
    EXPECT_LT(worst, 1e-4f * level);  // float rounding of nine products
}

// The depth atlas's texels (depth in [0, 1]): a depth texture (depthMaps=raster) or R32F (compute, rays).
constexpr float kRoundingApart = 1e-5f;  // depth (of [0, 1]): the two paths' float rounding stays under 1e-6

static std::vector<float> readAtlas(const gl::Texture& t) {
    std::vector<float> texels(static_cast<size_t>(t.width()) * static_cast<size_t>(t.height()));
    const GLenum format = t.desc().format == GL_R32F ? GL_RED : GL_DEPTH_COMPONENT;
    glGetTextureImage(t.id(), 0, format, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(float)), texels.data());
    return texels;
}

TEST_F(PhotonSplatGpuTest, CulledDepthMapsEqualTheMapsOfEveryCluster) {
    // The CPU cull (ClusterSet::cull, mayOverlap) only drops (bundle, cluster) pairs whose every
    // triangle depth.vert and depth_raster.comp clip (here depthMaps=compute; raster shares the cull):
    // the depth atlas with it equals, bit for bit, the atlas with every cluster drawn into every bundle's map. The smallest courtyard (2,128 triangles: arcades, columns
    // and the alpha-masked foliage) under its sun, 500 photons; the cull must also have dropped draws.
    auto scene = loadScene("courtyard", {{"triangles", "2128"}});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    auto atlas = [&](bool cull, double& draws) {
        auto p = makePipeline(*scene, "photon-splat", {{"photons", "500"}, {"depthMaps", "compute"}}, 32);
        splatOf(*p).setCullClusters(cull);
        draws = p->renderFrame(0).counters.at("clusterDraws");
        return readAtlas(splatOf(*p).depthAtlas());
    };
    double culledDraws = 0.0, allDraws = 0.0;
    const std::vector<float> culled = atlas(true, culledDraws), all = atlas(false, allDraws);
    ASSERT_EQ(culled.size(), all.size());
    size_t differ = 0, written = 0;
    for (size_t i = 0; i < all.size(); ++i) {
        differ += culled[i] != all[i] ? 1 : 0;
        written += all[i] < 1.0f ? 1 : 0;
    }
    EXPECT_EQ(differ, 0u) << "of " << all.size() << " texels";
    EXPECT_GT(written, all.size() / 10) << "the maps hold geometry";
    EXPECT_LT(culledDraws, 0.5 * allDraws) << culledDraws << " of " << allDraws;
}

TEST_F(PhotonSplatGpuTest, ComputedAndTracedDepthMapsEqualTheRasterisedMaps) {
    // depthMaps=compute (depth_raster.comp) and depthMaps=rays (DepthRays: llvmpipe's default) make the
    // maps depthMaps=raster (depth.vert and the rasteriser, a GPU's default) makes: the same scene and
    // photons as above (arcades, columns, alpha-masked foliage), every texel compared. Measured, of 7,522
    // texels written: compute 8 only by the rasteriser, none only by the compute pass, 14 more than 1e-5
    // apart; rays 8, none, 13 (texel centres on a clip plane or a shared edge, decided by different
    // arithmetic), the rest within float rounding; the images 2e-6 apart in relMSE on courtyard
    // (docs/techniques/photon-splat.md). Bound: 1 % of the written texels for each kind of disagreement
    // (3x the measured worst).
    auto scene = loadScene("courtyard", {{"triangles", "2128"}});
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    auto atlas = [&](const char* mode) {
        auto p = makePipeline(*scene, "photon-splat", {{"photons", "500"}, {"depthMaps", mode}}, 32);
        p->renderFrame(0);
        return readAtlas(splatOf(*p).depthAtlas());
    };
    const std::vector<float> raster = atlas("raster");
    for (const char* mode : {"compute", "rays"}) {
        const std::vector<float> other = atlas(mode);
        ASSERT_EQ(raster.size(), other.size());
        size_t written = 0, onlyRaster = 0, onlyOther = 0, apart = 0;
        for (size_t i = 0; i < raster.size(); ++i) {
            const bool r = raster[i] < 1.0f, c = other[i] < 1.0f;
            written += r ? 1 : 0;
            onlyRaster += r && !c ? 1 : 0;
            onlyOther += c && !r ? 1 : 0;
            apart += r && c && std::abs(raster[i] - other[i]) > kRoundingApart ? 1 : 0;
        }
        std::printf("depth maps (%s): %zu texels written by the rasteriser, %zu by it alone, %zu by %s alone, %zu more than %g apart\n",
                    mode, written, onlyRaster, onlyOther, mode, apart, static_cast<double>(kRoundingApart));
        EXPECT_GT(written, raster.size() / 10) << "the maps hold geometry";
        EXPECT_LE(onlyRaster, written / 100) << mode;
        EXPECT_LE(onlyOther, written / 100) << mode;
        EXPECT_LE(apart, written / 100) << mode;
    }
}
