// The reference path tracer against answers known in advance (/work/shared/specs/analytic-tests.md).
#include "ReferenceTestScenes.h"
#include "reference/PathTracer.h"
#include "scene/SceneLoader.h"
#include "techniques/vct/ConeQuadrature.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>

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

// 4096 spp on a tiny image (16 x 16, or 32 x 32 for the noisier indirect-only scopes): 10^6 or
// 4 * 10^6 paths per case. The tolerance of 0.5% on the image mean is what the issue asks for; it
// is safe because the image-level relative standard error that the renderer reports is asserted to
// be under 0.1%, so 0.5% is at least 5 standard errors, and the estimator is unbiased in every scope
// (checked separately at 16384 spp and several seeds while developing: deviations within 2 errors).
TEST_P(ReferenceFurnace, MatchesClosedForm) {
    const FurnaceCase& c = GetParam();
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    PathTracerSettings s;
    s.width = s.height = c.indirectOnly ? 32 : 16;
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
                      FurnaceCase{"indirectOnlyUnbounded", PathTracerSettings::kUnbounded, true, 0.5}),
    [](const ::testing::TestParamInfo<FurnaceCase>& p) { return std::string(p.param.name); });


// ---- Direct light on a plane, seen straight from above by an orthographic camera ----------------

// Mean and standard deviation of f over the footprint of pixel (px, py) of a size x size image of a
// view `view` metres wide centred on the origin (testscenes::planeUnderOrthoCamera), by the
// midpoint rule on a 32 x 32 grid. The renderer's pixel jitter samples the same footprint, so with
// n samples its estimate of the mean has standard error stddev / sqrt(n) when the light adds no
// noise of its own (delta lights).
struct Footprint {
    double mean = 0.0;
    double stddev = 0.0;
};
Footprint footprint(int px, int py, int size, float view, const std::function<double(double, double)>& f) {
    constexpr int kGrid = 32;
    const double pixel = view / size;
    double sum = 0.0, sum2 = 0.0;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
            const double x = -0.5 * view + (px + (i + 0.5) / kGrid) * pixel;
            const double z = -0.5 * view + (py + (j + 0.5) / kGrid) * pixel;
            const double v = f(x, z);
            sum += v;
            sum2 += v * v;
        }
    constexpr double n = kGrid * kGrid;
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean))};
}

double footprintAverage(int px, int py, int size, float view, const std::function<double(double, double)>& f) {
    return footprint(px, py, size, view, f).mean;
}

// Delta lights: a pixel must match its footprint mean within 5 of its jitter standard errors, plus
// 1e-4 for the midpoint rule and float rounding.
void expectPixelMatches(float rendered, const Footprint& fp, uint32_t spp, const char* what, int px, int py) {
    const double tolerance = 5.0 * fp.stddev / std::sqrt(static_cast<double>(spp)) + 1e-4 * fp.mean;
    EXPECT_NEAR(rendered, fp.mean, tolerance) << what << " pixel " << px << "," << py;
}

PathTracerSettings directOnly(int size, uint32_t spp) {
    PathTracerSettings s;
    s.width = s.height = size;
    s.samplesPerPixel = spp;
    s.bounces = 0;
    s.seed = 3;
    return s;
}

// Point light: E = I cos(theta) / r^2, reflected radiance L = rho E / pi, checked pixel by pixel.
TEST(ReferenceDirect, PointLightOverDiffusePlane) {
    constexpr float kRho = 0.5f, kView = 2.0f;
    constexpr int kSize = 32;
    const glm::vec3 lightPos(0.3f, 1.0f, -0.2f);
    constexpr float kIntensity = 2.0f;  // W/sr
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, kView);
    Light light;
    light.type = LightType::Point;
    light.position = lightPos;
    light.intensity = glm::vec3(kIntensity);
    scene.lights.push_back(light);
    const PathTracerResult r = render(scene, directOnly(kSize, 256));
    const auto radiance = [&](double x, double z) {
        const double dx = x - lightPos.x, dy = lightPos.y, dz = z - lightPos.z;
        const double r2 = dx * dx + dy * dy + dz * dz;
        const double cosTheta = dy / std::sqrt(r2);
        return kRho / glm::pi<double>() * kIntensity * cosTheta / r2;
    };
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px)
            expectPixelMatches(r.radiance.at(px, py).g, footprint(px, py, kSize, kView, radiance), 256, "point", px, py);
}

