// `area-light` — multiresolution textured area lights with screen-space voxel visibility (Nichols
// 2010, ch. 5; Nichols, Penmatsa & Wyman, Tech. Rep. UICS-10-01, 2010).
//
// Direct light only: this technique writes the frame's direct radiance (emission + the area lights'
// light, Eq. 5.2) and zero indirect light; the indirect light of area lights stays with the other
// techniques. Passes, per frame (timers in quotes):
//   "vpls"            a vplsPerSide^2 grid of VPLs per light (thesis 16^2 = 256) on the light texture's
//                     prefiltered mip level (§5.3.2.1; the texture animates: images, sequences, the
//                     bouncing square).
//   "voxelize"        the screen-space binary voxelization of the view frustum, voxelColumns^2 columns x
//                     voxelBits (thesis 128) linear depth slices, logical-OR blending (§5.3.3; shared
//                     machinery, techniques/screen_voxels); with voxelOutside a second grid of the same
//                     size, orthographic along the first light over the scene's and lights' bounds, for
//                     the parts of rays outside the camera's frustum (a deviation).
//   "min-max-mipmap"  the ch. 4 eye pyramid (depth derivative, normal min-max) down to coarsest (thesis:
//                     incremental visibility starts at 64^2), and "lobe-mipmap" the BRDF-frequency
//                     pyramid (min/max specular roughness per cell, §5.3.2.1).
//   per level, coarsest first (§5.3.4, incremental stencil rendering), for the diffuse buffer:
//   "classify"+"stencil"  which cells are in the refinement tree and which are rendered: parent refined by
//                     depth/normal or lit discontinuously; emitter cells, cells facing away from every
//                     light corner and cells behind one-sided lights culled (§5.3.2).
//   "gather-diffuse"  Eq. 5.2 at rendered cells, with per-VPL binary visibility by voxel ray marching
//                     (uniform steps, thick-ray bit test, origin bias; §5.3.3.1) refined incrementally:
//                     per-cell VPL bitstreams, a VPL's bit reused where the parent level's 3x3 block
//                     agrees, re-cast where it disagrees, 2x2 interleaved VPL subsets (§5.3.3.2);
//                     tree cells that are not rendered compute their bitstreams only.
//   "interleave"      subsets summed over same-surface neighbours; the bit-count metric (cells where at
//                     least bitCountFraction of the VPLs are partially visible are refined).
//   "upsample"        the §3.2.5 coarse-to-fine upsampling of this level (finer results replace coarser).
//   "discontinuity"   cells whose neighbourhood varies by more than colourThreshold are refined (§5.3.4).
//   then the same loop over the specular buffer ("gather-specular": the separate Phong pass, lobe-miss
//   culling, lobe-width refinement, 5x5 lobe-centred texture samples when fewer than 9 VPLs fall in
//   the lobe; §5.3.2.1), and "final": the emitters box-filtered over each pixel (16 rays against the
//   lights' rectangles, as the reference's pixels see them) + albedo/pi E + F S per pixel.
// visibility=brute ray-marches every VPL at every cell (§5.3.3.1, the baseline of Fig. 5.4);
// visibility=none is §5.3.2's V = 1.
//
// visibility=shadow-maps is §5.4.6's rasterized baseline: a paraboloid map per VPL ("vpl-shadow-maps",
// techniques/paraboloid/ParaboloidMaps.h).
//
// Deviations and assumptions (docs/techniques/area-light.md gives each its reason and values):
// - Eq. 5.2's r^2 is kept at or above A / pi (a near-field bound: no VPL gives more than pi L).
// - the "Phong" pass evaluates bounce's GGX lobe, its width from the equivalent Phong exponent.
// - the specular pass multiplies a per-pixel Schlick Fresnel at the end.
// - the specular pass ray-marches its VPLs without bitstreams.
// - sharp lobes' samples take §5.3.3.3's variance visibility (moments as ray fractions, 2x2
//   interleaved, 3x3 blur, Chebyshev).
// - bitstreams are RGBA32UI image layers of 128 bits written with image stores (the thesis: a
//   4 x 16-bit render target of 64 bits).
// - the colour threshold compares a white receiver's radiance (the display colour at 0 EV).
// - thresholds, ray steps, bias, the interleave reconstruction, the lobe threshold and the voxel
//   depth range (the scene bounds in view space) are assumptions (the thesis gives none).
// Only area lights are shaded: a scene with point, spot or directional lights or emissive materials
// is refused, so that the output is the like-for-like counterpart of `bounce reference --bounces 0`.
#include "techniques/area_light/AreaLightTechnique.h"

#include "core/Check.h"
#include "gpu/Bindings.h"
#include "gpu/Context.h"
#include "gpu/ShaderLimits.h"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce {

