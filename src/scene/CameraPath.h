#pragma once
// Recorded camera paths and camera bookmarks: what `bounce view` saves and `bounce render
// --camera-path` replays frame by frame, so a path flown in the viewer becomes a benchmark or a
// video. A path is a list of camera keys at scene times; between keys position, target, up and field
// of view are interpolated linearly (at a key the key's camera is returned exactly, which is what
// lets a replayed frame equal the viewer's frame at that key bit for bit). A path also carries the
// lights as the viewer had moved them, so the replay lights the scene the same way.
//
// File format (JSON, docs/viewer.md):
//   {"format": "bounce-camera-path", "version": 1, "scene": "cornell-box",
//    "keys": [{"time": 0.0, "position": [x,y,z], "target": [x,y,z], "up": [0,1,0], "verticalFov": 0.698}, ...],
//    "lights": [{"name": "spot", "position": [x,y,z], "direction": [x,y,z]}, ...]}
// Bookmarks: {"format": "bounce-camera-bookmarks", "version": 1, "bookmarks": [{"name": "...", <camera>}, ...]}
#include "core/Error.h"
#include "scene/Scene.h"

#include <filesystem>
#include <string>
#include <vector>

namespace bounce {

struct CameraPose {
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float verticalFov = 0.6981317f;  // radians

    static CameraPose of(const Camera& camera);
    // `base` with this pose (projection type, planes and ortho height are kept; animation cleared).
    Camera applyTo(const Camera& base) const;
};

struct CameraKey {
    float time = 0.0f;  // scene time, seconds
    CameraPose pose;
};

struct LightPose {
    std::string name;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
};

struct CameraPath {
    std::string scene;  // the scene it was recorded on (informational: a replay on another scene warns)
    std::vector<CameraKey> keys;  // strictly increasing times
    std::vector<LightPose> lights;

    float startTime() const { return keys.empty() ? 0.0f : keys.front().time; }
    float endTime() const { return keys.empty() ? 0.0f : keys.back().time; }
    // Clamped to the key range; exact at key times.
    CameraPose evaluate(float time) const;
    // The frames a replay renders at `frameRate`: round(start * rate) .. round(end * rate).
    std::pair<uint32_t, uint32_t> frameRange(float frameRate) const;
};

// Sets the lights named in `poses` to their recorded position and direction; a name the scene does
// not have is an error naming it. The lights' animation tracks are left as they are.
Expected<void> applyLightPoses(Scene& scene, const std::vector<LightPose>& poses);
std::vector<LightPose> lightPosesOf(const Scene& scene);

// Validates: at least one key, finite numbers, strictly increasing non-negative times, position !=
// target, up not parallel to the view direction, 0 < fov < pi. Messages name the file and the key.
Expected<CameraPath> parseCameraPath(const std::string& text, const std::string& source);
Expected<CameraPath> readCameraPath(const std::filesystem::path& path);
std::string cameraPathToJson(const CameraPath& path);
Expected<void> writeCameraPath(const std::filesystem::path& path, const CameraPath& cameraPath);

struct CameraBookmark {
    std::string name;
    CameraPose pose;
};
Expected<std::vector<CameraBookmark>> readCameraBookmarks(const std::filesystem::path& path);
Expected<void> writeCameraBookmarks(const std::filesystem::path& path, const std::vector<CameraBookmark>& bookmarks);

// "frame_%04d.png" style output patterns: exactly one %d or %0Nd (N <= 9) and no other % but "%%".
bool isFramePattern(const std::string& pattern);
Expected<std::string> formatFramePattern(const std::string& pattern, uint32_t frame);

}  // namespace bounce
