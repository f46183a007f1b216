#include "techniques/nichols/MultiresBuffer.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"

#include <fmt/format.h>

namespace bounce::nichols {

namespace {
constexpr int kLocalSize = 8;  // upsample.comp local size
}

Expected<MultiresBuffer> MultiresBuffer::create() {
    MultiresBuffer b;
    BOUNCE_TRY(b.m_stencil, gl::Program::build({"nichols.stencilSetup",
                                                {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                 {GL_FRAGMENT_SHADER, "techniques/nichols/stencil_setup.frag"}}}));
    BOUNCE_TRY(b.m_upsample, gl::Program::build({"nichols.upsample",
                                                 {{GL_COMPUTE_SHADER, "techniques/nichols/upsample.comp"}}}));
    BOUNCE_TRY(b.m_combine, gl::Program::build({"nichols.combine",
                                                {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                 {GL_FRAGMENT_SHADER, "techniques/nichols/combine.frag"}}}));
    b.m_atlasFbo = gl::Framebuffer::create("nichols.atlas.fbo");
    b.m_combineFbo = gl::Framebuffer::create("nichols.combine.fbo");
    return b;
}

void MultiresBuffer::begin(const MinMaxPyramid& pyramid) {
    std::vector<glm::ivec2> sizes;
    for (int k = 0; k < pyramid.levels(); ++k) sizes.push_back(pyramid.levelSize(k));
    begin(sizes);
}

void MultiresBuffer::begin(const std::vector<glm::ivec2>& levelSizes) {
    BOUNCE_CHECK(!levelSizes.empty(), "multiresolution buffer has at least one level");
    std::vector<glm::ivec2> sizes, origins;
    const glm::ivec2 base = levelSizes[0];
    const int levelCount = static_cast<int>(levelSizes.size());
    int y = 0;
    for (int k = 0; k < levelCount; ++k) {
        sizes.push_back(levelSizes[static_cast<size_t>(k)]);
        origins.push_back(k == 0 ? glm::ivec2(0) : glm::ivec2(base.x, y));
        if (k > 0) y += levelSizes[static_cast<size_t>(k)].y;
    }
    const glm::ivec2 atlasSize(base.x + (levelCount > 1 ? levelSizes[1].x : 0), base.y);
    BOUNCE_CHECK(y <= base.y, "atlas column of coarse levels fits the base height");
    if (atlasSize != m_atlasSize || sizes != m_sizes) {
        m_atlasSize = atlasSize;
        m_atlas = gl::Texture::create2D("nichols.atlas", atlasSize.x, atlasSize.y, GL_RGBA32F);
        m_atlas.setFilter(GL_NEAREST, GL_NEAREST);
        m_depthStencil = gl::Texture::create2D("nichols.atlas.stencil", atlasSize.x, atlasSize.y, GL_DEPTH24_STENCIL8);
        gl::TextureDesc d;
        d.target = GL_TEXTURE_2D_ARRAY;
        d.width = base.x;
        d.height = base.y;
        d.levels = levelCount;
        d.format = GL_RGBA32F;
        d.minFilter = GL_NEAREST_MIPMAP_NEAREST;
        d.magFilter = GL_NEAREST;
        m_result = gl::Texture::create("nichols.upsampled", d);
        m_atlasFbo.attach(GL_COLOR_ATTACHMENT0, m_atlas);
        m_atlasFbo.attach(GL_DEPTH_STENCIL_ATTACHMENT, m_depthStencil);
        m_atlasFbo.setDrawBuffers(1);
        BOUNCE_CHECK(m_atlasFbo.complete(), "nichols atlas framebuffer");
    }
    m_sizes = sizes;
    m_origins = origins;
    m_queriesUsed = 0;
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(m_atlasFbo.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfi(m_atlasFbo.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
}

void MultiresBuffer::forEachLevel(gl::Program& program, const std::function<void(int)>& perLevel) {
    m_atlasFbo.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    gl::Context::current()->bindEmptyVertexArray();
    for (int k = 0; k < levels(); ++k) {
        const glm::ivec2 o = levelOrigin(k), s = levelSize(k);
        glViewport(o.x, o.y, s.x, s.y);
        program.set("u_level", k);
        program.set("u_levelOrigin", o);
        program.use();
        perLevel(k);
    }
}

void MultiresBuffer::stencilSetup(const MinMaxPyramid& pyramid) {
    pyramid.geometry().bind(BINDING_TEX_TECH0);
    pyramid.refine().bind(BINDING_TEX_TECH1);
    m_stencil.set("u_coarsest", levels() - 1);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glStencilMask(0xFF);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    forEachLevel(m_stencil, [](int) { glDrawArrays(GL_TRIANGLES, 0, 3); });
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_STENCIL_TEST);
}

std::vector<int> MultiresBuffer::drawStencilled(gl::Program& program, int batches,
                                                const std::function<void(int)>& setBatch) {
    std::vector<int> tickets(static_cast<size_t>(levels()), 0);
    for (int k = 0; k < levels(); ++k) tickets[static_cast<size_t>(k)] = drawLevel(k, program, 1, batches, setBatch);
    return tickets;
}

void MultiresBuffer::stencilLevel(int level, gl::Program& program, int ref) {
    m_atlasFbo.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    gl::Context::current()->bindEmptyVertexArray();
    const glm::ivec2 o = levelOrigin(level), s = levelSize(level);
    glViewport(o.x, o.y, s.x, s.y);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, ref, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glStencilMask(0xFF);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    program.set("u_level", level);
    program.set("u_levelOrigin", o);
    program.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_STENCIL_TEST);
}

int MultiresBuffer::drawLevel(int level, gl::Program& program, int ref, int batches,
                              const std::function<void(int)>& setBatch) {
    const int ticket = m_queriesUsed++;
    if (ticket == static_cast<int>(m_queries.size()))
        m_queries.push_back(gl::Query::create(fmt::format("nichols.fragments.{}", ticket), GL_SAMPLES_PASSED));
    const GLuint query = m_queries[static_cast<size_t>(ticket)].id();
    m_atlasFbo.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    gl::Context::current()->bindEmptyVertexArray();
    const glm::ivec2 o = levelOrigin(level), s = levelSize(level);
    glViewport(o.x, o.y, s.x, s.y);
    program.set("u_level", level);
    program.set("u_levelOrigin", o);
    program.use();
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, ref, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    // The atlas starts at zero (begin()), so adding every batch, the first included, is the sum.
    if (batches > 1) {
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ZERO);
    }
    for (int b = 0; b < batches; ++b) {
        if (setBatch) {
            setBatch(b);
            program.use();
        }
        // Every batch shades the same stencilled fragments: count them once.
        if (b == 0) glBeginQuery(GL_SAMPLES_PASSED, query);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (b == 0) glEndQuery(GL_SAMPLES_PASSED);
        // llvmpipe queues draws until a flush: one unit of work per batch, as a watchdog needs.
        if (batches > 1) glFlush();
    }
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    return ticket;
}

