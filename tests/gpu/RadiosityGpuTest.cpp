// Hemicube radiosity (van de Hoef 2013) on the GPU: the furnace's E / (1 - rho), form-factor
// reciprocity through the shooting pass, agreement with the path tracer and with the gather method,
// the cross redistribution's 4 |M| hemicubes independent of |C|, no work in a converged still scene,
// and refusal of scenes the methods cannot shade (point, spot and directional lights:
// RadiosityLightsGpuTest.cpp).
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "scene/SceneLoader.h"
#include "techniques/Registry.h"
#include "techniques/radiosity/RadiosityTechnique.h"
#include "techniques/radiosity_cross/CrossRadiosityTechnique.h"
#include "scene/MeshBuilder.h"

#include <glm/gtc/constants.hpp>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class RadiosityGpuTest : public gputest::GpuTest {};

const char* const kMethods[] = {"radiosity-gather", "radiosity-pr", "radiosity-incremental", "radiosity-cross"};

RadiosityTechnique& radiosityOf(Pipeline& p) { return dynamic_cast<RadiosityTechnique&>(p.technique()); }

// `settings` with the shooting methods' time budget per frame off (frameBudgetMs=0): these tests
// compare solutions each frame completes (maxIterations alone bounds it), whatever the host's speed.
// The gather has no budget (and refuses the setting).
std::map<std::string, std::string> unbudgeted(const std::string& method, std::map<std::string, std::string> settings) {
    if (method != "radiosity-gather") settings["frameBudgetMs"] = "0";
    return settings;
}

Scene builtin(const std::string& name, const SceneParams& params = {}) {
    auto s = loadScene(name, params);
    EXPECT_TRUE(s.ok()) << name << ": " << (s.ok() ? "" : s.error().message);
    return std::move(*s);
}

// Area-weighted mean of per-element values over the elements of non-emitting quads.
glm::dvec3 meanOverReceivers(const radiosity::PatchModel& pm, const std::vector<glm::vec3>& values) {
    glm::dvec3 sum(0.0);
    double area = 0.0;
    for (size_t k = 0; k < values.size(); ++k) {
        const radiosity::Element& e = pm.elements()[k];
        if (pm.quads()[e.quad].flags & RAD_QUAD_LIGHT) continue;
        sum += glm::dvec3(values[k]) * double(e.area);
        area += e.area;
    }
    return sum / area;
}

// Full radiance of the path tracer (every bounce, Lambert only, like radiosity).
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

// The images restricted to pixels that show no emitter (the light's own pixels carry its radiance
// exactly in both and would swamp every error measure).
std::pair<Image, Image> receiversOnly(const Image& test, const Image& direct, const Image& ref) {
    Image a = test, b = ref;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            if (luminance(direct.at(x, y)) > 0.0f || luminance(ref.at(x, y)) > 2.0f) a.at(x, y) = b.at(x, y) = glm::vec3(0.0f);
    return {a, b};
}

}  // namespace

TEST_F(RadiosityGpuTest, FurnaceConvergesToEmissionOverOneMinusAlbedo) {
    // Closed furnace, E = 1 W/(m^2 sr), rho = 0.5: B = E / (1 - rho) = 2 everywhere. The gather
    // sweeps converge geometrically; the shooting methods leave unshot radiosity Bu below their
    // threshold, which would still add rho / (1 - rho) Bu each: B + rho/(1-rho) Bu is the fixed point.
    const Scene scene = builtin("furnace", {{"albedo", "0.5"}});
    const double expected = 2.0;
    for (const char* method : kMethods) {
        SCOPED_TRACE(method);
        std::map<std::string, std::string> settings = {{"elementSize", "0.25"}, {"hemicubeSize", "32"}};
        if (std::string(method) == "radiosity-gather") settings["bounces"] = "12";
        else settings["threshold"] = "0.01";
        auto p = makePipeline(scene, method, unbudgeted(method, settings), 32);
        p->renderFrame(0);
        auto& t = radiosityOf(*p);
        const auto& pm = t.system().patches();
        const glm::dvec3 b = meanOverReceivers(pm, t.system().readTotal());
        const glm::dvec3 bu = meanOverReceivers(pm, t.system().readUnshot());
        const double fixedPoint = b.g + 0.5 / 0.5 * bu.g;
        RecordProperty(std::string(method) + "_B", std::to_string(b.g));
        RecordProperty(std::string(method) + "_fixedPoint", std::to_string(fixedPoint));
        if (std::string(method) == "radiosity-gather") {
            // 12 Gauss-Seidel sweeps leave at most 0.5^12 = 2e-4 of the solution; the 32^2 delta form
            // factors sum to 1.0005 (measured). 0.5 % covers both.
            EXPECT_NEAR(b.g, expected, 0.005 * expected);
        } else {
            // The disk approximation with 8 x 8 sub-disks still loses about 0.4 % of a shot near the
            // shooter (measured 1.991 with threshold 0.002); 1.5 % leaves room for the 0.01 threshold's
            // uneven remainder. B itself is short by at most threshold / (1 - rho) x E of unshot light.
            EXPECT_NEAR(fixedPoint, expected, 0.015 * expected);
            EXPECT_NEAR(b.g, expected, 0.035 * expected);
        }
        // The display shows the solution: every pixel sees a furnace wall (bilinear between elements of
        // nearly equal B, 1 % for the texels nearest the corners).
        const Image full = p->readback(Component::Full);
        double mean = totalRadiance(full) / (3.0 * full.width() * full.height());
        EXPECT_NEAR(mean, b.g, 0.01 * expected) << "display of the solution";
    }
}