// Spot light: I(alpha) = I0 cos^n(alpha) inside the cutoff, 0 outside. Pixels whose footprint
// straddles the cutoff circle are skipped (the midpoint rule cannot place the edge exactly); pixels
// wholly outside must be exactly black.
TEST(ReferenceDirect, SpotLightOverDiffusePlane) {
    constexpr float kRho = 0.7f, kView = 4.0f, kHeight = 1.5f, kExponent = 4.0f;
    constexpr int kSize = 32;
    const float cutoff = glm::radians(40.0f);
    constexpr float kIntensity = 3.0f;
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, kView);
    Light light;
    light.type = LightType::Spot;
    light.position = glm::vec3(0.0f, kHeight, 0.0f);
    light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    light.intensity = glm::vec3(kIntensity);
    light.cutoffAngle = cutoff;
    light.falloffExponent = kExponent;
    scene.lights.push_back(light);
    const PathTracerResult r = render(scene, directOnly(kSize, 256));
    const double cosCutoff = std::cos(static_cast<double>(cutoff));
    const auto cosAlpha = [&](double x, double z) { return kHeight / std::sqrt(x * x + z * z + kHeight * kHeight); };
    const auto radiance = [&](double x, double z) {
        const double c = cosAlpha(x, z);
        if (c <= cosCutoff) return 0.0;
        const double r2 = x * x + z * z + kHeight * kHeight;
        return kRho / glm::pi<double>() * kIntensity * std::pow(c, kExponent) * c / r2;
    };
    int inside = 0, outside = 0;
    const double pixel = kView / kSize;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            bool anyIn = false, anyOut = false;
            for (int corner = 0; corner < 4; ++corner) {
                const double x = -0.5 * kView + (px + (corner & 1)) * pixel;
                const double z = -0.5 * kView + (py + (corner >> 1)) * pixel;
                (cosAlpha(x, z) > cosCutoff ? anyIn : anyOut) = true;
            }
            // The circle can cross a pixel edge without containing a corner only near its extreme
            // points; a one-pixel margin around straddling pixels keeps clear of those.
            if (anyIn && anyOut) continue;
            const Footprint fp = footprint(px, py, kSize, kView, radiance);
            if (anyOut) {
                bool nearEdge = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const double x = -0.5 * kView + (px + 0.5 + dx) * pixel;
                        const double z = -0.5 * kView + (py + 0.5 + dy) * pixel;
                        nearEdge |= cosAlpha(x, z) > cosCutoff;
                    }
                if (nearEdge) continue;
                EXPECT_EQ(r.radiance.at(px, py).r, 0.0f) << "pixel " << px << "," << py << " outside the cone";
                ++outside;
            } else {
                expectPixelMatches(r.radiance.at(px, py).r, fp, 256, "spot", px, py);
                ++inside;
            }
        }
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 100);
}

// --frame F renders the scene at time F / frameRate: a point light whose track moves it 0.5 m along
// x in 1 s is rendered at frame 30 (30 fps) where the track puts it, pixel by pixel as above.
TEST(ReferenceDirect, RendersTheSceneAtTheFramesTime) {
    constexpr float kRho = 0.5f, kView = 2.0f, kIntensity = 2.0f;
    constexpr int kSize = 16;
    constexpr uint32_t kSpp = 256;
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, kView);
    scene.frameRate = 30.0f;
    Light light;
    light.type = LightType::Point;
    light.position = glm::vec3(-0.2f, 1.0f, 0.1f);
    light.intensity = glm::vec3(kIntensity);
    TransformKey k0, k1;
    k0.time = 0.0f;
    k1.time = 1.0f;
    k1.translation = glm::vec3(0.5f, 0.0f, 0.0f);
    light.animation.keys = {k0, k1};
    light.animation.loop = false;
    scene.lights.push_back(light);
    PathTracerSettings s = directOnly(kSize, kSpp);
    s.frame = 30;
    const PathTracerResult r = render(scene, s);
    const glm::vec3 moved = light.position + glm::vec3(0.5f, 0.0f, 0.0f);
    const auto radiance = [&](double x, double z) {
        const double dx = x - moved.x, dy = moved.y, dz = z - moved.z;
        const double r2 = dx * dx + dy * dy + dz * dz;
        return kRho / glm::pi<double>() * kIntensity * (dy / std::sqrt(r2)) / r2;
    };
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px)
            expectPixelMatches(r.radiance.at(px, py).g, footprint(px, py, kSize, kView, radiance), kSpp, "frame 30",
                               px, py);
}

// Directional light: E = E_perp cos(theta) everywhere, no variation, so no noise either: the only
// error is float rounding (1e-5 relative).
TEST(ReferenceDirect, DirectionalLightOverDiffusePlane) {
    constexpr float kRho = 0.6f, kIrradiance = 3.0f;
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, 2.0f);
    Light light;
    light.type = LightType::Directional;
    light.direction = glm::normalize(glm::vec3(1.0f, -2.0f, 0.5f));
    light.irradiance = glm::vec3(kIrradiance);
    scene.lights.push_back(light);
    const PathTracerResult r = render(scene, directOnly(8, 16));
    const double expected = kRho / glm::pi<double>() * kIrradiance * (-light.direction.y);
    for (const glm::vec3& p : r.radiance.pixels()) EXPECT_NEAR(p.b / expected, 1.0, 1e-5);
}

