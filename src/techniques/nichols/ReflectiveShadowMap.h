#pragma once
// The reflective shadow map (RSM) of Nichols (2010) §3.2.1, shared by rsm, isr and hisr: a light-space
// G-buffer of the scene's primary light (light 0) storing per texel the world position, the light
// distance, the normal, the patch area and the reflected flux.
//
// Light treatment (the thesis assumes a spot light; bounce has four light types):
//   spot (cutoff <= kMaxPerspectiveCutoff): one perspective map whose frustum just covers the cone;
//   point, area (from its centre, cosine-weighted and one-sided) and wider spots: six 90-degree cube
//     faces (layers 0..5 of a 2D array), so no emitted direction is lost;
//   directional: one orthographic map fitted to the scene bounds.
// The reflected flux of texel t is Phi_t = I(omega_t) * dOmega_t * rho (directional: E * dA * rho), so
// the sum over the map is the power the lit surfaces reflect (no 1/(4 pi) of Eq. 4.2 / 4.4: the
// texel's exact solid angle replaces the equal-solid-angle approximation of Eq. 4.4).
#include "techniques/Technique.h"

namespace bounce::nichols {

// The layout of the RSM's texel arrays, which the VPL cache (RegularVpls) copies: `size` x `size`
// texels per layer, RGBA32F, read texel by texel (nearest).
gl::TextureDesc texelArrayDesc(int size, int layers);

class ReflectiveShadowMap {
public:
    static Expected<ReflectiveShadowMap> create();
    // Layers of the map of `light` (1: a narrow spot or a directional light; 6: cube faces), and of a
    // scene's map (its light 0; 1 without lights): setup checks size what the frames will allocate.
    static int layersFor(const Light& light);
    static int layersFor(const Scene& scene) { return scene.lights.empty() ? 1 : layersFor(scene.lights.front()); }

    // Renders the map of light 0 at `size` x `size` texels per layer. Returns false (and leaves the
    // map empty) when the scene has no light. equalSolidAngle: Eq. 4.4's approximation (every texel
    // gets the frustum's solid angle / size^2) instead of each texel's exact solid angle.
    bool render(FrameContext& ctx, int size, bool equalSolidAngle = false);

    bool valid() const { return m_valid; }
    int size() const { return m_size; }
    int layers() const { return m_layers; }
    // GL_TEXTURE_2D_ARRAY, RGBA32F: xyz world position, w light distance (0 where nothing was hit).
    const gl::Texture& position() const { return m_position; }
    // xyz unit normal facing the light, w patch area A_t in m^2 (Eq. 4.3 with the exact solid angle).
    const gl::Texture& normal() const { return m_normal; }
    // rgb reflected flux Phi_t in W, a = 1 where covered.
    const gl::Texture& flux() const { return m_flux; }
    // The viewer's debug views: rsm.position, rsm.normal, rsm.flux (flux scaled by the texel count so
    // that a texel shows the power the whole map would reflect at its value).
    void debugViews(std::vector<DebugView>& out) const;
    // Total reflected flux of the last render (W per channel; read back, for tests).
    glm::vec3 totalFlux() const;

private:
    gl::Program m_program;
    gl::Texture m_position, m_normal, m_flux, m_depth;
    gl::Framebuffer m_fbo;
    int m_size = 0, m_layers = 0;
    bool m_valid = false;
};

}  // namespace bounce::nichols
