#include "techniques/nichols/StencilledGather.h"

#include "gpu/Bindings.h"

#include <fmt/format.h>


namespace bounce::nichols {

Expected<StencilledGather> StencilledGather::create() {
    StencilledGather g;
    BOUNCE_TRY(g.m_eye, MinMaxPyramid::create());
    BOUNCE_TRY(g.m_buffer, MultiresBuffer::create());
    g.m_clearFbo = gl::Framebuffer::create("nichols.clear");
    return g;
}

void StencilledGather::prepare(FrameContext& ctx, int eyeCoarsest, const PyramidThresholds& thresholds, int scale) {
    {
        auto s = ctx.timers.scope("min-max-mipmap");
        m_eye->buildEye(ctx.gbuffer, eyeCoarsest, thresholds, std::nullopt, scale);
    }
    auto s = ctx.timers.scope("stencil-setup");
    m_tickets.clear();
    m_buffer->begin(*m_eye);
    m_buffer->stencilSetup(*m_eye);
}

void StencilledGather::gather(gl::Program& program, int batches, const std::function<void(int)>& setBatch) {
    m_eye->geometry().bind(BINDING_TEX_TECH0);
    m_eye->normal().bind(BINDING_TEX_TECH1);
    m_tickets = m_buffer->drawStencilled(program, batches, setBatch);
}

void StencilledGather::finish(FrameContext& ctx, const gl::Texture& indirect, UpsampleFilter filter) {
    auto s = ctx.timers.scope("upsample");
    m_buffer->upsample(filter);
    m_buffer->combine(ctx.gbuffer, indirect, 0.0f, m_eye->scale());
}

double StencilledGather::collectCounters(Counters& out) const {
    double total = 0.0;
    for (size_t k = 0; k < m_tickets.size(); ++k) {
        const double f = m_buffer->fragments(m_tickets[k]);
        out[fmt::format("fragments/level-{}", k)] = f;
        total += f;
    }
    if (!m_tickets.empty()) out["gatherFragments"] = total;
    return total;
}

void StencilledGather::clear(const gl::Texture& indirect) {
    m_tickets.clear();
    const float zero[4] = {0, 0, 0, 0};
    m_clearFbo.attach(GL_COLOR_ATTACHMENT0, indirect);
    glClearNamedFramebufferfv(m_clearFbo.id(), GL_COLOR, 0, zero);
}

}  // namespace bounce::nichols
