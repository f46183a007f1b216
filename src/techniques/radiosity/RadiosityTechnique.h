#pragma once
// The base of the four hemicube radiosity techniques of van de Hoef 2013 (radiosity-gather,
// radiosity-pr, radiosity-incremental, radiosity-cross): shared settings, the progressive-refinement
// iteration they all build on, the display, counters. See RadiosityTechnique.cpp for the passes and
// docs/techniques/radiosity.md for the settings, the D3D 11 -> GL 4.5 mapping and the deviations.
#include "techniques/Technique.h"
#include "techniques/radiosity/RadiositySystem.h"

#include <array>
#include <chrono>
#include <memory>
#include <string>

namespace bounce {

class RadiosityTechnique : public Technique {
public:
    void visitSettings(SettingsVisitor& v) override;
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
    bool ownsDirect() const override { return true; }
    // The hemicubes of the last batch the method rendered, those it uses (hemicubeUse): "radiosity.
    // hemicube.id" (the ID hemicubes of its shooters), ".idOld" (the same against the old transforms),
    // ".shot", ".backOld", ".back" (cross redistribution), ".radiosity" (the gather's). Layer 5 k is
    // hemicube k's top face, 5 k + 1..4 its half-high sides.
    void debugViews(std::vector<DebugView>& out) const override;
    // The element sizes as used, metres: the settings, or what auto derived from the scene's area.
    void derivedSettings(std::map<std::string, double>& out) const override;
    std::string_view frameReadbackReason() const override {
        return "van de Hoef (2013) FINDSHOOTINGQUAD: each quad's unshot power is read back for the CPU's "
               "arg-max over the quads, the thesis's own CPU-GPU stall";
    }

    static constexpr std::array<std::string_view, 2> kViews{"bilinear", "nearest"};

    // Tests.
    radiosity::RadiositySystem& system() { return *m_system; }
    // Per-frame work of the last frame.
    uint32_t lastHemicubes() const { return m_frameHemicubes; }
    uint32_t lastIterations() const { return m_frameIterations; }
    uint32_t lastMovingPatches() const { return m_frameMovingPatches; }
    uint32_t lastRedistributionHemicubes() const { return m_frameRedistributionHemicubes; }
    bool lastConverged() const { return m_converged; }
    bool lastBudgetHit() const { return m_budgetHit; }  // the last frame's shooting stopped on frameBudgetMs
    uint32_t lastShooters() const { return m_frameShooters; }

    // The shooting methods' per-frame shooting budget (frameBudgetMs): the CPU wall time from the start
    // of a frame's solve after which no further batch of shooters starts (bounce's, issue 30: the
    // thesis's shooter batches spread over frames). Chosen so that a frame of the larger built-in rooms
    // stays near 2 s at 256^2 on llvmpipe, the frame's other passes included (docs/techniques/
    // radiosity.md, "Per-frame shooting budget"). On a GPU profile (BOUNCE_PROFILE / the context's):
    // 33.3 ms, 30 frames a second, as viewer.frameBudgetMs.
    static constexpr float kDefaultFrameBudgetMs = 1200.0f;
    static constexpr float kGpuFrameBudgetMs = 33.3f;

protected:
    // One frame of the method: update the solution in the system's atlas.
    virtual void solve(FrameContext& ctx) = 0;
    // Method-specific settings (after the shared ones).
    virtual void visitMethodSettings(SettingsVisitor&) {}
    // Options the method fixes (gather uses no back hemicubes, ...).
    virtual void adjustOptions(radiosity::SystemOptions&) const {}
    // The hemicubes the method renders (only those hold anything to show); shooting: ID hemicubes.
    struct HemicubeUse {
        bool radiosity = false, id = true, idOld = false, shotAndBack = false;
    };
    virtual HemicubeUse hemicubeUse() const { return {}; }

    // Alg. 4.2 SHOOTINGITERATION until the brightest quad's mean unshot radiance is below the
    // threshold or `maxIterations` quads have shot (at least `minIterations`, even if converged), or
    // until the next batch of shooters would end past the frame's budget (frameBudgetMs; m_budgetHit
    // then): the rest of that quad's batches are pending and shot first by the next call. The first
    // batch of a call always runs, so the solution always advances.
    // removeMoving: the moving bodies take no part (cross redistribution's initial solution).
    void progressiveRefinement(FrameContext& ctx, int maxIterations, int minIterations, bool removeMoving);
    // Shoots the pending batches of the last iteration, all of them (before a redistribution, which
    // reuses the shooter buffer and must see that quad's light shot), or, `budgeted`, as many as the
    // frame's budget allows (`shotAny`: a batch already ran in this call). True when none is left.
    // `old`: hemicubes placed and drawn with the bodies of the last commit.
    bool shootPending(FrameContext& ctx, bool budgeted, bool& shotAny, bool old = false);
    // The frame start of the redistributing methods (incremental, cross after its insertion): the
    // bodies at this frame's time; if they moved since the last commit while batches are pending, those
    // are shot first, whole, in the scene as it was when their quad was chosen (the bodies of the last
    // commit: shooter and receiver positions, hemicubes and the drawn scene), so that the
    // redistribution, which corrects the old configuration's light to the new one, sees that quad's
    // light shot in the old configuration.
    void beginFrameFinishingPending(FrameContext& ctx);
    void commitFrame(const FrameContext& ctx);  // m_system->commit(), remembering the frame's time
    void dropPending() { m_pending = {}; }  // a restart (B = Bu = E) makes the pending shooters void
    // GENERATESHOOTINGPATCHES' subdivision: a quad carrying `flux` (W, luminance) is cut into about
    // flux / (shooterFlux x emitted flux) patches, at most one per element.
    std::vector<radiosity::ShooterRect> subdivide(uint32_t quad, float flux) const;
    // Whether the frame's budget lets a batch start now (always when `guaranteed` or without a budget).
    bool budgetAllows(bool guaranteed) const;

    std::unique_ptr<radiosity::RadiositySystem> m_system;
    radiosity::SystemOptions m_options;
    float m_elementSize = 0.0f;         // metres; 0 = auto (PatchModel.h autoElementSize)
    float m_dynamicElementSize = 0.0f;  // metres; 0 = auto
    float m_threshold = 1e-3f;
    int m_maxIterations = 400;
    float m_shooterFlux = 0.003f;
    int m_batch = 10;
    float m_frameBudgetMs = kDefaultFrameBudgetMs;  // 0: no time budget (maxIterations alone)
    std::string m_view{"bilinear"};

    uint32_t m_frameHemicubes = 0, m_frameShooters = 0, m_frameIterations = 0;
    uint32_t m_frameMovingPatches = 0;  // shooting patches of M in this frame's redistribution
    uint32_t m_frameRedistributionHemicubes = 0;  // hemicubes of the redistribution alone (incremental, cross)
    bool m_converged = false;
    bool m_budgetHit = false;
    std::chrono::steady_clock::time_point m_frameStart{};  // the start of this frame's solve (the budget's origin)
    float m_commitTime = 0.0f;  // the time of the last commit's frame
    double m_batchMs = 0.0;  // the last batch's measured wall time (glFinish), the next one's predicted cost
    // Shooters [next, count) of the shooter buffer not yet shot: the rest of an iteration the budget cut.
    struct Pending {
        uint32_t count = 0, next = 0;
        bool removeMoving = false;
    } m_pending;
    float m_maxEmission = 0.0f;  // brightest emitter radiance (luminance), W/(m^2 sr)
};

}  // namespace bounce
