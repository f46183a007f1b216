#pragma once
// FLIP, the perceptual difference evaluator of Andersson et al.:
//   LDR-FLIP: "FLIP: A Difference Evaluator for Alternating Images", HPG 2020.
//   HDR-FLIP: "Visualizing Errors in Rendered High Dynamic Range Images", Eurographics 2021 short papers.
// Both return a per-pixel error in [0, 1]; the papers pool it with the mean. Implemented from the
// papers' equations; docs/metrics.md lists every step, constant and the deviations.
//
// Argument order follows the rest of metrics/: (test, reference). LDR-FLIP is symmetric in its two
// inputs (the HyAB colour distance and the feature term |f(ref) - f(test)| both are); HDR-FLIP is not,
// because its exposure range is computed from the reference alone.
#include "core/Image.h"
#include "metrics/ErrorMap.h"

#include <numbers>

namespace bounce {

// Pixels per degree of visual angle for a monitor `widthMeters` wide with `horizontalPixels`
// pixels, seen from `distanceMeters` (small-angle form used by the FLIP papers).
constexpr double pixelsPerDegree(double distanceMeters, double widthMeters, double horizontalPixels) {
    return distanceMeters * (horizontalPixels / widthMeters) * std::numbers::pi / 180.0;
}

// The FLIP papers' default observer: a 0.7 m wide 3840-pixel (4K) monitor at 0.7 m, ~67.02 ppd.
inline constexpr double kFlipDefaultPixelsPerDegree = pixelsPerDegree(0.7, 0.7, 3840.0);

// The two pipelines of LDR-FLIP and their combination flip = color^(1 - feature), all in [0, 1].
struct FlipLayers {
    ErrorMap color;    // ΔE_c: spatially filtered, Hunt-adjusted HyAB distance, remapped to [0, 1]
    ErrorMap feature;  // ΔE_f: edge/point feature difference on normalised luminance
    ErrorMap flip;     // ΔE
};

// LDR-FLIP of display images given as *linear* RGB (decode sRGB first, as readImage does for PNG),
// values clamped to [0, 1]. The images must have the same size (checked).
FlipLayers ldrFlipLayers(const Image& test, const Image& reference,
                         double pixelsPerDegree = kFlipDefaultPixelsPerDegree);
ErrorMap ldrFlip(const Image& test, const Image& reference, double pixelsPerDegree = kFlipDefaultPixelsPerDegree);

// The exposure bracket HDR-FLIP evaluates, in stops (radiance is multiplied by 2^ev).
struct HdrFlipExposures {
    float startEv = 0.0f;  // brings the reference's maximum luminance to the tone mapper's 0.85 point
    float stopEv = 0.0f;   // brings the reference's median luminance to the same point
    int count = 2;         // max(2, ceil(stopEv - startEv)), evenly spaced, both ends included
};

// Computes the bracket from the reference's luminance (2021 paper, Sec. 3).
HdrFlipExposures hdrFlipExposures(const Image& reference);

// HDR-FLIP's tone mapper: the Narkowicz fit of ACES with its 0.6 pre-exposure, after 2^exposureEv;
// linear radiance in, linear display RGB in [0, 1] out.
glm::vec3 hdrFlipToneMap(glm::vec3 radiance, float exposureEv);

// HDR-FLIP of linear radiance images: per-pixel maximum of LDR-FLIP over the exposure bracket.
ErrorMap hdrFlip(const Image& test, const Image& reference, const HdrFlipExposures& exposures,
                 double pixelsPerDegree = kFlipDefaultPixelsPerDegree);
// Same, with the bracket computed from `reference`.
ErrorMap hdrFlip(const Image& test, const Image& reference, double pixelsPerDegree = kFlipDefaultPixelsPerDegree);

}  // namespace bounce