namespace {

// Two parallel, coaxial squares `gap` apart: `small` (side a) at y = 0 facing up, `large` (side b)
// at y = gap facing down; `emitting` chooses which one emits E = 1 (albedo 0), the other has albedo 1.
Scene facingSquares(float a, float b, float gap, bool smallEmits) {
    Scene s;
    s.name = "facing-squares";
    Material emitter, receiver;
    emitter.name = "emitter";
    emitter.baseColor = glm::vec3(0.0f);
    emitter.emission = glm::vec3(1.0f);
    receiver.name = "receiver";
    receiver.baseColor = glm::vec3(1.0f);
    s.materials = {emitter, receiver};
    const auto square = [&](const char* name, float side, float y, glm::vec3 front, uint32_t mat) {
        MeshBuilder mb(name);
        const float h = 0.5f * side;
        mb.quad({-h, y, -h}, {h, y, -h}, {h, y, h}, {-h, y, h}, front);
        Object o;
        o.name = name;
        o.mesh = static_cast<uint32_t>(s.meshes.size());
        o.material = mat;
        s.meshes.push_back(mb.take());
        s.objects.push_back(o);
    };
    square("small", a, 0.0f, {0, 1, 0}, smallEmits ? 0u : 1u);
    square("large", b, gap, {0, -1, 0}, smallEmits ? 1u : 0u);
    s.camera.position = {0.0f, 0.5f * gap, 2.0f};
    s.camera.target = {0.0f, 0.5f * gap, 0.0f};
    return s;
}

// F from square (side a) to the parallel coaxial square (side b) at `gap`, by midpoint quadrature
// of Eq. 2.2.1 (n x n points on each).
double squareToSquareFormFactor(double a, double b, double gap, int n) {
    const double pi = glm::pi<double>();
    double sum = 0.0;
    for (int i = 0; i < n * n; ++i) {
        const double x0 = (-0.5 + (i % n + 0.5) / n) * a, z0 = (-0.5 + (i / n + 0.5) / n) * a;
        for (int j = 0; j < n * n; ++j) {
            const double x1 = (-0.5 + (j % n + 0.5) / n) * b, z1 = (-0.5 + (j / n + 0.5) / n) * b;
            const double r2 = (x1 - x0) * (x1 - x0) + (z1 - z0) * (z1 - z0) + gap * gap;
            sum += gap * gap / (pi * r2 * r2);  // cos cos / (pi r^2), both cosines gap / r
        }
    }
    return sum * (b * b) / (double(n) * n * n * n);  // (1/A_a) int int dA_b dA_a
}

// Area-weighted mean B over the quads of object `object`.
double meanOfObject(RadiosityTechnique& t, uint32_t object) {
    const auto& pm = t.system().patches();
    const auto b = t.system().readTotal();
    double sum = 0.0, area = 0.0;
    for (size_t k = 0; k < b.size(); ++k) {
        const radiosity::Element& e = pm.elements()[k];
        if (pm.quads()[e.quad].body != object) continue;
        sum += double(b[k].g) * e.area;
        area += e.area;
    }
    return sum / area;
}

}  // namespace

