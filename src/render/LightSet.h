#pragma once
// The lights at the current time: each one's GPU description (LightGpu, in a uniform buffer) and
// its shadow map. Spot lights up to
// kMaxPerspectiveSpotAngle get a perspective 2D depth map; directional lights an orthographic one
// fitted to the scene bounds; point lights, area lights (from their centre) and wider spots a cube
// map of light-to-surface distance. A directional light's map is an atlas of view-fitted cascades
// and the whole-scene map (render/ShadowCascades.h, docs/rendering.md "Shadows"). Maps are re-rendered
// only when their light, a dynamic object or (cascades) the camera moved: static views render them once.
#include "common/shared.h"
#include "gpu/Program.h"
#include "render/RenderSettings.h"
#include "render/ShadowCascades.h"
#include "render/SceneDrawer.h"

#include <cstdint>
#include <vector>

namespace bounce::render {

class LightSet {
public:
    static Expected<LightSet> create();

    // Updates LightGpu data for the lights at the scene's current time and re-renders stale maps;
    // directional lights' cascades are fitted to `camera`.
    void update(SceneDrawer& drawer, const RenderSettings& settings, const View& camera);

    size_t count() const { return m_entries.size(); }
    const gpu::LightGpu& light(size_t i) const { return m_entries[i].gpu; }
    // Binds light i's UBO (BINDING_UBO_LIGHT) and map (BINDING_TEX_SHADOW or _CUBE).
    void bind(size_t i) const;
    // Binds light i's maps to chosen units: its 2D depth map (or a 1x1 dummy) at unit2D and its cube
    // distance map (or a dummy) at unitCube, so a pass can sample several lights at once.
    void bindShadowMaps(size_t i, unsigned unit2D, unsigned unitCube) const;
    size_t mapsRendered() const { return m_mapsRendered; }
    // Light i's emission texture (area lights, Scene.h AreaTexture) at the current time: RGBA32F with
    // a full mip chain and trilinear filtering, addressed (u, v) as the scene model (no flip needed); a
    // 1x1 white texture for an untextured light. Also bound at BINDING_TEX_AREA_LIGHT by bind(i).
    const gl::Texture& areaTexture(size_t i) const;
    // Changes whenever a light's texture shows a new image (a sequence's next frame, the bouncing
    // square moving), so that a technique can tell a dynamic light texture from a still one.
    uint64_t areaTextureUploads() const { return m_areaTextureUploads; }

private:
    struct Entry {
        gpu::LightGpu gpu{};
        gl::Texture depth;      // 2D depth (directional: the cascades' atlas), or cube depth for the z-test of cube maps
        gl::Texture distance;   // cube R32F distance / far
        gl::Framebuffer fbo;
        gl::Buffer ubo;
        int size = 0;
        int tiles = 1;          // atlas tiles per side (render/ShadowCascades.h)
        ShadowCascades cascades;  // what the map was rendered with
        Light rendered;         // the light state the map was rendered for
        bool valid = false;
        gl::Texture emission;   // area light texture (empty: untextured)
        int64_t emissionKey = -1;  // the frame it shows (sequences) or -1 - time in microseconds (procedural)
        glm::vec3 emissionMean{1.0f};  // mean texel of `emission` (1: untextured)
    };
    void updateAreaTexture(Entry& e, const Scene& scene, const Light& light, float time);
    gl::Program m_depthProgram, m_distanceProgram;
    // Bound to the shadow unit a light does not use, so both samplers always see a complete texture
    // of their type.
    gl::Texture m_dummy2D, m_dummyCube, m_white;
    std::vector<Entry> m_entries;
    uint64_t m_areaTextureUploads = 0;
    size_t m_mapsRendered = 0;
};

// The GPU form of a light (no shadow information).
gpu::LightGpu toGpu(const Light& light);

}  // namespace bounce::render
