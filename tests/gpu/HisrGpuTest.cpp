// `hisr` (Nichols 2010 §4.2.4): with a zero-size threshold and full depth the traversal visits every
// RSM texel and the image equals the every-texel rsm gather; with the defaults it stays close to the
// converged limit; every built-in scene renders; the stencil culls the gather (only stencilled
// fragments walk the tree).
#include "GpuTestSupport.h"
#include "NicholsTestSupport.h"
#include "techniques/hisr/HisrTechnique.h"

#include <algorithm>
#include <cmath>

using namespace bounce;
using namespace bounce::nicholstest;

namespace {
class HisrGpuTest : public gputest::GpuTest {};
}  // namespace

namespace {

// hisr/gather.glsl's walk of one cell, on the CPU: Eq. 4.8 with T_l = 2 (1 - tau) / (3 tau res_l^2) at
// each level l of the tree, the accepted nodes gathered with the disk-to-point form factor (vpl.glsl).
glm::vec3 walkTree(const std::vector<glm::vec4>& tree, const std::vector<int>& offsets, const std::vector<int>& sides,
                   int rootLevel, int rootsPerLayer, int layers, int maxDepth, float tau, glm::vec3 x, glm::vec3 n) {
    glm::vec3 irradiance(0.0f);
    const int finest = std::max(rootLevel - maxDepth, 0);
    for (int root = 0; root < layers * rootsPerLayer; ++root) {
        const int layer = root / rootsPerLayer;
        int m = root - layer * rootsPerLayer, level = rootLevel;
        while (true) {
            const size_t index =
                static_cast<size_t>(offsets[static_cast<size_t>(level)] + layer * (rootsPerLayer << (2 * (rootLevel - level))) + m) * 4;
            const glm::vec4 head = tree[index];
            bool refine = false;
            if (head.w >= 0.0f && level > finest) {
                const float res = static_cast<float>(sides[static_cast<size_t>(level)]);
                const float t = 2.0f * (1.0f - tau) / (3.0f * tau * res * res);
                const glm::vec3 d = glm::vec3(head) - x;
                refine = glm::dot(d, d) <= t * head.w * head.w;
            }
            if (refine) {
                m *= 4;
                level -= 1;
                continue;
            }
            if (head.w >= 0.0f) {
                const glm::vec4 position = tree[index + 1], normal = tree[index + 2], flux = tree[index + 3];
                const glm::vec3 d = glm::vec3(position) - x;
                const float r2 = std::max(glm::dot(d, d), 1e-12f);
                const glm::vec3 l = d / std::sqrt(r2);
                const float cosReceiver = std::max(glm::dot(n, l), 0.0f), cosSender = std::max(glm::dot(glm::vec3(normal), -l), 0.0f);
                irradiance += glm::vec3(flux) * (cosReceiver * cosSender / (3.14159265358979f * r2 + normal.w));
            }
            while (level < rootLevel && (m & 3) == 3) {
                m >>= 2;
                level += 1;
            }
            if (level == rootLevel) break;
            m += 1;
        }
    }
    return irradiance;
}

}  // namespace

