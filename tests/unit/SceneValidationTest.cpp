// finalizeScene: every rule in docs/scene.md "Validation", each on a small scene built in code.
#include "scene/SceneLoader.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <limits>

using namespace bounce;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// One triangle facing +z, one material, a point light and a camera looking at it.
Scene validScene() {
    Scene s;
    s.name = "tiny";
    s.source = "tiny.json";
    Mesh m;
    m.name = "tri";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2};
    s.meshes.push_back(m);
    Material mat;
    mat.name = "paint";
    s.materials.push_back(mat);
    Object o;
    o.name = "thing";
    s.objects.push_back(o);
    Light l;
    l.name = "bulb";
    l.type = LightType::Point;
    l.position = {0, 0, 2};
    l.intensity = glm::vec3(1.0f);
    s.lights.push_back(l);
    s.camera.position = {0, 0, 5};
    s.camera.target = {0, 0, 0};
    return s;
}

// finalizeScene fails and its message contains every one of `parts`.
template <class Mutate>
void expectRejected(Mutate mutate, std::initializer_list<const char*> parts) {
    Scene s = validScene();
    mutate(s);
    Expected<void> r = finalizeScene(s);
    ASSERT_FALSE(r.ok()) << "accepted; expected a message with " << *parts.begin();
    for (const char* part : parts) EXPECT_NE(r.error().message.find(part), std::string::npos) << r.error().message;
}

}  // namespace

TEST(FinalizeScene, AcceptsAValidSceneAndComputesNormals) {
    Scene s = validScene();
    ASSERT_TRUE(finalizeScene(s).ok());
    ASSERT_EQ(s.meshes[0].normals.size(), 3u);
    for (const glm::vec3& n : s.meshes[0].normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(FinalizeScene, AreaWeightedVertexNormals) {
    // Two triangles share vertex 0: a large one facing +z (area 2) and a small one facing +x (area 0.5).
    Scene s = validScene();
    Mesh& m = s.meshes[0];
    m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 1, 0}, {0, 0, 1}};
    m.indices = {0, 1, 2, 0, 3, 4};
    ASSERT_TRUE(finalizeScene(s).ok());
    const glm::vec3 expected = glm::normalize(glm::vec3(0.5f, 0.0f, 2.0f));
    EXPECT_NEAR(glm::length(m.normals[0] - expected), 0.0f, 1e-6f);
}

TEST(FinalizeScene, DropsDegenerateTrianglesWithAWarning) {
    Scene s = validScene();
    Mesh& m = s.meshes[0];
    m.positions.push_back({2, 0, 0});  // collinear with vertices 0 and 1
    m.indices.insert(m.indices.end(), {0, 1, 3, 2, 2, 1});
    ASSERT_TRUE(finalizeScene(s).ok());
    EXPECT_EQ(m.triangleCount(), 1u);
}

TEST(FinalizeScene, RejectsBadGeometry) {
    expectRejected([](Scene& s) { s.objects.clear(); }, {"tiny.json", "no objects"});
    expectRejected([](Scene& s) { s.meshes[0].positions[1].x = kNaN; }, {"tri", "thing", "position 1"});
    expectRejected([](Scene& s) { s.meshes[0].normals = {{0, 0, 1}, {0, 0, kInf}, {0, 0, 1}}; }, {"tri", "normal 1"});
    expectRejected([](Scene& s) { s.meshes[0].uvs = {{0, 0}, {kNaN, 0}, {0, 1}}; }, {"tri", "uv 1"});
    expectRejected([](Scene& s) { s.meshes[0].uvs = {{0, 0}}; }, {"tri", "uvs"});
    expectRejected([](Scene& s) { s.meshes[0].indices[2] = 3; }, {"tri", "out of range"});
    expectRejected([](Scene& s) { s.meshes[0].indices.push_back(0); }, {"tri", "multiple of 3"});
    expectRejected([](Scene& s) { s.meshes[0].positions[2] = {2, 0, 0}; }, {"tri", "degenerate"});
    expectRejected([](Scene& s) { s.objects[0].mesh = 4; }, {"thing", "mesh index"});
    expectRejected([](Scene& s) { s.objects[0].material = 1; }, {"thing", "material index"});
    expectRejected([](Scene& s) { s.objects[0].transform[3][0] = kNaN; }, {"thing", "transform"});
    expectRejected([](Scene& s) { s.objects[0].transform[1] = glm::vec4(0.0f); }, {"thing", "singular"});
    expectRejected(
        [](Scene& s) {
            s.objects[0].animation.keys.resize(2);
            s.objects[0].animation.keys[0].time = 1.0f;
        },
        {"thing", "sorted"});
    expectRejected(
        [](Scene& s) {
            s.objects[0].animation.keys.resize(1);
            s.objects[0].animation.keys[0].translation.y = kInf;
        },
        {"thing", "non-finite"});
}

TEST(FinalizeScene, RejectsBadMaterialsAndTextures) {
    expectRejected([](Scene& s) { s.materials[0].baseColor.r = 1.5f; }, {"paint", "base colour"});
    expectRejected([](Scene& s) { s.materials[0].baseColor.g = -0.1f; }, {"paint", "base colour"});
    expectRejected([](Scene& s) { s.materials[0].baseColor.b = kNaN; }, {"paint", "finite"});
    expectRejected([](Scene& s) { s.materials[0].roughness = 1.2f; }, {"paint", "roughness"});
    expectRejected([](Scene& s) { s.materials[0].metallic = -1.0f; }, {"paint", "metallic"});
    expectRejected([](Scene& s) { s.materials[0].emission = glm::vec3(-1.0f); }, {"paint", "negative emission"});
    expectRejected([](Scene& s) { s.materials[0].baseColorTexture = 0; }, {"paint", "texture index"});
    expectRejected(
        [](Scene& s) {
            Image img(2, 2, glm::vec3(0.5f));
            img.at(1, 1).g = kNaN;
            s.textures.push_back({"wood.png", img});
            s.materials[0].baseColorTexture = 0;
        },
        {"wood.png"});
}

