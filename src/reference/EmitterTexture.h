#pragma once
// A textured area light as the reference sees it at one instant: the texel multipliers of its
// emission texture (Scene.h AreaTexture, evaluated at the frame's time by areaTextureAt) and the
// piecewise-constant 2D distribution of its emitted luminance, for light sampling (pbrt-v3 13.6.7,
// "Piecewise-Constant 2D Distributions": the marginal over rows, then the conditional over the
// chosen row's columns, each inverted by binary search).
//
// The light emits radiance * texel at position + (u - 1/2) edgeU + (v - 1/2) edgeV; texel (column c,
// row r) covers u in [c/W, (c+1)/W) and v in (1 - (r+1)/H, 1 - r/H] (image row 0 is v = 1). Lookup is
// nearest (piecewise constant), so what a ray sees and what sample() draws have the same density:
// the pdf below is exact, and MIS weights are consistent.
#include "core/Image.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace bounce {

class EmitterTexture {
public:
    // `texture`: the multiplier image (non-negative, finite); `radiance`: the light's radiance, whose
    // product with each texel is what the distribution follows.
    EmitterTexture(const Image& texture, glm::vec3 radiance);

    int width() const noexcept { return m_width; }
    int height() const noexcept { return m_height; }

    // The texel covering (u, v) (clamped to the rectangle).
    size_t texelAt(glm::vec2 uv) const noexcept;
    glm::vec3 texel(size_t i) const noexcept { return m_texels[i]; }
    // Density of sample() over the unit square of (u, v) at texel i: W H lum_i / sum lum (1 for a
    // uniform texture), exactly the probability sample() gives the texel times W H. 0 for a texel
    // sample() never picks (black ones), and everywhere when the light is black.
    float pdf(size_t i) const noexcept { return m_pdf[i]; }

    struct Sample {
        glm::vec2 uv;  // on the rectangle
        size_t texel;  // the texel it falls in (returned, not looked up again, so it cannot round into a neighbour)
    };
    // Maps two uniform numbers in [0, 1) to a point distributed by the emitted luminance: u2 picks the
    // row, u1 the column, and each number's remainder within its bin places the point inside the texel
    // (so stratified numbers stay stratified). Only for a light that is not black.
    Sample sample(float u1, float u2) const noexcept;

    // Mean of lum(radiance * texel) over the texels: the light's power is pi * area * this (per side).
    float meanLuminance() const noexcept { return m_meanLuminance; }
    // True when no texel emits: the light has no power now and is never sampled.
    bool black() const noexcept { return !(m_meanLuminance > 0.0f); }

private:
    int m_width = 0, m_height = 0;
    std::vector<glm::vec3> m_texels;   // row-major, row 0 at v = 1
    std::vector<float> m_rowCdf;       // height + 1 values from 0 to 1
    std::vector<float> m_columnCdf;    // per row, width + 1 values from 0 to 1
    std::vector<float> m_pdf;          // per texel
    float m_meanLuminance = 0.0f;
};

}  // namespace bounce