namespace {

constexpr int kLocalSize = 8;        // 2D compute passes' local size
constexpr int kVplLocalSize = 64;    // vpls.comp
constexpr int kMaxBitstreamLayers = 8;  // 1024 bits per cell: incremental visibility's storage bound
// The shadow-map baseline (§5.4.6: "1024 rasterized 64^2 shadow maps"): at most that many maps.
constexpr int kMaxVplShadowMaps = 1024;
// Paraboloid maps as iir's: the VPL sits 1e-3 scene diagonals off the emitter so that the light's
// mounting surface does not shadow it, and the depth range is the scene diagonal (no two points are
// farther apart).
constexpr float kVplMapOffsetInDiagonals = 1e-3f;
constexpr float kVplMapFarInDiagonals = 1.01f;
// Depth bias of the map lookups, as a fraction of the far distance (assumption; the thesis gives
// none): 64^2 paraboloid texels span ~3 degrees, so receivers at grazing angles to a VPL differ from
// their texels' depths by centimetres. On cornell-box-area at 1024 VPLs 1e-3 lost 42 % of the
// receivers' energy to acne, 1e-2 14 %, 2e-2 (2 cm there) 7 %, as much as the voxels' over-occlusion.
constexpr float kVplMapDepthBias = 2e-2f;
// The second voxel grid's box (voxelOutside) is the scene's and the lights' bounds grown by this
// fraction of its diagonal, and at least kMinOuterExtent metres, each side (engineering choices: its
// faces then lie inside the grid, and a flat scene still has a depth range).
constexpr float kOuterGridMargin = 0.01f;
constexpr float kMinOuterExtent = 1e-3f;

gl::ProgramDesc fullscreen(std::string_view name, std::string_view fragment) {
    return {std::string(name), {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, std::string(fragment)}}};
}

GLuint groups(int n) { return static_cast<GLuint>((n + kLocalSize - 1) / kLocalSize); }

