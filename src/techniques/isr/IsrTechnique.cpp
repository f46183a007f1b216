// `isr` — image-space radiosity (Nichols 2010, Ch. 4; Nichols, Shopf & Wyman, CGF 2009).
//
// Passes (timers named after the rows of Table 4.1):
//   "rsm"             Generate Reflective Shadow Map: light 0's RSM (techniques/nichols/ReflectiveShadowMap).
//   "vpl-cache"       the VPL cache: a regular vplGrid^2 grid (vplMode=regular, the stencilled gather of
//                     Table 4.1) or multiresolution light-space clusters (vplMode=clusters, §4.2.2): a
//                     min-max pyramid over the RSM, and one VPL per valid light-space patch (16^2..64^2).
//   "min-max-mipmap"  Create Min-Max Mipmap: depth-derivative max-mipmap + per-component normal min-max
//                     over the G-buffer down to 16^2, with the refine flags (diagonal neighbours, §3.4.2).
//   "stencil-setup"   Multires Stencil Setup: marks each covered pixel at exactly one level of the
//                     flattened atlas (valid iff not refined at its level and its parent is).
//   "gather"          Stenciled Gathering: every marked atlas texel gathers every VPL (Eqs. 4.1-4.5).
//   "upsample"        Upsampling: coarse-to-fine empty-aware 3x3 interpolation (§3.2.5), then x albedo/pi.
// Counters: vpls, fragments per level ("fragments/level-k"), total gather fragments.
// With `vplVisibility` on (beyond the thesis, off by default; techniques/screen_voxels/VplVisibility.h):
//   "voxelize"        the camera's view voxelized; the gather multiplies each VPL's term by a voxel
//                     march from the cell's patch to the VPL, in smaller VPL ranges per draw.
// The eye-space passes (min-max-mipmap, stencil-setup, the stencilled draw, upsample) are
// techniques/nichols/StencilledGather, shared with hisr; isr adds the RSM, the VPL cache and its gather.
//
// Deviations (docs/techniques/isr.md gives each its reason):
// - stencil set-up is one quad per level rectangle of the atlas (same fragments as one full-atlas pass).
// - thresholds, atlas layout, upsampling weights, the coarse patches' position/normal (mean of the
//   covered pixels) and the finest light level are assumptions.
// - the flux uses each texel's exact solid angle (no equal-solid-angle approximation).
// - compute shaders replace the geometry-shader cluster pass (same selection rule).
#include "techniques/isr/IsrTechnique.h"

#include "core/Check.h"
#include "techniques/nichols/VplWindow.h"
#include "gpu/Bindings.h"
#include "gpu/ShaderLimits.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace bounce {

namespace {
constexpr int kLocalSize = 8;  // clusters.comp local size
constexpr int kMaxClusterLevels = 16;  // clusters.comp u_levelSize[16]
// lightFinest's default per device profile (issue 30): 64^2 on a GPU (an assumption: the thesis allows
// up to the RSM resolution); 32^2 on llvmpipe, where the gather over the clusters is the frame on a large
// scene: about a quarter of the VPLs for a small loss of fidelity (measured: docs/techniques/isr.md
// "Device profiles").
constexpr int kLightFinestLlvmpipe = 32;
constexpr int kLightFinestGpu = 64;
}

