// `multires-splat` — multiresolution splatting for indirect illumination (Nichols 2010, Ch. 3;
// Nichols & Wyman, I3D 2009), refinement modes B (refinement=shared, the thesis's default) and A
// (refinement=per-vpl, §3.2.3.1).
//
// Passes (timers): "rsm" (light 0's RSM), "vpl-cache" (regular vplGrid^2 VPLs), "min-max-mipmap" (eye
// pyramid: depth-derivative max-mipmap and per-component normal min-max down to 16^2, optionally the
// curvature max-mipmap of §3.3.1 / Eq. 3.1, refine flags with the diagonal-neighbour test), "refine"
// (iterative subsplat refinement: all cells of the coarsest level, then one geometry-shader pass per
// level that splits refined subsplats into their four children, captured by transform feedback into
// ping-pong buffers; refinePass=compute, the default: refine.comp, one atomic-append dispatch per pass and
// indirect draws, same decision, refine.glsl), "splat" (the shared list drawn as GL_POINTS once per VPL into the flattened
// multiresolution buffer, additive, Eq. 4.1's disk form factor (formFactor=disk, bounce's default) or
// Eq. 3.2 with the r^2 clamp (point); splatPrimitive=stencil: the list's
// points mark the atlas stencil and each VPL is one stencilled triangle per level, §4.2.1.1's stencilled
// splat, the same pairs, VPLs read from uniform-block windows, nichols/VplWindow.h; splatPrimitive=auto, the
// default, is stencil for mode B and points for mode A), "upsample"
// (coarse-to-fine, §3.2.5, then x albedo/pi).
// Mode A: every subsplat carries its VPL index (w), the initial list holds the coarsest cells once per
// VPL, and the refine pass also splits a subsplat when the glossy radiance toward the eye from its VPL,
// evaluated at the four children, varies by more than illuminationContrast times the children's mean
// radiance from that VPL (the thesis's SamplesDiffer made relative, with a black floor; OR-ed with the
// geometric flags so a Lambertian scene gives mode B's lists); each subsplat is then splatted with its
// own VPL only, and (glossyShading, default on) carries the receiver's full BRDF: the Lambert part as
// irradiance into the usual buffer (x albedo/pi per pixel after upsampling, as mode B), the GGX lobe of
// common/brdf.glsl toward the eye as radiance at the subsplat's patch into a second buffer (same
// levels, upsampled the same way, added). Its limit is `rsm glossy=true formFactor=point` with the same
// VPLs. VPLs are processed in batches whose worst-case lists fit 64 MiB.
// Counters: vpls, subsplats (B: entries of the shared list; A: sum over the per-VPL lists), splats
// (subsplat-VPL pairs drawn), fillFraction = splats / (VPLs x pixels) (R2).
// With `vplVisibility` on (beyond the thesis, off by default; techniques/screen_voxels/VplVisibility.h) a
// "voxelize" pass voxelizes the camera's view and every splatted subsplat-VPL pair is multiplied by a
// voxel march from the subsplat's patch to the VPL (mode A's refinement still sees unoccluded light).
//
// Eq. 3.3's detail modulation is optional (detailModulation, alpha 0.5); it scales the glossy part too.
// indirectSize caps the indirect resolution (thesis ch. 3: 128^2..1024^2 in a 1024^2 window): the eye
// pyramid, lists and atlas are built at output / 2^k and the result upsampled to the output
// (empty-aware bilinear, nichols/output_upsample.glsl); linearDepth selects §3.2.2.1's linear-depth
// min-max mipmap instead of the depth-derivative max-mipmap.
// Deviations (docs/techniques/multires-splat.md gives each its reason and measurement):
// - mode A: bounce's GGX lobe (common/brdf.glsl) in place of the thesis's Phong lobe.
// - mode A: the glossy material is read from the G-buffer at each cell's central pixel.
// - mode A: the contrast threshold T is relative (the thesis's is an unstated absolute radiance).
// - mode A: the Lambert part of the splats is applied per pixel, not at the patch.
// - the geometry shader runs four instances per subsplat, each emitting at most one point (the
//   thesis's emits up to four; llvmpipe's transform feedback lost multi-vertex output).
// - a flattened atlas instead of one render target per level (same texels).
// - the refinement test reads the pyramid's monotone refine flag, so the final list equals isr's stencil.
#include "techniques/multires_splat/MultiresSplatTechnique.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/DispatchGrid.h"
#include "techniques/nichols/SceneScale.h"
#include "techniques/nichols/VplWindow.h"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace bounce {