TEST_F(RadiosityGpuTest, ShotAndGatheredFormFactorsAreReciprocalAndExact) {
    // One shot from the emitting square gives the other rho F E (rho = 1, E = 1) as its mean B; the
    // swapped scene gives the reverse form factor. A_a F_ab = A_b F_ba (reciprocity), and both match
    // the quadrature of Eq. 2.2.1. The gather method's single sweep measures the same F with the
    // hemicube instead of the disk approximation.
    constexpr float kSmall = 0.2f, kLarge = 0.6f, kGap = 0.3f;  // metres
    const double fSmallToLarge = squareToSquareFormFactor(kSmall, kLarge, kGap, 24);
    const double fLargeToSmall = fSmallToLarge * (kSmall * kSmall) / (kLarge * kLarge);
    for (const char* method : {"radiosity-pr", "radiosity-gather"}) {
        SCOPED_TRACE(method);
        std::map<std::string, std::string> settings = {{"elementSize", "0.02"}};
        if (std::string(method) == "radiosity-pr") settings["maxIterations"] = "1";
        else settings["bounces"] = "1";
        const Scene smallEmits = facingSquares(kSmall, kLarge, kGap, true);  // the pipeline keeps a reference
        const Scene largeEmits = facingSquares(kSmall, kLarge, kGap, false);
        auto p1 = makePipeline(smallEmits, method, settings, 16);
        p1->renderFrame(0);
        const double largeFromSmall = meanOfObject(radiosityOf(*p1), 1);  // = F(large -> small)
        auto p2 = makePipeline(largeEmits, method, settings, 16);
        p2->renderFrame(0);
        const double smallFromLarge = meanOfObject(radiosityOf(*p2), 0);  // = F(small -> large)
        RecordProperty(std::string(method) + "_F_small_large", std::to_string(smallFromLarge));
        RecordProperty(std::string(method) + "_F_large_small", std::to_string(largeFromSmall));
        RecordProperty("quadrature_F_small_large", std::to_string(fSmallToLarge));
        // 2 %: the disk approximation with sub-disks and the 64^2 hemicube's pixel quantisation of a
        // square seen at up to 60 degrees; the quadrature itself is good to 1e-4.
        EXPECT_NEAR(smallFromLarge, fSmallToLarge, 0.02 * fSmallToLarge);
        EXPECT_NEAR(largeFromSmall, fLargeToSmall, 0.02 * fLargeToSmall);
        EXPECT_NEAR(kSmall * kSmall * smallFromLarge, kLarge * kLarge * largeFromSmall, 0.03 * kSmall * kSmall * smallFromLarge);
    }
}

TEST_F(RadiosityGpuTest, AgreesWithThePathTracerAndWithGather) {
    // The rotating-box Cornell box at frame 12 (the box turned 18 degrees), after frames 0 and 6 so the
    // incremental methods have redistributed twice. Reference: the path tracer with every bounce,
    // Lambert only. Pixels that show the light are left out (they are exact in both).
    const Scene scene = builtin("cornell-box-rotating");
    constexpr int kSize = 64;
    const Image ref = pathTraced(scene, kSize, 12, 256);
    std::map<std::string, Image> images;
    for (const char* method : kMethods) {
        SCOPED_TRACE(method);
        auto p = makePipeline(scene, method, unbudgeted(method, {{"elementSize", "0.05"}}), kSize);
        if (std::string(method) != "radiosity-gather")
            for (uint32_t f : {0u, 6u}) p->renderFrame(f);
        p->renderFrame(12);
        const Image full = p->readback(Component::Full), direct = p->readback(Component::Direct);
        auto [a, b] = receiversOnly(full, direct, ref);
        images[method] = a;
        auto m = compareImages(a, b);
        ASSERT_TRUE(m.ok());
        const double ratio = totalRadiance(a) / totalRadiance(b);
        RecordProperty(std::string(method) + "_relMse", std::to_string(m->relMse));
        RecordProperty(std::string(method) + "_ratio", std::to_string(ratio));
        // Measured: gather 0.020 / 0.969, pr 0.021 / 0.964, incremental 0.021 / 0.964, cross 0.027 /
        // 0.942 (0.039 / 0.982 without the progressive propagation after each redistribution, which this
        // bound now rejects). The path tracer's 256 spp noise alone is relMSE ~0.01; the radiosity methods
        // lose a few per cent to the disk approximation and the threshold (the thesis's PR is darker too).
        EXPECT_LT(m->relMse, 0.035);
        EXPECT_GT(ratio, 0.92);
        EXPECT_LT(ratio, 1.02);
    }
    // Theory (sec. 5.2.1): PR and incremental give the same solution in the Cornell scenes.
    auto incVsPr = compareImages(images["radiosity-incremental"], images["radiosity-pr"]);
    auto crossVsGather = compareImages(images["radiosity-cross"], images["radiosity-gather"]);
    RecordProperty("incremental_vs_pr_relMse", std::to_string(incVsPr->relMse));
    RecordProperty("cross_vs_gather_relMse", std::to_string(crossVsGather->relMse));
    EXPECT_LT(incVsPr->relMse, 0.005);  // measured 0.0002: the order of shots and the threshold
    // Measured 0.0082 (0.019 without the propagation after each redistribution: the box gathered the
    // unshadowed floor and its shadow stayed one bounce deep); 0.011 is the measurement + 30 %.
    EXPECT_LT(crossVsGather->relMse, 0.011);
}

