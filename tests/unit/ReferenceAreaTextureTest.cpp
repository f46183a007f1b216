// Textured and two-sided area lights in the reference path tracer (docs/reference.md "Textured area
// lights"): the direct light of a textured light against Lambert's polygon formula applied to its
// uniformly coloured parts, importance sampling by the texels' luminance against sampling only the
// bright part, black textures, two-sided emission, the texture at the frame's time, and the vectorised
// kernel against the scalar code with such lights.
#include "ReferenceTestScenes.h"
#include "reference/EmitterTexture.h"
#include "reference/PathTracer.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

using namespace bounce;

namespace {

constexpr double kPiD = glm::pi<double>();

PathTracerResult render(const Scene& scene, const PathTracerSettings& settings) {
    auto tracer = PathTracer::create(scene, settings);
    EXPECT_TRUE(tracer.ok()) << (tracer.ok() ? "" : tracer.error().message);
    if (!tracer.ok()) return {};
    return tracer->render();
}

PathTracerSettings directOnly(int size, uint32_t spp, uint64_t seed = 5) {
    PathTracerSettings s;
    s.width = s.height = size;
    s.samplesPerPixel = spp;
    s.bounces = 0;
    s.seed = seed;
    return s;
}

// Irradiance at x (unit normal n) from a uniform Lambertian polygon of radiance L lying wholly above
// x's tangent plane (Lambert's contour integral, e.g. Arvo 1995, "Applications of irradiance tensors",
// eq. 2): E = L/2 |sum_i beta_i n . (r_i x r_{i+1}) / |r_i x r_{i+1}||, r_i the unit directions from x
// to the vertices and beta_i the angle between consecutive ones.
double polygonIrradiance(const std::vector<glm::dvec3>& vertices, glm::dvec3 x, glm::dvec3 n, double radiance) {
    double sum = 0.0;
    for (size_t i = 0; i < vertices.size(); ++i) {
        const glm::dvec3 a = glm::normalize(vertices[i] - x);
        const glm::dvec3 b = glm::normalize(vertices[(i + 1) % vertices.size()] - x);
        const glm::dvec3 c = glm::cross(a, b);
        const double len = glm::length(c);
        if (len > 0.0) sum += std::atan2(len, glm::dot(a, b)) * glm::dot(n, c / len);
    }
    return 0.5 * radiance * std::abs(sum);
}

// The part [u0, u1] x [v0, v1] of a light's rectangle (Scene.h: position + (u - 1/2) edgeU + (v - 1/2)
// edgeV), as a polygon.
std::vector<glm::dvec3> lightPart(const Light& l, double u0, double u1, double v0, double v1) {
    const auto at = [&](double u, double v) {
        return glm::dvec3(l.position) + (u - 0.5) * glm::dvec3(l.edgeU) + (v - 0.5) * glm::dvec3(l.edgeV);
    };
    return {at(u0, v0), at(u1, v0), at(u1, v1), at(u0, v1)};
}

// Mean of f(x, z) over the footprint of pixel (px, py) of testscenes::planeUnderOrthoCamera's view
// (`view` metres wide, column -> x, row -> z), by the midpoint rule on a 16 x 16 grid: what the
// renderer's jittered pixel samples average.
double footprintMean(int px, int py, int size, double view, const std::function<double(double, double)>& f) {
    constexpr int kGrid = 16;
    const double pixel = view / size;
    double sum = 0.0;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i)
            sum += f(-0.5 * view + (px + (i + 0.5) / kGrid) * pixel, -0.5 * view + (py + (j + 0.5) / kGrid) * pixel);
    return sum / (kGrid * kGrid);
}

Light areaLight(glm::vec3 position, glm::vec3 edgeU, glm::vec3 edgeV, float radiance) {
    Light l;
    l.type = LightType::Area;
    l.name = "screen";
    l.position = position;
    l.edgeU = edgeU;
    l.edgeV = edgeV;
    l.radiance = glm::vec3(radiance);
    return l;
}

// Gives `light` the still image `image` (appended to scene.textures).
void setTexture(Scene& scene, Light& light, const Image& image) {
    light.texture.kind = AreaTexture::Kind::Images;
    light.texture.frames = {static_cast<uint32_t>(scene.textures.size())};
    scene.textures.push_back({"test-texture", image});
}

double channelMean(const Image& image, int channel) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += p[channel];
    return sum / static_cast<double>(image.pixelCount());
}

}  // namespace

