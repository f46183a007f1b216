#pragma once
// The base of the four hemicube radiosity techniques of van de Hoef 2013 (radiosity-gather,
// radiosity-pr, radiosity-incremental, radiosity-cross): shared settings, the progressive-refinement
// iteration they all build on, the display, counters. See RadiosityTechnique.cpp for the passes and
// docs/techniques/radiosity.md for the settings, the D3D 11 -> GL 4.5 mapping and the deviations.
#include "techniques/Technique.h"
#include "techniques/radiosity/RadiositySystem.h"

#include <array>
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
    // threshold or `maxIterations` quads have shot (at least `minIterations`, even if converged).
    // removeMoving: the moving bodies take no part (cross redistribution's initial solution).
    void progressiveRefinement(FrameContext& ctx, int maxIterations, int minIterations, bool removeMoving);
    // GENERATESHOOTINGPATCHES' subdivision: a quad carrying `flux` (W, luminance) is cut into about
    // flux / (shooterFlux x emitted flux) patches, at most one per element.
    std::vector<radiosity::ShooterRect> subdivide(uint32_t quad, float flux) const;
    // Renders the ID hemicubes of shooters [0, n) in batches and runs `mode` on `receivers`.
    void shootBatches(FrameContext& ctx, uint32_t count, int mode, int receivers, bool removeMoving);

    std::unique_ptr<radiosity::RadiositySystem> m_system;
    radiosity::SystemOptions m_options;
    float m_elementSize = 0.0f;         // metres; 0 = auto (PatchModel.h autoElementSize)
    float m_dynamicElementSize = 0.0f;  // metres; 0 = auto
    float m_threshold = 1e-3f;
    int m_maxIterations = 400;
    float m_shooterFlux = 0.003f;
    int m_batch = 10;
    std::string m_view{"bilinear"};

    uint32_t m_frameHemicubes = 0, m_frameShooters = 0, m_frameIterations = 0;
    uint32_t m_frameMovingPatches = 0;  // shooting patches of M in this frame's redistribution
    uint32_t m_frameRedistributionHemicubes = 0;  // hemicubes of the redistribution alone (incremental, cross)
    bool m_converged = false;
    float m_maxEmission = 0.0f;  // brightest emitter radiance (luminance), W/(m^2 sr)
};

}  // namespace bounce