// Irradiance under a corner of an a x b Lambertian rectangle of radiance L at distance c, parallel
// to the receiver (analytic-tests.md): E = pi L F.
double cornerIrradiance(double a, double b, double c, double radiance) {
    const double A = a / c, B = b / c;
    const double sa = std::sqrt(1.0 + A * A), sb = std::sqrt(1.0 + B * B);
    const double f = (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * glm::pi<double>());
    return glm::pi<double>() * radiance * f;
}

// A rectangular area light facing down over the plane; every pixel of a small view under it is
// compared with the sum of the four corner rectangles meeting above that point. Light sampling and
// BSDF sampling are both active (MIS). 4096 spp on 16 x 16 pixels: the image-mean standard error is
// asserted below 0.1%, so 0.5% on the mean ratio is a 5-sigma bound; per pixel, 3%.
TEST(ReferenceDirect, AreaLightOverDiffusePlane) {
    constexpr float kRho = 0.8f, kView = 0.4f, kHeight = 0.6f, kRadiance = 5.0f;
    constexpr float kSizeX = 0.5f, kSizeZ = 0.4f;
    constexpr int kSize = 16;
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, kView);
    Light light;
    light.type = LightType::Area;
    light.position = glm::vec3(0.05f, kHeight, -0.03f);
    light.edgeU = glm::vec3(kSizeX, 0.0f, 0.0f);
    light.edgeV = glm::vec3(0.0f, 0.0f, kSizeZ);  // cross(+x, +z) = -y: emits downwards
    light.radiance = glm::vec3(kRadiance);
    scene.lights.push_back(light);
    const PathTracerResult r = render(scene, directOnly(kSize, 4096));
    EXPECT_LT(r.noise.imageRelativeError, 0.001);
    const double x0 = light.position.x - 0.5 * kSizeX, x1 = light.position.x + 0.5 * kSizeX;
    const double z0 = light.position.z - 0.5 * kSizeZ, z1 = light.position.z + 0.5 * kSizeZ;
    const auto radiance = [&](double x, double z) {
        const double e = cornerIrradiance(x1 - x, z1 - z, kHeight, kRadiance) +
                         cornerIrradiance(x - x0, z1 - z, kHeight, kRadiance) +
                         cornerIrradiance(x1 - x, z - z0, kHeight, kRadiance) +
                         cornerIrradiance(x - x0, z - z0, kHeight, kRadiance);
        return kRho / glm::pi<double>() * e;
    };
    double ratioSum = 0.0;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            const double ratio = r.radiance.at(px, py).g / footprintAverage(px, py, kSize, kView, radiance);
            EXPECT_NEAR(ratio, 1.0, 0.03) << "pixel " << px << "," << py;
            ratioSum += ratio;
        }
    EXPECT_NEAR(ratioSum / (kSize * kSize), 1.0, 0.005);
}

// ---- Other closed-form and invariant checks --------------------------------------------------------

// White furnace (rho = 1): with K bounces every pixel reads (K + 2) Le exactly in expectation, and a
// correct transport keeps the image uniform. Same 5-sigma reasoning as the furnace cases.
TEST(ReferenceFurnaceWhite, StaysUniform) {
    const Scene scene = testscenes::furnaceRoom(1.0f, 1.0f);
    PathTracerSettings s;
    s.width = s.height = 16;
    s.samplesPerPixel = 1024;
    s.bounces = 4;
    const PathTracerResult r = render(scene, s);
    EXPECT_LT(r.noise.imageRelativeError, 0.001);
    EXPECT_NEAR(meanLuminance(r.radiance) / 6.0, 1.0, 0.005);
}

// Sphere furnace (analytic-tests.md): R = 1, rho = 0.5, a point light of I = pi at the centre.
// Direct radiance is rho I / (pi R^2) = 0.5, each bounce multiplies by rho: 0.75 with one bounce,
// 1.0 with all. The sphere is a 128 x 64 polyhedron, whose faces lie up to 0.06% closer to the
// centre than R: the direct light is up to 0.12% off, the interreflections of a closed uniformly
// lit surface are exact. So 0.5% is 0.12% plus at least 5 of the reported standard errors
// (asserted below 0.075%; with a delta light and uniform irradiance the bounded scopes are almost
// noise-free, only Russian roulette in the unbounded case needs many samples).
TEST(ReferenceSphereFurnace, MatchesClosedForm) {
    const Scene scene = testscenes::sphereFurnace(0.5f, glm::pi<float>(), 128, 64);
    struct Case {
        int bounces;
        uint32_t spp;
        double expected;
    };
    for (const Case& c : {Case{0, 64, 0.5}, Case{1, 64, 0.75}, Case{PathTracerSettings::kUnbounded, 3072, 1.0}}) {
        PathTracerSettings s;
        s.width = s.height = 16;
        s.samplesPerPixel = c.spp;
        s.bounces = c.bounces;
        const PathTracerResult r = render(scene, s);
        EXPECT_LT(r.noise.imageRelativeError, 0.00075) << "bounces " << c.bounces;
        EXPECT_NEAR(meanLuminance(r.radiance) / c.expected, 1.0, 0.005) << "bounces " << c.bounces;
    }
}