// A light over a white Lambertian plane whose 2 x 2 texture is red on its left half (u < 1/2), green on
// its top right quarter (u > 1/2, v > 1/2: image row 0 is v = 1) and blue on its bottom right one. Each
// channel is then the light of one uniform part of the rectangle, so the plane's radiance rho/pi E in
// each channel is Lambert's polygon formula for that part. `bounce reference --bounces 0` (light
// sampling by the texels' emitted luminance and BRDF sampling, combined by MIS) must match pixel by
// pixel. The radiance is coloured (5, 1.5, 20) so that each part gets a fair share of the light samples
// (46 %, 23 %, 31 %), and the distribution is that of lum(radiance * texel), not of the texel alone.
// Tolerances: 32768 spp on 8 x 8 pixels. Over 8 seeds at half that rate the per-pixel relative standard
// error of any channel was at most 2.0 % (mean 1.1 %), so at this rate at most 1.5 %: 7.5 % per pixel
// is 5 of those, and the mean over 64 pixels (errors 8 times smaller) within 0.75 % is 4 of the
// largest. Using the texture's mean instead of the texel, or dropping the texel's factor from the pdf,
// is off by 40 % to a factor of 3 in some channel.
TEST(ReferenceAreaTexture, DirectLightMatchesThePolygonFormulaOfEachColouredPart) {
    constexpr float kRho = 1.0f, kView = 0.4f, kHeight = 0.6f;
    const glm::vec3 kRadiance(5.0f, 1.5f, 20.0f);
    constexpr int kSize = 8;
    Scene scene = testscenes::planeUnderOrthoCamera(kRho, kView);
    // Emits downwards (cross(+x, +z) = -y); u runs along +x, v along +z. The camera, above, sees the
    // plane through the light's back.
    Light light = areaLight({0.05f, kHeight, -0.03f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.4f}, 1.0f);
    light.radiance = kRadiance;
    Image texture(2, 2);
    texture.at(0, 0) = texture.at(0, 1) = glm::vec3(1.0f, 0.0f, 0.0f);
    texture.at(1, 0) = glm::vec3(0.0f, 1.0f, 0.0f);  // row 0: v in (1/2, 1]
    texture.at(1, 1) = glm::vec3(0.0f, 0.0f, 1.0f);
    setTexture(scene, light, texture);
    scene.lights.push_back(light);
    const std::vector<glm::dvec3> parts[3] = {lightPart(light, 0.0, 0.5, 0.0, 1.0), lightPart(light, 0.5, 1.0, 0.5, 1.0),
                                              lightPart(light, 0.5, 1.0, 0.0, 0.5)};
    const PathTracerResult r = render(scene, directOnly(kSize, 32768));
    EXPECT_EQ(r.invalidSamples, 0u);
    for (int ch = 0; ch < 3; ++ch) {
        const std::function<double(double, double)> radiance = [&](double x, double z) {
            return kRho / kPiD * polygonIrradiance(parts[ch], {x, 0.0, z}, {0.0, 1.0, 0.0}, kRadiance[ch]);
        };
        double ratioSum = 0.0;
        for (int py = 0; py < kSize; ++py)
            for (int px = 0; px < kSize; ++px) {
                const double ratio = r.radiance.at(px, py)[ch] / footprintMean(px, py, kSize, kView, radiance);
                EXPECT_NEAR(ratio, 1.0, 0.075) << "channel " << ch << " pixel " << px << "," << py;
                ratioSum += ratio;
            }
        EXPECT_NEAR(ratioSum / (kSize * kSize), 1.0, 0.0075) << "channel " << ch;
    }
}