// The gather's per-level Eq. 4.8 against a CPU walk of the same tree (downloaded) from the same cells
// (eye pyramid level 0: eyeCoarsest = image size, so every covered pixel gathers at level 0), for each
// gather pass and two tau. This pins T_l per level: llvmpipe's textureSize with a level that differs
// between SIMD lanes returned the first lane's size, so lanes walking other levels refined with the wrong
// T_l (hisr.md); mutations: res_l = the root level's side for every level, or tau x 2 in the shader.
TEST_F(HisrGpuTest, GatherWalksEq48PerLevelAsTheCpuDoes) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 32;
    for (const char* pass : {"compute", "stencil"}) {
        for (const char* tau : {"0.01", "0.003"}) {
            SCOPED_TRACE(std::string(pass) + " tau " + tau);
            auto p = makePipeline(*scene, "hisr",
                                  {{"rsmSize", "64"}, {"rootGrid", "16"}, {"maxDepth", "2"}, {"tau", tau}, {"eyeCoarsest", "32"},
                                   {"gatherPass", pass}},
                                  kSize);
            const FrameStats stats = p->renderFrame(0);
            const auto& hisr = dynamic_cast<const HisrTechnique&>(p->technique());
            const nichols::MinMaxPyramid& light = hisr.lightPyramid();
            const int rootLevel = light.levels() - 1;
            ASSERT_EQ(rootLevel, 2);  // 64^2 RSM, 16^2 roots
            std::vector<int> sides;
            for (int k = 0; k <= rootLevel; ++k) sides.push_back(light.levelSize(k).x);
            std::vector<glm::vec4> tree(hisr.treeRecords().size() / sizeof(glm::vec4));
            hisr.treeRecords().download(0, tree.size() * sizeof(glm::vec4), tree.data());
            const std::vector<glm::vec4> geometry = readLevel(hisr.eyePyramid().geometry(), 0, {kSize, kSize});
            const std::vector<glm::vec4> normals = readLevel(hisr.eyePyramid().normal(), 0, {kSize, kSize});
            const gl::Texture& atlasTexture = hisr.buffer().atlas();
            const std::vector<glm::vec4> atlas = readLevel(atlasTexture, 0, {atlasTexture.width(), atlasTexture.height()});
            const int rootsPerLayer = light.levelSize(rootLevel).x * light.levelSize(rootLevel).y;
            int cells = 0, off = 0;
            double gpuSum = 0.0, cpuSum = 0.0;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const glm::vec4 g = geometry[static_cast<size_t>(y) * kSize + x];
                    if (g.w <= 0.0f) continue;
                    const glm::vec3 position = glm::vec3(g) / g.w;
                    const glm::vec3 normal = glm::normalize(glm::vec3(normals[static_cast<size_t>(y) * kSize + x]) + glm::vec3(0, 0, 1e-12f));
                    const glm::vec3 cpu = walkTree(tree, hisr.treeLevelOffsets(), sides, rootLevel, rootsPerLayer, light.layers(), 2,
                                                   std::stof(tau), position, normal);
                    const glm::vec3 gpu = glm::vec3(atlas[static_cast<size_t>(y) * atlasTexture.width() + x]);
                    ++cells;
                    gpuSum += gpu.r + gpu.g + gpu.b;
                    cpuSum += cpu.r + cpu.g + cpu.b;
                    // float rounding of the same sums (1e-4 relative, 1e-6 W/m^2 absolute for unlit cells);
                    // a node whose Eq. 4.8 test lands within rounding of its bound may go either way,
                    // hence the few allowed outliers below
                    if (glm::length(gpu - cpu) > 1e-4f * glm::length(cpu) + 1e-6f) ++off;
                }
            ASSERT_GT(cells, kSize * kSize / 2);
            EXPECT_GT(stats.counters.at("nodesPerFragment"), 256.0);  // the walk descends below the roots
            EXPECT_LE(off, cells / 100) << off << " of " << cells << " cells differ";
            EXPECT_NEAR(gpuSum, cpuSum, 1e-4 * cpuSum);
        }
    }
}

TEST_F(HisrGpuTest, FullTraversalEqualsTheEveryTexelGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 32;
    // rsmSize 64, roots 16^2, depth 2: the leaves are the 64^2 texels. tau -> 0 makes T huge, so every
    // node refines; eyeCoarsest = image size keeps one level (every pixel gathers for itself).
    const Image hisr = renderIndirect(*scene, "hisr",
                                      {{"rsmSize", "64"}, {"rootGrid", "16"}, {"maxDepth", "2"}, {"tau", "1e-6"}, {"eyeCoarsest", "32"}},
                                      kSize);
    const Image rsm = renderIndirect(*scene, "rsm", {{"rsmSize", "64"}, {"vplGrid", "64"}}, kSize);
    ASSERT_GT(totalRadiance(rsm), 0.0);
    // Same VPLs, same form factor; only the summation order differs (float rounding).
    EXPECT_LT(relativeRmsError(hisr, rsm), 1e-4);
}

