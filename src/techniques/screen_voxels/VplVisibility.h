#pragma once
// Optional VPL-to-receiver visibility for the RSM-family gathers (rsm, isr, hisr, multires-splat), beyond
// Nichols (2010) ch. 3-4, whose gathers have none: each VPL's contribution at a receiver is multiplied by
// a binary test of the segment between them in the screen-space voxelization of ch. 5 (§5.3.3,
// ScreenVoxels, march.glsl). One declaration of the settings for all four techniques; off by default
// (the thesis). Limitation: the voxels hold only what the camera's frustum holds, so occluders outside
// it (behind the camera, beside the view) do not block. Shaders include
// shaders/techniques/screen_voxels/vpl_visibility.glsl.
#include "core/Settings.h"
#include "techniques/Technique.h"
#include "techniques/screen_voxels/ScreenVoxels.h"

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace bounce::voxels {

inline constexpr std::array<std::string_view, 2> kRayMarches{"columns", "uniform"};

struct VplVisibilitySettings {
    bool enabled = false;  // off: the thesis's gathers, no indirect visibility
    int columns = 128;     // voxel columns per side (thesis §5.3.3: 128^2 "almost indistinguishable" from 1024^2)
    int bits = 128;        // depth slices per column (thesis: 128, one RGBA32UI target)
    // How a segment is tested: "columns" visits every voxel column it crosses but its end points' own
    // (voxelTrace, bounce's extension); "uniform" samples it at `steps` points (voxelMarch, the thesis's
    // march), which steps over thin occluders seen at grazing angles (a table top at eye level;
    // docs/techniques/rsm.md, "VPL visibility").
    std::string march{"columns"};
    int steps = 16;        // uniform march samples per segment: an assumption, the thesis gives no count
    // Extra bits each side of a sample's slice range (§5.3.3.1's thick ray). 0 by default: the column
    // traversal finds every surface without it (each surface's bits span its depth over the column),
    // and one extra bit darkened receivers within a slice of a concave edge. Measured on furnished-room
    // at 128^2 (rsm, 256 VPLs): relMSE against the one-bounce reference 0.011 with 0, 0.017 with 1; the
    // empty room against visibility off 0.0010 with 0, 0.0042 with 1. The thesis's uniform march relies on it
    // (with 0 it tests single slices).
    int thickness = 0;
    // Origin bias at both ends, along the receiver's and the VPL's normals, in slice depths: a surface
    // facing the camera clears its own bits after thickness + 1 slices (ScreenVoxelsGpuTest.
    // OriginBiasKeepsASegmentOffItsOwnSurface); 2 leaves a slice for surfaces seen obliquely.
    float bias = 2.0f;

    // Declares vplVisibility, voxelColumns, voxelBits, rayMarch, raySteps, rayThickness, rayBias.
    void visit(SettingsVisitor& v);
};

class VplVisibility {
public:
    // Checks the grid against the GL limits when visibility is on; errors name the setting.
    static Expected<VplVisibility> create(const VplVisibilitySettings& settings);

    bool enabled() const { return m_settings.enabled; }
    // Timer "voxelize": voxelizes the camera's view of the scene and zeroes the ray counters; nothing
    // when off.
    void build(FrameContext& ctx);
    // The host define of the gather shaders (vpl_visibility.glsl's VPL_VISIBILITY): build the gather
    // program with it, so that with visibility off the shader has no visibility code at all.
    std::vector<std::pair<std::string, std::string>> defines() const;
    // The march settings as uniforms of a gather program; when on, also binds the grid and the ray
    // counters (call before the gather's draws).
    void setUniforms(gl::Program& program) const;
    // Loop iterations one visibility test may add to a shader invocation (gpu/ShaderLimits.h), 0 when
    // off, counted as llvmpipe counts them: per SIMD vector of invocations (see the .cpp).
    int loopIterationsPerTest() const;
    // Counters "visibilityRays" (segments marched) and "visibilityBlocked" (of those, blocked), read
    // back from the gather shaders' sums; nothing when off. Waits for the GPU: from the technique's
    // collectCounters, after the frame is queued.
    void collectCounters(Counters& out) const;

private:
    VplVisibilitySettings m_settings;
    std::optional<ScreenVoxels> m_voxels;
    gl::Buffer m_rays;  // 4 x uint: marched (low, high word), blocked (low, high word)
};

}  // namespace bounce::voxels