// The camera sees radiance * texel on a textured light, nearest texel (the same 2 x 2 texture, the
// light now facing the camera). Pixels wholly inside one texel are exact up to float rounding.
TEST(ReferenceAreaTexture, CameraSeesTheTexels) {
    constexpr float kView = 1.0f, kRadiance = 2.0f;
    constexpr int kSize = 16;
    Scene scene = testscenes::planeUnderOrthoCamera(0.0f, kView);  // a black floor
    // u along +x, v along -z, normal cross(+x, -z) = +y, towards the camera. Image row y is world z
    // (row 0 at z = -1/2), so v = 1 (texture row 0) is at the top of the image.
    Light light = areaLight({0.0f, 0.5f, 0.0f}, {0.8f, 0.0f, 0.0f}, {0.0f, 0.0f, -0.8f}, kRadiance);
    Image texture(2, 2);
    texture.at(0, 0) = glm::vec3(1.0f, 0.0f, 0.0f);
    texture.at(1, 0) = glm::vec3(0.0f, 1.0f, 0.0f);
    texture.at(0, 1) = glm::vec3(0.0f, 0.0f, 1.0f);
    texture.at(1, 1) = glm::vec3(0.25f);
    setTexture(scene, light, texture);
    scene.lights.push_back(light);
    const PathTracerResult r = render(scene, directOnly(kSize, 4));
    // Pixel 4 covers x in [-0.25, -0.1875] (u in [0.1875, 0.27]), pixel 11 x in [0.1875, 0.25].
    EXPECT_EQ(r.radiance.at(4, 4), kRadiance * texture.at(0, 0));
    EXPECT_EQ(r.radiance.at(11, 4), kRadiance * texture.at(1, 0));
    EXPECT_EQ(r.radiance.at(4, 11), kRadiance * texture.at(0, 1));
    EXPECT_EQ(r.radiance.at(11, 11), kRadiance * texture.at(1, 1));
    EXPECT_EQ(r.radiance.at(0, 0), glm::vec3(0.0f)) << "outside the light: the black floor";
}

// Importance sampling: a 16 x 16 texture with one bright texel (256, so the mean is 1) and every other
// texel black. Sampling by luminance puts every light sample on the bright texel, so the image must be
// as good as that of an untextured light covering just that texel with 256 times the radiance (the two
// estimators have the same distribution). Uniform sampling of the rectangle would land one sample in
// 256 there: its relative error per pixel would be at least sqrt(256) = 16 times larger. The textured
// light's noise must stay within 1.25 of the small light's (both measured by the renderer at 256 spp
// over 1024 pixels: their ratio is known to a few per cent), and the image mean within 5 standard
// errors of the small light's.
TEST(ReferenceAreaTexture, ImportanceSamplingFindsTheOneBrightTexel) {
    constexpr float kView = 1.0f, kRadiance = 1.0f, kBright = 256.0f;
    constexpr int kSize = 32, kTexels = 16, kColumn = 11, kRow = 4;
    const glm::vec3 edgeU(0.8f, 0.0f, 0.0f), edgeV(0.0f, 0.0f, 0.8f);  // emits downwards
    const glm::vec3 centre(0.0f, 0.5f, 0.0f);
    Scene textured = testscenes::planeUnderOrthoCamera(0.8f, kView);
    Light light = areaLight(centre, edgeU, edgeV, kRadiance);
    Image texture(kTexels, kTexels, glm::vec3(0.0f));
    texture.at(kColumn, kRow) = glm::vec3(kBright);
    setTexture(textured, light, texture);
    textured.lights.push_back(light);

    // The bright texel's rectangle: u in [11/16, 12/16], v in [1 - 5/16, 1 - 4/16].
    Scene small = testscenes::planeUnderOrthoCamera(0.8f, kView);
    const float uc = (kColumn + 0.5f) / kTexels, vc = 1.0f - (kRow + 0.5f) / kTexels;
    small.lights.push_back(areaLight(centre + (uc - 0.5f) * edgeU + (vc - 0.5f) * edgeV, edgeU / float(kTexels),
                                     edgeV / float(kTexels), kRadiance * kBright));

    const PathTracerResult a = render(textured, directOnly(kSize, 256));
    const PathTracerResult b = render(small, directOnly(kSize, 256, 6));
    EXPECT_EQ(a.invalidSamples, 0u);
    EXPECT_LT(a.noise.meanPixelRelativeError, 1.25 * b.noise.meanPixelRelativeError)
        << "textured " << a.noise.meanPixelRelativeError << ", bright texel alone " << b.noise.meanPixelRelativeError;
    const double ma = channelMean(a.radiance, 1), mb = channelMean(b.radiance, 1);
    const double sigma = std::hypot(a.noise.imageRelativeError, b.noise.imageRelativeError);
    EXPECT_NEAR(ma / mb, 1.0, 5.0 * sigma);
}

