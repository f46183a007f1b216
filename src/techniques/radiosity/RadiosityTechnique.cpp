// Hemicube radiosity after M. van de Hoef, "Real-Time Dynamic Radiosity for High Quality Global
// Illumination", MSc thesis, Utrecht University, 2013 (seed 003). The shared machinery of the four
// methods; each method's algorithm is in its own folder (radiosity_gather, radiosity_pr,
// radiosity_incremental, radiosity_cross).
//
// Model (sec. 4.1; PatchModel.h): planar quads (charts of connected near-coplanar triangles, on their
// bounding rectangle), each with an nu x nv region of one RGBA32F atlas for B and one for the unshot
// Bu; the outer texel ring lies on the rectangle's edges; an element owns its cell clipped to the
// rectangle and the chart's triangles, its sample at the covered part's centroid. Area lights are
// emitter quads. Everything is stored as radiance (B / pi, radiosity_shared.h).
//
// Passes and their OpenGL 4.5 form (the thesis used Direct3D 11):
//   hemicube rendering   five projections -> one layered draw per hemicube: a geometry shader with
//                        invocations = 5 picks the face (gl_Layer), side faces clip v > 1 with
//                        gl_ClipDistance; ID (R32UI), radiosity (RGBA16F, 4x MSAA), combined
//                        ID + shot (MRT, no MSAA), back shot + distance (RGBA16F, 4x MSAA, 16^2);
//                        the scene through SceneDrawer (old transforms: an ObjectGpu array bound in
//                        place of the scene's), area lights by a vertex-buffer-less draw
//   MSAA resolve         D3D's ResolveSubresource -> a compute pass averaging the samples (colour
//                        and distance; GL's blit cannot average a depth buffer); for the gather
//                        hemicubes the resolve is folded into the integration
//   integration          compute parallel reduction over the five faces with the precomputed delta
//                        form factors (an R32F array), or the DX10 fallback: multiply, glGenerate-
//                        TextureMipmap, read the 1x1 level x R^2 (integration=mipmap, gather only)
//   FINDSHOOTINGQUAD     the mip chain + 1x1 inverted-depth render target -> a compute reduction per
//                        quad (area-weighted unshot, shot, total power) read back with
//                        glGetNamedBufferSubData (the same CPU-GPU stall, once per shooting quad);
//                        the arg-max of the mean unshot radiance runs on the CPU over |quads| values
//   T (shooter texture)  a storage buffer of shooter records filled by a compute pass
//   reconstruction       a compute pass, one thread per element, imageLoad/imageStore on B and Bu
//                        (the thesis's pixel shader over the element render targets), up to
//                        RAD_MAX_BATCH shooters per pass (thesis benchmarks: 10)
//   display              the scene drawn from the camera with B bilinear (or nearest) per quad
//
// Deviations and choices (docs/techniques/radiosity.md lists them with their reasons):
//   - the gather method keeps its elements in RGBA32F like the others (thesis: RGBA16F);
//   - quads are charts decoupled from the mesh's faces, every border sample at its clipped cell's
//     centroid (inset), not only the corners (PatchModel.h says why);
//   - element pitch (auto: from the scene's area), shooter subdivision rule, convergence threshold, form-factor
//     subdivision ratio are not given by the thesis: chosen and named as settings;
//   - emitters are area lights or emissive materials (the thesis's emitting patches); point, spot
//     and directional lights (bounce's extension) shoot their direct light, evaluated at the elements
//     with shadow-map visibility (D), as the elements' first unshot radiosity; a change of D (a
//     moving light or occluder) is shot as a change of emission;
//   - the display splits the solution into direct = E (emitters) plus the punctual lights' direct
//     light per pixel (the shared direct pass's) and indirect = B - E - D.
#include "techniques/radiosity/RadiosityTechnique.h"

#include "core/Image.h"

#include <spdlog/spdlog.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace bounce {

using namespace radiosity;

void RadiosityTechnique::debugViews(std::vector<DebugView>& out) const {
    if (!m_system) return;
    const HemicubeUse use = hemicubeUse();
    if (use.radiosity) out.push_back({"radiosity.hemicube.radiosity", &m_system->radiosityHemicubes(), DebugEncoding::Radiance});
    if (use.id) out.push_back({"radiosity.hemicube.id", &m_system->idHemicubes(false), DebugEncoding::Ids});
    if (use.idOld) out.push_back({"radiosity.hemicube.idOld", &m_system->idHemicubes(true), DebugEncoding::Ids});
    if (use.shotAndBack) {
        out.push_back({"radiosity.hemicube.shot", &m_system->shotHemicubes(), DebugEncoding::Radiance});
        out.push_back({"radiosity.hemicube.backOld", &m_system->backHemicubes(true), DebugEncoding::Radiance});
        out.push_back({"radiosity.hemicube.back", &m_system->backHemicubes(false), DebugEncoding::Radiance});
    }
}

