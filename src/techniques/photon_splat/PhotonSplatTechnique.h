#pragma once
// `photon-splat`: photon splatting with orthographic bundles (seed 004). See PhotonSplatTechnique.cpp
// for the passes and docs/techniques/photon-splat.md for settings and deviations.
#include "techniques/Technique.h"
#include "techniques/nichols/RegularVpls.h"
#include "techniques/photon_splat/BundleVolume.h"
#include "techniques/photon_splat/PhotonInjection.h"
#include "techniques/photon_splat/splat_shared.h"

#include <array>
#include <memory>
#include <optional>
#include <string>

namespace bounce {

class PhotonSplatTechnique final : public Technique {
public:
    std::string_view name() const override { return "photon-splat"; }
    void visitSettings(SettingsVisitor& v) override;
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
    std::string_view frameReadbackReason() const override;
    // M6: bundles per pixel (the overlap texture, read after the frame): mean and largest over the
    // pixels some bundle reached, and how many pixels that is.
    void collectCounters(Counters& out) override;
    // mapSizeMetres (bundle width 2h; 0: a twentieth of the scene diagonal), depthToleranceMetres (0: 1/20
    // texel of the bundle map), stepBackMetres and mapDepthMetres when set (0: per bundle, from its photon
    // and to where its rays leave the scene's box, so no single value), sceneDiagonalMetres.
    void derivedSettings(std::map<std::string, double>& out) const override;
    void debugViews(std::vector<DebugView>& out) const override {
        if (m_rsm) m_rsm->debugViews(out);
        // Where each bundle of the frame is centred: its photon's hit point, or where a photon's escaping
        // ray leaves the scene's box (5-pixel dots).
        if (m_bundlePoints) out.push_back({"photon-splat.bundles", &m_bundlePoints, DebugEncoding::Points, 5.0f});
        for (size_t i = 1; i < kDebugViews.size(); ++i)
            out.push_back({"photon-splat." + std::string(kDebugViews[i]), nullptr, DebugEncoding::Radiance, 1.0f, "debugView",
                           std::string(kDebugViews[i])});
    }

    static constexpr std::array<std::string_view, 3> kFilters{"gaussian", "tent", "box"};
    static constexpr std::array<std::string_view, 2> kEstimates{"flux", "normalized"};
    static constexpr std::array<std::string_view, 4> kDebugViews{"none", "overlap", "accumulation", "grid"};
    static constexpr std::array<std::string_view, 2> kInjections{"rays", "rsm"};
    static constexpr std::array<std::string_view, 3> kDepthMaps{"raster", "compute", "rays"};

    // For tests: the photons and bundles of the last frame.
    const std::vector<photonsplat::Photon>& photons() const { return m_photonList; }
    const std::vector<photonsplat::Bundle>& bundles() const { return m_bundles; }
    // For tests: the GL storage the byte counters describe.
    const gl::Buffer& bundleBuffer() const { return m_bundleBuffer; }
    const gl::Texture& depthAtlas() const { return m_maps; }
    // Tests: use these photons every frame instead of shooting them (stratification still applies).
    void setFixedPhotons(std::vector<photonsplat::Photon> photons) { m_fixedPhotons = std::move(photons); }
    // Tests: off draws every cluster into every bundle's map (the culling must not change the maps).
    void setCullClusters(bool on) { m_cullClusters = on; }

private:
    void updateGeometry(FrameContext& ctx);
    // Method B of 3.2: the reflective shadow map's regular VPLs as photons (GPU, read back).
    std::vector<photonsplat::Photon> rsmPhotons(FrameContext& ctx, uint64_t seed);
    void buildDraws(const std::vector<glm::uvec2>& pairs);
    void renderMapsByRaster(FrameContext& ctx, int first);
    void renderMapsInCompute(FrameContext& ctx, int first, const std::vector<glm::uvec4>& work);
    size_t traceMaps(int first, int n);  // depthMaps=rays; returns the rays traced

