// FLIP (Andersson et al. 2020) and HDR-FLIP (Andersson et al. 2021).
//
// LDR-FLIP, per image (both images go through the same steps):
//   1. linear RGB -> XYZ -> YCxCz opponent space;
//   2. each opponent channel is convolved with its contrast sensitivity function (CSF), a sum of
//      Gaussians whose width is set by the pixels-per-degree of the observer;
//   3. back to linear RGB, clamped to the unit cube, -> CIELAB, Hunt adjustment (a*, b* scaled by L*/100);
//   4. colour error: HyAB distance |ΔL| + ||(Δa, Δb)||, raised to qc, remapped so that [0, pc*cmax]
//      covers [0, pt] and [pc*cmax, cmax] covers [pt, 1]; cmax is the distance between Hunt-adjusted
//      green and blue, the largest in the RGB cube;
//   5. feature error on the normalised achromatic channel (Y/Yn): first (edge) and second (point)
//      Gaussian derivative filters; ΔE_f = (max(| |e_r| - |e_t| |, | |p_r| - |p_t| |) / sqrt 2)^qf;
//   6. ΔE = ΔE_c^(1 - ΔE_f).
// HDR-FLIP runs LDR-FLIP on tone-mapped copies at a bracket of exposures chosen from the reference
// and keeps the per-pixel maximum.
//
// All filters are separable (each CSF term is an isotropic Gaussian; the derivative filters are a
// 1D derivative times a 1D Gaussian, and their positive/negative normalisation factors separate too),
// so they run as two 1D passes. Borders are clamped (replicated), as in the authors' code.
#include "metrics/Flip.h"

#include "core/Check.h"
#include "metrics/ColorSpaces.h"
#include "metrics/Filter.h"

