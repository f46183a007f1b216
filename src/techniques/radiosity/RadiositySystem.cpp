#include "techniques/radiosity/RadiositySystem.h"

#include "core/Check.h"
#include "core/Image.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/DispatchGrid.h"
#include "techniques/radiosity/HemicubeMath.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>

namespace bounce::radiosity {

static_assert(sizeof(gpu::RadQuadGpu) == 8 * 16);
static_assert(sizeof(gpu::RadElementGpu) == 4 * 16);
static_assert(sizeof(gpu::RadShooterGpu) == 8 * 16);
static_assert(sizeof(gpu::RadHemicubeGpu) == 5 * 16);
static_assert(sizeof(gpu::RadBodyGpu) == 9 * 16);
static_assert(sizeof(gpu::RadPassUniforms) == 4 * 16);

namespace {

constexpr uint32_t kBatch = RAD_MAX_BATCH;
constexpr uint32_t kRoles = 4;  // front old / front new / back old / back new (Alg. 4.4 lines 6-9)
// Hemicube origin offset along the normal and near plane, as fractions of the scene diagonal: far
// enough off the surface that its own quad does not z-fight, near enough not to see past a corner.
constexpr float kOffsetFraction = 1e-4f;
// Far plane: beyond the whole scene from any hemicube inside it.
constexpr float kFarFactor = 4.0f;
// The back hemicubes' "nothing seen" distance, metres (fits RGBA16F).
constexpr float kMissDistance = 1.0e4f;

void barrier() { glMemoryBarrier(GL_ALL_BARRIER_BITS); }

gl::Texture msArray(const char* name, GLenum format, int size, int layers, int samples) {
    gl::TextureDesc d;
    d.target = GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
    d.format = format;
    d.width = d.height = size;
    d.depth = layers;
    d.samples = samples;
    return gl::Texture::create(name, d);
}

Expected<gl::Program> computeProgram(const char* label, int pass, int source = 0) {
    return gl::Program::build({label,
                               {{GL_COMPUTE_SHADER, "techniques/radiosity/passes.comp"}},
                               {{"RAD_PASS", std::to_string(pass)}, {"RAD_SOURCE", std::to_string(source)}}});
}

gpu::RadBodyGpu bodyOf(const glm::mat4& world, bool moving, bool animated) {
    gpu::RadBodyGpu b;
    b.worldFromObject = world;
    b.normalFromObject = glm::mat4(glm::inverseTranspose(glm::mat3(world)));
    b.info = glm::uvec4(moving ? 1u : 0u, animated ? 1u : 0u, 0u, 0u);
    return b;
}

}  // namespace

Expected<void> RadiositySystem::checkMsaa(int msaa, const gl::GpuInfo& info) {
    // The hemicubes are multisample colour and depth arrays (issue 29 #11: depth has its own limit,
    // 8 on many AMD/Intel drivers where colour has more).
    if (msaa > info.maxColorTextureSamples)
        return makeError("setting msaa={} exceeds this GL's {} samples of a multisample colour texture (GL_MAX_COLOR_TEXTURE_SAMPLES)",
                         msaa, info.maxColorTextureSamples);
    if (msaa > info.maxDepthTextureSamples)
        return makeError("setting msaa={} exceeds this GL's {} samples of a multisample depth texture (GL_MAX_DEPTH_TEXTURE_SAMPLES)",
                         msaa, info.maxDepthTextureSamples);
    return {};
}

Expected<std::unique_ptr<RadiositySystem>> RadiositySystem::create(const Scene& scene, const SystemOptions& opt) {
    if (opt.hemicubeSize < 4 || opt.hemicubeSize % 2 != 0) return makeError("hemicubeSize {} must be even and at least 4", opt.hemicubeSize);
    if (opt.backSize < 2 || opt.backSize % 2 != 0) return makeError("backHemicubeSize {} must be even and at least 2", opt.backSize);
    BOUNCE_TRY_VOID(checkMsaa(opt.msaa, gl::Context::current()->info()));
    BOUNCE_TRY(PatchModel model, PatchModel::build(scene, opt.patches));

    auto sys = std::unique_ptr<RadiositySystem>(new RadiositySystem());
    RadiositySystem& s = *sys;
    s.m_model = std::move(model);
    s.m_options = opt;
    const PatchModel& pm = s.m_model;

    glm::vec3 lo, hi;
    scene.bounds(0.0f, lo, hi);
    for (const Light& l : scene.lights) {
        lo = glm::min(lo, l.position - glm::abs(l.edgeU) - glm::abs(l.edgeV));
        hi = glm::max(hi, l.position + glm::abs(l.edgeU) + glm::abs(l.edgeV));
    }
    const float diagonal = std::max(glm::length(hi - lo), 1e-3f);
    s.m_offset = kOffsetFraction * diagonal;
    s.m_far = kFarFactor * diagonal;

    // Records.
    std::vector<gpu::RadQuadGpu> quads;
    for (const Quad& q : pm.quads()) {
        gpu::RadQuadGpu g{};
        g.p0 = glm::vec4(q.p[0], 0.0f);
        g.p1 = glm::vec4(q.p[1], 0.0f);
        g.p2 = glm::vec4(q.p[2], 0.0f);
        g.p3 = glm::vec4(q.p[3], 0.0f);
        g.normal = glm::vec4(q.normal, q.area);
        g.emission = glm::vec4(q.emission, 0.0f);
        g.atlas = glm::uvec4(q.atlasX, q.atlasY, q.nu, q.nv);
        g.info = glm::uvec4(q.body, q.firstElement, q.flags, q.surface);
        quads.push_back(g);
        s.m_maxShooters = std::max(s.m_maxShooters, static_cast<uint32_t>(q.nu * q.nv));
    }
    std::vector<gpu::RadElementGpu> elements;
    uint32_t animatedElements = 0;
    for (const Element& e : pm.elements()) {
        const Quad& q = pm.quads()[e.quad];
        gpu::RadElementGpu g{};
        g.position = glm::vec4(e.position, e.area);
        g.albedo = glm::vec4(e.albedo, 0.0f);
        g.emission = glm::vec4(e.emission, 0.0f);
        g.info = glm::uvec4(e.quad, static_cast<uint32_t>(q.atlasX + e.i) | static_cast<uint32_t>(q.atlasY + e.j) << 16, q.body,
                            static_cast<uint32_t>(e.i) | static_cast<uint32_t>(e.j) << 16);
        elements.push_back(g);
        s.m_emittedPower += e.area * luminance(e.emission);
        if (pm.bodyAnimated(scene, q.body)) ++animatedElements;
    }
    s.m_maxShooters = std::max(s.m_maxShooters, animatedElements);
    std::vector<glm::uvec4> triangles;
    triangles.push_back(glm::uvec4(pm.objectCount(), 0u, 0u, 0u));
    for (uint32_t base : pm.objectTriangleBase()) triangles.push_back(glm::uvec4(base, 0u, 0u, 0u));
    for (const TriangleRef& t : pm.triangles())
        triangles.push_back(glm::uvec4(t.quad, glm::packUnorm2x16(t.st[0]), glm::packUnorm2x16(t.st[1]), glm::packUnorm2x16(t.st[2])));

    s.m_quads = gl::Buffer::create("radiosity.quads", quads.size() * sizeof(gpu::RadQuadGpu), quads.data());
    s.m_elements = gl::Buffer::create("radiosity.elements", elements.size() * sizeof(gpu::RadElementGpu), elements.data());
    s.m_triangles = gl::Buffer::create("radiosity.triangles", triangles.size() * sizeof(glm::uvec4), triangles.data());
    s.m_bodyBuffer = gl::Buffer::create("radiosity.bodies", pm.bodyCount() * sizeof(gpu::RadBodyGpu));
    s.m_bodyOldBuffer = gl::Buffer::create("radiosity.bodiesOld", pm.bodyCount() * sizeof(gpu::RadBodyGpu));
    s.m_objectsOld = gl::Buffer::create("radiosity.objectsOld", std::max<size_t>(1, pm.objectCount()) * sizeof(gpu::ObjectGpu));
    s.m_shooters = gl::Buffer::create("radiosity.shooters", std::max<uint32_t>(s.m_maxShooters, kBatch) * sizeof(gpu::RadShooterGpu));
    s.m_records = gl::Buffer::create("radiosity.hemicubes", kRoles * kBatch * sizeof(gpu::RadHemicubeGpu));
    s.m_stats = gl::Buffer::create("radiosity.stats", std::max<size_t>(3 * quads.size(), kRoles * kBatch) * sizeof(glm::vec4));
    s.m_pass = gl::Buffer::create("radiosity.pass", sizeof(gpu::RadPassUniforms));
    s.m_bodies.resize(pm.bodyCount());
    s.m_bodiesOld.resize(pm.bodyCount());
    s.m_moving.assign(pm.bodyCount(), 0);

    const glm::ivec2 atlas = pm.atlasSize();
    s.m_total = gl::Texture::create2D("radiosity.B", atlas.x, atlas.y, GL_RGBA32F);
    s.m_unshot = gl::Texture::create2D("radiosity.Bu", atlas.x, atlas.y, GL_RGBA32F);
    // The direct light of point, spot and directional lights at the elements (passes.comp LIGHTS):
    // atlas-sized only when the scene has such a light (1x1 otherwise: the passes' loads read 0).
    for (size_t i = 0; i < scene.lights.size(); ++i)
        if (scene.lights[i].type != LightType::Area) s.m_punctual.push_back(i);
    const glm::ivec2 lightSize = s.m_punctual.empty() ? glm::ivec2(1) : atlas;
    s.m_lightNew = gl::Texture::create2D("radiosity.Dnew", lightSize.x, lightSize.y, GL_RGBA32F);
    s.m_light = gl::Texture::create2D("radiosity.D", lightSize.x, lightSize.y, GL_RGBA32F);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(s.m_lightNew.id(), 0, GL_RGBA, GL_FLOAT, zero);
    glClearTexImage(s.m_light.id(), 0, GL_RGBA, GL_FLOAT, zero);
    // The shooting thresholds' scale (emittedPower, RadiosityTechnique's maxEmission) counts each
    // punctual light's unshadowed direct light at the rest pose as emission.
    for (const Element& e : pm.elements()) {
        const Quad& q = pm.quads()[e.quad];
        const glm::mat4 world = pm.bodyTransform(scene, q.body, 0.0f);
        const glm::vec3 x(world * glm::vec4(e.position, 1.0f));
        const glm::vec3 n = glm::normalize(glm::mat3(glm::transpose(glm::inverse(world))) * q.normal);
        glm::vec3 d{0.0f};
        for (size_t i : s.m_punctual) d += punctualDirectRadiance(scene.lights[i].at(0.0f), x, n, e.albedo);
        s.m_emittedPower += e.area * luminance(d);
        s.m_maxLightRadiance = std::max(s.m_maxLightRadiance, luminance(d));
    }

    // Hemicubes.
    const int R = opt.hemicubeSize, Rb = opt.backSize, layers = static_cast<int>(5 * kBatch);
    const std::vector<float> deltaTable = deltaFormFactors(R);
    s.m_deltaFF = gl::Texture::create2DArray("radiosity.deltaFF", R, R, 5, GL_R32F, 1, GL_NEAREST);
    glTextureSubImage3D(s.m_deltaFF.id(), 0, 0, 0, 0, R, R, 5, GL_RED, GL_FLOAT, deltaTable.data());
    s.m_idA = gl::Texture::create2DArray("radiosity.hemicube.idOld", R, R, layers, GL_R32UI, 1, GL_NEAREST);
    s.m_idB = gl::Texture::create2DArray("radiosity.hemicube.idNew", R, R, layers, GL_R32UI, 1, GL_NEAREST);
    s.m_shot = gl::Texture::create2DArray("radiosity.hemicube.shot", R, R, layers, GL_RGBA16F, 1, GL_NEAREST);
    s.m_depth = gl::Texture::create2DArray("radiosity.hemicube.depth", R, R, layers, GL_DEPTH_COMPONENT32F, 1, GL_NEAREST);
    s.m_radMs = msArray("radiosity.hemicube.radiosity", GL_RGBA16F, R, layers, opt.msaa);
    s.m_depthMs = msArray("radiosity.hemicube.depthMs", GL_DEPTH_COMPONENT32F, R, layers, opt.msaa);
    s.m_backMs = msArray("radiosity.hemicube.back", GL_RGBA16F, Rb, layers, opt.msaa);
    s.m_backDepthMs = msArray("radiosity.hemicube.backDepth", GL_DEPTH_COMPONENT32F, Rb, layers, opt.msaa);
    s.m_backOld = gl::Texture::create2DArray("radiosity.hemicube.backOld", Rb, Rb, layers, GL_RGBA16F, 1, GL_LINEAR);
    s.m_backNew = gl::Texture::create2DArray("radiosity.hemicube.backNew", Rb, Rb, layers, GL_RGBA16F, 1, GL_LINEAR);
    if (opt.mipIntegration) {
        const int levels = static_cast<int>(std::log2(R)) + 1;
        if ((1 << (levels - 1)) != R) return makeError("integration=mipmap needs a power-of-two hemicubeSize, not {}", R);
        s.m_weighted = gl::Texture::create2DArray("radiosity.hemicube.weighted", R, R, layers, GL_RGBA32F, levels, GL_LINEAR);
    }
    const auto fbo = [](const char* name, std::initializer_list<const gl::Texture*> colours, const gl::Texture& depth) {
        gl::Framebuffer f = gl::Framebuffer::create(name);
        int k = 0;
        for (const gl::Texture* c : colours) f.attach(GL_COLOR_ATTACHMENT0 + k++, *c);
        f.attach(GL_DEPTH_ATTACHMENT, depth);
        f.setDrawBuffers(k);
        BOUNCE_CHECK(f.complete(), "framebuffer {}", name);
        return f;
    };
    s.m_fboIdA = fbo("radiosity.fbo.idOld", {&s.m_idA}, s.m_depth);
    s.m_fboIdB = fbo("radiosity.fbo.idNew", {&s.m_idB}, s.m_depth);
    s.m_fboCombined = fbo("radiosity.fbo.combined", {&s.m_idB, &s.m_shot}, s.m_depth);
    s.m_fboRad = fbo("radiosity.fbo.radiosity", {&s.m_radMs}, s.m_depthMs);
    s.m_fboBack = fbo("radiosity.fbo.back", {&s.m_backMs}, s.m_backDepthMs);
    s.m_emptyVao = gl::VertexArray::create("radiosity.lightQuads");

    // Programs.
    static const char* kModeNames[] = {"id", "radiosity", "combined", "back"};
    for (int m = 0; m < 4; ++m) {
        const std::vector<std::pair<std::string, std::string>> defines = {{"RAD_HEMICUBE", "1"}, {"RAD_HC_MODE", std::to_string(m)}};
        BOUNCE_TRY(s.m_hc[m], gl::Program::build({std::string("radiosity.hemicube.") + kModeNames[m],
                                                  {{GL_VERTEX_SHADER, "render/scene.vert"},
                                                   {GL_GEOMETRY_SHADER, "techniques/radiosity/patch.geom"},
                                                   {GL_FRAGMENT_SHADER, "techniques/radiosity/hemicube.frag"}},
                                                  defines}));
        BOUNCE_TRY(s.m_hcLight[m], gl::Program::build({std::string("radiosity.hemicube.light.") + kModeNames[m],
                                                       {{GL_VERTEX_SHADER, "techniques/radiosity/light.vert"},
                                                        {GL_GEOMETRY_SHADER, "techniques/radiosity/patch.geom"},
                                                        {GL_FRAGMENT_SHADER, "techniques/radiosity/hemicube.frag"}},
                                                       defines}));
    }
    const char* displayVs[2] = {"render/scene.vert", "techniques/radiosity/light.vert"};
    for (int k = 0; k < 2; ++k) {
        BOUNCE_TRY(s.m_display[k], gl::Program::build({k == 0 ? "radiosity.display" : "radiosity.display.light",
                                                       {{GL_VERTEX_SHADER, displayVs[k]},
                                                        {GL_GEOMETRY_SHADER, "techniques/radiosity/patch.geom"},
                                                        {GL_FRAGMENT_SHADER, "techniques/radiosity/display.frag"}},
                                                       {{"RAD_HEMICUBE", "0"}}}));
    }
    BOUNCE_TRY(s.m_place, computeProgram("radiosity.place", 0));
    BOUNCE_TRY(s.m_quadStats, computeProgram("radiosity.quadStats", 1));
    BOUNCE_TRY(s.m_shooterPass, computeProgram("radiosity.shooters", 2));
    BOUNCE_TRY(s.m_clear, computeProgram("radiosity.clear", 3));
    BOUNCE_TRY(s.m_integrateMs, computeProgram("radiosity.integrate.msaa", 4, 0));
    BOUNCE_TRY(s.m_integrateSingle, computeProgram("radiosity.integrate", 4, 1));
    BOUNCE_TRY(s.m_integrateMip, computeProgram("radiosity.integrate.mip", 4, 2));
    BOUNCE_TRY(s.m_resolve, computeProgram("radiosity.resolve", 5));
    BOUNCE_TRY(s.m_ffMultiply, computeProgram("radiosity.ffMultiply", 6));
    BOUNCE_TRY(s.m_lightPass, computeProgram("radiosity.lights", 7));
    if (!s.m_punctual.empty()) {
        BOUNCE_TRY(s.m_directLights, render::DirectLighting::create());
    }
    BOUNCE_TRY(s.m_reconstruct, gl::Program::build({"radiosity.reconstruct", {{GL_COMPUTE_SHADER, "techniques/radiosity/reconstruct.comp"}}}));
    return sys;
}

void RadiositySystem::bindCommon() const {
    m_quads.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_RAD_QUADS);
    m_elements.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_RAD_ELEMENTS);
    m_triangles.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_RAD_TRIANGLES);
    m_bodyBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_RAD_BODIES);
    m_bodyOldBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_RAD_BODIES_OLD);
    m_shooters.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_RAD_SHOOTERS);
    m_records.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_RAD_HEMICUBES);
    m_stats.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_RAD_STATS);
    m_total.bindImage(BINDING_IMG0, GL_READ_WRITE);
    m_unshot.bindImage(BINDING_IMG1, GL_READ_WRITE);
    m_light.bindImage(BINDING_IMG3, GL_READ_WRITE);
}