// A black texture: the light has no power, is never chosen, and shows black; no NaN anywhere. Alone
// it leaves the scene dark at this frame, which is a black image, not a scene without lights. Beside
// another light, where no ray can reach it (below the one-sided plane), the image is bit for bit the
// image without it: it takes no share of the light choice.
TEST(ReferenceAreaTexture, BlackTextureEmitsNothing) {
    Scene scene = testscenes::planeUnderOrthoCamera(0.8f, 1.0f);
    Light black = areaLight({0.0f, 0.5f, 0.0f}, {0.4f, 0.0f, 0.0f}, {0.0f, 0.0f, -0.4f}, 3.0f);  // faces the camera
    setTexture(scene, black, Image(4, 4, glm::vec3(0.0f)));
    scene.lights.push_back(black);
    const PathTracerResult dark = render(scene, directOnly(16, 4));
    EXPECT_EQ(dark.invalidSamples, 0u);
    for (const glm::vec3& p : dark.radiance.pixels()) ASSERT_EQ(p, glm::vec3(0.0f));

    Scene lit = testscenes::planeUnderOrthoCamera(0.8f, 1.0f);
    lit.lights.push_back(areaLight({0.1f, 0.6f, 0.0f}, {0.3f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.3f}, 4.0f));
    const PathTracerResult alone = render(lit, directOnly(16, 16));
    Light hidden = black;
    hidden.position.y = -1.0f;
    lit.lights.push_back(hidden);
    lit.textures = scene.textures;
    const PathTracerResult both = render(lit, directOnly(16, 16));
    ASSERT_EQ(both.radiance.pixelCount(), alone.radiance.pixelCount());
    EXPECT_EQ(std::memcmp(both.radiance.data(), alone.radiance.data(), alone.radiance.pixelCount() * sizeof(glm::vec3)), 0);
}

// Two-sided: a horizontal light halfway between two planes, the lower facing up and the upper facing
// down. Seen from above (through the upper plane's back) and from below (through the lower one's) the
// two images must agree: both planes are lit alike, and both faces show the light. The image means'
// standard errors, reported by the renderer, set the tolerance (5 of them combined). A one-sided light
// leaves one plane dark, and its back shows nothing.
TEST(ReferenceAreaTexture, TwoSidedLightLightsBothSides) {
    constexpr float kView = 1.6f, kRadiance = 3.0f;
    constexpr int kSize = 16;
    const auto scene = [&](bool twoSided, bool fromAbove) {
        Scene s = testscenes::planeUnderOrthoCamera(0.7f, kView);
        testscenes::addQuad(s.meshes[0], {0.0f, 1.0f, 0.0f}, {40.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 40.0f});  // faces -y
        Light l = areaLight({0.0f, 0.5f, 0.0f}, {0.4f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.3f}, kRadiance);  // front: -y
        Image texture(2, 1);
        texture.at(0, 0) = glm::vec3(1.0f);
        texture.at(1, 0) = glm::vec3(0.5f);
        setTexture(s, l, texture);
        l.twoSided = twoSided;
        s.lights.push_back(l);
        if (!fromAbove) {
            s.camera.position = {0.0f, -10.0f, 0.0f};
            s.camera.farPlane = 20.0f;
        }
        return s;
    };
    const PathTracerResult above = render(scene(true, true), directOnly(kSize, 1024));
    const PathTracerResult below = render(scene(true, false), directOnly(kSize, 1024));
    const double ma = channelMean(above.radiance, 1), mb = channelMean(below.radiance, 1);
    EXPECT_GT(ma, 0.0);
    const double sigma = std::hypot(above.noise.imageRelativeError, below.noise.imageRelativeError);
    EXPECT_NEAR(ma / mb, 1.0, 5.0 * sigma) << "above " << ma << ", below " << mb;
    // Both see the light's face at the centre: radiance * texel (u < 1/2 there on the left of the image
    // from above; from below the image is mirrored, the texel values are the same).
    EXPECT_EQ(above.radiance.at(kSize / 2 - 1, kSize / 2).g, kRadiance * 1.0f);
    EXPECT_EQ(below.radiance.at(kSize / 2 - 1, kSize / 2).g, kRadiance * 0.5f);  // the other half, mirrored

    // One-sided (front face down): from above, the camera sees the lit lower plane through the light's
    // back; from below it sees the emitting face, and around it the upper plane, which nothing lights.
    const PathTracerResult oneSidedAbove = render(scene(false, true), directOnly(kSize, 64));
    EXPECT_GT(oneSidedAbove.radiance.at(kSize / 2 - 1, kSize / 2).g, 0.0f) << "the lower plane under the face is lit";
    EXPECT_LT(oneSidedAbove.radiance.at(kSize / 2 - 1, kSize / 2).g, 0.5f * kRadiance) << "the back shows nothing";
    const PathTracerResult oneSidedBelow = render(scene(false, false), directOnly(kSize, 64));
    EXPECT_EQ(oneSidedBelow.radiance.at(kSize / 2 - 1, kSize / 2).g, kRadiance * 0.5f);
    EXPECT_EQ(oneSidedBelow.radiance.at(1, 1), glm::vec3(0.0f)) << "the upper plane, behind the light, is dark";
}

