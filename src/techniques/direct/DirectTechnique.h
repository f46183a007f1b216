#pragma once
// Baseline `direct`: no indirect light at all. The shared passes (render/DirectLighting) already
// computed the direct component, so the indirect target is cleared to zero.
#include "techniques/Technique.h"

namespace bounce {

class DirectTechnique final : public Technique {
public:
    std::string_view name() const override { return "direct"; }
    void visitSettings(SettingsVisitor&) override {}
    Expected<void> setup(const SetupContext&) override { return {}; }
    void renderIndirect(FrameContext& ctx, const gl::Texture& indirect) override;
};

}  // namespace bounce