void RadiositySystem::beginFrame(const Scene& scene, float time) {
    const uint32_t n = m_model.bodyCount();
    m_anyMoving = false;
    for (uint32_t b = 0; b < n; ++b) {
        const glm::mat4 world = m_model.bodyTransform(scene, b, time);
        bool moving = false;
        if (m_movingOverride) moving = (*m_movingOverride)[b] != 0;
        else if (m_haveOld)
            for (int c = 0; c < 4 && !moving; ++c)
                moving = glm::any(glm::notEqual(world[c], m_bodiesOld[b].worldFromObject[c]));
        m_moving[b] = moving ? 1 : 0;
        m_anyMoving = m_anyMoving || moving;
        m_bodies[b] = bodyOf(world, moving, m_model.bodyAnimated(scene, b));
    }
    m_bodyBuffer.upload(0, n * sizeof(gpu::RadBodyGpu), m_bodies.data());
    if (!m_haveOld) {
        m_bodiesOld = m_bodies;
        m_bodyOldBuffer.upload(0, n * sizeof(gpu::RadBodyGpu), m_bodiesOld.data());
        std::vector<gpu::ObjectGpu> objects(m_model.objectCount());
        for (uint32_t k = 0; k < m_model.objectCount(); ++k) {
            objects[k].worldFromObject = m_bodies[k].worldFromObject;
            objects[k].normalFromObject = m_bodies[k].normalFromObject;
            objects[k].info = glm::uvec4(scene.objects[k].material, scene.objects[k].isDynamic() ? 1u : 0u, k, 0u);
        }
        m_objectData = objects;
        if (!objects.empty()) m_objectsOld.upload(0, objects.size() * sizeof(gpu::ObjectGpu), objects.data());
    }
}

