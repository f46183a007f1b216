// The debug views the viewer lists (techniques/Technique.h DebugView) hold what their names say:
// photon-splat's bundles are the frame's bundles' hit points, hisr's tree views are the levels of its
// VPL tree a walk visits, the radiosity techniques' hemicube views are the hemicubes they rendered.
// (The viewer test, tests/viewer/ViewerLab.cmake, checks that the viewer draws them.)
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "scene/SceneLoader.h"
#include "techniques/Registry.h"
#include "techniques/photon_splat/PhotonSplatTechnique.h"
#include "techniques/radiosity/RadiosityTechnique.h"

#include <algorithm>
#include <set>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class DebugViewsGpuTest : public gputest::GpuTest {};

const DebugView* findView(const std::vector<DebugView>& views, const std::string& name) {
    auto it = std::find_if(views.begin(), views.end(), [&](const DebugView& v) { return v.name == name; });
    return it == views.end() ? nullptr : &*it;
}

std::vector<std::string> namesWithPrefix(const std::vector<DebugView>& views, const std::string& prefix) {
    std::vector<std::string> out;
    for (const DebugView& v : views)
        if (v.name.rfind(prefix, 0) == 0) out.push_back(v.name);
    return out;
}

// Level `level` of a float 2D-array texture, every layer, RGBA.
std::vector<glm::vec4> downloadLevel(const gl::Texture& t, int level, glm::ivec3& size) {
    glGetTextureLevelParameteriv(t.id(), level, GL_TEXTURE_WIDTH, &size.x);
    glGetTextureLevelParameteriv(t.id(), level, GL_TEXTURE_HEIGHT, &size.y);
    size.z = t.desc().depth;
    std::vector<glm::vec4> texels(static_cast<size_t>(size.x) * size.y * size.z);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);  // views may be written as images (BOUNCE_BARRIER_CHECK)
    glGetTextureImage(t.id(), level, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)), texels.data());
    return texels;
}

struct HemicubeIds {
    int topFacesWithHits = 0;
    int topFacesFull = 0;     // with at least 99 % of their pixels on a surface
    size_t surfacesSeen = 0;  // distinct IDs over every layer
    bool allValid = true;     // every ID <= the number of surfaces
};

// Radiosity's R32UI ID hemicube array (5 layers per hemicube, layer 5 k the top face).
HemicubeIds hemicubeIds(const gl::Texture& t, uint32_t surfaces) {
    const int r = t.desc().width, layers = t.desc().depth;
    std::vector<uint32_t> ids(static_cast<size_t>(r) * r * layers);
    glGetTextureImage(t.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(ids.size() * sizeof(uint32_t)), ids.data());
    HemicubeIds out;
    std::set<uint32_t> seen;
    for (uint32_t id : ids) {
        out.allValid = out.allValid && id <= surfaces;
        if (id != 0) seen.insert(id);
    }
    for (int l = 0; l < layers; l += 5) {
        int hits = 0;
        for (int i = 0; i < r * r; ++i) hits += ids[static_cast<size_t>(l) * r * r + static_cast<size_t>(i)] != 0;
        out.topFacesWithHits += hits > 0;
        out.topFacesFull += hits >= r * r * 99 / 100;
    }
    out.surfacesSeen = seen.size();
    return out;
}

uint32_t surfaceCount(Pipeline& p) {
    uint32_t surfaces = 0;
    for (const auto& q : dynamic_cast<RadiosityTechnique&>(p.technique()).system().patches().quads())
        surfaces = std::max(surfaces, q.surface + 1);
    return surfaces;
}

Scene builtin(const std::string& name) {
    auto s = loadScene(name);
    EXPECT_TRUE(s.ok()) << name;
    return std::move(*s);
}

}  // namespace

TEST_F(DebugViewsGpuTest, PhotonSplatBundlesAreTheFramesHitPoints) {
    const Scene scene = builtin("cornell-box");
    constexpr float kStepBack = 0.05f;
    auto p = makePipeline(scene, "photon-splat", {{"photons", "300"}, {"stepBack", "0.05"}}, 32);
    p->renderFrame(0);
    const auto& bundles = dynamic_cast<PhotonSplatTechnique&>(p->technique()).bundles();
    ASSERT_GT(bundles.size(), 100u);  // most of 300 photons hit the closed box
    const auto views = p->debugViews();
    const DebugView* v = findView(views, "photon-splat.bundles");
    ASSERT_NE(v, nullptr);
    EXPECT_EQ(v->encoding, DebugEncoding::Points);
    glm::ivec3 size;
    const std::vector<glm::vec4> texels = downloadLevel(*v->texture, 0, size);
    size_t valid = 0;
    for (size_t i = 0; i < texels.size(); ++i) {
        if (texels[i].w <= 0.0f) continue;
        ++valid;
        ASSERT_LT(i, bundles.size()) << "a point past the frame's bundles";
        // The photon's hit point: the bundle's origin plus its step back (at most the distance; a photon
        // whose ray escapes the open front starts its bundle at itself and shows where it leaves the box).
        const photonsplat::Bundle& b = bundles[i];
        const glm::vec3 hit = b.origin + (b.escaped ? b.hitDistance : std::min(kStepBack, b.hitDistance)) * b.direction;
        EXPECT_LT(glm::length(glm::vec3(texels[i]) - hit), 1e-5f) << i;  // float arithmetic of the same sum
    }
    EXPECT_EQ(valid, bundles.size());
}

