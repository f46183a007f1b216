#include "app/Options.h"

#include "core/ImageIo.h"
#include "reference/OneSidedCheck.h"
#include "core/Image.h"
#include "techniques/Registry.h"

#include <spdlog/spdlog.h>

#include <charconv>

namespace bounce {

Expected<glm::ivec2> parseSize(const std::string& text) {
    const size_t x = text.find_first_of("xX");
    auto number = [](std::string_view s, int& out) {
        auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
        return ec == std::errc() && end == s.data() + s.size() && !s.empty();
    };
    glm::ivec2 size;
    if (x == std::string::npos || !number(std::string_view(text).substr(0, x), size.x) ||
        !number(std::string_view(text).substr(x + 1), size.y))
        return makeError("--size '{}' is not of the form WIDTHxHEIGHT (e.g. 512x512)", text);
    if (size.x < 1 || size.y < 1 || size.x > kMaxImageSide || size.y > kMaxImageSide)
        return makeError("--size '{}': width and height must be between 1 and {}", text, kMaxImageSide);
    return size;
}

Expected<std::map<std::string, std::string>> parseAssignments(const std::vector<std::string>& items,
                                                              const std::string& flag) {
    std::map<std::string, std::string> out;
    for (const std::string& item : items) {
        auto kv = parseAssignment(item);
        if (!kv.ok()) return makeError("{}: {}", flag, kv.error().message);
        out[kv->first] = kv->second;
    }
    return out;
}

Expected<Scene> loadSceneWithParams(const std::string& scene, const std::vector<std::string>& params) {
    BOUNCE_TRY(auto values, parseAssignments(params, "--scene-param"));
    return loadScene(scene, values);
}

namespace {

// Sorts one key into the renderer's or the technique's map. Returns false for another technique's key.
bool route(const std::string& key, const std::string& value, std::string_view technique,
           std::map<std::string, std::string>& renderer, std::map<std::string, std::string>& own) {
    const size_t dot = key.find('.');
    if (dot == std::string::npos) {
        own[key] = value;
        return true;
    }
    const std::string owner = key.substr(0, dot), name = key.substr(dot + 1);
    if (owner == "renderer") renderer[name] = value;
    else if (owner == technique) own[name] = value;
    else return false;
    return true;
}

}  // namespace

Expected<void> checkSceneSetting(const std::string& profileKey, const std::string& value) {
    // The caller names the key: only the suffix's fault here.
    auto split = splitProfileKey(profileKey);
    if (!split.ok()) return makeError("'{}' is not a device profile (llvmpipe or gpu)", profileKey.substr(profileKey.rfind('@')));
    const std::string& key = split->key;
    const size_t dot = key.find('.');
    if (dot == std::string::npos) return makeError("not of the form technique.setting");
    const std::string owner = key.substr(0, dot), name = key.substr(dot + 1);
    if (owner == "renderer") {
        render::RenderSettings rs;
        return applySettings(rs, {{name, value}}, "renderer");
    }
    BOUNCE_TRY(auto technique, createTechnique(owner));
    return applySettings(*technique, {{name, value}}, fmt::format("technique '{}'", owner));
}

void warnOneSidedSurfaces(const Scene& scene, glm::ivec2 size, uint32_t frame) {
    if (scene.source.rfind("builtin:", 0) == 0) return;  // authored to be seen from the front
    for (const std::string& message : checkOneSidedSurfaces(scene, size, frame)) spdlog::warn("{}", message);
}

Expected<void> applyAllSettings(const Scene& scene, Technique& technique, render::RenderSettings& renderSettings,
                                const std::vector<std::string>& cliSettings, std::optional<DeviceProfile> profile) {
    if (profile) {
        applyProfileDefaults(technique, *profile);
        applyProfileDefaults(renderSettings, *profile);
    }
    std::map<std::string, std::string> renderer, own;
    // The scene's plain defaults, then those for this run's profile over them ("key@llvmpipe"); without
    // a profile (a check before the context exists) the plain ones only.
    std::vector<std::pair<std::string, std::string>> forProfile;
    for (const auto& [key, value] : scene.settings) {
        BOUNCE_TRY(const ProfileKey split, splitProfileKey(key));
        if (!split.profile) route(key, value, technique.name(), renderer, own);
        else if (profile && *split.profile == *profile) forProfile.emplace_back(split.key, value);
    }
    for (const auto& [key, value] : forProfile) route(key, value, technique.name(), renderer, own);
    BOUNCE_TRY(auto cli, parseAssignments(cliSettings, "--set"));
    for (const auto& [key, value] : cli)
        if (!route(key, value, technique.name(), renderer, own))
            return makeError("--set {}: the prefix names another technique (this run uses '{}'; renderer settings "
                             "start with 'renderer.')",
                             key, technique.name());
    BOUNCE_TRY_VOID(applySettings(renderSettings, renderer, "renderer"));
    BOUNCE_TRY_VOID(applySettings(technique, own, fmt::format("technique '{}'", technique.name())));
    return {};
}

}  // namespace bounce