// The view of the second voxel grid (voxelOutside): orthographic, along the first light's normal
// (rays towards a light run mostly along it), over the scene's bounds and every shaded light's
// rectangle, so that it holds every surface a segment from a receiver to a light can cross.
render::View outerGridView(const render::SceneGpu& sceneGpu, const std::vector<Light>& lights,
                           const std::vector<size_t>& shaded, glm::ivec2 columns) {
    const Light& first = lights[shaded.front()];
    const glm::vec3 n = first.areaNormal(), t = glm::normalize(first.edgeU), b = glm::cross(n, t);
    glm::vec3 lo, hi;
    sceneGpu.scene().bounds(sceneGpu.time(), lo, hi);
    std::vector<glm::vec3> points;
    for (int c = 0; c < 8; ++c) points.emplace_back((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    for (size_t i : shaded)
        for (int c = 0; c < 4; ++c)
            points.push_back(lights[i].position + ((c & 1) - 0.5f) * lights[i].edgeU + ((c >> 1) - 0.5f) * lights[i].edgeV);
    glm::vec3 mn(std::numeric_limits<float>::max()), mx(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : points) {
        const glm::vec3 q(glm::dot(p, t), glm::dot(p, b), glm::dot(p, n));
        mn = glm::min(mn, q);
        mx = glm::max(mx, q);
    }
    // A margin of kOuterGridMargin of the box's size (at least kMinOuterExtent) keeps its faces off the
    // grid's borders.
    const float margin = std::max(kOuterGridMargin * glm::length(mx - mn), kMinOuterExtent);
    mn -= margin;
    mx += margin;
    render::View v;
    for (int c = 0; c < 3; ++c) {  // rows t, b, n (GLM is column-major: [col][row])
        v.viewFromWorld[c][0] = t[c];
        v.viewFromWorld[c][1] = b[c];
        v.viewFromWorld[c][2] = n[c];
    }
    v.viewFromWorld[3][2] = -mx.z;  // the eye on the box's +n face, looking along -n
    v.nearPlane = 0.0f;
    v.farPlane = mx.z - mn.z;
    v.clipFromView = glm::ortho(mn.x, mx.x, mn.y, mx.y, v.nearPlane, v.farPlane);
    v.eye = glm::vec3(glm::inverse(v.viewFromWorld)[3]);
    v.viewport = columns;
    return v;
}

// The window-pixel rectangle (x0, y0, x1, y1) around the shaded lights' images, one pixel wider each
// side; the whole frame when a corner is at or behind the camera plane. The final pass box-filters the
// emitters only inside it.
glm::vec4 emitterRect(const render::View& camera, const std::vector<Light>& lights, const std::vector<size_t>& shaded,
                      glm::ivec2 size) {
    const glm::vec4 frame(0.0f, 0.0f, static_cast<float>(size.x), static_cast<float>(size.y));
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    const glm::mat4 clipFromWorld = camera.clipFromWorld();
    for (size_t i : shaded)
        for (int c = 0; c < 4; ++c) {
            const glm::vec3 p = lights[i].position + ((c & 1) - 0.5f) * lights[i].edgeU + ((c >> 1) - 0.5f) * lights[i].edgeV;
            const glm::vec4 h = clipFromWorld * glm::vec4(p, 1.0f);
            if (!(h.w > 1e-6f)) return frame;
            const glm::vec2 px = (glm::vec2(h) / h.w * 0.5f + 0.5f) * glm::vec2(size);
            lo = glm::min(lo, px);
            hi = glm::max(hi, px);
        }
    return glm::vec4(lo - 1.0f, hi + 1.0f);
}

}  // namespace

// raySteps per device profile (an assumption: the thesis gives no count). 64 on a GPU: 32 leaked light
// past the Cornell short block's corner. 40 on llvmpipe, where the march is most of the frame on a large
// scene; measured against the reference at both counts (docs/techniques/area-light.md "Device profiles").
constexpr int kRayStepsLlvmpipe = 40;
constexpr int kRayStepsGpu = 64;

void AreaLightTechnique::visitSettings(SettingsVisitor& v) {
    v.field("vplsPerSide", m_vplsPerSide, "VPLs per side of each light's grid (thesis 16: 256 VPLs; 128: 16,384)", 1, 128);
    v.field("coarsest", m_coarsest, "coarsest level of the multiresolution buffer (thesis: incremental visibility starts at 64^2)", 1, 4096);
    v.field("depthThreshold", m_thresholds.depth, "max relative depth derivative per pixel before a cell is refined (assumption)", 0.0f, 1e9f);
    v.field("normalThreshold", m_thresholds.normal, "normal component range, 0..2, before a cell is refined (assumption)", 0.0f, 2.0f);
    v.field("visibility", m_visibility, "incremental: bitstream reuse (§5.3.3.2); brute: every VPL ray-marched at every cell (§5.3.3.1); none: V = 1 (§5.3.2); shadow-maps: a paraboloid shadow map per VPL (§5.4.6 baseline)", kVisibilityModes);
    v.field("shadowMapSize", m_shadowMapSize, "visibility=shadow-maps: texels per side of each VPL's map (thesis 64)", 8, 1024);
    v.field("interleave", m_interleave, "2x2 interleaved VPL subsets (§5.3.3.2)");
    v.field("incrementalStencil", m_incrementalStencil, "refine cells lit discontinuously, coarse to fine (§5.3.4); off: depth/normal/lobe criteria only");
    v.field("colourThreshold", m_colourThreshold, "illumination discontinuity: neighbourhood range of a white receiver's radiance, W/(m^2 sr), the display colour at 0 EV (Fig. 5.10: 0.005)", 0.0f, 1e9f);
    v.field("bitCountFraction", m_bitCountFraction, "refine where at least this fraction of the VPLs is partially visible in a 3x3 neighbourhood (thesis 128 of 256); above 1: off", 0.0f, 2.0f);
    v.field("voxelColumns", m_voxelColumns, "voxel grid x/y resolution (thesis 128^2 .. 1024^2)", 1, 4096);
    v.field("voxelBits", m_voxelBits, "voxel depth bits per column, a multiple of 128 (thesis 128)", 128, 1024);
    v.field("voxelOutside", m_voxelOutside, "a second grid along the lights holds what lies outside the camera's frustum, for the parts of rays there (deviation; off: the thesis's screen-space grid only, in which they are free)");
    v.field("voxelFootprint", m_voxelFootprint, "a fragment sets every depth slice its triangle spans in the pixel (deviation; off: the one slice at the pixel centre, the thesis)");
    v.field("raySteps", m_raySteps, "uniform samples per visibility ray (assumption: 64 on a GPU, 40 on llvmpipe)", 1, 256,
            PerProfile<int>{kRayStepsLlvmpipe, kRayStepsGpu});
    v.field("rayThickness", m_rayThickness, "extra depth bits tested each side of a step (the thick ray; assumption)", 0, 64);
    v.field("rayBias", m_rayBias, "ray origin offset along the normal, in voxels (assumption; Fig. 5.12)", 0.0f, 64.0f);
    v.field("specular", m_specular, "separate specular (Phong) gather pass (§5.3.2.1)");
    v.field("varianceVisibility", m_varianceVisibility, "sharp lobes: variance visibility queries (24 moments, 3x3 blur, Chebyshev; §5.3.3.3); off: a binary ray per lobe sample");
    v.field("lobeThreshold", m_lobeThreshold, "fraction of the lobe's peak that bounds the lobe (culling, refinement, footprint; assumption)", 1e-4f, 0.999f);
    v.field("lobeVpls", m_lobeVpls, "fewer VPLs than this in the lobe: 5x5 lobe-centred texture samples (thesis 9)", 0.0f, 1e9f);
    v.field("lobeSpacing", m_lobeSpacing, "refine while a cell's angular spread exceeds this times the lobe half-angle (assumption)", 1e-3f, 1e3f);
    v.field("interleaveNormal", m_interleaveNormal, "interleave reconstruction: min normal cosine of neighbours on the same surface (assumption)", -1.0f, 1.0f);
    v.field("interleaveDepth", m_interleaveDepth, "interleave reconstruction: max plane distance / eye distance (assumption)", 0.0f, 1e9f);
}

Expected<void> AreaLightTechnique::setup(const SetupContext& ctx) {
    m_lightIndices.clear();
    for (size_t i = 0; i < ctx.scene.lights.size(); ++i) {
        const Light& l = ctx.scene.lights[i];
        if (l.type != LightType::Area)
            return makeError("scene '{}': light '{}' is not an area light (area-light shades rectangular area lights only)",
                             ctx.scene.name, l.name);
        m_lightIndices.push_back(i);
    }
    if (m_lightIndices.empty()) return makeError("scene '{}': no area light (area-light needs one)", ctx.scene.name);
    BOUNCE_TRY_VOID(nichols::checkAtlasSize(ctx.size, fmt::format("output {}x{}", ctx.size.x, ctx.size.y),
                                            gl::Context::current()->info()));  // issue 29 #16
    if (m_lightIndices.size() > AL_MAX_LIGHTS)
        return makeError("scene '{}': {} area lights; area-light shades at most {}", ctx.scene.name, m_lightIndices.size(),
                         AL_MAX_LIGHTS);
    for (const Material& m : ctx.scene.materials)
        if (glm::any(glm::greaterThan(m.emission, glm::vec3(0.0f))))
            return makeError("scene '{}': material '{}' is emissive; area-light treats only area lights as lights",
                             ctx.scene.name, m.name);
    m_hasSpecularMaterials = std::any_of(ctx.scene.materials.begin(), ctx.scene.materials.end(), [](const Material& m) {
        return m.specularF0 > 0.0f || m.metallic > 0.0f;
    });
    const int vplsPerLight = m_vplsPerSide * m_vplsPerSide;
    m_vplCount = vplsPerLight * static_cast<int>(m_lightIndices.size());
    const int subsets = m_interleave ? 4 : 1;
    if (m_vplCount % subsets != 0)
        return makeError("setting interleave=on needs a VPL count divisible by 4 (vplsPerSide={} gives {})", m_vplsPerSide,
                         m_vplCount);
    m_perCell = m_vplCount / subsets;
    m_layers = (m_perCell + SV_BITS_PER_LAYER - 1) / SV_BITS_PER_LAYER;
    if (m_visibility == "incremental" && m_layers > kMaxBitstreamLayers)
        return makeError("setting visibility=incremental stores {} VPL bits per cell, more than {}; use fewer VPLs, "
                         "interleave=on or visibility=brute",
                         m_perCell, kMaxBitstreamLayers * SV_BITS_PER_LAYER);
    BOUNCE_TRY_VOID(voxels::checkGrid({glm::ivec2(m_voxelColumns), m_voxelBits}, "voxelColumns", "voxelBits"));
    if (m_visibility == "shadow-maps") {
        if (m_vplCount > kMaxVplShadowMaps)
            return makeError("setting visibility=shadow-maps renders one map per VPL, at most {} (the thesis's baseline); "
                             "{} VPLs: use vplsPerSide <= 32", kMaxVplShadowMaps, m_vplCount);
        for (size_t i : m_lightIndices)
            if (ctx.scene.lights[i].twoSided)
                return makeError("setting visibility=shadow-maps: light '{}' is two-sided; a paraboloid map covers one "
                                 "hemisphere", ctx.scene.lights[i].name);
        BOUNCE_TRY(m_vplMaps, paraboloid::ParaboloidMaps::create(
                                  {"areaLight.vplShadowMap", "areaLight.vplShadowMaps", "areaLight.vplShadowMap.fbo"},
                                  GL_DEPTH_COMPONENT32F, m_shadowMapSize, m_vplCount));
    }
    glm::vec3 lo, hi;
    ctx.scene.bounds(0.0f, lo, hi);
    m_sceneDiagonal = std::max(glm::length(hi - lo), 1e-3f);

    BOUNCE_TRY(m_pyramid, nichols::MinMaxPyramid::create());
    BOUNCE_TRY(m_diffuse, nichols::MultiresBuffer::create());
    BOUNCE_TRY(m_specularBuffer, nichols::MultiresBuffer::create());
    BOUNCE_TRY(m_voxels, voxels::ScreenVoxels::create());
    BOUNCE_TRY(m_outerVoxels, voxels::ScreenVoxels::create());
    const gpu::ScreenVoxelsGpu noGrid{};  // 0 bits: march.glsl's outer grid is empty (voxelOutside off)
    m_noOuterGrid = gl::Buffer::create("areaLight.noOuterGrid", sizeof(noGrid), &noGrid);
    BOUNCE_TRY(m_vplProgram, gl::Program::build({"areaLight.vpls", {{GL_COMPUTE_SHADER, "techniques/area_light/vpls.comp"}}}));
    BOUNCE_TRY(m_lobeProgram, gl::Program::build({"areaLight.lobePyramid", {{GL_COMPUTE_SHADER, "techniques/area_light/lobe_pyramid.comp"}}}));
    BOUNCE_TRY(m_classify, gl::Program::build({"areaLight.classify", {{GL_COMPUTE_SHADER, "techniques/area_light/classify.comp"}}}));
    BOUNCE_TRY(m_resolve, gl::Program::build({"areaLight.resolve", {{GL_COMPUTE_SHADER, "techniques/area_light/resolve.comp"}}}));
    BOUNCE_TRY(m_discontinuity, gl::Program::build({"areaLight.discontinuity", {{GL_COMPUTE_SHADER, "techniques/area_light/discontinuity.comp"}}}));
    BOUNCE_TRY(m_stencil, gl::Program::build(fullscreen("areaLight.stencil", "techniques/area_light/stencil.frag")));
    BOUNCE_TRY(m_gatherDiffuse, gl::Program::build(fullscreen("areaLight.gatherDiffuse", "techniques/area_light/gather_diffuse.frag")));
    BOUNCE_TRY(m_gatherSpecular, gl::Program::build(fullscreen("areaLight.gatherSpecular", "techniques/area_light/gather_specular.frag")));
    BOUNCE_TRY(m_final, gl::Program::build(fullscreen("areaLight.final", "techniques/area_light/final.frag")));
    BOUNCE_TRY(m_moments, gl::Program::build(fullscreen("areaLight.varianceMoments", "techniques/area_light/variance_moments.frag")));
    m_passUbo = gl::Buffer::create("areaLight.pass", sizeof(gpu::AreaPassUniforms));
    m_vpls = gl::Buffer::create("areaLight.vpls", sizeof(gpu::AreaVplGpu) * static_cast<size_t>(m_vplCount));
    m_stats = gl::Buffer::create("areaLight.stats", sizeof(uint32_t) * AL_STAT_COUNT);
    m_finalFbo = gl::Framebuffer::create("areaLight.final.fbo");
    m_clearFbo = gl::Framebuffer::create("areaLight.clear.fbo");
    m_size = ctx.size;
    return {};
}

void AreaLightTechnique::updateUniforms(FrameContext& ctx) {
    gpu::AreaPassUniforms& u = m_uniforms;
    u = {};
    const std::vector<Light>& lights = ctx.sceneGpu.lights();
    for (size_t k = 0; k < m_lightIndices.size(); ++k) {
        const Light& l = lights[m_lightIndices[k]];
        const gl::Texture& tex = ctx.lights.areaTexture(m_lightIndices[k]);
        gpu::AreaLightGpu& g = u.lights[k];
        g.centre = glm::vec4(l.position, l.twoSided ? 1.0f : 0.0f);
        g.edgeU = glm::vec4(l.edgeU, glm::length(l.edgeU));
        g.edgeV = glm::vec4(l.edgeV, glm::length(l.edgeV));
        g.normal = glm::vec4(l.areaNormal(), l.area());
        g.radiance = glm::vec4(l.radiance, l.texture.textured() ? 1.0f : 0.0f);
        g.texture = glm::vec4(tex.width(), tex.height(), static_cast<float>(k) * m_vplsPerSide * m_vplsPerSide, m_vplsPerSide);
    }
    const float visibility = m_visibility == "none"          ? AL_VIS_NONE
                             : m_visibility == "brute"       ? AL_VIS_BRUTE
                             : m_visibility == "shadow-maps" ? AL_VIS_SHADOW_MAPS
                                                             : AL_VIS_INCREMENTAL;
    u.counts = glm::vec4(static_cast<float>(m_lightIndices.size()), m_vplCount, m_perCell, m_interleave ? 4 : 1);
    // The bias in metres: rayBias voxels of the larger of a slice's depth and a column's width at the
    // middle of the grid's depth range.
    const gpu::ScreenVoxelsGpu& vg = m_voxels->uniforms();
    const float midDepth = 0.5f * (vg.depth.x + vg.depth.y);
    const float columnWidth = 2.0f * midDepth / (ctx.camera.clipFromView[1][1] * static_cast<float>(m_voxelColumns));
    const float voxel = std::max(vg.depth.w, columnWidth);
    u.march = glm::vec4(m_raySteps, m_rayThickness, m_rayBias * voxel, visibility);
    u.refine = glm::vec4(m_colourThreshold, m_bitCountFraction * static_cast<float>(m_vplCount),
                         m_incrementalStencil ? 1.0f : 0.0f, 0.0f);
    // The angle one camera pixel subtends (perspective: 2 tan(fov/2) / height, small-angle).
    const float pixelAngle = 2.0f / (ctx.camera.clipFromView[1][1] * static_cast<float>(m_size.y));
    u.lobe = glm::vec4(m_lobeThreshold, m_lobeVpls, m_lobeSpacing, pixelAngle);
    u.geometry = glm::vec4(m_interleaveNormal, m_interleaveDepth, 0.0f, m_layers);
    u.shadow = glm::vec4(kVplMapDepthBias, 0.0f, 0.0f, kVplMapFarInDiagonals * m_sceneDiagonal);
    m_passUbo.upload(0, sizeof(u), &u);
    m_passUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_PASS);
}