void MultiresBuffer::splatLevel(int level, gl::Program& program, int ref, int instances) {
    m_atlasFbo.bind();
    glDisable(GL_DEPTH_TEST);
    gl::Context::current()->bindEmptyVertexArray();
    const glm::ivec2 o = levelOrigin(level), s = levelSize(level);
    glViewport(o.x, o.y, s.x, s.y);
    program.set("u_level", level);
    program.set("u_levelOrigin", o);
    program.use();
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, ref, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ZERO);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 3, instances);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
}

double MultiresBuffer::fragments(int ticket) const {
    BOUNCE_CHECK(ticket >= 0 && ticket < m_queriesUsed, "fragment-count ticket {} of {} this frame", ticket, m_queriesUsed);
    GLuint64 samples = 0;
    glGetQueryObjectui64v(m_queries[static_cast<size_t>(ticket)].id(), GL_QUERY_RESULT, &samples);
    return static_cast<double>(samples);
}

void MultiresBuffer::bindAtlas() {
    m_atlasFbo.bind();
    glViewport(0, 0, m_atlasSize.x, m_atlasSize.y);
}

UpsampleFilter upsampleFilter(std::string_view name) {
    for (size_t i = 0; i < std::size(kUpsampleFilters); ++i)
        if (kUpsampleFilters[i] == name) return static_cast<UpsampleFilter>(i);
    BOUNCE_CHECK(false, "unknown upsampling filter '{}' (settings validate the choice)", name);
    return UpsampleFilter::EmptyAware;
}

void MultiresBuffer::upsample(UpsampleFilter filter) {
    for (int k = levels() - 1; k >= 0; --k) upsampleLevel(k, false, filter);
}

void MultiresBuffer::upsampleLevel(int k, bool replaceInherited, UpsampleFilter filter) {
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    m_atlas.bind(BINDING_TEX_TECH0);
    m_result.bind(BINDING_TEX_TECH1);
    const glm::ivec2 s = levelSize(k);
    m_result.bindImage(BINDING_IMG0, GL_WRITE_ONLY, k, true);
    m_upsample.set("u_level", k);
    m_upsample.set("u_levelOrigin", levelOrigin(k));
    m_upsample.set("u_size", s);
    m_upsample.set("u_parentSize", k + 1 < levels() ? levelSize(k + 1) : s);
    m_upsample.set("u_hasParent", k + 1 < levels() ? 1 : 0);
    m_upsample.set("u_replaceInherited", replaceInherited ? 1 : 0);
    m_upsample.set("u_filter", static_cast<int>(filter));
    m_upsample.use();
    glDispatchCompute(static_cast<GLuint>((s.x + kLocalSize - 1) / kLocalSize),
                      static_cast<GLuint>((s.y + kLocalSize - 1) / kLocalSize), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void MultiresBuffer::combine(const render::GBuffer& gbuffer, const gl::Texture& indirect, float detailAlpha, int scale) {
    m_combineFbo.attach(GL_COLOR_ATTACHMENT0, indirect);
    m_combineFbo.setDrawBuffers(1);
    BOUNCE_CHECK(m_combineFbo.complete(), "nichols combine framebuffer");
    m_combineFbo.bind();
    glViewport(0, 0, indirect.width(), indirect.height());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    gbuffer.bind();
    m_result.bind(BINDING_TEX_TECH0);
    m_combine.set("u_detailAlpha", detailAlpha);
    m_combine.set("u_scale", scale);
    m_combine.use();
    gl::Context::current()->bindEmptyVertexArray();
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace bounce::nichols