// Two-sided materials shade both faces: the same furnace with two-sided walls reads the same.
TEST(ReferenceFurnaceTwoSided, MatchesOneSided) {
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f, true);
    PathTracerSettings s;
    s.width = s.height = 16;
    s.samplesPerPixel = 1024;
    s.bounces = 1;
    const PathTracerResult r = render(scene, s);
    EXPECT_LT(r.noise.imageRelativeError, 0.001);
    EXPECT_NEAR(meanLuminance(r.radiance) / furnaceRadiance(0.5, 1.0, 2), 1.0, 0.005);
}

// --diffuse-only keeps the Lambert lobe alone after the first reflection. In a furnace of pure
// metal (metallic 1, so the Lambert lobe is black) light can then reflect only once, so the
// diffuse-only image with 5 bounces must equal the full image with 0 bounces, while the full image
// with 5 bounces is brighter. Means compared within 5 combined standard errors.
TEST(ReferenceScopes, DiffuseOnlyDropsGlossyAfterFirstHit) {
    Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    scene.materials[0].metallic = 1.0f;
    scene.materials[0].roughness = 0.5f;
    PathTracerSettings s;
    s.width = s.height = 16;
    s.samplesPerPixel = 512;
    s.bounces = 5;
    s.diffuseOnly = true;
    const PathTracerResult diffuseOnly = render(scene, s);
    s.diffuseOnly = false;
    const PathTracerResult full = render(scene, s);
    s.bounces = 0;
    const PathTracerResult direct = render(scene, s);
    const double a = meanLuminance(diffuseOnly.radiance), b = meanLuminance(direct.radiance);
    const double sigma = std::hypot(a * diffuseOnly.noise.imageRelativeError, b * direct.noise.imageRelativeError);
    EXPECT_NEAR(a, b, 5.0 * sigma);
    EXPECT_GT(meanLuminance(full.radiance), 1.1 * b);
}

// The rasteriser culls back faces of one-sided surfaces, so the camera sees through them; they
// still cast shadows. A one-sided square at 1 m facing down, over a plane lit from straight above:
// seen from above, the square is invisible and its shadow is black (direct light only).
TEST(ReferenceVisibility, CameraSeesThroughBackFacesButTheyShadow) {
    constexpr float kRho = 0.5f, kIrradiance = 2.0f, kView = 4.0f;
    constexpr int kSize = 16;
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, kView);
    Mesh square;
    square.name = "square";
    testscenes::addQuad(square, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 2.0f}, {2.0f, 0.0f, 0.0f});  // faces +y...
    for (glm::vec3& n : square.normals) n = -n;
    std::swap(square.indices[1], square.indices[2]);  // ...turned to face -y
    std::swap(square.indices[4], square.indices[5]);
    scene.meshes.push_back(square);
    Object o;
    o.name = "square";
    o.mesh = 1;
    scene.objects.push_back(o);
    Light light;
    light.type = LightType::Directional;
    light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    light.irradiance = glm::vec3(kIrradiance);
    scene.lights.push_back(light);
    const PathTracerResult oneSided = render(scene, directOnly(kSize, 4));
    const double lit = kRho * kIrradiance / glm::pi<double>();
    // Pixels 4..11 lie under the square (x, z in [-1, 1]), 0..3 and 12..15 outside it.
    EXPECT_EQ(oneSided.radiance.at(8, 8).r, 0.0f);
    EXPECT_EQ(oneSided.radiance.at(5, 10).r, 0.0f);
    EXPECT_NEAR(oneSided.radiance.at(1, 1).r / lit, 1.0, 1e-5);
    EXPECT_NEAR(oneSided.radiance.at(14, 8).r / lit, 1.0, 1e-5);
    // Two-sided, the camera sees the square's lit top instead.
    Material twoSided;
    twoSided.name = "two-sided";
    twoSided.baseColor = glm::vec3(0.25f);
    twoSided.twoSided = true;
    scene.materials.push_back(twoSided);
    scene.objects[1].material = 1;
    const PathTracerResult seen = render(scene, directOnly(kSize, 4));
    EXPECT_NEAR(seen.radiance.at(8, 8).r / (0.25 * kIrradiance / glm::pi<double>()), 1.0, 1e-5);
}

