#include "techniques/direct/DirectTechnique.h"

namespace bounce {

void DirectTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    auto scope = ctx.timers.scope("clear");
    const float zero[4] = {0, 0, 0, 0};
    glClearTexImage(indirect.id(), 0, GL_RGBA, GL_FLOAT, zero);
}

}  // namespace bounce
