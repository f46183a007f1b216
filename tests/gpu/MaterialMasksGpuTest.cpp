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
#include <algorithm>
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
// MaskedNormalMappedGpuTest, measured at 96^2 on the constant pixels (llvmpipe, 256 spp): energy
// 0.9994, relMSE 1.4e-7 (the G-buffer's half floats: 3e-4 RMS; 8.9e-8 before the bilinear compare's
// exact slack); the reference's own noise there is 0 (a sun, Lambert, one exact shadow ray per sample:
// every sample of a constant pixel is equal). The bounds are 70x the measurement and far below any
// material error (the slack without its margin: 5e-5, acne): the normal map ignored gives
// relMSE ~5e-3 (0.80 against 0.94 of the light on half the floor), its tangent or bitangent flipped
// ~0.1, an ignored mask in the shadow map blackens the card's whole shadow.
constexpr double kAgreementEnergyTolerance = 0.005;
constexpr double kAgreementRelMse = 1e-5;
constexpr float kFlatNeighbours = 0.02f;

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
            // The shooting radiosity methods' time budget off: the three cards' images must shoot the same
            // iterations whatever the host's speed (maxIterations alone bounds a frame).
            auto runSettings = settings;
            if (framesOf(technique) > 1) runSettings["frameBudgetMs"] = "0";
            // Radiosity's automatic element size follows the scene's area, the card's included: pinned,
            // the three scenes share their walls' elements (measured: at auto, the card's area moved the
            // walls' elements and PR's 8-frame image by 0.5 %).
            if (technique.rfind("radiosity-", 0) == 0) {
                runSettings["elementSize"] = "0.1";
                runSettings["dynamicElementSize"] = "0.1";
            }
            auto p = makePipeline(scene, technique, runSettings, kSize);
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

namespace {

// The floor's normal map: 64^2 texels, the left half (u < 1/2) tilted 30 degrees toward the tangent
// (+u), the right half 30 degrees toward the bitangent (up the image, -v); encoded (n + 1) / 2.
Image tiltedNormalMap() {
    constexpr int kSide = 64;
    const float s = 0.5f, c = std::sqrt(3.0f) / 2.0f;  // sin, cos 30 degrees
    Image img(kSide, kSide);
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) {
            const glm::vec3 n = x < kSide / 2 ? glm::vec3(s, 0.0f, c) : glm::vec3(0.0f, s, c);
            img.at(x, y) = 0.5f * (n + 1.0f);
        }
    return img;
}

// A 2 m floor (normal-mapped) under a sun, a 1.2 m alpha-masked card 0.5 m above it whose 4 x 4
// checker of holes casts a checkered shadow; the camera looks down at both. Lambert only.
Scene maskedNormalMappedScene() {
    Scene s;
    s.name = "masked-normal-mapped";
    s.source = "test:masked-normal-mapped";
    MeshBuilder floor("floor"), card("card");
    floor.quad({-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {0, 1, 0}, 2, 2);
    card.quad({-0.6f, 0.5f, -0.6f}, {0.6f, 0.5f, -0.6f}, {0.6f, 0.5f, 0.6f}, {-0.6f, 0.5f, 0.6f}, {0, 1, 0});
    s.meshes.push_back(floor.take());
    s.meshes.push_back(card.take());
    s.textures.push_back({"tilted-normals", tiltedNormalMap()});
    Image checker(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) checker.at(x, y) = glm::vec3(((x / 2 + y / 2) % 2) ? 1.0f : 0.0f);
    s.textures.push_back({"checker-coverage", checker});
    Material floorMaterial;
    floorMaterial.name = "floor";
    floorMaterial.baseColor = glm::vec3(0.6f);
    floorMaterial.normalTexture = 0;
    Material cardMaterial;
    cardMaterial.name = "card";
    cardMaterial.baseColor = glm::vec3(0.5f);
    cardMaterial.twoSided = true;
    cardMaterial.alphaTexture = 1;
    cardMaterial.alphaCutoff = 0.5f;
    s.materials = {floorMaterial, cardMaterial};
    s.objects.resize(2);
    s.objects[0].name = "floor";
    s.objects[0].mesh = 0;
    s.objects[0].material = 0;
    s.objects[1].name = "card";
    s.objects[1].mesh = 1;
    s.objects[1].material = 1;
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.5f, -0.8f, 0.3f));
    sun.irradiance = glm::vec3(3.0f);
    s.lights.push_back(sun);
    s.camera.position = glm::vec3(0.0f, 2.2f, 2.2f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    s.camera.verticalFov = glm::radians(50.0f);
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

class MaskedNormalMappedGpuTest : public gputest::GpuTest {};

Image referenceDirect(const Scene& scene, int size, uint32_t spp, uint64_t seed) {
    PathTracerSettings pts;
    pts.width = pts.height = size;
    pts.samplesPerPixel = spp;
    pts.bounces = 0;
    pts.seed = seed;
    auto tracer = PathTracer::create(scene, pts);
    EXPECT_TRUE(tracer.ok()) << tracer.error().message;
    return tracer->render().radiance;
}

}  // namespace