void RadiositySystem::commit() {
    m_bodiesOld = m_bodies;
    m_bodyOldBuffer.upload(0, m_bodies.size() * sizeof(gpu::RadBodyGpu), m_bodiesOld.data());
    for (uint32_t k = 0; k < m_model.objectCount(); ++k) {
        m_objectData[k].worldFromObject = m_bodies[k].worldFromObject;
        m_objectData[k].normalFromObject = m_bodies[k].normalFromObject;
    }
    if (!m_objectData.empty()) m_objectsOld.upload(0, m_objectData.size() * sizeof(gpu::ObjectGpu), m_objectData.data());
    m_haveOld = true;
}

void RadiositySystem::setMovingOverride(const std::vector<char>* moving) { m_movingOverride = moving; }

size_t RadiositySystem::movingElementCount() const {
    size_t n = 0;
    for (const Quad& q : m_model.quads())
        if (m_moving[q.body]) n += static_cast<size_t>(q.nu * q.nv);
    return n;
}

void RadiositySystem::reset(int receivers, bool toEmission) {
    bindCommon();
    m_lightNew.bindImage(BINDING_IMG2, GL_READ_ONLY);
    m_clear.use();
    m_clear.set("u_mode", toEmission ? 1 : 2);
    m_clear.set("u_receivers", receivers);
    m_clear.set("u_count", static_cast<unsigned>(m_model.elements().size()));
    gl::dispatchLinear(m_model.elements().size(), 64);
    barrier();
}

