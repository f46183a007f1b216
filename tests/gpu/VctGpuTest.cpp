// Voxel cone tracing (Rauwendaal 2013): the GPU voxelizers against the CPU overlap test
// (src/techniques/vct/VoxelOverlap, itself tested against a brute-force test in tests/unit), the
// hybrid's split, sparse = dense mipmapping, the GPU mip filters against their CPU references, the
// indirect light against the one-bounce reference (still and animated), a closed sphere with a point
// light at its centre (analytic one bounce), settings errors and the counters.
// Mutations these tests were checked against are listed in docs/techniques/vct.md ("Tests").
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "metrics/ErrorMetrics.h"
#include "metrics/LightLeak.h"
#include "reference/PathTracer.h"
#include "techniques/Registry.h"
#include "techniques/vct/ShMath.h"
#include "techniques/vct/VctTechnique.h"
#include "techniques/vct/VoxelOverlap.h"

#include <glm/gtc/constants.hpp>

#include <cmath>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {

class VctGpuTest : public gputest::GpuTest {};

VctTechnique& vctOf(Pipeline& p) { return dynamic_cast<VctTechnique&>(p.technique()); }

// CPU occupancy of the scene at time 0 in the technique's grid (the same factored test).
std::vector<uint8_t> cpuOccupancy(const Scene& scene, const VctTechnique& vct, vct::Separability s) {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    const glm::mat4 voxelFromWorld = vct.voxelFromWorld();
    for (const Object& o : scene.objects) {
        const Mesh& m = scene.meshes[o.mesh];
        const glm::mat4 w = voxelFromWorld * o.worldFromObject(0.0f);
        const uint32_t base = static_cast<uint32_t>(positions.size());
        for (const glm::vec3& p : m.positions) positions.push_back(glm::vec3(w * glm::vec4(p, 1.0f)));
        for (uint32_t i : m.indices) indices.push_back(base + i);
    }
    const int n = vct.resolution();
    return vct::voxelizeMeshOccupancy(positions, indices, glm::ivec3(n), s);
}

size_t countSet(const std::vector<uint8_t>& v) {
    size_t c = 0;
    for (uint8_t x : v) c += x != 0;
    return c;
}

size_t countDifferent(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t c = 0;
    for (size_t i = 0; i < a.size(); ++i) c += (a[i] != 0) != (b[i] != 0);
    return c;
}


double meanOf(const Image& image) { return totalRadiance(image) / (3.0 * image.width() * image.height()); }

double relMse(const Image& test, const Image& reference) {
    auto m = compareImages(test, reference);
    EXPECT_TRUE(m.ok());
    return m.ok() ? m->relMse : 1e9;
}

}  // namespace

TEST_F(VctGpuTest, EveryVoxelizerMatchesTheCpuOverlapTest) {
    for (const char* name : {"cornell-box", "cornell-box-area", "cornell-box-dynamic", "indirect-light", "two-rooms", "atrium", "area-screen"}) {
        auto scene = loadScene(name);
        ASSERT_TRUE(scene.ok());
        // A grid box offset by a fraction of a voxel from the scene's round coordinates: walls lying
        // exactly on voxel faces are ties that GPU and CPU float rounding may break differently.
        glm::vec3 lo, hi;
        scene->bounds(0.0f, lo, hi);
        const float side = 1.1f * std::max(hi.x - lo.x, std::max(hi.y - lo.y, hi.z - lo.z));
        const glm::vec3 centre = 0.5f * (lo + hi) + glm::vec3(0.0137f, 0.0071f, -0.0093f) * side;
        const std::map<std::string, std::string> box = {{"boxSide", std::to_string(side)}, {"boxCentreX", std::to_string(centre.x)},
                                                        {"boxCentreY", std::to_string(centre.y)}, {"boxCentreZ", std::to_string(centre.z)},
                                                        {"binary", "true"}, {"resolution", "32"}};
        for (const char* sep : {"thin", "conservative"}) {
            const auto s = std::string(sep) == "thin" ? vct::Separability::Thin6 : vct::Separability::Conservative26;
            std::vector<uint8_t> cpu;
            for (const char* voxelizer : {"triangle", "fragment", "hybrid"}) {
                auto settings = box;
                settings["voxelizer"] = voxelizer;
                settings["separability"] = sep;
                auto p = makePipeline(*scene, "vct", settings, 16);
                p->renderFrame(0);
                const std::vector<uint8_t> gpu = vctOf(*p).downloadOccupancy();
                if (cpu.empty()) cpu = cpuOccupancy(*scene, vctOf(*p), s);
                ASSERT_EQ(gpu.size(), cpu.size());
                const size_t set = countSet(cpu), diff = countDifferent(gpu, cpu);
                RecordProperty(std::string(name) + "_" + sep + "_" + voxelizer + "_differing", std::to_string(diff) + " of " + std::to_string(set));
                ASSERT_GT(set, 1000u) << name;
                // Same test, same float formulas: only near-ties can differ. Measured on llvmpipe: 0
                // differing voxels on every scene (bench/results/vct-tests-*.json); 0.5 % leaves room
                // for a GPU that rounds differently.
                EXPECT_LE(double(diff), 0.005 * double(set)) << name << " " << sep << " " << voxelizer << ": " << diff << " of " << set;
            }
        }
    }
}

