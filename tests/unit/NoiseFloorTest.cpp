// The reference-noise floor (metrics/NoiseFloor.h, docs/metrics.md "Reference noise floor") on
// synthetic images of known error and noise, and the path tracer's variance image it reads.
#include "metrics/NoiseFloor.h"
#include "reference/PathTracer.h"
#include "scene/SceneLoader.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <random>

using namespace bounce;

namespace {

constexpr int kSide = 64;  // 64 x 64 x 3 = 12288 values: a mean of them has ~1.3% relative sd for chi^2(1) terms

// The "exact" image: values from 0.05 to 1 (full-image radiances, where relMSE's epsilon matters little).
Image exactImage() {
    Image img(kSide, kSide);
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x)
            img.at(x, y) = {0.05f + 0.95f * x / (kSide - 1.0f), 0.05f + 0.95f * y / (kSide - 1.0f), 0.5f};
    return img;
}

// sigma = relative * value per pixel and channel: variance image and a reference drawn with it.
Image varianceOf(const Image& exact, float relative) {
    Image v(exact.width(), exact.height());
    for (size_t i = 0; i < exact.pixelCount(); ++i) v.data()[i] = exact.data()[i] * exact.data()[i] * relative * relative;
    return v;
}

Image noisy(const Image& exact, const Image& variance, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> z;
    Image out(exact.width(), exact.height());
    for (size_t i = 0; i < exact.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) out.data()[i][c] = exact.data()[i][c] + std::sqrt(variance.data()[i][c]) * z(rng);
    return out;
}

Image scaled(const Image& image, float factor) {
    Image out = image;
    for (glm::vec3& p : out.pixels()) p *= factor;
    return out;
}

}  // namespace

// The closed-form relMSE floor is what an exact image scores against noisy references, on average:
// eight references with 10% noise; the mean measured relMSE and the mean floor agree to 5% (each is a
// mean of 12288 chi^2-like terms, ~1.3% sd, and the first-order denominator adds ~3 sigma^2/mu^2 = 3%
// at most). A floor missing its division by the denominator, or by the value count, is far off.
TEST(NoiseFloor, RelMseFloorIsTheExactImagesExpectedError) {
    const Image exact = exactImage();
    const Image variance = varianceOf(exact, 0.1f);
    double measured = 0.0, floor = 0.0;
    constexpr int kReferences = 8;
    for (unsigned s = 0; s < kReferences; ++s) {
        const Image reference = noisy(exact, variance, 100 + s);
        auto m = compareImages(exact, reference);
        auto f = referenceNoiseFloor(reference, variance);
        ASSERT_TRUE(m.ok() && f.ok());
        measured += m->relMse / kReferences;
        floor += f->relMse / kReferences;
        // The exact image is inside every flagged metric's floor (measured ~ floor <= 2 floor).
        const nlohmann::json inside = insideNoiseFloorJson(*m, *f);
        // (Not energy: one draw of the image mean, inside 2 standard errors 95% of the time; tested below.)
        for (const char* metric : {"relMse", "mse", "rmse", "relRms", "mae", "ssim", "flipLdr", "flipHdr", "psnr"})
            EXPECT_TRUE(inside[metric].get<bool>()) << metric << " of an exact image is outside its floor";
    }
    EXPECT_NEAR(measured / floor, 1.0, 0.05) << "measured " << measured << " floor " << floor;
    // The energy floor is the standard error of the reference's mean: over 64 references the RMS of
    // (energy - 1) matches it within 25% (chi with 64 degrees of freedom: ~9% sd).
    auto energyFloor = referenceNoiseFloor(exact, variance);
    ASSERT_TRUE(energyFloor.ok());
    double sumSquares = 0.0, exactSum = 0.0;
    for (const glm::vec3& p : exact.pixels()) exactSum += p.r + p.g + p.b;
    constexpr int kDraws = 64;
    for (unsigned s = 0; s < kDraws; ++s) {
        const Image reference = noisy(exact, variance, 1000 + s);
        double sum = 0.0;
        for (const glm::vec3& p : reference.pixels()) sum += p.r + p.g + p.b;
        sumSquares += (exactSum / sum - 1.0) * (exactSum / sum - 1.0) / kDraws;
    }
    EXPECT_NEAR(std::sqrt(sumSquares) / energyFloor->energy, 1.0, 0.25);
    // The simulated display floors follow the noise: 10% noise gives a FLIP floor well above 0 and an
    // SSIM floor well below 1; without noise both are perfect.
    auto f = referenceNoiseFloor(exact, varianceOf(exact, 0.1f));
    auto zero = referenceNoiseFloor(exact, Image(kSide, kSide));
    ASSERT_TRUE(f.ok() && zero.ok());
    EXPECT_GT(f->flipLdr, 0.01);
    EXPECT_LT(f->ssim, 0.99);
    EXPECT_EQ(zero->flipLdr, 0.0);
    EXPECT_EQ(zero->ssim, 1.0);
    EXPECT_EQ(zero->relMse, 0.0);
}

