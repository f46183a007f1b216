#pragma once
// Paraboloid shadow maps of VPLs (Brabec et al. 2002; Laine et al. 2007 §5.1), the one owner of the
// pass iir (one map per new VPL) and area-light's visibility=shadow-maps baseline (one map per VPL of
// each area light) share: the program of shaders/techniques/paraboloid/, a depth GL_TEXTURE_2D_ARRAY
// with one map per layer (linear filter, depth-compare sampling: sampler2DArrayShadow), and the
// framebuffer that renders one layer. A map covers the hemisphere around the VPL's normal; its depth
// is distance / far (paraboloid.frag).
#include "core/Error.h"
#include "gpu/Objects.h"
#include "gpu/Program.h"
#include "render/SceneDrawer.h"

#include <glm/glm.hpp>

#include <string>

namespace bounce::paraboloid {

// The VPL frame's matrix: rows tangent, bitangent, normal (u_vplFromWorld; the normal is +z).
glm::mat4 vplFromWorld(glm::vec3 tangent, glm::vec3 bitangent, glm::vec3 normal);

class ParaboloidMaps {
public:
    // Debug labels of the program, the array texture and the framebuffer.
    struct Names {
        std::string program, maps, framebuffer;
    };
    ParaboloidMaps() = default;
    // `layers` maps of size x size texels in `depthFormat` (GL_DEPTH_COMPONENT16, 32F).
    static Expected<ParaboloidMaps> create(const Names& names, GLenum depthFormat, int size, int layers);
    explicit operator bool() const { return static_cast<bool>(m_maps); }
    const gl::Texture& maps() const { return m_maps; }

    // One pass: begin() sets the depth-tested state with the back hemisphere's clip plane
    // (render::beginDepthTestedPass(1)) and the depth range `far` (metres); then per map the frame
    // (setFrame, shared by the maps of one emitter) and render(); end() disables the clip plane and
    // the depth test.
    void begin(float far);
    void setFrame(const glm::mat4& vplFromWorld);
    // Clears layer `layer` and draws the scene's `filter` objects seen from `position` (world).
    void render(render::SceneDrawer& drawer, int layer, glm::vec3 position, render::DrawFilter filter = render::DrawFilter::All);
    void end();

private:
    std::string m_name;
    int m_size = 0;
    gl::Program m_program;
    gl::Texture m_maps;
    gl::Framebuffer m_fbo;
};

}  // namespace bounce::paraboloid
