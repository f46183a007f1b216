#include "techniques/nichols/StencilledGather.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/DispatchGrid.h"
#include "gpu/ListDispatch.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>


namespace bounce::nichols {

namespace {
constexpr int kMaxCellLevels = 16;      // cell_list.comp's u_levelCells[16]; entries keep the level in 4 bits
constexpr int kMaxCellSide = 1 << 14;   // entries keep x and y in 14 bits each
constexpr size_t kCellHeaderBytes = (1 + kMaxCellLevels) * sizeof(uint32_t);
}  // namespace

GatherPass gatherPass(std::string_view name) {
    return name == "compute" ? GatherPass::Compute : GatherPass::Stencil;
}

int StencilledGather::s_maxGroupsXForTests = 0;

int StencilledGather::maxGroupsX() {
    const int device = static_cast<int>(gl::maxGroupsX());  // the device's, or gl::setMaxGroupsXForTests
    return s_maxGroupsXForTests > 0 ? std::min(s_maxGroupsXForTests, device) : device;
}

Expected<StencilledGather> StencilledGather::create() {
    StencilledGather g;
    BOUNCE_TRY(g.m_cellList, gl::Program::build({"nichols.cellList", {{GL_COMPUTE_SHADER, "techniques/nichols/cell_list.comp"}}}));
    BOUNCE_TRY(g.m_cellArgs, gl::ListDispatch::create());
    g.m_dispatch = gl::ListDispatch::createArgs("nichols.cellDispatch");
    BOUNCE_TRY(g.m_eye, MinMaxPyramid::create());
    BOUNCE_TRY(g.m_buffer, MultiresBuffer::create());
    g.m_clearFbo = gl::Framebuffer::create("nichols.clear");
    return g;
}

void StencilledGather::prepare(FrameContext& ctx, int eyeCoarsest, const PyramidThresholds& thresholds, int scale,
                               GatherPass pass) {
    {
        auto s = ctx.timers.scope("min-max-mipmap");
        m_eye->buildEye(ctx.gbuffer, eyeCoarsest, thresholds, std::nullopt, scale);
    }
    auto s = ctx.timers.scope("stencil-setup");
    m_tickets.clear();
    m_pass = pass;
    m_levels = m_eye->levels();
    m_buffer->begin(*m_eye);
    if (pass == GatherPass::Stencil) {
        m_buffer->stencilSetup(*m_eye);
        return;
    }
    BOUNCE_CHECK(m_levels <= kMaxCellLevels && m_eye->levelSize(0).x <= kMaxCellSide && m_eye->levelSize(0).y <= kMaxCellSide,
                 "cell list holds {} levels of {}x{}", m_levels, m_eye->levelSize(0).x, m_eye->levelSize(0).y);
    const glm::ivec2 base = m_eye->levelSize(0);
    // A covered pixel gathers at exactly one level, so the list never holds more cells than pixels.
    const size_t bytes = kCellHeaderBytes + static_cast<size_t>(base.x) * base.y * sizeof(uint32_t);
    if (!m_cells || m_cells.size() != bytes) m_cells = gl::Buffer::create("nichols.cells", bytes);
    m_cells.clearZero();
    m_eye->geometry().bind(BINDING_TEX_TECH0);
    m_eye->refine().bind(BINDING_TEX_TECH1);
    m_cells.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
    m_cellList.set("u_coarsest", m_levels - 1);
    for (int k = 0; k < m_levels; ++k) {
        const glm::ivec2 size = m_eye->levelSize(k);
        m_cellList.set("u_level", k);
        m_cellList.set("u_size", size);
        m_cellList.use();
        glDispatchCompute(static_cast<GLuint>((size.x + 7) / 8), static_cast<GLuint>((size.y + 7) / 8), 1);
    }
    m_cellArgs.writeArgs(m_cells, m_dispatch, gl::ListDispatch::kUnbounded, static_cast<uint32_t>(maxGroupsX()));
}

void StencilledGather::gather(gl::Program& program, int batches, const std::function<void(int)>& setBatch) {
    m_eye->geometry().bind(BINDING_TEX_TECH0);
    m_eye->normal().bind(BINDING_TEX_TECH1);
    if (m_pass == GatherPass::Stencil) {
        m_tickets = m_buffer->drawStencilled(program, batches, setBatch);
        return;
    }
    std::vector<glm::ivec2> origins(kMaxCellLevels, glm::ivec2(0));
    for (int k = 0; k < m_levels; ++k) origins[static_cast<size_t>(k)] = m_buffer->levelOrigin(k);
    program.set("u_levelOrigins", origins);
    m_cells.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
    m_buffer->atlas().bindImage(BINDING_IMG0, GL_READ_WRITE);
    for (int b = 0; b < batches; ++b) {
        if (setBatch) setBatch(b);
        program.set("u_accumulate", b > 0 ? 1 : 0);
        program.use();
        gl::ListDispatch::dispatch(m_dispatch);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        // llvmpipe queues work until a flush: one unit of work per batch, as for the stencilled draws.
        if (batches > 1) glFlush();
    }
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
}

void StencilledGather::finish(FrameContext& ctx, const gl::Texture& indirect, UpsampleFilter filter) {
    auto s = ctx.timers.scope("upsample");
    m_buffer->upsample(filter);
    m_buffer->combine(ctx.gbuffer, indirect, 0.0f, m_eye->scale());
}

double StencilledGather::collectCounters(Counters& out) const {
    double total = 0.0;
    if (m_pass == GatherPass::Compute) {
        if (m_levels == 0 || !m_cells) return 0.0;
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        uint32_t header[1 + kMaxCellLevels] = {};
        m_cells.download(0, sizeof(header), header);
        for (int k = 0; k < m_levels; ++k) out[fmt::format("fragments/level-{}", k)] = header[1 + k];
        out["gatherFragments"] = header[0];
        return header[0];
    }
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
    m_levels = 0;
    const float zero[4] = {0, 0, 0, 0};
    m_clearFbo.attach(GL_COLOR_ATTACHMENT0, indirect);
    glClearNamedFramebufferfv(m_clearFbo.id(), GL_COLOR, 0, zero);
}

}  // namespace bounce::nichols
