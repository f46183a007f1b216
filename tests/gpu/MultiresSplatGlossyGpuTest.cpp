// `multires-splat` mode A's glossy splats (Nichols 2010 §3.2.3.1): with every subsplat at full
// resolution mode A equals the glossy `rsm` gather of the same VPLs (its limit); at default settings it
// is closer to that limit than mode B or than mode A shaded Lambertian; the glossy term is non-zero and
// changes with the eye position while the Lambertian part does not; the relative SamplesDiffer
// threshold gives the same subsplats when the light is 100x brighter.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"

using namespace bounce;
using namespace bounce::nicholstest;

namespace {
class MultiresSplatGlossyGpuTest : public gputest::GpuTest {};

constexpr int kSize = 64;  // 64^2: coarse enough that mode A's extra refinement shows (64 VPLs)
constexpr float kSpecularF0 = 0.5f;   // a strong dielectric-like lobe, visible next to the Lambert part
constexpr float kRoughness = 0.2f;    // GGX alpha 0.04: a narrow lobe (about Phong n 1250)

// The Cornell box with every material given a glossy GGX lobe on top of its Lambert albedo.
Scene glossyCornellBox() {
    auto scene = loadScene("cornell-box");
    EXPECT_TRUE(scene.ok());
    Scene s = std::move(*scene);
    for (Material& m : s.materials) {
        m.specularF0 = kSpecularF0;
        m.roughness = kRoughness;
    }
    return s;
}

// The same scene seen orthographically along a fixed axis from `distance` metres: the pixel-to-surface
// mapping does not depend on the distance, only the eye position (the glossy lobe's view vector) does.
Scene orthographicView(Scene s, float distance) {
    const glm::vec3 centre(0.278f, 0.25f, 0.28f);  // metres, middle of the box (CornellBoxScene.cpp data)
    const glm::vec3 axis = glm::normalize(glm::vec3(0.0f, -0.4f, 1.0f));  // looking in and down at the floor
    s.camera.projection = Projection::Orthographic;
    s.camera.orthoHeight = 0.6f;  // metres: the back wall, floor and blocks fill the view
    s.camera.position = centre - distance * axis;
    s.camera.target = centre;
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.nearPlane = 0.01f;
    s.camera.farPlane = 10.0f;
    return s;
}

// formFactor=point (Eq. 3.2, both techniques): the glossy limit below and the measurements in
// docs/techniques/multires-splat.md were taken with it (multires-splat's default is now Eq. 4.1's disk).
const std::map<std::string, std::string> kVpls = {{"rsmSize", "32"}, {"vplGrid", "8"}, {"formFactor", "point"}};

std::map<std::string, std::string> with(std::map<std::string, std::string> s,
                                        const std::map<std::string, std::string>& extra) {
    for (const auto& [k, v] : extra) s[k] = v;
    return s;
}

// The limit of mode A: every VPL gathered at every pixel with the full BRDF and Eq. 3.2's point form factor.
Image glossyLimit(const Scene& scene) {
    return renderIndirect(scene, "rsm", with(kVpls, {{"glossy", "true"}}), kSize);
}
}  // namespace

TEST_F(MultiresSplatGlossyGpuTest, FullResolutionModeAEqualsTheGlossyRsmGather) {
    const Scene scene = glossyCornellBox();
    const Image limit = glossyLimit(scene);
    // eyeCoarsest = image size: one level, every covered pixel its own subsplat for every VPL.
    const Image modeA = renderIndirect(
        scene, "multires-splat", with(kVpls, {{"refinement", "per-vpl"}, {"eyeCoarsest", std::to_string(kSize)}}), kSize);
    const double error = relativeRmsError(modeA, limit);
    RecordProperty("relRms", std::to_string(error));
    // The same 64 terms of the same formulas at the same points (the pyramid's level 0 is the G-buffer):
    // only the summation order differs (additive blending vs the shader loop), a few float ulps per
    // term; 1e-5 would still catch a missing or doubled lobe, a wrong view vector or material.
    EXPECT_LT(error, 1e-5);
    // Non-trivial: the glossy lobe is a visible part of the limit (the Lambertian gather differs).
    const Image lambert = renderIndirect(scene, "rsm", kVpls, kSize);
    EXPECT_GT(relativeRmsError(lambert, limit), 0.05);
}

