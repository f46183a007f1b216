#include "techniques/Pipeline.h"

#include "core/Check.h"
#include "core/Resources.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/Readbacks.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <chrono>
#include <optional>

namespace bounce {

Expected<Component> parseComponent(std::string_view name) {
    if (name == "full") return Component::Full;
    if (name == "direct") return Component::Direct;
    if (name == "indirect") return Component::Indirect;
    return makeError("unknown component '{}' (known: full, direct, indirect)", name);
}

std::string_view componentName(Component c) {
    switch (c) {
        case Component::Full: return "full";
        case Component::Direct: return "direct";
        case Component::Indirect: return "indirect";
    }
    return "?";
}

namespace {

// The screen-sized targets every technique shares, bytes per pixel: G-buffer position RGBA32F (16),
// normal, albedo and emission RGBA16F (3 x 8), depth 32F (4), the direct, indirect and full outputs
// RGBA32F (3 x 16); and on the CPU the readback (RGBA32F 16, the Image 12, its encoded file up to 12).
constexpr uint64_t kSharedGpuBytesPerPixel = 16 + 3 * 8 + 4 + 3 * 16;
constexpr uint64_t kReadbackBytesPerPixel = 16 + 12 + 12;
constexpr GLenum kGpuMemoryInfoDedicatedVidmemNvx = 0x9047;  // GL_NVX_gpu_memory_info, in KiB

// A size whose shared targets cannot fit is refused before anything is allocated (a technique's own
// buffers come on top; an allocation that still fails is caught by gl::Texture::create).
Expected<void> checkTargetMemory(const gl::GpuInfo& info, glm::ivec2 size) {
    const uint64_t pixels = static_cast<uint64_t>(size.x) * static_cast<uint64_t>(size.y);
    const std::string what = fmt::format("image size {}x{}", size.x, size.y);
    // Software renderers keep textures in this process's memory.
    const bool software = info.renderer.find("llvmpipe") != std::string::npos ||
                          info.renderer.find("softpipe") != std::string::npos;
    if (software)
        return checkMemoryBudget(pixels * (kSharedGpuBytesPerPixel + kReadbackBytesPerPixel),
                                 what + ": the shared render targets (" + info.renderer.substr(0, info.renderer.find(' ')) +
                                     " renders in system memory) and the readback");
    BOUNCE_TRY_VOID(checkMemoryBudget(pixels * kReadbackBytesPerPixel, what + ": the readback buffers"));
    if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
        GLint kib = 0;
        glGetIntegerv(kGpuMemoryInfoDedicatedVidmemNvx, &kib);
        const uint64_t bytes = pixels * kSharedGpuBytesPerPixel, budget = static_cast<uint64_t>(kib) * 1024;
        if (kib > 0 && bytes > budget)
            return makeError("{}: the shared render targets need about {}, more than the GPU's {}", what, formatBytes(bytes),
                             formatBytes(budget));
    }
    return {};
}

}  // namespace

Pipeline::Pipeline(const Scene& scene, glm::ivec2 size, const render::RenderSettings& settings)
    : m_scene(scene), m_size(size), m_settings(settings), m_sceneGpu(scene), m_drawer(m_sceneGpu) {
    m_timers.setMode(settings.timing == "finish" ? gl::GpuTimers::Mode::Finish : gl::GpuTimers::Mode::Queries);
}

Expected<std::unique_ptr<Pipeline>> Pipeline::create(const Scene& scene, std::unique_ptr<Technique> technique,
                                                     glm::ivec2 size, const render::RenderSettings& settings) {
    BOUNCE_CHECK(technique != nullptr, "pipeline without technique");
    if (size.x <= 0 || size.y <= 0) return makeError("image size {}x{} is not positive", size.x, size.y);
    const gl::Context* context = gl::Context::current();
    BOUNCE_CHECK(context != nullptr, "no current GL context");
    const int maxSize = context->info().maxTextureSize;
    if (size.x > maxSize || size.y > maxSize)
        return makeError("image size {}x{} exceeds the GPU's maximum texture size {}", size.x, size.y, maxSize);
    BOUNCE_TRY_VOID(checkTargetMemory(context->info(), size));
    std::unique_ptr<Pipeline> p(new Pipeline(scene, size, settings));
    BOUNCE_TRY(p->m_lights, render::LightSet::create());
    BOUNCE_TRY(p->m_gbuffer, render::GBuffer::create(size));
    BOUNCE_TRY(p->m_directLighting, render::DirectLighting::create());
    BOUNCE_TRY(p->m_compose, gl::Program::build({"compose", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                             {GL_FRAGMENT_SHADER, "render/compose.frag"}}}));
    p->m_direct = gl::Texture::create2D("output.direct", size.x, size.y, GL_RGBA32F);
    p->m_indirect = gl::Texture::create2D("output.indirect", size.x, size.y, GL_RGBA32F);
    p->m_full = gl::Texture::create2D("output.full", size.x, size.y, GL_RGBA32F);
    p->m_composeFbo = gl::Framebuffer::create("compose.fbo");
    p->m_composeFbo.attach(GL_COLOR_ATTACHMENT0, p->m_full);
    p->m_composeFbo.setDrawBuffers(1);
    BOUNCE_CHECK(p->m_composeFbo.complete(), "compose framebuffer");
    p->m_frameUbo = gl::Buffer::create("frame.uniforms", sizeof(gpu::FrameUniforms));
    p->m_technique = std::move(technique);
    if (p->m_technique->bouncesLightsOnly() && scene.hasEmissiveMaterials())
        return makeError("technique '{}': scene '{}' has emissive materials, whose light this technique does not bounce "
                         "(its indirect light starts at the scene's lights only)",
                         p->m_technique->name(), scene.name);
    SetupContext setup{scene, p->m_sceneGpu, size, p->m_settings};
    auto ok = p->m_technique->setup(setup);
    if (!ok.ok()) return makeError("technique '{}': {}", p->m_technique->name(), ok.error().message);
    return p;
}

