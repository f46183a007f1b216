#pragma once
// `radiosity-incremental`: van de Hoef 2013 Alg. 4.3, incremental radiosity with reshooting.
#include "techniques/radiosity_pr/ProgressiveRadiosityTechnique.h"

namespace bounce {

class IncrementalRadiosityTechnique final : public ShootingRadiosityTechnique {
public:
    std::string_view name() const override { return "radiosity-incremental"; }

protected:
    void solve(FrameContext& ctx) override;
    HemicubeUse hemicubeUse() const override { return {.id = true, .idOld = true}; }

private:
    void redistribute(FrameContext& ctx);
    bool m_initialised = false;
};

}  // namespace bounce