// An area light is a one-sided emitter, not a mesh: from its emitting side it is an opaque surface
// of radiance L (it hides what is behind it and casts shadows), from behind it is not there. A 0.8 m
// square at 1 m, under a directional light travelling along (1, -1, 0): its shadow, if it casts one,
// is centred 1 m to the side, at x = 1 (pixels 11-12, rows 7-8 of the 16 x 16 view). The panel is
// dim (1e-3 W/(m^2 sr)) so that it is almost never chosen for light sampling (choice by flux) and
// the sunlit pixels are exact; its own light on the plane stays below 1e-3 of the sunlight.
TEST(ReferenceVisibility, AreaLightIsOneSidedAndNotAMesh) {
    constexpr float kRho = 0.5f, kIrradiance = 2.0f, kView = 4.0f, kRadiance = 1e-3f;
    constexpr int kSize = 16;
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, kView);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
    sun.irradiance = glm::vec3(kIrradiance);
    scene.lights.push_back(sun);
    Light panel;
    panel.type = LightType::Area;
    panel.position = {0.0f, 1.0f, 0.0f};
    panel.edgeU = {0.0f, 0.0f, 0.8f};  // cross(+z, +x) = +y: emits upwards, towards the camera
    panel.edgeV = {0.8f, 0.0f, 0.0f};
    panel.radiance = glm::vec3(kRadiance);
    scene.lights.push_back(panel);
    const double sunlit = kRho * kIrradiance * (1.0 / std::sqrt(2.0)) / glm::pi<double>();

    const PathTracerResult up = render(scene, directOnly(kSize, 16));
    EXPECT_NEAR(up.radiance.at(8, 8).r, kRadiance, 1e-5f) << "the camera sees the emitting side";
    EXPECT_NEAR(up.radiance.at(11, 7).r / sunlit, 1.0, 1e-5) << "no shadow from behind";
    EXPECT_NEAR(up.radiance.at(12, 8).r / sunlit, 1.0, 1e-5);

    std::swap(scene.lights[1].edgeU, scene.lights[1].edgeV);  // now emitting downwards
    const PathTracerResult down = render(scene, directOnly(kSize, 16));
    EXPECT_LT(down.radiance.at(11, 7).r, 1e-3 * sunlit) << "the emitting side casts a shadow";
    EXPECT_LT(down.radiance.at(12, 8).r, 1e-3 * sunlit);
    // Seen from behind it is not there: the camera sees the sunlit plane under it.
    EXPECT_NEAR(down.radiance.at(8, 8).r / sunlit, 1.0, 1e-3);
}

// The base-colour texture convention: uv (0, 0) is the first row of the stored image (its top),
// bilinear between texel centres. A 1 x 2 texture (row 0 dark, row 1 bright) on a 4 m quad whose v
// runs along world x, lit so that L = texel value: bilinear between the row centres at v = 1/4 and
// v = 3/4 is linear, so a pixel's footprint average is the texture at the footprint's mean v.
TEST(ReferenceTexture, RowZeroIsVZero) {
    constexpr float kDark = 0.2f, kBright = 0.8f, kView = 4.0f;
    constexpr int kSize = 16;
    Scene scene = testscenes::planeUnderOrthoCamera(1.0f, kView);
    scene.meshes[0] = Mesh{};
    testscenes::addQuad(scene.meshes[0], {0, 0, 0}, {0, 0, 4}, {4, 0, 0});  // uv.x along z, uv.y along x
    scene.meshes[0].name = "textured";
    TextureImage texture;
    texture.name = "rows";
    texture.image = Image(1, 2);
    texture.image.at(0, 0) = glm::vec3(kDark);
    texture.image.at(0, 1) = glm::vec3(kBright);
    scene.textures.push_back(texture);
    scene.materials[0].baseColorTexture = 0;
    Light light;
    light.type = LightType::Directional;
    light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    light.irradiance = glm::vec3(glm::pi<float>());  // L = texel * E / pi = texel
    scene.lights.push_back(light);
    const PathTracerResult r = render(scene, directOnly(kSize, 4096));
    for (int px : {4, 5, 8, 10, 11}) {
        // Pixel column px covers x in [-2 + px/4, -2 + (px+1)/4]; v = (x + 2) / 4.
        const double v = (px + 0.5) / kSize;
        const double t = 2.0 * v - 0.5;  // weight of row 1, linear between the row centres
        const double expected = kDark * (1.0 - t) + kBright * t;
        double column = 0.0;
        for (int py = 0; py < kSize; ++py) column += r.radiance.at(px, py).r;
        // Jitter noise: the value spans 0.6 * 0.0625 over a pixel, std 0.011; over 16 pixels x 4096
        // samples the mean's error is 4e-5, far inside 0.5%.
        EXPECT_NEAR(column / kSize / expected, 1.0, 0.005) << "column " << px;
    }
}

