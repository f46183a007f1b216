#include "metrics/ErrorMetrics.h"

#include "core/Check.h"
#include "core/ImageIo.h"
#include "metrics/Ssim.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce {
namespace {

void checkSameSize(const Image& test, const Image& reference) {
    BOUNCE_CHECK(test.width() == reference.width() && test.height() == reference.height(),
                 "images differ in size (test {}x{}, reference {}x{})", test.width(), test.height(), reference.width(),
                 reference.height());
}

template <class PerChannel>
ErrorMap channelMeanMap(const Image& test, const Image& reference, PerChannel perChannel) {
    checkSameSize(test, reference);
    ErrorMap map(reference.width(), reference.height());
    for (size_t i = 0; i < reference.pixelCount(); ++i) {
        const glm::vec3 x = test.data()[i], r = reference.data()[i];
        double sum = 0.0;
        for (int c = 0; c < 3; ++c) sum += perChannel(static_cast<double>(x[c]), static_cast<double>(r[c]));
        // Errors of finite float inputs are finite in double but can pass float's range (|x - r| of
        // 3e38 and -3e38): the map saturates at the largest float, so it stays finite and a heat map's
        // colour bar (CompareCommand.cpp: up to a percentile) has a finite top.
        map.values()[i] = static_cast<float>(std::min(sum / 3.0, static_cast<double>(std::numeric_limits<float>::max())));
    }
    return map;
}

// Linear display values: the sRGB encoding undone, so FLIP sees the same pixels the display shows.
Image decodeDisplay(const Image& display) {
    Image out(display.width(), display.height());
    for (size_t i = 0; i < display.pixelCount(); ++i) {
        const glm::vec3 d = display.data()[i];
        out.data()[i] = {srgbDecode(d.r), srgbDecode(d.g), srgbDecode(d.b)};
    }
    return out;
}

// Mean over pixels and channels, accumulated per channel in double so big images lose no precision.
template <class PerChannel>
double channelMean(const Image& test, const Image& reference, PerChannel perChannel) {
    double sum = 0.0;
    for (size_t i = 0; i < reference.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c)
            sum += perChannel(static_cast<double>(test.data()[i][c]), static_cast<double>(reference.data()[i][c]));
    return sum / (3.0 * static_cast<double>(reference.pixelCount()));
}

double squared(double x, double r) { return (x - r) * (x - r); }

}  // namespace

ErrorMap absoluteErrorMap(const Image& test, const Image& reference) {
    return channelMeanMap(test, reference, [](double x, double r) { return std::abs(x - r); });
}

ErrorMap squaredErrorMap(const Image& test, const Image& reference) {
    return channelMeanMap(test, reference, squared);
}

ErrorMap relativeSquaredErrorMap(const Image& test, const Image& reference, double epsilon) {
    return channelMeanMap(test, reference, [epsilon](double x, double r) { return squared(x, r) / (r * r + epsilon); });
}

