#pragma once
// The eye-space half of isr and hisr (Nichols 2010 §4.2.1, Table 4.1's "Create Min-Max Mipmap",
// "Multires Stencil Setup", "Stenciled Gathering" and "Upsampling" rows): the min-max pyramid over the
// camera G-buffer, the flattened multiresolution buffer with its one-pass stencil set-up, the
// stencilled per-level draw of a technique's gather program, and the coarse-to-fine upsampling into
// the indirect target. The techniques differ only in what their gather program reads (a VPL cache or
// a VPL tree), which they bind before gather().
#include "core/DeviceProfile.h"
#include "gpu/ListDispatch.h"
#include "techniques/nichols/MultiresBuffer.h"

#include <optional>

namespace bounce::nichols {

// How the gathering cells are found and shaded (setting `gatherPass` of isr and hisr): Stencil is the
// thesis's (§4.2.1.1: mark the cells in the stencil, draw each level's rectangle with early stencil
// culling); Compute lists the same cells (cell_list.comp) and gathers them in a compute dispatch over
// the list (cell_gather.glsl): same cells, same sums, no SIMD lanes lost to the stencil's sparse 4x4
// blocks on a CPU rasteriser.
enum class GatherPass { Stencil = 0, Compute = 1 };
inline constexpr std::string_view kGatherPasses[] = {"stencil", "compute"};
inline constexpr const char* kGatherPassHelp =
    "stencil: the thesis's stencil set-up and stencilled draws (§4.2.1.1); compute: the same cells listed and "
    "gathered by a compute dispatch over the list (faster on llvmpipe, same image; the llvmpipe profile's default)";
// The default per device profile (issue 29 #20): compute on llvmpipe (its speed is the only reason for
// it), the thesis's stencil on a GPU. A technique's member starts at the llvmpipe value.
inline constexpr PerProfile<std::string_view> kGatherPassDefaults{"compute", "stencil"};
GatherPass gatherPass(std::string_view name);

class StencilledGather {
public:
    static Expected<StencilledGather> create();
    // Columns of the compute gather's 2D group grid: GL_MAX_COMPUTE_WORK_GROUP_COUNT[0], or less when a
    // test sets s_maxGroupsXForTests (> 0) to see the grid wrap at llvmpipe's sizes (issue 29 #5).
    static int maxGroupsX();
    static int s_maxGroupsXForTests;
    // gatherPass=compute: the last frame's indirect dispatch size (common/list_args.comp's output), read back; tests.
    const gl::Buffer& dispatchArgs() const { return m_dispatch; }

    // Timers "min-max-mipmap" and "stencil-setup": builds the eye pyramid down to eyeCoarsest and
    // marks each covered pixel at exactly one level of the buffer.
    // scale: the indirect-resolution cap's divisor of the output (indirectScale; 1 = full size).
    // With GatherPass::Compute, "stencil-setup" builds the cell list instead of the stencil.
    void prepare(FrameContext& ctx, int eyeCoarsest, const PyramidThresholds& thresholds, int scale = 1,
                 GatherPass pass = GatherPass::Stencil);
    // Draws `program` over the stencilled cells of every level, with the eye pyramid's geometry and
    // normal bound at BINDING_TEX_TECH0/1 (the patch each cell gathers for). The caller opens the
    // "gather" timer and binds its light data first. With batches > 1, as
    // MultiresBuffer::drawStencilled: setBatch(b) sets batch b's uniforms.
    // With GatherPass::Compute, `program` is the technique's compute gather (cell_gather.glsl's main), one
    // indirect dispatch per batch.
    void gather(gl::Program& program, int batches = 1, const std::function<void(int)>& setBatch = {});
    // Timer "upsample": coarse-to-fine upsampling and indirect = albedo / pi * irradiance (upsampled to the
    // output size when prepare's scale > 1).
    void finish(FrameContext& ctx, const gl::Texture& indirect, UpsampleFilter filter = UpsampleFilter::EmptyAware);
    // After the frame is queued (Technique::collectCounters): the counters "fragments/level-k" and
    // "gatherFragments" of the last gather(); returns gatherFragments (0 when nothing was gathered).
    double collectCounters(Counters& out) const;
    // Writes zero indirect light (a scene without lights).
    void clear(const gl::Texture& indirect);

    const MinMaxPyramid& eye() const { return *m_eye; }
    const MultiresBuffer& buffer() const { return *m_buffer; }

private:
    std::optional<MinMaxPyramid> m_eye;
    std::optional<MultiresBuffer> m_buffer;
    gl::Framebuffer m_clearFbo;
    gl::Program m_cellList;  // GatherPass::Compute: the list
    gl::ListDispatch m_cellArgs;  // and its dispatch size
    gl::Buffer m_cells, m_dispatch;
    GatherPass m_pass = GatherPass::Stencil;
    int m_levels = 0;  // levels of the last prepare()
    std::vector<int> m_tickets;  // the last gather's fragment counts per level (MultiresBuffer::fragments)
};

}  // namespace bounce::nichols
