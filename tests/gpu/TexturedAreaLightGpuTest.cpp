// Textured and two-sided area lights in the shared GPU passes (docs/scene.md "Lights"): the direct
// pass lights both half-spaces of a two-sided light with the exact polygon irradiance (its cube shadow
// map at the centre, the emitter casting no shadow on itself) and only the front of a one-sided one;
// the G-buffer shows a textured emitter's texels.
#include "GpuTestSupport.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Pipeline.h"
#include "techniques/Registry.h"

#include <glm/gtc/constants.hpp>
#include <glm/vec4.hpp>

#include <cmath>
#include <vector>

using namespace bounce;

namespace {

class TexturedAreaLightGpuTest : public gputest::GpuTest {};

constexpr float kAlbedo = 0.5f;
constexpr float kRadiance = 2.0f;        // W/(m^2 sr)
constexpr float kLightHeight = 0.5f;     // m, halfway between the planes
constexpr float kHalfX = 0.3f, kHalfZ = 0.2f;  // the light's half edges, m
constexpr float kView = 4.0f;            // m, orthographic view height

// `scene` must outlive the pipeline.
std::unique_ptr<Pipeline> makePipeline(const Scene& scene, int size) {
    auto technique = createTechnique("direct");
    EXPECT_TRUE(technique.ok());
    render::RenderSettings settings;
    settings.pcfRadius = 0;
    auto pipeline = Pipeline::create(scene, std::move(*technique), {size, size}, settings);
    EXPECT_TRUE(pipeline.ok()) << pipeline.error().message;
    return pipeline.ok() ? std::move(*pipeline) : nullptr;
}

// Two 4 m grey planes, the lower (y = 0) facing up and the upper (y = 1) facing down, with a
// horizontal 0.6 x 0.4 m light between them whose front faces down; an orthographic camera 5 m above
// the upper plane or below the lower one, which it sees through (the rasteriser culls back faces).
Scene twoPlanes(bool twoSided, bool fromAbove) {
    Scene s;
    s.name = "two-planes";
    Mesh m;
    m.name = "planes";
    const float h = 2.0f;
    m.positions = {{-h, 0, -h}, {h, 0, -h}, {h, 0, h}, {-h, 0, h}, {-h, 1, -h}, {h, 1, -h}, {h, 1, h}, {-h, 1, h}};
    m.indices = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7};  // lower faces +y, upper faces -y
    s.meshes.push_back(m);
    Material mat;
    mat.name = "grey";
    mat.baseColor = glm::vec3(kAlbedo);
    s.materials.push_back(mat);
    Object o;
    o.name = "planes";
    s.objects.push_back(o);
    Light l;
    l.name = "panel";
    l.type = LightType::Area;
    l.position = {0.0f, kLightHeight, 0.0f};
    l.edgeU = {2.0f * kHalfX, 0.0f, 0.0f};
    l.edgeV = {0.0f, 0.0f, 2.0f * kHalfZ};  // cross(u, v) = -y: the front faces down
    l.radiance = glm::vec3(kRadiance);
    l.twoSided = twoSided;
    s.lights.push_back(l);
    s.camera.projection = Projection::Orthographic;
    s.camera.orthoHeight = kView;
    s.camera.position = fromAbove ? glm::vec3(0, 6, 0) : glm::vec3(0, -5, 0);
    s.camera.target = {0, 0.5f, 0};
    s.camera.up = {0, 0, -1};
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 20.0f;
    EXPECT_TRUE(finalizeScene(s).ok());
    return s;
}

// Irradiance at distance d from the plane of a uniform kHalfX x kHalfZ (half edges) rectangle of
// radiance L, at offset (px, pz) from the point under its centre: pi L F, F summed from the corner form
// factor of analytic-tests.md over the rectangle's corners (signed).
float rectangleIrradiance(float px, float pz, float d) {
    auto cornerF = [d](float a, float b) {
        const float A = std::abs(a) / d, B = std::abs(b) / d;
        const float sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
        const float f = (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0f * glm::pi<float>());
        return (a < 0 ? -1.0f : 1.0f) * (b < 0 ? -1.0f : 1.0f) * f;
    };
    const float x0 = -kHalfX - px, x1 = kHalfX - px, z0 = -kHalfZ - pz, z1 = kHalfZ - pz;
    return glm::pi<float>() * kRadiance * (cornerF(x1, z1) - cornerF(x0, z1) - cornerF(x1, z0) + cornerF(x0, z0));
}

std::vector<glm::vec4> readEmission(const Pipeline& p, glm::ivec2 size) {
    std::vector<glm::vec4> texels(static_cast<size_t>(size.x) * size.y);
    glGetTextureImage(p.gbuffer().emission().id(), 0, GL_RGBA, GL_FLOAT,
                      static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)), texels.data());
    return texels;  // GL order: row 0 at the bottom
}

}  // namespace