TEST_F(VctGpuTest, ThinSheetIsOneVoxelThickAndConservativeContainsIt) {
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.irradiance = glm::vec3(1.0f);
    const Scene scene = gputest::planeScene(sun);
    // A grid box whose voxel planes do not meet the plane y = 0: it sits at 0.3 voxels in a layer.
    const std::map<std::string, std::string> box = {{"boxSide", "4.8"}, {"boxCentreX", "0"}, {"boxCentreY", "0.045"},
                                                    {"boxCentreZ", "0"}, {"resolution", "32"}, {"binary", "true"}};
    auto thinSettings = box;
    thinSettings["separability"] = "thin";
    auto consSettings = box;
    consSettings["separability"] = "conservative";
    auto thin = makePipeline(scene, "vct", thinSettings, 16);
    auto cons = makePipeline(scene, "vct", consSettings, 16);
    thin->renderFrame(0);
    cons->renderFrame(0);
    const auto t = vctOf(*thin).downloadOccupancy(), c = vctOf(*cons).downloadOccupancy();
    const int n = 32;
    // The plane spans x, z in [-2, 2] = voxels 2.67 .. 29.33: columns 3..28 are fully covered.
    size_t interiorColumns = 0, interiorOk = 0, thickColumns = 0;
    for (int z = 0; z < n; ++z)
        for (int x = 0; x < n; ++x) {
            int count = 0;
            for (int y = 0; y < n; ++y) count += t[x + n * (y + n * z)];
            if (count > 1) ++thickColumns;
            if (x >= 3 && x <= 28 && z >= 3 && z <= 28) {
                ++interiorColumns;
                interiorOk += count == 1;
            }
        }
    EXPECT_EQ(thickColumns, 0u);
    EXPECT_EQ(interiorOk, interiorColumns);
    // The conservative voxelization of a plane in the middle of a voxel layer is the same single layer
    // inside, plus the partly covered edge columns' neighbours: a superset.
    for (size_t i = 0; i < t.size(); ++i) {
        if (t[i]) {
            ASSERT_TRUE(c[i]) << "thin voxel " << i << " missing from the conservative set";
        }
    }
    EXPECT_GE(countSet(c), countSet(t));
}

TEST_F(VctGpuTest, HybridSplitsTrianglesByProjectedArea) {
    auto scene = loadScene("two-rooms");
    ASSERT_TRUE(scene.ok());
    auto run = [&](const std::string& cutoff) {
        auto p = makePipeline(*scene, "vct", {{"cutoff", cutoff}, {"binary", "true"}, {"resolution", "32"}}, 16);
        return p->renderFrame(0).counters;
    };
    const Counters small = run("0.5"), large = run("64");
    const double triangles = small.at("triangles");
    // Every triangle is classified once: pass 1 voxelizes it or pass 2 receives it.
    EXPECT_EQ(small.at("trianglesPass1") + small.at("trianglesPass2"), triangles);
    EXPECT_EQ(large.at("trianglesPass1") + large.at("trianglesPass2"), triangles);
    // A larger cutoff keeps more triangles in pass 1 (two-rooms has triangles from under 1 to over
    // 64 voxels^2 at 32^3).
    EXPECT_GT(large.at("trianglesPass1"), small.at("trianglesPass1"));
    EXPECT_GT(small.at("trianglesPass2"), 0.0);
}

