#include "reference/EmitterTexture.h"

#include "core/Check.h"

#include <algorithm>

namespace bounce {

namespace {

// Cumulative sums of `weights`, normalised to end at exactly 1 (all zeros when the sum is 0). Summed in
// double so that a 2048-texel row keeps the small texels' share.
void buildCdf(const double* weights, size_t n, float* cdf) {
    double total = 0.0;
    for (size_t i = 0; i < n; ++i) total += weights[i];
    cdf[0] = 0.0f;
    double running = 0.0;
    for (size_t i = 0; i < n; ++i) {
        running += weights[i];
        cdf[i + 1] = total > 0.0 ? static_cast<float>(running / total) : 0.0f;
    }
    if (total > 0.0) cdf[n] = 1.0f;
}

// The bin i of `cdf` (n bins) with cdf[i] <= u < cdf[i + 1]; bins of zero width are never returned.
size_t findBin(const float* cdf, size_t n, float u) {
    const float* it = std::upper_bound(cdf, cdf + n + 1, u);
    const size_t bin = static_cast<size_t>(it - cdf);
    return std::min(bin == 0 ? 0 : bin - 1, n - 1);
}

}  // namespace

EmitterTexture::EmitterTexture(const Image& texture, glm::vec3 radiance)
    : m_width(texture.width()), m_height(texture.height()), m_texels(texture.pixels()) {
    BOUNCE_CHECK(m_width > 0 && m_height > 0, "an emitter texture has texels");
    const auto w = static_cast<size_t>(m_width), h = static_cast<size_t>(m_height);
    std::vector<double> lum(w * h), rowSum(h, 0.0);
    double total = 0.0;
    for (size_t r = 0; r < h; ++r)
        for (size_t c = 0; c < w; ++c) {
            const double l = std::max(0.0f, luminance(radiance * m_texels[r * w + c]));
            lum[r * w + c] = l;
            rowSum[r] += l;
        }
    for (double s : rowSum) total += s;
    m_meanLuminance = static_cast<float>(total / static_cast<double>(w * h));
    m_rowCdf.resize(h + 1);
    buildCdf(rowSum.data(), h, m_rowCdf.data());
    m_columnCdf.resize(h * (w + 1));
    for (size_t r = 0; r < h; ++r) buildCdf(lum.data() + r * w, w, m_columnCdf.data() + r * (w + 1));
    // The pdf is the product of the float bins' widths sample() inverts, not the double weights: then it
    // is exactly the density sample() draws, even for a texel whose share rounds away.
    m_pdf.resize(w * h);
    for (size_t r = 0; r < h; ++r) {
        const float rowP = m_rowCdf[r + 1] - m_rowCdf[r];
        const float* col = m_columnCdf.data() + r * (w + 1);
        for (size_t c = 0; c < w; ++c)
            m_pdf[r * w + c] = rowP * (col[c + 1] - col[c]) * static_cast<float>(w * h);
    }
}

size_t EmitterTexture::texelAt(glm::vec2 uv) const noexcept {
    const int c = std::clamp(static_cast<int>(uv.x * static_cast<float>(m_width)), 0, m_width - 1);
    const int r = std::clamp(static_cast<int>((1.0f - uv.y) * static_cast<float>(m_height)), 0, m_height - 1);
    return static_cast<size_t>(r) * static_cast<size_t>(m_width) + static_cast<size_t>(c);
}

EmitterTexture::Sample EmitterTexture::sample(float u1, float u2) const noexcept {
    const auto w = static_cast<size_t>(m_width), h = static_cast<size_t>(m_height);
    const size_t r = findBin(m_rowCdf.data(), h, u2);
    const float* col = m_columnCdf.data() + r * (w + 1);
    const size_t c = findBin(col, w, u1);
    // The remainders within the chosen bins, in [0, 1): where in the texel the point lies.
    const float fr = std::clamp((u2 - m_rowCdf[r]) / (m_rowCdf[r + 1] - m_rowCdf[r]), 0.0f, 1.0f);
    const float fc = std::clamp((u1 - col[c]) / (col[c + 1] - col[c]), 0.0f, 1.0f);
    Sample s;
    s.uv = {(static_cast<float>(c) + fc) / static_cast<float>(w), 1.0f - (static_cast<float>(r) + fr) / static_cast<float>(h)};
    s.texel = r * w + c;
    return s;
}

}  // namespace bounce