// A two-sided light lights the plane above it as the plane below, each with the polygon irradiance of
// its rectangle 0.5 m away, unshadowed (the emitter is not geometry: its cube map at the centre sees
// both planes). A one-sided light leaves the plane behind it black. Points outside the light's footprint
// are compared (over it the camera sees the emitter); 5e-3 relative covers the shader's float acos()
// of nearly parallel edge vectors for far points, as in DirectLightingGpuTest.
TEST_F(TexturedAreaLightGpuTest, TwoSidedLightLightsBothSides) {
    constexpr int kSize = 64;
    for (bool fromAbove : {true, false}) {
        SCOPED_TRACE(fromAbove ? "lower plane, seen from above" : "upper plane, seen from below");
        const Scene scene = twoPlanes(true, fromAbove);  // the pipeline keeps a reference
        auto p = makePipeline(scene, kSize);
        ASSERT_TRUE(p);
        p->renderFrame(0);
        const Image image = p->readback(Component::Direct);
        int checked = 0;
        for (int y = 1; y < kSize; y += 4)
            for (int x = 1; x < kSize; x += 4) {
                // Image column x is world x (from above) or -x (from below, mirrored); row y is z.
                const float wx = ((x + 0.5f) / kSize - 0.5f) * kView * (fromAbove ? 1.0f : -1.0f);
                const float wz = ((y + 0.5f) / kSize - 0.5f) * kView;
                if (std::abs(wx) < kHalfX + 0.1f && std::abs(wz) < kHalfZ + 0.1f) continue;
                const float expected = kAlbedo / glm::pi<float>() * rectangleIrradiance(wx, wz, kLightHeight);
                EXPECT_NEAR(image.at(x, y).r, expected, 5e-3f * expected + 1e-6f) << "pixel " << x << "," << y;
                ++checked;
            }
        EXPECT_GT(checked, 200);
        // Over the light's centre the camera sees an emitting face either way.
        EXPECT_NEAR(image.at(kSize / 2, kSize / 2).r, kRadiance, 1e-5f);
    }
    const Scene oneSidedScene = twoPlanes(false, false);
    auto oneSided = makePipeline(oneSidedScene, kSize);
    ASSERT_TRUE(oneSided);
    oneSided->renderFrame(0);
    const Image below = oneSided->readback(Component::Direct);
    EXPECT_EQ(below.at(5, 5).r, 0.0f) << "the upper plane is behind a one-sided light";
    EXPECT_NEAR(below.at(kSize / 2, kSize / 2).r, kRadiance, 1e-5f) << "its front faces the camera below";
}

// A textured emitter seen by the camera shows its texture in the G-buffer's emission: a 2 x 1 texture,
// red on the left (u < 1/2), green on the right, on a 1.6 x 0.9 m screen facing the camera (pixels
// 19.2 to 44.8 of the 64-pixel, 4 m view). The texture is filtered bilinearly, clamped at its edges:
// between the texel centres (u = 1/4 and 3/4) it blends, outside them it is one texel exactly, so the
// pixels checked lie at u < 0.2 and u > 0.8; 0.01 covers float rounding of the RGBA32F chain.
TEST_F(TexturedAreaLightGpuTest, EmitterShowsItsTexture) {
    Scene s = gputest::planeScene(Light{}, Projection::Orthographic);
    s.lights.clear();
    Light screen;
    screen.name = "screen";
    screen.type = LightType::Area;
    screen.position = {0.0f, 1.0f, 0.0f};
    screen.edgeU = {1.6f, 0.0f, 0.0f};   // u to the right in the image
    screen.edgeV = {0.0f, 0.0f, -0.9f};  // v up in the image (row 0 is -z); cross(u, v) = +y, to the camera
    screen.radiance = glm::vec3(3.0f);
    Image texture(2, 1);
    texture.at(0, 0) = glm::vec3(1.0f, 0.0f, 0.0f);
    texture.at(1, 0) = glm::vec3(0.0f, 1.0f, 0.0f);
    screen.texture.kind = AreaTexture::Kind::Images;
    screen.texture.frames = {static_cast<uint32_t>(s.textures.size())};
    s.textures.push_back({"red-green", texture});
    s.lights.push_back(screen);
    ASSERT_TRUE(finalizeScene(s).ok());
    constexpr int kSize = 64;
    auto p = makePipeline(s, kSize);
    ASSERT_TRUE(p);
    p->renderFrame(0);
    const std::vector<glm::vec4> e = readEmission(*p, {kSize, kSize});
    const auto at = [&](int x, int yFromTop) { return glm::vec3(e[static_cast<size_t>(kSize - 1 - yFromTop) * kSize + x]); };
    for (int y : {28, 32, 35}) {
        for (int x : {20, 22, 24}) {  // u = 0.04, 0.11, 0.19
            EXPECT_NEAR(at(x, y).r, 3.0f, 0.01f) << x << "," << y;
            EXPECT_NEAR(at(x, y).g, 0.0f, 0.01f) << x << "," << y;
        }
        for (int x : {40, 42, 44}) {  // u = 0.82, 0.89, 0.97
            EXPECT_NEAR(at(x, y).r, 0.0f, 0.01f) << x << "," << y;
            EXPECT_NEAR(at(x, y).g, 3.0f, 0.01f) << x << "," << y;
        }
    }
    EXPECT_EQ(at(5, 5), glm::vec3(0.0f)) << "off the screen: the plane emits nothing";
}