TEST_F(RadiosityGpuTest, CrossRendersFourHemicubesPerMovingPatchWhateverTheStaticCount) {
    // The thesis's central claim (sec. 3.3): a cross redistribution renders 4 |M| hemicubes, |M| the
    // moving patches, independent of the static elements. Two static resolutions, 4x apart in count.
    const Scene scene = builtin("cornell-box-rotating");
    std::vector<uint32_t> hemicubes;
    std::vector<size_t> statics;
    for (const char* size : {"0.1", "0.05"}) {
        auto p = makePipeline(scene, "radiosity-cross", {{"elementSize", size}, {"maxIterations", "60"}, {"frameBudgetMs", "0"}}, 32);
        auto& t = dynamic_cast<CrossRadiosityTechnique&>(p->technique());
        p->renderFrame(0);
        for (uint32_t f : {1u, 2u}) {
            p->renderFrame(f);
            EXPECT_GT(t.lastPatches(), 0u);
            // The redistribution's own hemicubes; the regular progressive propagation that follows it
            // shoots static quads only while their unshot radiosity is above the threshold.
            EXPECT_EQ(t.lastRedistributionHemicubes(), 4u * t.lastPatches()) << "frame " << f;
            EXPECT_GE(t.lastHemicubes(), t.lastRedistributionHemicubes());
        }
        hemicubes.push_back(t.lastRedistributionHemicubes());
        statics.push_back(t.system().patches().elements().size() - t.system().movingElementCount());
    }
    RecordProperty("staticElements", std::to_string(statics[0]) + " " + std::to_string(statics[1]));
    RecordProperty("hemicubesPerFrame", std::to_string(hemicubes[0]) + " " + std::to_string(hemicubes[1]));
    EXPECT_GT(double(statics[1]), 3.0 * double(statics[0]));
    EXPECT_EQ(hemicubes[0], hemicubes[1]);
}

TEST_F(RadiosityGpuTest, AConvergedStillSceneRendersNoHemicube) {
    // With nothing moving, incremental and cross redistribution keep their solution: no hemicube,
    // the same image; so does PR, which restarts only when something moved (converged in frame 0 here).
    // Gather restarts every frame (sec. 5.2) and renders them again.
    const Scene scene = builtin("cornell-box-area");
    for (const char* method : kMethods) {
        SCOPED_TRACE(method);
        std::map<std::string, std::string> settings = {{"elementSize", "0.1"}};
        if (std::string(method) == "radiosity-gather") settings["bounces"] = "2";
        auto p = makePipeline(scene, method, unbudgeted(method, settings), 32);
        auto& t = radiosityOf(*p);
        p->renderFrame(0);
        EXPECT_GT(t.lastHemicubes(), 0u);
        const Image first = p->readback(Component::Full);
        p->renderFrame(1);
        p->renderFrame(2);
        const bool keeps = std::string(method) != "radiosity-gather";
        if (keeps) {
            EXPECT_EQ(t.lastHemicubes(), 0u);
            auto m = compareImages(p->readback(Component::Full), first);
            EXPECT_EQ(m->mse, 0.0);
        } else {
            EXPECT_GT(t.lastHemicubes(), 0u);
        }
    }
}

