// The path tracer's building blocks: texture lookup, BRDF, sampling, random numbers, camera rays.
#include "ReferenceTestScenes.h"
#include "reference/Bsdf.h"
#include "reference/CameraRays.h"
#include "reference/Rng.h"
#include "reference/Sampling.h"
#include "reference/TextureLookup.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <cmath>

using namespace bounce;

namespace {

// 2 x 2 texture: row 0 (the image's top) red, green; row 1 blue, white.
Image quadTexture() {
    Image image(2, 2);
    image.at(0, 0) = {1, 0, 0};
    image.at(1, 0) = {0, 1, 0};
    image.at(0, 1) = {0, 0, 1};
    image.at(1, 1) = {1, 1, 1};
    return image;
}

// Bilinear weights are exact binary fractions here, so the results are exact up to float rounding.
constexpr float kExact = 1e-6f;

TEST(ReferenceTextureLookup, TexelCentresAndTopLeftOrigin) {
    const Image image = quadTexture();
    const auto expectColour = [&](glm::vec2 uv, glm::vec3 expected) {
        const glm::vec3 c = lookupBilinearRepeat(image, uv);
        EXPECT_NEAR(c.r, expected.r, kExact) << uv.x << "," << uv.y;
        EXPECT_NEAR(c.g, expected.g, kExact) << uv.x << "," << uv.y;
        EXPECT_NEAR(c.b, expected.b, kExact) << uv.x << "," << uv.y;
    };
    expectColour({0.25f, 0.25f}, {1, 0, 0});  // v small = first row = top
    expectColour({0.75f, 0.25f}, {0, 1, 0});
    expectColour({0.25f, 0.75f}, {0, 0, 1});
    expectColour({0.75f, 0.75f}, {1, 1, 1});
    expectColour({0.5f, 0.25f}, {0.5f, 0.5f, 0});        // halfway between red and green
    expectColour({0.0f, 0.25f}, {0.5f, 0.5f, 0});        // wraps: between green (x = -1) and red
    expectColour({0.0f, 0.0f}, {0.5f, 0.5f, 0.5f});      // corner: all four texels equally
    expectColour({1.25f, -0.75f}, {1, 0, 0});            // repeat in both directions
    expectColour({-3.75f, 5.75f}, {0, 0, 1});            // same as (0.25, 0.75)
}

TEST(ReferenceBsdf, LambertIsAlbedoOverPi) {
    Material m;
    m.baseColor = glm::vec3(0.6f, 0.3f, 0.1f);
    const Bsdf bsdf(m, m.baseColor, false);
    EXPECT_TRUE(bsdf.isLambertian());
    const glm::vec3 wo = glm::normalize(glm::vec3(0.3f, 0.1f, 0.9f));
    const glm::vec3 wi = glm::normalize(glm::vec3(-0.5f, 0.2f, 0.4f));
    const glm::vec3 f = bsdf.eval(wo, wi);
    EXPECT_NEAR(f.r, 0.6f / glm::pi<float>(), 1e-7f);
    EXPECT_NEAR(f.b, 0.1f / glm::pi<float>(), 1e-7f);
    EXPECT_NEAR(bsdf.pdf(wo, wi), wi.z / glm::pi<float>(), 1e-7f);
    EXPECT_EQ(bsdf.eval(wo, {0.0f, 0.6f, -0.8f}), glm::vec3(0.0f));
    Bsdf::Sample s;
    ASSERT_TRUE(bsdf.sample(wo, 0.5f, 0.3f, 0.7f, s));
    EXPECT_NEAR(s.weight.g, 0.3f, 1e-6f);  // (albedo/pi) cos / (cos/pi)
    // metallic scales the Lambert lobe by (1 - metallic) and adds the GGX lobe.
    m.metallic = 0.5f;
    EXPECT_FALSE(Bsdf(m, m.baseColor, false).isLambertian());
    EXPECT_NEAR(Bsdf(m, m.baseColor, true).eval(wo, wi).r, 0.3f / glm::pi<float>(), 1e-7f);
}

// Monte Carlo over the hemisphere; 2^16 samples give about 0.5% standard error on these integrals,
// so 2% is 4 standard errors.
constexpr int kMcSamples = 1 << 16;
constexpr float kMcTolerance = 0.02f;

// The sampler and the pdf must agree: the mean of f cos / pdf over BRDF samples and the mean of
// f cos / (1 / 2 pi) over uniform directions estimate the same directional albedo; and the pdf
// integrates to at most 1 (the GGX visible-normal lobe loses what reflects below the horizon).
TEST(ReferenceBsdf, GgxSamplingMatchesEvaluation) {
    for (float roughness : {0.3f, 0.7f}) {
        Material m;
        m.baseColor = glm::vec3(0.5f);
        m.metallic = 0.3f;
        m.specularF0 = 0.04f;
        m.roughness = roughness;
        const Bsdf bsdf(m, m.baseColor, false);
        const glm::vec3 wo = glm::normalize(glm::vec3(0.6f, 0.0f, 0.8f));
        Rng rng(1, 2, 3);
        double sampled = 0.0, uniform = 0.0, pdfIntegral = 0.0;
        for (int i = 0; i < kMcSamples; ++i) {
            Bsdf::Sample s;
            if (bsdf.sample(wo, rng.next(), rng.next(), rng.next(), s)) {
                sampled += luminance(s.weight);
                EXPECT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 1e-3f * s.pdf);
            }
            // Uniform hemisphere direction: z uniform in [0, 1), pdf 1 / (2 pi).
            const float z = rng.next(), phi = 2.0f * glm::pi<float>() * rng.next();
            const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            const glm::vec3 wi(r * std::cos(phi), r * std::sin(phi), z);
            uniform += luminance(bsdf.eval(wo, wi)) * wi.z * 2.0 * glm::pi<double>();
            pdfIntegral += bsdf.pdf(wo, wi) * 2.0 * glm::pi<double>();
        }
        sampled /= kMcSamples;
        uniform /= kMcSamples;
        pdfIntegral /= kMcSamples;
        EXPECT_NEAR(sampled / uniform, 1.0, kMcTolerance) << "roughness " << roughness;
        EXPECT_LT(pdfIntegral, 1.0 + kMcTolerance);
        EXPECT_GT(pdfIntegral, 0.8);
        EXPECT_LT(sampled, 1.0) << "energy conservation";
    }
}

