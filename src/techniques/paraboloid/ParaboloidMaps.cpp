#include "techniques/paraboloid/ParaboloidMaps.h"

#include "core/Check.h"

namespace bounce::paraboloid {

glm::mat4 vplFromWorld(glm::vec3 tangent, glm::vec3 bitangent, glm::vec3 normal) {
    glm::mat4 m(1.0f);
    for (int c = 0; c < 3; ++c) {  // rows t, b, n (GLM is column-major: [col][row])
        m[c][0] = tangent[c];
        m[c][1] = bitangent[c];
        m[c][2] = normal[c];
    }
    return m;
}

Expected<ParaboloidMaps> ParaboloidMaps::create(const Names& names, GLenum depthFormat, int size, int layers) {
    ParaboloidMaps p;
    p.m_name = names.program;
    p.m_size = size;
    BOUNCE_TRY(p.m_program, gl::Program::build({names.program,
                                                {{GL_VERTEX_SHADER, "techniques/paraboloid/paraboloid.vert"},
                                                 {GL_FRAGMENT_SHADER, "techniques/paraboloid/paraboloid.frag"}}}));
    p.m_maps = gl::Texture::create2DArray(names.maps, size, size, layers, depthFormat, 1, GL_LINEAR);
    p.m_maps.setCompareMode(true);
    p.m_fbo = gl::Framebuffer::create(names.framebuffer);
    return p;
}

void ParaboloidMaps::begin(float far) {
    render::beginDepthTestedPass(1);
    m_program.use();
    m_program.set("u_far", far);
    m_program.set("u_size", glm::vec2(static_cast<float>(m_size)));
}

void ParaboloidMaps::setFrame(const glm::mat4& vplFromWorld) { m_program.set("u_vplFromWorld", vplFromWorld); }

void ParaboloidMaps::render(render::SceneDrawer& drawer, int layer, glm::vec3 position, render::DrawFilter filter) {
    const float one = 1.0f;
    render::View view;
    view.viewport = glm::ivec2(m_size);
    m_program.set("u_vplPosition", position);
    m_fbo.attachLayer(GL_DEPTH_ATTACHMENT, m_maps, layer);
    glNamedFramebufferDrawBuffer(m_fbo.id(), GL_NONE);
    BOUNCE_CHECK(m_fbo.complete(), "{} framebuffer (layer {})", m_name, layer);
    m_fbo.bind();
    glClearNamedFramebufferfv(m_fbo.id(), GL_DEPTH, 0, &one);
    drawer.draw(view, filter);
}

void ParaboloidMaps::end() {
    render::endDepthTestedPass(1);
    glDisable(GL_DEPTH_TEST);
}

}  // namespace bounce::paraboloid