void RadiositySystem::computeLights(const render::LightSet& lights) {
    if (m_punctual.empty()) return;
    bindCommon();
    m_lightNew.bindImage(BINDING_IMG2, GL_READ_WRITE);
    m_lightPass.use();
    m_lightPass.set("u_mode", 0);
    m_lightPass.set("u_count", static_cast<unsigned>(m_model.elements().size()));
    for (size_t k = 0; k < m_punctual.size(); ++k) {
        lights.bind(m_punctual[k]);  // its uniforms and shadow maps at BINDING_UBO_LIGHT / _TEX_SHADOW(_CUBE)
        m_lightPass.set("u_accumulate", k == 0 ? 0 : 1);
        gl::dispatchLinear(m_model.elements().size(), 64);
        barrier();
    }
}

void RadiositySystem::applyLights(int receivers) {
    if (m_punctual.empty()) return;
    bindCommon();
    m_lightNew.bindImage(BINDING_IMG2, GL_READ_WRITE);
    m_lightPass.use();
    m_lightPass.set("u_mode", 1);
    m_lightPass.set("u_receivers", receivers);
    m_lightPass.set("u_count", static_cast<unsigned>(m_model.elements().size()));
    gl::dispatchLinear(m_model.elements().size(), 64);
    barrier();
}