// The texture shown is the one at the frame's time: a two-frame sequence at 2 frames per second
// (frame 0 red, frame 1 green) in a scene of 4 frames per second shows frame 0 at scene frames 0 and
// 1 (t = 0, 0.25 s), frame 1 at scene frames 2 and 3, and frame 0 again at 4 (it loops).
TEST(ReferenceAreaTexture, ShowsTheFrameOfTheRenderedTime) {
    Scene scene = testscenes::planeUnderOrthoCamera(0.0f, 1.0f);
    scene.frameRate = 4.0f;
    Light light = areaLight({0.0f, 0.5f, 0.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -2.0f}, 1.0f);  // faces the camera
    light.texture.kind = AreaTexture::Kind::Images;
    light.texture.frames = {0, 1};
    light.texture.frameRate = 2.0f;
    scene.textures.push_back({"red", Image(1, 1, glm::vec3(1.0f, 0.0f, 0.0f))});
    scene.textures.push_back({"green", Image(1, 1, glm::vec3(0.0f, 1.0f, 0.0f))});
    scene.lights.push_back(light);
    for (uint32_t frame : {0u, 1u, 2u, 3u, 4u}) {
        PathTracerSettings s = directOnly(4, 1);
        s.frame = frame;
        const PathTracerResult r = render(scene, s);
        const glm::vec3 expected = (frame == 2 || frame == 3) ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        EXPECT_EQ(r.radiance.at(2, 2), expected) << "frame " << frame;
    }
}

// The vectorised kernel hands textured lights' samples over from LightSampler::textureSample, so the
// image must stay bit-identical to the scalar code's with textured, two-sided and untextured lights
// mixed, in the full scope (reflected rays hit both faces, MIS against texel pdfs).
TEST(ReferenceAreaTexture, VectorisedKernelEqualsScalarCode) {
    Scene scene = testscenes::furnaceRoom(0.6f, 0.0f);
    Light screen = areaLight({0.0f, 0.2f, -0.3f}, {0.6f, 0.0f, 0.0f}, {0.0f, 0.4f, 0.2f}, 2.0f);
    Image texture(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) texture.at(x, y) = glm::vec3(0.1f * x, 0.3f * y, (x + y) % 3 == 0 ? 1.0f : 0.0f);
    setTexture(scene, screen, texture);
    screen.twoSided = true;
    scene.lights.push_back(screen);
    Light square = areaLight({0.5f, 0.9f, 0.2f}, {0.3f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.3f}, 5.0f);
    square.texture.kind = AreaTexture::Kind::BouncingSquare;
    square.texture.resolution = 8;
    scene.lights.push_back(square);
    scene.lights.push_back(areaLight({-0.5f, 0.9f, 0.0f}, {0.2f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.2f}, 3.0f));
    PathTracerSettings s;
    s.width = 37;
    s.height = 29;
    s.samplesPerPixel = 6;
    s.seed = 11;
    const PathTracerResult vectorised = render(scene, s);
    s.vectorized = false;
    const PathTracerResult scalar = render(scene, s);
    ASSERT_EQ(vectorised.radiance.pixelCount(), scalar.radiance.pixelCount());
    EXPECT_GT(channelMean(scalar.radiance, 0), 0.0);
    EXPECT_EQ(std::memcmp(vectorised.radiance.data(), scalar.radiance.data(), scalar.radiance.pixelCount() * sizeof(glm::vec3)), 0);
    EXPECT_EQ(vectorised.rays, scalar.rays);
}

