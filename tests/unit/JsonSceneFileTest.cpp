// JSON scene files: models, lights, camera and animations placed, the committed example, leak regions,
// area-light textures, and the errors bad input must give (with line and column: JsonLocator).
#include "core/ImageIo.h"
#include "scene/JsonLocator.h"
#include "scene/SceneLoader.h"
#include "SceneFileTestSupport.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace bounce;
using namespace bounce::scenefiletest;

TEST(JsonScene, PlacesModelsLightsCameraAndAnimations) {
    writeFile("json/models/cube.obj", kCubeObj);
    const fs::path p = writeFile("json/scene.json", R"({
  "name": "test",
  "frameRate": 24,
  "settings": {"vpl.count": 128, "vct.enabled": true, "rsm.mode": "splat"},
  "materials": {"gold": {"baseColor": [0.9, 0.7, 0.2], "metallic": 1, "roughness": 0.3}},
  "objects": [
    {"name": "box", "model": "models/cube.obj", "material": "gold",
     "transform": {"translation": [1, 0.5, 0], "rotation": {"axis": [0, 1, 0], "degrees": 90}, "scale": [2, 1, 1]}},
    {"name": "mover", "model": "models/cube.obj", "material": {"baseColor": 0.5, "emission": [1, 2, 3]},
     "animation": {"interpolation": "catmull-rom", "loop": false,
                   "keys": [{"time": 0, "translation": [0, 0, 0]}, {"time": 2, "translation": [4, 0, 0]}]}}
  ],
  "lights": [
    {"name": "lamp", "type": "spot", "position": [0, 3, 0], "target": [0, 0, 0], "intensity": [1, 2, 3],
     "cutoffDegrees": 30, "falloffExponent": 2},
    {"name": "panel", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 0.5], "radiance": 4}
  ],
  "camera": {"position": [0, 1, 5], "target": [0, 1, 0], "fovDegrees": 50, "near": 0.05, "far": 80,
             "animation": {"keys": [{"time": 0}, {"time": 1, "translation": [0, 1, 0]}]}}
})");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->name, "test");
    EXPECT_EQ(scene->source, p.string());
    EXPECT_FLOAT_EQ(scene->frameRate, 24.0f);
    EXPECT_EQ(scene->settings.at("vpl.count"), "128");
    EXPECT_EQ(scene->settings.at("vct.enabled"), "true");
    EXPECT_EQ(scene->settings.at("rsm.mode"), "splat");

    const Object* box = findObject(*scene, "box");
    const Object* mover = findObject(*scene, "mover");
    ASSERT_TRUE(box && mover);
    EXPECT_EQ(scene->materials[box->material].name, "gold");
    EXPECT_FLOAT_EQ(scene->materials[box->material].metallic, 1.0f);
    EXPECT_EQ(scene->materials[mover->material].emission, glm::vec3(1, 2, 3));
    // Scale 2 along x, then 90 degrees about y puts that length along z; translated by (1, 0.5, 0).
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const glm::vec3& q : scene->meshes[box->mesh].positions) {
        const glm::vec3 w(box->worldFromObject(0.0f) * glm::vec4(q, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
    EXPECT_NEAR(hi.z - lo.z, 2.0f, 1e-5f);
    EXPECT_NEAR(hi.x - lo.x, 1.0f, 1e-5f);
    EXPECT_NEAR(0.5f * (lo.x + hi.x), 1.0f, 1e-5f);
    EXPECT_NEAR(lo.y, 0.0f, 1e-5f);

    EXPECT_FALSE(box->isDynamic());
    ASSERT_TRUE(mover->isDynamic());
    EXPECT_EQ(mover->animation.interpolation, Interpolation::CatmullRom);
    EXPECT_FALSE(mover->animation.loop);
    EXPECT_NEAR(mover->worldFromObject(1.0f)[3].x, 2.0f, 1e-5f);  // two keys: Catmull-Rom is linear between them
    EXPECT_NEAR(mover->worldFromObject(5.0f)[3].x, 4.0f, 1e-5f);  // held after the end (no loop)

    ASSERT_EQ(scene->lights.size(), 2u);
    const Light& lamp = scene->lights[0];
    EXPECT_EQ(lamp.type, LightType::Spot);
    EXPECT_NEAR(lamp.direction.y, -1.0f, 1e-6f);
    EXPECT_NEAR(lamp.cutoffAngle, glm::radians(30.0f), 1e-6f);
    EXPECT_EQ(lamp.intensity, glm::vec3(1, 2, 3));
    const Light& panel = scene->lights[1];
    EXPECT_NEAR(panel.area(), 0.5f, 1e-6f);
    EXPECT_NEAR(panel.areaNormal().y, -1.0f, 1e-6f);  // cross(+x, +z) = -y

    EXPECT_NEAR(scene->camera.verticalFov, glm::radians(50.0f), 1e-6f);
    // Looping by default: halfway through the key range the camera has risen by half of 1 m.
    EXPECT_NEAR(scene->camera.at(0.5f).position.y, 1.5f, 1e-5f);
}

TEST(JsonScene, CommittedExampleLoads) {
    const fs::path example = fs::path(BOUNCE_SOURCE_DIR) / "scenes" / "example.json";
    Expected<Scene> scene = loadScene(example.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    EXPECT_EQ(scene->name, "example");
    EXPECT_EQ(scene->objects.size(), 3u);
    EXPECT_EQ(scene->lights.size(), 4u);  // one of each type
    EXPECT_EQ(scene->triangleCount(), 2u + 12u + 12u);
    EXPECT_TRUE(findObject(*scene, "spinner")->isDynamic());
    EXPECT_FALSE(findObject(*scene, "crate")->isDynamic());
    // The crate keeps its MTL colour; the spinner's is overridden.
    EXPECT_NEAR(scene->materials[findObject(*scene, "crate")->material].baseColor.b, 0.7f, 1e-6f);
    EXPECT_EQ(scene->materials[findObject(*scene, "spinner")->material].name, "orange");
    const Light& key = scene->lights[0];
    ASSERT_TRUE(key.isDynamic());
    EXPECT_GT(glm::length(key.at(1.0f).position - key.at(0.0f).position), 0.5f);  // moves on its loop
    EXPECT_EQ(scene->settings.at("rsm.vplGrid"), "16");
}

TEST(JsonScene, MalformedJsonReportsLineAndColumn) {
    const fs::path p = writeFile("bad/syntax.json", "{\n  \"name\": \"x\",\n  \"objects\": [\n    {\"model\": \"a.obj\"\n  ]\n}\n");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_FALSE(scene.ok());
    EXPECT_TRUE(contains(scene.error().message, "syntax.json:5:")) << scene.error().message;
}

TEST(JsonScene, UnknownKeyNamesItAndTheKnownKeys) {
    writeFile("bad/models/cube.obj", kCubeObj);
    const fs::path p = writeFile("bad/typo.json", "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                                                  "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n"
                                                  "  \"lihgts\": []\n}\n");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_FALSE(scene.ok());
    const std::string& msg = scene.error().message;
    EXPECT_TRUE(contains(msg, "typo.json:4:")) << msg;
    EXPECT_TRUE(contains(msg, "\"lihgts\"")) << msg;
    EXPECT_TRUE(contains(msg, "lights")) << msg;
    EXPECT_TRUE(contains(msg, "camera")) << msg;

    const fs::path q = writeFile("bad/lightkey.json", "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                                                      "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n"
                                                      "  \"lights\": [\n    {\"name\": \"k\", \"type\": \"point\",\n"
                                                      "     \"position\": [0, 1, 0], \"intensity\": 1, \"radius\": 2}\n  ]\n}\n");
    Expected<Scene> light = loadScene(q.string());
    ASSERT_FALSE(light.ok());
    EXPECT_TRUE(contains(light.error().message, "lightkey.json:6:")) << light.error().message;
    EXPECT_TRUE(contains(light.error().message, "light 'k'")) << light.error().message;
    EXPECT_TRUE(contains(light.error().message, "intensity")) << light.error().message;
}

TEST(JsonScene, NonFiniteLightValues) {
    writeFile("nan/models/cube.obj", kCubeObj);
    const std::string head = "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                             "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n  \"lights\": [\n";
    // JSON has no NaN literal: it is a syntax error at its line.
    const fs::path literal = writeFile("nan/literal.json", head + "    {\"name\": \"k\", \"type\": \"point\", \"position\": [0, 1, 0],\n"
                                                                  "     \"intensity\": NaN}\n  ]\n}\n");
    Expected<Scene> a = loadScene(literal.string());
    ASSERT_FALSE(a.ok());
    EXPECT_TRUE(contains(a.error().message, "literal.json:6:")) << a.error().message;
    // An overflowing number parses to infinity and is rejected where it stands.
    const fs::path overflow = writeFile("nan/overflow.json", head + "    {\"name\": \"k\", \"type\": \"point\", \"position\": [0, 1, 0],\n"
                                                                    "     \"intensity\": [1, 1e999, 1]}\n  ]\n}\n");
    Expected<Scene> b = loadScene(overflow.string());
    ASSERT_FALSE(b.ok());
    EXPECT_TRUE(contains(b.error().message, "overflow.json:6:")) << b.error().message;
    EXPECT_TRUE(contains(b.error().message, "finite")) << b.error().message;
}

TEST(JsonScene, MissingFilesAndReferences) {
    Expected<Scene> none = loadScene((tempDir() / "absent.json").string());
    ASSERT_FALSE(none.ok());
    EXPECT_TRUE(contains(none.error().message, "absent.json")) << none.error().message;

    const fs::path p = writeFile("refs/scene.json", "{\n  \"objects\": [\n    {\"name\": \"ghost\", \"model\": \"models/ghost.obj\"}\n  ],\n"
                                                    "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}\n}\n");
    Expected<Scene> model = loadScene(p.string());
    ASSERT_FALSE(model.ok());
    EXPECT_TRUE(contains(model.error().message, "scene.json:3:")) << model.error().message;
    EXPECT_TRUE(contains(model.error().message, "ghost.obj")) << model.error().message;

    writeFile("refs/models/cube.obj", kCubeObj);
    const fs::path m = writeFile("refs/material.json", "{\n  \"objects\": [\n    {\"model\": \"models/cube.obj\", \"material\": \"steel\"}\n  ],\n"
                                                       "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}\n}\n");
    Expected<Scene> material = loadScene(m.string());
    ASSERT_FALSE(material.ok());
    EXPECT_TRUE(contains(material.error().message, "\"steel\"")) << material.error().message;

    // A missing texture is a warning, not an error.
    const fs::path t = writeFile("refs/texture.json", "{\n  \"materials\": {\"wood\": {\"baseColor\": 0.4, \"baseColorTexture\": \"wood.png\"}},\n"
                                                      "  \"objects\": [{\"model\": \"models/cube.obj\", \"material\": \"wood\"}],\n"
                                                      "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}\n}\n");
    LogCapture log;
    Expected<Scene> textured = loadScene(t.string());
    ASSERT_TRUE(textured.ok()) << textured.error().message;
    EXPECT_EQ(textured->materials[0].baseColorTexture, -1);
    EXPECT_TRUE(contains(log.text(), "wood.png")) << log.text();

    // An emission texture loads like a base-colour texture; missing, it is a warning too.
    ASSERT_TRUE(writeImage(tempDir() / "refs/glow.exr", Image(2, 1, glm::vec3(0.5f))).ok());
    const fs::path e = writeFile("refs/emission.json", "{\n  \"materials\": {\"lamp\": {\"emission\": 2, \"emissionTexture\": \"glow.exr\"},\n"
                                                       "    \"dud\": {\"emission\": 2, \"emissionTexture\": \"none.png\"}},\n"
                                                       "  \"objects\": [{\"model\": \"models/cube.obj\", \"material\": \"lamp\"}],\n"
                                                       "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}\n}\n");
    Expected<Scene> glowing = loadScene(e.string());
    ASSERT_TRUE(glowing.ok()) << glowing.error().message;
    const Material* lamp = findMaterial(*glowing, "lamp");
    const Material* dud = findMaterial(*glowing, "dud");
    ASSERT_TRUE(lamp && dud);
    ASSERT_GE(lamp->emissionTexture, 0);
    EXPECT_EQ(glowing->textures[static_cast<size_t>(lamp->emissionTexture)].image.at(1, 0), glm::vec3(0.5f));
    EXPECT_EQ(dud->emissionTexture, -1);
    EXPECT_TRUE(contains(log.text(), "none.png")) << log.text();
}

TEST(JsonScene, LeakRegions) {
    writeFile("leak/models/cube.obj", kCubeObj);
    const std::string head = "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                             "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n  \"leakRegions\": ";
    const auto load = [&](const std::string& name, const std::string& regions) {
        return loadScene(writeFile("leak/" + name, head + regions + "\n}\n").string());
    };
    Expected<Scene> none = load("none.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]},\n"
                                             "   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}");
    ASSERT_TRUE(none.ok()) << none.error().message;
    ASSERT_TRUE(none->leakRegions.has_value());
    EXPECT_EQ(none->leakRegions->darkMin, glm::vec3(0.0f));
    EXPECT_EQ(none->leakRegions->darkMax, glm::vec3(1.0f));
    EXPECT_EQ(none->leakRegions->litMin, glm::vec3(-1.0f));
    EXPECT_EQ(none->leakRegions->litMax, glm::vec3(0.0f, 1.0f, 1.0f));  // touching at x = 0: open boxes share no point
    Expected<Scene> without = loadScene(writeFile("leak/without.json", head + "null\n}\n").string());
    ASSERT_FALSE(without.ok());  // null is not an object
    EXPECT_TRUE(contains(without.error().message, "without.json:4:")) << without.error().message;

    struct Bad {
        const char* name;
        std::string regions;
        std::vector<std::string> says;  // the message names the file and line, the key and the problem
    };
    const std::vector<Bad> bad = {
        {"missing-lit.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]}}", {"missing-lit.json:4:", "\"lit\""}},
        {"unknown.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]},\n   \"grey\": {}}",
         {"unknown.json:6:", "\"grey\"", "dark, lit"}},
        {"box-key.json", "{\"dark\": {\"min\": [0, 0, 0], \"maximum\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}",
         {"box-key.json:4:", "\"maximum\"", "leak region 'dark'", "max, min"}},
        {"empty.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1],\n           \"max\": [0, 1, -1]}}",
         {"empty.json:6:", "leakRegions/lit/max", "not above min -1 on z"}},
        {"short.json", "{\"dark\": {\"min\": [0, 0], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}",
         {"short.json:4:", "leakRegions/dark/min", "3 numbers"}},
        {"text.json", "{\"dark\": {\"min\": [0, 0, \"0\"], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}",
         {"text.json:4:", "leakRegions/dark/min/2", "the string \"0\""}},
        {"infinite.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1e999, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0, 1, 1]}}",
         {"infinite.json:4:", "not finite"}},  // the JSON parser refuses the overflow at its line
        {"overlap.json", "{\"dark\": {\"min\": [0, 0, 0], \"max\": [1, 1, 1]},\n   \"lit\": {\"min\": [-1, -1, -1], \"max\": [0.5, 1, 1]}}",
         {"overlap.json:5:", "overlap"}},
    };
    for (const Bad& b : bad) {
        Expected<Scene> scene = load(b.name, b.regions);
        ASSERT_FALSE(scene.ok()) << b.name;
        for (const std::string& part : b.says) EXPECT_TRUE(contains(scene.error().message, part)) << b.name << ": " << scene.error().message;
        EXPECT_EQ(scene.error().message.find('\n'), std::string::npos) << b.name;
    }
}

TEST(JsonScene, AreaLightTexturesAndTwoSided) {
    writeFile("arealight/models/cube.obj", kCubeObj);
    // A PNG is decoded from sRGB: full red and green stay 1 and 0 exactly, 8-bit 128 is 0.2158 (sRGB EOTF).
    Image still(2, 1);
    still.at(0, 0) = glm::vec3(1.0f, 0.0f, 0.0f);
    still.at(1, 0) = glm::vec3(0.0f, 1.0f, 0.0f);
    ASSERT_TRUE(writeImage(tempDir() / "arealight/still.png", still, ToneMap{0.0f, ToneCurve::Clamp}).ok());
    ASSERT_TRUE(writeImage(tempDir() / "arealight/f0.exr", Image(4, 2, glm::vec3(0.25f))).ok());
    ASSERT_TRUE(writeImage(tempDir() / "arealight/f1.exr", Image(4, 2, glm::vec3(3.0f))).ok());
    const fs::path p = writeFile("arealight/scene.json", R"({
  "objects": [{"model": "models/cube.obj"}],
  "camera": {"position": [0, 0, 5], "target": [0, 0, 0]},
  "lights": [
    {"name": "still", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 1],
     "radiance": 2, "twoSided": true, "texture": "still.png"},
    {"name": "video", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 1],
     "radiance": 2, "texture": {"frames": ["f0.exr", "f1.exr"], "frameRate": 12}},
    {"name": "square", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 1],
     "radiance": 2, "texture": {"pattern": "bouncing-square", "resolution": 32, "size": 0.5,
                                "velocity": [0.1, -0.2], "start": [0.5, 0.25]}},
    {"name": "plain", "type": "area", "position": [0, 2, 0], "edgeU": [1, 0, 0], "edgeV": [0, 0, 1], "radiance": 2}
  ]
})");
    Expected<Scene> scene = loadScene(p.string());
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    ASSERT_EQ(scene->lights.size(), 4u);
    const Light& still0 = scene->lights[0];
    EXPECT_TRUE(still0.twoSided);
    ASSERT_EQ(still0.texture.kind, AreaTexture::Kind::Images);
    ASSERT_EQ(still0.texture.frames.size(), 1u);
    const Image& png = scene->textures[still0.texture.frames[0]].image;
    ASSERT_EQ(png.width(), 2);
    EXPECT_EQ(png.at(0, 0), glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(png.at(1, 0), glm::vec3(0.0f, 1.0f, 0.0f));

    const Light& video = scene->lights[1];
    EXPECT_FALSE(video.twoSided);
    ASSERT_EQ(video.texture.frames.size(), 2u);
    EXPECT_FLOAT_EQ(video.texture.frameRate, 12.0f);
    EXPECT_EQ(scene->textures[video.texture.frames[0]].image.at(3, 1), glm::vec3(0.25f));  // EXR is linear as stored
    EXPECT_EQ(scene->textures[video.texture.frames[1]].image.at(0, 0), glm::vec3(3.0f));

    const AreaTexture& sq = scene->lights[2].texture;
    EXPECT_EQ(sq.kind, AreaTexture::Kind::BouncingSquare);
    EXPECT_EQ(sq.resolution, 32);
    EXPECT_FLOAT_EQ(sq.squareSize, 0.5f);
    EXPECT_EQ(sq.squareVelocity, glm::vec2(0.1f, -0.2f));
    EXPECT_EQ(sq.squareStart, glm::vec2(0.5f, 0.25f));

    EXPECT_FALSE(scene->lights[3].texture.textured());
    EXPECT_FALSE(scene->lights[3].twoSided);
}

