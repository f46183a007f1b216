// glTF materials in every pass (issue 30): alpha masks and normal maps.
//
// MaskedTexelsAreAbsentInEveryPass: a horizontal card between the light and the floor of a Cornell box
// in three forms: absent, present but masked out everywhere (coverage 0 < cutoff 0.5), present and
// opaque. A technique that honours masks in all its passes (G-buffer, 2D/cube shadow maps, RSMs,
// paraboloid maps, voxelizations, hemicubes, photon tracing and depth maps) renders the masked card
// exactly as the absent one; the opaque card changes the image a lot, so a pass that ignored the mask
// would fail. One instance per technique: each pass family is covered by the techniques using it.
//
// MaskedNormalMappedSceneMatchesTheReference: a floor with a normal map (two tilts, so the tangent and
// the bitangent both matter) under a sun, and a checkered alpha-masked card above it casting a
// checkered shadow: `direct` against the path tracer's direct light (--bounces 0).
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "render/RenderSettings.h"
#include "scene/MeshBuilder.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

enum class Card { Absent, MaskedOut, Opaque };

// Measured at 64^2 on llvmpipe (docs/scene.md "Alpha masks in every pass"): with the mask honoured the
// masked-out card leaves every technique's image the same to float rounding (mean ratio 1.0000, relMSE
// <= 3e-14: the same fragments survive every pass); the opaque card moves the mean by 17 % (area-light)
// to 100 % (direct). 1e-3 is far above rounding and far below what one ignoring pass does (the card
// then shadows or reflects: >= 17 %); 0.1 keeps the opaque card's effect, which makes the test able to
// fail, well clear of noise.
constexpr double kMaskedTolerance = 1e-3;
constexpr double kOpaqueChangeAtLeast = 0.1;

// The card: a two-sided horizontal quad 0.14 m under the Cornell box's ceiling, over most of the box.
constexpr float kCardHeight = 0.40f;  // metres
constexpr float kCardMin = 0.06f, kCardMax = 0.50f;

Scene withCard(const std::string& name, Card card) {
    auto loaded = loadScene(name);
    EXPECT_TRUE(loaded.ok());
    Scene s = std::move(*loaded);
    if (card == Card::Absent) return s;
    MeshBuilder b("card");
    b.quad({kCardMin, kCardHeight, kCardMin}, {kCardMax, kCardHeight, kCardMin}, {kCardMax, kCardHeight, kCardMax},
           {kCardMin, kCardHeight, kCardMax}, {0, -1, 0}, 4, 4);
    Material m;
    m.name = "card";
    m.baseColor = glm::vec3(0.7f);
    m.twoSided = true;
    m.alphaTexture = static_cast<int>(s.textures.size());
    s.textures.push_back({"zero-coverage", Image(4, 4, glm::vec3(0.0f))});
    m.alphaCutoff = card == Card::MaskedOut ? 0.5f : 0.0f;  // 0: opaque, the texture unused
    Object o;
    o.name = "card";
    o.mesh = static_cast<uint32_t>(s.meshes.size());
    o.material = static_cast<uint32_t>(s.materials.size());
    s.meshes.push_back(b.take());
    s.materials.push_back(m);
    s.objects.push_back(o);
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

double meanOf(const Image& img) {
    double sum = 0.0;
    for (const glm::vec3& p : img.pixels()) sum += (p.r + p.g + p.b) / 3.0;
    return sum / static_cast<double>(img.pixelCount());
}

// Progressive radiosity shoots over frames: two, so that shooting (not only the first frame's set-up)
// runs through the hemicubes. Convergence is not needed: the three images are compared with each other.
int framesOf(const std::string& technique) {
    return technique == "radiosity-pr" || technique == "radiosity-incremental" || technique == "radiosity-cross" ? 2 : 1;
}

class MaterialMasksGpuTest : public gputest::GpuTest, public ::testing::WithParamInterface<std::string> {};

}  // namespace

TEST_P(MaterialMasksGpuTest, MaskedTexelsAreAbsentInEveryPass) {
    const std::string technique = GetParam();
    const TechniqueInfo* info = nullptr;
    for (const TechniqueInfo& t : registeredTechniques())
        if (t.name == technique) info = &t;
    ASSERT_NE(info, nullptr);
    // The spot-lit box where the technique takes it, else the area-lit one (radiosity, area-light);
    // `direct` on both: the spot's 2D shadow map and the area light's cube distance map.
    std::vector<std::string> sceneNames;
    for (const char* name : {"cornell-box", "cornell-box-area"})
        if (setupRefusal(withCard(name, Card::Absent), technique).empty() && (sceneNames.empty() || technique == "direct"))
            sceneNames.push_back(name);
    ASSERT_FALSE(sceneNames.empty()) << technique << " accepts neither Cornell box";
    const Component component = technique == "direct" ? Component::Full : info->scope.component;
    constexpr int kSize = 64;
    // vct's default hybrid voxelizes the card's large triangles fragment-parallel; its triangle-parallel
    // voxelizer (the small triangles' path) masks in the geometry shader: both are run.
    std::vector<std::pair<std::string, std::map<std::string, std::string>>> runs;
    for (const std::string& name : sceneNames) runs.push_back({name, {}});
    if (technique == "vct") runs.push_back({sceneNames.front(), {{"voxelizer", "triangle"}}});
    for (const auto& [sceneName, settings] : runs) {
        Image images[3];
        for (int k = 0; k < 3; ++k) {
            const Scene scene = withCard(sceneName, static_cast<Card>(k));
            auto p = makePipeline(scene, technique, settings, kSize);
            for (int f = 0; f < framesOf(technique); ++f) p->renderFrame(static_cast<uint32_t>(f));
            images[k] = p->readback(component);
        }
        const double absent = meanOf(images[0]), masked = meanOf(images[1]), opaque = meanOf(images[2]);
        ASSERT_GT(absent, 0.0) << technique;
        auto same = compareImages(images[1], images[0]);
        ASSERT_TRUE(same.ok());
        const double maskedChange = std::abs(masked / absent - 1.0), opaqueChange = std::abs(opaque / absent - 1.0);
        const std::string label = sceneName + (settings.empty() ? "" : "_" + settings.begin()->second);
        std::printf("masks %-22s %-17s masked/absent %.4f relMSE %.2e  opaque/absent %.3f\n", technique.c_str(),
                    label.c_str(), masked / absent, same->relMse, opaque / absent);
        RecordProperty(label + "_maskedOverAbsent", std::to_string(masked / absent));
        RecordProperty(label + "_maskedRelMse", std::to_string(same->relMse));
        RecordProperty(label + "_opaqueOverAbsent", std::to_string(opaque / absent));
        EXPECT_LT(maskedChange, kMaskedTolerance) << technique << " on " << label << ": the masked-out card changed the light";
        EXPECT_GT(opaqueChange, kOpaqueChangeAtLeast)
            << technique << " on " << label << ": the opaque card must matter for the test to mean anything";
    }
}

INSTANTIATE_TEST_SUITE_P(Techniques, MaterialMasksGpuTest, ::testing::ValuesIn([] {
                             std::vector<std::string> names;
                             // ambient draws no geometry of its own; radiosity-gather (two minutes here)
                             // uses the same RadiositySystem hemicubes as the three progressive methods.
                             for (const TechniqueInfo& registered : registeredTechniques())
                                 if (registered.name != "ambient" && registered.name != "radiosity-gather")
                                     names.push_back(registered.name);
                             return names;
                         }()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                             std::string n = p.param;
                             for (char& c : n)
                                 if (c == '-') c = '_';
                             return n;
                         });
