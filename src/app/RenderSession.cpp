#include "app/RenderSession.h"

#include "app/Options.h"
#include "app/ProcessContext.h"
#include "app/RunRecord.h"
#include "core/ImageIo.h"
#include "techniques/Registry.h"

#include <spdlog/spdlog.h>

namespace bounce {

Expected<std::unique_ptr<Technique>> createRenderTechnique(const std::string& name) {
    auto technique = createTechnique(name);
    if (!technique.ok()) return makeError("--technique: {}", technique.error().message);
    return std::move(*technique);
}

Expected<std::unique_ptr<RenderSession>> RenderSession::create(std::shared_ptr<Scene> scene, std::unique_ptr<Technique> technique,
                                                               glm::ivec2 size, const std::vector<std::string>& settings,
                                                               uint32_t firstFrame, const gl::ContextConfig& contextConfig) {
    // As `bounce reference` (PathTracer::create): a black image is not a render of anything.
    if (!scene->emitsLight())
        return makeError("scene '{}': no light source (no light with non-zero power and no object with an emissive material)",
                         scene->name);
    render::RenderSettings renderSettings;
    BOUNCE_TRY_VOID(applyAllSettings(*scene, *technique, renderSettings, settings));
    warnOneSidedSurfaces(*scene, size, firstFrame);
    std::unique_ptr<RenderSession> session(new RenderSession());
    BOUNCE_TRY(session->m_context, processContext(contextConfig));
    // The device profile's defaults (core/DeviceProfile.h), then the scene's and the caller's values again.
    renderSettings = render::RenderSettings{};
    BOUNCE_TRY_VOID(applyAllSettings(*scene, *technique, renderSettings, settings, session->m_context->info().profile));
    BOUNCE_TRY(session->m_pipeline, Pipeline::create(*scene, std::move(technique), size, renderSettings));
    session->m_scene = std::move(scene);
    return session;
}

FrameStats RenderSession::renderFrame(uint32_t frame, const Camera* camera) { return m_pipeline->renderFrame(frame, camera); }

FrameStats RenderSession::renderFrame(uint32_t frame, float time, const Camera* camera) {
    return m_pipeline->renderFrame(frame, time, camera);
}

Expected<Image> RenderSession::readback(Component component, const std::string& what) const {
    Image image = m_pipeline->readback(component);
    BOUNCE_TRY_VOID(checkFinite(image, fmt::format("{} output{}", m_pipeline->technique().name(), what)));
    return image;
}

void RenderSession::invalidateObjects() { m_pipeline->sceneGpu().invalidateObjects(); }

nlohmann::json RenderSession::runRecord(const std::vector<FrameStats>& frames, const nlohmann::json& extra) {
    return renderRunRecord(*m_scene, *m_pipeline, frames, m_context->info(), extra);
}

ToneMap RenderSession::toneMap() const {
    ToneMap toneMap;
    toneMap.exposureEv = m_pipeline->renderSettings().exposure;
    toneMap.curve = *parseToneCurve(m_pipeline->renderSettings().toneCurve);
    return toneMap;
}

}  // namespace bounce