TEST_F(VctGpuTest, SparseMipmappingEqualsDense) {
    // cornell-box-dynamic over 4 frames: from frame 1 the sparse path clears only the voxels the last
    // frame listed (passes.glsl VCT_PASS 5), so voxels the spot and the turning block leave must be
    // zeroed through the lists; a stale voxel would differ from the dense path, which clears everything.
    auto scene = loadScene("cornell-box-dynamic");
    ASSERT_TRUE(scene.ok());
    for (const char* storage : {"iso", "aniso", "sh-f32", "sh-u8"}) {
        auto run = [&](const char* sparse) {
            auto p = makePipeline(*scene, "vct", {{"storage", storage}, {"sparseMip", sparse}, {"resolution", "32"}}, 32);
            for (uint32_t f = 0; f < 4; ++f) p->renderFrame(f * 6);
            return p->readback(Component::Indirect);
        };
        const Image sparse = run("true"), dense = run("false");
        ASSERT_GT(totalRadiance(dense), 0.0) << storage;
        // The same voxels are filtered by the same code: identical up to the order of float atomics.
        EXPECT_LT(relativeRmsError(sparse, dense), 1e-5) << storage;
    }
}

TEST_F(VctGpuTest, ShMipmapMatchesTheCpuFaceProjection) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    auto p = makePipeline(*scene, "vct", {{"storage", "sh-f32"}, {"resolution", "32"}}, 16);
    p->renderFrame(0);
    VctTechnique& v = vctOf(*p);
    const int n = 32, h = 16;
    std::vector<std::vector<float>> level0(12), level1(12);
    for (int c = 0; c < 12; ++c) {
        level0[c] = v.downloadVolume(c, 0);
        level1[c] = v.downloadVolume(c, 1);
    }
    const std::vector<uint32_t> alpha0 = v.downloadIso(0);
    size_t parents = 0;
    double maxError = 0.0, maxValue = 0.0;
    for (int z = 0; z < h; ++z)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < h; ++x) {
                std::array<std::optional<vct::ShRgb>, 8> children;
                bool any = false;
                for (int i = 0; i < 8; ++i) {
                    const int cx = 2 * x + (i & 1), cy = 2 * y + ((i >> 1) & 1), cz = 2 * z + ((i >> 2) & 1);
                    const size_t k = static_cast<size_t>(cx + n * (cy + n * cz));
                    if ((alpha0[k] >> 24) == 0) continue;
                    vct::ShRgb sh;
                    sh.r = {level0[0][k], level0[1][k], level0[2][k], level0[3][k]};
                    sh.g = {level0[4][k], level0[5][k], level0[6][k], level0[7][k]};
                    sh.b = {level0[8][k], level0[9][k], level0[10][k], level0[11][k]};
                    children[static_cast<size_t>(i)] = sh;
                    any = true;
                }
                if (!any) continue;
                ++parents;
                const vct::ShRgb expected = vct::shMipParent(children, true);
                const size_t k = static_cast<size_t>(x + h * (y + h * z));
                const glm::vec4 got[3] = {{level1[0][k], level1[1][k], level1[2][k], level1[3][k]},
                                          {level1[4][k], level1[5][k], level1[6][k], level1[7][k]},
                                          {level1[8][k], level1[9][k], level1[10][k], level1[11][k]}};
                const glm::vec4 want[3] = {expected.r, expected.g, expected.b};
                for (int c = 0; c < 3; ++c)
                    for (int j = 0; j < 4; ++j) {
                        maxError = std::max(maxError, double(std::abs(got[c][j] - want[c][j])));
                        maxValue = std::max(maxValue, double(std::abs(want[c][j])));
                    }
            }
    ASSERT_GT(parents, 100u);
    ASSERT_GT(maxValue, 0.0);
    // Float sums of up to 48 terms in a different order on the GPU: relative 1e-5 of the largest.
    EXPECT_LT(maxError, 1e-5 * maxValue) << "max error " << maxError << " of " << maxValue;
}