void RadiositySystem::placeRecords(int mode, uint32_t first, uint32_t count, uint32_t recordBase, bool old) {
    bindCommon();
    m_place.use();
    m_place.set("u_mode", mode);
    m_place.set("u_first", first);
    m_place.set("u_count", count);
    m_place.set("u_recordBase", recordBase);
    m_place.set("u_old", old ? 1 : 0);
    m_place.set("u_offset", m_offset);
    m_place.set("u_near", 0.5f * m_offset);
    m_place.set("u_rotate", m_options.randomRotation ? 1 : 0);
    gl::dispatchLinear(count, 64);
    barrier();
}

void RadiositySystem::placeShooterHemicubes(uint32_t role, uint32_t first, uint32_t count, ShooterAt at, bool old) {
    placeRecords(at == ShooterAt::Front ? 1 : 2, first, count, role * kBatch, old);
}

void RadiositySystem::renderHemicubes(render::SceneDrawer& drawer, HemicubeKind kind, uint32_t role, uint32_t count, bool old,
                                      render::DrawFilter filter, gl::GpuTimers& timers) {
    BOUNCE_CHECK(count <= kBatch && role < kRoles, "hemicube batch {} role {}", count, role);
    auto scope = timers.scope("radiosity.hemicubes");
    const int mode = static_cast<int>(kind);
    const gl::Framebuffer* fbo = nullptr;
    int size = m_options.hemicubeSize;
    switch (kind) {
        case HemicubeKind::Id: fbo = role == 0 ? &m_fboIdA : &m_fboIdB; break;
        case HemicubeKind::Radiosity: fbo = &m_fboRad; break;
        case HemicubeKind::Combined: fbo = &m_fboCombined; break;
        case HemicubeKind::Back:
            fbo = &m_fboBack;
            size = m_options.backSize;
            break;
    }
    fbo->bind();
    const GLuint zero[4] = {0, 0, 0, 0};
    const float black[4] = {0.0f, 0.0f, 0.0f, 0.0f}, miss[4] = {0.0f, 0.0f, 0.0f, kMissDistance};
    const float one = 1.0f;
    if (kind == HemicubeKind::Id || kind == HemicubeKind::Combined) glClearNamedFramebufferuiv(fbo->id(), GL_COLOR, 0, zero);
    if (kind == HemicubeKind::Combined) glClearNamedFramebufferfv(fbo->id(), GL_COLOR, 1, black);
    if (kind == HemicubeKind::Radiosity) glClearNamedFramebufferfv(fbo->id(), GL_COLOR, 0, black);
    if (kind == HemicubeKind::Back) glClearNamedFramebufferfv(fbo->id(), GL_COLOR, 0, miss);
    glClearNamedFramebufferfv(fbo->id(), GL_DEPTH, 0, &one);
    render::beginDepthTestedPass(1);
    bindCommon();
    m_total.bind(BINDING_TEX_TECH0);
    m_unshot.bind(BINDING_TEX_TECH1);
    render::View view;
    view.viewport = {size, size};
    const glm::vec2 atlas(m_model.atlasSize());
    const uint32_t lights = static_cast<uint32_t>(m_model.lightQuadCount());
    for (uint32_t k = 0; k < count; ++k) {
        const unsigned record = role * kBatch + k;
        for (gl::Program* p : {&m_hc[mode], &m_hcLight[mode]}) {
            p->use();
            p->set("u_hemicube", record);
            p->set("u_layerBase", static_cast<int>(5 * k));
            p->set("u_far", m_far);
            p->set("u_atlasSize", atlas);
            if (p == &m_hc[mode]) {
                if (old) drawer.draw(view, filter, m_objectsOld);
                else drawer.draw(view, filter);
            } else if (lights > 0) {
                p->set("u_firstLightQuad", m_model.firstLightQuad());
                p->set("u_old", old ? 1 : 0);
                p->set("u_filter", static_cast<int>(filter));
                m_emptyVao.bind();
                glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(6 * lights));
            }
        }
    }
    render::endDepthTestedPass(1);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    m_hemicubes += count;
    if (kind == HemicubeKind::Back) {
        const gl::Texture& target = role == 2 ? m_backOld : m_backNew;
        m_resolve.use();
        m_backMs.bind(BINDING_TEX_TECH2);
        target.bindImage(BINDING_IMG2, GL_WRITE_ONLY, 0, true);
        m_resolve.set("u_samples", m_options.msaa);
        m_resolve.set("u_resolution", size);
        m_resolve.set("u_count", 5 * count);
        gl::dispatchLinear(size * size * 5 * count, 64);
        barrier();
    }
}

