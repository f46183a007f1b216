#pragma once
// `hisr`: hierarchical image-space radiosity, Nichols (2010) §4.2.4: the isr eye-space machinery
// (min-max mipmaps, stencil set-up over the flattened atlas, upsampling) with a per-fragment
// traversal of a per-frame VPL tree built over the RSM (threshold tau, maximum depth 1-3).
#include "techniques/Technique.h"
#include "techniques/nichols/StencilledGather.h"
#include "techniques/screen_voxels/VplVisibility.h"

#include <optional>

namespace bounce {

class HisrTechnique final : public Technique {
public:
    std::string_view name() const override { return "hisr"; }
    bool bouncesLightsOnly() const override { return true; }
    void visitSettings(SettingsVisitor& v) override;
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
    void collectCounters(Counters& out) override;
    // The RSM's views and the VPL tree: "hisr.tree.depthD", the nodes a fragment's walk may visit D
    // levels below the roots (D = 0: the rootGrid^2 roots), as dots at their mean VPL positions.
    void debugViews(std::vector<DebugView>& out) const override;

    const nichols::MultiresBuffer& buffer() const { return m_eye->buffer(); }
    const nichols::MinMaxPyramid& eyePyramid() const { return m_eye->eye(); }
    // The VPL tree as the gather reads it (tree.comp's records), for tests that walk it on the CPU.
    const gl::Buffer& treeRecords() const { return m_tree; }
    const std::vector<int>& treeLevelOffsets() const { return m_treeOffsets; }
    const nichols::MinMaxPyramid& lightPyramid() const { return *m_light; }

private:
    // Loop iterations of one root's walk to `depth` levels, its visibility tests included.
    int rootWalkIterations(int depth) const;
    // "vpl-tree": the light pyramid re-laid out as Morton-ordered node records (shaders/techniques/hisr/tree.comp).
    void buildTree();
    static constexpr int kMaxTreeLevels = 16;  // gather.frag's u_levelOffset[16], u_refineT[16]
    static constexpr size_t kTreeRecordBytes = 4 * 16;  // four vec4 per node (tree.comp)

    int m_rsmSize = 256;       // §4.2.1.2
    int m_rootGrid = 16;       // §4.2.4: 16^2 coarsest light patches
    int m_maxDepth = 2;        // 1..3 (32^2..128^2); 2 is an assumption within the thesis's range
    float m_tau = 0.01f;       // Eq. 4.8 threshold on the normalised bound (assumption; thesis gives none)
    int m_indirectSize = 0;  // indirect-resolution cap (thesis ch. 3: 128^2..1024^2 in 1024^2); 0 = output size
    int m_eyeCoarsest = 16;
    std::string m_upsampling = "empty-aware";  // nichols::UpsampleFilter (§3.2.5; the others for comparison)
    std::string m_gatherPass = "compute";      // nichols::GatherPass (bounce default; "stencil" is the thesis's)
    nichols::PyramidThresholds m_eyeThresholds{0.1f, 0.3f, false};
    voxels::VplVisibilitySettings m_visibilitySettings;  // beyond the thesis; off by default
    std::optional<voxels::VplVisibility> m_visibility;
    std::optional<nichols::ReflectiveShadowMap> m_rsm;
    std::optional<nichols::MinMaxPyramid> m_light;
    std::optional<nichols::StencilledGather> m_eye;
    gl::Program m_gather, m_treeBuild;
    gl::Buffer m_gatherCounts;
    gl::Buffer m_tree;        // the VPL tree's records
    gl::Texture m_treeView;   // m_tree as an RGBA32F buffer texture (the gather's texelFetch)
    std::vector<int> m_treeOffsets;  // records before each level
    bool m_gathered = false;  // this frame ran the gather (collectCounters has counts to read)
};

}  // namespace bounce