// ---- Determinism, time limit, bad input -------------------------------------------------------------

TEST(ReferenceDeterminism, SameSeedSameImageWhateverTheThreads) {
    const Scene scene = testscenes::furnaceRoom(0.7f, 1.0f);
    PathTracerSettings s;
    s.width = 40;  // not a multiple of the tile or packet size
    s.height = 23;
    s.samplesPerPixel = 8;
    s.seed = 1234;
    s.threads = 1;
    const PathTracerResult one = render(scene, s);
    s.threads = 2;
    const PathTracerResult two = render(scene, s);
    ASSERT_EQ(one.radiance.pixelCount(), two.radiance.pixelCount());
    EXPECT_EQ(std::memcmp(one.radiance.data(), two.radiance.data(), one.radiance.pixelCount() * sizeof(glm::vec3)), 0);
    EXPECT_EQ(one.rays, two.rays);
    s.seed = 1235;
    const PathTracerResult other = render(scene, s);
    EXPECT_NE(std::memcmp(one.radiance.data(), other.radiance.data(), one.radiance.pixelCount() * sizeof(glm::vec3)), 0);
}

// The vectorised kernel performs scatter()'s floating-point operations in the same order, so with
// the same random numbers the images must be bit-identical, in every scope. The built-in
// cornell-box-area has area-light rectangles, one-sided walls and roulette; the furnace room's
// lights are emissive triangles (MIS on both strategies); cornell-box, two-rooms and atrium bring a
// spot, a point and a directional light, and atrium's columns have vertex normals.
TEST(ReferenceDeterminism, VectorisedKernelEqualsScalarCode) {
    auto loaded = loadScene("cornell-box-area");
    ASSERT_TRUE(loaded.ok());
    auto spot = loadScene("cornell-box");  // a spot light
    ASSERT_TRUE(spot.ok());
    auto point = loadScene("two-rooms");  // a point light
    ASSERT_TRUE(point.ok());
    auto sun = loadScene("atrium", {{"triangles", "1916"}});  // a directional light, smooth columns
    ASSERT_TRUE(sun.ok());
    struct Case {
        const char* name;
        const Scene* scene;
        int bounces;
        bool indirectOnly, diffuseOnly;
    };
    const Scene furnace = testscenes::furnaceRoom(0.7f, 1.0f);
    for (const Case& c : {Case{"cornell", &*loaded, PathTracerSettings::kUnbounded, false, false},
                          Case{"cornell direct", &*loaded, 0, false, false},
                          Case{"cornell indirect", &*loaded, 3, true, true},
                          Case{"furnace", &furnace, PathTracerSettings::kUnbounded, false, false},
                          Case{"furnace indirect", &furnace, 2, true, false},
                          Case{"spot", &*spot, PathTracerSettings::kUnbounded, false, false},
                          Case{"point", &*point, 2, false, false},
                          Case{"directional, smooth", &*sun, PathTracerSettings::kUnbounded, false, false}}) {
        PathTracerSettings s;
        s.width = 37;  // not a multiple of the packet size: partial packets
        s.height = 29;
        s.samplesPerPixel = 6;
        s.bounces = c.bounces;
        s.indirectOnly = c.indirectOnly;
        s.diffuseOnly = c.diffuseOnly;
        s.seed = 99;
        const PathTracerResult vectorised = render(*c.scene, s);
        s.vectorized = false;
        const PathTracerResult scalar = render(*c.scene, s);
        ASSERT_EQ(vectorised.radiance.pixelCount(), scalar.radiance.pixelCount());
        EXPECT_GT(meanLuminance(scalar.radiance), 0.0) << c.name;
        EXPECT_EQ(std::memcmp(vectorised.radiance.data(), scalar.radiance.data(),
                              scalar.radiance.pixelCount() * sizeof(glm::vec3)),
                  0)
            << c.name;
        EXPECT_EQ(vectorised.rays, scalar.rays) << c.name;
    }
}

