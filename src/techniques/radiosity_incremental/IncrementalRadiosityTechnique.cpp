// Incremental radiosity with reshooting, van de Hoef 2013 sec. 4.4, Alg. 4.3 (on the incremental
// radiosity of Chen 1990 / George et al. 1990, Eq. 3.2.1):
//   the first frame is a progressive-refinement solution (Alg. 4.2, to convergence, or as far as the
//   frame's shooting budget frameBudgetMs goes: still frames continue it, so the initial solution
//   converges over frames); after that the solution is modified, never restarted. In a frame where bodies moved (M: the quads of bodies whose
//   transform changed since the last redistribution; C: the rest):
//   1. R_p(M,C) part 1: every quad of M shoots its negative shot radiosity to C with the OLD form
//      factors (ID hemicubes at the old positions, in the scene as it was);
//   2. M is reset to its emission;
//   3. every quad of C generates shooting patches of its total radiosity (T: shot and unshot), clears
//      its unshot texture, and per patch renders an ID hemicube in the old and one in the new scene:
//      R_p(C,M) reshoots the TOTAL to M (Eq. 4.4.1, M was reset), and C's elements take the four
//      visibility cases of INCREMENTALRECONSTRUCTIONSHADER (newly occluded: -shot; newly visible:
//      total; both: unshot; neither: nothing);
//   4. a progressive-refinement iteration always follows (R_p(M,M) and R_p(M,C) part 2 ride on it;
//      sec. 5.2.2: "always runs a PR iteration on redistribution"), then PR continues to the threshold.
//   The redistribution is linear in what each quad has shot so far (M removes its shot, C shoots its
//   total), so it is exact on an unconverged solution too; it always completes, the budget bounds only
//   the progressive refinement after it.
//   Cost: 2 |M| + 2 |C| shooter hemicubes per redistribution (sec. 3.2); a frame where nothing moved
//   shoots only while unshot radiosity is above the threshold, so a converged still scene renders
//   no hemicube at all.
#include "techniques/radiosity_incremental/IncrementalRadiosityTechnique.h"

#include "core/Image.h"

#include <glm/gtc/constants.hpp>

namespace bounce {

using namespace radiosity;

void IncrementalRadiosityTechnique::solve(FrameContext& ctx) {
    beginFrameFinishingPending(ctx);  // a quad the last frame's budget cut shoots the rest of its light first
    m_system->computeLights(ctx.lights);
    if (!m_initialised) {
        m_system->reset(RAD_RECEIVERS_ALL, true);
        progressiveRefinement(ctx, m_maxIterations, 0, false);
        m_initialised = true;
    } else if (m_system->anyMoving()) {
        redistribute(ctx);  // M reset to E + D_new
        m_system->applyLights(RAD_RECEIVERS_ALL);  // the static elements' change of D, as unshot
        progressiveRefinement(ctx, m_maxIterations, 1, false);
    } else {
        m_system->applyLights(RAD_RECEIVERS_ALL);
        progressiveRefinement(ctx, m_maxIterations, 0, false);
    }
    commitFrame(ctx);
}

void IncrementalRadiosityTechnique::redistribute(FrameContext& ctx) {
    const uint32_t hemicubesBefore = m_system->hemicubesRendered();
    const auto& quads = m_system->patches().quads();
    const float pi = glm::pi<float>();
    // 1. M shoots its negative shot radiosity to C with the old form factors.
    std::vector<QuadStats> stats = m_system->quadStats();
    std::vector<ShooterRect> rects;
    for (uint32_t q = 0; q < quads.size(); ++q)
        if (m_system->bodyMoving(quads[q].body) && stats[q].area > 0.0f) {
            const auto r = subdivide(q, pi * std::abs(luminance(stats[q].shot)));
            rects.insert(rects.end(), r.begin(), r.end());
        }
    m_system->loadShooters(rects);
    const auto nm = static_cast<uint32_t>(rects.size());
    m_system->computeShooters(0, nm, false);
    for (uint32_t first = 0; first < nm; first += static_cast<uint32_t>(m_batch)) {
        const uint32_t n = std::min<uint32_t>(static_cast<uint32_t>(m_batch), nm - first);
        m_system->placeShooterHemicubes(0, first, n, ShooterAt::Front, true);
        m_system->renderHemicubes(ctx.drawer, HemicubeKind::Id, 0, n, true, render::DrawFilter::All, ctx.timers);
        m_system->reconstruct(RAD_SHOOT_NEG_SHOT, RAD_RECEIVERS_STATIC, first, n, false, ctx.timers);
    }
    m_frameShooters += nm;
    m_frameMovingPatches = nm;
    // 2. Reset M to its emission.
    m_system->reset(RAD_RECEIVERS_MOVING, true);
    // 3. Every static quad shoots its total: reshooting to M, the four cases to C.
    stats = m_system->quadStats();
    for (uint32_t q = 0; q < quads.size(); ++q) {
        if (m_system->bodyMoving(quads[q].body) || stats[q].area <= 0.0f) continue;
        const auto r = subdivide(q, pi * std::abs(luminance(stats[q].total)));
        m_system->loadShooters(r);
        const auto ns = static_cast<uint32_t>(r.size());
        m_system->computeShooters(0, ns, false);
        m_system->clearShooterUnshot(0, ns);
        for (uint32_t first = 0; first < ns; first += static_cast<uint32_t>(m_batch)) {
            const uint32_t n = std::min<uint32_t>(static_cast<uint32_t>(m_batch), ns - first);
            m_system->placeShooterHemicubes(0, first, n, ShooterAt::Front, true);
            m_system->placeShooterHemicubes(1, first, n, ShooterAt::Front, false);
            m_system->renderHemicubes(ctx.drawer, HemicubeKind::Id, 0, n, true, render::DrawFilter::All, ctx.timers);
            m_system->renderHemicubes(ctx.drawer, HemicubeKind::Id, 1, n, false, render::DrawFilter::All, ctx.timers);
            m_system->reconstruct(RAD_SHOOT_TOTAL, RAD_RECEIVERS_MOVING, first, n, false, ctx.timers);
            m_system->reconstruct(RAD_SHOOT_INCREMENTAL, RAD_RECEIVERS_STATIC, first, n, false, ctx.timers);
        }
        m_frameShooters += ns;
    }
    m_frameRedistributionHemicubes = m_system->hemicubesRendered() - hemicubesBefore;
}

}  // namespace bounce