TEST_F(VctGpuTest, IsotropicMipIsThePremultipliedMeanOfTheChildren) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    auto p = makePipeline(*scene, "vct", {{"storage", "iso"}, {"resolution", "32"}}, 16);
    p->renderFrame(0);
    VctTechnique& v = vctOf(*p);
    const auto l0 = v.downloadIso(0), l1 = v.downloadIso(1);
    const int n = 32, h = 16;
    int worst = 0;
    size_t occupied = 0;
    for (int z = 0; z < h; ++z)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < h; ++x) {
                glm::vec4 sum(0.0f);
                for (int i = 0; i < 8; ++i) {
                    const uint32_t c = l0[static_cast<size_t>((2 * x + (i & 1)) + n * ((2 * y + ((i >> 1) & 1)) + n * (2 * z + ((i >> 2) & 1))))];
                    sum += glm::vec4(c & 0xFF, (c >> 8) & 0xFF, (c >> 16) & 0xFF, (c >> 24) & 0xFF);
                }
                const glm::vec4 expected = sum / 8.0f;
                const uint32_t g = l1[static_cast<size_t>(x + h * (y + h * z))];
                const glm::vec4 got(g & 0xFF, (g >> 8) & 0xFF, (g >> 16) & 0xFF, (g >> 24) & 0xFF);
                occupied += expected.a > 0.0f;
                for (int j = 0; j < 4; ++j) worst = std::max(worst, int(std::lround(std::abs(got[j] - expected[j]))));
            }
    ASSERT_GT(occupied, 100u);
    // One 8-bit step: the GPU rounds the float mean to the nearest of 256 levels.
    EXPECT_LE(worst, 1);
}

TEST_F(VctGpuTest, IndirectLightAgainstTheOneBounceReference) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const Image ref = oneBounceReference(*scene, kSize, 0, 256);
    const double refMean = meanOf(ref);
    ASSERT_GT(refMean, 0.0);
    // Measured on llvmpipe (64^3 grid, 64^2 image, 256-spp reference; bench/results/vct-tests-*.json):
    // relMSE iso 0.078, aniso 0.045, sh-f32 0.065, sh-u8 0.081; image mean / reference iso 0.77,
    // aniso 0.94, sh-f32 0.95, sh-u8 0.75. relMSE bounds at ~1.25x the measurement (the reference's
    // 256-spp noise moves it by a few per cent): the default (aniso) fails its bound with the tangent
    // cap off (self-light), the transmittance blend off or a halved injection; every format's light
    // stays within the fidelity bound of its measurement (sh-u8's 8-bit range loses the dim levels).
    const std::map<std::string, double> bound = {{"iso", 0.1}, {"aniso", 0.056}, {"sh-f32", 0.082}, {"sh-u8", 0.1}};
    std::map<std::string, double> mean;
    for (const auto& [storage, b] : bound) {
        const Image img = renderIndirect(*scene, "vct", {{"storage", storage}}, kSize);
        ASSERT_TRUE(finiteAndNonNegative(img)) << storage;
        const double e = relMse(img, ref);
        mean[storage] = meanOf(img) / refMean;
        RecordProperty(storage + "_relMse", std::to_string(e));
        RecordProperty(storage + "_meanRatio", std::to_string(mean[storage]));
        EXPECT_LT(e, b) << storage;
    }
    // The default storage within the fidelity bound (+-15 %, DEVELOPERS.md): measured 0.94.
    EXPECT_NEAR(mean["aniso"], 1.0, 0.15);
    EXPECT_NEAR(mean["sh-f32"], 1.0, 0.15);
}

TEST_F(VctGpuTest, FollowsTheMovingLightAndBlockOfCornellBoxDynamic) {
    auto scene = loadScene("cornell-box-dynamic");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 48;
    auto p = makePipeline(*scene, "vct", {{"storage", "aniso"}}, kSize);
    Image first, last;
    double worst = 0.0;
    for (uint32_t frame : {0u, 15u, 30u}) {
        p->renderFrame(frame);
        const Image img = p->readback(Component::Indirect);
        const Image ref = oneBounceReference(*scene, kSize, frame, 128);
        const double e = relMse(img, ref);
        worst = std::max(worst, e);
        RecordProperty("relMse_frame" + std::to_string(frame), std::to_string(e));
        if (frame == 0) first = img;
        last = img;
    }
    // Re-voxelized every frame: the indirect light moves with the spot (a volume frozen after frame 0
    // keeps frame 0's light and fails the bound at frame 30: 0.34 before issue 28). Measured 0.061 /
    // 0.087 / 0.048 at frames 0 / 15 / 30, 48^2 (bench/results/vct-tests-*.json); 0.12 is 1.4x the worst.
    EXPECT_LT(worst, 0.12);
    EXPECT_GT(relativeRmsError(last, first), 0.05);
}

