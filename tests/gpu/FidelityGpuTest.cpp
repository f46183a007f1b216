// The bound every technique meets (DEVELOPERS.md, issue 28): at its default settings, on every
// built-in scene it accepts, against the reference scope `bounce list` declares for it, its image
// holds the reference's energy within +-15 % and has a relMSE below the no-GI image's (the shared
// direct pass's image of the same component: black for indirect scopes). A scene a technique
// refuses must be refused with a one-line error. Where a technique's own method provably adds or
// loses light on a scene, the pair is listed in kKnownBiases with the measured energy, its cause and
// the doc page that derives it; the test then holds the pair to that measurement (so the bias can
// neither grow unnoticed nor vanish without the table being corrected).
//
// 64^2 images against 256-spp references (the reference's noise on the image mean is below 0.3 %),
// one reference per scene and scope shared by every technique. The benchmark record with FLIP and
// the 128^2 / 1024-spp table is bench/fidelity/run.py's (README "Fidelity").
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "techniques/vct/ConeQuadrature.h"
#include "techniques/Registry.h"

#include <cstdio>
#include <map>
#include <tuple>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

constexpr int kSize = 64;
constexpr uint32_t kReferenceSpp = 256;
constexpr double kEnergyTolerance = 0.15;  // DEVELOPERS.md: within +-15 % of the reference's energy

// Frames before the image is taken (bench/fidelity/run.py's FRAMES): the progressive radiosity
// methods shoot a budget per frame until converged; everything else is complete in frame 0.
bool shootsRadiosity(const std::string& technique) {
    return technique == "radiosity-pr" || technique == "radiosity-incremental" || technique == "radiosity-cross";
}
int framesOf(const std::string& technique) { return shootsRadiosity(technique) ? 8 : 1; }

// The defaults, except the shooting radiosity methods' time budget per frame (frameBudgetMs), off as in
// bench/fidelity/run.py: a time budget makes the frame a solution reaches depend on the host's speed;
// maxIterations alone bounds the frames (docs/techniques/radiosity.md, "Per-frame shooting budget").
std::map<std::string, std::string> settingsOf(const std::string& technique) {
    if (shootsRadiosity(technique)) return {{"frameBudgetMs", "0"}};
    return {};
}

// Default radiosity takes minutes on llvmpipe for most scenes' elements (the gather, the expensive
// reference, everywhere but cornell-box-area; the shooting methods on the larger rooms, where
// radiosity-pr re-solves each of its 8 frames: two-rooms 170 s; the radiosity performance work is
// issue 30): the benchmark record (bench/fidelity/run.py) covers them. The Cornell boxes keep every
// light type in CI: area (cornell-box-area, -rotating) and spot (cornell-box, -dynamic).
bool tooSlowForCi(const std::string& technique, const std::string& scene) {
    // The Sponza-class courtyard (150K triangles by default) is checked at a few thousand triangles by
    // CourtyardGpuTest (every technique runs or refuses in one line); its fidelity is a bench record.
    if (scene == "courtyard") return true;
    if (technique == "radiosity-gather") return scene != "cornell-box-area";
    return technique.rfind("radiosity-", 0) == 0 && scene.rfind("cornell-box", 0) != 0 && scene != "furnace";
}

struct KnownBias {
    double energy;      // measured at 64^2 (tests/gpu/FidelityGpuTest.cpp's RecordProperty)
    double tolerance;   // how far the measurement may move (reference noise, llvmpipe vs GPU filtering)
    bool addsLight;     // the method adds light where the reference is dark: relMSE may exceed no-GI's
    const char* why;    // the cause, derived in the doc page named
    // vct: `energy` is the ideal quadrature of the six cones against the reference (the method's own
    // bias, derived by the path tracer's cone quadrature: vct.md "The six cones' own bias"), and the
    // technique is held within +-kEnergyTolerance of that quadrature's energy instead of the reference's.
    bool againstConeQuadrature = false;
};

