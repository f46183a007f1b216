#pragma once
// One technique rendering one scene: the frame loop shared by `bounce render`, `bounce view`, the
// tests and the benchmarks. Per frame: scene update (time = frame / frameRate), light set and
// shadow maps, camera G-buffer, direct light, the technique's indirect light, full = direct +
// indirect. Every pass is timed (GpuTimers) under the names used in run records.
#include "core/Image.h"
#include "techniques/Technique.h"

#include <memory>

namespace bounce {

enum class Component { Full, Direct, Indirect };
Expected<Component> parseComponent(std::string_view name);
std::string_view componentName(Component c);

struct FrameStats {
    uint32_t frame = 0;
    float time = 0.0f;               // seconds
    double cpuMilliseconds = 0.0;    // wall time of renderFrame, including the GPU wait unless timings are late
    std::vector<gl::PassTime> passes;  // "frame" first
    bool passesLate = false;           // passes are the previous renderFrame's (setLateTimings)
    Counters counters;
    gl::LiveResources resources;  // the GL objects and storage bytes live after the frame (gpu/Objects.h)
    uint64_t residentBytes = 0;   // the process's resident set size after the frame (core/Resources.h)
};

class Pipeline {
public:
    // The technique's settings must already be applied. Builds programs and uploads the scene.
    static Expected<std::unique_ptr<Pipeline>> create(const Scene& scene, std::unique_ptr<Technique> technique,
                                                      glm::ivec2 size, const render::RenderSettings& settings);

    // Renders frame `frame`; the camera is the scene's (animated) camera unless overridden.
    FrameStats renderFrame(uint32_t frame, const Camera* cameraOverride = nullptr);
    // The same with the scene's animation at `time` seconds instead of frame / frameRate: frame
    // `frame` of the run showing another moment, e.g. a study's animation held after an event while
    // an incremental technique keeps converging (docs/studies.md "Temporal").
    FrameStats renderFrame(uint32_t frame, float time, const Camera* cameraOverride = nullptr);

    const gl::Texture& output(Component c) const;
    // The shared views (outputs, G-buffer channels) followed by the technique's (Technique::debugViews).
    std::vector<DebugView> debugViews() const;
    Image readback(Component c) const;

    // Timings one frame late (the viewer; gl::GpuTimers::Latency::OneFrame): renderFrame no longer
    // waits for the GPU at its end, and FrameStats::passes are the previous frame's. Measured runs
    // (`render --stats`, sweeps, benchmarks) keep the default: each frame waits and holds its own times.
    void setLateTimings(bool late);
    bool lateTimings() const { return m_lateTimings; }

    Technique& technique() { return *m_technique; }
    const render::RenderSettings& renderSettings() const { return m_settings; }
    render::SceneGpu& sceneGpu() { return m_sceneGpu; }
    const render::GBuffer& gbuffer() const { return m_gbuffer; }
    glm::ivec2 size() const { return m_size; }

private:
    Pipeline(const Scene& scene, glm::ivec2 size, const render::RenderSettings& settings);

    const Scene& m_scene;
    glm::ivec2 m_size;
    render::RenderSettings m_settings;
    render::SceneGpu m_sceneGpu;
    render::SceneDrawer m_drawer;
    render::LightSet m_lights;
    render::GBuffer m_gbuffer;
    render::DirectLighting m_directLighting;
    std::unique_ptr<Technique> m_technique;
    gl::Program m_compose;
    gl::Texture m_direct, m_indirect, m_full;
    gl::Framebuffer m_composeFbo;
    gl::Buffer m_frameUbo;
    gl::GpuTimers m_timers;
    bool m_lateTimings = false;
};

// Linear RGB of an RGBA32F texture, top row first.
Image readTexture(const gl::Texture& texture);

}  // namespace bounce