TEST_F(RadiosityGpuTest, RefusesScenesItCannotShade) {
    for (const char* method : kMethods) {
        SCOPED_TRACE(method);
        // A textured (animated) screen: its picture would be lost in a uniform emitter quad.
        const Scene screen = builtin("area-screen");
        auto tScreen = createTechnique(method);
        auto pScreen = Pipeline::create(screen, std::move(*tScreen), {16, 16}, smallRenderSettings());
        ASSERT_FALSE(pScreen.ok());
        EXPECT_NE(pScreen.error().message.find("area light 'screen' is textured"), std::string::npos) << pScreen.error().message;
        EXPECT_NE(pScreen.error().message.find(method), std::string::npos) << pScreen.error().message;

        Scene dark = facingSquares(0.2f, 0.2f, 0.3f, true);
        dark.materials[0].emission = glm::vec3(0.0f);
        auto t2 = createTechnique(method);
        auto p2 = Pipeline::create(dark, std::move(*t2), {16, 16}, smallRenderSettings());
        ASSERT_FALSE(p2.ok());
        EXPECT_NE(p2.error().message.find("no light and no emissive material"), std::string::npos) << p2.error().message;

        auto t3 = createTechnique(method);
        EXPECT_FALSE(applySettings(**t3, {{"hemicubeSize", "0"}}, method).ok());
        // The reconstruction pass's settings: the shooting methods take them, radiosity-gather (which never
        // reconstructs) refuses them as unknown, one line naming the setting.
        for (const char* setting : {"visibilitySamples", "ffSubdivideRatio", "ffSubdivisions"}) {
            auto t4 = createTechnique(method);
            auto applied = applySettings(**t4, {{setting, "1"}}, method);
            if (std::string(method) == "radiosity-gather") {
                ASSERT_FALSE(applied.ok()) << setting;
                EXPECT_NE(applied.error().message.find(std::string("unknown setting '") + setting + "'"), std::string::npos)
                    << applied.error().message;
                EXPECT_EQ(applied.error().message.find('\n'), std::string::npos);
            } else {
                EXPECT_TRUE(applied.ok()) << setting << ": " << (applied.ok() ? "" : applied.error().message);
            }
        }
        if (std::string(method) != "radiosity-gather") {
            auto t5 = createTechnique(method);
            EXPECT_FALSE(applySettings(**t5, {{"visibilitySamples", "9"}}, method).ok());
        }
    }
}

TEST_F(RadiosityGpuTest, DisplayAndIntegrationVariants) {
    // The nearest-filter debug view shows the same solution, texel by texel (Fig. 4.1.1); the mip-chain
    // integration (the DX10 fallback) sums the same hemicubes as the compute reduction.
    const Scene scene = builtin("cornell-box-area");
    auto bilinear = makePipeline(scene, "radiosity-gather", {{"elementSize", "0.1"}, {"bounces", "2"}}, 32);
    auto nearest = makePipeline(scene, "radiosity-gather", {{"elementSize", "0.1"}, {"bounces", "2"}, {"view", "nearest"}}, 32);
    auto mip = makePipeline(scene, "radiosity-gather", {{"elementSize", "0.1"}, {"bounces", "2"}, {"integration", "mipmap"}}, 32);
    for (auto* p : {bilinear.get(), nearest.get(), mip.get()}) p->renderFrame(0);
    const Image a = bilinear->readback(Component::Full), b = nearest->readback(Component::Full);
    auto m = compareImages(b, a);
    EXPECT_GT(m->mae, 0.0) << "nearest differs from bilinear";
    // The same solution: image means within 3 % (nearest and bilinear weight texels differently).
    EXPECT_NEAR(totalRadiance(b) / totalRadiance(a), 1.0, 0.03);
    const auto tc = radiosityOf(*bilinear).system().readTotal(), tm = radiosityOf(*mip).system().readTotal();
    double worst = 0.0;
    for (size_t k = 0; k < tc.size(); ++k)
        worst = std::max(worst, double(glm::length(tc[k] - tm[k])) / std::max(1e-3, double(glm::length(tc[k]))));
    RecordProperty("mipVsComputeWorstRelative", std::to_string(worst));
    // Float summation order (mip levels of RGBA32F vs a 256-thread tree): 1e-4 relative.
    EXPECT_LT(worst, 1e-4);
}

