// Gather radiosity, van de Hoef 2013 sec. 4.2, Alg. 4.1 (after Cohen & Greenberg 1985):
//   for b <- 0, maxBounces: for every element i: render all B_j into a hemicube on i, multiply by
//   the delta form factors, integrate, store B_i = E_i + rho_i sum.
// Passes per sweep, in batches of RAD_MAX_BATCH elements: place hemicube records at the elements
// (random per-position rotation), render the radiosity hemicubes (RGBA16F, 4x MSAA: more visibility
// samples per pixel at a 64^2 top face, sec. 4.2), integrate (compute reduction with the resolve
// folded in, or the mip-chain fallback), write B. Each batch sees the previous batches' new values
// (Gauss-Seidel, as Cohen & Greenberg), so `bounces` sweeps carry at least that many bounces.
// The solution restarts from B = E every frame (sec. 5.2: gather does not reuse the last frame), so
// it follows moving objects and lights by construction; at high settings it is the radiosity
// reference of the other three methods (the thesis's reference images, Table 5.1).
// Deviation: elements in RGBA32F (thesis: RGBA16F), shared with the other methods.
#include "techniques/radiosity_gather/GatherRadiosityTechnique.h"

namespace bounce {

void GatherRadiosityTechnique::visitMethodSettings(SettingsVisitor& v) {
    v.field("bounces", m_bounces, "gather sweeps over all elements per frame (thesis: capped, value not given)", 1, 1000);
    v.field("msaa", m_msaa, "samples per radiosity-hemicube pixel (thesis sec. 5.3.1: 4)", 1, 16);
    v.field("integration", m_integration, "compute: parallel reduction (thesis's choice); mipmap: the DX10 fallback (1x1 mip level x pixel count)", kIntegrations);
}

void GatherRadiosityTechnique::adjustOptions(radiosity::SystemOptions& o) const {
    o.msaa = m_msaa;
    o.mipIntegration = m_integration == "mipmap";
}

void GatherRadiosityTechnique::solve(FrameContext& ctx) {
    m_system->beginFrame(ctx.scene, ctx.time);
    m_system->computeLights(ctx.lights);
    m_system->reset(RAD_RECEIVERS_ALL, true);
    for (int b = 0; b < m_bounces; ++b) m_system->gatherSweep(ctx.drawer, ctx.timers);
    m_frameIterations = static_cast<uint32_t>(m_bounces);
    m_converged = true;
    m_system->commit();
}

}  // namespace bounce