TEST_F(VctGpuTest, SphereWithACentralPointLightGivesTheAnalyticBounce) {
    // A closed inward-facing sphere of radius R, albedo rho, point light I at its centre: every point
    // receives E0 = I / R^2 and reflects L1 = rho I / (pi R^2), and sees L1 in every direction, so the
    // one-bounce indirect radiance is rho L1 (analytic-tests.md, "sphere furnace").
    constexpr float R = 1.0f, rho = 0.5f, I = glm::pi<float>();
    Scene s;
    s.name = "sphere-furnace";
    Mesh sphere;
    sphere.name = "sphere";
    constexpr int kU = 48, kV = 24;
    for (int j = 0; j <= kV; ++j)
        for (int i = 0; i <= kU; ++i) {
            const float phi = 2.0f * glm::pi<float>() * float(i) / kU, theta = glm::pi<float>() * float(j) / kV;
            const glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            sphere.positions.push_back(R * d);
            sphere.normals.push_back(-d);  // facing the centre
        }
    auto at = [&](int i, int j) { return static_cast<uint32_t>(i + (kU + 1) * j); };
    for (int j = 0; j < kV; ++j)
        for (int i = 0; i < kU; ++i) {
            // Wound counter-clockwise seen from the centre, as the normals face (the G-buffer turns the
            // normal of a two-sided surface's back face around, so a mesh wound against its normals
            // would send the cones outwards); the pole rows keep only their non-degenerate triangle.
            if (j > 0) sphere.indices.insert(sphere.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j)});
            if (j < kV - 1) sphere.indices.insert(sphere.indices.end(), {at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)});
        }
    s.meshes.push_back(sphere);
    Material m;
    m.name = "grey";
    m.baseColor = glm::vec3(rho);
    m.twoSided = true;  // lit and seen from the inside whichever way the winding faces
    s.materials.push_back(m);
    Object o;
    o.name = "sphere";
    s.objects.push_back(o);
    Light l;
    l.type = LightType::Point;
    l.position = glm::vec3(0.0f);
    l.intensity = glm::vec3(I);
    s.lights.push_back(l);
    s.camera.position = {0.0f, 0.0f, 0.5f};
    s.camera.target = {0.0f, 0.0f, -1.0f};
    s.camera.verticalFov = glm::radians(60.0f);
    s.camera.nearPlane = 0.01f;
    s.camera.farPlane = 4.0f;
    ASSERT_TRUE(finalizeScene(s).ok());
    const double expected = rho * rho * I / (glm::pi<float>() * R * R);
    std::map<std::string, double> got;
    for (const char* storage : {"iso", "aniso", "sh-f32"}) {
        const Image img = renderIndirect(s, "vct", {{"storage", storage}, {"resolution", "64"}, {"specular", "false"}}, 32);
        got[storage] = meanOf(img) / expected;
        RecordProperty(std::string(storage) + "_ratio", std::to_string(got[storage]));
    }
    // Measured ratios on llvmpipe at 64^3 (bench/results/vct-tests-*.json): iso 0.92, aniso 0.85,
    // sh-f32 0.85. The shortfall is light that cones carry through the shell where it is crossed
    // obliquely at a coarse level (docs/techniques/vct.md, "Where the light goes"). Bounds: 0.1 under
    // each measurement (llvmpipe and GPU filtering may differ by a few per cent) and no gain: a halved
    // injection (0.46) or a missing opacity (cones through every wall) fails them.
    EXPECT_GT(got["iso"], 0.82);
    EXPECT_LT(got["iso"], 1.05);
    EXPECT_GT(got["aniso"], 0.75);
    EXPECT_LT(got["aniso"], 1.05);
    EXPECT_GT(got["sh-f32"], 0.75);
    EXPECT_LT(got["sh-f32"], 1.05);
}