TEST_F(HisrGpuTest, DefaultsStayCloseToTheEveryTexelGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    const Image& limit = convergedLimit("cornell-box", kSize);
    const Image hisr = renderIndirect(*scene, "hisr", {{"rsmSize", "128"}}, kSize);
    const double error = relativeRmsError(hisr, limit);
    RecordProperty("hisrRelRms", std::to_string(error));
    // Thesis R6: 5-6 % RMS at 1024^2. Measured here 10.9 % against the 256^2 every-texel limit (64^2
    // image: the coarse eye levels cover more of the screen; a 128^2 RSM alone is 5.5 % off the limit;
    // tau and maxDepth are this implementation's defaults). Bound: measured plus ~20 %.
    EXPECT_LT(error, 0.13);
}

TEST_F(HisrGpuTest, EnergyDoesNotGrowWithTreeDepth) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    constexpr int kSize = 64;
    // rsmSize 128 with 16^2 roots: depth 3 reaches the texels. eyeCoarsest = image size keeps the eye
    // side at full resolution, so only the light hierarchy changes.
    std::vector<double> energies;
    for (int depth : {0, 1, 2, 3}) {
        const double energy = totalRadiance(renderIndirect(
            *scene, "hisr", {{"rsmSize", "128"}, {"rootGrid", "16"}, {"maxDepth", std::to_string(depth)}, {"eyeCoarsest", "64"}},
            kSize));
        RecordProperty("energyDepth" + std::to_string(depth), std::to_string(energy));
        ASSERT_GT(energy, 0.0);
        energies.push_back(energy);
    }
    // A node carries the summed flux of its texels, so descending only changes where that flux is shot
    // from; it never adds any. Measured: 431.5, 449.2, 457.7, 458.7 for depths 0..3 — a coarse node
    // shot from one sample under-lights the receivers close to it (5.9 % at depth 0).
    const double deepest = energies.back();
    for (size_t d = 0; d < energies.size(); ++d) {
        // 0.5 %: float summation order between depths (measured 0.02 %); anything above is energy created.
        EXPECT_LE(energies[d], deepest * 1.005) << "depth " << d;
        // 8 %: the near-field loss of coarse nodes (measured 5.9 % at depth 0) with margin.
        EXPECT_GE(energies[d], deepest * 0.92) << "depth " << d;
    }
}

TEST_F(HisrGpuTest, EveryBuiltinSceneRendersFiniteIndirectLight) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        auto scene = loadScene(info.name);
        ASSERT_TRUE(scene.ok()) << info.name;
        if (scene->hasEmissiveMaterials()) {  // furnace: lit by emission only
            expectRefusesEmissiveScene(*scene, "hisr");
            continue;
        }
        const Image indirect = renderIndirect(*scene, "hisr", {{"rsmSize", "32"}, {"maxDepth", "1"}}, 32);
        EXPECT_TRUE(finiteAndNonNegative(indirect)) << info.name;
    }
}

