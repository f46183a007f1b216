// Cross redistribution radiosity, van de Hoef 2013 ch. 3.3 and sec. 4.5, Alg. 4.4 / 4.5.
// Redistribution R(P,P) split by role (Eq. 3.1.2): R_g(C,M) is gathered at M, R_p(M,C) and R_p(M,M)
// are shot from M, and R(C,C), usually the expensive part, becomes the cross projection R_x(C,C)
// (Eq. 3.3.1): the static shot radiosity seen through each moved patch j from a static element i is
// projected onto j and shot from j to i, with j's old position giving light back (+F P(C,j,i)) and
// its new position taking it away (-F' P(C,j',i)). Hemicubes are rendered only for M: four per
// patch (front old ID, front new ID + shot, back old and back new shot + distance), so a
// redistribution costs 4 |M| hemicubes whatever |C| is (the thesis's central claim).
// Per frame with motion (every element of M is its own patch, no substructuring):
//   GENERATESHOOTINGPATCHES(q, shot) for q in M (T keeps the old shot), clear M (to E);
//   per batch: the four hemicubes; GATHERRADIOSITY (B_s += rho_s sum over the front shot hemicube);
//   T <- new total, clear the unshot; RECONSTRUCTION(total) on M; CROSSPROJECTIONRECONSTRUCTION on C:
//     old: visible in the old front hemicube: (-shot_s + P(C, s, e)) F_old
//     new: visible in the new front hemicube: (total_s - P(C, s', e)) F_new
//   (the equation's sign for the new term; Alg. 4.5 as printed adds P there, docs say why not).
//   PROJECTEDRADIOSITY: gridSize^2 rays through s, REPROJECTed with the back distance hemicube.
// Initial solution (sec. 4.5.2): progressive refinement with the animated bodies REMOVED (not drawn
// into hemicubes, not shooting or receiving), then one insertion redistribution (new terms only).
// Under the per-frame shooting budget (frameBudgetMs) the M-free refinement spans as many frames as it
// needs; the insertion follows in the frame it converges (or stops on maxIterations).
// Regular progressive propagation (sec. 3.1: "ordinary progressive iterations are still needed
// afterwards to propagate the changes"; sec. 3.3.4: the radiosity gathered during a redistribution "is
// shot during the regular progressive propagation"): after the insertion and after every
// redistribution, progressive refinement runs to the threshold with M in place, shooting the unshot
// radiosity the redistribution left (C's new shadows are negative unshot radiosity). Without it C's
// shot radiosity stayed the M-free solution for ever: R_g(C, M) gathered unshadowed surroundings, which
// weakened the shadows cast through M and left every second bounce of the change out
// (docs/techniques/radiosity.md, "Cross redistribution's error", has the measurements).
// As in the thesis, M is not removed and re-inserted around these iterations ("costly, ... only for
// the initial radiosity propagation"), so C's shot radiosity changes between redistributions and the
// negation of the old position is exact only to that change (docs/techniques/radiosity.md measures it).
// No PR iteration is part of the redistribution itself (sec. 4.5.3): its 4 |M| hemicubes are counted
// apart (redistributionHemicubes); `propagate=false` leaves the iterations out.
#include "techniques/radiosity_cross/CrossRadiosityTechnique.h"