#include <glm/common.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace bounce {
namespace {

// --- Constants of the 2020 paper ---
constexpr float kColorExponent = 0.7f;       // qc, exponent on the HyAB distance
constexpr float kFeatureExponent = 0.5f;     // qf, exponent on the feature difference
constexpr float kRemapCutoff = 0.4f;         // pc, fraction of cmax mapped to pt
constexpr float kRemapTarget = 0.95f;        // pt
constexpr double kEdgeWidthDegrees = 0.082;  // w, peak-to-trough width of the human edge detector (deg)
constexpr float kHuntScale = 0.01f;          // chroma scale per unit L* (Hunt effect), L* in [0, 100]

// CSF of one opponent channel in the spatial domain, x in degrees:
//   S(x) = a1 sqrt(pi/b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi/b2) exp(-pi^2 x^2 / b2),
// sums of Gaussians fitted to the contrast sensitivity functions of Johnson & Fairchild (2020
// paper, colour pipeline); a is unitless, b in deg^2. Channels with a single Gaussian set a2 = 0.
struct CsfTerms {
    double a1, b1, a2, b2;
};
constexpr CsfTerms kCsfAchromatic{1.0, 0.0047, 0.0, 0.0};
constexpr CsfTerms kCsfRedGreen{1.0, 0.0053, 0.0, 0.0};
constexpr CsfTerms kCsfBlueYellow{34.1, 0.04, 13.5, 0.025};
// The filter radius covers 3 standard deviations of the widest Gaussian (b = 0.04 deg^2) in all channels.
constexpr double kCsfWidestB = 0.04;

// --- HDR-FLIP (2021 paper) ---
// Tone-mapped value the exposure bracket aims the reference's maximum and median luminance at.
constexpr double kHdrTargetValue = 0.85;
// Narkowicz's ACES fit y = (2.51x^2 + 0.03x) / (2.43x^2 + 0.59x + 0.14) evaluated at 0.6x, i.e. the
// rational polynomial (k0 x^2 + k1 x + k2) / (k3 x^2 + k4 x + k5) below.
constexpr double kAcesPreExposure = 0.6;
constexpr double kAcesK0 = kAcesPreExposure * kAcesPreExposure * 2.51;
constexpr double kAcesK1 = kAcesPreExposure * 0.03;
constexpr double kAcesK2 = 0.0;
constexpr double kAcesK3 = kAcesPreExposure * kAcesPreExposure * 2.43;
constexpr double kAcesK4 = kAcesPreExposure * 0.59;
constexpr double kAcesK5 = 0.14;
// A black median (e.g. a mostly black frame) would put the stop exposure at infinity; floor the
// median at float epsilon like the authors' code does, giving a long but finite bracket.
constexpr float kMinMedianLuminance = 1.1920929e-7f;

// One separable term of a filter: weight * (kernel (x) kernel).
struct SeparableTerm {
    float weight;
    std::vector<float> kernel;
};

std::vector<SeparableTerm> csfFilter(const CsfTerms& csf, double ppd) {
    const int radius = static_cast<int>(std::ceil(3.0 * std::sqrt(kCsfWidestB / (2.0 * std::numbers::pi * std::numbers::pi)) * ppd));
    const double dx = 1.0 / ppd;  // degrees per pixel
    std::vector<SeparableTerm> terms;
    std::vector<double> amplitudes;  // a sqrt(pi/b) times the 2D sum of the unnormalised Gaussian
    for (auto [a, b] : {std::pair{csf.a1, csf.b1}, std::pair{csf.a2, csf.b2}}) {
        if (a == 0.0) continue;
        std::vector<float> kernel(static_cast<size_t>(2 * radius + 1));
        double sum = 0.0;
        for (int i = -radius; i <= radius; ++i) {
            const double x = i * dx;
            const double g = std::exp(-std::numbers::pi * std::numbers::pi * x * x / b);
            kernel[static_cast<size_t>(i + radius)] = static_cast<float>(g);
            sum += g;
        }
        for (float& k : kernel) k = static_cast<float>(k / sum);
        amplitudes.push_back(a * std::sqrt(std::numbers::pi / b) * sum * sum);
        terms.push_back({0.0f, std::move(kernel)});
    }
    // Normalise the 2D filter to unit sum, so constant images pass unchanged.
    double total = 0.0;
    for (double amp : amplitudes) total += amp;
    for (size_t i = 0; i < terms.size(); ++i) terms[i].weight = static_cast<float>(amplitudes[i] / total);
    return terms;
}

Plane applyFilter(const Plane& in, const std::vector<SeparableTerm>& terms) {
    Plane out(in.width, in.height);
    for (const SeparableTerm& term : terms) {
        const Plane filtered = convolveSeparable(in, term.kernel, term.kernel);
        for (size_t i = 0; i < out.values.size(); ++i) out.values[i] += term.weight * filtered.values[i];
    }
    return out;
}

// 1D factors of the edge (first derivative) and point (second derivative) detectors. The 2D
// kernel is derivative(x) * gaussian(y); the paper normalises its positive weights to sum 1 and its
// negative weights to -1, which factors into the 1D derivative normalised the same way times a
// unit-sum Gaussian.
struct FeatureKernels {
    std::vector<float> edge, point, gaussian;
};

FeatureKernels featureKernels(double ppd) {
    const double sigma = 0.5 * kEdgeWidthDegrees * ppd;  // pixels
    const int radius = static_cast<int>(std::ceil(3.0 * sigma));
    FeatureKernels k;
    k.gaussian = gaussianKernel(sigma, radius);
    std::vector<double> edge, point;
    for (int i = -radius; i <= radius; ++i) {
        const double g = std::exp(-(i * i) / (2.0 * sigma * sigma));
        edge.push_back(-i * g);
        point.push_back((i * i / (sigma * sigma) - 1.0) * g);
    }
    auto normalise = [](const std::vector<double>& raw) {
        double positive = 0.0, negative = 0.0;
        for (double v : raw) (v > 0.0 ? positive : negative) += v;
        std::vector<float> out;
        for (double v : raw) out.push_back(static_cast<float>(v > 0.0 ? v / positive : (v < 0.0 ? -v / negative : 0.0)));
        return out;
    };
    k.edge = normalise(edge);
    k.point = normalise(point);
    return k;
}

glm::vec3 huntAdjustedLab(glm::vec3 linearRgb) {
    glm::vec3 lab = xyzToCielab(linearRgbToXyz(linearRgb));
    lab.y *= kHuntScale * lab.x;
    lab.z *= kHuntScale * lab.x;
    return lab;
}

float hyab(glm::vec3 a, glm::vec3 b) {
    return std::abs(a.x - b.x) + std::hypot(a.y - b.y, a.z - b.z);
}

// cmax: the largest colour distance in the pipeline, between Hunt-adjusted green and blue, raised to qc.
float maxColorDistance() {
    static const float kMax = std::pow(hyab(huntAdjustedLab({0, 1, 0}), huntAdjustedLab({0, 0, 1})), kColorExponent);
    return kMax;
}

float remapColorError(float powered) {
    const float cmax = maxColorDistance();
    const float cutoff = kRemapCutoff * cmax;
    if (powered < cutoff) return kRemapTarget / cutoff * powered;
    return kRemapTarget + (powered - cutoff) / (cmax - cutoff) * (1.0f - kRemapTarget);
}

// What one image contributes: its filtered, Hunt-adjusted CIELAB colours and its feature magnitudes.
struct Prepared {
    std::vector<glm::vec3> lab;
    Plane edgeMagnitude, pointMagnitude;
};

Prepared prepare(const Image& image, const std::array<std::vector<SeparableTerm>, 3>& csf, const FeatureKernels& fk) {
    const int w = image.width(), h = image.height();
    std::array<Plane, 3> opponent{Plane(w, h), Plane(w, h), Plane(w, h)};
    Plane luminance(w, h);
    const float whiteY = referenceWhiteXyz().y;
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        const glm::vec3 xyz = linearRgbToXyz(glm::clamp(image.data()[i], 0.0f, 1.0f));
        const glm::vec3 ycxcz = xyzToYcxcz(xyz);
        for (int c = 0; c < 3; ++c) opponent[c].values[i] = ycxcz[c];
        // The paper's normalised achromatic channel, (Y_ycxcz + 16) / 116, is Y / Yn.
        luminance.values[i] = xyz.y / whiteY;
    }