TEST_F(MaskedNormalMappedGpuTest, DirectMatchesTheReferenceWithinItsNoise) {
    constexpr int kSize = 96;
    constexpr uint32_t kSpp = 256;
    const Scene scene = maskedNormalMappedScene();
    auto technique = createTechnique("direct");
    ASSERT_TRUE(technique.ok());
    render::RenderSettings rs;
    rs.shadowMapSize = 2048;  // shadow edges within a fraction of a pixel, as ReferenceAgreementGpuTest
    rs.pcfRadius = 0;         // hard shadows: a directional light's shadow rays are exact
    auto pipeline = Pipeline::create(scene, std::move(*technique), {kSize, kSize}, rs);
    ASSERT_TRUE(pipeline.ok()) << pipeline.error().message;
    (*pipeline)->renderFrame(0);
    const Image gpu = (*pipeline)->readback(Component::Direct);
    const Image ref = referenceDirect(scene, kSize, kSpp, 1);
    const Image ref2 = referenceDirect(scene, kSize, kSpp, 2);
    // Pixels on a geometric or shadow edge differ legitimately (the GPU shades the pixel centre, the
    // reference integrates the footprint): the comparison keeps interior pixels, where a third
    // reference (independent of both compared images) is locally constant: its four neighbours within
    // 2 % (the scene's direct light is piecewise constant: flat floor halves, card cells, shadow cells;
    // second differences alone, ReferenceAgreementGpuTest's test, pass a pixel halfway up a one-pixel
    // edge ramp). Black pixels (the background, full shadow) count: the masks must agree there too.
    const Image select = referenceDirect(scene, kSize, kSpp, 3);
    auto interior = [&](int x, int y) {
        auto L = [&](int px, int py) { return luminance(select.at(px, py)); };
        const float c = L(x, y), tolerance = kFlatNeighbours * c;
        return std::abs(L(x - 1, y) - c) <= tolerance && std::abs(L(x + 1, y) - c) <= tolerance &&
               std::abs(L(x, y - 1) - c) <= tolerance && std::abs(L(x, y + 1) - c) <= tolerance;
    };
    double errGpu = 0.0, errRef = 0.0, sumGpu = 0.0, sumRef = 0.0;
    int pixels = 0;
    for (int y = 1; y < kSize - 1; ++y)
        for (int x = 1; x < kSize - 1; ++x) {
            if (!interior(x, y)) continue;
            ++pixels;
            for (int c = 0; c < 3; ++c) {
                const double r = ref.at(x, y)[c], g = gpu.at(x, y)[c], r2 = ref2.at(x, y)[c];
                errGpu += (g - r) * (g - r) / (r * r + kRelMseEpsilon);
                errRef += (r2 - r) * (r2 - r) / (r * r + kRelMseEpsilon);
                sumGpu += g;
                sumRef += r;
            }
        }
    ASSERT_GT(pixels, kSize * kSize / 2);
    const double relMse = errGpu / (3.0 * pixels), noise = errRef / (3.0 * pixels);  // noise: twice one reference's
    const double energy = sumGpu / sumRef;
    auto whole = compareImages(gpu, ref);
    ASSERT_TRUE(whole.ok());
    std::printf("masked normal-mapped: %d interior pixels, energy %.4f relMSE %.2e, reference vs reference %.2e "
                "(whole image: energy %.4f relMSE %.4f)\n",
                pixels, energy, relMse, noise, whole->energy, whole->relMse);
    RecordProperty("energy", std::to_string(energy));
    RecordProperty("relMse", std::to_string(relMse));
    RecordProperty("referenceNoiseRelMse", std::to_string(noise));
    EXPECT_NEAR(energy, 1.0, kAgreementEnergyTolerance);
    EXPECT_LT(relMse, kAgreementRelMse) << "reference noise on these pixels: relMSE " << noise / 2.0;
}
