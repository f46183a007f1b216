#pragma once
// `vct`: voxel cone tracing with hybrid voxelization and spherical-harmonics radiance (Rauwendaal
// 2013). See VctTechnique.cpp for the passes and docs/techniques/vct.md for settings and deviations.
#include "gpu/GpuInfo.h"
#include "gpu/ListDispatch.h"
#include "techniques/Technique.h"
#include "techniques/vct/RadianceRange.h"
#include "techniques/vct/vct_shared.h"

#include <array>
#include <string>
#include <vector>

namespace bounce {

class VctTechnique final : public Technique {
public:
    std::string_view name() const override { return "vct"; }
    bool bouncesLightsOnly() const override { return true; }
    void visitSettings(SettingsVisitor& v) override;
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
    void collectCounters(Counters& out) override;
    // The voxel grid as used (boxSide = 0: a cube around the scene's bounds): boxSideMetres,
    // boxCentre{X,Y,Z}Metres, voxelSizeMetres, and the cone lengths maxDistanceMetres (0: the grid's
    // diagonal) and aoDistanceMetres (0: a quarter of the grid's side).
    void derivedSettings(std::map<std::string, double>& out) const override;
    void debugViews(std::vector<DebugView>& out) const override {
        for (size_t i = 1; i < kDebugViews.size(); ++i)
            out.push_back({"vct." + std::string(kDebugViews[i]), nullptr, DebugEncoding::Radiance, 1.0f, "debugView",
                           std::string(kDebugViews[i])});
    }
    // With coneShadows the pixel's direct light is shadowed by a cone per light (Eq. 6.3).
    bool ownsDirect() const override { return m_coneShadows; }

    static constexpr std::array<std::string_view, 3> kVoxelizers{"hybrid", "triangle", "fragment"};
    static constexpr std::array<std::string_view, 2> kSeparabilities{"conservative", "thin"};
    static constexpr std::array<std::string_view, 4> kStorages{"iso", "aniso", "sh-f32", "sh-u8"};
    static constexpr std::array<std::string_view, 2> kAtomics{"average", "max"};
    static constexpr std::array<std::string_view, 2> kTracers{"generic", "specialised"};
    static constexpr std::array<std::string_view, 2> kAnisoBlends{"transmittance", "linear"};
    static constexpr std::array<std::string_view, 5> kDebugViews{"none", "occupancy", "radiance", "ao", "slice"};

    // For tests and benchmarks: the volumes of the last frame.
    int resolution() const { return m_resolution; }
    // Level-0 occupancy (x fastest), from the binary volume or the isotropic volume's opacity.
    std::vector<uint8_t> downloadOccupancy() const;
    // Level `level` of the isotropic volume as RGBA8 (x fastest).
    std::vector<uint32_t> downloadIso(int level) const;
    // Level `level` of the volume texture `index` (aniso face, SH coefficient or SH-U8 channel) as
    // floats, 4 per voxel for RGBA formats and 1 for R32F.
    std::vector<float> downloadVolume(int index, int level) const;
    glm::mat4 voxelFromWorld() const { return m_uniforms.voxelFromWorld; }
    // Bytes per level-0 voxel of the radiance storage alone (R8), the thesis's figures per format.
    static double radianceBytesPerVoxel(std::string_view storage);
    // Refuses, in one line, a storage buffer past `info`'s GL_MAX_SHADER_STORAGE_BLOCK_SIZE: the
    // large-triangle list (6 words per scene triangle) and the active lists (level 0 holds up to
    // 32 N^2 voxels) at `resolution` (issue 29 #6; setup passes the context's limits).
    static Expected<void> checkBuffers(const gl::GpuInfo& info, int resolution, size_t triangles);
    // Bytes per level-0 voxel of the radiance volumes and of the opacity volume as allocated: the
    // level-0 texel sizes GL reports for the textures this frame uses (the R8 counters).
    double allocatedRadianceBytesPerVoxel() const;
    double allocatedAlphaBytesPerVoxel() const;

private:
    struct ActiveList {
        gl::Buffer buffer;  // ListHead (count, capacity), then packed voxels
        gl::Buffer args;    // the passes' DispatchIndirectCommand over it (gpu/ListDispatch.h)
        uint32_t capacity = 0;
    };
    int storageId() const;
    Expected<void> buildPrograms();
    Expected<void> allocate(const SetupContext& ctx);
    void updateUniforms(FrameContext& ctx);
    void clearVolumes();
    // Sparse path: zero last frame's listed voxels of every level instead of the dense levels.
    void clearListedVoxels();
    void voxelize(FrameContext& ctx);
    void postVoxelize(bool sparse);
    void mipmap(bool sparse);
    void runPass(gl::Program& dense, gl::Program& sparse, bool sparseMode, int level, int listIn, int listOut);
    void trace(FrameContext& ctx, const gl::Texture& indirect);
    void coneShadowedDirect(FrameContext& ctx);
    // Binds `target`, the G-buffer, the volumes and the parameters for a full-screen pass.
    void beginFullScreen(FrameContext& ctx, const gl::Texture& target);
    void bindVolumes() const;