TEST_F(DebugViewsGpuTest, HisrTreeViewsAreTheWalkedLevelsOfTheVplTree) {
    const Scene scene = builtin("cornell-box");
    auto p = makePipeline(scene, "hisr", {{"rsmSize", "64"}, {"rootGrid", "8"}, {"maxDepth", "2"}}, 32);
    p->renderFrame(0);
    const auto views = p->debugViews();
    // 64^2 RSM, 8^2 roots: levels 64, 32, 16, 8; a walk goes 2 levels down: depths 0 (8^2) to 2 (32^2).
    EXPECT_EQ(namesWithPrefix(views, "hisr.tree."), (std::vector<std::string>{"hisr.tree.depth0", "hisr.tree.depth1", "hisr.tree.depth2"}));
    double coveredAtDepth0 = -1.0;
    glm::vec3 lo, hi;
    scene.bounds(0.0f, lo, hi);
    for (int depth = 0; depth <= 2; ++depth) {
        SCOPED_TRACE(depth);
        const DebugView* v = findView(views, "hisr.tree.depth" + std::to_string(depth));
        ASSERT_NE(v, nullptr);
        EXPECT_EQ(v->encoding, DebugEncoding::ClusterPoints);
        glm::ivec3 size;
        const std::vector<glm::vec4> nodes = downloadLevel(*v->texture, v->level, size);
        EXPECT_EQ(size.x, 8 << depth);
        EXPECT_EQ(size.y, 8 << depth);
        // Each depth partitions the RSM: the nodes' texel counts sum to the covered texels (the same
        // at every depth), and each node's mean position is a point of the scene.
        double covered = 0.0;
        for (const glm::vec4& n : nodes) {
            covered += n.w;
            if (n.w <= 0.0f) continue;
            const glm::vec3 mean = glm::vec3(n) / n.w;
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(mean, lo - 1e-3f)) && glm::all(glm::lessThanEqual(mean, hi + 1e-3f)));
        }
        EXPECT_GT(covered, 0.5 * 64 * 64);  // the spot's map sees the box over most of its texels
        if (depth == 0) coveredAtDepth0 = covered;
        else EXPECT_EQ(covered, coveredAtDepth0);  // integer counts, exact in float up to 2^24
    }
}

TEST_F(DebugViewsGpuTest, RadiosityHemicubeViewsHoldTheRenderedHemicubes) {
    const Scene scene = builtin("cornell-box-rotating");
    const std::map<std::string, std::vector<std::string>> expected{
        {"radiosity-gather", {"radiosity.hemicube.radiosity"}},
        {"radiosity-pr", {"radiosity.hemicube.id"}},
        {"radiosity-incremental", {"radiosity.hemicube.id", "radiosity.hemicube.idOld"}},
        {"radiosity-cross", {"radiosity.hemicube.id", "radiosity.hemicube.idOld", "radiosity.hemicube.shot",
                             "radiosity.hemicube.backOld", "radiosity.hemicube.back"}},
    };
    for (const auto& [method, names] : expected) {
        SCOPED_TRACE(method);
        std::map<std::string, std::string> settings{{"elementSize", "0.25"}, {"hemicubeSize", "16"}};
        // maxIterations bounds the shooting, not the host's speed: the time budget per frame off (cross
        // inserts the box after its budget-free initial solution, and frame 1 redistributes).
        if (method != "radiosity-gather") {
            settings["maxIterations"] = "20";
            settings["frameBudgetMs"] = "0";
        }
        auto p = makePipeline(scene, method, settings, 32);
        p->renderFrame(0);
        p->renderFrame(1);  // the box turns: the redistributions render their old/new hemicubes
        const auto views = p->debugViews();
        EXPECT_EQ(namesWithPrefix(views, "radiosity.hemicube."), names);
        const uint32_t surfaces = surfaceCount(*p);
        for (const std::string& name : names) {
            const DebugView* v = findView(views, name);
            ASSERT_NE(v, nullptr);
            if (name == "radiosity.hemicube.radiosity") {
                // Multisampled (the viewer averages the samples); its content is the viewer test's.
                EXPECT_EQ(v->texture->desc().target, GL_TEXTURE_2D_MULTISAMPLE_ARRAY);
                continue;
            }
            if (v->encoding != DebugEncoding::Ids) continue;
            // Some hemicube of the last batch saw surfaces, two at least, and every ID is a surface
            // of the model plus one (layers past the batch are cleared to 0).
            const HemicubeIds h = hemicubeIds(*v->texture, surfaces);
            EXPECT_GT(h.topFacesWithHits, 0) << name;
            EXPECT_GE(h.surfacesSeen, 2u) << name;
            EXPECT_TRUE(h.allValid) << name;
        }
    }
}

TEST_F(DebugViewsGpuTest, RadiosityIdHemicubesInAClosedRoomSeeWallsEverywhere) {
    // In the closed furnace room every hemicube the batch rendered sees a wall through every pixel
    // of its top face (a ray from inside a closed room always hits it): each top face is either full
    // (rendered) or empty (past the batch, cleared), the first one full, and a top face sees the
    // floor or ceiling opposite and the four walls at its edges.
    auto scene = loadScene("furnace");
    ASSERT_TRUE(scene.ok());
    auto p = makePipeline(*scene, "radiosity-pr", {{"elementSize", "0.25"}, {"hemicubeSize", "16"}, {"threshold", "0.01"}}, 32);
    p->renderFrame(0);
    const auto views = p->debugViews();
    const DebugView* v = findView(views, "radiosity.hemicube.id");
    ASSERT_NE(v, nullptr);
    const HemicubeIds h = hemicubeIds(*v->texture, surfaceCount(*p));
    EXPECT_GT(h.topFacesFull, 0);
    EXPECT_EQ(h.topFacesFull, h.topFacesWithHits);
    EXPECT_GE(h.surfacesSeen, 5u);
    EXPECT_TRUE(h.allValid);
}
