#include "scene/BuiltinScenes.h"

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

}  // namespace bounce