void Pipeline::setLateTimings(bool late) {
    m_lateTimings = late;
    m_timers.setLatency(late ? gl::GpuTimers::Latency::OneFrame : gl::GpuTimers::Latency::Immediate);
}

FrameStats Pipeline::renderFrame(uint32_t frame, const Camera* cameraOverride) {
    return renderFrame(frame, m_scene.timeOfFrame(frame), cameraOverride);
}

FrameStats Pipeline::renderFrame(uint32_t frame, float time, const Camera* cameraOverride) {
    const auto start = std::chrono::steady_clock::now();
    FrameStats stats;
    stats.frame = frame;
    stats.time = time;
    std::optional<gl::FramePath> framePath(std::in_place);  // the frame's submission: no waiting reads
    m_timers.beginFrame();
    m_sceneGpu.update(stats.time);
    const Camera camera = cameraOverride ? *cameraOverride : m_sceneGpu.camera();
    const render::View view = render::cameraView(camera, m_size);

    gpu::FrameUniforms fu{};
    fu.clipFromWorld = view.clipFromWorld();
    fu.worldFromClip = glm::inverse(fu.clipFromWorld);
    fu.viewFromWorld = view.viewFromWorld;
    fu.eyePosition = glm::vec4(camera.position, stats.time);
    fu.viewport = glm::vec4(m_size.x, m_size.y, 1.0f / m_size.x, 1.0f / m_size.y);
    fu.ambient = glm::vec4(0.0f, 0.0f, 0.0f, static_cast<float>(frame));
    m_frameUbo.upload(0, sizeof(fu), &fu);
    m_frameUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_FRAME);

    {
        auto s = m_timers.scope("shadow-maps");
        m_lights.update(m_drawer, m_settings, view);
    }
    {
        auto s = m_timers.scope("gbuffer");
        m_gbuffer.render(m_drawer, view, m_lights);
    }
    if (!m_technique->ownsDirect()) {  // a technique that owns its direct light writes m_direct itself
        auto s = m_timers.scope("direct");
        m_frameUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_FRAME);
        m_directLighting.render(m_gbuffer, m_lights, m_direct);
    }
    {
        auto s = m_timers.scope(m_technique->name());
        m_frameUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_FRAME);
        FrameContext ctx{m_scene,  m_sceneGpu, m_drawer,        m_lights, m_gbuffer, view,   m_direct,
                         m_timers, stats.counters, stats.time, frame,    m_size};
        m_technique->renderIndirect(ctx, m_indirect);
    }
    {
        auto s = m_timers.scope("compose");
        m_composeFbo.bind();
        glViewport(0, 0, m_size.x, m_size.y);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        m_direct.bind(BINDING_TEX_INPUT0);
        m_indirect.bind(BINDING_TEX_INPUT1);
        m_compose.use();
        gl::Context::current()->bindEmptyVertexArray();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    framePath.reset();
    m_technique->collectCounters(stats.counters);
    stats.passes = m_timers.endFrame();
    stats.passesLate = m_lateTimings;
    // A measured frame ends when the GPU is done with it (cpuMilliseconds is its wall time); with late
    // timings the CPU goes on to the next frame while the GPU works (issue 29 #8).
    if (!m_lateTimings) glFinish();
    stats.cpuMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats.counters["shadowMapsRendered"] = static_cast<double>(m_lights.mapsRendered());
    stats.counters["triangles"] = static_cast<double>(m_sceneGpu.triangleCount(render::DrawFilter::All));
    stats.resources = gl::liveResources();
    stats.residentBytes = residentBytes();
    gl::throwIfContextReset();  // a frame on a context lost to a GPU reset rendered nothing (issue 29 #22)
    return stats;
}

const gl::Texture& Pipeline::output(Component c) const {
    switch (c) {
        case Component::Full: return m_full;
        case Component::Direct: return m_direct;
        case Component::Indirect: return m_indirect;
    }
    return m_full;
}

std::vector<DebugView> Pipeline::debugViews() const {
    std::vector<DebugView> views{
        {"output.direct", &m_direct, DebugEncoding::Radiance},
        {"output.indirect", &m_indirect, DebugEncoding::Radiance},
        {"gbuffer.position", &m_gbuffer.position(), DebugEncoding::Position},
        {"gbuffer.normal", &m_gbuffer.normal(), DebugEncoding::Normal},
        {"gbuffer.albedo", &m_gbuffer.albedo(), DebugEncoding::Color},
        {"gbuffer.emission", &m_gbuffer.emission(), DebugEncoding::Radiance},
    };
    m_technique->debugViews(views);
    return views;
}

Image Pipeline::readback(Component c) const { return readTexture(output(c)); }

Image readTexture(const gl::Texture& texture) {
    const int w = texture.width(), h = texture.height();
    std::vector<glm::vec4> rgba(static_cast<size_t>(w) * h);
    glGetTextureImage(texture.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(rgba.size() * sizeof(glm::vec4)),
                      rgba.data());
    Image image(w, h);
    // GL rows start at the bottom; Image rows at the top.
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) image.at(x, h - 1 - y) = glm::vec3(rgba[static_cast<size_t>(y) * w + x]);
    return image;
}

}  // namespace bounce
