// GPU progressive refinement radiosity, van de Hoef 2013 sec. 4.3, Alg. 4.2 (after Cohen et al.
// 1988 and Coombe et al. 2004, with the thesis's improvements):
//   SHOOTINGITERATION: FINDSHOOTINGQUAD (the quad of highest mean unshot radiosity; stop below the
//   convergence threshold), GENERATESHOOTINGPATCHES (dynamic shooter subdivision by the quad's unshot
//   flux, patches summed into the shooter buffer T), clear the quad's unshot texture, then per batch
//   of shooters an ID hemicube each and one RECONSTRUCTIONSHADER pass over all elements
//   (Delta B_e = rho_e B_s^u A_s F_se with the disk approximation and the 4-nearest-pixel quad-ID
//   visibility test).
// Like the thesis's benchmarks the solution restarts from B = Bu = E whenever something moved (sec.
// 5.2), which makes it follow any motion; maxIterations and frameBudgetMs bound a frame's shooting
// quads. A frame in which nothing moved continues the last frame's shooting instead of repeating it
// (bounce's choice: the same solution, the same sequence of shooting quads, reached over frames where
// one frame's budget does not converge).
#include "techniques/radiosity_pr/ProgressiveRadiosityTechnique.h"

namespace bounce {

void ShootingRadiosityTechnique::visitMethodSettings(SettingsVisitor& v) {
    // The reconstruction pass's settings: radiosity-gather never reconstructs, so it does not declare them
    // (and refuses them as unknown settings).
    v.field("visibilitySamples", m_options.visibilitySamples, "ID-hemicube pixels tested per receiver: 4 nearest (thesis sec. 5.2.1) or 1", 1, 4);
    v.field("ffSubdivideRatio", m_options.ffSubdivideRatio, "split the disk approximation when shooter area / distance^2 exceeds this (thesis: threshold not given)", 0.0f, 1e6f);
    v.field("ffSubdivisions", m_options.ffSubdivisions, "sub-disks per side when split", 1, 8);
    v.field("threshold", m_threshold, "convergence: stop when the brightest quad's mean unshot radiance is below this fraction of the brightest emitter's (thesis: value not given)", 0.0f, 1.0f);
    v.field("maxIterations", m_maxIterations, "shooting quads per frame at most (Alg. 4.2 iterations)", 1, 1000000);
    v.field("frameBudgetMs", m_frameBudgetMs,
            "per-frame shooting budget, ms of CPU wall time from the start of the frame's solve: no batch of shooters starts that "
            "would end past it (the first of a frame always runs; a cut quad's rest is shot next frame), so the solution converges "
            "over frames (bounce's; thesis: shooter batches). 0: off",
            0.0f, 1e7f, PerProfile<float>{kDefaultFrameBudgetMs, kGpuFrameBudgetMs});
    v.field("shooterFlux", m_shooterFlux, "dynamic shooter subdivision: a patch carries at most about this fraction of the emitted flux (thesis: mapping not given)", 1e-6f, 1.0f);
    v.field("batch", m_batch, "shooters per reconstruction pass (thesis benchmarks: 10)", 1, RAD_MAX_BATCH);
}

void ProgressiveRadiosityTechnique::solve(FrameContext& ctx) {
    m_system->beginFrame(ctx.scene, ctx.time);
    m_system->computeLights(ctx.lights);
    // Bodies include the lights: a moving light, object or emitter restarts the solution.
    if (!m_started || m_system->anyMoving()) {
        m_system->reset(RAD_RECEIVERS_ALL, true);
        dropPending();  // the batches the last frame's budget left belong to the solution just dropped
    }
    m_started = true;
    progressiveRefinement(ctx, m_maxIterations, 0, false);
    m_system->commit();
}

}  // namespace bounce