    // Settings (docs/techniques/vct.md gives the sources of the defaults).
    std::string m_voxelizer{"hybrid"};
    int m_resolution = 64;
    std::string m_separability{"conservative"};
    float m_cutoff = 3.0f;
    std::string m_storage{"aniso"};
    std::string m_atomic{"average"};
    int m_casRetries = 255;
    // voxelizer=triangle: 8 geometry-shader invocations a triangle (GL guarantees 32). The thesis's one
    // invocation loops over a triangle's whole box: on llvmpipe it lost 25 % of cornell-box's voxel
    // writes at N=64 (20,987 of 27,918; 4, 8 and 32 invocations all write 27,918, as the hybrid does),
    // and at N=512 a floor's box is ~10^6 iterations on a GPU (watchdog; issue 29 #10).
    int m_triangleInvocations = 8;
    bool m_sparseMip = true;
    bool m_binary = false;
    std::string m_tracer{"generic"};
    bool m_tangentCap = true;
    std::string m_anisoBlend{"transmittance"};
    bool m_opacityCorrection = true;
    float m_startOffset = 1.5f;
    float m_maxStartOffset = 4.0f;
    float m_maxDistance = 0.0f;
    float coneLength(float side) const;  // maxDistance, or 0: the grid's diagonal (metres)
    float aoLength(float side) const;    // aoDistance, or 0: a quarter of the grid's side (metres)
    float m_aoDistance = 0.0f;
    bool m_specular = true;
    bool m_coneShadows = false;
    float m_shadowAperture = 2.0f;  // degrees
    float m_specularApertureScale = 1.0f;
    float m_radianceRange = 0.0f;
    std::string m_debugView{"none"};
    int m_debugLevel = 0;
    float m_debugSlice = 0.5f;
    float m_boxSide = 0.0f;
    glm::vec3 m_boxCentre{0.0f};
    int m_memoryBudgetMiB = 2048;

    int m_levels = 1;
    bool m_floatAtomics = true;   // GL_NV_shader_atomic_float present (else SH-F32 adds by CAS loops)
    bool m_sparseActive = false;  // sparse path on (off after an overflow of a list)
    bool m_frameSparse = false;   // this frame mipmapped sparsely (collectCounters reads its lists)
    bool m_warnedOversized = false;  // the oversizedTriangles warning is given once
    bool m_listsValid = false;    // the lists hold every voxel the last frame wrote (sparse clear possible)
    gpu::VctUniforms m_uniforms{};
    gl::Buffer m_ubo, m_counters, m_large;
    uint32_t m_largeCapacity = 0;
    gl::Texture m_iso, m_binaryVolume, m_mutex, m_count;
    std::vector<gl::Texture> m_volumes;  // aniso faces / SH coefficients / SH-U8 channels
    std::vector<ActiveList> m_lists;     // per level
    gl::Texture m_dummy2D, m_dummyCube;
    gl::Framebuffer m_voxelFbo, m_traceFbo;
    gl::Program m_voxTriangle, m_voxHybrid, m_voxFragment, m_voxLarge;
    gl::Program m_postDense, m_postSparse, m_mipIsoDense, m_mipIsoSparse, m_mipDense, m_mipSparse, m_clearSparse;
    gl::ListDispatch m_listDispatch;  // the sparse passes' dispatch sizes from the lists' counts
    gl::Program m_traceDiffuse, m_traceSpecular, m_emission, m_directCone;
    const render::SceneGpu* m_sceneGpu = nullptr;
    std::vector<vct::RangeSample> m_rangeSamples;  // the automatic radiance range's surface samples
};

}  // namespace bounce