TEST(FinalizeScene, RejectsBadLights) {
    expectRejected([](Scene& s) { s.lights[0].position.x = kNaN; }, {"bulb", "finite"});
    expectRejected([](Scene& s) { s.lights[0].intensity.r = -1.0f; }, {"bulb", "negative intensity"});
    expectRejected(
        [](Scene& s) {
            s.lights[0].type = LightType::Spot;
            s.lights[0].cutoffAngle = 0.0f;
        },
        {"bulb", "cutoff"});
    expectRejected(
        [](Scene& s) {
            s.lights[0].type = LightType::Spot;
            s.lights[0].direction = glm::vec3(0.0f);
        },
        {"bulb", "direction"});
    expectRejected(
        [](Scene& s) {
            s.lights[0].type = LightType::Area;
            s.lights[0].radiance = glm::vec3(1.0f);
            s.lights[0].edgeV = s.lights[0].edgeU;
        },
        {"bulb", "zero area"});
    expectRejected(
        [](Scene& s) {
            s.lights[0].type = LightType::Area;
            s.lights[0].radiance = glm::vec3(-1.0f);
        },
        {"bulb", "negative radiance"});
    expectRejected(
        [](Scene& s) {
            s.lights[0].type = LightType::Directional;
            s.lights[0].irradiance = glm::vec3(kInf);
        },
        {"bulb", "finite"});
}

TEST(FinalizeScene, RejectsBadAreaLightTextures) {
    // An area light with a two-frame sequence of 2x1 images; each case breaks one rule.
    const auto textured = [](Scene& s) {
        Light& l = s.lights[0];
        l.type = LightType::Area;
        l.radiance = glm::vec3(1.0f);
        l.texture.kind = AreaTexture::Kind::Images;
        s.textures.push_back({"a.png", Image(2, 1, glm::vec3(1.0f))});
        s.textures.push_back({"b.png", Image(2, 1, glm::vec3(0.5f))});
        l.texture.frames = {0, 1};
    };
    {
        Scene s = validScene();
        textured(s);
        ASSERT_TRUE(finalizeScene(s).ok());
    }
    expectRejected(
        [&](Scene& s) {
            textured(s);
            s.lights[0].texture.frames = {0, 7};
        },
        {"bulb", "frame 1", "out of range"});
    expectRejected(
        [&](Scene& s) {
            textured(s);
            s.lights[0].texture.frames.clear();
        },
        {"bulb", "no frames"});
    expectRejected(
        [&](Scene& s) {
            textured(s);
            s.textures[1].image = Image(3, 1, glm::vec3(1.0f));
        },
        {"bulb", "frame 1 is 3x1", "same size"});
    expectRejected(
        [&](Scene& s) {
            textured(s);
            s.lights[0].texture.frameRate = 0.0f;
        },
        {"bulb", "frame rate"});
    expectRejected(
        [&](Scene& s) {
            textured(s);
            s.textures[0].image.at(1, 0).g = -0.5f;
        },
        {"bulb", "negative or non-finite texel"});
    expectRejected(
        [&](Scene& s) {
            textured(s);
            s.lights[0].type = LightType::Point;
        },
        {"bulb", "only area lights"});
    expectRejected([](Scene& s) { s.lights[0].twoSided = true; }, {"bulb", "two-sided"});
    const auto square = [](Scene& s) {
        Light& l = s.lights[0];
        l.type = LightType::Area;
        l.radiance = glm::vec3(1.0f);
        l.texture.kind = AreaTexture::Kind::BouncingSquare;
    };
    expectRejected(
        [&](Scene& s) {
            square(s);
            s.lights[0].texture.resolution = 0;
        },
        {"bulb", "resolution 0"});
    expectRejected(
        [&](Scene& s) {
            square(s);
            s.lights[0].texture.squareSize = 1.5f;
        },
        {"bulb", "size 1.5"});
    expectRejected(
        [&](Scene& s) {
            square(s);
            s.lights[0].texture.squareVelocity.x = kNaN;
        },
        {"bulb", "not finite"});
}

TEST(FinalizeScene, RejectsBadCameras) {
    expectRejected([](Scene& s) { s.camera.target = s.camera.position; }, {"camera", "position equals target"});
    expectRejected([](Scene& s) { s.camera.verticalFov = 0.0f; }, {"camera", "field of view"});
    expectRejected([](Scene& s) { s.camera.verticalFov = glm::pi<float>(); }, {"camera", "field of view"});
    expectRejected([](Scene& s) { s.camera.position.z = kNaN; }, {"camera", "finite"});
    expectRejected([](Scene& s) { s.camera.up = glm::vec3(0, 0, 1); }, {"camera", "parallel"});
    expectRejected([](Scene& s) { s.camera.farPlane = s.camera.nearPlane; }, {"camera", "near"});
    expectRejected(
        [](Scene& s) {
            s.camera.projection = Projection::Orthographic;
            s.camera.orthoHeight = 0.0f;
        },
        {"camera", "orthographic"});
    expectRejected([](Scene& s) { s.frameRate = 0.0f; }, {"frame rate"});
    expectRejected([](Scene& s) { s.settings.emplace("count", std::string(1, '3')); }, {"count", "technique.setting"});
}