void RadiosityTechnique::visitSettings(SettingsVisitor& v) {
    v.field("elementSize", m_elementSize, "metres between element (texel) centres on static surfaces (thesis: not given); 0 = auto: sqrt(scene surface area / 1000), logged and in the run record's `derived`", 0.0f, 100.0f);
    v.field("dynamicElementSize", m_dynamicElementSize, "metres between element centres on animated objects; 0 = auto, as elementSize", 0.0f, 100.0f);
    v.field("hemicubeSize", m_options.hemicubeSize, "hemicube top-face pixels per side; side faces are half as high (thesis: 64)", 4, 512);
    v.field("randomRotation", m_options.randomRotation, "rotate each hemicube about its normal by a hash of its position (thesis sec. 4.2)");
    v.field("view", m_view, "display filter of the radiosity textures: bilinear (thesis) or nearest (Fig. 4.1.1 debug view)", kViews);
    visitMethodSettings(v);
}

Expected<void> RadiosityTechnique::setup(const SetupContext& ctx) {
    if (m_options.visibilitySamples != 1 && m_options.visibilitySamples != 4)
        return makeError("setting visibilitySamples={}: 1 or 4", m_options.visibilitySamples);
    if (m_options.hemicubeSize % 2 != 0) return makeError("setting hemicubeSize={}: must be even", m_options.hemicubeSize);
    if (m_batch < 1 || m_batch > RAD_MAX_BATCH) return makeError("setting batch={}: 1 to {}", m_batch, RAD_MAX_BATCH);
    m_options.patches.elementSize = m_elementSize;
    m_options.patches.dynamicElementSize = m_dynamicElementSize;
    adjustOptions(m_options);
    BOUNCE_TRY(m_system, RadiositySystem::create(ctx.scene, m_options));
    const PatchModel& pm = m_system->patches();
    spdlog::info("{}: elementSize {:.4g} m{}, dynamicElementSize {:.4g} m{}: {} elements ({} on the surfaces, the rest "
                 "ghosts) in {} charts",
                 name(), pm.elementSize(), m_elementSize > 0.0f ? "" : " (auto)", pm.dynamicElementSize(),
                 m_dynamicElementSize > 0.0f ? "" : " (auto)", pm.elements().size(), pm.activeElementCount(), pm.quads().size());
    m_maxEmission = 0.0f;
    for (const Element& e : m_system->patches().elements()) m_maxEmission = std::max(m_maxEmission, luminance(e.emission));
    // Point, spot and directional lights: their brightest unshadowed element radiance is the emission scale.
    m_maxEmission = std::max(m_maxEmission, m_system->maxLightRadiance());
    return {};
}

void RadiosityTechnique::derivedSettings(std::map<std::string, double>& out) const {
    if (!m_system) return;
    out["elementSizeMetres"] = m_system->patches().elementSize();
    out["dynamicElementSizeMetres"] = m_system->patches().dynamicElementSize();
}

void RadiosityTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    m_frameShooters = m_frameIterations = m_frameMovingPatches = m_frameRedistributionHemicubes = 0;
    m_budgetHit = false;
    m_system->resetCounters();
    m_frameStart = std::chrono::steady_clock::now();
    {
        auto s = ctx.timers.scope("radiosity.solve");
        solve(ctx);
    }
    m_frameHemicubes = m_system->hemicubesRendered();
    {
        auto s = ctx.timers.scope("radiosity.display");
        m_system->display(ctx.drawer, ctx.camera, ctx.gbuffer, ctx.lights, ctx.direct, indirect, m_view == "nearest");
    }
    const PatchModel& pm = m_system->patches();
    ctx.counters["elements"] = static_cast<double>(pm.elements().size());
    ctx.counters["activeElements"] = static_cast<double>(pm.activeElementCount());
    ctx.counters["quads"] = static_cast<double>(pm.quads().size());
    ctx.counters["hemicubes"] = m_frameHemicubes;
    ctx.counters["shooters"] = m_frameShooters;
    ctx.counters["iterations"] = m_frameIterations;
    ctx.counters["converged"] = m_converged ? 1.0 : 0.0;
    ctx.counters["budgetHit"] = m_budgetHit ? 1.0 : 0.0;
    ctx.counters["movingElements"] = static_cast<double>(m_system->movingElementCount());
    ctx.counters["movingPatches"] = m_frameMovingPatches;
    ctx.counters["redistributionHemicubes"] = m_frameRedistributionHemicubes;
}

std::vector<ShooterRect> RadiosityTechnique::subdivide(uint32_t quad, float flux) const {
    const Quad& q = m_system->patches().quads()[quad];
    const float emitted = glm::pi<float>() * m_system->emittedPower();
    const float perShooter = std::max(m_shooterFlux * emitted, 1e-30f);
    const int cells = q.nu * q.nv;
    const int n = std::clamp(static_cast<int>(std::ceil(flux / perShooter)), 1, cells);
    const int gu = std::clamp(static_cast<int>(std::lround(std::sqrt(double(n) * q.nu / q.nv))), 1, q.nu);
    const int gv = std::clamp((n + gu - 1) / gu, 1, q.nv);
    std::vector<ShooterRect> rects;
    for (int b = 0; b < gv; ++b)
        for (int a = 0; a < gu; ++a) {
            ShooterRect r;
            r.quad = quad;
            r.lo = {a * q.nu / gu, b * q.nv / gv};
            r.hi = {(a + 1) * q.nu / gu - 1, (b + 1) * q.nv / gv - 1};
            rects.push_back(r);
        }
    return rects;
}

