#pragma once
// `area-light`: direct light from large, textured, animated area lights with soft visibility,
// Nichols 2010 ch. 5 (Nichols, Penmatsa & Wyman, "Interactive, multiresolution image-space rendering
// for dynamic area lighting", UICS-10-01): VPLs on the light's mip-mapped texture, the stencilled
// multiresolution gather of ch. 4 with area-light culling, a separate specular (Phong) pass with
// lobe-centred texture samples, screen-space binary voxel visibility refined incrementally through
// per-pixel VPL bitstreams, and incremental (coarse-to-fine) stencil rendering.
#include "techniques/Technique.h"
#include "techniques/area_light/area_shared.h"
#include "techniques/nichols/MultiresBuffer.h"
#include "techniques/paraboloid/ParaboloidMaps.h"
#include "techniques/screen_voxels/ScreenVoxels.h"

#include <array>
#include <optional>

namespace bounce {

class AreaLightTechnique final : public Technique {
public:
    std::string_view name() const override { return "area-light"; }
    void visitSettings(SettingsVisitor& v) override;
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
    void collectCounters(Counters& out) override;
    bool ownsDirect() const override { return true; }

    static constexpr std::array<std::string_view, 4> kVisibilityModes{"incremental", "brute", "none", "shadow-maps"};

    // For tests: the last frame's cell flags (R32UI over the multiresolution atlas, AL_CELL_*) and VPL
    // bitstreams (RGBA32UI atlas array, 128 VPLs of a cell's subset per layer) of the diffuse pass,
    // unless a specular pass ran after it (it reuses the flags), and the diffuse buffer's atlas layout.
    const gl::Texture& cellFlags() const { return m_flags; }
    const gl::Texture& bitstreams() const { return m_bits; }
    const nichols::MultiresBuffer& diffuseBuffer() const { return *m_diffuse; }


private:
    // Fragment-count tickets per level (nichols::MultiresBuffer::fragments), read by collectCounters:
    // rendered = cells shaded; tree = cells of the incremental tree pass (-1: none), plus the rendered.
    struct PassCounts {
        std::vector<int> rendered, tree;
    };
    void updateUniforms(FrameContext& ctx);
    void buildLobePyramid(FrameContext& ctx);
    void bindLightTextures(FrameContext& ctx);
    void bindVoxels();
    int vplsPerDraw() const;
    void renderVplShadowMaps(FrameContext& ctx);
    // The coarse-to-fine level loop of §5.3.4 over one buffer (diffuse or specular).
    PassCounts renderMultires(FrameContext& ctx, nichols::MultiresBuffer& buffer, bool specular);

    // Settings (defaults from the thesis where it gives them; docs/techniques/area-light.md).
    int m_vplsPerSide = 16;            // §5.3.2.1, §5.4.7: 16 x 16 = 256 VPLs
    int m_coarsest = 64;               // §5.3.3.2: incremental visibility starts at 64^2
    nichols::PyramidThresholds m_thresholds{0.1f, 0.3f, false};  // assumptions (as isr; thesis gives none)
    std::string m_visibility{"incremental"};
    bool m_interleave = true;          // §5.3.3.2: 2 x 2 interleaved sampling
    bool m_incrementalStencil = true;  // §5.3.4
    float m_colourThreshold = 0.005f;  // Fig. 5.10
    float m_bitCountFraction = 0.5f;   // §5.3.3.2: 128 of 256 VPLs partially visible
    int m_voxelColumns = 128;          // §5.3.3: 128^2 "almost indistinguishable" from 1024^2
    int m_voxelBits = 128;             // §5.3.3: 128 bits per pixel
    bool m_voxelFootprint = true;      // deviation: fragments set the slices they span (voxelize.frag)
    bool m_voxelOutside = true;        // deviation: a second grid along the lights beyond the camera's frustum
    int m_raySteps = 40;               // the llvmpipe profile's (kRayStepsLlvmpipe); the gpu profile's 64 in visitSettings
    int m_rayThickness = 0;            // extra bits each side of a step's slice span (assumption; 1 over-occludes, docs)
    float m_rayBias = 1.5f;            // voxels (assumption; "bias", Fig. 5.12)
    bool m_specular = true;            // §5.3.2.1: separate Phong pass
    bool m_varianceVisibility = true;  // §5.3.3.3: variance queries for the lobe samples of sharp lobes
    float m_lobeThreshold = 0.1f;      // fraction of the lobe peak bounding the lobe (assumption)
    float m_lobeVpls = 9.0f;           // §5.3.2.1: fewer than 9 VPLs in the lobe -> 5 x 5 samples
    float m_lobeSpacing = 1.0f;        // refine while the cell's angular spread exceeds this x lobe half-angle
    float m_interleaveNormal = 0.9f;   // resolve: neighbours on the same surface (assumption)
    float m_interleaveDepth = 0.05f;   // resolve: plane distance / eye distance (assumption)
    int m_shadowMapSize = 64;          // §5.4.6 baseline: 1024 rasterized 64^2 shadow maps

    std::optional<nichols::MinMaxPyramid> m_pyramid;
    std::optional<nichols::MultiresBuffer> m_diffuse, m_specularBuffer;
    std::optional<voxels::ScreenVoxels> m_voxels, m_outerVoxels;
    gl::Buffer m_noOuterGrid;  // an empty grid's uniforms, bound when voxelOutside is off
    gl::Program m_vplProgram, m_lobeProgram, m_classify, m_stencil, m_gatherDiffuse, m_gatherSpecular, m_resolve,
        m_discontinuity, m_final;
    gl::Buffer m_passUbo, m_vpls, m_stats;
    gl::Texture m_lobe, m_flags, m_bits, m_subsets;
    paraboloid::ParaboloidMaps m_vplMaps;  // visibility=shadow-maps: one layer per VPL
    gl::Program m_moments;
    gl::Texture m_momentsTexture;
    std::vector<gpu::AreaVplGpu> m_vplCpu;  // shadow-map baseline: the VPL positions to render maps from
    float m_sceneDiagonal = 1.0f;
    gl::Framebuffer m_finalFbo, m_clearFbo;
    gpu::AreaPassUniforms m_uniforms{};
    std::vector<size_t> m_lightIndices;  // scene light index of each area light shaded
    int m_vplCount = 0, m_perCell = 0, m_layers = 0;
    bool m_hasSpecularMaterials = false;
    glm::ivec2 m_size{0};
    PassCounts m_frameDiffuse, m_frameSpecular;  // this frame's tickets, for collectCounters
    bool m_frameRan = false;
};

}  // namespace bounce
