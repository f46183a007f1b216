#include "scene/BuiltinScenes.h"

#include <glm/gtc/constants.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace bounce {

Expected<double> numberParam(const SceneParams& params, std::string_view scene, const std::string& key,
                             double fallback, double lo, double hi) {
    const auto it = params.find(key);
    if (it == params.end()) return fallback;
    const std::string& text = it->second;
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
        return makeError("scene '{}': parameter {}='{}' is not a number", scene, key, text);
    if (value < lo || value > hi)
        return makeError("scene '{}': parameter {}={} is outside [{}, {}]", scene, key, text, lo, hi);
    return value;
}

Expected<std::string> choiceParam(const SceneParams& params, std::string_view scene, const std::string& key,
                                  std::string_view fallback, std::initializer_list<std::string_view> choices) {
    const auto it = params.find(key);
    if (it == params.end()) return std::string(fallback);
    std::string known;
    for (std::string_view c : choices) {
        if (c == it->second) return it->second;
        known += (known.empty() ? "" : ", ") + std::string(c);
    }
    return makeError("scene '{}': parameter {}='{}' is not one of {}", scene, key, it->second, known);
}

TransformTrack turntable(glm::vec3 centre, float periodSeconds) {
    constexpr int kQuarterTurns = 4;
    TransformTrack track;
    track.interpolation = Interpolation::Linear;
    track.loop = true;
    for (int k = 0; k <= kQuarterTurns; ++k) {
        TransformKey key;
        key.time = periodSeconds * static_cast<float>(k) / static_cast<float>(kQuarterTurns);
        key.translation = centre;
        key.rotation = glm::angleAxis(glm::half_pi<float>() * static_cast<float>(k), glm::vec3(0.0f, 1.0f, 0.0f));
        track.keys.push_back(key);
    }
    return track;
}

}  // namespace bounce