int AreaLightTechnique::vplsPerDraw() const {
    // A ray costs at most raySteps march iterations, each testing up to voxelBits / 32 words of a
    // column in the camera's grid and as many in the second grid, plus its VPL loop iteration: draws
    // of at most half the shader loop budget (gpu/ShaderLimits.h; the other half covers a specular
    // cell's 25 lobe samples and the region loops). With 64 steps and 128 bits, 56 VPLs a draw.
    const int wordsPerTest = m_voxelBits / 32;
    const int rayIterations = 1 + m_raySteps * (1 + 2 * wordsPerTest);
    return std::max(1, gl::shaderLoopIterationBudget() / 2 / rayIterations);
}

void AreaLightTechnique::bindVoxels() {
    m_voxels->bind();
    if (m_voxelOutside) {
        m_outerVoxels->bind(BINDING_UBO_VOXELS_OUTER, BINDING_TEX_VOXELS_OUTER);
    } else {
        m_noOuterGrid.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_VOXELS_OUTER);
        m_voxels->bitsTexture().bind(BINDING_TEX_VOXELS_OUTER);  // never read: a valid texture there
    }
}

void AreaLightTechnique::bindLightTextures(FrameContext& ctx) {
    // Light i's texture at unit i of these (the specular gather and the final pass read them by light).
    const unsigned units[AL_MAX_LIGHTS] = {BINDING_TEX_AREA_LIGHT, BINDING_TEX_INPUT0, BINDING_TEX_INPUT1, BINDING_TEX_INPUT2};
    for (size_t i = 0; i < AL_MAX_LIGHTS; ++i)
        ctx.lights.areaTexture(m_lightIndices[std::min(i, m_lightIndices.size() - 1)]).bind(units[i]);
}

