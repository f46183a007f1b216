#pragma once
// `radiosity-gather`: van de Hoef 2013 Alg. 4.1, the gather baseline and reference.
#include "techniques/radiosity/RadiosityTechnique.h"

namespace bounce {

class GatherRadiosityTechnique final : public RadiosityTechnique {
public:
    std::string_view name() const override { return "radiosity-gather"; }
    std::string_view frameReadbackReason() const override { return {}; }  // gathers: no shooter to select
    static constexpr std::array<std::string_view, 2> kIntegrations{"compute", "mipmap"};

protected:
    void solve(FrameContext& ctx) override;
    void visitMethodSettings(SettingsVisitor& v) override;
    void adjustOptions(radiosity::SystemOptions& o) const override;
    HemicubeUse hemicubeUse() const override { return {.radiosity = true, .id = false}; }

private:
    int m_bounces = 8;
    int m_msaa = 4;
    std::string m_integration{"compute"};
};

}  // namespace bounce
