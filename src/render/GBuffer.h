#pragma once
// The camera's G-buffer: world position, shading normal, albedo, emission and depth, rendered by
// SceneDrawer, plus rectangular area lights drawn as visible emitters. Every technique reads it.
#include "gpu/Program.h"
#include "render/LightSet.h"
#include "render/SceneDrawer.h"

namespace bounce::render {

class GBuffer {
public:
    static Expected<GBuffer> create(glm::ivec2 size);
    void render(SceneDrawer& drawer, const View& view, const LightSet& lights);
    // Binds the G-buffer textures to BINDING_TEX_GBUF_*.
    void bind() const;

    glm::ivec2 size() const { return m_size; }
    const gl::Texture& position() const { return m_position; }
    const gl::Texture& normal() const { return m_normal; }
    const gl::Texture& albedo() const { return m_albedo; }
    const gl::Texture& emission() const { return m_emission; }
    const gl::Texture& depth() const { return m_depth; }
    const gl::Framebuffer& framebuffer() const { return m_fbo; }

private:
    glm::ivec2 m_size{0};
    gl::Program m_program, m_emitterProgram;
    gl::Texture m_position, m_normal, m_albedo, m_emission, m_depth;
    gl::Framebuffer m_fbo;
};

}  // namespace bounce::render
