#include "metrics/NoiseFloor.h"

#include "core/ImageIo.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <numbers>

namespace bounce {
namespace {

// sqrt(2/pi): E|z| of a standard normal z, the expected absolute deviation per unit of sigma.
const double kMeanAbsNormal = std::sqrt(2.0 / std::numbers::pi);

// splitmix64 (Steele, Lea and Flood 2014): a counter-based stream, the same on every platform and
// standard library (std::normal_distribution is not), so a floor is reproducible anywhere.
uint64_t splitmix64(uint64_t& state) {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// A uniform in (0, 1]: 53 random bits, never 0 (Box-Muller takes its logarithm).
double uniform(uint64_t& state) { return (static_cast<double>(splitmix64(state) >> 11) + 1.0) * 0x1.0p-53; }

// The metrics that have a floor, in toJson's key order.
constexpr std::string_view kFloorMetrics[] = {"mse",  "rmse",    "nrmse", "relMse",  "relRms", "mae",
                                              "psnr", "rmsSum8", "ssim",  "flipLdr", "flipHdr", "energy"};

double field(const ErrorMetrics& m, std::string_view name) {
    if (name == "mse") return m.mse;
    if (name == "rmse") return m.rmse;
    if (name == "nrmse") return m.nrmse;
    if (name == "relMse") return m.relMse;
    if (name == "relRms") return m.relRms;
    if (name == "mae") return m.mae;
    if (name == "psnr") return m.psnr;
    if (name == "rmsSum8") return m.rmsSum8;
    if (name == "ssim") return m.ssim;
    if (name == "flipLdr") return m.flipLdr;
    if (name == "flipHdr") return m.flipHdr;
    if (name == "energy") return m.energy;
    return std::numeric_limits<double>::quiet_NaN();
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

Expected<ErrorMetrics> linearNoiseFloor(const Image& reference, const Image& variance) {
    if (variance.width() != reference.width() || variance.height() != reference.height())
        return makeError("the variance image is {}x{}, its reference {}x{}", variance.width(), variance.height(),
                         reference.width(), reference.height());
    if (reference.empty()) return makeError("the reference is empty");
    BOUNCE_TRY_VOID(checkFinite(reference, "reference image"));
    BOUNCE_TRY_VOID(checkFinite(variance, "variance image"));
    for (const glm::vec3& v : variance.pixels())
        if (v.r < 0.0f || v.g < 0.0f || v.b < 0.0f) return makeError("the variance image has a negative value");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    ErrorMetrics floor;
    floor.nrmse = floor.psnr = floor.rmsSum8 = floor.ssim = floor.flipLdr = floor.flipHdr = nan;
    // docs/metrics.md "Reference noise floor": with the exact image x = mu and the reference
    // r = mu + e, E[e] = 0, E[e^2] = sigma^2, each term's expectation given the observed r.
    double sumVariance = 0.0, sumRelative = 0.0, sumSigma = 0.0, sumSquare = 0.0, sum = 0.0;
    for (size_t i = 0; i < reference.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double r = reference.data()[i][c], v = variance.data()[i][c];
            sumVariance += v;
            sumRelative += v / (r * r + kRelMseEpsilon);
            sumSigma += std::sqrt(v);
            sumSquare += r * r;
            sum += r;
        }
    const double values = 3.0 * static_cast<double>(reference.pixelCount());
    floor.mse = sumVariance / values;
    floor.rmse = std::sqrt(floor.mse);
    floor.relMse = sumRelative / values;
    floor.mae = kMeanAbsNormal * sumSigma / values;
    floor.relRms = sumSquare > 0.0 ? std::sqrt(sumVariance / sumSquare) : (sumVariance > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
    floor.testMean = floor.referenceMean = sum / values;
    // energy = test mean / reference mean: one draw of the reference's mean, not a mean of many
    // terms, so its floor is that mean's relative standard error sqrt(sum sigma^2) / sum r (an exact
    // test is within 2 of them 95% of the time).
    floor.energy = sum > 0.0 ? std::sqrt(sumVariance) / sum : 0.0;
    return floor;
}

Expected<ErrorMetrics> referenceNoiseFloor(const Image& reference, const Image& variance, const CompareOptions& options) {
    BOUNCE_TRY(const ErrorMetrics linear, linearNoiseFloor(reference, variance));
    // The display metrics: measured on a stand-in for the exact image (the reference's noise drawn
    // again around it; radiance is never negative, so the stand-in is clamped at 0).
    Image standIn(reference.width(), reference.height());
    uint64_t state = kNoiseFloorSeed;
    for (size_t i = 0; i < reference.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) {
            // Box-Muller: one normal deviate from two uniforms (the second of the pair is not needed).
            const double z = std::sqrt(-2.0 * std::log(uniform(state))) * std::cos(2.0 * std::numbers::pi * uniform(state));
            const double sigma = std::sqrt(static_cast<double>(variance.data()[i][c]));
            standIn.data()[i][c] = static_cast<float>(std::max(0.0, reference.data()[i][c] + sigma * z));
        }
    BOUNCE_TRY(ErrorMetrics floor, compareImages(standIn, reference, options));
    floor.mse = linear.mse;
    floor.rmse = linear.rmse;
    floor.relMse = linear.relMse;
    floor.mae = linear.mae;
    floor.relRms = linear.relRms;
    floor.testMean = linear.testMean;
    floor.referenceMean = linear.referenceMean;
    floor.energy = linear.energy;
    return floor;
}

double biasCorrectedRelMse(const Image& test, const Image& reference, const Image& variance) {
    double total = 0.0;
    for (size_t i = 0; i < reference.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double x = test.data()[i][c], r = reference.data()[i][c], v = variance.data()[i][c];
            total += ((x - r) * (x - r) - v) / (r * r + kRelMseEpsilon);
        }
    return reference.pixelCount() ? total / (3.0 * static_cast<double>(reference.pixelCount())) : 0.0;
}

double errorScale(std::string_view metric, double value, bool isFloor) {
    if (metric == "ssim") return 1.0 - value;
    if (metric == "psnr") return std::isinf(value) && value > 0.0 ? 0.0 : std::pow(10.0, -value / 10.0);
    if (metric == "energy") return isFloor ? value : std::abs(value - 1.0);
    for (std::string_view m : kFloorMetrics)
        if (m == metric) return value;
    return std::numeric_limits<double>::quiet_NaN();
}

bool insideNoiseFloor(std::string_view metric, double measured, double floor) {
    return errorScale(metric, measured, false) <= kNoiseFloorFactor * errorScale(metric, floor, true);
}

nlohmann::json noiseFloorJson(const ErrorMetrics& floor) {
    nlohmann::json j = nlohmann::json::object();
    for (std::string_view m : kFloorMetrics) j[std::string(m)] = number(field(floor, m));
    return j;
}

nlohmann::json insideNoiseFloorJson(const ErrorMetrics& measured, const ErrorMetrics& floor) {
    nlohmann::json j = nlohmann::json::object();
    for (std::string_view m : kFloorMetrics) {
        const double e = errorScale(m, field(measured, m), false), f = errorScale(m, field(floor, m), true);
        // A metric that is undefined here (relRMS of a black reference, PSNR of identical images is not:
        // its error is 0) gets no flag.
        j[std::string(m)] = std::isnan(e) || std::isnan(f) ? nlohmann::json(nullptr) : nlohmann::json(e <= kNoiseFloorFactor * f);
    }
    return j;
}

}  // namespace bounce