void IsrTechnique::visitSettings(SettingsVisitor& v) {
    v.field("equalSolidAngle", m_equalSolidAngle, "Eq. 4.4: every RSM texel gets the frustum's solid angle / texels (thesis); off = exact per-texel solid angle");
    v.field("rsmSize", m_rsmSize, "RSM resolution per side (thesis 256)", 8, 2048);
    v.field("vplMode", m_vplMode, "clusters: multiresolution light-space patches (§4.2.2); regular: fixed VPL grid (Table 4.1)", kVplModes);
    v.field("vplGrid", m_vplGrid, "regular mode: VPLs per side per RSM layer (thesis 16..128)", 1, 2048);
    v.field("lightCoarsest", m_lightCoarsest, "clusters: coarsest light-space patch grid (thesis 16)", 1, 2048);
    v.field("lightFinest", m_lightFinest, "clusters: finest light-space patch grid (assumption 64 on a GPU, 32 on llvmpipe; up to rsmSize)", 1, 2048,
            PerProfile<int>{kLightFinestLlvmpipe, kLightFinestGpu});
    v.field("eyeCoarsest", m_eyeCoarsest, "coarsest illumination-buffer level (thesis 16)", 1, 4096);
    v.field("upsampling", m_upsampling, nichols::kUpsampleFilterHelp, nichols::kUpsampleFilters);
    v.field("gatherPass", m_gatherPass, nichols::kGatherPassHelp, nichols::kGatherPasses, nichols::kGatherPassDefaults);
    v.field("depthThreshold", m_eyeThresholds.depth, "eye-space max relative depth derivative per pixel (assumption)", 0.0f, 1e9f);
    v.field("normalThreshold", m_eyeThresholds.normal, "eye-space normal component range, 0..2 (assumption)", 0.0f, 2.0f);
    v.field("edgeNeighbours", m_eyeThresholds.edgeNeighbours, "also test edge-adjacent cells (§3.4.2: not adopted, up to 40 % slower)");
    nichols::visitEyeSettings(v, m_eyeThresholds, m_indirectSize);
    v.field("lightDepthThreshold", m_lightThresholds.depth, "clusters: light-space max relative distance derivative (assumption)", 0.0f, 1e9f);
    v.field("lightNormalThreshold", m_lightThresholds.normal, "clusters: light-space normal component range (assumption)", 0.0f, 2.0f);
    m_visibilitySettings.visit(v);
}

Expected<void> IsrTechnique::setup(const SetupContext& ctx) {
    BOUNCE_TRY_VOID(nichols::checkIndirectSize(m_indirectSize, ctx.size));
    BOUNCE_TRY_VOID(nichols::RegularVpls::checkGrid(m_rsmSize, m_vplGrid, nichols::ReflectiveShadowMap::layersFor(ctx.scene)));
    if (m_lightFinest > m_rsmSize || m_lightCoarsest > m_lightFinest)
        return makeError("settings need lightCoarsest={} <= lightFinest={} <= rsmSize={}", m_lightCoarsest, m_lightFinest, m_rsmSize);
    BOUNCE_TRY(m_rsm, nichols::ReflectiveShadowMap::create());
    BOUNCE_TRY(m_regular, nichols::RegularVpls::create());
    BOUNCE_TRY(m_light, nichols::MinMaxPyramid::create());
    BOUNCE_TRY(m_eye, nichols::StencilledGather::create());
    BOUNCE_TRY(m_visibility, voxels::VplVisibility::create(m_visibilitySettings));
    // gatherPass: the stencilled draw (the thesis's) or the compute dispatch over the cell list (same sums).
    if (nichols::gatherPass(m_gatherPass) == nichols::GatherPass::Compute) {
        BOUNCE_TRY(m_gather, gl::Program::build({"isr.gather", {{GL_COMPUTE_SHADER, "techniques/isr/gather.comp"}}, nichols::VplWindow::withDefines(m_visibility->defines())}));
    } else {
        BOUNCE_TRY(m_gather, gl::Program::build({"isr.gather",
                                                 {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                  {GL_FRAGMENT_SHADER, "techniques/isr/gather.frag"}},
                                                 nichols::VplWindow::withDefines(m_visibility->defines())}));
    }

    BOUNCE_TRY(m_clusters, gl::Program::build({"isr.clusters", {{GL_COMPUTE_SHADER, "techniques/isr/clusters.comp"}}}));
    m_count = gl::Buffer::create("isr.vplCount", sizeof(uint32_t));
    return {};
}

void IsrTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    {
        auto s = ctx.timers.scope("rsm");
        m_gathered = false;
        if (!m_rsm->render(ctx, m_rsmSize, m_equalSolidAngle)) {
            m_eye->clear(indirect);
            m_vplCount = 0;
            return;
        }
    }
    const gl::Buffer* vpls = nullptr;
    int vplBound = 0;  // an upper bound of the VPLs in the cache; the GPU-side count (m_count) is exact
    {
        auto s = ctx.timers.scope("vpl-cache");
        if (m_vplMode == "regular") {
            m_regular->extract(*m_rsm, m_vplGrid);
            vplBound = m_regular->count();
            const uint32_t count = static_cast<uint32_t>(vplBound);
            m_count.upload(0, sizeof(count), &count);
            vpls = &m_regular->buffer();
        } else {
            m_light->buildLight(*m_rsm, m_lightCoarsest, m_lightThresholds);
            int finest = 0;
            while (finest + 1 < m_light->levels() && m_light->levelSize(finest).x > m_lightFinest) ++finest;
            const glm::ivec2 fine = m_light->levelSize(finest);
            const size_t capacity = static_cast<size_t>(fine.x) * fine.y * m_light->layers() * sizeof(nichols::VplRecord);
            // Padded to a whole uniform-block window past the capacity (VplWindow::bind; issue 29 #13).
            const size_t padded = static_cast<size_t>(nichols::VplWindow::paddedRecords(static_cast<int>(capacity / sizeof(nichols::VplRecord)))) *
                                  sizeof(nichols::VplRecord);
            if (!m_clusterVpls || m_clusterVpls.size() != padded) m_clusterVpls = gl::Buffer::create("isr.clusterVpls", padded);
            m_count.clearZero();
            m_light->geometry().bind(BINDING_TEX_TECH0);
            m_light->normal().bind(BINDING_TEX_TECH1);
            m_light->flux().bind(BINDING_TEX_TECH2);
            m_light->refine().bind(BINDING_TEX_TECH3);
            m_clusterVpls.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
            m_count.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
            m_clusters.set("u_finest", finest);
            m_clusters.set("u_coarsest", m_light->levels() - 1);
            m_clusters.set("u_levelSize", m_light->levelSizes(kMaxClusterLevels));
            m_clusters.use();
            glDispatchCompute(static_cast<GLuint>((fine.x + kLocalSize - 1) / kLocalSize),
                              static_cast<GLuint>((fine.y + kLocalSize - 1) / kLocalSize),
                              static_cast<GLuint>(m_light->layers()));
            // The gather reads the clusters through uniform-block windows (VplWindow): GL_UNIFORM_BARRIER_BIT
            // (issue 29 #3; radeonsi invalidates its constant cache only on it).
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
            // The cluster count stays on the GPU (the gather reads it): the draws cover the capacity, and
            // a draw past the count ends its loops at once. No readback on the frame's path (issue 18).
            vplBound = static_cast<int>(capacity / sizeof(nichols::VplRecord));
            vpls = &m_clusterVpls;
        }
    }
    m_eye->prepare(ctx, m_eyeCoarsest, m_eyeThresholds, nichols::indirectScale(m_indirectSize, ctx.gbuffer.size()),
                   nichols::gatherPass(m_gatherPass));
    m_visibility->build(ctx);
    {
        auto s = ctx.timers.scope("gather");
        m_count.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
        m_visibility->setUniforms(m_gather);
        // One loop iteration per VPL, plus its visibility test when on: draws of at most half the shader
        // loop budget (gpu/ShaderLimits.h), so a million-VPL cache is gathered whole on llvmpipe too.
        // The VPLs are read through a uniform-block window (nichols/VplWindow.h), at most one window a draw.
        const int vplsPerDraw =
            nichols::VplWindow::perDraw(gl::shaderLoopIterationBudget() / 2 / (1 + m_visibility->loopIterationsPerTest()));
        const int batches = std::max(1, (vplBound + vplsPerDraw - 1) / vplsPerDraw);
        m_eye->gather(m_gather, batches, [&](int b) {
            m_gather.set("u_vplFirst", static_cast<unsigned>(b * vplsPerDraw));
            m_gather.set("u_windowFirst", static_cast<unsigned>(nichols::VplWindow::bind(*vpls, b * vplsPerDraw, vplsPerDraw)));
            m_gather.set("u_vplEnd", static_cast<unsigned>((b + 1) * vplsPerDraw));
        });
        ctx.counters["gatherDraws"] = static_cast<double>(batches);
    }
    m_eye->finish(ctx, indirect, nichols::upsampleFilter(m_upsampling));
    m_gathered = true;
}

void IsrTechnique::collectCounters(Counters& out) {
    if (!m_gathered) {
        out["vpls"] = 0.0;
        return;
    }
    uint32_t count = 0;
    m_count.download(0, sizeof(count), &count);
    m_vplCount = static_cast<int>(count);
    out["vpls"] = static_cast<double>(m_vplCount);
    m_eye->collectCounters(out);
    m_visibility->collectCounters(out);
}

}  // namespace bounce