TEST_F(MultiresSplatGlossyGpuTest, DefaultModeAIsCloserToTheGlossyLimitThanModeB) {
    const Scene scene = glossyCornellBox();
    const Image limit = glossyLimit(scene);
    auto render = [&](const std::map<std::string, std::string>& extra) {
        auto p = makePipeline(scene, "multires-splat", with(kVpls, extra), kSize);
        const FrameStats stats = p->renderFrame(0);
        return std::make_pair(p->readback(Component::Indirect), stats.counters.at("splats"));
    };
    const auto [modeA, splatsA] = render({{"refinement", "per-vpl"}});
    const auto [modeB, splatsB] = render({{"refinement", "shared"}});
    const auto [lambertA, splatsLambertA] = render({{"refinement", "per-vpl"}, {"glossyShading", "false"}});
    // Glossy shading without the illumination criterion: mode B's lists for every VPL.
    const auto [unrefinedA, splatsUnrefinedA] = render({{"refinement", "per-vpl"}, {"illuminationContrast", "1e9"}});
    const double errorA = relativeRmsError(modeA, limit), errorB = relativeRmsError(modeB, limit),
                 errorLambertA = relativeRmsError(lambertA, limit), errorUnrefinedA = relativeRmsError(unrefinedA, limit);
    RecordProperty("modeARelRms", std::to_string(errorA));
    RecordProperty("modeBRelRms", std::to_string(errorB));
    RecordProperty("lambertModeARelRms", std::to_string(errorLambertA));
    RecordProperty("unrefinedModeARelRms", std::to_string(errorUnrefinedA));
    RecordProperty("modeASplats", std::to_string(splatsA));
    RecordProperty("modeBSplats", std::to_string(splatsB));
    RecordProperty("unrefinedModeASplats", std::to_string(splatsUnrefinedA));
    EXPECT_LT(errorA, errorB);
    EXPECT_LT(errorA, errorLambertA);
    // The glossy criterion refines (more pairs than mode B's lists) and the refinement pays off
    // against the same splats without it.
    EXPECT_EQ(splatsUnrefinedA, splatsB);
    EXPECT_EQ(splatsLambertA, splatsA);  // shading does not change the lists
    EXPECT_GT(splatsA, splatsB);
    EXPECT_LT(errorA, errorUnrefinedA);
    EXPECT_TRUE(finiteAndNonNegative(modeA));
}

TEST_F(MultiresSplatGlossyGpuTest, GlossyTermIsNonZeroAndViewDependent) {
    const Scene glossy = glossyCornellBox();
    const Scene nearView = orthographicView(glossy, 1.2f), farView = orthographicView(glossy, 2.4f);
    // Full resolution: the same pixels are the same subsplats from either distance (the relative depth
    // criterion and the glossy criterion would otherwise refine differently).
    const auto modeA = with(kVpls, {{"refinement", "per-vpl"}, {"eyeCoarsest", std::to_string(kSize)}});
    const auto lambertA = with(modeA, {{"glossyShading", "false"}});
    const Image glossyNear = renderIndirect(nearView, "multires-splat", modeA, kSize);
    const Image glossyFar = renderIndirect(farView, "multires-splat", modeA, kSize);
    const Image lambertNear = renderIndirect(nearView, "multires-splat", lambertA, kSize);
    const Image lambertFar = renderIndirect(farView, "multires-splat", lambertA, kSize);
    // The Lambert part sees the same points from either distance: equal up to float rounding of the
    // G-buffer positions (1e-4 relative RMS).
    EXPECT_LT(relativeRmsError(lambertFar, lambertNear), 1e-4);
    // The glossy term adds light (never removes it) and is a visible share of the image.
    double glossyNearSum = 0.0, glossyFarSum = 0.0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int c = 0; c < 3; ++c) {
                // 1e-5 relative: the glossy and Lambert lists are identical, sums differ by rounding.
                ASSERT_GE(glossyNear.at(x, y)[c], lambertNear.at(x, y)[c] * (1.0f - 1e-5f));
                glossyNearSum += glossyNear.at(x, y)[c] - lambertNear.at(x, y)[c];
                glossyFarSum += glossyFar.at(x, y)[c] - lambertFar.at(x, y)[c];
            }
    RecordProperty("glossyShareNear", std::to_string(glossyNearSum / totalRadiance(lambertNear)));
    RecordProperty("glossyShareFar", std::to_string(glossyFarSum / totalRadiance(lambertFar)));
    EXPECT_GT(glossyNearSum, 0.01 * totalRadiance(lambertNear));
    // Moving the eye moves the highlights: the glossy images differ well beyond the Lambertian ones.
    const double change = relativeRmsError(glossyFar, glossyNear);
    RecordProperty("glossyViewChange", std::to_string(change));
    EXPECT_GT(change, 0.01);
}

TEST_F(MultiresSplatGlossyGpuTest, RelativeThresholdDoesNotDependOnTheLightIntensity) {
    const Scene scene = glossyCornellBox();
    Scene bright = scene;
    bright.lights.front().intensity *= 100.0f;
    const auto settings = with(kVpls, {{"refinement", "per-vpl"}});
    auto dim = makePipeline(scene, "multires-splat", settings, kSize);
    auto strong = makePipeline(bright, "multires-splat", settings, kSize);
    const FrameStats a = dim->renderFrame(0), b = strong->renderFrame(0);
    RecordProperty("subsplats", std::to_string(a.counters.at("subsplats")));
    EXPECT_EQ(a.counters.at("subsplats"), b.counters.at("subsplats"));
    EXPECT_EQ(a.counters.at("splats"), b.counters.at("splats"));
    // The criterion does refine here (more pairs than mode B's lists), so the equality is not vacuous.
    auto shared = makePipeline(scene, "multires-splat", with(kVpls, {{"refinement", "shared"}}), kSize);
    EXPECT_GT(a.counters.at("splats"), shared->renderFrame(0).counters.at("splats"));
    // The image scales with the light (1e-5: float rounding of the 100x larger sums).
    Image scaled = strong->readback(Component::Indirect);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) scaled.at(x, y) /= 100.0f;
    EXPECT_LT(relativeRmsError(scaled, dim->readback(Component::Indirect)), 1e-5);
}
