#pragma once
// `isr`: image-space radiosity, Nichols (2010) Ch. 4 (§4.2.1-4.2.2): eye-space min-max mipmaps, a
// one-pass stencil set-up over the flattened multiresolution buffer, a stencilled gather from a VPL
// cache with the disk-to-point form factor, coarse-to-fine upsampling; VPLs either on a regular RSM
// grid (the stencilled gather of Table 4.1) or as multiresolution light-space clusters (§4.2.2).
#include "techniques/Technique.h"
#include "techniques/nichols/RegularVpls.h"
#include "techniques/nichols/StencilledGather.h"
#include "techniques/screen_voxels/VplVisibility.h"

#include <array>
#include <optional>

namespace bounce {

class IsrTechnique final : public Technique {
public:
    std::string_view name() const override { return "isr"; }
    bool bouncesLightsOnly() const override { return true; }
    void visitSettings(SettingsVisitor& v) override;
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
    void collectCounters(Counters& out) override;
    void debugViews(std::vector<DebugView>& out) const override {
        if (m_rsm) m_rsm->debugViews(out);
        if (m_regular) m_regular->debugViews(out);
    }

    const nichols::MultiresBuffer& buffer() const { return m_eye->buffer(); }
    const nichols::MinMaxPyramid& eyePyramid() const { return m_eye->eye(); }
    const nichols::StencilledGather& gather() const { return *m_eye; }  // for tests
    int vplCount() const { return m_vplCount; }  // as of the last collectCounters
    // vplMode=clusters: the light pyramid and the cluster VPLs (count in clusterCount()), for tests.
    const nichols::MinMaxPyramid& lightPyramid() const { return *m_light; }
    const gl::Buffer& clusterVpls() const { return m_clusterVpls; }
    const gl::Buffer& clusterCount() const { return m_count; }

    static constexpr std::array<std::string_view, 2> kVplModes{"clusters", "regular"};

private:
    bool m_equalSolidAngle = false;  // Eq. 4.4 approximation off: exact texel solid angles
    int m_rsmSize = 256;            // §4.2.1.2
    std::string m_vplMode{"clusters"};
    int m_vplGrid = 16;             // regular mode: 16^2 = 256 VPLs (Table 4.1)
    int m_lightCoarsest = 16;       // §4.2.4: "16^2 coarsest light patches"
    int m_lightFinest = 32;         // finest cluster level (the llvmpipe profile's; the gpu profile's 64 in visitSettings)
    int m_indirectSize = 0;  // indirect-resolution cap (thesis ch. 3: 128^2..1024^2 in 1024^2); 0 = output size
    int m_eyeCoarsest = 16;         // §3.2.4: illumination buffer from 16^2
    std::string m_upsampling = "empty-aware";  // nichols::UpsampleFilter (§3.2.5; the others for comparison)
    std::string m_gatherPass = "compute";      // nichols::GatherPass (bounce default; "stencil" is the thesis's)
    nichols::PyramidThresholds m_eyeThresholds{0.1f, 0.3f, false};    // assumptions (thesis gives none)
    nichols::PyramidThresholds m_lightThresholds{0.1f, 0.3f, false};  // assumptions
    voxels::VplVisibilitySettings m_visibilitySettings;  // beyond the thesis; off by default
    std::optional<voxels::VplVisibility> m_visibility;
    std::optional<nichols::ReflectiveShadowMap> m_rsm;
    std::optional<nichols::RegularVpls> m_regular;
    std::optional<nichols::MinMaxPyramid> m_light;
    std::optional<nichols::StencilledGather> m_eye;
    gl::Program m_gather, m_clusters;
    gl::Buffer m_clusterVpls, m_count;
    int m_vplCount = 0;
    bool m_gathered = false;  // this frame ran the gather (collectCounters has counts to read)
};

}  // namespace bounce