    // Settings (docs/techniques/photon-splat.md gives the sources of the defaults).
    std::string m_injection{"rays"};
    std::string m_depthMaps{"rays"};  // a device-profile default: raster on a GPU
    int m_rsmSize = 256;
    int m_vplGrid = 32;
    int m_photonCount = 16384;
    int m_bounces = 1;
    int m_seed = 0;
    bool m_reseed = false;
    bool m_stratify = false;
    int m_gridSize = 16;
    int m_threshold = 2;
    float m_mapSize = 0.0f;
    float m_mapDepth = 0.0f;
    float m_stepBack = 0.0f;
    int m_mapResolution = 8;
    float m_depthTolerance = 0.0f;
    std::string m_filter{"gaussian"};
    std::string m_estimate{"flux"};
    float m_exposure = 1.0f;
    float m_ambient = 0.0f;
    int m_blur = 5;
    std::string m_debugView{"none"};

    float depthTolerance() const;  // metres: depthTolerance, or 0: kAutoToleranceTexels of a map texel
    float m_half = 0.0f, m_depth = 0.0f, m_back = 0.0f;  // bundle half width h, depth D, step back b (metres)
    float m_emitterOffset = 0.0f;                         // metres
    glm::vec3 m_lo{0.0f}, m_hi{0.0f};
    glm::ivec2 m_tiles{1};  // depth atlas tiles per row, rows
    std::optional<RayCaster> m_caster;
    std::optional<nichols::ReflectiveShadowMap> m_rsm;
    std::optional<nichols::RegularVpls> m_vpls;
    float m_casterTime = -1.0f;
    std::vector<photonsplat::Photon> m_photonList;
    std::optional<std::vector<photonsplat::Photon>> m_fixedPhotons;
    bool m_cullClusters = true;
    std::vector<photonsplat::Bundle> m_bundles;
    std::vector<photonsplat::BundleVolume> m_volumes;
    // Per-frame CPU work space, kept across frames (the soak test holds the process's memory flat).
    struct DrawCommand {  // DrawElementsIndirectCommand
        GLuint count, instanceCount, firstIndex;
        GLint baseVertex;
        GLuint baseInstance;
    };
    struct CullScratch {
        std::vector<uint32_t> kept, perCluster;
        std::vector<glm::uvec2> pairs;     // (cluster, bundle)
        std::vector<DrawCommand> commands;
        std::vector<glm::uvec2> drawData;  // (bundle, object) per instance
        std::vector<glm::uvec4> rasterPairs;  // depthMaps=compute: (bundle, object, first index, index count)
    } m_cull;
    photonsplat::BundleScratch m_bundleScratch;
    std::vector<gpu::BundleGpu> m_gpuBundles;
    std::vector<glm::vec4> m_pointScratch;
    std::vector<float> m_overlapScratch;
    photonsplat::ClusterSet m_clusters;
    gl::Buffer m_clusterIndices, m_drawCommands, m_drawData;
    size_t m_drawCapacity = 0;  // commands the two draw buffers hold
    std::vector<float> m_tracedAtlas;  // depthMaps=rays: the atlas's rows, traced on the CPU
    int m_tracedRows = 0;              // texel rows of the atlas the last upload wrote
    gl::Buffer m_rasterPairs;   // depthMaps=compute: CullScratch::rasterPairs
    size_t m_rasterCapacity = 0;
    gl::VertexArray m_depthVao;
    int m_pointsWritten = 0;    // texels of m_bundlePoints the last frame wrote
    gl::Buffer m_bundleBuffer;
    gl::Buffer m_ranges;  // per bundle: the depth range of its first hits (tile_range.comp)
    gl::Texture m_maps, m_accum, m_stats, m_blurTemp;
    gl::Texture m_mapsUint;  // depthMaps=compute: m_maps (R32F) viewed as R32UI for depth_raster.comp's atomics
    // The viewer's "photon-splat.bundles": RGBA32F 2D array (one layer), texel i = bundle i's hit point
    // (xyz, w = 1), w = 0 past the frame's bundles.
    gl::Texture m_bundlePoints;
    gl::Framebuffer m_mapFbo, m_accumFbo, m_outFbo;
    gl::Program m_depthProgram, m_rasterProgram, m_rangeProgram, m_splat, m_resolve, m_blurProgram;
};

}  // namespace bounce
