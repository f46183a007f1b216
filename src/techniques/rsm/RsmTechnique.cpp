// `rsm` — full-resolution reflective-shadow-map gather (baseline of Nichols 2010, Ch. 4).
//
// Passes: (1) "Generate Reflective Shadow Map" — the RSM of light 0 (techniques/nichols/
// ReflectiveShadowMap: spot perspective, point/area/wide spot cube, directional orthographic);
// (2) "VPL cache" — a regular vplGrid^2 grid of VPLs per RSM layer, each carrying its block's summed
// flux; (3) "gather" — full-screen passes in which every pixel sums every VPL (Eq. 3.2 or Eq. 4.1), no
// indirect visibility, radiance = rho / pi * irradiance. The VPLs are gathered in batches of vplBatch,
// one draw per batch, added by blending: the sum is linear in the VPLs, so the batched image is the
// one-pass image up to float rounding, and the million-VPL limit (rsmSize = vplGrid = 1024) is 16 draws
// of bounded length instead of one draw of minutes on llvmpipe (on a desktop GPU a long draw trips the
// driver's watchdog). The gather reads the VPL cache through uniform-block windows (nichols/VplWindow.h):
// on llvmpipe several times faster than indexing the SSBO or walking the VPL textures (docs/techniques/rsm.md).
// With `glossy` on (bounce's extension, off by default), the GGX lobe of the receiver's BRDF toward
// the eye is added per VPL: the limit of multires-splat's mode A.
// With `vplVisibility` on (beyond the thesis, off by default; techniques/screen_voxels/VplVisibility.h) a
// "voxelize" pass voxelizes the camera's view and each VPL's contribution is multiplied by a voxel
// march from the pixel to the VPL; the march multiplies a VPL's loop iterations, so batches shrink.
//
// Deviations (docs/techniques/rsm.md gives each its reason):
// - each texel's exact solid angle and the light's intensity give the flux in watts (the thesis: a spot
//   light, equal texel solid angles, Eq. 4.4), so the 1/(4 pi) mismatch of Eqs. 4.4 and 4.7 does not arise.
// - point, area and directional lights too (nichols/ReflectiveShadowMap.h); no lights: zero indirect light.
// References: Nichols (2010) §3.2.1, §4.2.1.2; Dachsbacher & Stamminger (2005).
#include "techniques/rsm/RsmTechnique.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/ShaderLimits.h"
#include "techniques/nichols/SceneScale.h"
#include "techniques/nichols/VplWindow.h"

#include <algorithm>

