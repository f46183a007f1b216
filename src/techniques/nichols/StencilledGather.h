#pragma once
// The eye-space half of isr and hisr (Nichols 2010 §4.2.1, Table 4.1's "Create Min-Max Mipmap",
// "Multires Stencil Setup", "Stenciled Gathering" and "Upsampling" rows): the min-max pyramid over the
// camera G-buffer, the flattened multiresolution buffer with its one-pass stencil set-up, the
// stencilled per-level draw of a technique's gather program, and the coarse-to-fine upsampling into
// the indirect target. The techniques differ only in what their gather program reads (a VPL cache or
// a VPL tree), which they bind before gather().
#include "techniques/nichols/MultiresBuffer.h"

#include <optional>

namespace bounce::nichols {

class StencilledGather {
public:
    static Expected<StencilledGather> create();

    // Timers "min-max-mipmap" and "stencil-setup": builds the eye pyramid down to eyeCoarsest and
    // marks each covered pixel at exactly one level of the buffer.
    // scale: the indirect-resolution cap's divisor of the output (indirectScale; 1 = full size).
    void prepare(FrameContext& ctx, int eyeCoarsest, const PyramidThresholds& thresholds, int scale = 1);
    // Draws `program` over the stencilled cells of every level, with the eye pyramid's geometry and
    // normal bound at BINDING_TEX_TECH0/1 (the patch each cell gathers for). The caller opens the
    // "gather" timer and binds its light data first. With batches > 1, as
    // MultiresBuffer::drawStencilled: setBatch(b) sets batch b's uniforms.
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
    std::vector<int> m_tickets;  // the last gather's fragment counts per level (MultiresBuffer::fragments)
};

}  // namespace bounce::nichols
