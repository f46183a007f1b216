#include "render/DirectLighting.h"

#include "core/Check.h"
#include "gpu/Context.h"

namespace bounce::render {

Expected<DirectLighting> DirectLighting::create() {
    DirectLighting d;
    BOUNCE_TRY(d.m_emission, gl::Program::build({"direct.emission", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                                      {GL_FRAGMENT_SHADER, "render/emission.frag"}}}));
    BOUNCE_TRY(d.m_light, gl::Program::build({"direct.light", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                                {GL_FRAGMENT_SHADER, "render/direct_light.frag"}}}));
    d.m_fbo = gl::Framebuffer::create("direct.fbo");
    return d;
}

void DirectLighting::begin(const GBuffer& gbuffer, const gl::Texture& target) {
    m_fbo.attach(GL_COLOR_ATTACHMENT0, target);
    m_fbo.setDrawBuffers(1);
    BOUNCE_CHECK(m_fbo.complete(), "direct-light framebuffer");
    m_fbo.bind();
    glViewport(0, 0, target.width(), target.height());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    gbuffer.bind();
    gl::Context::current()->bindEmptyVertexArray();
}

void DirectLighting::addLight(const LightSet& lights, size_t i) {
    lights.bind(i);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void DirectLighting::render(const GBuffer& gbuffer, const LightSet& lights, const gl::Texture& target) {
    begin(gbuffer, target);
    glDisable(GL_BLEND);
    m_emission.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    m_light.use();
    for (size_t i = 0; i < lights.count(); ++i) addLight(lights, i);
    glDisable(GL_BLEND);
}

void DirectLighting::addLights(const GBuffer& gbuffer, const LightSet& lights, const gl::Texture& target,
                               const std::vector<size_t>& which) {
    begin(gbuffer, target);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    m_light.use();
    for (size_t i : which) addLight(lights, i);
    glDisable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace bounce::render
