// `hisr` — hierarchical image-space radiosity (Nichols 2010 §4.2.4; Nichols, Shopf & Wyman 2009).
//
// Passes (timers after Table 4.1's rows): "rsm" (the RSM of light 0), "vpl-tree" (the per-frame VPL
// tree: the light-space min-max pyramid over the RSM with summed flux and area and max light distance
// per node, techniques/nichols/MinMaxPyramid), "min-max-mipmap" (eye space), "stencil-setup",
// "gather" (per fragment: traversal of the tree from the 16^2 roots with Eq. 4.8, at most maxDepth
// levels down, disk-to-point form factor per accepted node), "upsample" (§3.2.5, then x albedo/pi).
// Counters: fragments per level, tree nodes visited per gathered fragment, gather invocations. The
// eye-space passes are techniques/nichols/StencilledGather, shared with isr.
// With `vplVisibility` on (beyond the thesis, off by default; techniques/screen_voxels/VplVisibility.h) a
// "voxelize" pass voxelizes the camera's view and each accepted node's term is multiplied by a voxel
// march from the cell's patch to the node's VPL; fewer roots per draw keep the walk within the budget.
//
// Deviations (docs/techniques/hisr.md gives each its reason):
// - the tree is the RSM's mip chain itself (a 2D-array mipmap), not §4.2.4's cache-coherent re-layout.
// - Eq. 4.8 uses I = 1 (normalised light) and the node level's resolution for RSM_res.
// - tau and maxDepth defaults are assumptions.
#include "techniques/hisr/HisrTechnique.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/SetupLimits.h"
#include "gpu/ShaderLimits.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace bounce {

void HisrTechnique::visitSettings(SettingsVisitor& v) {
    v.field("rsmSize", m_rsmSize, "RSM resolution per side, a power of two (thesis 256)", 16, 2048);
    v.field("rootGrid", m_rootGrid, "VPL-tree roots per side (thesis 16)", 1, 2048);
    v.field("maxDepth", m_maxDepth, "tree levels below the roots a fragment may descend (thesis 1..3)", 0, 6);
    v.field("tau", m_tau, "Eq. 4.8 refinement threshold on the normalised contribution bound (assumption)", 1e-6f, 0.999f);
    v.field("eyeCoarsest", m_eyeCoarsest, "coarsest illumination-buffer level (thesis 16)", 1, 4096);
    v.field("upsampling", m_upsampling, nichols::kUpsampleFilterHelp, nichols::kUpsampleFilters);
    v.field("gatherPass", m_gatherPass, nichols::kGatherPassHelp, nichols::kGatherPasses, nichols::kGatherPassDefaults);
    v.field("depthThreshold", m_eyeThresholds.depth, "eye-space max relative depth derivative per pixel (assumption)", 0.0f, 1e9f);
    v.field("normalThreshold", m_eyeThresholds.normal, "eye-space normal component range, 0..2 (assumption)", 0.0f, 2.0f);
    v.field("edgeNeighbours", m_eyeThresholds.edgeNeighbours, "also test edge-adjacent cells (§3.4.2)");
    nichols::visitEyeSettings(v, m_eyeThresholds, m_indirectSize);
    m_visibilitySettings.visit(v);
}