uint32_t RadiositySystem::gatherElementCount() const {
    // Light quads come last and reflect nothing: gather at the scene's elements only.
    const Quad& firstLight = m_model.quads()[std::min<size_t>(m_model.firstLightQuad(), m_model.quads().size() - 1)];
    return m_model.lightQuadCount() > 0 ? firstLight.firstElement : static_cast<uint32_t>(m_model.elements().size());
}

void RadiositySystem::gatherSweep(render::SceneDrawer& drawer, gl::GpuTimers& timers, const std::function<void(uint32_t)>& afterBatch) {
    const uint32_t elements = gatherElementCount();
    const int R = m_options.hemicubeSize;
    for (uint32_t first = 0; first < elements; first += kBatch) {
        const uint32_t count = std::min(kBatch, elements - first);
        placeRecords(0, first, count, 0, false);
        renderHemicubes(drawer, HemicubeKind::Radiosity, 0, count, false, render::DrawFilter::All, timers);
        auto scope = timers.scope("radiosity.integrate");
        bindCommon();
        m_deltaFF.bind(BINDING_TEX_TECH3);
        if (m_options.mipIntegration) {
            m_ffMultiply.use();
            m_radMs.bind(BINDING_TEX_TECH2);
            m_weighted.bindImage(BINDING_IMG2, GL_WRITE_ONLY, 0, true);
            m_ffMultiply.set("u_samples", m_options.msaa);
            m_ffMultiply.set("u_resolution", R);
            m_ffMultiply.set("u_count", 5 * count);
            gl::dispatchLinear(R * R * 5 * count, 256);
            barrier();
            m_weighted.generateMipmaps();
            m_integrateMip.use();
            m_weighted.bind(BINDING_TEX_TECH2);
            m_integrateMip.set("u_topLevel", static_cast<int>(std::log2(R)));
            m_integrateMip.set("u_resolution", R);
            m_integrateMip.set("u_mode", 0);
            m_integrateMip.set("u_recordBase", 0u);
        } else {
            m_integrateMs.use();
            m_radMs.bind(BINDING_TEX_TECH2);
            m_integrateMs.set("u_samples", m_options.msaa);
            m_integrateMs.set("u_resolution", R);
            m_integrateMs.set("u_mode", 0);
            m_integrateMs.set("u_recordBase", 0u);
        }
        glDispatchCompute(count, 1, 1);
        barrier();
        if (afterBatch) afterBatch(first + count);
    }
}