TEST(ReferenceSampling, CosineHemisphereHasCosinePdf) {
    // E[z] under pdf cos/pi is 2/3, E[z^2] = 1/2; E[x] = E[y] = 0. 2^16 samples: standard error
    // about 0.001 on each mean, so 0.005 is 5 standard errors. Both the rejection sampler (used by
    // the path tracer) and the polar map (used by the BRDF with given numbers) are checked.
    for (int method = 0; method < 2; ++method) {
        Rng rng(9, 9, static_cast<uint64_t>(method));
        double sumZ = 0.0, sumZ2 = 0.0, sumX = 0.0;
        for (int i = 0; i < kMcSamples; ++i) {
            const glm::vec3 d = method == 0 ? cosineHemisphere(rng) : cosineHemisphere(rng.next(), rng.next());
            EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
            EXPECT_GT(d.z, 0.0f);
            sumZ += d.z;
            sumZ2 += d.z * d.z;
            sumX += d.x;
        }
        EXPECT_NEAR(sumZ / kMcSamples, 2.0 / 3.0, 0.005) << method;
        EXPECT_NEAR(sumZ2 / kMcSamples, 0.5, 0.005) << method;
        EXPECT_NEAR(sumX / kMcSamples, 0.0, 0.01) << method;
    }
}

TEST(ReferenceSampling, RayOffsetLeavesTheSurface) {
    for (float scale : {0.001f, 1.0f, 1000.0f}) {
        const glm::vec3 p(0.3f * scale, -0.7f * scale, 0.1f * scale);
        const glm::vec3 n = glm::normalize(glm::vec3(1.0f, 2.0f, -0.5f));
        const glm::vec3 q = offsetRayOrigin(p, n);
        EXPECT_GT(glm::dot(q - p, n), 0.0f);
        EXPECT_LT(glm::length(q - p), 1e-3f * std::max(1.0f, scale));
    }
}

TEST(ReferenceRng, CounterBasedAndUniform) {
    Rng a(5, 100, 7), b(5, 100, 7), c(5, 101, 7), d(5, 100, 8);
    EXPECT_EQ(a.nextBits(), b.nextBits());
    Rng a2(5, 100, 7);
    const uint32_t first = a2.nextBits();
    EXPECT_NE(first, c.nextBits());
    EXPECT_NE(first, d.nextBits());
    // Mean of 2^16 uniforms: 0.5 with standard error 0.0011.
    Rng r(1, 1, 1);
    double sum = 0.0;
    for (int i = 0; i < kMcSamples; ++i) {
        const float u = r.next();
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        sum += u;
    }
    EXPECT_NEAR(sum / kMcSamples, 0.5, 0.005);
}

// Camera rays invert clipFromView * viewFromWorld: the centre pixel looks at the target, row 0 is
// the top of the image, and the ray runs from the near plane to the far plane.
TEST(ReferenceCamera, RaysFollowTheRasteriserConvention) {
    Camera camera;
    camera.position = {0.0f, 0.0f, 5.0f};
    camera.target = {0.0f, 0.0f, 0.0f};
    camera.nearPlane = 0.5f;
    camera.farPlane = 50.0f;
    const CameraRays rays(camera, 200, 100);
    const CameraRay centre = rays.generate(100.0f, 50.0f);
    EXPECT_NEAR(centre.direction.z, -1.0f, 1e-6f);
    EXPECT_NEAR(centre.origin.z, 4.5f, 1e-4f);
    EXPECT_NEAR(centre.tMax, 49.5f, 1e-3f);
    const CameraRay top = rays.generate(100.0f, 0.0f);
    EXPECT_NEAR(std::atan2(top.direction.y, -top.direction.z), 0.5f * camera.verticalFov, 1e-5f);
    const CameraRay right = rays.generate(200.0f, 50.0f);
    EXPECT_NEAR(std::atan2(right.direction.x, -right.direction.z),
                std::atan(2.0f * std::tan(0.5f * camera.verticalFov)), 1e-5f);  // aspect 2
    camera.projection = Projection::Orthographic;
    camera.orthoHeight = 4.0f;
    const CameraRays ortho(camera, 100, 100);
    const CameraRay corner = ortho.generate(0.0f, 0.0f);
    EXPECT_NEAR(corner.origin.x, -2.0f, 1e-5f);
    EXPECT_NEAR(corner.origin.y, 2.0f, 1e-5f);
    EXPECT_NEAR(corner.direction.z, -1.0f, 1e-6f);
}

}  // namespace
