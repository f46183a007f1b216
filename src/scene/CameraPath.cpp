#include "scene/CameraPath.h"

#include "core/Check.h"
#include "core/FileIo.h"
#include "scene/JsonLocator.h"

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

namespace bounce {

using nlohmann::json;

CameraPose CameraPose::of(const Camera& camera) {
    return {camera.position, camera.target, camera.up, camera.verticalFov};
}

Camera CameraPose::applyTo(const Camera& base) const {
    Camera c = base;
    c.position = position;
    c.target = target;
    c.up = up;
    c.verticalFov = verticalFov;
    c.animation = {};
    return c;
}

CameraPose CameraPath::evaluate(float time) const {
    BOUNCE_CHECK(!keys.empty(), "camera path without keys");
    if (time <= keys.front().time) return keys.front().pose;
    if (time >= keys.back().time) return keys.back().pose;
    size_t i = 0;
    while (i + 2 < keys.size() && keys[i + 1].time <= time) ++i;
    const CameraKey& a = keys[i];
    const CameraKey& b = keys[i + 1];
    if (time == a.time) return a.pose;  // exact at keys (not a + 0 * (b - a), which may round)
    if (time == b.time) return b.pose;
    const float s = (time - a.time) / (b.time - a.time);
    CameraPose p;
    p.position = glm::mix(a.pose.position, b.pose.position, s);
    p.target = glm::mix(a.pose.target, b.pose.target, s);
    p.up = glm::normalize(glm::mix(a.pose.up, b.pose.up, s));
    p.verticalFov = a.pose.verticalFov + (b.pose.verticalFov - a.pose.verticalFov) * s;
    return p;
}

std::pair<uint32_t, uint32_t> CameraPath::frameRange(float frameRate) const {
    return {static_cast<uint32_t>(std::lround(startTime() * frameRate)),
            static_cast<uint32_t>(std::lround(endTime() * frameRate))};
}

Expected<void> applyLightPoses(Scene& scene, const std::vector<LightPose>& poses) {
    for (const LightPose& p : poses) {
        Light* light = nullptr;
        for (Light& l : scene.lights)
            if (l.name == p.name) light = &l;
        if (!light) return makeError("light '{}' is not in scene '{}'", p.name, scene.name);
        light->position = p.position;
        light->direction = p.direction;
    }
    return {};
}

std::vector<LightPose> lightPosesOf(const Scene& scene) {
    std::vector<LightPose> out;
    for (const Light& l : scene.lights) out.push_back({l.name, l.position, l.direction});
    return out;
}

namespace {

json vec(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }

Expected<glm::vec3> readVec(const json& object, const char* name, const std::string& where) {
    const auto it = object.find(name);
    if (it == object.end()) return makeError("{}: '{}' is missing", where, name);
    if (!it->is_array() || it->size() != 3) return makeError("{}: '{}' must be an array of 3 numbers", where, name);
    glm::vec3 v{0.0f};
    for (int i = 0; i < 3; ++i) {
        if (!(*it)[i].is_number()) return makeError("{}: '{}' must be an array of 3 numbers", where, name);
        v[i] = (*it)[i].get<float>();
        if (!std::isfinite(v[i])) return makeError("{}: '{}' is not finite", where, name);
    }
    return v;
}

Expected<CameraPose> readPose(const json& object, const std::string& where) {
    if (!object.is_object()) return makeError("{}: must be an object", where);
    CameraPose p;
    BOUNCE_TRY(p.position, readVec(object, "position", where));
    BOUNCE_TRY(p.target, readVec(object, "target", where));
    if (object.contains("up")) {
        BOUNCE_TRY(p.up, readVec(object, "up", where));
    }
    if (object.contains("verticalFov")) {
        if (!object["verticalFov"].is_number()) return makeError("{}: 'verticalFov' must be a number", where);
        p.verticalFov = object["verticalFov"].get<float>();
    }
    const glm::vec3 d = p.target - p.position;
    if (glm::length(d) <= 0.0f) return makeError("{}: position and target coincide", where);
    if (glm::length(p.up) <= 0.0f || glm::length(glm::cross(glm::normalize(d), glm::normalize(p.up))) < 1e-6f)
        return makeError("{}: 'up' is zero or parallel to the view direction", where);
    if (!(p.verticalFov > 0.0f && p.verticalFov < std::numbers::pi_v<float>))
        return makeError("{}: 'verticalFov' {} must be between 0 and pi radians", where, p.verticalFov);
    return p;
}

json poseJson(const CameraPose& p) {
    return {{"position", vec(p.position)}, {"target", vec(p.target)}, {"up", vec(p.up)}, {"verticalFov", p.verticalFov}};
}

Expected<json> parseDocument(const std::string& text, const std::string& source, const char* format) {
    BOUNCE_TRY(json root, parseJsonDocument(text, source));
    if (!root.is_object() || !root.contains("format") || root["format"] != format)
        return makeError("{}: not a {} file (expected \"format\": \"{}\")", source, format, format);
    if (!root.contains("version") || root["version"] != 1) return makeError("{}: unsupported version (expected 1)", source);
    return root;
}

}  // namespace

Expected<CameraPath> parseCameraPath(const std::string& text, const std::string& source) {
    BOUNCE_TRY(json root, parseDocument(text, source, "bounce-camera-path"));
    CameraPath path;
    if (root.contains("scene") && root["scene"].is_string()) path.scene = root["scene"].get<std::string>();
    if (!root.contains("keys") || !root["keys"].is_array() || root["keys"].empty())
        return makeError("{}: 'keys' must be a non-empty array", source);
    for (size_t i = 0; i < root["keys"].size(); ++i) {
        const json& k = root["keys"][i];
        const std::string where = fmt::format("{}: key {}", source, i);
        if (!k.is_object() || !k.contains("time") || !k["time"].is_number())
            return makeError("{}: 'time' (seconds) is missing or not a number", where);
        CameraKey key;
        key.time = k["time"].get<float>();
        if (!std::isfinite(key.time) || key.time < 0.0f) return makeError("{}: time {} must be finite and >= 0", where, key.time);
        if (!path.keys.empty() && key.time <= path.keys.back().time)
            return makeError("{}: time {} is not after the previous key's {}", where, key.time, path.keys.back().time);
        BOUNCE_TRY(key.pose, readPose(k, where));
        path.keys.push_back(key);
    }
    if (root.contains("lights")) {
        if (!root["lights"].is_array()) return makeError("{}: 'lights' must be an array", source);
        for (size_t i = 0; i < root["lights"].size(); ++i) {
            const json& l = root["lights"][i];
            const std::string where = fmt::format("{}: light {}", source, i);
            if (!l.is_object() || !l.contains("name") || !l["name"].is_string())
                return makeError("{}: 'name' is missing", where);
            LightPose p;
            p.name = l["name"].get<std::string>();
            BOUNCE_TRY(p.position, readVec(l, "position", where));
            BOUNCE_TRY(p.direction, readVec(l, "direction", where));
            path.lights.push_back(p);
        }
    }
    return path;
}

Expected<CameraPath> readCameraPath(const std::filesystem::path& path) {
    BOUNCE_TRY(std::string text, readTextFile(path));
    return parseCameraPath(text, path.string());
}

std::string cameraPathToJson(const CameraPath& path) {
    json keys = json::array(), lights = json::array();
    for (const CameraKey& k : path.keys) {
        json j = poseJson(k.pose);
        j["time"] = k.time;
        keys.push_back(j);
    }
    for (const LightPose& l : path.lights)
        lights.push_back({{"name", l.name}, {"position", vec(l.position)}, {"direction", vec(l.direction)}});
    json root = {{"format", "bounce-camera-path"}, {"version", 1}, {"scene", path.scene}, {"keys", keys}, {"lights", lights}};
    return root.dump(2) + "\n";
}

Expected<void> writeCameraPath(const std::filesystem::path& path, const CameraPath& cameraPath) {
    return writeTextFileAtomic(path, cameraPathToJson(cameraPath));
}

Expected<std::vector<CameraBookmark>> readCameraBookmarks(const std::filesystem::path& path) {
    BOUNCE_TRY(std::string text, readTextFile(path));
    const std::string source = path.string();
    BOUNCE_TRY(json root, parseDocument(text, source, "bounce-camera-bookmarks"));
    if (!root.contains("bookmarks") || !root["bookmarks"].is_array())
        return makeError("{}: 'bookmarks' must be an array", source);
    std::vector<CameraBookmark> out;
    for (size_t i = 0; i < root["bookmarks"].size(); ++i) {
        const json& b = root["bookmarks"][i];
        const std::string where = fmt::format("{}: bookmark {}", source, i);
        CameraBookmark bm;
        bm.name = b.is_object() && b.contains("name") && b["name"].is_string() ? b["name"].get<std::string>()
                                                                              : fmt::format("bookmark {}", i);
        BOUNCE_TRY(bm.pose, readPose(b, where));
        out.push_back(bm);
    }
    return out;
}

Expected<void> writeCameraBookmarks(const std::filesystem::path& path, const std::vector<CameraBookmark>& bookmarks) {
    json list = json::array();
    for (const CameraBookmark& b : bookmarks) {
        json j = poseJson(b.pose);
        j["name"] = b.name;
        list.push_back(j);
    }
    json root = {{"format", "bounce-camera-bookmarks"}, {"version", 1}, {"bookmarks", list}};
    return writeTextFileAtomic(path, root.dump(2) + "\n");
}

namespace {

// Position and width of the one frame conversion; npos when the pattern is not valid.
struct Conversion {
    size_t begin = std::string::npos, end = 0;
    int width = 0;
};

Conversion findConversion(const std::string& p) {
    Conversion found, none;
    for (size_t i = 0; i < p.size(); ++i) {
        if (p[i] != '%') continue;
        if (i + 1 < p.size() && p[i + 1] == '%') {
            ++i;
            continue;
        }
        size_t j = i + 1;
        int width = 0;
        if (j < p.size() && p[j] == '0') {
            ++j;
            if (j >= p.size() || p[j] < '1' || p[j] > '9') return none;
            width = p[j] - '0';
            ++j;
        }
        if (j >= p.size() || p[j] != 'd' || found.begin != std::string::npos) return none;
        found = {i, j + 1, width};
        i = j;
    }
    return found;
}

}  // namespace

bool isFramePattern(const std::string& pattern) { return findConversion(pattern).begin != std::string::npos; }

Expected<std::string> formatFramePattern(const std::string& pattern, uint32_t frame) {
    const Conversion c = findConversion(pattern);
    if (c.begin == std::string::npos)
        return makeError("'{}' is not a frame pattern: it needs exactly one %d or %0Nd (e.g. frame_%04d.png)", pattern);
    auto unescape = [](std::string s) {
        for (size_t i = s.find("%%"); i != std::string::npos; i = s.find("%%", i + 1)) s.erase(i, 1);
        return s;
    };
    return unescape(pattern.substr(0, c.begin)) + fmt::format("{:0{}}", frame, c.width) + unescape(pattern.substr(c.end));
}

}  // namespace bounce