namespace {

// A floor under an area light and a plate that jumps between frames: frame 0 beside the light's
// footprint, frame 1 right under the light (a new shadow: the newly-occluded case), frame 2 off to
// the other side (the shadow goes: the newly-visible case).
Scene slidingOccluder() {
    Scene s;
    s.name = "sliding-occluder";
    Material floor, plate;
    floor.name = "floor";
    floor.baseColor = glm::vec3(0.6f);
    plate.name = "plate";
    plate.baseColor = glm::vec3(0.9f);
    s.materials = {floor, plate};
    MeshBuilder fb("floor");
    fb.quad({-0.6f, 0.0f, -0.6f}, {0.6f, 0.0f, -0.6f}, {0.6f, 0.0f, 0.6f}, {-0.6f, 0.0f, 0.6f}, {0, 1, 0});
    // A ceiling around the light (an opening for it, as the Cornell box's): the plate's lit top
    // reflects onto it, so the plate's own shot radiosity matters (the negative shot of Alg. 4.3).
    MeshBuilder cb("ceiling");
    const float y = 1.0f, h = 0.15f, w = 0.6f;
    const glm::vec3 down(0, -1, 0);
    cb.quad({-w, y, -w}, {w, y, -w}, {w, y, -h}, {-w, y, -h}, down);
    cb.quad({-w, y, h}, {w, y, h}, {w, y, w}, {-w, y, w}, down);
    cb.quad({-w, y, -h}, {-h, y, -h}, {-h, y, h}, {-w, y, h}, down);
    cb.quad({h, y, -h}, {w, y, -h}, {w, y, h}, {h, y, h}, down);
    MeshBuilder pb("plate");
    pb.axisBox({-0.15f, 0.45f, -0.15f}, {0.15f, 0.5f, 0.15f});
    s.meshes = {fb.take(), pb.take(), cb.take()};
    Object f;
    f.name = "floor";
    f.mesh = 0;
    f.material = 0;
    Object p;
    p.name = "plate";
    p.mesh = 1;
    p.material = 1;
    p.animation.loop = false;
    const float frame = 1.0f / s.frameRate;
    for (auto [t, x] : {std::pair{0.0f, -0.45f}, std::pair{frame, 0.0f}, std::pair{2.0f * frame, 0.45f}}) {
        TransformKey k;
        k.time = t;
        k.translation = {x, 0.0f, 0.0f};
        p.animation.keys.push_back(k);
    }
    Object c;
    c.name = "ceiling";
    c.mesh = 2;
    c.material = 0;
    s.objects = {f, p, c};
    Light l;
    l.name = "panel";
    l.type = LightType::Area;
    l.position = {0.0f, 1.0f, 0.0f};
    l.edgeU = {0.3f, 0.0f, 0.0f};
    l.edgeV = {0.0f, 0.0f, 0.3f};  // cross(U, V) = -y: emits downward
    l.radiance = glm::vec3(10.0f);
    s.lights = {l};
    s.camera.position = {0.0f, 0.9f, 1.3f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    return s;
}

// Area-weighted relative RMS difference of B over the static elements (floor and ceiling).
double staticDifference(RadiosityTechnique& a, RadiosityTechnique& b) {
    const auto& pm = a.system().patches();
    const auto ba = a.system().readTotal(), bb = b.system().readTotal();
    double num = 0.0, den = 0.0;
    for (size_t k = 0; k < ba.size(); ++k) {
        const radiosity::Element& e = pm.elements()[k];
        if (pm.quads()[e.quad].body == 1 || (pm.quads()[e.quad].flags & RAD_QUAD_LIGHT)) continue;
        num += double(glm::dot(ba[k] - bb[k], ba[k] - bb[k])) * e.area;
        den += double(glm::dot(bb[k], bb[k])) * e.area;
    }
    return std::sqrt(num / den);
}

}  // namespace

TEST_F(RadiosityGpuTest, RedistributionFollowsASuddenOcclusionAndItsRemoval) {
    // Progressive refinement restarts every frame: the truth for the same elements. Incremental
    // radiosity must reach it by modification alone (the four visibility cases, the negative shot),
    // cross redistribution by its cross projection (approximate: 16 rays through coarse patches).
    const Scene scene = slidingOccluder();
    const std::map<std::string, std::string> settings = {
        {"elementSize", "0.05"}, {"dynamicElementSize", "0.05"}, {"threshold", "0.001"}, {"frameBudgetMs", "0"}};
    auto pr = makePipeline(scene, "radiosity-pr", settings, 32);
    auto inc = makePipeline(scene, "radiosity-incremental", settings, 32);
    auto cross = makePipeline(scene, "radiosity-cross", settings, 32);
    for (uint32_t f = 0; f < 3; ++f) {
        SCOPED_TRACE(f);
        for (auto* p : {pr.get(), inc.get(), cross.get()}) p->renderFrame(f);
        const double dInc = staticDifference(radiosityOf(*inc), radiosityOf(*pr));
        const double dCross = staticDifference(radiosityOf(*cross), radiosityOf(*pr));
        RecordProperty("frame" + std::to_string(f) + "_incremental_vs_pr", std::to_string(dInc));
        RecordProperty("frame" + std::to_string(f) + "_cross_vs_pr", std::to_string(dCross));
        // The shadow covers a quarter of the lit floor: leaving it out gives ~0.3 (see the mutations
        // in docs/techniques/radiosity.md). Incremental differs from PR only by the order of shots and
        // the threshold's remainder (measured 0.000 / 0.011 / 0.012); cross also by its projection's
        // undersampling and PR's own 4-pixel visibility, whose shadows are too small (measured 0.023 /
        // 0.071 / 0.021 at frames 0 / 1 / 2). Bounds: the measured values + about 20 %.
        EXPECT_LT(dInc, 0.02);
        EXPECT_LT(dCross, f == 1 ? 0.085 : 0.03);
    }
}

TEST_F(RadiosityGpuTest, RedistributionOnAnUnconvergedSolutionUnderTheShootingBudget) {
    // The per-frame shooting budget (frameBudgetMs) leaves the initial solution unconverged while the
    // plate moves (frames 0-2). Incremental redistribution is linear in what each quad has shot (M
    // removes its shot, C shoots its total), so it stays right on a partial solution; cross keeps its
    // M-free initial solution going over frames and inserts M where it is when that converged. Both
    // must end at PR's solution (unbudgeted: converged in every frame) of the plate's last position.
    // The budget counts iterations: a 1 ns budget stops every call after its one guaranteed quad.
    const Scene scene = slidingOccluder();
    std::map<std::string, std::string> settings = {
        {"elementSize", "0.05"}, {"dynamicElementSize", "0.05"}, {"threshold", "0.001"}, {"frameBudgetMs", "0"}};
    auto pr = makePipeline(scene, "radiosity-pr", settings, 32);
    for (uint32_t f = 0; f < 3; ++f) pr->renderFrame(f);
    ASSERT_TRUE(radiosityOf(*pr).lastConverged());
    settings["frameBudgetMs"] = "0.000001";
    for (const char* method : {"radiosity-incremental", "radiosity-cross"}) {
        SCOPED_TRACE(method);
        auto p = makePipeline(scene, method, settings, 32);
        RadiosityTechnique& t = radiosityOf(*p);
        uint32_t frame = 0;
        for (; frame < 600 && (frame < 3 || !t.lastConverged()); ++frame) {
            p->renderFrame(frame);
            if (frame < 3) {
                EXPECT_FALSE(t.lastConverged()) << "frame " << frame;  // the budget, not convergence, ended it
                EXPECT_LE(t.lastIterations(), 2u) << "frame " << frame;
            }
            // Incremental redistributes in each frame the plate moved, whatever the budget.
            if (std::string(method) == "radiosity-incremental" && (frame == 1 || frame == 2)) {
                EXPECT_GT(t.lastMovingPatches(), 0u) << "frame " << frame;
            }
        }
        ASSERT_TRUE(t.lastConverged());
        const double d = staticDifference(t, radiosityOf(*pr));
        const std::string name = method;
        RecordProperty(name + "_frames", static_cast<int>(frame));
        RecordProperty(name + "_vs_pr", std::to_string(d));
        // Bounds as in RedistributionFollowsASuddenOcclusionAndItsRemoval (the plate's shadow left out:
        // ~0.3): incremental differs from PR by the order of shots and the threshold's remainder,
        // cross also by its projection. Measured 0.008 (converged in frame 10) and 0.022 (frame 5).
        EXPECT_LT(d, std::string(method) == "radiosity-incremental" ? 0.02 : 0.03);
    }
}