// The gather draws a full rectangle per atlas level and relies on the stencil set-up to shade only the
// cells chosen at that level. gather.frag writes counters (SSBO atomics), and a fragment shader with
// side effects gets its depth/stencil tests after it runs unless it declares early_fragment_tests (GL
// 4.5, "Early Per-Fragment Tests"): without the qualifier every fragment of every level rectangle walks
// the tree, and the stencil only masks the colour write. Mutation check: remove
// `layout(early_fragment_tests) in;` from shaders/techniques/hisr/gather.frag (or point
// BOUNCE_SHADER_DIR at an edited copy) and both configurations fail (measured on llvmpipe: 5376
// invocations for 2257 stencilled fragments at 64^2, 3840 for 3 draws x 890 at 32^2: the whole
// rectangles).
// gatherPass=compute lists the cells the stencil would mark and gathers them in a compute dispatch:
// the same cells, the same walks, so the same image and counts (float rounding only: the same sums in
// the same order per cell). With vplVisibility and deep trees the walk is split over several dispatches,
// which accumulate into the atlas (u_accumulate).
TEST_F(HisrGpuTest, ComputeGatherEqualsTheStencilledGather) {
    for (const char* sceneName : {"cornell-box", "cornell-box-dynamic"}) {
        auto scene = loadScene(sceneName);
        ASSERT_TRUE(scene.ok());
        for (const char* visibility : {"false", "true"}) {
            SCOPED_TRACE(std::string(sceneName) + ", visibility " + visibility);
            std::map<std::string, std::string> settings = {{"vplVisibility", visibility}, {"gatherPass", "stencil"}};
            auto stencil = makePipeline(*scene, "hisr", settings, 48);
            settings["gatherPass"] = "compute";
            auto compute = makePipeline(*scene, "hisr", settings, 48);
            const Counters a = stencil->renderFrame(1).counters, b = compute->renderFrame(1).counters;
            const Image x = stencil->readback(Component::Indirect), y = compute->readback(Component::Indirect);
            ASSERT_GT(totalRadiance(x), 0.0);
            EXPECT_LT(relativeRmsError(y, x), 1e-6);
            EXPECT_EQ(b.at("gatherFragments"), a.at("gatherFragments"));
            EXPECT_EQ(b.at("nodesPerFragment"), a.at("nodesPerFragment"));
            EXPECT_EQ(b.at("gatherDraws"), a.at("gatherDraws"));
        }
    }
}

TEST_F(HisrGpuTest, StencilCullsTheGather) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok());
    struct Case {
        int size, rsmSize, rootGrid, maxDepth;
        double draws;
    };
    // One draw (defaults' shape, 3 eye levels), and 64^2 roots at depth 2: 4096 roots in draws of 1524
    // (the loop budget, HisrTechnique.cpp), so the count is summed over several draws.
    // gatherPass=compute: the same count, from invocations past the cell list's end returning first.
    for (const char* pass : {"stencil", "compute"})
    for (const Case& c : {Case{64, 64, 16, 2, 1.0}, Case{32, 256, 64, 2, 3.0}}) {
        SCOPED_TRACE(std::string(pass) + ", size " + std::to_string(c.size) + ", rootGrid " + std::to_string(c.rootGrid));
        auto p = makePipeline(*scene, "hisr",
                              {{"rsmSize", std::to_string(c.rsmSize)},
                               {"rootGrid", std::to_string(c.rootGrid)},
                               {"maxDepth", std::to_string(c.maxDepth)},
                               {"eyeCoarsest", "16"},
                               {"gatherPass", pass}},
                              c.size);
        const Counters counters = p->renderFrame(0).counters;
        const double fragments = counters.at("gatherFragments"), draws = counters.at("gatherDraws");
        ASSERT_EQ(draws, c.draws);
        // The level rectangles hold more fragments than the stencil passes (each covered pixel is
        // stencilled at exactly one level), so shading the rejected ones would show.
        double rectangles = 0.0;
        for (int s = c.size; s >= 16; s /= 2) rectangles += double(s) * s;
        ASSERT_GT(fragments, 0.0);
        ASSERT_LT(fragments, rectangles);
        // Exact: one invocation per fragment that passed the stencil (GL_SAMPLES_PASSED of the same
        // draw, single-sampled) in every draw; helper invocations' atomics have no effect (GLSL 4.50,
        // gl_HelperInvocation), so no tolerance is needed.
        EXPECT_EQ(counters.at("gatherInvocations"), fragments * draws);
        // No fragment walks more than every node above the depth limit: rootGrid^2 roots (one RSM layer,
        // a spot) x (4^(d+1) - 1) / 3 nodes each.
        const double nodesPerRoot = double((1 << (2 * (c.maxDepth + 1))) - 1) / 3.0;
        EXPECT_LE(counters.at("nodesPerFragment"), double(c.rootGrid) * c.rootGrid * nodesPerRoot);
        EXPECT_GT(counters.at("nodesPerFragment"), 0.0);
    }
}
