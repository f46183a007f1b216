// The optional curvature max-mipmap of Nichols (2010) §3.3.1 (Eq. 3.1) in the eye pyramid and its use as
// a refinement criterion of `multires-splat`: a 90-degree crease has kappa = 2 sin(45 deg) = sqrt(2) at
// its pixels and 0 elsewhere, a flat plane is 0 everywhere, each coarser level is the max of its
// children, and enabling the criterion never removes refinement and refines a crease the other
// criteria are set to miss.
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "techniques/multires_splat/MultiresSplatTechnique.h"

#include <cmath>
#include <vector>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {
class MultiresSplatCurvatureGpuTest : public gputest::GpuTest {};

constexpr int kSize = 64;
const float kSqrtTwo = std::sqrt(2.0f);
// Normals are axis-aligned unit vectors, exact in the G-buffer's half floats: only the chord's
// float rounding remains.
constexpr float kKappaTolerance = 1e-6f;

// A floor (y = 0, normal +y) meeting a back wall (z = -1, normal +z) at a 90-degree crease, both 2 m
// wide, lit by a point light in front of the wall and seen from the front and above.
Scene creaseScene() {
    Scene s;
    s.name = "crease";
    Mesh m;
    m.name = "crease";
    m.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}};
    m.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    m.indices = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7};
    s.meshes.push_back(m);
    Material grey;
    grey.name = "grey";
    grey.baseColor = glm::vec3(0.5f);
    s.materials.push_back(grey);
    Object o;
    o.name = "crease";
    s.objects.push_back(o);
    Light light;
    light.name = "point";
    light.type = LightType::Point;
    light.position = {0.0f, 1.0f, 0.0f};
    light.intensity = glm::vec3(5.0f);  // W/sr
    s.lights.push_back(light);
    s.camera.position = {0.0f, 1.2f, 1.6f};
    s.camera.target = {0.0f, 0.4f, -1.0f};
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 10.0f;
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

std::vector<float> readCurvature(const nichols::MinMaxPyramid& pyramid, int level) {
    const glm::ivec2 size = pyramid.levelSize(level);
    std::vector<glm::vec4> texels(static_cast<size_t>(size.x) * size.y);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glGetTextureImage(pyramid.curvature().id(), level, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)),
                      texels.data());
    std::vector<float> kappa;
    for (const glm::vec4& t : texels) kappa.push_back(t.r);
    return kappa;
}

const nichols::MinMaxPyramid& eyePyramid(Pipeline& p) {
    return dynamic_cast<MultiresSplatTechnique&>(p.technique()).eyePyramid();
}

const std::map<std::string, std::string> kCurvatureOn = {
    {"rsmSize", "32"}, {"vplGrid", "8"}, {"curvature", "true"}, {"eyeCoarsest", "8"}};
}  // namespace

TEST_F(MultiresSplatCurvatureGpuTest, CreaseIsSqrtTwoAndFlatSurfacesAreZero) {
    const Scene creaseSource = creaseScene();  // the pipeline keeps a reference
    auto crease = makePipeline(creaseSource, "multires-splat", kCurvatureOn, kSize);
    crease->renderFrame(0);
    const std::vector<float> kappa = readCurvature(eyePyramid(*crease), 0);
    int creasePixels = 0;
    for (float k : kappa) {
        // Eq. 3.1 at a 90-degree crease: 2 sin(pi / 4) = sqrt(2); on either face: 0.
        const bool flat = std::abs(k) <= kKappaTolerance, creased = std::abs(k - kSqrtTwo) <= kKappaTolerance;
        ASSERT_TRUE(flat || creased) << "kappa " << k;
        creasePixels += creased ? 1 : 0;
    }
    RecordProperty("creasePixels", creasePixels);
    // The crease crosses the image once: about two pixel rows (one on each face), not more.
    EXPECT_GE(creasePixels, kSize);
    EXPECT_LE(creasePixels, 4 * kSize);

    Light light;
    light.type = LightType::Point;
    light.position = {0.0f, 2.0f, 0.0f};
    light.intensity = glm::vec3(5.0f);
    const Scene planeSource = planeScene(light);
    auto plane = makePipeline(planeSource, "multires-splat", kCurvatureOn, kSize);
    plane->renderFrame(0);
    for (int level = 0; level < eyePyramid(*plane).levels(); ++level)
        for (float k : readCurvature(eyePyramid(*plane), level)) ASSERT_LE(k, kKappaTolerance) << "level " << level;
}