Expected<void> HisrTechnique::setup(const SetupContext& ctx) {
    BOUNCE_TRY_VOID(nichols::checkIndirectSize(m_indirectSize, ctx.size));
    if ((m_rsmSize & (m_rsmSize - 1)) != 0) return makeError("setting rsmSize={} is not a power of two", m_rsmSize);
    if (m_rootGrid > m_rsmSize) return makeError("setting rootGrid={} exceeds rsmSize={}", m_rootGrid, m_rsmSize);
    {
        // The VPL tree: every light-pyramid level down to rootGrid (at most 4/3 of the base), 64 bytes a
        // node, one storage buffer also read as an RGBA32F buffer texture (issue 29 #6: rsmSize=1024 with a
        // cube RSM is 537 MB).
        const int layers = nichols::ReflectiveShadowMap::layersFor(ctx.scene);
        size_t nodes = 0;
        for (int side = m_rsmSize;; side /= 2) {  // MinMaxPyramid's levels: down to the first side <= rootGrid
            nodes += static_cast<size_t>(side) * static_cast<size_t>(side) * static_cast<size_t>(layers);
            if (side <= m_rootGrid || side == 1) break;
        }
        const std::string settings = fmt::format("setting rsmSize={}", m_rsmSize);
        const std::string what = fmt::format("hisr's VPL tree ({} nodes, {} RSM layers)", nodes, layers);
        const gl::GpuInfo& info = gl::Context::current()->info();
        BOUNCE_TRY_VOID(gl::checkStorageBuffer(info, nodes * kTreeRecordBytes, settings, what));
        BOUNCE_TRY_VOID(gl::checkTextureBuffer(info, nodes * kTreeRecordBytes / 16, settings, what));
    }
    BOUNCE_TRY(m_rsm, nichols::ReflectiveShadowMap::create());
    BOUNCE_TRY(m_light, nichols::MinMaxPyramid::create());
    BOUNCE_TRY(m_eye, nichols::StencilledGather::create());
    BOUNCE_TRY(m_visibility, voxels::VplVisibility::create(m_visibilitySettings));
    // One root is the smallest draw: its walk must fit the shader loop budget, or llvmpipe drops nodes.
    int rootLevel = 0;
    for (int side = m_rsmSize; side > m_rootGrid; side /= 2) ++rootLevel;
    const int walk = rootWalkIterations(std::min(m_maxDepth, rootLevel));
    if (walk + 1 > gl::shaderLoopIterationBudget())
        return makeError("maxDepth={}{}: one root's walk may take {} loop iterations, past the shader loop budget of {}; "
                         "lower maxDepth{}",
                         m_maxDepth, m_visibility->enabled() ? " with vplVisibility" : "", walk,
                         gl::shaderLoopIterationBudget(), m_visibility->enabled() ? ", voxelColumns or voxelBits" : "");
    // gatherPass: the stencilled draw (the thesis's) or the compute dispatch over the cell list (same sums).
    if (nichols::gatherPass(m_gatherPass) == nichols::GatherPass::Compute) {
        BOUNCE_TRY(m_gather, gl::Program::build({"hisr.gather", {{GL_COMPUTE_SHADER, "techniques/hisr/gather.comp"}}, m_visibility->defines()}));
    } else {
        BOUNCE_TRY(m_gather, gl::Program::build({"hisr.gather",
                                                 {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                  {GL_FRAGMENT_SHADER, "techniques/hisr/gather.frag"}},
                                                 m_visibility->defines()}));
    }

    BOUNCE_TRY(m_treeBuild, gl::Program::build({"hisr.tree", {{GL_COMPUTE_SHADER, "techniques/hisr/tree.comp"}}}));
    m_gatherCounts = gl::Buffer::create("hisr.gatherCounts", 3 * sizeof(uint32_t));
    return {};
}

int HisrTechnique::rootWalkIterations(int depth) const {
    // A root's walk visits at most (4^(d+1) - 1) / 3 nodes at depth d, each one iteration of the walk plus
    // at most one climbing iteration. llvmpipe counts a SIMD vector's iterations (VplVisibility.h), and
    // the lanes accept nodes at different steps, so with visibility every step of the walk may run one
    // visibility test.
    const int nodes = ((1 << (2 * (depth + 1))) - 1) / 3;
    return 2 * nodes * (1 + m_visibility->loopIterationsPerTest());
}

void HisrTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    {
        auto s = ctx.timers.scope("rsm");
        m_gathered = false;
        if (!m_rsm->render(ctx, m_rsmSize)) {
            m_eye->clear(indirect);
            return;
        }
    }
    {
        auto s = ctx.timers.scope("vpl-tree");
        // Flags are not used by the traversal; the thresholds only shape the (unused) refine chain.
        m_light->buildLight(*m_rsm, m_rootGrid, nichols::PyramidThresholds{});
        buildTree();
    }
    m_eye->prepare(ctx, m_eyeCoarsest, m_eyeThresholds, nichols::indirectScale(m_indirectSize, ctx.gbuffer.size()),
                   nichols::gatherPass(m_gatherPass));
    m_visibility->build(ctx);
    {
        auto s = ctx.timers.scope("gather");
        m_treeView.bind(BINDING_TEX_INPUT0);
        m_gatherCounts.clearZero();
        m_gatherCounts.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
        const int top = m_light->levels() - 1;
        m_gather.set("u_rootLevel", top);
        m_gather.set("u_maxDepth", m_maxDepth);
        m_gather.set("u_layers", m_light->layers());
        m_gather.set("u_rootsPerLayer", m_light->levelSize(top).x * m_light->levelSize(top).y);
        // Eq. 4.8's res_l per level (the shader forms T_l = 2 (1 - tau) / (3 tau res_l^2), I = 1).
        std::vector<int> sides(kMaxTreeLevels, 1);
        for (int k = 0; k <= top; ++k) sides[static_cast<size_t>(k)] = m_light->levelSize(k).x;
        m_gather.set("u_tau", m_tau);
        m_gather.set("u_levelOffset", m_treeOffsets);
        m_gather.set("u_levelSide", sides);
        m_visibility->setUniforms(m_gather);
        // Draws of as many roots as fit the shader loop budget (gpu/ShaderLimits.h), so deep trees are
        // walked whole on llvmpipe too.
        const int rootLevel = m_light->levels() - 1;
        const int rootsPerDraw =
            std::max(1, gl::shaderLoopIterationBudget() / (rootWalkIterations(std::min(m_maxDepth, rootLevel)) + 1));
        const glm::ivec2 roots = m_light->levelSize(rootLevel);
        const int rootCount = roots.x * roots.y * m_light->layers();
        const int batches = (rootCount + rootsPerDraw - 1) / rootsPerDraw;
        m_eye->gather(m_gather, batches, [&](int b) {
            m_gather.set("u_rootFirst", b * rootsPerDraw);
            m_gather.set("u_rootEnd", (b + 1) * rootsPerDraw);
        });
        ctx.counters["gatherDraws"] = static_cast<double>(batches);
    }
    m_eye->finish(ctx, indirect, nichols::upsampleFilter(m_upsampling));
    m_gathered = true;
}

