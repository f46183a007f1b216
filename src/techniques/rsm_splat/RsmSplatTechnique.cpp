// `rsm-splat` — reflective-shadow-map splatting (Dachsbacher & Stamminger 2005), the splatting
// baselines of Nichols (2010) §4.3 and Fig. 4.8.
//
// Passes: "rsm" (light 0's RSM), "vpl-cache" (regular grid), "splat" (one instanced quad per VPL,
// additive blending of Eq. 4.1's contribution). Modes: full (full-screen splats; equals the rsm gather),
// fixed (VPL influence limited to `radius` metres: the reduced-overdraw splats), matched (the radius is
// rescaled every frame by sqrt(target / measured fragments per splat), since a splat's fragments grow
// with its screen area, so splats converge to `targetFragments` — the thesis sets the radius "to
// generate the same number of fragments per splat as our multiresolution approach").
// Deviations: the radius adapts across frames (the first frame uses a quarter of the scene radius).
#include "techniques/rsm_splat/RsmSplatTechnique.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "techniques/nichols/SceneScale.h"
#include "techniques/nichols/VplWindow.h"

#include <algorithm>
#include <cmath>

namespace bounce {

namespace {
constexpr float kInitialRadiusFraction = 0.25f;  // of the scene's bounding radius (first matched frame)
constexpr int kQuadVertices = 6;
}  // namespace

void RsmSplatTechnique::visitSettings(SettingsVisitor& v) {
    v.field("rsmSize", m_rsmSize, "RSM resolution per side (thesis 256)", 8, 2048);
    v.field("vplGrid", m_vplGrid, "VPLs per side per RSM layer (thesis 16..128)", 1, 2048);
    v.field("mode", m_mode, "full: full-screen splats; fixed: splats limited to `radius`; matched: radius adapted to targetFragments", kModes);
    v.field("radius", m_radius, "fixed mode: VPL influence radius, metres (assumption); 0 = 0.3 of the scene's diagonal", 0.0f, 1e4f);
    v.field("targetFragments", m_targetFragments, "matched mode: fragments per splat (isr's gatherFragments)", 1.0f, 1e9f);
}

Expected<void> RsmSplatTechnique::setup(const SetupContext& ctx) {
    BOUNCE_TRY_VOID(nichols::RegularVpls::checkGrid(m_rsmSize, m_vplGrid, nichols::ReflectiveShadowMap::layersFor(ctx.scene)));
    m_radiusMetres = nichols::sceneLength(ctx.scene, m_radius, nichols::kSplatRadiusDiagonalFraction);
    BOUNCE_TRY(m_rsm, nichols::ReflectiveShadowMap::create());
    BOUNCE_TRY(m_vpls, nichols::RegularVpls::create());
    BOUNCE_TRY(m_splat, gl::Program::build({"rsmSplat", {{GL_VERTEX_SHADER, "techniques/rsm_splat/splat.vert"},
                                                         {GL_FRAGMENT_SHADER, "techniques/rsm_splat/splat.frag"}},
                                             nichols::VplWindow::defines()}));
    m_fbo = gl::Framebuffer::create("rsmSplat.fbo");
    m_query = gl::Query::create("rsmSplat.fragments", GL_SAMPLES_PASSED);
    m_matchedRadius = 0.0f;
    return {};
}

void RsmSplatTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    const float zero[4] = {0, 0, 0, 0};
    m_fbo.attach(GL_COLOR_ATTACHMENT0, indirect);
    m_fbo.setDrawBuffers(1);
    BOUNCE_CHECK(m_fbo.complete(), "rsm-splat framebuffer");
    glClearNamedFramebufferfv(m_fbo.id(), GL_COLOR, 0, zero);
    m_splatRadius = -1.0f;
    {
        auto s = ctx.timers.scope("rsm");
        if (!m_rsm->render(ctx, m_rsmSize)) return;
    }
    {
        auto s = ctx.timers.scope("vpl-cache");
        m_vpls->extract(*m_rsm, m_vplGrid);
    }
    float radius = 0.0f;
    if (m_mode == "fixed") radius = m_radiusMetres;
    if (m_mode == "matched") {
        if (m_matchedRadius <= 0.0f) {
            glm::vec3 lo, hi;
            ctx.scene.bounds(ctx.time, lo, hi);
            m_matchedRadius = kInitialRadiusFraction * 0.5f * glm::length(hi - lo);
        }
        radius = m_matchedRadius;
    }
    auto s = ctx.timers.scope("splat");
    m_fbo.bind();
    glViewport(0, 0, ctx.size.x, ctx.size.y);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    ctx.gbuffer.bind();
    m_vpls->buffer().bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
    m_splat.set("u_radius", radius);
    m_splat.use();
    gl::Context::current()->bindEmptyVertexArray();
    glBeginQuery(GL_SAMPLES_PASSED, m_query.id());
    // One draw per window of the VPL cache the fragment shader reads (nichols/VplWindow.h).
    const int perDraw = nichols::VplWindow::perDraw(m_vpls->count());
    for (int first = 0; first < m_vpls->count(); first += perDraw) {
        const int count = std::min(perDraw, m_vpls->count() - first);
        m_splat.set("u_windowFirst", static_cast<unsigned>(nichols::VplWindow::bind(m_vpls->buffer(), first, count)));
        m_splat.set("u_vplFirst", first);
        m_splat.use();
        glDrawArraysInstanced(GL_TRIANGLES, 0, kQuadVertices, count);
    }
    glEndQuery(GL_SAMPLES_PASSED);
    glDisable(GL_BLEND);
    m_splatRadius = radius;
}

void RsmSplatTechnique::collectCounters(Counters& out) {
    if (m_splatRadius < 0.0f) return;
    // Read after the frame is queued (no wait on the frame's path); matched mode's radius update
    // steers the next frame's splats, as it did when read here mid-frame.
    GLuint64 fragments = 0;
    glGetQueryObjectui64v(m_query.id(), GL_QUERY_RESULT, &fragments);
    const double perSplat = static_cast<double>(fragments) / std::max(m_vpls->count(), 1);
    if (m_mode == "matched" && perSplat > 0.0)
        m_matchedRadius *= static_cast<float>(std::sqrt(m_targetFragments / perSplat));
    out["vpls"] = static_cast<double>(m_vpls->count());
    out["fragmentsPerSplat"] = perSplat;
    out["splatRadius"] = m_splatRadius;
}

}  // namespace bounce