TEST_F(VctGpuTest, CountersReportStorageSizes) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    // Thesis R8: bytes per level-0 voxel iso 4 : aniso 24 : SH-F32 48 : SH-U8 12 (+ opacity).
    const std::map<std::string, double> bytes = {{"iso", 4}, {"aniso", 24}, {"sh-f32", 48}, {"sh-u8", 12}};
    for (const auto& [storage, b] : bytes) {
        auto p = makePipeline(*scene, "vct", {{"storage", storage}, {"resolution", "16"}}, 16);
        const Counters c = p->renderFrame(0).counters;
        EXPECT_EQ(c.at("bytesPerVoxel"), b) << storage;
        EXPECT_GT(c.at("activeVoxels"), 0.0);
        EXPECT_GT(c.at("voxelWrites"), c.at("activeVoxels") * 0.99);
    }
}

TEST_F(VctGpuTest, DebugViewsShowTheVolume) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    const Image occupancy = renderIndirect(*scene, "vct", {{"debugView", "occupancy"}, {"resolution", "32"}}, 32);
    const Image ao = renderIndirect(*scene, "vct", {{"debugView", "ao"}, {"resolution", "32"}}, 32);
    // The camera looks into the box through its open side: most rays meet an occupied voxel, each
    // pixel is 0 or 1.
    EXPECT_GT(meanOf(occupancy), 0.8);
    for (int y = 0; y < occupancy.height(); ++y)
        for (int x = 0; x < occupancy.width(); ++x) {
            const float v = occupancy.at(x, y).r;
            ASSERT_TRUE(v == 0.0f || v == 1.0f) << v;
        }
    double lo = 1.0, hi = 0.0;
    for (int y = 0; y < ao.height(); ++y)
        for (int x = 0; x < ao.width(); ++x) lo = std::min(lo, double(ao.at(x, y).r)), hi = std::max(hi, double(ao.at(x, y).r));
    EXPECT_GE(lo, 0.0);
    EXPECT_LE(hi, 1.0 + 1e-6);
    EXPECT_LT(lo, hi);  // corners are more occluded than open floor
}

TEST_F(VctGpuTest, BadSettingsAreOneLineErrors) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    auto fails = [&](const std::map<std::string, std::string>& settings, const std::string& needle) {
        auto t = createTechnique("vct");
        ASSERT_TRUE(t.ok());
        ASSERT_TRUE(applySettings(**t, settings, "vct").ok());
        auto p = Pipeline::create(*scene, std::move(*t), {16, 16}, smallRenderSettings());
        ASSERT_FALSE(p.ok());
        EXPECT_NE(p.error().message.find(needle), std::string::npos) << p.error().message;
        EXPECT_EQ(p.error().message.find('\n'), std::string::npos);
    };
    fails({{"resolution", "48"}}, "power of two");
    fails({{"cutoff", "0.1"}}, "cutoff");
    fails({{"resolution", "512"}, {"storage", "sh-f32"}, {"memoryBudgetMiB", "1024"}}, "memoryBudgetMiB");
}

TEST_F(VctGpuTest, ConeShadowsMatchTheDirectReference) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    PathTracerSettings pts;
    pts.width = pts.height = kSize;
    pts.samplesPerPixel = 256;
    pts.bounces = 0;
    auto tracer = PathTracer::create(*scene, pts);
    ASSERT_TRUE(tracer.ok());
    const Image ref = tracer->render().radiance;
    auto p = makePipeline(*scene, "vct", {{"coneShadows", "true"}, {"shadowAperture", "2"}}, kSize);
    EXPECT_TRUE(p->technique().ownsDirect());
    const FrameStats stats = p->renderFrame(0);
    // The shared shadow-mapped pass does not run when the technique owns the direct light.
    for (const gl::PassTime& t : stats.passes) EXPECT_NE(t.name, "direct");
    const Image direct = p->readback(Component::Direct);
    const double e = relMse(direct, ref);
    RecordProperty("coneShadowRelMse", std::to_string(e));
    // Measured 0.008 at 128^2 (shadow maps: 0.004): the cone's shadow is soft and the 64^3 volume
    // blurs the block's edges. Without visibility (the block's shadows lit) the error is many times
    // larger; 0.015 is ~1.5x the measurement (256-spp reference noise).
    EXPECT_LT(e, 0.015);
}

