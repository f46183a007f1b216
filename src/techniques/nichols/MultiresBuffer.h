#pragma once
// The multiresolution illumination buffer of Nichols (2010) §3.2.4 and §4.2.1.1 (checklist items 5,
// 6, 11), flattened into one atlas so that a pass can touch every level: level 0 at the origin, the
// coarser levels in a column to its right (shaders/techniques/nichols/atlas.glsl). It owns the
// atlas colour (RGBA32F irradiance, alpha = rendered), its depth-stencil buffer, the one-pass
// stencil set-up, the coarse-to-fine empty-aware upsampling and the final combine.
#include "techniques/nichols/MinMaxPyramid.h"

#include <functional>
#include <string_view>

namespace bounce::nichols {

// How a cell that was not rendered at its level takes its value from the coarser levels (§3.2.5):
// EmptyAware is the thesis's (a tent-weighted 3x3 of the neighbours that have data); Nearest copies the
// parent cell (blocky); Bilinear interpolates the parent level at the cell centre with empty parents
// counted as black (the naive filter §3.2.5 rejects: light bleeds into and out of empty cells). The
// last two exist to show why the first is needed (settings `upsampling` of isr, hisr, multires-splat).
enum class UpsampleFilter { EmptyAware = 0, Nearest = 1, Bilinear = 2 };
inline constexpr std::string_view kUpsampleFilters[] = {"empty-aware", "nearest", "bilinear"};
inline constexpr const char* kUpsampleFilterHelp =
    "§3.2.5 reconstruction: empty-aware (thesis: tent-weighted 3x3 of the cells with data), nearest (parent "
    "cell, blocky) or bilinear (naive: empty cells count as black; the artefact §3.2.5 avoids)";
UpsampleFilter upsampleFilter(std::string_view name);

class MultiresBuffer {
public:
    static Expected<MultiresBuffer> create();

    // (Re)allocates for `pyramid`'s levels and clears the atlas (colour and stencil).
    void begin(const MinMaxPyramid& pyramid);
    // The same for explicit level sizes (level 0 first, each the floor half of the previous): tests fill
    // the atlas with synthetic data through atlas() and run upsample() on it.
    void begin(const std::vector<glm::ivec2>& levelSizes);
    // Marks each covered pixel's cell at exactly one level in the stencil (ref 1).
    void stencilSetup(const MinMaxPyramid& pyramid);
    // Draws `program` (full-screen-triangle vertex stage) over every level's rectangle with the stencil
    // test EQUAL 1; u_level and u_levelOrigin are set per level. Returns one fragment-count ticket per
    // level (see fragments()).
    // With batches > 1 each level is drawn `batches` times, setBatch(b) setting the program's uniforms
    // for batch b first; the batches' RGB add up (blending) and alpha stays the program's (the "rendered
    // here" flag) — how a long gather stays within the shader loop budget (gpu/ShaderLimits.h).
    std::vector<int> drawStencilled(gl::Program& program, int batches = 1,
                                    const std::function<void(int)>& setBatch = {});
    // Binds the atlas framebuffer with the whole atlas as viewport (for point splatting, no stencil).
    void bindAtlas();
    glm::ivec2 atlasSize() const { return m_atlasSize; }
    // Coarse-to-fine upsampling (§3.2.5) into result() level 0.
    void upsample(UpsampleFilter filter = UpsampleFilter::EmptyAware);

    // One level at a time, for techniques that build the stencil of level k from what levels > k
    // computed (Nichols 2010 §5.3.4, incremental stencil rendering), coarsest first:
    // stencilLevel writes `ref` into the stencil where `program` (full-screen-triangle vertex stage,
    // u_level and u_levelOrigin set) does not discard, colour writes off, over level k's rectangle.
    void stencilLevel(int level, gl::Program& program, int ref);
    // drawLevel draws `program` over level k where the stencil equals `ref`, `batches` times with
    // additive blending as drawStencilled does; returns a ticket for the fragments that passed the
    // stencil (counted once, over the first batch).
    int drawLevel(int level, gl::Program& program, int ref, int batches = 1,
                  const std::function<void(int)>& setBatch = {});
    // Splats `instances` instances of `program` (full-screen triangle, instance = the caller's VPL) over
    // level k where the stencil equals `ref`, added by blending (RGB summed, alpha the program's): the
    // stencilled splat of Nichols 2010 §4.2.1.1 (multires-splat splatPrimitive=stencil). No fragment count
    // (the caller knows its subsplats).
    void splatLevel(int level, gl::Program& program, int ref, int instances);
    // The fragments counted under a ticket of this frame (since begin()). Waits for the GPU: call it
    // after the frame's work is queued (Technique::collectCounters), not on the frame's path.
    double fragments(int ticket) const;
    // upsampleLevel computes result() level k from the atlas level k and result() level k + 1; after
    // it, result() level k holds every covered cell of level k that has data. replaceInherited: a cell
    // rendered at k takes its rendered value only (else rendered + inherited, see upsample.comp).
    void upsampleLevel(int level, bool replaceInherited = false, UpsampleFilter filter = UpsampleFilter::EmptyAware);
    const gl::Texture& depthStencil() const { return m_depthStencil; }
    // indirect = albedo / pi * result level 0, times Eq. 3.3's detail term when detailAlpha > 0. With
    // scale > 1 (the indirect-resolution cap, MinMaxPyramid::scale) level 0 is 1/scale of the output per
    // side and is upsampled to it by empty-aware bilinear interpolation (output_upsample.glsl).
    void combine(const render::GBuffer& gbuffer, const gl::Texture& indirect, float detailAlpha = 0.0f, int scale = 1);

    glm::ivec2 levelOrigin(int level) const { return m_origins[static_cast<size_t>(level)]; }
    glm::ivec2 levelSize(int level) const { return m_sizes[static_cast<size_t>(level)]; }
    int levels() const { return static_cast<int>(m_sizes.size()); }
    const gl::Texture& atlas() const { return m_atlas; }
    const gl::Texture& result() const { return m_result; }

private:
    void forEachLevel(gl::Program& program, const std::function<void(int)>& perLevel);

    gl::Program m_stencil, m_upsample, m_combine;
    gl::Texture m_atlas, m_depthStencil, m_result;
    gl::Framebuffer m_atlasFbo, m_combineFbo;
    std::vector<gl::Query> m_queries;  // GL_SAMPLES_PASSED, one per drawLevel call of the frame
    int m_queriesUsed = 0;
    std::vector<glm::ivec2> m_origins, m_sizes;
    glm::ivec2 m_atlasSize{0};
};

}  // namespace bounce::nichols
