#pragma once
// Option parsing shared by the commands: image sizes, name=value lists, scene loading with
// parameters, and the settings of a technique and the shared renderer.
#include "core/Error.h"
#include "render/RenderSettings.h"
#include "scene/SceneLoader.h"
#include "techniques/Technique.h"

#include <glm/vec2.hpp>

#include <optional>
#include <string>
#include <vector>

namespace bounce {

// "WxH" with 1 <= W, H <= 16384.
Expected<glm::ivec2> parseSize(const std::string& text);
// A list of "name=value" into a map; `flag` names the option in messages.
Expected<std::map<std::string, std::string>> parseAssignments(const std::vector<std::string>& items,
                                                              const std::string& flag);
// Loads a scene by name or path with --scene-param values.
Expected<Scene> loadSceneWithParams(const std::string& scene, const std::vector<std::string>& params);

// Applies the scene file's default settings, then the command line's (--set), to the technique and
// the shared renderer settings. Keys: "renderer.NAME", "TECHNIQUE.NAME" or a bare "NAME" (the
// technique's). A key for another technique is ignored in the scene file and an error on the
// command line.
// The scene-file setting check of scene/SceneLoader.h against the registry: "renderer.NAME" against
// RenderSettings, "TECHNIQUE.NAME" against a fresh instance of that technique (the key and its value).
Expected<void> checkSceneSetting(const std::string& key, const std::string& value);

// The one-sided-surface check of reference/OneSidedCheck.h on scene files (not built-ins): each
// finding is one warning line naming the file and the object.
void warnOneSidedSurfaces(const Scene& scene, glm::ivec2 size, uint32_t frame);

// With a device profile (the context's, gl::GpuInfo::profile), the settings that declare per-profile
// defaults (core/Settings.h) are first set to that profile's; without one they keep their initial
// (llvmpipe) values. Commands validate the settings before creating a context and apply them again,
// with the profile, once it exists.
Expected<void> applyAllSettings(const Scene& scene, Technique& technique, render::RenderSettings& renderSettings,
                                const std::vector<std::string>& cliSettings,
                                std::optional<DeviceProfile> profile = std::nullopt);

}  // namespace bounce