// (technique, scene) -> the measured bias of the technique's own method.
const std::map<std::pair<std::string, std::string>, KnownBias>& knownBiases() {
    static const std::map<std::pair<std::string, std::string>, KnownBias> biases = {
        // The RSM gathers have no indirect visibility (Nichols 2010 ch. 3-4, Dachsbacher & Stamminger
        // 2005): in the furnished room the table and the bookshelf cast large indirect shadows the
        // gathers light (docs/techniques/rsm.md); the added light also lifts their relMSE above the
        // no-GI image's (0.433 against 0.409).
        {{"rsm", "furnished-room"}, {1.29, 0.06, true, "no indirect visibility (rsm.md)"}},
        {{"rsm-splat", "furnished-room"}, {1.29, 0.06, true, "no indirect visibility (rsm.md)"}},
        {{"isr", "furnished-room"}, {1.29, 0.06, true, "no indirect visibility (isr.md)"}},
        {{"hisr", "furnished-room"}, {1.29, 0.06, true, "no indirect visibility (hisr.md)"}},
        {{"multires-splat", "furnished-room"}, {1.29, 0.06, true, "no indirect visibility (multires-splat.md)"}},
        // The same missing visibility where the converged gather leaves +15 % too (rsm.md's table: 1.15 on
        // cornell-box-area, 1.19 on the atrium; with VPL visibility 0.99 and 0.96).
        {{"isr", "cornell-box-area"}, {1.15, 0.05, false, "no indirect visibility (rsm.md)"}},
        {{"isr", "atrium"}, {1.19, 0.05, false, "no indirect visibility (rsm.md)"}},
        {{"hisr", "atrium"}, {1.18, 0.05, false, "no indirect visibility (rsm.md)"}},
        // vct: the 2 cm wall is a third of a voxel, so both rooms' light shares its voxels (vct.md, "Where
        // the light goes"). In the furnished room the six cones' own quadrature of the exact light holds
        // 0.81 of it (light between the cones is lost; measured 0.804 at 64^2, 256 spp; bound 0.03 for the
        // reference noise of both images and the cones' frame turning with the normal): vct
        // is held within 15 % of that (0.89 of it at 128^2, record vct-cone-quadrature-2026-12-06).
        {{"vct", "two-rooms"}, {1.17, 0.06, false, "thin-wall leak (vct.md)"}},
        {{"vct", "furnished-room"}, {0.81, 0.03, false, "the six cones' quadrature (vct.md)", true}},
        // iir: a textured area light is one cosine spot at its centre with the texture's mean radiance
        // (the paper's crude approximation, iir.md "Primary lights").
        {{"iir", "area-screen"}, {0.80, 0.06, false, "area light as one cosine spot (iir.md)"}},
        };
    return biases;
}

double meanOf(const Image& img) {
    double sum = 0.0;
    for (const glm::vec3& p : img.pixels()) sum += (p.r + p.g + p.b) / 3.0;
    return sum / static_cast<double>(img.pixelCount());
}

// One reference per (scene, scope, frame), shared by every technique's test. The frame is the one the
// technique's image shows (its last): in an animated scene the light or the objects have moved by then.
// coneQuadrature: the first reflection by vct's six cones instead of the cosine lobe
// (PathTracerSettings::firstReflectionCones).
const Image& reference(const std::string& sceneName, const Scene& scene, const ReferenceScope& scope, uint32_t frame,
                       bool coneQuadrature = false) {
    static std::map<std::tuple<std::string, int, bool, bool, uint32_t, bool>, Image> cache;
    const auto key = std::make_tuple(sceneName, scope.bounces, scope.indirectOnly, scope.diffuseOnly, frame, coneQuadrature);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    PathTracerSettings pts;
    if (coneQuadrature) pts.firstReflectionCones = vct::diffuseQuadratureCones();
    pts.width = pts.height = kSize;
    pts.samplesPerPixel = kReferenceSpp;
    pts.bounces = scope.bounces;
    pts.indirectOnly = scope.indirectOnly;
    pts.diffuseOnly = scope.diffuseOnly;
    pts.frame = frame;
    auto tracer = PathTracer::create(scene, pts);
    EXPECT_TRUE(tracer.ok());
    return cache[key] = tracer->render().radiance;
}

// Frames [first, last] in order; the image of the last.
Image renderComponent(const Scene& scene, const std::string& technique, Component component, uint32_t first, uint32_t last) {
    auto p = makePipeline(scene, technique, settingsOf(technique), kSize);
    for (uint32_t f = first; f <= last; ++f) p->renderFrame(f);
    return p->readback(component);
}