    Prepared p;
    std::array<Plane, 3> filtered;
    for (int c = 0; c < 3; ++c) filtered[c] = applyFilter(opponent[c], csf[c]);
    p.lab.resize(image.pixelCount());
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        const glm::vec3 ycxcz(filtered[0].values[i], filtered[1].values[i], filtered[2].values[i]);
        const glm::vec3 rgb = glm::clamp(xyzToLinearRgb(ycxczToXyz(ycxcz)), 0.0f, 1.0f);
        p.lab[i] = huntAdjustedLab(rgb);
    }

    auto magnitude = [&](const std::vector<float>& derivative) {
        const Plane dx = convolveSeparable(luminance, derivative, fk.gaussian);
        const Plane dy = convolveSeparable(luminance, fk.gaussian, derivative);
        Plane m(w, h);
        for (size_t i = 0; i < m.values.size(); ++i) m.values[i] = std::hypot(dx.values[i], dy.values[i]);
        return m;
    };
    p.edgeMagnitude = magnitude(fk.edge);
    p.pointMagnitude = magnitude(fk.point);
    return p;
}

void checkSameSize(const Image& test, const Image& reference) {
    BOUNCE_CHECK(test.width() == reference.width() && test.height() == reference.height(),
                 "FLIP needs images of the same size (test {}x{}, reference {}x{})", test.width(), test.height(),
                 reference.width(), reference.height());
}

}  // namespace

FlipLayers ldrFlipLayers(const Image& test, const Image& reference, double ppd) {
    checkSameSize(test, reference);
    BOUNCE_CHECK(ppd > 0.0 && std::isfinite(ppd), "pixels per degree must be positive, got {}", ppd);
    const std::array<std::vector<SeparableTerm>, 3> csf{csfFilter(kCsfAchromatic, ppd), csfFilter(kCsfRedGreen, ppd),
                                                        csfFilter(kCsfBlueYellow, ppd)};
    const FeatureKernels fk = featureKernels(ppd);
    const Prepared r = prepare(reference, csf, fk);
    const Prepared t = prepare(test, csf, fk);

    const int w = reference.width(), h = reference.height();
    FlipLayers layers{ErrorMap(w, h), ErrorMap(w, h), ErrorMap(w, h)};
    const float invSqrt2 = static_cast<float>(1.0 / std::numbers::sqrt2);
    for (size_t i = 0; i < reference.pixelCount(); ++i) {
        const float color = remapColorError(std::pow(hyab(r.lab[i], t.lab[i]), kColorExponent));
        const float featureDiff = std::max(std::abs(r.edgeMagnitude.values[i] - t.edgeMagnitude.values[i]),
                                           std::abs(r.pointMagnitude.values[i] - t.pointMagnitude.values[i]));
        const float feature = std::pow(std::min(invSqrt2 * featureDiff, 1.0f), kFeatureExponent);
        layers.color.values()[i] = color;
        layers.feature.values()[i] = feature;
        layers.flip.values()[i] = std::pow(color, 1.0f - feature);
    }
    return layers;
}

