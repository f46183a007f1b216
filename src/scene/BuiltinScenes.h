#pragma once
// Builders of the built-in scenes (docs/scene.md "Built-in scenes"). loadScene() has already rejected
// unknown parameter names; each builder parses and range-checks the values it accepts.
#include "core/Error.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"

#include <initializer_list>
#include <string>
#include <string_view>

namespace bounce {

Expected<Scene> buildCornellBox(const SceneParams& params);
Expected<Scene> buildCornellBoxArea(const SceneParams& params);
Expected<Scene> buildCornellBoxDynamic(const SceneParams& params);
Expected<Scene> buildFurnace(const SceneParams& params);
Expected<Scene> buildTwoRooms(const SceneParams& params);
Expected<Scene> buildAtrium(const SceneParams& params);
Expected<Scene> buildCourtyard(const SceneParams& params);
Expected<Scene> buildCornellBoxRotating(const SceneParams& params);
Expected<Scene> buildIndirectLight(const SceneParams& params);
Expected<Scene> buildAreaScreen(const SceneParams& params);
Expected<Scene> buildFurnishedRoom(const SceneParams& params);

// Reads parameter `key` of built-in `scene` as a number in [lo, hi], or `fallback` when absent.
Expected<double> numberParam(const SceneParams& params, std::string_view scene, const std::string& key,
                             double fallback, double lo, double hi);

// Reads parameter `key` of built-in `scene` as one of the words in `choices`, or `fallback` when absent.
Expected<std::string> choiceParam(const SceneParams& params, std::string_view scene, const std::string& key,
                                  std::string_view fallback, std::initializer_list<std::string_view> choices);

// A looping track that turns an object once about the vertical axis through `centre` every
// `periodSeconds` (counter-clockwise seen from above), in quarter-turn keys: linear translation (constant,
// `centre`) and slerp, whose keys must be less than half a turn apart to go the intended way round. The
// object's mesh is meant to be centred on the axis, with an identity `transform`.
TransformTrack turntable(glm::vec3 centre, float periodSeconds);

}  // namespace bounce