// Bias-corrected relMSE on a test of known error: 10% too bright and too dark on alternate pixels
// (true relMSE against the exact image t = mean (0.1 x)^2 / (x^2 + eps)) measured against a reference
// with as much noise. The plain relMSE reads about t + floor (here ~2t); the corrected one reads t
// within 10% (sd of the noise part ~1.3% of the floor, ~3% from the first-order denominator).
// Dropping the subtraction fails. (Errors of one sign add relMSE's cross term of docs/metrics.md,
// the noisy denominator's correlation with the noise: a uniformly 10% darker image reads 0.66 t.)
TEST(NoiseFloor, BiasCorrectedRelMseRecoversTheTrueError) {
    const Image exact = exactImage();
    Image test = exact;
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) test.at(x, y) *= (x + y) % 2 ? 1.1f : 0.9f;
    auto truth = compareImages(test, exact);
    ASSERT_TRUE(truth.ok());
    const Image variance = varianceOf(exact, 0.1f);
    const Image reference = noisy(exact, variance, 7);
    auto plain = compareImages(test, reference);
    auto floor = referenceNoiseFloor(reference, variance);
    ASSERT_TRUE(plain.ok() && floor.ok());
    const double corrected = biasCorrectedRelMse(test, reference, variance);
    EXPECT_GT(plain->relMse, 1.5 * truth->relMse) << "the noise should inflate the plain relMSE";
    EXPECT_NEAR(corrected / truth->relMse, 1.0, 0.1) << "corrected " << corrected << " true " << truth->relMse;
    EXPECT_NEAR(corrected, plain->relMse - floor->relMse, 1e-12);
    // A 30% darker image is outside the relMSE and energy floors; an image with three times the
    // reference's noise is outside the SSIM and FLIP floors too (SSIM barely sees a uniform scale).
    auto darker = compareImages(scaled(exact, 0.7f), reference);
    auto noisier = compareImages(noisy(exact, varianceOf(exact, 0.3f), 8), reference);
    ASSERT_TRUE(darker.ok() && noisier.ok());
    EXPECT_FALSE(insideNoiseFloor("relMse", darker->relMse, floor->relMse));
    EXPECT_FALSE(insideNoiseFloor("energy", darker->energy, floor->energy));
    for (const char* metric : {"relMse", "ssim", "flipLdr", "flipHdr", "mae"})
        EXPECT_FALSE(insideNoiseFloorJson(*noisier, *floor)[metric].get<bool>()) << metric;
}

TEST(NoiseFloor, ErrorScales) {
    EXPECT_DOUBLE_EQ(errorScale("ssim", 0.9, false), 0.1);
    EXPECT_DOUBLE_EQ(errorScale("psnr", 20.0, false), 0.01);
    EXPECT_DOUBLE_EQ(errorScale("energy", 0.8, false), 0.2);
    EXPECT_DOUBLE_EQ(errorScale("energy", 0.05, true), 0.05);
    EXPECT_TRUE(std::isnan(errorScale("nonsense", 1.0, false)));
    // PSNR: 3 dB below the floor's PSNR is twice its display MSE, the edge of "within 2x".
    EXPECT_TRUE(insideNoiseFloor("psnr", 30.0 - 3.0, 30.0));
    EXPECT_FALSE(insideNoiseFloor("psnr", 30.0 - 3.1, 30.0));
}

TEST(NoiseFloor, BadInput) {
    const Image exact = exactImage();
    EXPECT_FALSE(referenceNoiseFloor(exact, Image(3, 3)).ok());
    Image negative(kSide, kSide, glm::vec3(-1.0f));
    EXPECT_FALSE(referenceNoiseFloor(exact, negative).ok());
    EXPECT_FALSE(referenceNoiseFloor(Image(), Image()).ok());
}

// The path tracer's variance image against the spread of independent renders: 16 seeds of an 8 x 8
// cornell box at 16 spp; summed over pixels and channels, the seeds' sample variance of each pixel's
// value and the mean estimated variance agree within 25% (the sums of 192 values with 15 and
// ~16*... degrees of freedom, heavy-tailed path-tracing samples included). A variance image not
// divided by n (the per-sample variance) is 16x too large; one of luminance only differs per channel.
TEST(NoiseFloor, PathTracerVarianceMatchesTheSpreadOfSeeds) {
    auto scene = loadScene("cornell-box");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    PathTracerSettings s;
    s.width = 8;
    s.height = 8;
    s.samplesPerPixel = 16;
    constexpr int kSeeds = 16;
    std::vector<Image> images;
    Image meanVariance(8, 8);
    for (int seed = 0; seed < kSeeds; ++seed) {
        s.seed = static_cast<uint64_t>(seed) + 1;
        auto tracer = PathTracer::create(*scene, s);
        ASSERT_TRUE(tracer.ok());
        PathTracerResult r = tracer->render();
        ASSERT_EQ(r.variance.width(), 8);
        for (size_t i = 0; i < r.variance.pixelCount(); ++i) meanVariance.data()[i] += r.variance.data()[i] / float(kSeeds);
        images.push_back(std::move(r.radiance));
    }
    double empirical = 0.0, estimated = 0.0;
    for (size_t i = 0; i < meanVariance.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) {
            double mean = 0.0, sq = 0.0;
            for (const Image& im : images) mean += im.data()[i][c] / double(kSeeds);
            for (const Image& im : images) sq += (im.data()[i][c] - mean) * (im.data()[i][c] - mean);
            empirical += sq / (kSeeds - 1);
            estimated += meanVariance.data()[i][c];
        }
    ASSERT_GT(estimated, 0.0);
    EXPECT_NEAR(empirical / estimated, 1.0, 0.25) << "empirical " << empirical << " estimated " << estimated;
}
