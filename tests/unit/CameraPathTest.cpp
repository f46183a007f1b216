// Camera paths and bookmarks (scene/CameraPath.h): round trip, exact keys, validation messages, and
// the frame-pattern names `bounce render --camera-path` writes.
#include "scene/CameraPath.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace bounce {
namespace {

CameraPath twoKeys() {
    CameraPath p;
    p.scene = "cornell-box";
    p.keys.push_back({0.0f, {{0.1f, 0.2f, 3.3333333f}, {0.0f, 0.5f, 0.0f}, {0, 1, 0}, 0.7f}});
    p.keys.push_back({1.0f / 3.0f, {{1.0f, 0.25f, 2.0f}, {0.1f, 0.4f, 0.0f}, {0, 1, 0}, 0.5f}});
    p.lights.push_back({"spot", {0.0f, 1.9f, 0.1f}, {0.0f, -1.0f, 0.0f}});
    return p;
}

TEST(CameraPath, RoundTripIsExact) {
    const CameraPath p = twoKeys();
    auto q = parseCameraPath(cameraPathToJson(p), "mem");
    ASSERT_TRUE(q.ok()) << q.error().message;
    ASSERT_EQ(q->keys.size(), 2u);
    // Bit-exact: a replayed frame can only equal the viewer's frame when the camera does.
    EXPECT_EQ(q->keys[1].time, p.keys[1].time);
    EXPECT_EQ(q->keys[0].pose.position, p.keys[0].pose.position);
    EXPECT_EQ(q->keys[1].pose.target, p.keys[1].pose.target);
    EXPECT_EQ(q->keys[1].pose.verticalFov, p.keys[1].pose.verticalFov);
    ASSERT_EQ(q->lights.size(), 1u);
    EXPECT_EQ(q->lights[0].name, "spot");
    EXPECT_EQ(q->scene, "cornell-box");
}

TEST(CameraPath, EvaluateIsExactAtKeysAndLinearBetween) {
    const CameraPath p = twoKeys();
    EXPECT_EQ(p.evaluate(p.keys[1].time).position, p.keys[1].pose.position);
    EXPECT_EQ(p.evaluate(-1.0f).position, p.keys[0].pose.position);  // clamped before the first key
    EXPECT_EQ(p.evaluate(5.0f).target, p.keys[1].pose.target);       // and after the last
    const CameraPose mid = p.evaluate(p.keys[1].time * 0.5f);
    EXPECT_NEAR(mid.position.x, 0.55f, 1e-6f);
    EXPECT_NEAR(mid.verticalFov, 0.6f, 1e-6f);
    const auto [first, last] = p.frameRange(30.0f);
    EXPECT_EQ(first, 0u);
    EXPECT_EQ(last, 10u);
}

TEST(CameraPath, RejectsBadInputWithOneNamedMessage) {
    auto expectError = [](const std::string& text, const std::string& needle) {
        auto r = parseCameraPath(text, "p.json");
        ASSERT_FALSE(r.ok()) << text;
        EXPECT_NE(r.error().message.find(needle), std::string::npos) << r.error().message;
        EXPECT_EQ(r.error().message.find('\n'), std::string::npos) << r.error().message;
    };
    const std::string head = R"({"format":"bounce-camera-path","version":1,)";
    expectError("{", "p.json:1:2: malformed JSON");
    expectError(R"({"format":"other","version":1})", "not a bounce-camera-path file");
    expectError(head + R"("keys":[]})", "'keys' must be a non-empty array");
    expectError(head + R"("keys":[{"time":0,"position":[0,0,1]}]})", "key 0: 'target' is missing");
    expectError(head + R"("keys":[{"time":0,"position":[0,0,1],"target":[0,0,1]}]})", "coincide");
    expectError(head + R"("keys":[{"time":1,"position":[0,0,1],"target":[0,0,0]},{"time":1,"position":[0,0,1],"target":[0,0,0]}]})",
                "key 1: time 1 is not after");
    expectError(head + R"("keys":[{"time":-1,"position":[0,0,1],"target":[0,0,0]}]})", ">= 0");
    expectError(head + R"("keys":[{"time":0,"position":[0,0,1],"target":[0,0,0],"verticalFov":4}]})", "verticalFov");
    expectError(head + R"("keys":[{"time":0,"position":[0,"a",1],"target":[0,0,0]}]})", "array of 3 numbers");
}

TEST(CameraPath, LightPosesNameUnknownLights) {
    Scene scene;
    scene.name = "s";
    scene.lights.emplace_back();
    scene.lights[0].name = "key";
    EXPECT_TRUE(applyLightPoses(scene, {{"key", {1, 2, 3}, {0, -1, 0}}}).ok());
    EXPECT_EQ(scene.lights[0].position, glm::vec3(1, 2, 3));
    auto r = applyLightPoses(scene, {{"fill", {}, {}}});
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("light 'fill'"), std::string::npos);
}

TEST(CameraPath, BookmarksRoundTrip) {
    const auto file = std::filesystem::temp_directory_path() / "bounce-bookmarks-test.json";
    std::vector<CameraBookmark> marks{{"door", {{0, 1, 4}, {0, 1, 0}, {0, 1, 0}, 0.6f}}};
    ASSERT_TRUE(writeCameraBookmarks(file, marks).ok());
    auto back = readCameraBookmarks(file);
    ASSERT_TRUE(back.ok()) << back.error().message;
    ASSERT_EQ(back->size(), 1u);
    EXPECT_EQ((*back)[0].name, "door");
    EXPECT_EQ((*back)[0].pose.position, marks[0].pose.position);
    std::filesystem::remove(file);
}

TEST(CameraPath, FramePatterns) {
    EXPECT_EQ(*formatFramePattern("frame_%04d.png", 7), "frame_0007.png");
    EXPECT_EQ(*formatFramePattern("f%d.exr", 12), "f12.exr");
    EXPECT_EQ(*formatFramePattern("100%%_%02d.png", 3), "100%_03.png");
    EXPECT_FALSE(isFramePattern("frame.png"));
    EXPECT_FALSE(isFramePattern("a%d_%d.png"));
    EXPECT_FALSE(isFramePattern("a%s.png"));
    EXPECT_FALSE(isFramePattern("a%0d.png"));
    EXPECT_FALSE(formatFramePattern("frame.png", 0).ok());
}

}  // namespace
}  // namespace bounce