namespace bounce {

void RsmTechnique::visitSettings(SettingsVisitor& v) {
    v.field("equalSolidAngle", m_equalSolidAngle, "Eq. 4.4: every RSM texel gets the frustum's solid angle / texels (thesis); off = exact per-texel solid angle");
    v.field("rsmSize", m_rsmSize, "RSM resolution per side (per cube face for point/area lights); thesis 256, 1024 for the reference", 8, 2048);
    v.field("vplGrid", m_vplGrid, "VPLs per side per RSM layer (must divide rsmSize); thesis 16..128, = rsmSize for the converged limit", 1, 2048);
    v.field("formFactor", m_formFactor, "disk: Eq. 4.1 disk-to-point form factor; point: Eq. 3.2 with an r^2 clamp", kFormFactors);
    v.field("minDistance", m_minDistance, "r clamp of the point form factor (formFactor=point), metres (assumption; the thesis gives no value); 0 = 0.05 of the scene's diagonal", 0.0f, 1e4f);
    v.field("glossy", m_glossy, "shade with the receiver's full BRDF (Lambert + GGX lobe of common/brdf.glsl) toward the eye; "
            "off = the thesis's Lambertian gather. On with vplGrid = rsmSize and formFactor=point: the limit of multires-splat's mode A");
    m_visibilitySettings.visit(v);
    v.field("vplBatch", m_vplBatch, "VPLs per gather draw, capped by one uniform-block window of the cache (1024 VPLs) and the shader loop budget (65535 loop iterations per invocation on llvmpipe), rounded down to a multiple of 16; batches are added by blending (same sum, bounded draw time)", 1, 1 << 24,
            PerProfile<int>{kVplBatchLlvmpipe, kVplBatchGpu});
}

Expected<void> RsmTechnique::setup(const SetupContext& ctx) {
    BOUNCE_TRY_VOID(nichols::RegularVpls::checkGrid(m_rsmSize, m_vplGrid, nichols::ReflectiveShadowMap::layersFor(ctx.scene)));
    m_minDistanceMetres = nichols::sceneLength(ctx.scene, m_minDistance, nichols::kMinDistanceDiagonalFraction);
    BOUNCE_TRY(m_rsm, nichols::ReflectiveShadowMap::create());
    BOUNCE_TRY(m_vpls, nichols::RegularVpls::create());
    BOUNCE_TRY(m_visibility, voxels::VplVisibility::create(m_visibilitySettings));
    // A draw sums at least one VPL; one whose march alone passes the shader loop budget would lose light
    // on llvmpipe (gpu/ShaderLimits.h; the device's budget: llvmpipe's 65535, a GPU's 2^24).
    const int budget = gl::shaderLoopIterationBudget();
    if (1 + m_visibility->loopIterationsPerTest() + 1 > budget)
        return makeError("vplVisibility: one VPL's {} march iterations pass the shader loop budget of {} ({} profile); lower raySteps or voxelBits",
                         m_visibility->loopIterationsPerTest(), budget, profileName(gl::currentProfile()));
    BOUNCE_TRY(m_gather, gl::Program::build({"rsm.gather",
                                             {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                              {GL_FRAGMENT_SHADER, "techniques/rsm/gather.frag"}},
                                             nichols::VplWindow::withDefines(m_visibility->defines())}));
    m_fbo = gl::Framebuffer::create("rsm.fbo");
    return {};
}

void RsmTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    const float zero[4] = {0, 0, 0, 0};
    m_fbo.attach(GL_COLOR_ATTACHMENT0, indirect);
    m_fbo.setDrawBuffers(1);
    BOUNCE_CHECK(m_fbo.complete(), "rsm framebuffer");
    {
        auto s = ctx.timers.scope("rsm");
        if (!m_rsm->render(ctx, m_rsmSize, m_equalSolidAngle)) {
            glClearNamedFramebufferfv(m_fbo.id(), GL_COLOR, 0, zero);
            ctx.counters["vpls"] = 0.0;
            return;
        }
    }
    {
        auto s = ctx.timers.scope("vpl-cache");
        m_vpls->extract(*m_rsm, m_vplGrid);
    }
    m_visibility->build(ctx);
    auto s = ctx.timers.scope("gather");
    m_fbo.bind();
    glViewport(0, 0, ctx.size.x, ctx.size.y);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    ctx.gbuffer.bind();
    m_gather.set("u_diskForm", m_formFactor == "disk" ? 1 : 0);
    m_gather.set("u_minDistance2", m_minDistanceMetres * m_minDistanceMetres);
    m_gather.set("u_glossy", m_glossy ? 1 : 0);
    m_visibility->setUniforms(m_gather);
    gl::Context::current()->bindEmptyVertexArray();
    // A batch is at most one uniform-block window of the VPL cache (nichols/VplWindow.h) and vplBatch VPLs;
    // each VPL costs one loop iteration plus at most one visibility march: batches stay within the shader
    // loop budget, or llvmpipe drops the batch's last VPLs (gpu/ShaderLimits.h). The first batch writes
    // (also clearing pixels without geometry), the others add.
    const int count = m_vpls->count();
    const int perVpl = 1 + m_visibility->loopIterationsPerTest();
    const int perDraw = nichols::VplWindow::perDraw(std::min(m_vplBatch, (gl::shaderLoopIterationBudget() - 1) / perVpl));
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    int draws = 0;
    for (int first = 0; first < count; first += perDraw, ++draws) {
        if (first > 0) glEnable(GL_BLEND);
        const int end = std::min(first + perDraw, count);
        m_gather.set("u_windowFirst", static_cast<unsigned>(nichols::VplWindow::bind(m_vpls->buffer(), first, end - first)));
        m_gather.set("u_vplFirst", static_cast<unsigned>(first));
        m_gather.set("u_vplEnd", static_cast<unsigned>(end));
        m_gather.use();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        // llvmpipe queues a frame's draws before rasterising; a flush per batch makes each batch a
        // separate unit of work (as a GPU's per-submission watchdog would need).
        glFlush();
    }
    glDisable(GL_BLEND);
    ctx.counters["gatherDraws"] = static_cast<double>(draws);
    ctx.counters["vpls"] = static_cast<double>(m_vpls->count());
    ctx.counters["gatherFragments"] = static_cast<double>(ctx.size.x) * ctx.size.y;
}

}  // namespace bounce
