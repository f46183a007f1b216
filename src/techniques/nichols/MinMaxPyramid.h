#pragma once
// Min-max mipmap pyramid (Nichols 2010 §3.2.2, checklist items 4 and 13), over the camera G-buffer
// (eye space: depth-derivative max-mipmap + per-component normal min-max, Fig. 4.2(c)) or over the
// RSM (light space, with summed flux and area for VPL clusters and the VPL tree of hisr). Levels
// halve (floor) down to the first level whose larger side is <= coarsestSize (16 in the thesis).
// Texel records: shaders/techniques/nichols/pyramid.glsl. The eye pyramid can also carry the optional
// curvature max-mipmap of §3.3.1 (Eq. 3.1), used as an extra refinement criterion.
#include "gpu/GpuInfo.h"
#include "techniques/nichols/ReflectiveShadowMap.h"

#include <optional>
#include <vector>

namespace bounce::nichols {

struct PyramidThresholds {
    float depth = 0.1f;   // max relative depth derivative per base texel
    float normal = 0.3f;  // max - min of any normal component, range 0..2
    bool edgeNeighbours = false;
    // Eye pyramid only (§3.2.2.1): false = the depth-derivative max-mipmap (chs. 4, 5; bounce's default);
    // true = the conventional min-max mipmap of linear view depth, a cell discontinuous where
    // (max - min) / min of its depths exceeds `depth` (relative, so one threshold serves every distance).
    bool linearDepth = false;
};

// The indirect-resolution cap (thesis ch. 3 renders the indirect light at 128^2..1024^2 in a 1024^2
// window): setting `indirectSize` of multires-splat, isr and hisr. 0 = the output size; otherwise a
// power of two, and the eye pyramid's base is the output divided by the smallest power of two s that
// brings the output's larger side to at most indirectSize (ceil per axis), each base texel a point
// sample of the G-buffer at the centre of its s x s block.
inline constexpr const char* kIndirectSizeHelp =
    "indirect-light resolution cap (thesis ch. 3: 128..1024 in a 1024^2 window): 0 = output size; else a power of "
    "two <= the output's larger side; the output is divided by the smallest power of two that fits, the result "
    "upsampled to the output by empty-aware bilinear interpolation";
// Declares the settings `linearDepth` (t.linearDepth) and `indirectSize` of an eye pyramid's technique
// (multires-splat, isr, hisr): one declaration, one help text.
void visitEyeSettings(SettingsVisitor& v, PyramidThresholds& t, int& indirectSize);
// One-line error unless indirectSize is 0 or a power of two no larger than output's larger side.
Expected<void> checkIndirectSize(int indirectSize, glm::ivec2 output);
// The power-of-two divisor s of the output for indirectSize (1 for 0 or a cap the output already fits).
int indirectScale(int indirectSize, glm::ivec2 output);
// One-line error when the multiresolution atlas (nichols/MultiresBuffer: the base level beside a column of
// the coarser ones, 1.5x the base width) of an indirect base of `base` texels passes `info`'s
// GL_MAX_TEXTURE_SIZE (issue 29 #16: outputs past about 10,900 pixels on a 16,384 GL). checkIndirectSize
// runs it on the current context; techniques without indirectSize (area-light) call it themselves.
Expected<void> checkAtlasSize(glm::ivec2 base, const std::string& settings, const gl::GpuInfo& info);

class MinMaxPyramid {
public:
    // Image units the pyramid's compute passes bind (pyramid_flag.comp: units 0..6; pyramid_reduce.comp
    // writes 5 and reads level k-1 through samplers), within GL 4.5's and NVIDIA's 8 (issue 29 #1).
    static constexpr int kImageUniforms = 7;
    // Texture units up to BINDING_TEX_PYRAMID4 (36) + 1; GL 4.5 guarantees 80.
    static constexpr int kTextureUnits = 37;
    // One-line error when `info` has fewer compute image uniforms / image units / texture units than that.
    static Expected<void> checkLimits(const gl::GpuInfo& info);
    static Expected<MinMaxPyramid> create();

    // Eye space over the G-buffer (u_frame must be bound). With curvatureThreshold, also builds the
    // curvature max-mipmap (Eq. 3.1) and flags cells whose max curvature exceeds it (§3.3.1); without
    // it (isr, hisr, multires-splat's default) the curvature chain is neither built nor read.
    // scale (indirectScale): the base level is ceil(G-buffer size / scale), one point sample per block.
    void buildEye(const render::GBuffer& gbuffer, int coarsestSize, const PyramidThresholds& t,
                  std::optional<float> curvatureThreshold = std::nullopt, int scale = 1);
    // Light space over the RSM.
    void buildLight(const ReflectiveShadowMap& rsm, int coarsestSize, const PyramidThresholds& t);

    int levels() const { return m_levels; }  // base level 0 .. levels() - 1 (the coarsest)
    int layers() const { return m_layers; }
    int scale() const { return m_scale; }  // eye pyramid: G-buffer pixels per base texel side (1 = full size)
    glm::ivec2 levelSize(int level) const { return m_sizes[static_cast<size_t>(level)]; }
    // Every level's size, padded with zeros to `count` entries: a shader's `uniform ivec2 name[count]`.
    // Shaders whose level differs between invocations read sizes from it: textureSize with such a level
    // returns the first SIMD lane's size on llvmpipe.
    std::vector<glm::ivec2> levelSizes(int count) const;
    // GL_TEXTURE_2D_ARRAY mip chains (nearest sampling); see pyramid.glsl.
    const gl::Texture& geometry() const { return m_geometry; }
    const gl::Texture& normal() const { return m_normal; }
    const gl::Texture& normalMin() const { return m_normalMin; }
    const gl::Texture& normalMax() const { return m_normalMax; }
    const gl::Texture& flux() const { return m_flux; }
    const gl::Texture& refine() const { return m_refine; }
    // Eye pyramid only, valid after a buildEye with a curvature threshold: r = max over the cell's base
    // texels of Eq. 3.1's kappa = 2 sin(arccos(N1.N2) / 2) to any 4-neighbour (0..2); RGBA32F, gba 0.
    const gl::Texture& curvature() const { return m_curvature; }

private:
    void allocate(glm::ivec2 size, int layers, int coarsestSize, bool flux);
    void reduceAndFlag(const PyramidThresholds& t, bool flux, std::optional<float> curvatureThreshold, bool linearDepth);

    gl::Program m_baseEye, m_baseLight, m_reduce, m_flag;
    gl::Texture m_geometry, m_normal, m_normalMin, m_normalMax, m_flux, m_curvature, m_refine;
    std::vector<glm::ivec2> m_sizes;
    glm::ivec2 m_baseSize{0};
    int m_levels = 0, m_layers = 0, m_coarsest = 0, m_scale = 1;
    bool m_hasFlux = false;
};

}  // namespace bounce::nichols