double relativeRmsError(const Image& test, const Image& reference) {
    checkSameSize(test, reference);
    const double meanSquaredError = channelMean(test, reference, squared);
    const double meanSquare = channelMean(test, reference, [](double, double r) { return r * r; });
    if (meanSquare > 0.0) return std::sqrt(meanSquaredError / meanSquare);
    return meanSquaredError > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

double psnr(const Image& testDisplay, const Image& referenceDisplay) {
    checkSameSize(testDisplay, referenceDisplay);
    const double mse = channelMean(testDisplay, referenceDisplay, squared);
    if (mse == 0.0) return std::numeric_limits<double>::infinity();
    constexpr double kPeak = 1.0;  // display values span [0, 1]
    return 10.0 * std::log10(kPeak * kPeak / mse);
}

double rmsSum8Bit(const Image& testDisplay, const Image& referenceDisplay) {
    checkSameSize(testDisplay, referenceDisplay);
    auto q = [](float v) { return std::round(255.0 * std::clamp(static_cast<double>(v), 0.0, 1.0)); };
    double sum[3] = {0.0, 0.0, 0.0};
    for (size_t i = 0; i < testDisplay.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = q(testDisplay.data()[i][c]) - q(referenceDisplay.data()[i][c]);
            sum[c] += d * d;
        }
    const double n = static_cast<double>(testDisplay.pixelCount());
    return std::sqrt(sum[0] / n) + std::sqrt(sum[1] / n) + std::sqrt(sum[2] / n);
}

Expected<ErrorMetrics> compareImages(const Image& test, const Image& reference, const CompareOptions& options,
                                     CompareMaps* maps) {
    if (test.width() != reference.width() || test.height() != reference.height())
        return makeError("images differ in size: test is {}x{}, reference is {}x{}", test.width(), test.height(),
                         reference.width(), reference.height());
    if (reference.empty()) return makeError("images are empty");
    BOUNCE_TRY_VOID(checkFinite(test, "test image"));
    BOUNCE_TRY_VOID(checkFinite(reference, "reference image"));
    if (!(options.pixelsPerDegree > 0.0) || !std::isfinite(options.pixelsPerDegree))
        return makeError("pixels per degree must be positive, got {}", options.pixelsPerDegree);

    ErrorMetrics m;
    m.mse = channelMean(test, reference, squared);
    m.rmse = std::sqrt(m.mse);
    m.relMse = channelMean(test, reference,
                           [](double x, double r) { return squared(x, r) / (r * r + kRelMseEpsilon); });
    m.mae = channelMean(test, reference, [](double x, double r) { return std::abs(x - r); });
    m.relRms = relativeRmsError(test, reference);
    m.testMean = channelMean(test, test, [](double x, double) { return x; });
    m.referenceMean = channelMean(reference, reference, [](double x, double) { return x; });
    m.energy = m.referenceMean > 0.0 ? m.testMean / m.referenceMean
                                     : (m.testMean == 0.0 ? 1.0 : std::numeric_limits<double>::infinity());

    const Image testDisplay = toDisplay(test, options.testToneMap);
    const Image referenceDisplay = toDisplay(reference, options.referenceToneMap);
    m.psnr = psnr(testDisplay, referenceDisplay);
    {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const glm::vec3& v : referenceDisplay.pixels())
            for (int c = 0; c < 3; ++c) {
                lo = std::min(lo, double(v[c]));
                hi = std::max(hi, double(v[c]));
            }
        const double rmse = std::sqrt(channelMean(testDisplay, referenceDisplay, squared));
        m.nrmse = hi > lo ? rmse / (hi - lo) : (rmse > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
    }
    m.rmsSum8 = rmsSum8Bit(testDisplay, referenceDisplay);
    m.ssim = meanSsim(testDisplay, referenceDisplay);

    ErrorMap flipLdr = ldrFlip(decodeDisplay(testDisplay), decodeDisplay(referenceDisplay), options.pixelsPerDegree);
    m.hdrFlipExposures = hdrFlipExposures(reference);
    ErrorMap flipHdr = hdrFlip(test, reference, m.hdrFlipExposures, options.pixelsPerDegree);
    m.flipLdr = flipLdr.mean();
    m.flipHdr = flipHdr.mean();
    if (maps) {
        maps->flipLdr = std::move(flipLdr);
        maps->flipHdr = std::move(flipHdr);
    }
    return m;
}

nlohmann::json toJson(const ErrorMetrics& m) {
    nlohmann::json j;
    j["mse"] = m.mse;
    j["rmse"] = m.rmse;
    if (std::isfinite(m.nrmse)) j["nrmse"] = m.nrmse;
    else j["nrmse"] = nullptr;
    j["relMse"] = m.relMse;
    j["relRms"] = std::isfinite(m.relRms) ? nlohmann::json(m.relRms) : nlohmann::json(nullptr);
    j["mae"] = m.mae;
    j["psnr"] = std::isfinite(m.psnr) ? nlohmann::json(m.psnr) : nlohmann::json(nullptr);
    j["rmsSum8"] = m.rmsSum8;
    j["ssim"] = m.ssim;
    j["flipLdr"] = m.flipLdr;
    j["flipHdr"] = m.flipHdr;
    j["testMean"] = m.testMean;
    j["referenceMean"] = m.referenceMean;
    j["energy"] = std::isfinite(m.energy) ? nlohmann::json(m.energy) : nlohmann::json(nullptr);
    j["hdrFlipExposures"] = {{"startEv", m.hdrFlipExposures.startEv},
                             {"stopEv", m.hdrFlipExposures.stopEv},
                             {"count", m.hdrFlipExposures.count}};
    return j;
}

}  // namespace bounce
