// scene/AreaTexture: which frame of a sequence is shown at time t, and the bouncing-square pattern
// (exact coverage, so its mean is the square's area; reflection off the edges).
#include "scene/AreaTexture.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace bounce;

namespace {

AreaTexture sequence(size_t frames, float frameRate) {
    AreaTexture t;
    t.kind = AreaTexture::Kind::Images;
    for (size_t i = 0; i < frames; ++i) t.frames.push_back(static_cast<uint32_t>(i));
    t.frameRate = frameRate;
    return t;
}

// Centroid (u, v) of an image's texel weights, row 0 at v = 1 (Scene.h).
glm::dvec2 centroid(const Image& image) {
    glm::dvec2 sum(0.0);
    double total = 0.0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const double w = image.at(x, y).r;
            sum += w * glm::dvec2((x + 0.5) / image.width(), 1.0 - (y + 0.5) / image.height());
            total += w;
        }
    return sum / total;
}

}  // namespace

// floor(t * frameRate) modulo the frame count; before t = 0 (and for a still image) frame 0. Times are
// taken mid-frame, away from the boundaries where float rounding of t * rate decides.
TEST(AreaTexture, SequenceFrameAtTime) {
    const AreaTexture t = sequence(3, 24.0f);
    for (int k = 0; k < 9; ++k) EXPECT_EQ(areaTextureFrame(t, (k + 0.5f) / 24.0f), static_cast<size_t>(k % 3)) << k;
    EXPECT_EQ(areaTextureFrame(t, 0.0f), 0u);
    EXPECT_EQ(areaTextureFrame(t, -1.0f), 0u);
    EXPECT_EQ(areaTextureFrame(t, 100.0f + 1.5f / 24.0f), static_cast<size_t>((2400 + 1) % 3));
    EXPECT_EQ(areaTextureFrame(sequence(1, 24.0f), 7.3f), 0u);
    EXPECT_EQ(areaTextureFrame(sequence(4, 0.5f), 3.0f), 1u);  // 2 s per frame
}

// Each texel holds the fraction of its area the square covers, so the image mean is size^2 wherever
// the square is (float sums of 4096 texels: 1e-5), and the centroid of the weights is the square's
// centre. Moving at velocity v from start s, each coordinate reflects off [size/2, 1 - size/2]:
// start (0.3, 0.6), velocity (0.35, 0.22), size 0.25: at t = 2 s, u would be 1.0, 0.125 past the far
// edge 0.875, so it is back at 0.75; v = 1.04 reflects to 0.71.
TEST(AreaTexture, BouncingSquareCoverageAndReflection) {
    AreaTexture t;
    t.kind = AreaTexture::Kind::BouncingSquare;
    t.resolution = 64;
    t.squareSize = 0.25f;
    t.squareVelocity = {0.35f, 0.22f};
    t.squareStart = {0.3f, 0.6f};
    for (float time : {0.0f, 0.37f, 1.0f, 2.0f, 5.55f, 13.0f}) {
        const Image image = renderBouncingSquare(t, time);
        ASSERT_EQ(image.width(), 64);
        EXPECT_NEAR(imageMean(image).r, 0.0625f, 1e-5f) << "t = " << time;
        for (const glm::vec3& p : image.pixels()) {
            ASSERT_GE(p.r, 0.0f);
            ASSERT_LE(p.r, 1.0f + 1e-5f);
        }
        const glm::vec2 c = bouncingSquareCentre(t, time);
        const glm::dvec2 m = centroid(image);
        EXPECT_NEAR(m.x, c.x, 1e-4) << "t = " << time;
        EXPECT_NEAR(m.y, c.y, 1e-4) << "t = " << time;
        EXPECT_GE(c.x, 0.125f);
        EXPECT_LE(c.x, 0.875f);
    }
    EXPECT_NEAR(bouncingSquareCentre(t, 0.0f).x, 0.3f, 1e-6f);
    EXPECT_NEAR(bouncingSquareCentre(t, 2.0f).x, 0.75f, 1e-5f);
    EXPECT_NEAR(bouncingSquareCentre(t, 2.0f).y, 0.71f, 1e-5f);
    // Row 0 is v = 1: at t = 0 the square spans v in [0.475, 0.725], rows 17.6 to 33.6 from the top.
    const Image first = renderBouncingSquare(t, 0.0f);
    EXPECT_EQ(first.at(16, 10).r, 0.0f);
    EXPECT_NEAR(first.at(16, 25).r, 1.0f, 1e-5f);
    // A square as large as the light covers it all, wherever it "moves".
    t.squareSize = 1.0f;
    EXPECT_NEAR(imageMean(renderBouncingSquare(t, 3.3f)).r, 1.0f, 1e-5f);
}

// The mean multiplier a light's flux takes: 1 untextured, the frame's mean for a sequence.
TEST(AreaTexture, MeanOfTheFrameShown) {
    Scene scene;
    scene.textures.push_back({"a", Image(2, 2, glm::vec3(0.5f))});
    scene.textures.push_back({"b", Image(2, 2, glm::vec3(2.0f, 1.0f, 0.0f))});
    Light light;
    light.type = LightType::Area;
    EXPECT_EQ(areaTextureMean(scene, light, 0.0f), glm::vec3(1.0f));
    light.texture = sequence(2, 1.0f);
    EXPECT_EQ(areaTextureMean(scene, light, 0.5f), glm::vec3(0.5f));
    EXPECT_EQ(areaTextureMean(scene, light, 1.5f), glm::vec3(2.0f, 1.0f, 0.0f));
}