void RadiositySystem::gatherShot(uint32_t count, gl::GpuTimers& timers) {
    auto scope = timers.scope("radiosity.integrate");
    bindCommon();
    m_integrateSingle.use();
    m_shot.bind(BINDING_TEX_TECH2);
    m_deltaFF.bind(BINDING_TEX_TECH3);
    m_integrateSingle.set("u_resolution", m_options.hemicubeSize);
    m_integrateSingle.set("u_mode", 1);
    m_integrateSingle.set("u_recordBase", 1u * kBatch);
    glDispatchCompute(count, 1, 1);
    barrier();
}

std::vector<QuadStats> RadiositySystem::quadStats() {
    const size_t n = m_model.quads().size();
    bindCommon();
    m_quadStats.use();
    m_quadStats.set("u_first", 0u);
    m_quadStats.set("u_count", static_cast<unsigned>(n));
    gl::dispatchGroupsLinear(n);  // one group per quad: a mesh scene's quads can pass 65,535
    barrier();
    std::vector<glm::vec4> raw(3 * n);
    m_stats.download(0, raw.size() * sizeof(glm::vec4), raw.data());  // the thesis's readback stall
    std::vector<QuadStats> out(n);
    for (size_t q = 0; q < n; ++q) {
        out[q].unshot = glm::vec3(raw[3 * q]);
        out[q].area = raw[3 * q].w;
        out[q].shot = glm::vec3(raw[3 * q + 1]);
        out[q].total = glm::vec3(raw[3 * q + 2]);
    }
    return out;
}

void RadiositySystem::loadShooters(const std::vector<ShooterRect>& rects) {
    BOUNCE_CHECK(rects.size() <= std::max<uint32_t>(m_maxShooters, kBatch), "{} shooters exceed the buffer", rects.size());
    std::vector<gpu::RadShooterGpu> g(rects.size());
    for (size_t k = 0; k < rects.size(); ++k) {
        const Quad& q = m_model.quads()[rects[k].quad];
        const float du = 1.0f / static_cast<float>(q.nu - 1), dv = 1.0f / static_cast<float>(q.nv - 1);
        gpu::RadShooterGpu& s = g[k];
        s = {};
        s.rect = glm::vec4(std::max(0.0f, (rects[k].lo.x - 0.5f) * du), std::max(0.0f, (rects[k].lo.y - 0.5f) * dv),
                           std::min(1.0f, (rects[k].hi.x + 0.5f) * du), std::min(1.0f, (rects[k].hi.y + 0.5f) * dv));
        s.range = glm::uvec4(rects[k].lo.x, rects[k].lo.y, rects[k].hi.x, rects[k].hi.y);
        s.info = glm::uvec4(rects[k].quad, q.body, q.flags, 0u);
    }
    if (!g.empty()) m_shooters.upload(0, g.size() * sizeof(gpu::RadShooterGpu), g.data());
}

void RadiositySystem::computeShooters(uint32_t first, uint32_t count, bool keepShot) {
    if (count == 0) return;
    bindCommon();
    m_shooterPass.use();
    m_shooterPass.set("u_first", first);
    m_shooterPass.set("u_mode", keepShot ? 1 : 0);
    glDispatchCompute(count, 1, 1);
    barrier();
}

void RadiositySystem::clearShooterUnshot(uint32_t first, uint32_t count) {
    if (count == 0) return;
    bindCommon();
    m_clear.use();
    m_clear.set("u_mode", 0);
    m_clear.set("u_first", first);
    glDispatchCompute(count, 1, 1);
    barrier();
}

