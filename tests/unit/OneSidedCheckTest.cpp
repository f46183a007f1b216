// The one-sided default and the check for one-sided surfaces wound the wrong way (docs/scene.md
// "One-sided or two-sided"; reference/OneSidedCheck.h), on scene files as a user writes them.
#include "reference/OneSidedCheck.h"
#include "scene/SceneLoader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace bounce;

namespace {

fs::path dir() {
    static const fs::path d = [] {
        fs::path p = fs::temp_directory_path() / ("bounce-one-sided-test-" + std::to_string(::getpid()));
        fs::create_directories(p);
        return p;
    }();
    return d;
}

void write(const std::string& name, const std::string& text) { std::ofstream(dir() / name, std::ios::binary) << text; }

// A 4 m square floor at y = 0, its triangles wound to face +y (up) or -y (down), seen from above
// (camera at y = 2) and lit from above or below by a point light.
Scene floorScene(const std::string& name, bool facesUp, const std::string& material, float lightY) {
    write("up.obj", "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 1 0 -1\nf 1 2 3\nf 3 2 4\n");
    write("down.obj", "v 0 0 0\nv 0 0 -1\nv 1 0 0\nv 1 0 -1\nf 1 2 3\nf 3 2 4\n");
    write(name, fmt::format(R"({{"objects": [{{"name": "floor", "model": "{}"{}, "transform": {{"scale": 4, "translation": [-2, 0, 2]}}}}],
 "materials": {{"one": {{"twoSided": false}}, "plain": {{}}}},
 "camera": {{"position": [0, 2, 2], "target": [0, 0, 0]}},
 "lights": [{{"type": "point", "position": [0, {}, 0], "intensity": 1}}]}})",
                            facesUp ? "up.obj" : "down.obj", material.empty() ? "" : ", \"material\": \"" + material + "\"",
                            lightY));
    auto scene = loadScene((dir() / name).string());
    EXPECT_TRUE(scene.ok()) << scene.error().message;
    return scene.ok() ? std::move(*scene) : Scene{};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

// One default for both paths: a JSON material is two-sided unless it says otherwise, as the OBJ's own.
TEST(OneSided, JsonMaterialsAreTwoSidedByDefaultLikeObjMaterials) {
    const Scene plain = floorScene("plain.json", false, "plain", 1.0f);
    const Scene own = floorScene("own.json", false, "", 1.0f);
    const Scene one = floorScene("one.json", false, "one", 1.0f);
    ASSERT_FALSE(plain.objects.empty());
    EXPECT_TRUE(plain.materials[plain.objects[0].material].twoSided);  // JSON material, no twoSided key
    EXPECT_TRUE(own.materials[own.objects[0].material].twoSided);      // the OBJ's own material
    EXPECT_FALSE(one.materials[one.objects[0].material].twoSided);     // "twoSided": false
}

// A one-sided floor wound downward, seen and lit from above: both findings, naming file and object.
TEST(OneSided, ReversedFloorIsReportedForCameraAndLights) {
    const Scene scene = floorScene("reversed.json", false, "one", 1.0f);
    const auto messages = checkOneSidedSurfaces(scene, {64, 64}, 0);
    ASSERT_EQ(messages.size(), 2u);
    for (const std::string& m : messages) {
        EXPECT_TRUE(contains(m, "reversed.json")) << m;
        EXPECT_TRUE(contains(m, "object 'floor'")) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;  // one line each
    }
    EXPECT_TRUE(contains(messages[0], "seen from behind over")) << messages[0];
    EXPECT_TRUE(contains(messages[1], "every light is behind it")) << messages[1];
}

TEST(OneSided, CorrectOrTwoSidedFloorsAreNotReported) {
    EXPECT_TRUE(checkOneSidedSurfaces(floorScene("right.json", true, "one", 1.0f), {64, 64}, 0).empty());
    EXPECT_TRUE(checkOneSidedSurfaces(floorScene("both.json", false, "plain", 1.0f), {64, 64}, 0).empty());
}

// Wound toward the camera but lit from below: only the light finding. The share of the image is the
// one threshold: a tiny share of back faces (here none) is not reported.
TEST(OneSided, FloorLitFromBehindIsReportedForLightsOnly) {
    const auto messages = checkOneSidedSurfaces(floorScene("below.json", true, "one", -1.0f), {64, 64}, 0);
    ASSERT_EQ(messages.size(), 1u);
    EXPECT_TRUE(contains(messages[0], "every light is behind it")) << messages[0];
    const auto wide = checkOneSidedSurfaces(floorScene("tiny.json", false, "one", 1.0f), {64, 64}, 0,
                                            OneSidedCheckOptions{1.01f, 64});
    ASSERT_EQ(wide.size(), 1u);  // no share reaches 101 %: the camera finding is gone, the light one stays
    EXPECT_TRUE(contains(wide[0], "every light")) << wide[0];
}