void AreaLightTechnique::buildLobePyramid(FrameContext& ctx) {
    const int levels = m_pyramid->levels();
    if (!m_lobe || m_lobe.width() != m_size.x || m_lobe.height() != m_size.y || m_lobe.desc().levels != levels) {
        m_lobe = gl::Texture::create2DArray("areaLight.lobePyramid", m_size.x, m_size.y, 1, GL_RGBA32F, levels);
    }
    ctx.gbuffer.bind();
    for (int k = 0; k < levels; ++k) {
        const glm::ivec2 s = m_pyramid->levelSize(k);
        BOUNCE_CHECK(k > 0 || s == m_size, "eye pyramid level 0 is the frame size");
        if (k > 0) m_lobe.bindImage(BINDING_IMG0, GL_READ_ONLY, k - 1, true);
        m_lobe.bindImage(BINDING_IMG1, GL_WRITE_ONLY, k, true);
        m_lobeProgram.set("u_base", k == 0 ? 1 : 0);
        m_lobeProgram.set("u_size", s);
        m_lobeProgram.set("u_childSize", k > 0 ? m_pyramid->levelSize(k - 1) : s);
        m_lobeProgram.use();
        glDispatchCompute(groups(s.x), groups(s.y), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
}

void AreaLightTechnique::renderVplShadowMaps(FrameContext& ctx) {
    // The VPL positions of vpls.comp, on the CPU: the maps are drawn one per VPL.
    const std::vector<Light>& lights = ctx.sceneGpu.lights();
    const float offset = kVplMapOffsetInDiagonals * m_sceneDiagonal;
    m_vplMaps.begin(kVplMapFarInDiagonals * m_sceneDiagonal);
    const int n = m_vplsPerSide;
    for (size_t k = 0; k < m_lightIndices.size(); ++k) {
        const Light& l = lights[m_lightIndices[k]];
        const glm::vec3 normal = l.areaNormal(), t = glm::normalize(l.edgeU), b = glm::cross(normal, t);
        m_vplMaps.setFrame(paraboloid::vplFromWorld(t, b, normal));
        for (int i = 0; i < n * n; ++i) {
            const glm::vec2 uv = (glm::vec2(i % n, i / n) + 0.5f) / static_cast<float>(n);
            const glm::vec3 p = l.position + (uv.x - 0.5f) * l.edgeU + (uv.y - 0.5f) * l.edgeV;
            m_vplMaps.render(ctx.drawer, static_cast<int>(k) * n * n + i, p + normal * offset);
        }
    }
    m_vplMaps.end();
}

AreaLightTechnique::PassCounts AreaLightTechnique::renderMultires(FrameContext& ctx, nichols::MultiresBuffer& buffer,
                                                                  bool specular) {
    PassCounts counts;
    buffer.begin(*m_pyramid);
    const glm::ivec2 atlas = buffer.atlasSize();
    if (!m_flags || m_flags.width() != atlas.x || m_flags.height() != atlas.y) {
        m_flags = gl::Texture::create2D("areaLight.flags", atlas.x, atlas.y, GL_R32UI);
        m_flags.setFilter(GL_NEAREST, GL_NEAREST);
        m_subsets = gl::Texture::create2D("areaLight.subsets", atlas.x, atlas.y, GL_RGBA32F);
        m_subsets.setFilter(GL_NEAREST, GL_NEAREST);
        m_bits = gl::Texture::create2DArray("areaLight.bitstreams", atlas.x, atlas.y, m_layers, GL_RGBA32UI);
    }
    const GLuint zero = 0;
    glClearTexImage(m_flags.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    m_uniforms.geometry.z = specular ? 1.0f : 0.0f;
    m_passUbo.upload(0, sizeof(m_uniforms), &m_uniforms);
    m_passUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_PASS);

    const int levels = buffer.levels();
    const int coarsest = levels - 1;
    const bool incremental = m_visibility == "incremental" && !specular;
    const bool interleave = m_interleave && !specular;
    counts.rendered.assign(static_cast<size_t>(levels), -1);
    counts.tree.assign(static_cast<size_t>(levels), -1);
    gl::Program& gather = specular ? m_gatherSpecular : m_gatherDiffuse;
    if (m_visibility != "none") bindVoxels();
    m_vpls.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
    m_stats.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH1);

    for (int k = coarsest; k >= 0; --k) {
        const glm::ivec2 size = buffer.levelSize(k), origin = buffer.levelOrigin(k);
        const glm::ivec2 parentOrigin = k < coarsest ? buffer.levelOrigin(k + 1) : origin;
        const glm::ivec2 parentSize = k < coarsest ? buffer.levelSize(k + 1) : size;
        {
            auto s = ctx.timers.scope("stencil");
            m_pyramid->geometry().bind(BINDING_TEX_TECH0);
            m_pyramid->refine().bind(BINDING_TEX_TECH1);
            m_pyramid->normal().bind(BINDING_TEX_TECH2);
            (m_lobe ? m_lobe : m_pyramid->normal()).bind(BINDING_TEX_TECH3);
            m_pyramid->normalMin().bind(BINDING_TEX_INPUT0);
            m_pyramid->normalMax().bind(BINDING_TEX_INPUT1);
            m_flags.bindImage(BINDING_IMG0, GL_READ_WRITE);
            m_classify.set("u_level", k);
            m_classify.set("u_levelOrigin", origin);
            m_classify.set("u_parentOrigin", parentOrigin);
            m_classify.set("u_coarsest", coarsest);
            m_classify.set("u_specular", specular ? 1 : 0);
            m_classify.use();
            glDispatchCompute(groups(size.x), groups(size.y), 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
            m_flags.bind(BINDING_TEX_TECH0);
            m_stencil.set("u_ref", 1);
            buffer.stencilLevel(k, m_stencil, 1);
            if (incremental) {
                m_stencil.set("u_ref", 2);
                buffer.stencilLevel(k, m_stencil, 2);
            }
        }
        {
            auto s = ctx.timers.scope(specular ? "gather-specular" : "gather-diffuse");
            m_pyramid->geometry().bind(BINDING_TEX_TECH0);
            m_pyramid->normal().bind(BINDING_TEX_TECH1);
            if (specular) {
                m_lobe.bind(BINDING_TEX_TECH2);
                bindLightTextures(ctx);
                // One loop iteration per VPL plus up to raySteps march iterations for each: draws of at most
                // half the shader loop budget (gpu/ShaderLimits.h).
                const bool variance = m_varianceVisibility && m_visibility != "none";
                if (variance) {
                    // Three RGBA32F layers per light: six queries' (d, d^2) per cell (§5.3.3.3).
                    const int layers = 3 * static_cast<int>(m_lightIndices.size());
                    if (!m_momentsTexture || m_momentsTexture.width() != atlas.x || m_momentsTexture.height() != atlas.y) {
                        m_momentsTexture = gl::Texture::create2DArray("areaLight.varianceMoments", atlas.x, atlas.y, layers, GL_RGBA32F);
                    }
                    m_momentsTexture.bindImage(BINDING_IMG0, GL_READ_WRITE, 0, true);
                    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
                    buffer.drawLevel(k, m_moments, 1);
                    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
                    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
                }
                gather.set("u_variance", variance ? 1 : 0);
                gather.set("u_levelSize", size);
                const int perDraw = vplsPerDraw();
                const int batches = (m_vplCount + perDraw - 1) / perDraw;
                counts.rendered[static_cast<size_t>(k)] = buffer.drawLevel(k, gather, 1, batches, [&](int b) {
                    gather.set("u_vplFirst", static_cast<unsigned>(b * perDraw));
                    gather.set("u_vplEnd", static_cast<unsigned>((b + 1) * perDraw));
                });
            } else {
                m_flags.bind(BINDING_TEX_TECH2);
                m_bits.bindImage(BINDING_IMG0, GL_READ_WRITE, 0, true);
                if (m_vplMaps) m_vplMaps.maps().bind(BINDING_TEX_TECH3);
                gather.set("u_parentOrigin", parentOrigin);
                gather.set("u_parentSize", parentSize);
                gather.set("u_coarsest", coarsest);
                // Draws of at most vplsPerDraw() VPLs of one bitstream layer each (the shader loop budget):
                // a layer's later draws add their bits to the earlier ones' (the image barrier between).
                std::vector<glm::ivec3> draws;  // layer, first VPL, end VPL (of the cell's subset)
                const int perDraw = vplsPerDraw();
                for (int layer = 0; layer < m_layers; ++layer) {
                    const int end = std::min(m_perCell, (layer + 1) * SV_BITS_PER_LAYER);
                    for (int first = layer * SV_BITS_PER_LAYER; first < end; first += perDraw)
                        draws.emplace_back(layer, first, std::min(end, first + perDraw));
                }
                const auto setBatch = [&](int b) {
                    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
                    gather.set("u_batch", draws[static_cast<size_t>(b)].x);
                    gather.set("u_vplBegin", draws[static_cast<size_t>(b)].y);
                    gather.set("u_vplEnd", draws[static_cast<size_t>(b)].z);
                };
                const int batches = static_cast<int>(draws.size());
                gather.set("u_shade", 1);
                counts.rendered[static_cast<size_t>(k)] = buffer.drawLevel(k, gather, 1, batches, setBatch);
                if (incremental) {
                    gather.set("u_shade", 0);
                    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
                    counts.tree[static_cast<size_t>(k)] = buffer.drawLevel(k, gather, 2, batches, setBatch);
                    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
                }
                glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
            }
        }
        const bool bitCount = incremental && m_bitCountFraction <= 1.0f && m_incrementalStencil;
        if (interleave || bitCount) {
            auto s = ctx.timers.scope("interleave");
            glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
            if (interleave)
                glCopyImageSubData(buffer.atlas().id(), GL_TEXTURE_2D, 0, origin.x, origin.y, 0, m_subsets.id(), GL_TEXTURE_2D,
                                   0, origin.x, origin.y, 0, size.x, size.y, 1);
            m_subsets.bind(BINDING_TEX_TECH0);
            m_pyramid->geometry().bind(BINDING_TEX_TECH1);
            m_pyramid->normal().bind(BINDING_TEX_TECH2);
            buffer.atlas().bindImage(BINDING_IMG0, GL_WRITE_ONLY);
            m_flags.bindImage(BINDING_IMG1, GL_READ_WRITE);
            m_bits.bindImage(BINDING_IMG2, GL_READ_ONLY, 0, true);
            m_resolve.set("u_level", k);
            m_resolve.set("u_levelOrigin", origin);
            m_resolve.set("u_size", size);
            m_resolve.set("u_resolve", interleave ? 1 : 0);
            m_resolve.set("u_bitCount", bitCount ? 1 : 0);
            m_resolve.use();
            glDispatchCompute(groups(size.x), groups(size.y), 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
        {
            auto s = ctx.timers.scope("upsample");
            buffer.upsampleLevel(k, true);
        }
        if (m_incrementalStencil && k > 0) {
            auto s = ctx.timers.scope("discontinuity");
            m_passUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_PASS);
            buffer.result().bind(BINDING_TEX_TECH0);
            m_flags.bindImage(BINDING_IMG1, GL_READ_WRITE);
            m_discontinuity.set("u_level", k);
            m_discontinuity.set("u_levelOrigin", origin);
            m_discontinuity.set("u_size", size);
            // Display colours at bounce's default exposure (0 EV: 1 W/(m^2 sr) is about display white): the
            // specular buffer holds radiance / F, the diffuse one irradiance, E / pi for a white receiver.
            m_discontinuity.set("u_scale", specular ? 1.0f : 1.0f / glm::pi<float>());
            m_discontinuity.use();
            glDispatchCompute(groups(size.x), groups(size.y), 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
        m_passUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_PASS);
    }
    return counts;
}

void AreaLightTechnique::renderIndirect(FrameContext& ctx, const gl::Texture& indirect) {
    const float zero[4] = {0, 0, 0, 0};
    m_clearFbo.attach(GL_COLOR_ATTACHMENT0, indirect);
    glClearNamedFramebufferfv(m_clearFbo.id(), GL_COLOR, 0, zero);
    m_frameRan = false;
    m_stats.clearZero();
    if (m_visibility != "none") {
        auto s = ctx.timers.scope("voxelize");
        const voxels::GridSize grid{glm::ivec2(m_voxelColumns), m_voxelBits, m_voxelFootprint};
        if (m_voxelOutside)
            m_outerVoxels->build(ctx.drawer, outerGridView(ctx.sceneGpu, ctx.sceneGpu.lights(), m_lightIndices, grid.columns), grid);
        m_voxels->build(ctx.drawer, ctx.camera, grid);
    }
    updateUniforms(ctx);
    if (m_visibility == "shadow-maps") {
        auto s = ctx.timers.scope("vpl-shadow-maps");
        renderVplShadowMaps(ctx);
    }
    {
        auto s = ctx.timers.scope("vpls");
        m_vpls.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_TECH0);
        const int perLight = m_vplsPerSide * m_vplsPerSide;
        for (size_t k = 0; k < m_lightIndices.size(); ++k) {
            ctx.lights.areaTexture(m_lightIndices[k]).bind(BINDING_TEX_AREA_LIGHT);
            m_vplProgram.set("u_light", static_cast<int>(k));
            m_vplProgram.use();
            glDispatchCompute(static_cast<GLuint>((perLight + kVplLocalSize - 1) / kVplLocalSize), 1, 1);
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        auto s = ctx.timers.scope("min-max-mipmap");
        m_pyramid->buildEye(ctx.gbuffer, m_coarsest, m_thresholds);
    }
    const bool specular = m_specular && m_hasSpecularMaterials;
    if (specular) {
        auto s = ctx.timers.scope("lobe-mipmap");
        buildLobePyramid(ctx);
    }
    m_passUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_PASS);
    m_frameDiffuse = renderMultires(ctx, *m_diffuse, false);
    m_frameSpecular = specular ? renderMultires(ctx, *m_specularBuffer, true) : PassCounts{};
    m_frameRan = true;
    {
        auto s = ctx.timers.scope("final");
        m_finalFbo.attach(GL_COLOR_ATTACHMENT0, ctx.direct);
        m_finalFbo.setDrawBuffers(1);
        BOUNCE_CHECK(m_finalFbo.complete(), "area-light final framebuffer");
        m_finalFbo.bind();
        glViewport(0, 0, m_size.x, m_size.y);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_STENCIL_TEST);
        ctx.gbuffer.bind();
        m_passUbo.bindBase(GL_UNIFORM_BUFFER, BINDING_UBO_PASS);
        m_diffuse->result().bind(BINDING_TEX_TECH0);
        (specular ? m_specularBuffer->result() : m_diffuse->result()).bind(BINDING_TEX_TECH1);
        bindLightTextures(ctx);
        m_final.set("u_emitterRect", emitterRect(ctx.camera, ctx.sceneGpu.lights(), m_lightIndices, m_size));
        m_final.set("u_hasSpecular", specular ? 1 : 0);
        m_final.use();
        gl::Context::current()->bindEmptyVertexArray();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

}

void AreaLightTechnique::collectCounters(Counters& c) {
    if (!m_frameRan) return;
    uint32_t stats[AL_STAT_COUNT] = {};
    // The gathers wrote the counters as a storage buffer: the CPU read needs this bit (issue 29 #7).
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    m_stats.download(0, sizeof(stats), stats);
    c["vpls"] = m_vplCount;
    c["raysCast"] = stats[AL_STAT_RAYS_CAST];
    c["raysReused"] = stats[AL_STAT_RAYS_REUSED];
    c["raysCulled"] = stats[AL_STAT_RAYS_CULLED];
    c["lobeSampledCells"] = stats[AL_STAT_LOBE_SAMPLED];
    // Partially visible VPLs over the VPLs examined (those whose subset had two or more tree cells in
    // the region; every VPL of an interior cell), summed over the tree cells of every level.
    c["partiallyVisibleVpls"] = stats[AL_STAT_PARTIAL_VPLS];
    c["examinedVpls"] = stats[AL_STAT_EXAMINED_VPLS];
    c["partiallyVisibleFraction"] =
        stats[AL_STAT_EXAMINED_VPLS] > 0 ? double(stats[AL_STAT_PARTIAL_VPLS]) / double(stats[AL_STAT_EXAMINED_VPLS]) : 0.0;
    const auto count = [](const nichols::MultiresBuffer& b, int ticket) { return ticket < 0 ? 0.0 : b.fragments(ticket); };
    double diffuseTotal = 0.0, specularTotal = 0.0;
    for (size_t k = 0; k < m_frameDiffuse.rendered.size(); ++k) {
        const glm::ivec2 s = m_diffuse->levelSize(static_cast<int>(k));
        const double rendered = count(*m_diffuse, m_frameDiffuse.rendered[k]);
        c[fmt::format("fragments/level-{}", k)] = rendered;
        c[fmt::format("renderedFraction/level-{}", k)] = rendered / (double(s.x) * s.y);
        c[fmt::format("treeCells/level-{}", k)] = rendered + count(*m_diffuse, m_frameDiffuse.tree[k]);
        diffuseTotal += rendered;
    }
    for (size_t k = 0; k < m_frameSpecular.rendered.size(); ++k) {
        const double rendered = count(*m_specularBuffer, m_frameSpecular.rendered[k]);
        c[fmt::format("specularFragments/level-{}", k)] = rendered;
        specularTotal += rendered;
    }
    c["gatherFragments"] = diffuseTotal;
    c["specularFragments"] = specularTotal;
}

}  // namespace bounce
