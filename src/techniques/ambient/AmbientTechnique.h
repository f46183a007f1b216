#pragma once
// Baseline `ambient`: the classic constant ambient term. Every surface receives a uniform incident
// radiance L_a from all directions; a Lambertian surface of albedo rho then reflects rho * L_a (the
// cosine-weighted hemisphere integral of L_a * rho/pi is rho * L_a). No visibility, no colour
// bleeding: the floor every GI technique must beat.
#include "gpu/Program.h"
#include "techniques/Technique.h"

namespace bounce {

class AmbientTechnique final : public Technique {
public:
    std::string_view name() const override { return "ambient"; }
    void visitSettings(SettingsVisitor& v) override {
        v.field("radiance", m_radiance, "uniform incident ambient radiance L_a, W/(m^2 sr)", 0.0f, 1e6f);
    }
    Expected<void> setup(const SetupContext& ctx) override;
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;

private:
    float m_radiance = 0.05f;
    gl::Program m_program;
    gl::Framebuffer m_fbo;
};

}  // namespace bounce
