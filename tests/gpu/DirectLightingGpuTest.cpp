// The direct-lighting renderer against closed forms (../shared/specs/analytic-tests.md):
// a Lambertian plane under point, spot and directional lights, and a rectangular area light.
#include "GpuTestSupport.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <glm/gtc/constants.hpp>

#include <cmath>

using namespace bounce;

namespace {

constexpr float kAlbedo = gputest::kPlaneAlbedo;
using gputest::kPlaneHalf;

Scene planeScene(const Light& light) { return gputest::planeScene(light, Projection::Orthographic); }

// World point on the plane seen by pixel (x, y) of a size x size image (row 0 at the top, -z).
glm::vec3 planePoint(int x, int y, int size) {
    const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(size);
    const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(size);
    return {(2.0f * u - 1.0f) * kPlaneHalf, 0.0f, (2.0f * v - 1.0f) * kPlaneHalf};
}

Image renderDirect(const Scene& scene, int size) {
    auto technique = createTechnique("direct");
    EXPECT_TRUE(technique.ok());
    render::RenderSettings settings;
    settings.pcfRadius = 0;
    auto pipeline = Pipeline::create(scene, std::move(*technique), {size, size}, settings);
    EXPECT_TRUE(pipeline.ok()) << pipeline.error().message;
    (*pipeline)->renderFrame(0);
    return (*pipeline)->readback(Component::Direct);
}

class DirectLightingGpuTest : public gputest::GpuTest {};

}  // namespace

TEST_F(DirectLightingGpuTest, PointLightFollowsInverseSquareCosineLaw) {
    Light light;
    light.type = LightType::Point;
    light.position = {0.3f, 1.0f, -0.2f};
    light.intensity = glm::vec3(2.0f);
    const Scene scene = planeScene(light);
    constexpr int size = 64;
    const Image image = renderDirect(scene, size);
    for (int y = 2; y < size; y += 7)
        for (int x = 3; x < size; x += 7) {
            const glm::vec3 p = planePoint(x, y, size);
            const glm::vec3 d = light.position - p;
            const float r2 = glm::dot(d, d);
            const float cosTheta = d.y / std::sqrt(r2);
            const float expected = kAlbedo / glm::pi<float>() * light.intensity.r * cosTheta / r2;
            // Radiance is stored in 32-bit float; 1e-4 relative covers the shader's float arithmetic.
            EXPECT_NEAR(image.at(x, y).r, expected, 1e-4f * expected + 1e-7f) << "pixel " << x << "," << y;
        }
}

TEST_F(DirectLightingGpuTest, SpotLightCosinePowerFalloffAndCutoff) {
    Light light;
    light.type = LightType::Spot;
    light.position = {0.0f, 1.0f, 0.0f};
    light.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
    light.intensity = glm::vec3(3.0f);
    light.cutoffAngle = glm::radians(50.0f);
    light.falloffExponent = 4.0f;
    const Scene scene = planeScene(light);
    constexpr int size = 64;
    const Image image = renderDirect(scene, size);
    int inside = 0, outside = 0;
    for (int y = 1; y < size; y += 3)
        for (int x = 1; x < size; x += 3) {
            const glm::vec3 p = planePoint(x, y, size);
            const glm::vec3 d = light.position - p;
            const float r2 = glm::dot(d, d);
            const glm::vec3 l = d / std::sqrt(r2);
            const float cosAlpha = glm::dot(-l, light.direction);
            // Skip a band around the cutoff, where a pixel's centre and the shader's sample of it
            // may fall on different sides of the hard edge.
            if (std::abs(std::acos(cosAlpha) - light.cutoffAngle) < glm::radians(2.0f)) continue;
            float expected = 0.0f;
            if (cosAlpha > std::cos(light.cutoffAngle)) {
                expected = kAlbedo / glm::pi<float>() * light.intensity.r * std::pow(cosAlpha, 4.0f) * l.y / r2;
                ++inside;
            } else {
                ++outside;
            }
            EXPECT_NEAR(image.at(x, y).r, expected, 1e-4f * expected + 1e-7f) << "pixel " << x << "," << y;
        }
    EXPECT_GT(inside, 20);
    EXPECT_GT(outside, 20);
}

TEST_F(DirectLightingGpuTest, DirectionalLightIsUniform) {
    Light light;
    light.type = LightType::Directional;
    light.direction = glm::normalize(glm::vec3(1.0f, -2.0f, 0.5f));
    light.irradiance = glm::vec3(1.5f);
    const Scene scene = planeScene(light);
    const Image image = renderDirect(scene, 32);
    const float expected = kAlbedo / glm::pi<float>() * 1.5f * (2.0f / glm::length(glm::vec3(1.0f, -2.0f, 0.5f)));
    for (int y = 0; y < 32; y += 5)
        for (int x = 0; x < 32; x += 5) EXPECT_NEAR(image.at(x, y).r, expected, 1e-4f * expected);
}

