// Photon mapping (src/reference/PhotonMap.h): photon power against the lights' flux, the kd-tree
// gather against an analytic density, the image against analytic direct light and against the path
// tracer of the same scope. Every tolerance says where it comes from; each test was checked to fail
// under a deliberate mutation of the code (docs/techniques/photon-map.md, "Tests").
#include "ReferenceTestScenes.h"
#include "metrics/ErrorMetrics.h"
#include "reference/PathTracer.h"
#include "reference/PhotonMap.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <array>
#include <cmath>
#include <random>

namespace bounce {
namespace {

constexpr double kPi = glm::pi<double>();

PhotonMapper makeMapper(const Scene& scene, const PhotonMapSettings& settings) {
    auto mapper = PhotonMapper::create(scene, settings);
    EXPECT_TRUE(mapper) << (mapper ? "" : mapper.error().message);
    return std::move(mapper).value();
}

glm::dvec3 storedPower(const std::vector<Photon>& photons) {
    glm::dvec3 sum(0.0);
    for (const Photon& p : photons) sum += glm::dvec3(p.power);
    return sum;
}

// The closed cube room of half-size 1 m (inner faces of albedo rho) with the camera at its centre.
Scene room(glm::vec3 albedo) {
    Scene scene = testscenes::furnaceRoom(0.5f, 0.0f);
    scene.materials[0].baseColor = albedo;
    return scene;
}

Light pointLight(glm::vec3 position, float intensity) {
    Light light;
    light.type = LightType::Point;
    light.position = position;
    light.intensity = glm::vec3(intensity);
    return light;
}

PhotonMapSettings scope(int bounces, bool indirectOnly, uint64_t photons) {
    PhotonMapSettings s;
    s.width = s.height = 32;
    s.bounces = bounces;
    s.indirectOnly = indirectOnly;
    s.photons = photons;
    s.k = 32;
    s.samplesPerPixel = 4;
    return s;
}

// Photons stored at first hits (bounces 0, full scope) in a closed room: every photon hits a wall
// once, so the stored power is each light's flux exactly, up to float rounding of the per-photon
// power (one float per photon, ~6e-8 relative) summed in double: 1e-5 relative is far above that
// and far below any real error (a lost or doubled photon in 50,000 is 2e-5; halving power is 0.5).
TEST(PhotonMapPower, FirstHitsSumToTheLightFlux) {
    constexpr uint64_t kPhotons = 50'000;
    struct Case {
        const char* name;
        Scene scene;
        double flux;
    };
    std::vector<Case> cases;
    {
        Scene s = room(glm::vec3(0.5f));
        s.lights.push_back(pointLight({0.3f, 0.5f, -0.2f}, 2.0f));
        cases.push_back({"point", s, 4.0 * kPi * 2.0});
    }
    {
        Scene s = room(glm::vec3(0.5f));
        Light spot = pointLight({0.0f, 0.9f, 0.0f}, 3.0f);
        spot.type = LightType::Spot;
        spot.direction = {0.0f, -1.0f, 0.0f};
        spot.cutoffAngle = 1.0f;
        spot.falloffExponent = 2.0f;
        s.lights.push_back(spot);
        cases.push_back({"spot", s, 3.0 * 2.0 * kPi * (1.0 - std::pow(std::cos(1.0), 3.0)) / 3.0});
    }
    {
        Scene s = room(glm::vec3(0.5f));
        Light area;
        area.type = LightType::Area;
        area.position = {0.0f, 0.9f, 0.0f};
        area.edgeU = {0.5f, 0.0f, 0.0f};
        area.edgeV = {0.0f, 0.0f, 0.4f};  // cross(edgeU, edgeV) points down
        area.radiance = glm::vec3(5.0f);
        s.lights.push_back(area);
        cases.push_back({"area", s, kPi * 5.0 * 0.2});
    }
    {
        // A textured two-sided area light: both faces emit, flux 2 pi L A mean(texture). The texture is
        // grey, so each photon's texel / pdf is the texture's mean exactly and the sum stays exact.
        Scene s = room(glm::vec3(0.5f));
        Light area;
        area.type = LightType::Area;
        area.position = {0.1f, 0.2f, 0.0f};
        area.edgeU = {0.5f, 0.0f, 0.0f};
        area.edgeV = {0.0f, 0.2f, 0.3f};
        area.radiance = glm::vec3(5.0f);
        area.twoSided = true;
        Image texture(4, 2, glm::vec3(0.0f));
        texture.at(0, 0) = glm::vec3(1.0f);
        texture.at(3, 0) = glm::vec3(0.25f);
        texture.at(2, 1) = glm::vec3(3.0f);  // mean (1 + 0.25 + 3) / 8
        area.texture.kind = AreaTexture::Kind::Images;
        area.texture.frames = {0};
        s.textures.push_back({"grey", texture});
        s.lights.push_back(area);
        cases.push_back({"textured two-sided area", s, 2.0 * kPi * 5.0 * area.area() * (4.25 / 8.0)});
    }
    {
        // The same walls with a uniform emission texture of 1/2: every photon carries half the power.
        Scene s = testscenes::furnaceRoom(0.5f, 0.25f);
        s.textures.push_back({"half", Image(2, 2, glm::vec3(0.5f))});
        s.materials[0].emissionTexture = 0;
        cases.push_back({"emission-textured", s, kPi * 0.25 * 24.0 * 0.5});
    }
    {
        // Emissive walls (the light list's triangles): 24 m^2 emitting Le = 0.25 inwards.
        Scene s = testscenes::furnaceRoom(0.5f, 0.25f);
        cases.push_back({"emissive", s, kPi * 0.25 * 24.0});
    }
    for (const Case& c : cases) {
        const PhotonMapper mapper = makeMapper(c.scene, scope(0, false, kPhotons));
        const std::vector<Photon> photons = mapper.tracePhotons(0, kPhotons, static_cast<double>(kPhotons));
        EXPECT_EQ(photons.size(), kPhotons) << c.name << ": one stored hit per photon in a closed room";
        const glm::dvec3 sum = storedPower(photons);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(sum[ch] / c.flux, 1.0, 1e-5) << c.name << " channel " << ch;
    }
}

// One bounce with Russian roulette by albedo rho = (0.8, 0.5, 0.25): a photon survives with
// q = max(rho) = 0.8 and then carries power * rho / q, so the stored second-hit power is rho * Phi in
// expectation; the survivor count is binomial, standard deviation sqrt(q (1 - q) N) photons, i.e.
// sqrt((1 - q) / (q N)) = 0.16 % of the sum at N = 100,000 for every channel. Tolerance: 5 of those.
TEST(PhotonMapPower, OneBounceCarriesTheAlbedo) {
    constexpr uint64_t kPhotons = 100'000;
    const glm::dvec3 rho(0.8, 0.5, 0.25);
    Scene scene = room(glm::vec3(rho));
    scene.lights.push_back(pointLight({0.3f, 0.5f, -0.2f}, 2.0f));
    const double flux = 4.0 * kPi * 2.0;
    const double sigma = std::sqrt((1.0 - 0.8) / (0.8 * static_cast<double>(kPhotons)));
    {
        // Indirect only, one bounce: the second hits alone.
        const PhotonMapper mapper = makeMapper(scene, scope(1, true, kPhotons));
        const glm::dvec3 sum = storedPower(mapper.tracePhotons(0, kPhotons, static_cast<double>(kPhotons)));
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(sum[ch] / (rho[ch] * flux), 1.0, 5.0 * sigma) << "channel " << ch;
    }
    {
        // Full scope, one bounce: first and second hits, (1 + rho) Phi; the first-hit part is exact.
        const PhotonMapper mapper = makeMapper(scene, scope(1, false, kPhotons));
        const glm::dvec3 sum = storedPower(mapper.tracePhotons(0, kPhotons, static_cast<double>(kPhotons)));
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR((sum[ch] / flux - 1.0) / rho[ch], 1.0, 5.0 * sigma) << "channel " << ch;
    }
}

// A directional light of irradiance E on the 40 m x 40 m plane: photons leave a disc of the
// bounding sphere's radius R carrying pi R^2 E in all; the plane intercepts E cos(theta) A. Which
// photons hit is binomial with p = A cos / (pi R^2) ~ 0.6: relative deviation sqrt((1-p)/(p N)) =
// 0.18 % at N = 200,000; tolerance 5 of those (1 %).
TEST(PhotonMapPower, DirectionalLightOnAPlane) {
    constexpr uint64_t kPhotons = 200'000;
    Scene scene = testscenes::planeUnderOrthoCamera(0.5f, 2.0f);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.irradiance = glm::vec3(3.0f);
    scene.lights.push_back(sun);
    const double cosTheta = -static_cast<double>(sun.direction.y);
    const double expected = 3.0 * cosTheta * 40.0 * 40.0;
    const double radius = 0.5 * std::sqrt(40.0 * 40.0 * 2.0);
    const double p = 40.0 * 40.0 * cosTheta / (kPi * radius * radius);
    const double sigma = std::sqrt((1.0 - p) / (p * static_cast<double>(kPhotons)));
    const PhotonMapper mapper = makeMapper(scene, scope(0, false, kPhotons));
    const glm::dvec3 sum = storedPower(mapper.tracePhotons(0, kPhotons, static_cast<double>(kPhotons)));
    EXPECT_NEAR(sum.x / expected, 1.0, 5.0 * sigma);
}

// The kd-tree gather on a uniform field of photons on the plane z = 0 (irradiance E = 1 W/m^2),
// with two distractor layers a few millimetres away that the tangent-plane rejection must drop: the
// back of a thin wall (normal -z) and a parallel surface above (normal +z, offset 3 mm, beyond a
// tenth of the gather radius). For Poisson points the estimate (k-1)/(pi r_k^2) has mean E and
// relative standard deviation 1/sqrt(k-2); averaged over Q queries far apart (independent) that is
// 1/sqrt((k-2) Q): 0.91 % for k = 8, Q = 2000, and 0.32 % for k = 50. Tolerances are 4 of those;
// k/(pi r_k^2) would be 14 % (k = 8) too high, and keeping the distractors 11 times.
TEST(PhotonMapGather, UniformFieldGivesTheAnalyticDensity) {
    constexpr int kPerLayer = 100'000;
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Photon> photons;
    const auto layer = [&](float z, glm::vec3 normal, float power) {
        for (int i = 0; i < kPerLayer; ++i) {
            Photon p;
            p.position = {u(gen), u(gen), z};
            p.power = glm::vec3(power);
            p.incoming = normal;
            p.normal = normal;
            photons.push_back(p);
        }
    };
    const float power = 4.0f / kPerLayer;  // 4 W over 4 m^2
    layer(0.0f, {0, 0, 1}, power);
    layer(-0.002f, {0, 0, -1}, 10.0f * power);
    layer(0.003f, {0, 0, 1}, 10.0f * power);
    const PhotonMap map(std::move(photons));
    EXPECT_GE(map.memoryBytes(), 3u * kPerLayer * sizeof(Photon));

    for (int k : {8, 50}) {
        double sum = 0.0;
        constexpr int kSide = 45;  // 2025 queries 3.6 cm apart over [-0.8, 0.8]^2; r_k <= 2.5 cm
        for (int i = 0; i < kSide; ++i)
            for (int j = 0; j < kSide; ++j) {
                const glm::vec3 x(-0.8f + 1.6f * static_cast<float>(i) / (kSide - 1),
                                  -0.8f + 1.6f * static_cast<float>(j) / (kSide - 1), 0.0f);
                sum += map.irradiance(x, {0, 0, 1}, PhotonGatherParams{k, 0.0f, true}).x;
            }
        const double mean = sum / (kSide * kSide);
        EXPECT_NEAR(mean, 1.0, 4.0 / std::sqrt((k - 2.0) * kSide * kSide)) << "k = " << k;
    }
    // A radius cap below r_k: the photons inside the cap's disc over its area, still unbiased.
    // About 2 photons per disc of 5 mm, so 1/sqrt(2 * 2025) = 1.6 % relative; tolerance 4 of those.
    double sum = 0.0;
    for (int i = 0; i < 45; ++i)
        for (int j = 0; j < 45; ++j)
            sum += map.irradiance({-0.8f + 1.6f * static_cast<float>(i) / 44, -0.8f + 1.6f * static_cast<float>(j) / 44, 0.0f},
                                  {0, 0, 1}, PhotonGatherParams{50, 0.005f, true})
                       .x;
    EXPECT_NEAR(sum / (45 * 45), 1.0, 0.064);
}

// Direct light of a point light over a diffuse plane, seen from above (bounces 0, full scope: first
// hits stored): L = rho/pi * I cos(theta) / r^2 per pixel. Each estimate has relative noise
// 1/sqrt(k-2) = 13 % (k = 64), 4 per pixel; the image mean of 1024 pixels is then known to ~0.3 %,
// and the spatial bias of a gather radius of 2-5 cm against E's 1 m scale is ~0.1 %: tolerance 1.5 %
// on the mean. Per pixel, relMSE ~ 0.13^2 / 4 = 0.004 from noise: tolerance 0.01.
TEST(PhotonMapImage, PointLightOverPlaneMatchesTheAnalyticDirectLight) {
    constexpr float kRho = 0.5f, kView = 2.0f, kIntensity = 2.0f;
    constexpr int kSize = 32;
    const glm::vec3 lightPos(0.3f, 1.0f, -0.2f);
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, kView);
    scene.lights.push_back(pointLight(lightPos, kIntensity));
    PhotonMapSettings s = scope(0, false, 400'000);
    s.k = 64;
    const PhotonMapper mapper = makeMapper(scene, s);
    const PhotonMapResult r = mapper.render();
    EXPECT_EQ(r.photonsEmitted, 400'000u);
    Image expected(kSize, kSize);
    double sumImage = 0.0, sumExpected = 0.0;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            const double x = (px + 0.5) / kSize * kView - 0.5 * kView, z = (py + 0.5) / kSize * kView - 0.5 * kView;
            const double dx = x - lightPos.x, dy = lightPos.y, dz = z - lightPos.z;
            const double r2 = dx * dx + dy * dy + dz * dz;
            const double L = kRho / kPi * kIntensity * (dy / std::sqrt(r2)) / r2;
            expected.at(px, py) = glm::vec3(static_cast<float>(L));
            sumImage += r.radiance.at(px, py).y;
            sumExpected += L;
        }
    EXPECT_NEAR(sumImage / sumExpected, 1.0, 0.015);
    const auto m = compareImages(r.radiance, expected);
    ASSERT_TRUE(m);
    EXPECT_LT(m->relMse, 0.01);
}

// Irradiance at x on the plane y = 0 (normal +y) from the uniform rectangle with corners `c`, radiance
// L, above it (Lambert's polygon formula: E = L/2 |sum beta_i n . (r_i x r_i+1)/|r_i x r_i+1||).
double polygonIrradiance(const std::array<glm::dvec3, 4>& c, glm::dvec3 x, double radiance) {
    double sum = 0.0;
    for (size_t i = 0; i < 4; ++i) {
        const glm::dvec3 a = glm::normalize(c[i] - x), b = glm::normalize(c[(i + 1) % 4] - x);
        const glm::dvec3 g = glm::cross(a, b);
        sum += std::atan2(glm::length(g), glm::dot(a, b)) * g.y / glm::length(g);
    }
    return 0.5 * radiance * std::abs(sum);
}

// A textured light over the plane: photons leave it where its texture is bright (left half 1, right
// half 1/4 of the radiance) with power texel / pdf, so the photon map's direct light must be the sum
// of the halves' polygon formulas. Same tolerances as the point light above (the estimate's noise and
// blur at k = 64, 400,000 photons); ignoring the texture would make both halves alike.
TEST(PhotonMapImage, TexturedAreaLightOverPlaneMatchesThePolygonFormula) {
    constexpr float kRho = 0.5f, kView = 2.0f, kHeight = 0.8f, kRadiance = 3.0f;
    constexpr int kSize = 32;
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, kView);
    Light area;
    area.type = LightType::Area;
    area.position = {0.0f, kHeight, 0.0f};
    area.edgeU = {1.2f, 0.0f, 0.0f};
    area.edgeV = {0.0f, 0.0f, 0.8f};  // cross(+x, +z) = -y: emits downwards
    area.radiance = glm::vec3(kRadiance);
    Image texture(2, 1, glm::vec3(1.0f));
    texture.at(1, 0) = glm::vec3(0.25f);
    area.texture.kind = AreaTexture::Kind::Images;
    area.texture.frames = {0};
    scene.textures.push_back({"halves", texture});
    scene.lights.push_back(area);
    PhotonMapSettings s = scope(0, false, 400'000);
    s.k = 64;
    const PhotonMapResult r = makeMapper(scene, s).render();
    const auto corners = [&](double u0, double u1) {
        const auto at = [&](double u, double v) {
            return glm::dvec3(area.position) + (u - 0.5) * glm::dvec3(area.edgeU) + (v - 0.5) * glm::dvec3(area.edgeV);
        };
        return std::array<glm::dvec3, 4>{at(u0, 0), at(u1, 0), at(u1, 1), at(u0, 1)};
    };
    const auto left = corners(0.0, 0.5), right = corners(0.5, 1.0);
    Image expected(kSize, kSize);
    double sumImage = 0.0, sumExpected = 0.0;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            const glm::dvec3 x((px + 0.5) / kSize * kView - 0.5 * kView, 0.0, (py + 0.5) / kSize * kView - 0.5 * kView);
            const double e = polygonIrradiance(left, x, kRadiance) + polygonIrradiance(right, x, 0.25 * kRadiance);
            const double L = kRho / kPi * e;
            expected.at(px, py) = glm::vec3(static_cast<float>(L));
            sumImage += r.radiance.at(px, py).y;
            sumExpected += L;
        }
    EXPECT_NEAR(sumImage / sumExpected, 1.0, 0.015);
    const auto m = compareImages(r.radiance, expected);
    ASSERT_TRUE(m);
    EXPECT_LT(m->relMse, 0.01);
    // Under the bright half against under the dim half (1.81 to 1): within 0.1. Over seeds 1-5 the ratio
    // of these 4 x 4-pixel patches deviated by at most 0.073 (neighbouring gathers share photons, so the
    // patches average less noise away than 16 independent gathers would); emitting as if untextured gives 1.0.
    const auto patch = [&](const Image& image, int x0) {
        double sum = 0.0;
        for (int y = kSize / 2 - 2; y < kSize / 2 + 2; ++y)
            for (int x = x0; x < x0 + 4; ++x) sum += image.at(x, y).y;
        return sum;
    };
    EXPECT_NEAR(patch(r.radiance, kSize / 4 - 2) / patch(r.radiance, 3 * kSize / 4 - 2),
                patch(expected, kSize / 4 - 2) / patch(expected, 3 * kSize / 4 - 2), 0.1);
}

// A light whose texture is black at this frame: the mapper emits nothing and renders black, without
// failing (the scene has a light, dark now).
TEST(PhotonMapImage, BlackTexturedLightGivesABlackImage) {
    Scene scene = testscenes::planeUnderOrthoCamera(0.5f, 2.0f);
    Light area;
    area.type = LightType::Area;
    area.position = {0.0f, 0.8f, 0.0f};
    area.edgeU = {1.0f, 0.0f, 0.0f};
    area.edgeV = {0.0f, 0.0f, 1.0f};
    area.radiance = glm::vec3(2.0f);
    area.texture.kind = AreaTexture::Kind::Images;
    area.texture.frames = {0};
    scene.textures.push_back({"black", Image(2, 2, glm::vec3(0.0f))});
    scene.lights.push_back(area);
    const PhotonMapResult r = makeMapper(scene, scope(0, false, 1000)).render();
    for (const glm::vec3& p : r.radiance.pixels()) ASSERT_EQ(p, glm::vec3(0.0f));
}

// Indirect light (--indirect-only, unbounded) in a closed room lit by a point light: the photon map
// converges to the path tracer's image of the same scope as photons (and k, with r_k ~ sqrt(k/N)
// shrinking) grow. The estimate's noise dominates: relative variance 1/(k-2) per gather, and the
// four gathers of a pixel share most of their photons (r_k spans several pixels), so relMSE ~ 1/k
// and each step (k doubled) should halve it: it must fall by at least a quarter at each step, and
// the last (k = 64, noise ~0.016) must be below 0.02. The reference's own noise (1024 spp, a few per
// cent per pixel) adds ~0.001.
TEST(PhotonMapImage, ConvergesToThePathTracerAsPhotonsGrow) {
    Scene scene = room(glm::vec3(0.7f, 0.6f, 0.5f));
    scene.lights.push_back(pointLight({0.4f, 0.6f, -0.5f}, 2.0f));
    PathTracerSettings pt;
    pt.width = pt.height = 32;
    pt.samplesPerPixel = 1024;
    pt.indirectOnly = true;
    pt.seed = 3;
    auto tracer = PathTracer::create(scene, pt);
    ASSERT_TRUE(tracer);
    const Image reference = tracer->render().radiance;

    double previous = std::numeric_limits<double>::infinity();
    for (const auto& [photons, k] : {std::pair<uint64_t, int>{20'000, 16}, {80'000, 32}, {320'000, 64}}) {
        PhotonMapSettings s = scope(PhotonMapSettings::kUnbounded, true, photons);
        s.k = k;
        const PhotonMapResult r = makeMapper(scene, s).render();
        const auto m = compareImages(r.radiance, reference);
        ASSERT_TRUE(m);
        std::printf("photons %llu k %d: relMSE %.5f\n", static_cast<unsigned long long>(photons), k, m->relMse);
        EXPECT_LT(m->relMse, 0.75 * previous) << photons << " photons";
        previous = m->relMse;
    }
    EXPECT_LT(previous, 0.02);
}

// The image depends on the seed alone: one and two threads give the same bits.
TEST(PhotonMapDeterminism, SameImageOnOneAndTwoThreads) {
    Scene scene = room(glm::vec3(0.6f));
    scene.lights.push_back(pointLight({0.4f, 0.6f, -0.5f}, 2.0f));
    PhotonMapSettings s = scope(PhotonMapSettings::kUnbounded, true, 300'000);  // two passes, many chunks
    s.threads = 1;
    const PhotonMapResult one = makeMapper(scene, s).render();
    s.threads = 2;
    const PhotonMapResult two = makeMapper(scene, s).render();
    EXPECT_EQ(one.photonsStored, two.photonsStored);
    EXPECT_EQ(one.radiance.pixels(), two.radiance.pixels());
    s.seed = 1;
    const PhotonMapResult other = makeMapper(scene, s).render();
    EXPECT_NE(one.radiance.pixels(), other.radiance.pixels());
}

TEST(PhotonMapSettingsTest, TimeLimitStopsTracingAfterAPass) {
    Scene scene = room(glm::vec3(0.6f));
    scene.lights.push_back(pointLight({0.4f, 0.6f, -0.5f}, 2.0f));
    PhotonMapSettings s = scope(PhotonMapSettings::kUnbounded, true, 100 * PhotonMapSettings::kPhotonsPerPass);
    s.timeLimitSeconds = 1e-3;
    const PhotonMapResult r = makeMapper(scene, s).render();
    EXPECT_TRUE(r.stoppedByTimeLimit);
    EXPECT_EQ(r.photonsEmitted % PhotonMapSettings::kPhotonsPerPass, 0u);
    EXPECT_LT(r.photonsEmitted, s.photons);
    EXPECT_GT(r.photonsStored, 0u);
}

TEST(PhotonMapSettingsTest, BadSettingsAreErrors) {
    Scene scene = room(glm::vec3(0.6f));
    scene.lights.push_back(pointLight({0.4f, 0.6f, -0.5f}, 2.0f));
    const auto fails = [&](PhotonMapSettings s, const char* words) {
        auto m = PhotonMapper::create(scene, s);
        ASSERT_FALSE(m);
        EXPECT_NE(m.error().message.find(words), std::string::npos) << m.error().message;
    };
    PhotonMapSettings s = scope(0, false, 1000);
    s.k = 1;
    fails(s, "k 1");
    s = scope(0, false, 0);
    fails(s, "photons 0");
    s = scope(0, false, 1000);
    s.maxRadius = -1.0f;
    fails(s, "max radius");
    s = scope(-2, false, 1000);
    fails(s, "bounces");
    const Scene dark = room(glm::vec3(0.6f));
    auto m = PhotonMapper::create(dark, scope(0, false, 1000));
    ASSERT_FALSE(m);
    EXPECT_NE(m.error().message.find("no light source"), std::string::npos);
}

}  // namespace
}  // namespace bounce