ErrorMap ldrFlip(const Image& test, const Image& reference, double ppd) {
    return std::move(ldrFlipLayers(test, reference, ppd).flip);
}

HdrFlipExposures hdrFlipExposures(const Image& reference) {
    std::vector<float> lum;
    lum.reserve(reference.pixelCount());
    for (const glm::vec3& p : reference.pixels()) lum.push_back(luminance(glm::max(p, glm::vec3(0.0f))));
    HdrFlipExposures e;
    if (lum.empty()) return e;
    const float maxLum = *std::max_element(lum.begin(), lum.end());
    // An all-black reference has no scale to aim at: evaluate at 0 EV only (as the authors do).
    if (maxLum <= 0.0f) return e;
    const size_t mid = lum.size() / 2;
    std::nth_element(lum.begin(), lum.begin() + static_cast<std::ptrdiff_t>(mid), lum.end());
    const float medianLum = std::max(lum[mid], kMinMedianLuminance);

    // x with toneMap(x) = t solves (k0 - t k3) x^2 + (k1 - t k4) x + (k2 - t k5) = 0; take the positive root.
    const double t = kHdrTargetValue;
    const double qa = kAcesK0 - t * kAcesK3, qb = kAcesK1 - t * kAcesK4, qc = kAcesK2 - t * kAcesK5;
    const double xTarget = (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
    e.startEv = static_cast<float>(std::log2(xTarget / maxLum));
    e.stopEv = static_cast<float>(std::log2(xTarget / medianLum));
    e.count = std::max(2, static_cast<int>(std::ceil(e.stopEv - e.startEv)));
    return e;
}

glm::vec3 hdrFlipToneMap(glm::vec3 radiance, float exposureEv) {
    const glm::vec3 x = glm::max(radiance, glm::vec3(0.0f)) * std::exp2(exposureEv);
    glm::vec3 out;
    for (int c = 0; c < 3; ++c) {
        const double v = x[c];
        if (!std::isfinite(v)) {
            out[c] = 1.0f;  // the curve tends to k0/k3 > 1 and is clamped
            continue;
        }
        const double y = (kAcesK0 * v * v + kAcesK1 * v + kAcesK2) / (kAcesK3 * v * v + kAcesK4 * v + kAcesK5);
        out[c] = static_cast<float>(std::clamp(y, 0.0, 1.0));
    }
    return out;
}

ErrorMap hdrFlip(const Image& test, const Image& reference, const HdrFlipExposures& exposures, double ppd) {
    checkSameSize(test, reference);
    BOUNCE_CHECK(exposures.count >= 1, "HDR-FLIP needs at least one exposure, got {}", exposures.count);
    const int w = reference.width(), h = reference.height();
    const float step = exposures.count > 1 ? (exposures.stopEv - exposures.startEv) / static_cast<float>(exposures.count - 1)
                                           : 0.0f;
    // Exposures are independent: each worker keeps its own running maximum, merged at the end.
    tbb::enumerable_thread_specific<ErrorMap> partialMax([&] { return ErrorMap(w, h); });
    tbb::parallel_for(0, exposures.count, [&](int i) {
        const float ev = exposures.startEv + static_cast<float>(i) * step;
        Image testLdr(w, h), referenceLdr(w, h);
        for (size_t p = 0; p < reference.pixelCount(); ++p) {
            testLdr.data()[p] = hdrFlipToneMap(test.data()[p], ev);
            referenceLdr.data()[p] = hdrFlipToneMap(reference.data()[p], ev);
        }
        const ErrorMap ldr = ldrFlip(testLdr, referenceLdr, ppd);
        ErrorMap& local = partialMax.local();
        for (size_t p = 0; p < local.pixelCount(); ++p) local.values()[p] = std::max(local.values()[p], ldr.values()[p]);
    });
    ErrorMap result(w, h);
    for (const ErrorMap& local : partialMax)
        for (size_t p = 0; p < result.pixelCount(); ++p) result.values()[p] = std::max(result.values()[p], local.values()[p]);
    return result;
}

ErrorMap hdrFlip(const Image& test, const Image& reference, double ppd) {
    return hdrFlip(test, reference, hdrFlipExposures(reference), ppd);
}

}  // namespace bounce