class FidelityGpuTest : public gputest::GpuTest, public ::testing::WithParamInterface<std::string> {};

}  // namespace

TEST_P(FidelityGpuTest, DefaultsHoldTheReferenceScopesLightOnEveryBuiltinScene) {
    const std::string technique = GetParam();
    const TechniqueInfo* info = nullptr;
    for (const TechniqueInfo& t : registeredTechniques())
        if (t.name == technique) info = &t;
    ASSERT_NE(info, nullptr);
    size_t accepted = 0;
    for (const BuiltinSceneInfo& s : builtinScenes()) {
        if (tooSlowForCi(technique, s.name)) continue;
        auto scene = loadScene(s.name);
        ASSERT_TRUE(scene.ok()) << s.name;
        const std::string refusal = setupRefusal(*scene, technique);
        if (!refusal.empty()) {
            EXPECT_EQ(refusal.find('\n'), std::string::npos) << technique << " on " << s.name << ": " << refusal;
            continue;
        }
        ++accepted;
        const auto last = static_cast<uint32_t>(framesOf(technique) - 1);
        const Image& ref = reference(s.name, *scene, info->scope, last);
        const Image img = renderComponent(*scene, technique, info->scope.component, 0, last);
        const Image noGi = renderComponent(*scene, "direct", info->scope.component, last, last);
        const double energy = meanOf(img) / meanOf(ref);
        auto m = compareImages(img, ref);
        auto m0 = compareImages(noGi, ref);
        ASSERT_TRUE(m.ok() && m0.ok());
        RecordProperty(s.name + "_energy", std::to_string(energy));
        RecordProperty(s.name + "_relMse", std::to_string(m->relMse));
        RecordProperty(s.name + "_noGiRelMse", std::to_string(m0->relMse));
        std::printf("fidelity %-22s %-22s energy %.3f relMSE %.4f (no GI %.4f)\n", technique.c_str(), s.name.c_str(), energy,
                    m->relMse, m0->relMse);
        const auto bias = knownBiases().find({technique, s.name});
        if (bias != knownBiases().end() && bias->second.againstConeQuadrature) {
            const Image& quadrature = reference(s.name, *scene, info->scope, last, true);
            const double own = meanOf(quadrature) / meanOf(ref), vsOwn = meanOf(img) / meanOf(quadrature);
            std::printf("fidelity %-22s %-22s the cones' quadrature %.3f of the reference; the technique %.3f of it\n",
                        technique.c_str(), s.name.c_str(), own, vsOwn);
            EXPECT_NEAR(own, bias->second.energy, bias->second.tolerance) << s.name << ": " << bias->second.why;
            EXPECT_NEAR(vsOwn, 1.0, kEnergyTolerance) << technique << " on " << s.name << " against its cones' quadrature";
        } else if (bias != knownBiases().end()) {
            EXPECT_NEAR(energy, bias->second.energy, bias->second.tolerance) << technique << " on " << s.name << ": " << bias->second.why;
        } else {
            EXPECT_NEAR(energy, 1.0, kEnergyTolerance) << technique << " on " << s.name;
        }
        // A technique that is not the no-GI image itself must be closer to the reference than it.
        const bool addsLight = bias != knownBiases().end() && bias->second.addsLight;
        if (!addsLight) {
            EXPECT_LT(m->relMse, m0->relMse) << technique << " on " << s.name;
        }
    }
    EXPECT_GT(accepted, 0u) << technique << " accepts no built-in scene";
}

// Every registered technique but the baselines (`direct` is the no-GI image; `ambient`'s constant is
// an arbitrary setting).
namespace {
std::vector<std::string> nonBaselineTechniques() {
    std::vector<std::string> names;
    for (const TechniqueInfo& registered : registeredTechniques())
        if (registered.name != "direct" && registered.name != "ambient") names.push_back(registered.name);
    return names;
}
}  // namespace

INSTANTIATE_TEST_SUITE_P(Techniques, FidelityGpuTest, ::testing::ValuesIn(nonBaselineTechniques()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                             std::string n = p.param;
                             for (char& c : n)
                                 if (c == '-') c = '_';
                             return n;
                         });