// Bad input a scene built in code can carry past finalizeScene: the reference checks it and fails
// with a message, never a crash.
TEST(ReferenceBadInput, BrokenAreaTextureIsAnError) {
    Scene scene = testscenes::planeUnderOrthoCamera(0.8f, 1.0f);
    Light light = areaLight({0.0f, 0.5f, 0.0f}, {0.4f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.4f}, 1.0f);
    light.texture.kind = AreaTexture::Kind::Images;
    light.texture.frames = {3};  // no such texture
    scene.lights.push_back(light);
    auto tracer = PathTracer::create(scene, directOnly(4, 1));
    ASSERT_FALSE(tracer.ok());
    EXPECT_NE(tracer.error().message.find("light 'screen'"), std::string::npos) << tracer.error().message;
    EXPECT_NE(tracer.error().message.find("out of range"), std::string::npos) << tracer.error().message;
}

// ---- EmitterTexture: the distribution itself ------------------------------------------------------

// The pdf integrates to 1 over the unit square and is the emitted luminance over its mean; sampling
// lands in each texel with that probability (a histogram of 2^18 stratified samples against it, each
// bin within 5 binomial standard deviations); black texels are never drawn.
TEST(EmitterTexture, SamplesTheTexelsByLuminance) {
    Image image(4, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) image.at(x, y) = glm::vec3(static_cast<float>((x * 3 + y * 5) % 4));
    image.at(2, 1) = glm::vec3(0.0f);
    const glm::vec3 radiance(1.0f, 2.0f, 0.5f);
    const EmitterTexture t(image, radiance);
    double lumSum = 0.0, pdfSum = 0.0;
    for (const glm::vec3& p : image.pixels()) lumSum += luminance(radiance * p);
    for (size_t i = 0; i < 12; ++i) pdfSum += t.pdf(i);
    EXPECT_NEAR(pdfSum / 12.0, 1.0, 1e-6);
    EXPECT_NEAR(t.meanLuminance(), lumSum / 12.0, 1e-6);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_NEAR(t.pdf(static_cast<size_t>(y * 4 + x)), luminance(radiance * image.at(x, y)) / (lumSum / 12.0), 1e-5);

    constexpr int kSide = 512;  // kSide^2 stratified samples
    std::vector<double> count(12, 0.0);
    for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i) {
            const EmitterTexture::Sample s = t.sample((i + 0.5f) / kSide, (j + 0.5f) / kSide);
            ASSERT_EQ(s.texel, t.texelAt(s.uv)) << "the point lies in the texel it reports";
            count[s.texel] += 1.0;
        }
    const double n = double(kSide) * kSide;
    for (size_t i = 0; i < 12; ++i) {
        const double p = t.pdf(i) / 12.0;
        EXPECT_NEAR(count[i] / n, p, 5.0 * std::sqrt(p * (1.0 - p) / n) + 1e-9) << "texel " << i;
    }
    EXPECT_EQ(count[1 * 4 + 2], 0.0) << "black texel drawn";
}

// Texel (column c, row r) covers u in [c/W, (c+1)/W) and v in (1 - (r+1)/H, 1 - r/H] (Scene.h: image
// row 0 is v = 1); outside the square lookups clamp. A black texture is black().
TEST(EmitterTexture, TexelConventionAndBlack) {
    const EmitterTexture t(Image(4, 2, glm::vec3(1.0f)), glm::vec3(1.0f));
    EXPECT_EQ(t.texelAt({0.1f, 0.9f}), 0u);
    EXPECT_EQ(t.texelAt({0.9f, 0.9f}), 3u);
    EXPECT_EQ(t.texelAt({0.3f, 0.1f}), 5u);
    EXPECT_EQ(t.texelAt({1.0f, 0.0f}), 7u);
    EXPECT_EQ(t.texelAt({-0.2f, 1.3f}), 0u);
    EXPECT_FALSE(t.black());
    EXPECT_FLOAT_EQ(t.pdf(5), 1.0f);
    const EmitterTexture black(Image(3, 3, glm::vec3(0.0f)), glm::vec3(2.0f));
    EXPECT_TRUE(black.black());
    EXPECT_EQ(black.pdf(4), 0.0f);
}

// ---- Emission textures of materials (Material::emissionTexture) -----------------------------------