namespace {
constexpr GLuint kSubsplatAttribute = 0;  // refine.vert / splat.vert a_subsplat
constexpr int kMaxLevels = 16;            // splat.vert u_origins[16]
// Mode A list memory per batch (two ping-pong buffers of this size); bounce's choice, not the thesis's
// (its Table 3.1 marks configurations "N/A" that exceeded the GTX 280's memory).
constexpr size_t kListBudgetBytes = size_t{64} << 20;
// refinePass=compute (refine.comp): dispatch sizes (two uvec4) before the draw commands, 16 bytes each;
// at most one workgroup row per list (GL_MAX_COMPUTE_WORK_GROUP_COUNT's guaranteed 65,535).
constexpr size_t kControlHeaderBytes = 2 * 4 * sizeof(uint32_t);
constexpr size_t kDrawCommandBytes = 4 * sizeof(uint32_t);
constexpr int kMaxRegions = 65535;
}  // namespace

void MultiresSplatTechnique::buildEye(FrameContext& ctx) {
    m_eye->buildEye(ctx.gbuffer, m_eyeCoarsest, m_thresholds,
                    m_curvature ? std::optional<float>(m_curvatureThreshold) : std::nullopt,
                    nichols::indirectScale(m_indirectSize, ctx.gbuffer.size()));
}

void MultiresSplatTechnique::visitSettings(SettingsVisitor& v) {
    v.field("rsmSize", m_rsmSize, "RSM resolution per side", 8, 2048);
    v.field("vplGrid", m_vplGrid, "VPLs per side per RSM layer (thesis 16..128)", 1, 2048);
    v.field("eyeCoarsest", m_eyeCoarsest, "coarsest illumination-buffer level (thesis 16)", 1, 4096);
    static constexpr std::string_view kPrimitives[] = {"auto", "points", "quads", "stencil"};
    v.field("splatPrimitive", m_splatPrimitive,
            "subsplats drawn as points (thesis), as one-texel quads through a geometry shader (§3.4.1's comparison), or "
            "stencil: the list marks the atlas stencil once and each VPL splats one stencilled full-level triangle per level "
            "(§4.2.1.1's stencilled splat; refinement=shared only); auto: stencil with refinement=shared, points with "
            "per-vpl; same image",
            kPrimitives);
    static constexpr std::string_view kRefinePasses[] = {"compute", "geometry"};
    v.field("refinePass", m_refinePass,
            "how each refinement pass runs: compute (an atomic-append dispatch per pass, indirect draws; bounce's default) "
            "or geometry (the thesis's geometry shader with transform feedback); same subsplats, same image. Per device profile: "
            "compute on llvmpipe (which runs geometry shaders and transform feedback on one thread), geometry on a GPU",
            kRefinePasses, PerProfile<std::string_view>{"compute", "geometry"});
    v.field("upsampling", m_upsampling, nichols::kUpsampleFilterHelp, nichols::kUpsampleFilters);
    v.field("formFactor", m_formFactor,
            "disk: Eq. 4.1's disk-to-point form factor, as the rsm gather (bounce's default; the VPL's patch area bounds the "
            "near field); point: Eq. 3.2 with the r^2 clamp minDistance (the thesis's ch. 3)",
            kFormFactors);
    v.field("minDistance", m_minDistance, "r clamp of Eq. 3.2 (formFactor=point), metres (assumption); 0 = 0.05 of the scene's diagonal", 0.0f, 1e4f);
    v.field("detailModulation", m_detailModulation, "Eq. 3.3: modulate indirect light by alpha <V,N> + (1 - alpha) (§3.3.3)");
    v.field("detailAlpha", m_detailAlpha, "Eq. 3.3's alpha (thesis 0.5, Fig. 3.9)", 0.0f, 1.0f);
    v.field("depthThreshold", m_thresholds.depth, "max relative depth derivative per pixel (assumption)", 0.0f, 1e9f);
    v.field("normalThreshold", m_thresholds.normal, "normal component range, 0..2 (assumption)", 0.0f, 2.0f);
    v.field("refinement", m_refinement,
            "shared: mode B, one geometric list for all VPLs (thesis default, §3.2.3); per-vpl: mode A, one list per "
            "VPL also split where the glossy light toward it varies (§3.2.3.1)",
            kRefinements);
    v.field("illuminationContrast", m_illuminationContrast,
            "mode A SamplesDiffer threshold T, relative: split where max - min of the children's glossy radiance toward "
            "the VPL exceeds T x their mean radiance from it (Lambert + glossy; a black floor keeps unlit regions coarse); "
            "unitless, assumption (the thesis's T is absolute and unstated)",
            0.0f, 1e9f);
    v.field("glossyShading", m_glossyShading,
            "mode A splats the receiver's full BRDF toward the eye (Lambert + GGX lobe of common/brdf.glsl); off: "
            "Lambertian, like mode B and the thesis's splats");
    v.field("curvature", m_curvature, "§3.3.1: also refine where Eq. 3.1's curvature max-mipmap exceeds curvatureThreshold");
    v.field("curvatureThreshold", m_curvatureThreshold,
            "max curvature kappa = 2 sin(angle / 2) between neighbouring pixels, 0..2 (Fig. 3.10: 0.1, 0.3)", 0.0f, 2.0f);
    v.field("edgeNeighbours", m_thresholds.edgeNeighbours, "also test edge-adjacent cells (§3.4.2: up to 40 % slower)");
    nichols::visitEyeSettings(v, m_thresholds, m_indirectSize);
    m_visibilitySettings.visit(v);
}

