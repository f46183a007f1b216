#include "techniques/ambient/AmbientTechnique.h"

#include "core/Check.h"
#include "gpu/Context.h"

namespace bounce {

Expected<void> AmbientTechnique::setup(const SetupContext&) {
    BOUNCE_TRY(m_program, gl::Program::build({"ambient", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                          {GL_FRAGMENT_SHADER, "techniques/ambient/ambient.frag"}}}));
    m_fbo = gl::Framebuffer::create("ambient.fbo");
    return {};
}

void AmbientTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    auto scope = ctx.timers.scope("term");
    m_fbo.attach(GL_COLOR_ATTACHMENT0, indirect);
    m_fbo.setDrawBuffers(1);
    BOUNCE_CHECK(m_fbo.complete(), "ambient framebuffer");
    m_fbo.bind();
    glViewport(0, 0, ctx.size.x, ctx.size.y);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    ctx.gbuffer.bind();
    m_program.set("u_ambientRadiance", m_radiance);
    m_program.use();
    gl::Context::current()->bindEmptyVertexArray();
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace bounce
