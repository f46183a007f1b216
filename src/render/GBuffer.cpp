#include "render/GBuffer.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"

namespace bounce::render {

Expected<GBuffer> GBuffer::create(glm::ivec2 size) {
    GBuffer g;
    g.m_size = size;
    BOUNCE_TRY(g.m_program, gl::Program::build({"gbuffer", {{GL_VERTEX_SHADER, "render/scene.vert"},
                                                            {GL_FRAGMENT_SHADER, "render/gbuffer.frag"}}}));
    BOUNCE_TRY(g.m_emitterProgram, gl::Program::build({"gbuffer.emitter", {{GL_VERTEX_SHADER, "render/emitter.vert"},
                                                                           {GL_FRAGMENT_SHADER, "render/emitter.frag"}}}));
    g.m_position = gl::Texture::create2D("gbuffer.position", size.x, size.y, GL_RGBA32F);
    g.m_normal = gl::Texture::create2D("gbuffer.normal", size.x, size.y, GL_RGBA16F);
    g.m_albedo = gl::Texture::create2D("gbuffer.albedo", size.x, size.y, GL_RGBA16F);
    g.m_emission = gl::Texture::create2D("gbuffer.emission", size.x, size.y, GL_RGBA16F);
    g.m_depth = gl::Texture::create2D("gbuffer.depth", size.x, size.y, GL_DEPTH_COMPONENT32F);
    for (gl::Texture* t : {&g.m_position, &g.m_normal, &g.m_albedo, &g.m_emission}) t->setFilter(GL_NEAREST, GL_NEAREST);
    g.m_fbo = gl::Framebuffer::create("gbuffer.fbo");
    g.m_fbo.attach(GL_COLOR_ATTACHMENT0, g.m_position);
    g.m_fbo.attach(GL_COLOR_ATTACHMENT1, g.m_normal);
    g.m_fbo.attach(GL_COLOR_ATTACHMENT2, g.m_albedo);
    g.m_fbo.attach(GL_COLOR_ATTACHMENT3, g.m_emission);
    g.m_fbo.attach(GL_DEPTH_ATTACHMENT, g.m_depth);
    g.m_fbo.setDrawBuffers(4);
    BOUNCE_CHECK(g.m_fbo.complete(), "G-buffer framebuffer");
    return g;
}

void GBuffer::render(SceneDrawer& drawer, const View& view, const LightSet& lights) {
    m_fbo.bind();
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    for (int i = 0; i < 4; ++i) glClearNamedFramebufferfv(m_fbo.id(), GL_COLOR, i, zero);
    glClearNamedFramebufferfv(m_fbo.id(), GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    // Culling of one-sided back faces happens per material in gbuffer.frag (discard).
    glDisable(GL_CULL_FACE);
    m_program.use();
    drawer.draw(view);
    m_emitterProgram.use();
    gl::Context::current()->bindEmptyVertexArray();
    for (size_t i = 0; i < lights.count(); ++i) {
        if (static_cast<int>(lights.light(i).position.w) != LIGHT_AREA) continue;
        lights.bind(i);
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
}

void GBuffer::bind() const {
    m_position.bind(BINDING_TEX_GBUF_POSITION);
    m_normal.bind(BINDING_TEX_GBUF_NORMAL);
    m_albedo.bind(BINDING_TEX_GBUF_ALBEDO);
    m_emission.bind(BINDING_TEX_GBUF_EMISSION);
}

}  // namespace bounce::render