Expected<void> MultiresSplatTechnique::setup(const SetupContext& ctx) {
    BOUNCE_TRY_VOID(nichols::checkIndirectSize(m_indirectSize, ctx.size));
    BOUNCE_TRY_VOID(nichols::RegularVpls::checkGrid(m_rsmSize, m_vplGrid, nichols::ReflectiveShadowMap::layersFor(ctx.scene)));
    m_minDistanceMetres = nichols::sceneLength(ctx.scene, m_minDistance, nichols::kMinDistanceDiagonalFraction);
    // auto (the default): the stencilled splat where it applies (one shared list), else the thesis's points.
    m_primitive = m_splatPrimitive != "auto" ? m_splatPrimitive : m_refinement == "shared" ? "stencil" : "points";
    if (m_splatPrimitive == "stencil" && m_refinement != "shared")
        return makeError("splatPrimitive=stencil splats one shared list (refinement=shared); refinement={} has one list per VPL",
                         m_refinement);
    BOUNCE_TRY(m_rsm, nichols::ReflectiveShadowMap::create());
    BOUNCE_TRY(m_vpls, nichols::RegularVpls::create());
    BOUNCE_TRY(m_eye, nichols::MinMaxPyramid::create());
    BOUNCE_TRY(m_buffer, nichols::MultiresBuffer::create());
    BOUNCE_TRY(m_glossy, nichols::MultiresBuffer::create());
    BOUNCE_TRY(m_visibility, voxels::VplVisibility::create(m_visibilitySettings));
    BOUNCE_TRY(m_glossyCombine, gl::Program::build({"multiresSplat.glossyCombine",
                                                    {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                     {GL_FRAGMENT_SHADER, "techniques/multires_splat/glossy_combine.frag"}}}));
    m_splatFbo = gl::Framebuffer::create("multiresSplat.splatFbo");
    m_glossyFbo = gl::Framebuffer::create("multiresSplat.glossyFbo");
    // refinePass: only the selected pass's programs (each costs llvmpipe a compile).
    if (m_refinePass == "compute") {
        BOUNCE_TRY(m_refineCompute, gl::Program::build({"multiresSplat.refineCompute",
                                                        {{GL_COMPUTE_SHADER, "techniques/multires_splat/refine.comp"}}}));
        BOUNCE_TRY(m_refineReset, gl::Program::build({"multiresSplat.refineReset",
                                                      {{GL_COMPUTE_SHADER, "techniques/multires_splat/refine_reset.comp"}}}));
    } else {
        BOUNCE_TRY(m_refine, gl::Program::build({"multiresSplat.refine",
                                                 {{GL_VERTEX_SHADER, "techniques/multires_splat/refine.vert"},
                                                  {GL_GEOMETRY_SHADER, "techniques/multires_splat/refine.geom"}},
                                                 {},
                                                 {"g_subsplat"}}));
    }
    {
        // splatPrimitive=quads: a geometry shader turns each point into a one-texel quad (§3.4.1's
        // comparison; same fragments, same image).
        gl::ProgramDesc splat{"multiresSplat.splat",
                              {{GL_VERTEX_SHADER, "techniques/multires_splat/splat.vert"},
                               {GL_FRAGMENT_SHADER, "techniques/multires_splat/splat.frag"}},
                              m_visibility->defines()};
        if (m_primitive == "quads") {
            splat.stages.push_back({GL_GEOMETRY_SHADER, "techniques/multires_splat/splat_quad.geom"});
            splat.defines.emplace_back("SPLAT_QUADS", "1");
        }
        BOUNCE_TRY(m_splat, gl::Program::build(splat));
    }
    if (m_primitive == "stencil") {
        BOUNCE_TRY(m_mark, gl::Program::build({"multiresSplat.mark",
                                               {{GL_VERTEX_SHADER, "techniques/multires_splat/splat.vert"},
                                                {GL_FRAGMENT_SHADER, "techniques/multires_splat/mark.frag"}},
                                               m_visibility->defines()}));
        BOUNCE_TRY(m_splatStencil, gl::Program::build({"multiresSplat.splatStencil",
                                                       {{GL_VERTEX_SHADER, "techniques/multires_splat/splat_stencil.vert"},
                                                        {GL_FRAGMENT_SHADER, "techniques/multires_splat/splat_stencil.frag"}},
                                                       nichols::VplWindow::withDefines(m_visibility->defines())}));
    }
    m_feedback[0] = gl::TransformFeedback::create("multiresSplat.feedback0");
    m_feedback[1] = gl::TransformFeedback::create("multiresSplat.feedback1");
    m_levelCounts = gl::Buffer::create("multiresSplat.levelCounts", kMaxLevels * sizeof(uint32_t));
    return {};
}

void MultiresSplatTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    m_frameVpls = -1;
    {
        auto s = ctx.timers.scope("rsm");
        if (!m_rsm->render(ctx, m_rsmSize)) {
            buildEye(ctx);
            m_buffer->begin(*m_eye);  // empty atlas: zero indirect light
            m_buffer->upsample(nichols::upsampleFilter(m_upsampling));
            m_buffer->combine(ctx.gbuffer, indirect, 0.0f, m_eye->scale());
            return;
        }
    }
    {
        auto s = ctx.timers.scope("vpl-cache");
        m_vpls->extract(*m_rsm, m_vplGrid);
    }
    {
        auto s = ctx.timers.scope("min-max-mipmap");
        buildEye(ctx);
    }
    m_visibility->build(ctx);
    const int levels = m_eye->levels();
    BOUNCE_CHECK(levels <= kMaxLevels, "multires-splat supports up to {} levels", kMaxLevels);
    const bool perVpl = m_refinement == "per-vpl";
    const bool glossy = perVpl && m_glossyShading;
    const glm::ivec2 base = m_eye->levelSize(0);
    const size_t perList = static_cast<size_t>(base.x) * base.y;  // a list never exceeds one subsplat per pixel
    const int vplCount = m_vpls->count();
    // Mode A holds one list per VPL side by side; VPLs are refined and splatted in batches whose
    // worst-case lists fit kListBudgetBytes.
    int batch = perVpl ? static_cast<int>(std::clamp<size_t>(kListBudgetBytes / (perList * sizeof(glm::ivec4)), 1,
                                                                   static_cast<size_t>(std::max(vplCount, 1))))
                             : 1;
    const bool computeRefine = m_refinePass == "compute";
    // refinePass=compute: one workgroup row per list of the batch (GL guarantees 65,535 rows).
    if (computeRefine) batch = std::min(batch, kMaxRegions);
    const size_t capacity = perList * static_cast<size_t>(batch) * sizeof(glm::ivec4);
    if (capacity != m_capacity) {
        m_capacity = capacity;
        for (int i = 0; i < 2; ++i) {
            m_lists[i] = gl::Buffer::create(i == 0 ? "multiresSplat.list0" : "multiresSplat.list1", capacity);
            m_vaos[i] = gl::VertexArray::create(i == 0 ? "multiresSplat.vao0" : "multiresSplat.vao1");
            glVertexArrayVertexBuffer(m_vaos[i].id(), 0, m_lists[i].id(), 0, sizeof(glm::ivec4));
            glEnableVertexArrayAttrib(m_vaos[i].id(), kSubsplatAttribute);
            glVertexArrayAttribIFormat(m_vaos[i].id(), kSubsplatAttribute, 4, GL_INT, 0);
            glVertexArrayAttribBinding(m_vaos[i].id(), kSubsplatAttribute, 0);
            glTransformFeedbackBufferBase(m_feedback[i].id(), 0, m_lists[i].id());
        }
    }
    // refinePass=compute's control block: two uvec4 dispatch sizes, then two sides of one
    // DrawArraysIndirectCommand per list (refine.comp).
    const size_t controlBytes = kControlHeaderBytes + 2 * static_cast<size_t>(batch) * kDrawCommandBytes;
    if (computeRefine && (!m_control || m_control.size() != controlBytes))
        m_control = gl::Buffer::create("multiresSplat.refineControl", controlBytes);
    m_levelCounts.clearZero();
    {
        auto s = ctx.timers.scope("splat");
        m_buffer->begin(*m_eye);
        if (glossy) {
            m_glossy->begin(*m_eye);
            m_splatFbo.attach(GL_COLOR_ATTACHMENT0, m_buffer->atlas());
            m_splatFbo.attach(GL_COLOR_ATTACHMENT1, m_glossy->atlas());
            m_splatFbo.setDrawBuffers(2);
            BOUNCE_CHECK(m_splatFbo.complete(), "multires-splat glossy splat framebuffer");
        }
    }
    // Mode B: one list with w = 0, drawn once per VPL. Mode A: VPLs [first, first + n) with w = VPL.
    const int lists = perVpl ? vplCount : 1;
    for (int first = 0; first < lists; first += batch) {
        const int n = std::min(batch, lists - first);
        int current = 0;
        {
            auto s = ctx.timers.scope("refine");
            m_eye->geometry().bind(BINDING_TEX_TECH0);
            m_eye->refine().bind(BINDING_TEX_TECH1);
            m_eye->normal().bind(BINDING_TEX_TECH2);
            ctx.gbuffer.bind();
            m_vpls->buffer().bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
            gl::Program& refine = computeRefine ? m_refineCompute : m_refine;
            refine.set("u_levelSize", m_eye->levelSizes(kMaxLevels));
            refine.set("u_perVpl", perVpl ? 1 : 0);
            refine.set("u_relativeThreshold", m_illuminationContrast);
            refine.set("u_minDistance2", m_minDistanceMetres * m_minDistanceMetres);
            refine.set("u_diskForm", m_formFactor == "disk" ? 1 : 0);
            refine.set("u_gbufferScale", m_eye->scale());
            const glm::ivec2 top = m_eye->levelSize(levels - 1);
            if (computeRefine) {
                // The final list is drawn once: mode B's splat with one instance per VPL; mode A's lists
                // and the stencil marks with one.
                const int instances = perVpl || m_primitive == "stencil" ? 1 : vplCount;
                m_refineReset.set("u_regions", n);
                m_refineReset.set("u_regionStride", static_cast<unsigned>(perList));
                m_refineReset.set("u_instances", static_cast<unsigned>(instances));
                refine.set("u_coarsest", levels - 1);
                refine.set("u_coarsestSize", top);
                refine.set("u_firstVpl", first);
                refine.set("u_regionStride", static_cast<unsigned>(perList));
                refine.set("u_regions", n);
                refine.set("u_maxGroupsX", gl::maxGroupsX());
                m_control.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH3);
                glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, m_control.id());
                // One pass per level (16^2 -> full resolution); the first generates the coarsest cells
                // and drops the uncovered ones.
                for (int pass = 0; pass < levels; ++pass) {
                    const int next = 1 - current;
                    m_refineReset.set("u_side", next);
                    m_refineReset.use();
                    glDispatchCompute(static_cast<GLuint>((n + 63) / 64), 1, 1);
                    // The reset writes the other side of the control block than the indirect dispatch below
                    // reads; the command bit keeps the barrier tracker's whole-buffer rule exact (issue 29).
                    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
                    m_lists[current].bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
                    m_lists[next].bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH2);
                    refine.set("u_initial", pass == 0 ? 1 : 0);
                    refine.set("u_src", current);
                    refine.use();
                    if (pass == 0) {
                        const gl::GroupGrid g = gl::groupGrid((static_cast<uint64_t>(top.x) * top.y + 63) / 64, gl::maxGroupsX());
                        glDispatchCompute(g.x, static_cast<GLuint>(n), g.y);
                    } else {
                        glDispatchComputeIndirect(static_cast<GLintptr>(current * sizeof(glm::uvec4)));
                    }
                    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
                    current = next;
                }
                glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
            } else {
                std::vector<glm::ivec4> initial;
                for (int l = first; l < first + n; ++l)
                    for (int y = 0; y < top.y; ++y)
                        for (int x = 0; x < top.x; ++x) initial.emplace_back(levels - 1, x, y, perVpl ? l : 0);
                m_lists[0].upload(0, initial.size() * sizeof(glm::ivec4), initial.data());
                refine.use();
                glEnable(GL_RASTERIZER_DISCARD);
                // One pass per level (16^2 -> full resolution); the first pass also drops uncovered cells.
                for (int pass = 0; pass < levels; ++pass) {
                    const int next = 1 - current;
                    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, m_feedback[next].id());
                    m_vaos[current].bind();
                    glBeginTransformFeedback(GL_POINTS);
                    if (pass == 0) glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(initial.size()));
                    else glDrawTransformFeedback(GL_POINTS, m_feedback[current].id());
                    glEndTransformFeedback();
                    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
                    current = next;
                }
                glDisable(GL_RASTERIZER_DISCARD);
            }
        }
        // The final list as points: refinePass=compute draws one indirect command per list (counts from
        // refine.comp, instances from refine_reset.comp), geometry its transform feedback.
        const auto drawList = [&](int instances) {
            if (computeRefine) {
                glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_control.id());
                const size_t offset = kControlHeaderBytes + static_cast<size_t>(current) * n * kDrawCommandBytes;
                glMultiDrawArraysIndirect(GL_POINTS, reinterpret_cast<const void*>(offset), n, static_cast<GLsizei>(kDrawCommandBytes));
                glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
            } else {
                glDrawTransformFeedbackInstanced(GL_POINTS, m_feedback[current].id(), instances);
            }
        };
        {
            auto s = ctx.timers.scope("splat");
            if (glossy) {
                m_splatFbo.bind();
                glViewport(0, 0, m_buffer->atlasSize().x, m_buffer->atlasSize().y);
            } else {
                m_buffer->bindAtlas();
            }
            glDisable(GL_DEPTH_TEST);
            glDisable(GL_STENCIL_TEST);
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            std::vector<glm::ivec2> origins(kMaxLevels, glm::ivec2(0));
            for (int k = 0; k < levels; ++k) origins[static_cast<size_t>(k)] = m_buffer->levelOrigin(k);
            // splatPrimitive=stencil: the list's points only mark the stencil (splat.vert, one instance, so
            // its per-level subsplat counts are the list's); the VPLs are splatted below.
            gl::Program& points = m_primitive == "stencil" ? m_mark : m_splat;
            points.set("u_origins", origins);
            points.set("u_atlasSize", m_buffer->atlasSize());
            points.set("u_minDistance2", m_minDistanceMetres * m_minDistanceMetres);
            points.set("u_diskForm", m_formFactor == "disk" ? 1 : 0);
            points.set("u_gbufferScale", m_eye->scale());
            points.set("u_perVpl", perVpl ? 1 : 0);
            if (m_primitive != "stencil") points.set("u_glossy", glossy ? 1 : 0);
            // One fragment is one subsplat-VPL pair: a single visibility test per invocation, far within
            // the shader loop budget, so the splat draw needs no batching for it.
            m_visibility->setUniforms(points);
            m_eye->geometry().bind(BINDING_TEX_TECH0);
            m_eye->normal().bind(BINDING_TEX_TECH2);
            ctx.gbuffer.bind();
            m_vpls->buffer().bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
            m_levelCounts.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);
            points.use();
            m_vaos[current].bind();
            if (m_primitive == "stencil") {
                glDisable(GL_BLEND);
                glEnable(GL_STENCIL_TEST);
                glStencilFunc(GL_ALWAYS, 1, 0xFF);
                glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
                glStencilMask(0xFF);
                glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
                drawList(1);
                glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
                glDisable(GL_STENCIL_TEST);
                m_splatStencil.set("u_minDistance2", m_minDistanceMetres * m_minDistanceMetres);
                m_splatStencil.set("u_diskForm", m_formFactor == "disk" ? 1 : 0);
                m_visibility->setUniforms(m_splatStencil);
                // One window of VPLs per instanced draw (nichols/VplWindow.h), one draw per level.
                const int perDraw = nichols::VplWindow::perDraw(vplCount);
                for (int v = 0; v < vplCount; v += perDraw) {
                    const int count = std::min(perDraw, vplCount - v);
                    m_splatStencil.set("u_windowFirst", static_cast<unsigned>(nichols::VplWindow::bind(m_vpls->buffer(), v, count)));
                    m_splatStencil.set("u_vplFirst", static_cast<unsigned>(v));
                    for (int k = 0; k < levels; ++k) m_buffer->splatLevel(k, m_splatStencil, 1, count);
                }
            } else {
                drawList(perVpl ? 1 : vplCount);
            }
            glDisable(GL_BLEND);
        }
    }
    m_frameVpls = vplCount;
    m_frameLevels = levels;
    m_framePixels = static_cast<double>(perList);
    m_framePerVpl = perVpl;
    {
        auto s = ctx.timers.scope("upsample");
        m_buffer->upsample(nichols::upsampleFilter(m_upsampling));
        const float detailAlpha = m_detailModulation ? m_detailAlpha : 0.0f;
        m_buffer->combine(ctx.gbuffer, indirect, detailAlpha, m_eye->scale());
        if (glossy) {
            m_glossy->upsample(nichols::upsampleFilter(m_upsampling));
            m_glossyFbo.attach(GL_COLOR_ATTACHMENT0, indirect);
            m_glossyFbo.setDrawBuffers(1);
            BOUNCE_CHECK(m_glossyFbo.complete(), "multires-splat glossy combine framebuffer");
            m_glossyFbo.bind();
            glViewport(0, 0, indirect.width(), indirect.height());
            glDisable(GL_DEPTH_TEST);
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            ctx.gbuffer.bind();
            m_glossy->result().bind(BINDING_TEX_TECH0);
            m_glossyCombine.set("u_detailAlpha", detailAlpha);
            m_glossyCombine.set("u_scale", m_eye->scale());
            m_glossyCombine.use();
            gl::Context::current()->bindEmptyVertexArray();
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glDisable(GL_BLEND);
        }
    }
}

void MultiresSplatTechnique::collectCounters(Counters& out) {
    if (m_frameVpls < 0) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    uint32_t perLevel[kMaxLevels] = {};
    m_levelCounts.download(0, sizeof(perLevel), perLevel);
    double subsplats = 0.0;
    for (int k = 0; k < m_frameLevels; ++k) {
        out[fmt::format("subsplats/level-{}", k)] = perLevel[k];
        subsplats += perLevel[k];
    }
    const double splats = subsplats * (m_framePerVpl ? 1.0 : static_cast<double>(m_frameVpls));
    out["vpls"] = static_cast<double>(m_frameVpls);
    // Mode B: entries of the shared list; mode A: the sum over the per-VPL lists (Table 3.1's count).
    out["subsplats"] = subsplats;
    out["splats"] = splats;  // subsplat-VPL pairs drawn
    out["fillFraction"] = m_frameVpls > 0 ? splats / (static_cast<double>(m_frameVpls) * m_framePixels) : 0.0;
    m_visibility->collectCounters(out);
}

}  // namespace bounce