TEST_F(DirectLightingGpuTest, AreaLightMatchesRectangleFormFactor) {
    // A 0.6 x 0.4 m emitter 0.5 m above the plane, facing down. The irradiance at a plane point is
    // pi * L * F, F the form factor to the parallel rectangle: signed sums of the corner formula of
    // analytic-tests.md over the rectangle's corners relative to the point. The camera sees the
    // emitter's unlit back from above, so only points outside its footprint are checked.
    Light light;
    light.type = LightType::Area;
    light.position = {0.0f, 0.5f, 0.0f};
    light.edgeU = {0.6f, 0.0f, 0.0f};
    light.edgeV = {0.0f, 0.0f, 0.4f};  // cross(u, v) points to -y: emits downward
    light.radiance = glm::vec3(2.0f);
    const Scene scene = planeScene(light);
    constexpr int size = 64;
    const Image image = renderDirect(scene, size);
    auto cornerF = [](float a, float b, float c) {
        const float A = a / c, B = b / c;
        const float sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
        return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0f * glm::pi<float>());
    };
    auto signedF = [&](float a, float b) {
        const float s = (a < 0 ? -1.0f : 1.0f) * (b < 0 ? -1.0f : 1.0f);
        return s * cornerF(std::abs(a), std::abs(b), 0.5f);
    };
    int checked = 0;
    for (int y = 1; y < size; y += 4)
        for (int x = 1; x < size; x += 4) {
            const glm::vec3 p = planePoint(x, y, size);
            if (std::abs(p.x) < 0.35f && std::abs(p.z) < 0.25f) continue;  // under the emitter
            const float x0 = -0.3f - p.x, x1 = 0.3f - p.x, z0 = -0.2f - p.z, z1 = 0.2f - p.z;
            const float F = signedF(x1, z1) - signedF(x0, z1) - signedF(x1, z0) + signedF(x0, z0);
            const float expected = kAlbedo / glm::pi<float>() * glm::pi<float>() * 2.0f * F;
            // The contour integral is exact; 5e-3 relative covers float acos() of nearly parallel
            // edge vectors for far points in the shader.
            EXPECT_NEAR(image.at(x, y).r, expected, 5e-3f * expected + 1e-6f) << "pixel " << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 100);
}

// An emissive material's emission texture (docs/scene.md "Materials"): the G-buffer shows emission times
// the texel, bilinear. A black plane (albedo 0: nothing reflected) emitting 2 W/(m^2 sr) times a 2 x 1
// texture (0.2, 1.0) with u running along +x; between the texel centres (u = 1/4, 3/4) the lookup is
// linear in u, so a pixel shows the value at its centre. The 1e-2 covers RGBA16F storage (1e-3
// relative) and llvmpipe's 8-bit filtering weights (0.8 / 256 of the 0.2..1 step, times 2).
TEST_F(DirectLightingGpuTest, EmissionTextureIsShownTimesTheEmission) {
    Light light;
    light.type = LightType::Directional;
    light.direction = {0.0f, -1.0f, 0.0f};
    light.irradiance = glm::vec3(1.0f);
    Scene scene = planeScene(light);
    Mesh& plane = scene.meshes[0];
    for (const glm::vec3& p : plane.positions) plane.uvs.push_back({(p.x + kPlaneHalf) / (2.0f * kPlaneHalf), 0.5f});
    Image texture(2, 1);
    texture.at(0, 0) = glm::vec3(0.2f);
    texture.at(1, 0) = glm::vec3(1.0f);
    scene.textures.push_back({"ramp", texture});
    scene.materials[0].baseColor = glm::vec3(0.0f);
    scene.materials[0].emission = glm::vec3(2.0f);
    scene.materials[0].emissionTexture = 0;
    ASSERT_TRUE(finalizeScene(scene).ok());
    constexpr int size = 64;
    const Image image = renderDirect(scene, size);
    int checked = 0;
    for (int x = 0; x < size; ++x) {
        const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(size);
        if (u < 0.25f || u > 0.75f) continue;
        const float t = (u - 0.25f) / 0.5f;
        const float expected = 2.0f * (0.2f * (1.0f - t) + 1.0f * t);
        EXPECT_NEAR(image.at(x, size / 2).g, expected, 1e-2f) << "column " << x;
        ++checked;
    }
    EXPECT_EQ(checked, 32);
}
