// Hemicube radiosity with point, spot and directional lights (bounce's extension of van de Hoef 2013,
// docs/techniques/radiosity.md "Point, spot and directional lights"): the light's direct radiance at
// the elements (D, shadow-mapped) is shot as their first unshot radiosity, the display adds the
// direct light per pixel and shows B - E - D as indirect; a moving light is a change of D shot into
// the solution. Each method against the path tracer (every bounce, Lambert after the first hit: the
// techniques' declared scope) on the spot-lit Cornell box, still and with the light orbiting.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "scene/SceneLoader.h"
#include "techniques/radiosity/RadiosityTechnique.h"

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class RadiosityLightsGpuTest : public gputest::GpuTest {};

const char* const kMethods[] = {"radiosity-gather", "radiosity-pr", "radiosity-incremental", "radiosity-cross"};

Scene builtin(const std::string& name) {
    auto s = loadScene(name, {});
    EXPECT_TRUE(s.ok()) << name << ": " << (s.ok() ? "" : s.error().message);
    return std::move(*s);
}

Image pathTraced(const Scene& scene, int size, uint32_t frame, uint32_t spp) {
    PathTracerSettings pts;
    pts.width = pts.height = size;
    pts.samplesPerPixel = spp;
    pts.diffuseOnly = true;
    pts.frame = frame;
    auto tracer = PathTracer::create(scene, pts);
    EXPECT_TRUE(tracer.ok()) << tracer.error().message;
    return tracer->render().radiance;
}

// Coarser than the defaults (0.05 m, 64^2 hemicubes) to keep the gather inside CI's time: the
// elements' own error grows a little (measured below).
const std::map<std::string, std::string> kSettings = {{"elementSize", "0.1"}, {"hemicubeSize", "32"}};
// The shooting methods also with their time budget per frame off: each frame's solution completes
// (maxIterations alone bounds it) whatever the host's speed; the gather has no budget.
std::map<std::string, std::string> settingsOf(const std::string& method) {
    auto s = kSettings;
    // insert_or_assign with a std::string: gcc 12's -Wrestrict misfires on operator=(const char*)
    // after a map copy (CI's -Werror build stopped on it).
    if (method != "radiosity-gather") s.insert_or_assign("frameBudgetMs", std::string("0"));
    return s;
}
constexpr int kSize = 48;
constexpr uint32_t kSpp = 256;

}  // namespace

TEST_F(RadiosityLightsGpuTest, EveryMethodMatchesThePathTracerUnderASpotLight) {
    const Scene scene = builtin("cornell-box");
    const Image ref = pathTraced(scene, kSize, 0, kSpp);
    for (const char* method : kMethods) {
        SCOPED_TRACE(method);
        auto p = makePipeline(scene, method, settingsOf(method), kSize);
        p->renderFrame(0);
        const Image full = p->readback(Component::Full), direct = p->readback(Component::Direct);
        const Image indirect = p->readback(Component::Indirect);
        auto m = compareImages(full, ref);
        ASSERT_TRUE(m.ok());
        const double energy = totalRadiance(full) / totalRadiance(ref);
        const double indirectShare = totalRadiance(indirect) / totalRadiance(full);
        RecordProperty(std::string(method) + "_energy", std::to_string(energy));
        RecordProperty(std::string(method) + "_relMse", std::to_string(m->relMse));
        RecordProperty(std::string(method) + "_indirectShare", std::to_string(indirectShare));
        // Measured at these settings: energy 0.956 (pr, incremental, cross) and 0.959 (gather), relMSE
        // 0.0189 / 0.0186, indirect share 0.634; the no-GI image (the direct pass) scores 0.37 / 0.22. The
        // path tracer's 256 spp noise alone is relMSE ~0.01. The bounds: energy 1 +- 0.08 (the
        // measurement's 4.4 % shortfall, the disk approximation and threshold as in RadiosityGpuTest, plus
        // the reference's noise), relMSE 0.03 (measurement + 60 %). A halved D scores 0.65 / 0.069 and
        // fails both; the display without the per-pixel direct light fails the energy (mutation table in
        // radiosity.md).
        EXPECT_NEAR(energy, 1.0, 0.08);
        EXPECT_LT(m->relMse, 0.03);
        EXPECT_GT(indirectShare, 0.45);
        EXPECT_LT(indirectShare, 0.75);
        // The direct output is the shared direct pass's light where no emitter is seen (the Cornell box's
        // spot has no emitter quad): the same pixels as the `direct` technique's image.
        EXPECT_GT(totalRadiance(direct), 0.0);
    }
}

TEST_F(RadiosityLightsGpuTest, AMovingLightIsFollowed) {
    // cornell-box-dynamic: the spot orbits (4 s loop) and the tall block turns. Frames 0, 15 and 30
    // (the incremental methods update from the previous frame's solution; a quarter of the loop in all),
    // the last against the path tracer at frame 30. Measured (energy / relMSE): incremental 0.978 /
    // 0.0166, cross 1.002 / 0.0184. With D frozen after frame 0 (applyLights skipped): relMSE 0.118 and
    // 0.121; with a halved D: 0.60 / 0.061 and 0.63 / 0.055. The bounds: energy 1 +- 0.08 as above,
    // relMSE 0.03 (measurement + 60 %, a quarter of the frozen light's).
    const Scene scene = builtin("cornell-box-dynamic");
    constexpr uint32_t kLast = 30;
    const Image ref = pathTraced(scene, kSize, kLast, kSpp);
    for (const char* method : {"radiosity-incremental", "radiosity-cross"}) {
        SCOPED_TRACE(method);
        auto p = makePipeline(scene, method, settingsOf(method), kSize);
        for (uint32_t f : {0u, kLast / 2, kLast}) p->renderFrame(f);
        const Image full = p->readback(Component::Full);
        auto m = compareImages(full, ref);
        ASSERT_TRUE(m.ok());
        const double energy = totalRadiance(full) / totalRadiance(ref);
        RecordProperty(std::string(method) + "_energy", std::to_string(energy));
        RecordProperty(std::string(method) + "_relMse", std::to_string(m->relMse));
        EXPECT_NEAR(energy, 1.0, 0.08);
        EXPECT_LT(m->relMse, 0.03);
    }
}
