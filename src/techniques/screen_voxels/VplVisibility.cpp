// Optional VPL visibility of the RSM-family gathers: the settings declared once, the per-frame
// voxelization (timer "voxelize") and the ray counters. The test itself is
// shaders/techniques/screen_voxels/vpl_visibility.glsl; see VplVisibility.h and docs/techniques/rsm.md
// ("VPL visibility").
#include "techniques/screen_voxels/VplVisibility.h"

#include "gpu/Bindings.h"
#include "gpu/ShaderLimits.h"

#include <cstdint>

namespace bounce::voxels {

namespace {
constexpr int kBitsPerWord = 32;  // voxelBitsSet (march.glsl) tests one 32-bit word per iteration
}

void VplVisibilitySettings::visit(SettingsVisitor& v) {
    v.field("vplVisibility", enabled,
            "beyond the thesis: multiply each VPL's contribution by a voxel march from the receiver to the VPL in a "
            "screen-space voxelization of the view (Nichols 2010 §5.3.3); off = the thesis (no indirect visibility). "
            "Occluders outside the camera's frustum are not seen");
    v.field("voxelColumns", columns, "vplVisibility: voxel columns per side (thesis 128)", 1, 4096);
    v.field("voxelBits", bits, "vplVisibility: depth slices per column, a multiple of 128 (thesis 128)", 128, 1024);
    v.field("rayMarch", march,
            "vplVisibility: columns = visit every voxel column a receiver-VPL segment crosses (exact; bounce's); uniform = "
            "raySteps samples (the thesis's march; misses thin occluders seen at grazing angles)",
            kRayMarches);
    v.field("raySteps", steps, "vplVisibility, rayMarch=uniform: samples per receiver-VPL segment (assumption; the thesis gives none)", 1, 256);
    v.field("rayThickness", thickness, "vplVisibility: extra bits tested each side of a sample's slice range (thick ray, §5.3.3.1)", 0, 16);
    v.field("rayBias", bias,
            "vplVisibility: segment ends moved off their surfaces along the normals, in slice depths (a surface facing "
            "the camera needs rayThickness + 1)",
            0.0f, 100.0f);
}

Expected<VplVisibility> VplVisibility::create(const VplVisibilitySettings& settings) {
    VplVisibility v;
    v.m_settings = settings;
    if (!settings.enabled) return v;
    BOUNCE_TRY_VOID(checkGrid(GridSize{glm::ivec2(settings.columns), settings.bits}, "voxelColumns", "voxelBits"));
    // The gathers batch VPLs down to one per draw; one test must fit the shader loop budget by itself.
    if (v.loopIterationsPerTest() + 1 > gl::shaderLoopIterationBudget())
        return makeError("voxelColumns={} voxelBits={} rayMarch={} raySteps={}: one visibility test may take {} loop "
                         "iterations, past the shader loop budget of {}",
                         settings.columns, settings.bits, settings.march, settings.steps, v.loopIterationsPerTest(),
                         gl::shaderLoopIterationBudget());
    BOUNCE_TRY(v.m_voxels, ScreenVoxels::create());
    v.m_rays = gl::Buffer::create("vplVisibility.rays", 4 * sizeof(uint32_t));
    return v;
}

void VplVisibility::build(FrameContext& ctx) {
    if (!m_settings.enabled) return;
    auto s = ctx.timers.scope("voxelize");
    m_voxels->build(ctx.drawer, ctx.camera, GridSize{glm::ivec2(m_settings.columns), m_settings.bits});
    m_rays.clearZero();
}

std::vector<std::pair<std::string, std::string>> VplVisibility::defines() const {
    // vpl_visibility.glsl: 0 off, 1 column traversal (voxelTrace), 2 uniform samples (voxelMarch).
    const char* mode = !m_settings.enabled ? "0" : m_settings.march == "columns" ? "1" : "2";
    return {{"VPL_VISIBILITY", mode}};
}

void VplVisibility::setUniforms(gl::Program& program) const {
    if (!m_settings.enabled) return;
    m_voxels->bind();
    m_rays.bindBase(GL_SHADER_STORAGE_BUFFER, BINDING_SSBO_VOXEL_RAYS);
    program.set("u_raySteps", m_settings.steps);
    program.set("u_rayThickness", m_settings.thickness);
    program.set("u_rayBias", m_settings.bias);
}

int VplVisibility::loopIterationsPerTest() const {
    if (!m_settings.enabled) return 0;
    // llvmpipe counts loop iterations per SIMD vector of invocations (gallivm's loop limiter): a loop
    // runs as often as its busiest lane needs, and a loop reached with no lane active may still count
    // one iteration. So the bounds hold per vector: each column test (voxelBitsSet) loops over at most a
    // column's bits / 32 words, plus one.
    const int wordsPerColumn = m_settings.bits / kBitsPerWord + 1;
    // uniform: `steps` samples, one column test each.
    if (m_settings.march == "uniform") return m_settings.steps * (1 + wordsPerColumn) + 1;
    // columns: a segment clipped to the frustum crosses at most grid.x + grid.y - 1 columns, one test each.
    return 2 * m_settings.columns * (1 + wordsPerColumn) + 1;
}

void VplVisibility::collectCounters(Counters& out) const {
    if (!m_settings.enabled) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    uint32_t r[4] = {0, 0, 0, 0};
    m_rays.download(0, sizeof(r), r);
    out["visibilityRays"] = static_cast<double>((uint64_t{r[1]} << 32) | r[0]);
    out["visibilityBlocked"] = static_cast<double>((uint64_t{r[3]} << 32) | r[2]);
}

}  // namespace bounce::voxels
