#pragma once
// Separable 2D convolution of scalar planes with clamp-to-edge borders (the border rule FLIP's
// reference implementation uses). Shared by FLIP and SSIM.
#include <span>
#include <vector>

namespace bounce {

// A row-major plane of floats; width * height values.
struct Plane {
    int width = 0;
    int height = 0;
    std::vector<float> values;

    Plane() = default;
    Plane(int w, int h, float fill = 0.0f) : width(w), height(h), values(static_cast<size_t>(w) * h, fill) {}
    float& at(int x, int y) { return values[static_cast<size_t>(y) * width + x]; }
    float at(int x, int y) const { return values[static_cast<size_t>(y) * width + x]; }
};

// out(x, y) = sum_{i,j} kernelX[i] * kernelY[j] * in(x + i - rx, y + j - ry), rx = kernelX.size() / 2,
// with coordinates clamped to the plane. Kernels have odd length and are applied as given
// (correlation, not flipped: all kernels used here are symmetric or antisymmetric about their centre,
// and FLIP only uses the magnitude of the antisymmetric responses).
Plane convolveSeparable(const Plane& in, std::span<const float> kernelX, std::span<const float> kernelY);

// Samples exp(-x^2 / (2 sigma^2)) at integer x in [-radius, radius], normalised to sum 1.
std::vector<float> gaussianKernel(double sigma, int radius);

}  // namespace bounce