bool RadiosityTechnique::budgetAllows(bool guaranteed) const {
    if (guaranteed || m_frameBudgetMs <= 0.0f) return true;
    const double elapsed = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_frameStart).count();
    return elapsed + m_batchMs <= static_cast<double>(m_frameBudgetMs);
}

bool RadiosityTechnique::shootPending(FrameContext& ctx, bool budgeted, bool& shotAny, bool old) {
    const bool removeMoving = m_pending.removeMoving;
    const render::DrawFilter filter = removeMoving ? render::DrawFilter::Static : render::DrawFilter::All;
    const int receivers = removeMoving ? RAD_RECEIVERS_STATIC : RAD_RECEIVERS_ALL;
    while (m_pending.next < m_pending.count) {
        if (budgeted && !budgetAllows(!shotAny)) {
            m_budgetHit = true;
            return false;
        }
        const uint32_t first = m_pending.next;
        const uint32_t n = std::min<uint32_t>(static_cast<uint32_t>(m_batch), m_pending.count - first);
        const auto start = std::chrono::steady_clock::now();
        m_system->placeShooterHemicubes(1, first, n, ShooterAt::Front, old);
        m_system->renderHemicubes(ctx.drawer, HemicubeKind::Id, 1, n, old, filter, ctx.timers);
        m_system->reconstruct(RAD_SHOOT_UNSHOT, receivers, first, n, false, ctx.timers);
        if (m_frameBudgetMs > 0.0f) {
            // The batch's GPU work done, so its wall time is its cost (the budget's only CPU-GPU wait
            // besides FINDSHOOTINGQUAD's readback; none without a budget).
            glFinish();
            m_batchMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        }
        m_pending.next += n;
        m_frameShooters += n;
        shotAny = true;
    }
    m_pending = {};
    return true;
}

void RadiosityTechnique::beginFrameFinishingPending(FrameContext& ctx) {
    m_system->beginFrame(ctx.scene, ctx.time);
    if (!m_system->anyMoving() || m_pending.next >= m_pending.count) return;
    m_system->beginFrame(ctx.scene, m_commitTime);  // the last commit's bodies, current and old alike
    bool shotAny = true;
    shootPending(ctx, false, shotAny, true);  // hemicubes drawn with the last commit's transforms
    m_system->beginFrame(ctx.scene, ctx.time);
}

void RadiosityTechnique::commitFrame(const FrameContext& ctx) {
    m_system->commit();
    m_commitTime = ctx.time;
}

void RadiosityTechnique::progressiveRefinement(FrameContext& ctx, int maxIterations, int minIterations, bool removeMoving) {
    m_converged = false;
    const auto& quads = m_system->patches().quads();
    bool shotAny = false;
    // The last frame's iteration first: its quad's unshot was cleared when its shooters were made.
    if (!shootPending(ctx, true, shotAny)) return;
    for (int it = 0; it < maxIterations; ++it) {
        std::vector<QuadStats> stats;
        {
            auto s = ctx.timers.scope("radiosity.select");
            stats = m_system->quadStats();
        }
        // FINDSHOOTINGQUAD: the highest area-weighted mean unshot radiance (luminance), by magnitude:
        // redistribution leaves negative unshot radiosity (removed light) that must propagate too.
        int best = -1;
        float bestMean = 0.0f;
        for (size_t q = 0; q < quads.size(); ++q) {
            if (stats[q].area <= 0.0f || (removeMoving && m_system->bodyMoving(quads[q].body))) continue;
            const float mean = std::abs(luminance(stats[q].unshot)) / stats[q].area;
            if (mean > bestMean) {
                bestMean = mean;
                best = static_cast<int>(q);
            }
        }
        if (best < 0 || (bestMean < m_threshold * m_maxEmission && it >= minIterations)) {
            m_converged = true;
            break;
        }
        // The frame's shooting budget: a new quad only if its first batch fits (the last batch's
        // measured cost as its estimate).
        if (it >= minIterations && !budgetAllows(!shotAny)) {
            m_budgetHit = true;
            break;
        }
        const auto rects = subdivide(static_cast<uint32_t>(best), glm::pi<float>() * std::abs(luminance(stats[best].unshot)));
        m_system->loadShooters(rects);
        const auto n = static_cast<uint32_t>(rects.size());
        m_system->computeShooters(0, n, false);
        m_system->clearShooterUnshot(0, n);
        m_pending = {n, 0, removeMoving};
        ++m_frameIterations;
        if (!shootPending(ctx, true, shotAny)) return;
    }
}

}  // namespace bounce
