#pragma once
// `rsm`: the full-resolution reflective-shadow-map gather, baseline of Nichols (2010) §4.3. Every
// pixel gathers every VPL. With vplGrid = rsmSize it is the "1M-VPL full gather" reference of
// Figs. 4.9/4.13 (rsmSize = 1024) that isr and hisr converge to.
#include "techniques/Technique.h"
#include "techniques/nichols/RegularVpls.h"
#include "techniques/screen_voxels/VplVisibility.h"

#include <array>
#include <optional>

namespace bounce {

class RsmTechnique final : public Technique {
public:
    std::string_view name() const override { return "rsm"; }
    bool bouncesLightsOnly() const override { return true; }
    void visitSettings(SettingsVisitor& v) override;
    void derivedSettings(std::map<std::string, double>& out) const override { out["minDistanceMetres"] = m_minDistanceMetres; }
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
    void collectCounters(Counters& out) override { m_visibility->collectCounters(out); }
    void debugViews(std::vector<DebugView>& out) const override {
        if (m_rsm) m_rsm->debugViews(out);
        if (m_vpls) m_vpls->debugViews(out);
    }

    const nichols::ReflectiveShadowMap& rsm() const { return *m_rsm; }
    const nichols::RegularVpls& vpls() const { return *m_vpls; }

    static constexpr std::array<std::string_view, 2> kFormFactors{"disk", "point"};

private:
    bool m_equalSolidAngle = false;  // Eq. 4.4 approximation off: exact texel solid angles
    int m_rsmSize = 256;      // thesis §4.2.1.2: 256^2 RSM
    int m_vplGrid = 16;       // 16^2 = 256 VPLs (Table 4.1)
    std::string m_formFactor{"disk"};
    float m_minDistance = 0.0f;   // metres; Eq. 3.2's r^2 clamp, value not given; 0 = derived (nichols/SceneScale.h)
    float m_minDistanceMetres = 0.0f;  // the clamp in use
    bool m_glossy = false;        // the thesis's gather is Lambertian; on = full BRDF (multires-splat mode A's limit)
    // VPLs per gather draw, per device profile (core/DeviceProfile.h). llvmpipe: half of its
    // 65535-iteration loop budget per invocation (gpu/ShaderLimits.h); 32k VPLs over a 64^2 image take a
    // few seconds on llvmpipe. GPU: one uniform-block window of the cache (nichols/VplWindow.h, 1024
    // VPLs), which caps a draw on llvmpipe too: a 1080p draw of 1024 VPLs is ~2 G loop iterations, about
    // 0.5 s on an integrated GPU, under the ~2 s watchdog. Engineering choices, not from the thesis.
    static constexpr int kVplBatchLlvmpipe = 32768;
    static constexpr int kVplBatchGpu = 1024;
    int m_vplBatch = kVplBatchLlvmpipe;
    voxels::VplVisibilitySettings m_visibilitySettings;  // beyond the thesis; off by default
    std::optional<voxels::VplVisibility> m_visibility;
    std::optional<nichols::ReflectiveShadowMap> m_rsm;
    std::optional<nichols::RegularVpls> m_vpls;
    gl::Program m_gather;
    gl::Framebuffer m_fbo;
};

}  // namespace bounce