namespace bounce {

using namespace radiosity;

namespace {
// The back hemicubes hold P(C, j, i) of Eq. 3.3.2, a sum over static patches only: the moving
// object is not drawn into them (drawn, a closed object's own far side fills every back hemicube
// and hides the static light behind it; measured: the shadow of the rotating box 10 % too bright).
constexpr render::DrawFilter kBackFilter = render::DrawFilter::Static;
}  // namespace

void CrossRadiosityTechnique::visitMethodSettings(SettingsVisitor& v) {
    ShootingRadiosityTechnique::visitMethodSettings(v);
    v.field("backHemicubeSize", m_backSize, "back shot hemicubes' top face, pixels per side (thesis sec. 4.5.2: 16)", 2, 256);
    v.field("msaa", m_msaa, "samples of the back hemicubes, resolved as a blur (thesis: 4)", 1, 16);
    v.field("crossGrid", m_grid, "PROJECTEDRADIOSITY gridSize: gridSize^2 rays per patch (thesis: 4)", 1, 16);
    v.field("reprojection", m_reprojection, "REPROJECT the rays with the back distance hemicube (thesis Fig. 4.5.3; off samples the ray direction itself)");
    v.field("crossWeights", m_weights,
            "PROJECTEDRADIOSITY's average over the rays: area (thesis, Eq. 3.3.2's area-weighted sum) or formFactor (each ray "
            "weighted by its cell's form factor seen from the receiver; bounce's, exact where the patch is large against its distance)",
            kWeights);
    v.field("propagate", m_propagate,
            "progressive refinement to the threshold after each redistribution, shooting the unshot radiosity it left (the "
            "thesis's regular progressive propagation, sec. 3.1 / 3.3.4); off: the redistribution alone");
}

void CrossRadiosityTechnique::adjustOptions(SystemOptions& o) const {
    o.backSize = m_backSize;
    o.msaa = m_msaa;
    o.crossGrid = m_grid;
    o.reprojection = m_reprojection;
    o.crossFormFactorWeights = m_weights == "formFactor";
}

void CrossRadiosityTechnique::solve(FrameContext& ctx) {
    if (!m_initialised) {
        const PatchModel& pm = m_system->patches();
        m_animated.assign(pm.bodyCount(), 0);
        for (uint32_t b = 0; b < pm.bodyCount(); ++b) m_animated[b] = pm.bodyAnimated(ctx.scene, b) ? 1 : 0;
        m_system->setMovingOverride(&m_animated);
        m_system->beginFrame(ctx.scene, ctx.time);
        m_system->computeLights(ctx.lights);
        m_system->reset(RAD_RECEIVERS_STATIC, true);
        m_system->reset(RAD_RECEIVERS_MOVING, false);
        m_initialised = true;
    } else if (!m_inserted) {
        // The initial M-free solution goes on over frames under the shooting budget (M still removed:
        // the override holds; the animated bodies' current transforms are the ones the insertion uses).
        m_system->beginFrame(ctx.scene, ctx.time);
        m_system->computeLights(ctx.lights);
        m_system->applyLights(RAD_RECEIVERS_STATIC);
    }
    if (!m_inserted) {
        // Sec. 4.5.2: PR with M removed to convergence (or maxIterations, as before the budget), then
        // one insertion. Where the frame's time budget ends it first, the insertion waits for a later
        // frame (M shows its direct light only until then), so what is inserted into does not depend on
        // the host's speed.
        progressiveRefinement(ctx, m_maxIterations, 0, true);
        if (m_budgetHit) return;
        if (m_system->anyMoving()) redistribute(ctx, true);
        m_system->setMovingOverride(nullptr);
        if (m_propagate) progressiveRefinement(ctx, m_maxIterations, 0, false);
        commitFrame(ctx);
        m_inserted = true;
        return;
    }
    beginFrameFinishingPending(ctx);  // a quad the last frame's budget cut shoots the rest of its light first
    m_system->computeLights(ctx.lights);
    if (m_system->anyMoving()) redistribute(ctx, false);  // M reset to E + D_new
    m_system->applyLights(RAD_RECEIVERS_ALL);             // the static elements' change of D, as unshot
    if (m_propagate) progressiveRefinement(ctx, m_maxIterations, 0, false);
    commitFrame(ctx);
}

void CrossRadiosityTechnique::redistribute(FrameContext& ctx, bool insert) {
    const uint32_t hemicubesBefore = m_system->hemicubesRendered();
    const PatchModel& pm = m_system->patches();
    std::vector<ShooterRect> patches;
    for (uint32_t q = 0; q < pm.quads().size(); ++q) {
        const Quad& quad = pm.quads()[q];
        if (!m_system->bodyMoving(quad.body)) continue;
        for (int j = 0; j < quad.nv; ++j)
            for (int i = 0; i < quad.nu; ++i) {
                if (!(pm.elements()[quad.firstElement + static_cast<size_t>(j * quad.nu + i)].area > 0.0f)) continue;
                patches.push_back({q, {i, j}, {i, j}});
            }
    }
    m_system->loadShooters(patches);
    const auto np = static_cast<uint32_t>(patches.size());
    m_system->computeShooters(0, np, false);  // T: the old shot of every patch of M
    m_system->reset(RAD_RECEIVERS_MOVING, true);
    for (uint32_t first = 0; first < np; first += static_cast<uint32_t>(m_batch)) {
        const uint32_t n = std::min<uint32_t>(static_cast<uint32_t>(m_batch), np - first);
        if (!insert) {
            m_system->placeShooterHemicubes(0, first, n, ShooterAt::Front, true);
            m_system->renderHemicubes(ctx.drawer, HemicubeKind::Id, 0, n, true, render::DrawFilter::All, ctx.timers);
            m_system->placeShooterHemicubes(2, first, n, ShooterAt::Back, true);
            m_system->renderHemicubes(ctx.drawer, HemicubeKind::Back, 2, n, true, kBackFilter, ctx.timers);
        }
        m_system->placeShooterHemicubes(1, first, n, ShooterAt::Front, false);
        m_system->renderHemicubes(ctx.drawer, HemicubeKind::Combined, 1, n, false, render::DrawFilter::All, ctx.timers);
        m_system->placeShooterHemicubes(3, first, n, ShooterAt::Back, false);
        m_system->renderHemicubes(ctx.drawer, HemicubeKind::Back, 3, n, false, kBackFilter, ctx.timers);
        m_system->gatherShot(n, ctx.timers);
        m_system->computeShooters(first, n, true);
        m_system->clearShooterUnshot(first, n);
        m_system->reconstruct(RAD_SHOOT_TOTAL, RAD_RECEIVERS_MOVING, first, n, false, ctx.timers);
        m_system->reconstruct(RAD_SHOOT_CROSS, RAD_RECEIVERS_STATIC, first, n, insert, ctx.timers);
    }
    m_frameShooters += np;
    m_frameMovingPatches = np;
    m_frameRedistributionHemicubes += m_system->hemicubesRendered() - hemicubesBefore;
}

}  // namespace bounce
