#pragma once
// How far an error measured against a path-traced reference can be trusted. The reference is itself
// an estimate: with per-pixel variance sigma^2 (PathTracerResult::variance, the sample variance over
// its n samples divided by n) even an exact image scores an error against it. That expected score is
// the metric's noise floor; a measured error within kNoiseFloorFactor of it cannot be told from the
// reference's noise, so rankings there say nothing. docs/metrics.md "Reference noise floor" derives
// each floor and the bias-corrected relMSE.
#include "core/Error.h"
#include "core/Image.h"
#include "metrics/ErrorMetrics.h"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string_view>

namespace bounce {

// A measured error at most this many times its floor (on the metric's error scale, errorScale()) is
// flagged as inside the floor: the "within 2x". For relMSE, measured = true + floor on
// average, so a flag means the technique's own error is at most about the reference's noise.
inline constexpr double kNoiseFloorFactor = 2.0;

// Seed of the Gaussian stand-in noise of the display metrics' floors: fixed, so a floor is a pure
// function of the reference and its variance (studies' records are reproducible).
inline constexpr uint64_t kNoiseFloorSeed = 0x6e6f697365ull;  // "noise"

// The expected value of every metric of ErrorMetrics for an exact image compared with `reference`,
// whose per-pixel, per-channel variance is `variance` (same size, finite, >= 0). Closed forms
// (docs/metrics.md): relMSE = mean sigma^2 / (r^2 + eps); MSE = mean sigma^2; RMSE = sqrt(MSE);
// relRMS = sqrt(sum sigma^2 / sum r^2); MAE = sqrt(2/pi) mean sigma; energy holds the standard
// error of |energy - 1|, sqrt(sum sigma^2) / sum r (one draw, not a mean). The display metrics (PSNR, SSIM, LDR/HDR-FLIP,
// RMS-8, NRMSE) have no closed form through the tone curve: they are measured on a stand-in for the
// exact image, max(0, r + sigma z) with z standard normal (kNoiseFloorSeed), with `options`.
// testMean and referenceMean are the reference's mean. Fails on a size mismatch or bad values.
Expected<ErrorMetrics> referenceNoiseFloor(const Image& reference, const Image& variance, const CompareOptions& options = {});
// Only the closed forms (relMSE, MSE, RMSE, relRMS, MAE, energy, means); the display metrics are NaN.
// Cheap: per-frame floors of temporal studies. Same checks.
Expected<ErrorMetrics> linearNoiseFloor(const Image& reference, const Image& variance);

// relMSE with the reference's noise taken out: mean over pixels and channels of
// ((x - r)^2 - sigma^2) / (r^2 + eps), i.e. relMSE(test, reference) minus the relMSE floor. Its
// expectation is the test's relMSE against the exact image (to first order in the denominator); it
// may be negative for a test closer to the truth than the noise resolves.
double biasCorrectedRelMse(const Image& test, const Image& reference, const Image& variance);

// The error scale on which the floor is compared: the value for relMSE, MSE, RMSE, relRMS, MAE,
// NRMSE, FLIP and RMS-8; 1 - SSIM; the display MSE 10^(-PSNR/10) for PSNR; |energy - 1| for energy
// (the floor's energy is already that deviation). NaN for a metric without a floor.
double errorScale(std::string_view metric, double value, bool isFloor);
// errorScale(measured) <= kNoiseFloorFactor * errorScale(floor).
bool insideNoiseFloor(std::string_view metric, double measured, double floor);

// {"relMse": floor, ...}: the floors under toJson(ErrorMetrics)'s keys (no hdrFlipExposures, means).
nlohmann::json noiseFloorJson(const ErrorMetrics& floor);
// {"relMse": true|false, ...} for the metrics of noiseFloorJson.
nlohmann::json insideNoiseFloorJson(const ErrorMetrics& measured, const ErrorMetrics& floor);

}  // namespace bounce
