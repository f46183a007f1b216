#pragma once
// `radiosity-gather`: van de Hoef 2013 Alg. 4.1, the gather baseline and reference.
#include "techniques/radiosity/RadiosityTechnique.h"

#include <string>
#include <vector>

namespace bounce {

class GatherRadiosityTechnique final : public RadiosityTechnique {
public:
    std::string_view name() const override { return "radiosity-gather"; }
    std::string_view frameReadbackReason() const override { return {}; }  // gathers: no shooter to select
    static constexpr std::array<std::string_view, 2> kIntegrations{"compute", "mipmap"};
    static constexpr std::array<std::string_view, 3> kProgress{"auto", "on", "off"};
    // At most one progress line per this many seconds (issue 30: "says how long it will take").
    static constexpr double kProgressIntervalS = 2.0;
    // Tests: the progress lines the last frame printed (or would have printed with progress=on).
    const std::vector<std::string>& lastProgressLines() const { return m_progressLines; }

protected:
    void solve(FrameContext& ctx) override;
    void visitMethodSettings(SettingsVisitor& v) override;
    void adjustOptions(radiosity::SystemOptions& o) const override;
    HemicubeUse hemicubeUse() const override { return {.radiosity = true, .id = false}; }

private:
    int m_bounces = 8;
    int m_msaa = 4;
    std::string m_integration{"compute"};
    std::string m_progress{"auto"};  // auto: when stderr is a terminal
    std::vector<std::string> m_progressLines;
};

}  // namespace bounce