TEST_F(MultiresSplatCurvatureGpuTest, ReductionIsTheMaxOfTheChildren) {
    auto scene = loadScene("cornell-box");  // creases and silhouettes at many angles
    ASSERT_TRUE(scene.ok());
    auto p = makePipeline(*scene, "multires-splat", kCurvatureOn, kSize);
    p->renderFrame(0);
    const nichols::MinMaxPyramid& pyramid = eyePyramid(*p);
    ASSERT_GE(pyramid.levels(), 4);
    std::vector<float> child = readCurvature(pyramid, 0);
    for (int level = 1; level < pyramid.levels(); ++level) {
        const std::vector<float> parent = readCurvature(pyramid, level);
        const glm::ivec2 size = pyramid.levelSize(level), childSize = pyramid.levelSize(level - 1);
        for (int y = 0; y < size.y; ++y)
            for (int x = 0; x < size.x; ++x) {
                float expected = 0.0f;
                for (int cy = 2 * y; cy <= 2 * y + 1; ++cy)
                    for (int cx = 2 * x; cx <= 2 * x + 1; ++cx) {
                        const float c = child[static_cast<size_t>(cy * childSize.x + cx)];
                        ASSERT_GE(parent[static_cast<size_t>(y * size.x + x)], c) << "level " << level;
                        expected = std::max(expected, c);
                    }
                // A max is exact: no tolerance.
                ASSERT_EQ(parent[static_cast<size_t>(y * size.x + x)], expected) << "level " << level;
            }
        child = parent;
    }
    EXPECT_GT(*std::max_element(child.begin(), child.end()), 1.0f) << "the coarsest level sees the box's creases";
}

TEST_F(MultiresSplatCurvatureGpuTest, CurvatureCriterionNeverReducesRefinement) {
    // With the normal and depth criteria set to miss it, only the curvature mipmap finds the crease.
    const Scene crease = creaseScene();
    std::map<std::string, std::string> blind = {
        {"rsmSize", "32"}, {"vplGrid", "8"}, {"eyeCoarsest", "8"}, {"normalThreshold", "2"}, {"depthThreshold", "1e9"}};
    auto withCurvature = blind;
    withCurvature["curvature"] = "true";
    const double off = makePipeline(crease, "multires-splat", blind, kSize)->renderFrame(0).counters.at("subsplats");
    const double on = makePipeline(crease, "multires-splat", withCurvature, kSize)->renderFrame(0).counters.at("subsplats");
    RecordProperty("creaseSubsplatsOff", std::to_string(off));
    RecordProperty("creaseSubsplatsOn", std::to_string(on));
    EXPECT_GT(on, off);

    // Default thresholds on the Cornell box: an extra OR-ed criterion can only add subsplats.
    auto box = loadScene("cornell-box");
    ASSERT_TRUE(box.ok());
    const std::map<std::string, std::string> defaults = {{"rsmSize", "32"}, {"vplGrid", "8"}, {"eyeCoarsest", "8"}};
    auto boxCurvature = defaults;
    boxCurvature["curvature"] = "true";
    auto pOff = makePipeline(*box, "multires-splat", defaults, kSize);
    auto pOn = makePipeline(*box, "multires-splat", boxCurvature, kSize);
    const FrameStats a = pOff->renderFrame(0), b = pOn->renderFrame(0);
    RecordProperty("boxSubsplatsOff", std::to_string(a.counters.at("subsplats")));
    RecordProperty("boxSubsplatsOn", std::to_string(b.counters.at("subsplats")));
    EXPECT_GE(b.counters.at("subsplats"), a.counters.at("subsplats"));
    // Per level: every pixel sits at the same or a finer level, so the finest level cannot lose cells.
    EXPECT_GE(b.counters.at("subsplats/level-0"), a.counters.at("subsplats/level-0"));
}
