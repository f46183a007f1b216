#pragma once
// `radiosity-cross`: van de Hoef 2013 Alg. 4.4/4.5, cross redistribution radiosity.
#include "techniques/radiosity_pr/ProgressiveRadiosityTechnique.h"

namespace bounce {

class CrossRadiosityTechnique final : public ShootingRadiosityTechnique {
public:
    std::string_view name() const override { return "radiosity-cross"; }
    CrossRadiosityTechnique() { m_dynamicElementSize = kDefaultDynamicElementSize; }
    // Coarser elements on the moving object: each is its own patch with four hemicubes (sec. 4.5.1,
    // no substructuring for M). The thesis's boxes have 52-90 CR elements against 318-918 for the
    // other methods, 3.5-10x fewer; 0.15 m gives the rotating box 54 patches (165 elements at 0.05 m).
    static constexpr float kDefaultDynamicElementSize = 0.15f;  // metres

    uint32_t lastPatches() const { return m_frameMovingPatches; }
    static constexpr std::array<std::string_view, 2> kWeights{"area", "formFactor"};

protected:
    void solve(FrameContext& ctx) override;
    void visitMethodSettings(SettingsVisitor& v) override;
    void adjustOptions(radiosity::SystemOptions& o) const override;
    HemicubeUse hemicubeUse() const override { return {.id = true, .idOld = true, .shotAndBack = true}; }

private:
    void redistribute(FrameContext& ctx, bool insert);

    int m_backSize = 16;
    int m_msaa = 4;
    int m_grid = 4;
    bool m_reprojection = true;
    std::string m_weights{"area"};  // PROJECTEDRADIOSITY's ray weights: area (Eq. 3.3.2, the thesis) or formFactor
    bool m_propagate = true;        // the regular progressive propagation after each redistribution (sec. 3.1, 3.3.4)
    bool m_initialised = false;
    bool m_inserted = false;  // the M-free initial solution converged and M was inserted (sec. 4.5.2)
    std::vector<char> m_animated;
};

}  // namespace bounce
