#pragma once
// `bounce render` as a library: one technique on one scene in the process's GL context
// (app/ProcessContext.h), frames rendered on demand, read back and recorded. The command and
// `import bounce` both drive it, so both check the same things in the same order and fail with the
// same one-line messages. The scene is shared: edits made to it between frames (scene/SceneEdits.h)
// show in the next frame (after invalidateObjects() for moved objects).
#include "core/Error.h"
#include "core/ToneMap.h"
#include "gpu/Context.h"
#include "techniques/Pipeline.h"

#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

namespace bounce {

// The technique named by --technique ("--technique: unknown technique ..."), checked before the scene
// is loaded, as the command does.
Expected<std::unique_ptr<Technique>> createRenderTechnique(const std::string& name);

class RenderSession {
public:
    // The scene must emit light; scene-file defaults, then `settings` ("name=value", as --set) are
    // checked; a scene file's one-sided surfaces are warned about at `firstFrame`; the context is made
    // with `contextConfig` (or reused, app/ProcessContext.h); the settings are applied again over the
    // device profile's defaults (core/DeviceProfile.h) and the pipeline built. A technique that cannot
    // render the scene fails here.
    static Expected<std::unique_ptr<RenderSession>> create(std::shared_ptr<Scene> scene, std::unique_ptr<Technique> technique,
                                                           glm::ivec2 size, const std::vector<std::string>& settings,
                                                           uint32_t firstFrame = 0, const gl::ContextConfig& contextConfig = {});

    // Frame `frame` at time frame / frameRate, or at `time` seconds (the animation held or moved by
    // hand); the camera is the scene's unless overridden.
    FrameStats renderFrame(uint32_t frame, const Camera* camera = nullptr);
    FrameStats renderFrame(uint32_t frame, float time, const Camera* camera = nullptr);
    // The component of the last frame, checked finite ("{technique} output{what}: ...").
    Expected<Image> readback(Component component, const std::string& what = "") const;
    // Moved objects are uploaded again with the next frame.
    void invalidateObjects();

    // `bounce render --stats`'s record of these frames plus `extra`'s fields.
    nlohmann::json runRecord(const std::vector<FrameStats>& frames, const nlohmann::json& extra);
    // The PNG transform of renderer.exposure and renderer.toneCurve.
    ToneMap toneMap() const;

    Scene& scene() { return *m_scene; }
    Pipeline& pipeline() { return *m_pipeline; }
    const gl::GpuInfo& gpuInfo() const { return m_context->info(); }

private:
    RenderSession() = default;
    std::shared_ptr<Scene> m_scene;
    gl::Context* m_context = nullptr;
    std::unique_ptr<Pipeline> m_pipeline;
};

}  // namespace bounce