TEST(JsonScene, AreaLightTextureBadInput) {
    writeFile("areabad/models/cube.obj", kCubeObj);
    ASSERT_TRUE(writeImage(tempDir() / "areabad/small.exr", Image(2, 2, glm::vec3(1.0f))).ok());
    ASSERT_TRUE(writeImage(tempDir() / "areabad/large.exr", Image(4, 2, glm::vec3(1.0f))).ok());
    Image negative(2, 2, glm::vec3(1.0f));
    negative.at(1, 1) = glm::vec3(-1.0f);
    ASSERT_TRUE(writeImage(tempDir() / "areabad/negative.exr", negative).ok());
    writeFile("areabad/garbage.png", "this is not a PNG file");
    int n = 0;
    // The light's extra keys are on line 5 of the file: every error names the file, that line and `expect`.
    // `tail`: the light's last keys.
    const auto fails = [&](const std::string& type, const std::string& extra, const std::string& tail, const std::string& expect) {
        SCOPED_TRACE(extra);
        const std::string name = "case" + std::to_string(n++) + ".json";
        const fs::path p = writeFile("areabad/" + name,
                                     "{\n  \"objects\": [{\"model\": \"models/cube.obj\"}],\n"
                                     "  \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n"
                                     "  \"lights\": [{\"name\": \"screen\", \"type\": \"" + type + "\",\n" +
                                         "    " + extra + ",\n"
                                         "    \"position\": [0, 2, 0], \"edgeU\": [1, 0, 0], \"edgeV\": [0, 0, 1], " +
                                         tail + "}]\n}\n");
        Expected<Scene> scene = loadScene(p.string());
        ASSERT_FALSE(scene.ok());
        const std::string& msg = scene.error().message;
        EXPECT_TRUE(contains(msg, name + ":5:")) << msg;
        EXPECT_TRUE(contains(msg, expect)) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    };
    // `check` gives a non-area light area keys too: "texture" and "twoSided" must be reported before the
    // unknown-key check would name the others. `area` cases are well-formed area lights but for `extra`.
    const auto check = [&](const std::string& type, const std::string& extra, const std::string& expect) {
        fails(type, extra, R"("radiance": 1, "intensity": 1)", expect);
    };
    const auto area = [&](const std::string& extra, const std::string& expect) { fails("area", extra, R"("radiance": 1)", expect); };
    area(R"("texture": "absent.png")", "absent.png: file not found");
    area(R"("texture": "garbage.png")", "garbage.png");
    area(R"("texture": "negative.exr")", "negative texel");
    area(R"("texture": 3)", "must be an image path");
    area(R"("texture": {"frames": ["small.exr", "large.exr"]})", "frame 1 is 4x2, frame 0 is 2x2");
    area(R"("texture": {"frames": []})", "non-empty array");
    area(R"("texture": {"frames": ["small.exr", "absent.exr"]})", "absent.exr: file not found");
    area(R"("texture": {"frames": ["small.exr"], "frameRate": 0})", "frame rate must be positive");
    area(R"("texture": {"frames": ["small.exr"], "frameRate": -24})", "outside");
    area(R"("texture": {"frames": ["small.exr"], "fps": 24})", "unknown key \"fps\"");
    area(R"("texture": {"frames": ["small.exr"], "pattern": "bouncing-square"})", "exactly one of");
    area(R"("texture": {"pattern": "checkerboard"})", "unknown texture pattern \"checkerboard\"");
    area(R"("texture": {"pattern": "bouncing-square", "resolution": 0})", "resolution must be an integer");
    area(R"("texture": {"pattern": "bouncing-square", "resolution": 2.5})", "resolution must be an integer");
    area(R"("texture": {"pattern": "bouncing-square", "resolution": 100000})", "resolution must be an integer");
    area(R"("texture": {"pattern": "bouncing-square", "size": 0})", "size must be in (0, 1]");
    area(R"("texture": {"pattern": "bouncing-square", "size": 1.5})", "outside [0, 1]");
    area(R"("texture": {"pattern": "bouncing-square", "velocity": [1]})", "array of 2 numbers");
    area(R"("texture": {"pattern": "bouncing-square", "start": [0.5, 2]})", "outside [0, 1]");
    area(R"("texture": {"pattern": "bouncing-square", "speed": 1})", "unknown key \"speed\"");
    area(R"("twoSided": "yes")", "expected true or false");
    check("point", R"("texture": "small.exr")", "applies to area lights only");
    check("spot", R"("twoSided": true)", "applies to area lights only");
}

TEST(JsonLocator, FindsLinesOfKeysAndElements) {
    const std::string text = "{\n  \"a\": 1,\n  \"b\": [\n    {\"c\": \"x\"},\n    {\"d\": 2}\n  ],\n  \"e/f\": {}\n}\n";
    const JsonLocator locator(text);
    EXPECT_EQ(locator.line(""), 1);
    EXPECT_EQ(locator.line("/a"), 2);
    EXPECT_EQ(locator.line("/b"), 3);
    EXPECT_EQ(locator.line("/b/0/c"), 4);
    EXPECT_EQ(locator.line("/b/1"), 5);
    EXPECT_EQ(locator.line("/b/1/d"), 5);
    EXPECT_EQ(locator.line("/e~1f"), 7);
    EXPECT_EQ(locator.line("/b/1/zzz"), 5);  // nearest ancestor
    EXPECT_EQ(JsonLocator::lineColumn(text, 0), std::make_pair(1, 1));
    EXPECT_EQ(JsonLocator::lineColumn(text, 4), std::make_pair(2, 3));
}
