#include "metrics/Filter.h"

#include "core/Check.h"

#include <algorithm>
#include <cmath>

namespace bounce {

Plane convolveSeparable(const Plane& in, std::span<const float> kernelX, std::span<const float> kernelY) {
    BOUNCE_CHECK(kernelX.size() % 2 == 1 && kernelY.size() % 2 == 1, "kernels must have odd length ({}, {})",
                 kernelX.size(), kernelY.size());
    BOUNCE_CHECK(static_cast<size_t>(in.width) * in.height == in.values.size(), "plane size mismatch");
    const int w = in.width, h = in.height;
    const int rx = static_cast<int>(kernelX.size() / 2), ry = static_cast<int>(kernelY.size() / 2);
    if (w == 0 || h == 0) return in;

    // Horizontal pass into a row buffer padded by rx on both sides so the inner loop has no branches.
    Plane horizontal(w, h);
    std::vector<float> padded(static_cast<size_t>(w + 2 * rx));
    for (int y = 0; y < h; ++y) {
        const float* row = &in.values[static_cast<size_t>(y) * w];
        for (int i = 0; i < w + 2 * rx; ++i) padded[i] = row[std::clamp(i - rx, 0, w - 1)];
        // Tap-outer loops: each tap is a vectorisable multiply-add over the row (a per-pixel dot
        // product would not vectorise without reassociating float sums).
        float* out = &horizontal.values[static_cast<size_t>(y) * w];
        for (size_t k = 0; k < kernelX.size(); ++k) {
            const float weight = kernelX[k];
            const float* src = &padded[k];
            for (int x = 0; x < w; ++x) out[x] += weight * src[x];
        }
    }

    // Vertical pass: the same, whole rows at a time.
    Plane result(w, h);
    for (int y = 0; y < h; ++y) {
        float* out = &result.values[static_cast<size_t>(y) * w];
        for (size_t k = 0; k < kernelY.size(); ++k) {
            const int sy = std::clamp(y + static_cast<int>(k) - ry, 0, h - 1);
            const float weight = kernelY[k];
            const float* src = &horizontal.values[static_cast<size_t>(sy) * w];
            for (int x = 0; x < w; ++x) out[x] += weight * src[x];
        }
    }
    return result;
}

std::vector<float> gaussianKernel(double sigma, int radius) {
    BOUNCE_CHECK(sigma > 0.0 && radius >= 0, "bad Gaussian kernel (sigma {}, radius {})", sigma, radius);
    std::vector<float> kernel(static_cast<size_t>(2 * radius + 1));
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) sum += std::exp(-(i * i) / (2.0 * sigma * sigma));
    for (int i = -radius; i <= radius; ++i)
        kernel[static_cast<size_t>(i + radius)] = static_cast<float>(std::exp(-(i * i) / (2.0 * sigma * sigma)) / sum);
    return kernel;
}

}  // namespace bounce