TEST_F(VctGpuTest, LightLeakOfEachStorageOnTwoRooms) {
    auto scene = loadScene("two-rooms");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    constexpr float kWallHalfThickness = 0.01f;  // two-rooms' default 2 cm wall
    std::map<std::string, double> leak;
    for (const char* storage : {"iso", "aniso", "sh-f32", "sh-u8"}) {
        auto p = makePipeline(*scene, "vct", {{"storage", storage}}, kSize);
        p->renderFrame(0);
        const TwoRoomsMasks masks = twoRoomsMasks(readTexture(p->gbuffer().position()), kWallHalfThickness);
        auto score = lightLeakScore(p->readback(Component::Full), masks.dark, masks.lit);
        ASSERT_TRUE(score.ok()) << score.error().message;
        leak[storage] = *score;
        RecordProperty(std::string(storage) + "_leak", std::to_string(*score));
        // A leak-free renderer scores 0 (the dark room receives no light by any path). The 2 cm wall
        // is a third of a 64^3 voxel, so the lit side's radiance is averaged into voxels the dark side
        // also sees: every format leaks, none may make the dark room brighter than a tenth of the lit.
        EXPECT_GE(*score, 0.0);
        EXPECT_LT(*score, 0.1) << storage;
    }
}

TEST_F(VctGpuTest, InjectionIsTheReflectedRadianceOfTheLight) {
    // Eq. 7.1 radiometrically: a voxel of a Lambertian plane (albedo rho) stores L = rho / pi * E at
    // its column centre. SH-F32 keeps it in float: level-0 DC = L / Y00 (no 8-bit range).
    constexpr float kHeight = 1.0f;  // metres, light above the plane
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.irradiance = glm::vec3(3.0f);
    Light point;
    point.type = LightType::Point;
    point.position = {0.0f, kHeight, 0.0f};
    point.intensity = glm::vec3(2.0f);
    for (const Light& light : {sun, point}) {
        for (const char* voxelizer : {"triangle", "fragment"}) {
            const Scene scene = gputest::planeScene(light);
            auto p = makePipeline(scene, "vct", {{"storage", "sh-f32"}, {"voxelizer", voxelizer}, {"resolution", "32"},
                                                 {"boxSide", "4.8"}, {"boxCentreY", "0.045"}}, 16);
            p->renderFrame(0);
            VctTechnique& v = vctOf(*p);
            const std::vector<float> dc = v.downloadVolume(0, 0);  // red DC coefficients
            const std::vector<uint32_t> iso = v.downloadIso(0);
            const glm::mat4 worldFromVoxel = glm::inverse(v.voxelFromWorld());
            const int n = 32;
            size_t checked = 0;
            double worst = 0.0;
            for (int z = 0; z < n; ++z)
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x) {
                        const size_t k = static_cast<size_t>(x + n * (y + n * z));
                        if ((iso[k] >> 24) == 0) continue;
                        // The column centre on the plane y = 0 (the plane's dominant axis is y).
                        const glm::vec3 w = glm::vec3(worldFromVoxel * glm::vec4(x + 0.5f, 0.0f, z + 0.5f, 1.0f));
                        if (std::abs(w.x) > gputest::kPlaneHalf - 0.2f || std::abs(w.z) > gputest::kPlaneHalf - 0.2f) continue;
                        double e = 3.0;
                        if (light.type == LightType::Point) {
                            const double d2 = double(w.x) * w.x + double(w.z) * w.z + double(kHeight) * kHeight;
                            e = 2.0 * kHeight / (d2 * std::sqrt(d2));
                        }
                        const double expected = gputest::kPlaneAlbedo / glm::pi<double>() * e;
                        const double got = double(dc[k]) * vct::kShY00;
                        worst = std::max(worst, std::abs(got - expected) / expected);
                        ++checked;
                    }
            ASSERT_GT(checked, 400u) << voxelizer;
            // Float arithmetic and the shadow map's bias sample at the same point: 1e-3 relative.
            EXPECT_LT(worst, 1e-3) << voxelizer << " light type " << int(light.type);
        }
    }
}