TEST(ReferenceTimeLimit, KeepsTheCompletePassesWithinBudget) {
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    PathTracerSettings s;
    s.width = s.height = 128;  // passes of 2^20 paths: 64 spp each
    s.samplesPerPixel = 1000000;
    s.timeLimitSeconds = 1.0;
    auto tracer = PathTracer::create(scene, s);
    ASSERT_TRUE(tracer.ok());
    uint32_t lastReported = 0;
    const PathTracerResult r = tracer->render([&](const RenderProgress& p) { lastReported = p.samplesDone; });
    EXPECT_TRUE(r.stoppedByTimeLimit);
    EXPECT_GE(r.samplesPerPixel, 64u);
    EXPECT_EQ(r.samplesPerPixel % 64u, 0u) << "whole passes only";
    EXPECT_EQ(r.samplesPerPixel, lastReported);
    EXPECT_EQ(r.paths, uint64_t{128} * 128 * r.samplesPerPixel);
    // After the first pass (which always completes), work stops at the first tile that starts
    // past the deadline: a 16 x 16 tile at 64 spp is 16384 paths, a few tens of ms; 0.5 s allows
    // for a machine busy with other jobs.
    if (r.samplesPerPixel > 64u) {
        EXPECT_LT(r.renderSeconds, s.timeLimitSeconds + 0.5);
    }
    EXPECT_NEAR(meanLuminance(r.radiance) / 2.0, 1.0, 0.05);  // converging to Le / (1 - rho)
    // The abandoned pass left no trace: the image equals a render of exactly the samples reached.
    PathTracerSettings same = s;
    same.samplesPerPixel = r.samplesPerPixel;
    same.timeLimitSeconds = 0.0;
    const PathTracerResult exact = render(scene, same);
    EXPECT_EQ(std::memcmp(exact.radiance.data(), r.radiance.data(), r.radiance.pixelCount() * sizeof(glm::vec3)), 0);
    EXPECT_EQ(exact.rays, r.rays);
}

TEST(ReferenceBadInput, SceneWithoutLightIsAnError) {
    Scene scene = testscenes::furnaceRoom(0.5f, 0.0f);  // nothing emits
    auto tracer = PathTracer::create(scene, PathTracerSettings{});
    ASSERT_FALSE(tracer.ok());
    EXPECT_NE(tracer.error().message.find("no light source"), std::string::npos) << tracer.error().message;
    Light dark;  // a light of zero power does not count
    dark.type = LightType::Point;
    scene.lights.push_back(dark);
    EXPECT_FALSE(PathTracer::create(scene, PathTracerSettings{}).ok());
}

TEST(ReferenceBadInput, SettingsAreChecked) {
    const Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    PathTracerSettings s;
    s.samplesPerPixel = 0;
    auto zeroSpp = PathTracer::create(scene, s);
    ASSERT_FALSE(zeroSpp.ok());
    EXPECT_NE(zeroSpp.error().message.find("spp"), std::string::npos);
    s = {};
    s.width = 0;
    EXPECT_FALSE(PathTracer::create(scene, s).ok());
    s = {};
    s.bounces = -2;
    EXPECT_FALSE(PathTracer::create(scene, s).ok());
    s = {};
    s.threads = -1;
    EXPECT_FALSE(PathTracer::create(scene, s).ok());
    s = {};
    s.timeLimitSeconds = std::nan("");
    EXPECT_FALSE(PathTracer::create(scene, s).ok());
}

TEST(ReferenceBadInput, NonFiniteTextureIsAnError) {
    Scene scene = testscenes::furnaceRoom(0.5f, 1.0f);
    TextureImage texture;
    texture.name = "broken.exr";
    texture.image = Image(2, 2, glm::vec3(0.5f));
    texture.image.at(1, 0).g = std::numeric_limits<float>::infinity();
    scene.textures.push_back(texture);
    scene.materials[0].baseColorTexture = 0;
    auto tracer = PathTracer::create(scene, PathTracerSettings{});
    ASSERT_FALSE(tracer.ok());
    EXPECT_NE(tracer.error().message.find("broken.exr"), std::string::npos) << tracer.error().message;
}

}  // namespace