void HisrTechnique::buildTree() {
    const int levels = m_light->levels();
    BOUNCE_CHECK(levels <= kMaxTreeLevels, "hisr's VPL tree has at most {} levels", kMaxTreeLevels);
    m_treeOffsets.assign(kMaxTreeLevels, 0);
    int records = 0;
    for (int k = 0; k < levels; ++k) {
        const glm::ivec2 side = m_light->levelSize(k);
        // Morton order needs square power-of-two levels: rsmSize is a power of two (setup) and halves.
        BOUNCE_CHECK(side.x == side.y && (side.x & (side.x - 1)) == 0, "VPL tree level {} is {}x{}", k, side.x, side.y);
        m_treeOffsets[static_cast<size_t>(k)] = records;
        records += side.x * side.y * m_light->layers();
    }
    const size_t bytes = static_cast<size_t>(records) * kTreeRecordBytes;
    if (!m_tree || m_tree.size() != bytes) {
        m_tree = gl::Buffer::create("hisr.tree", bytes);
        m_treeView = gl::Texture::createBufferView("hisr.treeView", m_tree, GL_RGBA32F);
    }
    m_light->geometry().bind(BINDING_TEX_INPUT0);
    m_light->normal().bind(BINDING_TEX_INPUT1);
    m_light->normalMax().bind(BINDING_TEX_INPUT2);
    m_light->flux().bind(BINDING_TEX_INPUT3);
    m_tree.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
    for (int k = 0; k < levels; ++k) {
        const int side = m_light->levelSize(k).x;
        m_treeBuild.set("u_level", k);
        m_treeBuild.set("u_levelOffset", m_treeOffsets[static_cast<size_t>(k)]);
        m_treeBuild.set("u_side", side);
        m_treeBuild.use();
        glDispatchCompute(static_cast<GLuint>((side + 7) / 8), static_cast<GLuint>((side + 7) / 8),
                          static_cast<GLuint>(m_light->layers()));
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void HisrTechnique::debugViews(std::vector<DebugView>& out) const {
    if (m_rsm) m_rsm->debugViews(out);
    if (!m_light || m_light->levels() == 0) return;  // the tree exists after the first frame
    const int rootLevel = m_light->levels() - 1;
    for (int depth = 0; depth <= std::min(m_maxDepth, rootLevel); ++depth) {
        // Smaller dots for the finer levels (4x the nodes per level), so that each level stays legible.
        const float dot = std::max(2.0f, 7.0f - 2.0f * static_cast<float>(depth));
        DebugView v{fmt::format("hisr.tree.depth{}", depth), &m_light->geometry(), DebugEncoding::ClusterPoints, dot};
        v.level = rootLevel - depth;
        out.push_back(std::move(v));
    }
}

void HisrTechnique::collectCounters(Counters& out) {
    if (!m_gathered) return;
    const double total = m_eye->collectCounters(out);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    // gather.frag's counters: visited nodes (low, high word) and its invocations over all draws.
    uint32_t counts[3] = {0, 0, 0};
    m_gatherCounts.download(0, sizeof(counts), counts);
    const double nodes = static_cast<double>((uint64_t{counts[1]} << 32) | counts[0]);
    out["nodesPerFragment"] = total > 0.0 ? nodes / total : 0.0;
    // = gatherFragments x gatherDraws when the stencil culls the gather (early fragment tests), more
    // when fragments the stencil rejects are shaded too (HisrGpuTest.StencilCullsTheGather).
    out["gatherInvocations"] = static_cast<double>(counts[2]);
    m_visibility->collectCounters(out);
}

}  // namespace bounce
