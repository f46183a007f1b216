#pragma once
// Full-reference image error metrics (definitions in docs/metrics.md and
// shared/specs/analytic-tests.md, "Metric definitions"):
//   on linear values:        MSE, RMSE, relMSE, MAE, HDR-FLIP
//   on tone-mapped images:   PSNR, SSIM, LDR-FLIP (CompareOptions states the display transforms)
// Argument order is (test, reference) throughout.
#include "core/Error.h"
#include "core/Image.h"
#include "core/ToneMap.h"
#include "metrics/ErrorMap.h"
#include "metrics/Flip.h"

#include <nlohmann/json_fwd.hpp>

namespace bounce {

// ε of relMSE, in the image's linear units: keeps black reference pixels from dominating.
inline constexpr double kRelMseEpsilon = 0.01;

// Display transform of an image read from PNG: readImage() decodes its sRGB values to linear, and
// clamping at 0 EV re-encodes exactly the stored values.
inline constexpr ToneMap kDisplayImageToneMap{0.0f, ToneCurve::Clamp};

struct CompareOptions {
    // Display transforms for PSNR, SSIM and LDR-FLIP, one per input so that a radiance image can be
    // compared with a display image. For EXR radiance, {0, Aces} is what `bounce render` writes to
    // PNG; for PNG inputs use kDisplayImageToneMap.
    ToneMap testToneMap{0.0f, ToneCurve::Aces};
    ToneMap referenceToneMap{0.0f, ToneCurve::Aces};
    double pixelsPerDegree = kFlipDefaultPixelsPerDegree;  // FLIP observer
};

struct ErrorMetrics {
    double mse = 0.0;     // mean over pixels and channels of (x - r)^2, linear
    double rmse = 0.0;    // sqrt(mse)
    double nrmse = 0.0;   // RMSE of the display values / (max - min of the reference's display values);
                          // van de Hoef 2013 Table 5.1 compares its figures' images by an NRMSE whose
                          // normalisation it does not give: this is the range one on what is shown
    double relMse = 0.0;  // mean of (x - r)^2 / (r^2 + ε), ε = kRelMseEpsilon, linear
    double relRms = 0.0;  // sqrt(sum (x - r)^2 / sum r^2) over pixels and channels, linear: the relative RMS
                          // of Nichols 2010 Figs. 4.9/4.13; scale-free, so it reads the same for dim
                          // indirect-only images (relMSE's epsilon swamps those); +inf for a black reference
                          // against a non-black test
    double mae = 0.0;     // mean of |x - r|, linear
    double psnr = 0.0;    // 10 log10(1 / MSE of display values), dB; +infinity for identical displays
    double rmsSum8 = 0.0; // photon-splatting document's RMS: sum over R, G, B of the RMS difference of the
                          // display values on the 0..255 scale (8-bit quantised), seed 004 section 5.1
    double ssim = 1.0;    // mean SSIM of the display images (metrics/Ssim.h)
    double flipLdr = 0.0; // mean LDR-FLIP of the display images
    double flipHdr = 0.0; // mean HDR-FLIP of the linear images
    HdrFlipExposures hdrFlipExposures;  // the bracket HDR-FLIP used (from the reference)
    double testMean = 0.0;       // mean over pixels and channels of the test image, linear
    double referenceMean = 0.0;  // the same of the reference
    double energy = 0.0;         // testMean / referenceMean: the image's light relative to the reference's
                                 // (+inf for a black reference and a test that is not, 1 for two black images)
};

// Per-pixel maps a caller may want alongside the pooled numbers (e.g. for a heat map).
struct CompareMaps {
    ErrorMap flipLdr, flipHdr;
};

// Fails (naming both sizes) when the images differ in size, are empty, or hold non-finite values.
Expected<ErrorMetrics> compareImages(const Image& test, const Image& reference, const CompareOptions& options = {},
                                     CompareMaps* maps = nullptr);

// Per-pixel maps, each the mean over the three channels. The images must have the same size (checked).
// Values beyond float's range saturate at its largest value, so every map of finite images is finite.
ErrorMap absoluteErrorMap(const Image& test, const Image& reference);
ErrorMap squaredErrorMap(const Image& test, const Image& reference);
ErrorMap relativeSquaredErrorMap(const Image& test, const Image& reference, double epsilon = kRelMseEpsilon);

// sqrt(sum (x - r)^2 / sum r^2) over pixels and channels, linear: the RMS error relative to the
// reference's RMS, the measure of Nichols (2010) Figs. 4.9/4.13. 0 for two black images, +infinity for a
// black reference and a test that is not. Same size required (checked).
double relativeRmsError(const Image& test, const Image& reference);

// Seed 004's error (section 5.1): for each channel the RMS over pixels of the difference of the 8-bit
// display values (round(255 v)), summed over R, G and B. Same size required (checked).
double rmsSum8Bit(const Image& testDisplay, const Image& referenceDisplay);

// PSNR in dB of two display images with peak value 1; +infinity when they are identical.
double psnr(const Image& testDisplay, const Image& referenceDisplay);

// {"mse":..., ..., "hdrFlipExposures": {"startEv", "stopEv", "count"}}; an infinite PSNR is written as null
// (JSON has no infinity).
nlohmann::json toJson(const ErrorMetrics& metrics);

}  // namespace bounce
