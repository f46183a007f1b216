#pragma once
// Min-max mipmap pyramid (Nichols 2010 §3.2.2, checklist items 4 and 13), over the camera G-buffer
// (eye space: depth-derivative max-mipmap + per-component normal min-max, Fig. 4.2(c)) or over the
// RSM (light space, with summed flux and area for VPL clusters and the VPL tree of hisr). Levels
// halve (floor) down to the first level whose larger side is <= coarsestSize (16 in the thesis).
// Texel records: shaders/techniques/nichols/pyramid.glsl. The eye pyramid can also carry the optional
// curvature max-mipmap of §3.3.1 (Eq. 3.1), used as an extra refinement criterion.
#include "techniques/nichols/ReflectiveShadowMap.h"

#include <optional>
#include <vector>

namespace bounce::nichols {

struct PyramidThresholds {
    float depth = 0.1f;   // max relative depth derivative per base texel
    float normal = 0.3f;  // max - min of any normal component, range 0..2
    bool edgeNeighbours = false;
};

class MinMaxPyramid {
public:
    static Expected<MinMaxPyramid> create();

    // Eye space over the G-buffer (u_frame must be bound). With curvatureThreshold, also builds the
    // curvature max-mipmap (Eq. 3.1) and flags cells whose max curvature exceeds it (§3.3.1); without
    // it (isr, hisr, multires-splat's default) the curvature chain is neither built nor read.
    void buildEye(const render::GBuffer& gbuffer, int coarsestSize, const PyramidThresholds& t,
                  std::optional<float> curvatureThreshold = std::nullopt);
    // Light space over the RSM.
    void buildLight(const ReflectiveShadowMap& rsm, int coarsestSize, const PyramidThresholds& t);

    int levels() const { return m_levels; }  // base level 0 .. levels() - 1 (the coarsest)
    int layers() const { return m_layers; }
    glm::ivec2 levelSize(int level) const { return m_sizes[static_cast<size_t>(level)]; }
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
    void reduceAndFlag(const PyramidThresholds& t, bool flux, std::optional<float> curvatureThreshold);

    gl::Program m_baseEye, m_baseLight, m_reduce, m_flag;
    gl::Texture m_geometry, m_normal, m_normalMin, m_normalMax, m_flux, m_curvature, m_refine;
    std::vector<glm::ivec2> m_sizes;
    glm::ivec2 m_baseSize{0};
    int m_levels = 0, m_layers = 0, m_coarsest = 0;
    bool m_hasFlux = false;
};

}  // namespace bounce::nichols
