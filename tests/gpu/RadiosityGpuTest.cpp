// Hemicube radiosity (van de Hoef 2013) on the GPU: the furnace's E / (1 - rho), form-factor
// reciprocity through the shooting pass, agreement with the path tracer and with the gather method,
// the cross redistribution's 4 |M| hemicubes independent of |C|, no work in a converged still scene,
// and refusal of scenes the methods cannot shade.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "scene/SceneLoader.h"
#include "techniques/Registry.h"
#include "techniques/radiosity/RadiosityTechnique.h"
#include "techniques/radiosity_cross/CrossRadiosityTechnique.h"

#include <glm/gtc/constants.hpp>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class RadiosityGpuTest : public gputest::GpuTest {};

const char* const kMethods[] = {"radiosity-gather", "radiosity-pr", "radiosity-incremental", "radiosity-cross"};

RadiosityTechnique& radiosityOf(Pipeline& p) { return dynamic_cast<RadiosityTechnique&>(p.technique()); }

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
        auto p = makePipeline(scene, method, settings, 32);
        p->renderFrame(0);
        auto& t = radiosityOf(*p);
        const auto& pm = t.system().patches();
        const glm::dvec3 b = meanOverReceivers(pm, t.system().readTotal());
        const glm::dvec3 bu = meanOverReceivers(pm, t.system().readUnshot());
        const double fixedPoint = b.g + 0.5 / 0.5 * bu.g;
        RecordProperty(std::string(method) + "_B", std::to_string(b.g));
        RecordProperty(std::string(method) + "_fixedPoint", std::to_string(fixedPoint));
        // 12 Gauss-Seidel sweeps leave at most 0.5^12 of the first bounce: 5e-4. Hemicube aliasing of
        // the 32^2 delta form factors and the disk approximation's per-patch error: 2 %.
        EXPECT_NEAR(fixedPoint, expected, 0.02 * expected);
        if (std::string(method) == "radiosity-gather") EXPECT_NEAR(b.g, expected, 0.02 * expected);
        // Converged to the threshold: at most threshold x E unshot per quad (the mean is lower).
        else EXPECT_NEAR(b.g, expected, 0.05 * expected);
        const Image full = p->readback(Component::Full);
        double mean = totalRadiance(full) / (3.0 * full.width() * full.height());
        EXPECT_NEAR(mean, b.g, 0.03 * expected) << "display of the solution";
    }
}

TEST_F(RadiosityGpuTest, DebugCornell) {
    const char* sceneName = std::getenv("RAD_SCENE") ? std::getenv("RAD_SCENE") : "cornell-box-rotating";
    const Scene scene = builtin(sceneName);
    constexpr int kSize = 64;
    const uint32_t frames[] = {0, 6, 12};
    std::map<uint32_t, Image> refs;
    for (uint32_t f : frames) refs[f] = pathTraced(scene, kSize, f, 256);
    for (const char* method : kMethods) {
        auto p = makePipeline(scene, method, {{"elementSize", "0.05"}}, kSize);
        for (uint32_t f : frames) {
            p->renderFrame(f);
            const Image full = p->readback(Component::Full), direct = p->readback(Component::Direct);
            auto [a, b] = receiversOnly(full, direct, refs[f]);
            auto m = compareImages(a, b);
            printf("%-22s frame %2u relMSE %.4f ratio %.4f hemicubes %u it %u conv %d\n", method, f, m->relMse, totalRadiance(a) / totalRadiance(b),
                   radiosityOf(*p).lastHemicubes(), radiosityOf(*p).lastIterations(), int(radiosityOf(*p).lastConverged()));
        }
    }
}

TEST_F(RadiosityGpuTest, DebugFurnace) {
    const Scene scene = builtin("furnace", {{"albedo", "0.5"}});
    std::vector<std::map<std::string, std::string>> variants = {
        {{"ffSubdivideRatio", "0.1"}, {"ffSubdivisions", "4"}}, {{"ffSubdivideRatio", "0.05"}, {"ffSubdivisions", "4"}}, {{"ffSubdivideRatio", "0.02"}, {"ffSubdivisions", "4"}},
        {{"ffSubdivideRatio", "0.1"}, {"ffSubdivisions", "6"}},{{"ffSubdivideRatio", "0.05"}, {"ffSubdivisions", "8"}}, {{"ffSubdivideRatio", "0.05"}, {"ffSubdivisions", "6"}, {"elementSize", "0.1"}}};
    for (auto v : variants) {
        auto set = v;
        if (!set.count("elementSize")) set["elementSize"] = "0.25";
        set["threshold"] = "0.002";
        set["maxIterations"] = "3000";
        auto p = makePipeline(scene, "radiosity-pr", set, 32);
        p->renderFrame(0);
        auto& t = radiosityOf(*p);
        const auto& pm = t.system().patches();
        const glm::dvec3 b = meanOverReceivers(pm, t.system().readTotal());
        const glm::dvec3 bu = meanOverReceivers(pm, t.system().readUnshot());
        std::string name;
        for (auto& kv : v) name += kv.first + "=" + kv.second + " ";
        printf("%-40s B %.4f Bu %.5f fixed %.4f it %u\n", name.c_str(), b.g, bu.g, b.g + bu.g, t.lastIterations());
    }
}
