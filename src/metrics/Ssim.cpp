#include "metrics/Ssim.h"

#include "core/Check.h"
#include "metrics/Filter.h"

namespace bounce {
namespace {

constexpr double kWindowSigma = 1.5;  // pixels (Wang et al. 2004, Sec. III-C)
constexpr int kWindowRadius = 5;      // 11x11 window
constexpr float kK1 = 0.01f;          // stabilises the luminance term
constexpr float kK2 = 0.03f;          // stabilises the contrast-structure term
constexpr float kDynamicRange = 1.0f; // display values span [0, 1]
constexpr float kC1 = (kK1 * kDynamicRange) * (kK1 * kDynamicRange);
constexpr float kC2 = (kK2 * kDynamicRange) * (kK2 * kDynamicRange);

}  // namespace

ErrorMap ssimMap(const Image& test, const Image& reference) {
    BOUNCE_CHECK(test.width() == reference.width() && test.height() == reference.height(),
                 "SSIM needs images of the same size (test {}x{}, reference {}x{})", test.width(), test.height(),
                 reference.width(), reference.height());
    const int w = reference.width(), h = reference.height();
    const std::vector<float> window = gaussianKernel(kWindowSigma, kWindowRadius);
    ErrorMap result(w, h);
    for (int c = 0; c < 3; ++c) {
        Plane x(w, h), y(w, h), xx(w, h), yy(w, h), xy(w, h);
        for (size_t i = 0; i < reference.pixelCount(); ++i) {
            const float a = test.data()[i][c], b = reference.data()[i][c];
            x.values[i] = a;
            y.values[i] = b;
            xx.values[i] = a * a;
            yy.values[i] = b * b;
            xy.values[i] = a * b;
        }
        const Plane muX = convolveSeparable(x, window, window), muY = convolveSeparable(y, window, window);
        const Plane exx = convolveSeparable(xx, window, window), eyy = convolveSeparable(yy, window, window);
        const Plane exy = convolveSeparable(xy, window, window);
        for (size_t i = 0; i < result.pixelCount(); ++i) {
            const float mx = muX.values[i], my = muY.values[i];
            const float varX = exx.values[i] - mx * mx, varY = eyy.values[i] - my * my;
            const float cov = exy.values[i] - mx * my;
            const float s = ((2.0f * mx * my + kC1) * (2.0f * cov + kC2)) /
                            ((mx * mx + my * my + kC1) * (varX + varY + kC2));
            result.values()[i] += s / 3.0f;
        }
    }
    return result;
}

double meanSsim(const Image& test, const Image& reference) {
    const ErrorMap map = ssimMap(test, reference);
    const int w = map.width(), h = map.height();
    const int windowSize = 2 * kWindowRadius + 1;
    if (w < windowSize || h < windowSize) return map.mean();
    double sum = 0.0;
    for (int y = kWindowRadius; y < h - kWindowRadius; ++y)
        for (int x = kWindowRadius; x < w - kWindowRadius; ++x) sum += map.at(x, y);
    return sum / (static_cast<double>(w - 2 * kWindowRadius) * (h - 2 * kWindowRadius));
}

}  // namespace bounce
