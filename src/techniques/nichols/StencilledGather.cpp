#include "techniques/nichols/StencilledGather.h"

#include "gpu/Bindings.h"

#include <fmt/format.h>

#include <numeric>

namespace bounce::nichols {

Expected<StencilledGather> StencilledGather::create() {
    StencilledGather g;
    BOUNCE_TRY(g.m_eye, MinMaxPyramid::create());
    BOUNCE_TRY(g.m_buffer, MultiresBuffer::create());
    g.m_clearFbo = gl::Framebuffer::create("nichols.clear");
    return g;
}

void StencilledGather::prepare(FrameContext& ctx, int eyeCoarsest, const PyramidThresholds& thresholds) {
    {
        auto s = ctx.timers.scope("min-max-mipmap");
        m_eye->buildEye(ctx.gbuffer, eyeCoarsest, thresholds);
    }
    auto s = ctx.timers.scope("stencil-setup");
    m_buffer->begin(*m_eye);
    m_buffer->stencilSetup(*m_eye);
}

std::vector<double> StencilledGather::gather(gl::Program& program, int batches,
                                             const std::function<void(int)>& setBatch) {
    m_eye->geometry().bind(BINDING_TEX_TECH0);
    m_eye->normal().bind(BINDING_TEX_TECH1);
    return m_buffer->drawStencilled(program, batches, setBatch);
}

void StencilledGather::finish(FrameContext& ctx, const gl::Texture& indirect, const std::vector<double>& fragments,
                              UpsampleFilter filter) {
    {
        auto s = ctx.timers.scope("upsample");
        m_buffer->upsample(filter);
        m_buffer->combine(ctx.gbuffer, indirect);
    }
    for (size_t k = 0; k < fragments.size(); ++k) ctx.counters[fmt::format("fragments/level-{}", k)] = fragments[k];
    ctx.counters["gatherFragments"] = std::accumulate(fragments.begin(), fragments.end(), 0.0);
}

void StencilledGather::clear(const gl::Texture& indirect) {
    const float zero[4] = {0, 0, 0, 0};
    m_clearFbo.attach(GL_COLOR_ATTACHMENT0, indirect);
    glClearNamedFramebufferfv(m_clearFbo.id(), GL_COLOR, 0, zero);
}

}  // namespace bounce::nichols
