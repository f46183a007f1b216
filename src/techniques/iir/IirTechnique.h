#pragma once
// Incremental instant radiosity (Laine, Saransaari, Kontkanen, Lehtinen, Aila, EGSR 2007): a VPL set
// maintained incrementally on the CPU (VplDistribution, CGAL), paraboloid shadow maps rendered only
// for new VPLs, and interleaved-sampling accumulation with a geometry-aware filter. See IirTechnique.cpp
// and docs/techniques/iir.md.
#include "gpu/Program.h"
#include "reference/RayCaster.h"
#include "techniques/Technique.h"
#include "techniques/iir/TileAssignment.h"
#include "techniques/paraboloid/ParaboloidMaps.h"
#include "techniques/iir/VplDistribution.h"

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <optional>
#include <vector>

namespace bounce {

// What the VPLs are shot from: the scene's first light, turned into a point emitter (docs: "Lights").
struct IirPrimaryLight {
    Light emitter;        // a Spot or Point light at the current time
    glm::vec3 flux{0.0f};  // W per channel, the flux the sampling domain distributes
    bool supported = false;
};

class IirTechnique final : public Technique {
public:
    static constexpr std::array<std::string_view, 2> kFilters{"tent", "box"};
    std::string_view name() const override { return "iir"; }
    bool bouncesLightsOnly() const override { return true; }
    void visitSettings(SettingsVisitor& v) override;
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
    // vplMapSamples: depth samples that passed over this frame's paraboloid maps (a query read after the
    // frame is queued): the fragment work behind a map's cost (docs/techniques/iir.md, R1).
    void collectCounters(Counters& out) override;
    // positionThresholdMetres (the filter's alpha), clampDistanceMetres (d_c), shadowBiasMetres: the
    // settings, fractions of the scene diagonal, times the diagonal.
    void derivedSettings(std::map<std::string, double>& out) const override;

    // For tests and benchmarks: the distribution, the flux each sample carries this frame (W per
    // channel, indexed by slot) and the primary light's flux.
    const VplDistribution* distribution() const { return m_distribution ? &*m_distribution : nullptr; }
    const std::vector<glm::vec3>& sampleFlux() const { return m_sampleFlux; }
    glm::vec3 primaryFlux() const { return m_primary.flux; }
    uint32_t shadowMapsRenderedLastFrame() const { return m_mapsRenderedLastFrame; }
    // The interleaving tile of each VPL (kept for the VPL's life, TileAssignment.h).
    const TileAssignment& tiles() const { return m_tiles; }
    // The buffers the accumulation reads: iir.vpls (64 B per VPL: position with w = slot, normal,
    // tangent, intensity) and iir.tiles (n*m + 1 offsets, then each tile's VPL indices).
    const gl::Buffer& vplBuffer() const { return m_vplBuffer; }
    const gl::Buffer& tileBuffer() const { return m_tileBuffer; }
    // The paraboloid shadow maps (GL_DEPTH_COMPONENT16 2D array, layer = slot) and the unit normal
    // (the map's +z) of the VPL in a slot, for tests that check the maps' contents.
    const gl::Texture& shadowMaps() const { return m_maps.maps(); }
    glm::vec3 slotNormal(SlotId slot) const { return m_slots.at(slot).normal; }
    // The paraboloid frame's +x for a normal (+y is normal x tangent) and the world position the map
    // is rendered from for a VPL at `position` with `normal`.
    static glm::vec3 paraboloidTangent(glm::vec3 normal);
    glm::vec3 paraboloidOrigin(glm::vec3 position, glm::vec3 normal) const;
    float paraboloidFar() const;

    // The primary light for `scene` at time t (exposed for tests).
    static IirPrimaryLight primaryLight(const Scene& scene, float time);

private:
    struct SlotAttributes {
        glm::vec3 normal{0.0f, 1.0f, 0.0f};  // unit, facing the light
        glm::vec3 albedo{0.0f};              // diffuse albedo at the hit (blurred texture)
    };
    void updateVpls(FrameContext& ctx, const LightPose& pose);
    void renderShadowMaps(FrameContext& ctx, const std::vector<SlotId>& slots);
    void uploadVpls();

    // Settings (paper defaults where the paper gives one).
    int m_maxLights = 256;
    int m_recalcMin = 4;
    int m_recalcMax = 8;
    bool m_incremental = true;
    int m_shadowMapSize = 256;
    int m_tilesX = 4, m_tilesY = 4;
    std::string m_filterKernel{"tent"};
    float m_normalThreshold = 0.8f;
    float m_positionThreshold = 0.03f;
    float m_clampDistance = 0.05f;
    float m_shadowBias = 0.004f;
    bool m_paperNormalisation = false;

    // State.
    const Scene* m_scene = nullptr;
    IirPrimaryLight m_primary;
    std::optional<VplDistribution> m_distribution;
    std::optional<RayCaster> m_rayCaster;
    std::vector<SlotAttributes> m_slots;
    std::vector<glm::vec3> m_sampleFlux;
    std::vector<glm::vec3> m_textureMeans;
    TileAssignment m_tiles;
    float m_sceneDiagonal = 1.0f;
    glm::ivec2 m_tileSize{1};
    uint32_t m_mapsRenderedLastFrame = 0;
    gl::Query m_mapSamples;     // GL_SAMPLES_PASSED over the frame's maps
    bool m_mapQueries = false;  // this frame's maps were queried

    gl::Program m_split, m_accumulate, m_combine, m_filter;
    paraboloid::ParaboloidMaps m_maps;  // GL_DEPTH_COMPONENT16, one layer per slot
    gl::Texture m_splitPosition, m_splitNormal, m_tileIrradiance, m_irradiance;
    gl::Framebuffer m_splitFbo, m_accumulateFbo, m_combineFbo, m_filterFbo;
    gl::Buffer m_vplBuffer, m_tileBuffer;
};

}  // namespace bounce
