#pragma once
// `rsm-splat`: reflective-shadow-map splatting, the baselines of Nichols (2010) §4.3 / Fig. 4.8:
// full-screen splats (mode full), splats limited to a fixed world radius (mode fixed), or a radius
// adapted every frame so each splat covers a target number of fragments (mode matched: the thesis
// matches the multiresolution approach's fragments per VPL).
#include "techniques/Technique.h"
#include "techniques/nichols/RegularVpls.h"

#include <array>
#include <optional>

namespace bounce {

class RsmSplatTechnique final : public Technique {
public:
    std::string_view name() const override { return "rsm-splat"; }
    bool bouncesLightsOnly() const override { return true; }
    void visitSettings(SettingsVisitor& v) override;
    void derivedSettings(std::map<std::string, double>& out) const override { out["radiusMetres"] = m_radiusMetres; }
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
    void collectCounters(Counters& out) override;
    void debugViews(std::vector<DebugView>& out) const override {
        if (m_rsm) m_rsm->debugViews(out);
        if (m_vpls) m_vpls->debugViews(out);
    }

    static constexpr std::array<std::string_view, 3> kModes{"full", "fixed", "matched"};

private:
    int m_rsmSize = 256;
    int m_vplGrid = 16;
    std::string m_mode{"full"};
    float m_radius = 0.0f;            // fixed mode, metres (assumption); 0 = derived (nichols/SceneScale.h)
    float m_radiusMetres = 0.0f;      // the fixed radius in use
    float m_targetFragments = 5000.0f;  // matched mode: fragments per splat (set to isr's gatherFragments)
    float m_matchedRadius = 0.0f;       // matched mode state, metres
    std::optional<nichols::ReflectiveShadowMap> m_rsm;
    std::optional<nichols::RegularVpls> m_vpls;
    gl::Program m_splat;
    gl::Framebuffer m_fbo;
    gl::Query m_query;
    float m_splatRadius = -1.0f;        // this frame's splat radius (metres; 0 = full screen), -1: no splat
};

}  // namespace bounce