void RadiositySystem::reconstruct(int mode, int receivers, uint32_t first, uint32_t count, bool insert, gl::GpuTimers& timers) {
    auto scope = timers.scope(mode == RAD_SHOOT_CROSS ? "radiosity.crossProjection" : "radiosity.reconstruct");
    gpu::RadPassUniforms u{};
    u.modes = glm::uvec4(static_cast<uint32_t>(mode), static_cast<uint32_t>(receivers), count,
                         static_cast<uint32_t>(m_options.visibilitySamples));
    u.counts = glm::uvec4(static_cast<uint32_t>(m_model.elements().size()), static_cast<uint32_t>(m_options.hemicubeSize),
                          static_cast<uint32_t>(m_options.backSize), static_cast<uint32_t>(m_options.crossGrid));
    u.slots = glm::uvec4(first, 0u, 0u,
                         (m_options.reprojection ? RAD_CROSS_REPROJECT : 0u) | (m_options.crossFormFactorWeights ? RAD_CROSS_FF_WEIGHTS : 0u));
    u.params = glm::vec4(m_options.ffSubdivideRatio, static_cast<float>(m_options.ffSubdivisions), static_cast<float>(m_options.msaa),
                         insert ? 1.0f : 0.0f);
    m_pass.upload(0, sizeof(u), &u);
    m_pass.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_PASS);
    bindCommon();
    m_idA.bind(BINDING_TEX_TECH0);
    m_idB.bind(BINDING_TEX_TECH1);
    m_backOld.bind(BINDING_TEX_TECH2);
    m_backNew.bind(BINDING_TEX_TECH3);
    m_reconstruct.use();
    gl::dispatchLinear(m_model.elements().size(), 64);
    barrier();
}

void RadiositySystem::display(render::SceneDrawer& drawer, const render::View& camera, const render::GBuffer& gbuffer,
                              const render::LightSet& lights, const gl::Texture& direct, const gl::Texture& indirect,
                              bool nearest) {
    const glm::ivec2 size(direct.width(), direct.height());
    if (size != m_displaySize) {
        m_displayDepth = gl::Texture::create2D("radiosity.display.depth", size.x, size.y, GL_DEPTH_COMPONENT32F);
        m_fboDisplay = gl::Framebuffer::create("radiosity.fbo.display");
        m_displaySize = size;
    }
    m_fboDisplay.attach(GL_COLOR_ATTACHMENT0, direct);
    m_fboDisplay.attach(GL_COLOR_ATTACHMENT1, indirect);
    m_fboDisplay.attach(GL_DEPTH_ATTACHMENT, m_displayDepth);
    m_fboDisplay.setDrawBuffers(2);
    BOUNCE_CHECK(m_fboDisplay.complete(), "radiosity display framebuffer");
    m_fboDisplay.bind();
    const float clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    const float one = 1.0f;
    glClearNamedFramebufferfv(m_fboDisplay.id(), GL_COLOR, 0, clear);
    glClearNamedFramebufferfv(m_fboDisplay.id(), GL_COLOR, 1, clear);
    glClearNamedFramebufferfv(m_fboDisplay.id(), GL_DEPTH, 0, &one);
    render::beginDepthTestedPass();
    bindCommon();
    m_total.bind(BINDING_TEX_TECH0);
    m_light.bind(BINDING_TEX_TECH1);
    const glm::vec2 atlas(m_model.atlasSize());
    for (int k = 0; k < 2; ++k) {
        m_display[k].use();
        m_display[k].set("u_atlasSize", atlas);
        m_display[k].set("u_nearest", nearest ? 1 : 0);
        if (k == 0) {
            drawer.draw(camera);
        } else if (m_model.lightQuadCount() > 0) {
            m_display[k].set("u_firstLightQuad", m_model.firstLightQuad());
            m_display[k].set("u_old", 0);
            m_display[k].set("u_filter", 0);
            m_emptyVao.bind();
            glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(6 * m_model.lightQuadCount()));
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    // The punctual lights' direct light at the pixels (the shared direct pass's, shadow-mapped): the
    // elements hold it at their resolution for shooting (D) and the display's indirect is B - E - D.
    if (!m_punctual.empty()) {
        glViewport(0, 0, size.x, size.y);
        m_directLights.addLights(gbuffer, lights, direct, m_punctual);
    }
}

std::vector<glm::vec3> RadiositySystem::readAtlas(const gl::Texture& t) const {
    const glm::ivec2 a = m_model.atlasSize();
    std::vector<glm::vec4> texels(static_cast<size_t>(a.x) * a.y);
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)), texels.data());
    std::vector<glm::vec3> out;
    out.reserve(m_model.elements().size());
    for (const Element& e : m_model.elements()) {
        const Quad& q = m_model.quads()[e.quad];
        out.emplace_back(texels[static_cast<size_t>(q.atlasY + e.j) * a.x + q.atlasX + e.i]);
    }
    return out;
}

std::vector<glm::vec3> RadiositySystem::readTotal() const { return readAtlas(m_total); }

std::vector<gpu::RadHemicubeGpu> RadiositySystem::readHemicubeRecords(uint32_t role, uint32_t count) const {
    BOUNCE_CHECK(role < kRoles && count <= kBatch, "hemicube records role {} count {}", role, count);
    std::vector<gpu::RadHemicubeGpu> out(count);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    m_records.download(role * kBatch * sizeof(gpu::RadHemicubeGpu), count * sizeof(gpu::RadHemicubeGpu), out.data());
    return out;
}
std::vector<glm::vec3> RadiositySystem::readUnshot() const { return readAtlas(m_unshot); }

}  // namespace bounce::radiosity
