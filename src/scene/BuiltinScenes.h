#pragma once
// Builders of the built-in scenes (docs/scene.md "Built-in scenes"). loadScene() has already rejected
// unknown parameter names; each builder parses and range-checks the values it accepts.
#include "core/Error.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"

#include <string_view>

namespace bounce {

Expected<Scene> buildCornellBox(const SceneParams& params);
Expected<Scene> buildCornellBoxArea(const SceneParams& params);
Expected<Scene> buildCornellBoxDynamic(const SceneParams& params);
Expected<Scene> buildFurnace(const SceneParams& params);
Expected<Scene> buildTwoRooms(const SceneParams& params);
Expected<Scene> buildAtrium(const SceneParams& params);

// Reads parameter `key` of built-in `scene` as a number in [lo, hi], or `fallback` when absent.
Expected<double> numberParam(const SceneParams& params, std::string_view scene, const std::string& key,
                             double fallback, double lo, double hi);

}  // namespace bounce
