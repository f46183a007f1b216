// The reference path tracer against answers known in advance (/work/shared/specs/analytic-tests.md).
#include "ReferenceTestScenes.h"
#include "reference/PathTracer.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <cmath>

using namespace bounce;

namespace {

PathTracerResult render(const Scene& scene, const PathTracerSettings& settings) {
    auto tracer = PathTracer::create(scene, settings);
    EXPECT_TRUE(tracer.ok()) << (tracer.ok() ? "" : tracer.error().message);
    if (!tracer.ok()) return {};
    return tracer->render();
}

double meanLuminance(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += luminance(p);
    return sum / static_cast<double>(image.pixelCount());
}

// Radiance everywhere in a furnace room of albedo rho emitting Le, with at most n reflections per
// path (analytic-tests.md "Furnace room"): Le (1 - rho^(n+1)) / (1 - rho).
double furnaceRadiance(double rho, double emitted, int reflections) {
    return emitted * (1.0 - std::pow(rho, reflections + 1)) / (1.0 - rho);
}

struct FurnaceCase {
    const char* name;
    int bounces;
    bool indirectOnly;
    double expected;  // rho = 0.5, Le = 1
};

class ReferenceFurnace : public ::testing::TestWithParam<FurnaceCase> {};

// 16 x 16 pixels at 4096 spp: 10^6 paths per case. The tolerance of 0.5% on the image mean is what
// the issue asks for; it is safe because the image-level relative standard error measured by the
// renderer itself is far below it (asserted below: under 0.1%, so 0.5% is more than 5 standard
// errors), and the estimator is unbiased for every scope.
TEST_P(ReferenceFurnace, MatchesClosedForm) {
    const FurnaceCase& c = GetParam();
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    PathTracerSettings s;
    s.width = s.height = 16;
    s.samplesPerPixel = 4096;
    s.bounces = c.bounces;
    s.indirectOnly = c.indirectOnly;
    s.seed = 7;
    const PathTracerResult r = render(scene, s);
    ASSERT_EQ(r.samplesPerPixel, 4096u);
    EXPECT_EQ(r.invalidSamples, 0u);
    const double mean = meanLuminance(r.radiance);
    EXPECT_NEAR(mean / c.expected, 1.0, 0.005) << c.name << ": mean " << mean << " expected " << c.expected;
    EXPECT_LT(r.noise.imageRelativeError, 0.001) << c.name;
    // Every pixel sees the same radiance: no pixel may stray by more than 6 of its own standard
    // errors. The renderer reports the mean relative error over pixels; individual pixels differ
    // from it by a small factor, so allow 6x that mean plus the 0.5% bias budget.
    const double pixelTolerance = 6.0 * r.noise.meanPixelRelativeError + 0.005;
    for (const glm::vec3& p : r.radiance.pixels())
        ASSERT_NEAR(luminance(p) / c.expected, 1.0, pixelTolerance) << c.name;
}

// rho = 0.5, Le = 1. Direct light is one reflection, so --bounces K allows n = K + 1 reflections.
// The indirect-only part is everything from the second reflection on: full - (Le + rho Le).
INSTANTIATE_TEST_SUITE_P(
    Scopes, ReferenceFurnace,
    ::testing::Values(FurnaceCase{"bounces0", 0, false, furnaceRadiance(0.5, 1.0, 1)},
                      FurnaceCase{"bounces1", 1, false, furnaceRadiance(0.5, 1.0, 2)},
                      FurnaceCase{"bounces3", 3, false, furnaceRadiance(0.5, 1.0, 4)},
                      FurnaceCase{"unbounded", PathTracerSettings::kUnbounded, false, 2.0},
                      FurnaceCase{"indirectOnlyBounces1", 1, true, furnaceRadiance(0.5, 1.0, 2) - 1.5},
                      FurnaceCase{"indirectOnlyBounces3", 3, true, furnaceRadiance(0.5, 1.0, 4) - 1.5},
                      FurnaceCase{"indirectOnlyUnbounded", PathTracerSettings::kUnbounded, true, 0.5}),
    [](const ::testing::TestParamInfo<FurnaceCase>& p) { return std::string(p.param.name); });

}  // namespace