namespace {

// An emissive quad 0.6 m above the plane of planeUnderOrthoCamera, 0.4 m square, facing down (or up).
Scene emissiveQuadOverPlane(float emission, bool facingUp) {
    Scene scene = testscenes::planeUnderOrthoCamera(0.8f, 1.0f);
    Mesh quad;
    quad.name = "lamp";
    if (facingUp) testscenes::addQuad(quad, {0.0f, 0.6f, 0.0f}, {0.4f, 0.0f, 0.0f}, {0.0f, 0.0f, -0.4f});
    else testscenes::addQuad(quad, {0.0f, 0.6f, 0.0f}, {0.4f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.4f});
    Material m;
    m.name = "glow";
    m.baseColor = glm::vec3(0.0f);
    m.emission = glm::vec3(emission);
    testscenes::addObject(scene, quad, m);
    return scene;
}

}  // namespace

// A uniform emission texture of 1/4 on emission 4 is emission 1: next-event estimation (the light's
// texel at the sampled point) and BRDF-sampled hits (the texel at the hit) both multiply, so the image
// is bit for bit that of the untextured emitter (the same random numbers, the same products: 4 x 0.25
// is exactly 1).
TEST(ReferenceEmissionTexture, ScalesTheEmittersLight) {
    Scene textured = emissiveQuadOverPlane(4.0f, false);
    textured.textures.push_back({"quarter", Image(3, 2, glm::vec3(0.25f))});
    textured.materials[1].emissionTexture = 0;
    const Scene plain = emissiveQuadOverPlane(1.0f, false);
    const PathTracerResult a = render(textured, directOnly(16, 16));
    const PathTracerResult b = render(plain, directOnly(16, 16));
    EXPECT_GT(channelMean(b.radiance, 0), 0.0);
    ASSERT_EQ(a.radiance.pixelCount(), b.radiance.pixelCount());
    EXPECT_EQ(std::memcmp(a.radiance.data(), b.radiance.data(), a.radiance.pixelCount() * sizeof(glm::vec3)), 0);
}

// The camera sees emission times the texture, bilinear (docs/scene.md "Materials"): a 2 x 1 texture
// (0.2, 1.0) on the upward-facing quad, whose u runs along +x. Between the texel centres (u = 1/4, 3/4)
// the lookup is linear in u, so a pixel's jittered average is the value at its centre: at u = 3/8 it
// is 0.75 * 0.2 + 0.25 * 1.0. Pixel 28 of 64 over the 1 m view has its centre at x = -0.0547, u = 0.363;
// 256 samples of a slope of 1.6 per unit u over 1/64 m (u spans 0.039) leave 1e-3 of noise.
TEST(ReferenceEmissionTexture, CameraSeesEmissionTimesTheTexture) {
    Scene scene = emissiveQuadOverPlane(2.0f, true);
    Image texture(2, 1);
    texture.at(0, 0) = glm::vec3(0.2f);
    texture.at(1, 0) = glm::vec3(1.0f);
    scene.textures.push_back({"ramp", texture});
    scene.materials[1].emissionTexture = 0;
    const PathTracerResult r = render(scene, directOnly(64, 256));
    const double u = (((28 + 0.5) / 64.0 - 0.5) + 0.2) / 0.4;
    const double t = (u - 0.25) / 0.5;  // weight of texel 1
    EXPECT_NEAR(r.radiance.at(28, 32).r, 2.0 * (0.2 * (1.0 - t) + 1.0 * t), 3e-3);
}

// The kernel hands emission-textured triangles' samples over from LightSampler::textureSample: images
// stay bit-identical to the scalar code in a furnace room whose walls carry a varied emission texture.
TEST(ReferenceEmissionTexture, VectorisedKernelEqualsScalarCode) {
    Scene scene = testscenes::furnaceRoom(0.6f, 1.0f);
    Image texture(4, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) texture.at(x, y) = glm::vec3(0.2f * x, 0.1f + 0.4f * y, (x + y) % 2);
    scene.textures.push_back({"varied", texture});
    scene.materials[0].emissionTexture = 0;
    PathTracerSettings s;
    s.width = 37;
    s.height = 29;
    s.samplesPerPixel = 6;
    s.seed = 13;
    const PathTracerResult vectorised = render(scene, s);
    s.vectorized = false;
    const PathTracerResult scalar = render(scene, s);
    ASSERT_EQ(vectorised.radiance.pixelCount(), scalar.radiance.pixelCount());
    EXPECT_GT(channelMean(scalar.radiance, 1), 0.0);
    EXPECT_EQ(std::memcmp(vectorised.radiance.data(), scalar.radiance.data(), scalar.radiance.pixelCount() * sizeof(glm::vec3)), 0);
}
