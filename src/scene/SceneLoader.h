#pragma once
// Where scenes come from: built-in procedural scenes (no files needed), JSON scene files that place
// models, lights, camera and animations, and model files read through assimp (glTF 2.0 with
// KHR_lights_punctual and cameras, OBJ/MTL, PLY).
#include "core/Error.h"
#include "scene/Scene.h"

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace bounce {

using SceneParams = std::map<std::string, std::string>;

struct BuiltinSceneInfo {
    std::string name;
    std::string description;
    // Parameters the scene accepts (name -> "default: doc").
    std::map<std::string, std::string> params;
};

const std::vector<BuiltinSceneInfo>& builtinScenes();

// `nameOrPath` is a built-in name (see builtinScenes()) or a file: *.json scene files, or a model
// file (.gltf .glb .obj .ply) placed at the origin with its own lights/camera (or defaults).
// `params` are built-in scene parameters (e.g. atrium's "triangles"); unknown ones are errors.
// The returned scene has passed finalizeScene().
Expected<Scene> loadScene(std::string_view nameOrPath, const SceneParams& params = {});

// Checks one scene-file setting ("technique.setting" or "renderer.setting" -> value text) against the
// settings the program declares. The scene layer knows no techniques: the application installs the
// check (app/Options.cpp), and JSON scene files run every key through it whatever technique (or the
// reference) runs, so a typo fails with the file and line. No check installed: keys are not checked.
using SceneSettingCheck = std::function<Expected<void>(const std::string& key, const std::string& value)>;
void setSceneSettingCheck(SceneSettingCheck check);
const SceneSettingCheck& sceneSettingCheck();

// Validates a scene and fills derived data. Errors (non-finite values, indices out of range,
// meshes whose every triangle is degenerate, bad light or camera parameters) name the object.
// Degenerate triangles in otherwise valid meshes are dropped with a warning; missing normals are
// computed (area-weighted vertex normals).
Expected<void> finalizeScene(Scene& scene);

// Fills mesh.tangents (Scene.h) from its positions, normals and uvs (uvs required).
void computeTangents(Mesh& mesh);

}  // namespace bounce