namespace {

// The floor (albedo 0.5) seen around the origin by an orthographic camera from 45 degrees above +x, and
// one square (side `side`, albedo 1) at 1 m from the origin in direction `dir`, facing it, lit by a
// point light halfway: the floor's indirect light (--bounces 1 --indirect-only) is the square's.
Scene floorUnderASquare(glm::vec3 dir, float side) {
    Scene scene = testscenes::planeUnderOrthoCamera(0.5f, 0.02f);
    dir = glm::normalize(dir);
    const glm::vec3 helper = std::abs(dir.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 u = side * glm::normalize(glm::cross(helper, dir)), v = side * glm::normalize(glm::cross(dir, u));
    Mesh square;
    square.name = "square";
    testscenes::addQuad(square, dir, v, u);  // front side cross(v, u) = -dir: towards the origin
    Material white;
    white.name = "white";
    white.baseColor = glm::vec3(1.0f);
    testscenes::addObject(scene, square, white);
    Light l;
    l.type = LightType::Point;
    l.name = "bulb";
    l.position = 0.5f * dir;
    l.intensity = glm::vec3(1.0f);
    scene.lights.push_back(l);
    scene.camera.position = {5.0f, 5.0f, 0.0f};
    scene.camera.up = {0.0f, 1.0f, 0.0f};
    return scene;
}

PathTracerSettings coneQuadratureSettings(bool cones) {
    PathTracerSettings s;
    s.width = s.height = 8;
    s.samplesPerPixel = 16384;
    s.bounces = 1;
    s.indirectOnly = true;
    s.seed = 3;
    if (cones) s.firstReflectionCones = vct::diffuseQuadratureCones();
    return s;
}

}  // namespace

// PathTracerSettings::firstReflectionCones with vct's six cones (`bounce reference --first-reflection
// vct-cones`, vct.md "The six cones' own bias"): the quadrature rho/pi sum W_k mean_k(L).
TEST(ReferenceConeQuadrature, UniformFieldIsExactSourceOnTheNormalIsWeightedAndAGapIsDark) {
    // A uniform field (the furnace, Le = 1, rho = 0.5, one bounce): sum W_k = pi makes it exact.
    {
        PathTracerSettings s = coneQuadratureSettings(true);
        s.width = s.height = 16;
        s.samplesPerPixel = 1024;
        const PathTracerResult r = render(testscenes::furnaceRoom(0.5f, 1.0f), s);
        // Indirect-only, one bounce: rho^2 Le = 0.25 (furnaceRadiance(2) - furnaceRadiance(1)); measured
        // 0.24994; 0.5 % as the furnace tests (the cosine lobe's own bound).
        EXPECT_NEAR(meanLuminance(r.radiance), 0.25, 0.00125);
    }
    // A 0.6 m square straight above (within 23 degrees of the normal, in the central cone only): the
    // quadrature weighs its light by W_0 / Omega_0 = (pi/4) / (2 pi (1 - cos 30)) = 0.9330 instead of
    // cos theta, which the integral below averages over the square (point-light irradiance, solid angle).
    {
        const Scene scene = floorUnderASquare({0, 1, 0}, 0.6f);
        const double quad = meanLuminance(render(scene, coneQuadratureSettings(true)).radiance);
        const double exact = meanLuminance(render(scene, coneQuadratureSettings(false)).radiance);
        double withCos = 0.0, without = 0.0;
        constexpr int kSteps = 200;
        for (int j = 0; j < kSteps; ++j)
            for (int i = 0; i < kSteps; ++i) {
                const glm::dvec3 p(0.6 * ((i + 0.5) / kSteps - 0.5), 1.0, 0.6 * ((j + 0.5) / kSteps - 0.5));
                const glm::dvec3 toLight = glm::dvec3(0.0, 0.5, 0.0) - p;
                const double radiance = (-toLight.y / glm::length(toLight)) / glm::dot(toLight, toLight);  // cos / r^2
                const double d = glm::length(p), cosAtSquare = p.y / d, solidAngle = cosAtSquare / (d * d);
                withCos += radiance * solidAngle * (p.y / d);
                without += radiance * solidAngle;
            }
        const double expected = 1.0 / (8.0 * (1.0 - std::cos(glm::radians(30.0)))) * without / withCos;
        std::printf("square on the normal: quadrature / cosine %.4f, expected %.4f\n", quad / exact, expected);
        // 16384 spp x 64 pixels each: measured 0.9535 / 0.9579 / 0.9701 with seeds 3 / 5 / 11 against
        // 0.9563 (a spread of 0.8 %); bound 2 %. The cosine lobe (1.0), a ring cone's weight (0.60) or
        // no cone (0) fall outside.
        EXPECT_NEAR(quad / exact, expected, 0.02);
    }
    // A 0.1 m square 80 degrees from the normal midway in azimuth between two ring cones (39 degrees from
    // either axis, 9 past their 30-degree radius; its corners reach 4 degrees): the six cones do not
    // see it at all; the cosine lobe does. (At 60 degrees the gap is 0.6 degrees wide.)
    {
        const float s80 = std::sin(glm::radians(80.0f)), c80 = std::cos(glm::radians(80.0f));
        const float c36 = std::cos(glm::radians(36.0f)), s36 = std::sin(glm::radians(36.0f));
        // Cone directions (dx, dy, dz) map to (-dz, dy, dx) on the floor (helper +x: tx = +z, tz = -x).
        const Scene scene = floorUnderASquare({-s80 * c36, c80, s80 * s36}, 0.1f);
        const double quad = meanLuminance(render(scene, coneQuadratureSettings(true)).radiance);
        const double exact = meanLuminance(render(scene, coneQuadratureSettings(false)).radiance);
        std::printf("gap: quadrature %.6g, cosine %.6g\n", quad, exact);
        EXPECT_GT(exact, 0.0);
        EXPECT_EQ(quad, 0.0);
    }
}
