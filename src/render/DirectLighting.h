#pragma once
// Direct lighting of the G-buffer: emitted radiance first, then one additive full-screen pass per
// light with its shadow map (Lambert + GGX, common/brdf.glsl). The result is linear radiance.
#include "gpu/Program.h"
#include "render/GBuffer.h"
#include "render/LightSet.h"

#include <vector>

namespace bounce::render {

class DirectLighting {
public:
    static Expected<DirectLighting> create();
    // Writes into `target` (RGBA32F, G-buffer size). FrameUniforms must be bound.
    void render(const GBuffer& gbuffer, const LightSet& lights, const gl::Texture& target);
    // Adds the direct light of lights `which` (indices into `lights`) to `target`, no emission: for a
    // technique that computes the rest of the image itself (radiosity with point lights).
    void addLights(const GBuffer& gbuffer, const LightSet& lights, const gl::Texture& target,
                   const std::vector<size_t>& which);

private:
    void begin(const GBuffer& gbuffer, const gl::Texture& target);  // target bound, full-screen state
    void addLight(const LightSet& lights, size_t i);                  // one additive light pass
    gl::Program m_emission, m_light;
    gl::Framebuffer m_fbo;
};

}  // namespace bounce::render
