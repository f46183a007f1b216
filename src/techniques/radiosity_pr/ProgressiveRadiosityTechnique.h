#pragma once
// `radiosity-pr`: van de Hoef 2013 Alg. 4.2, GPU progressive refinement.
#include "techniques/radiosity/RadiosityTechnique.h"

namespace bounce {

// The shooting methods' settings (progressive refinement and the two redistributions built on it).
class ShootingRadiosityTechnique : public RadiosityTechnique {
protected:
    void visitMethodSettings(SettingsVisitor& v) override;
};

class ProgressiveRadiosityTechnique final : public ShootingRadiosityTechnique {
public:
    std::string_view name() const override { return "radiosity-pr"; }

protected:
    void solve(FrameContext& ctx) override;

private:
    bool m_started = false;  // frame 0 solved: a still frame continues it
};

}  // namespace bounce
