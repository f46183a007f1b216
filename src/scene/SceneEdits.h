#pragma once
// The edits made to a scene between frames: what the viewer's arrow keys, ctrl-drag and panel do
// (`bounce view`), what a camera path replays (`bounce render --camera-path`) and what `import bounce`
// does from Python. GL-free: a renderer picks up moved lights by itself (LightSet re-renders a moved
// light's shadow map) and must be told about moved objects (SceneGpu::invalidateObjects), because
// geometry is uploaded only when the scene's time changes.
#include "core/Error.h"
#include "scene/CameraPath.h"
#include "scene/Scene.h"

#include <string>
#include <vector>

namespace bounce {

// The objects that may be moved: the animated ones (static geometry is uploaded once).
std::vector<size_t> movableObjects(const Scene& scene);

// Light i's base position moves by delta metres (its animation track, if any, still applies on top).
Expected<void> moveLight(Scene& scene, size_t light, glm::vec3 delta);
// Animated object i moves by delta metres: transform = translate(delta) * transform.
Expected<void> moveObject(Scene& scene, size_t object, glm::vec3 delta);
// Sets a light's position and direction, as a camera path's recorded lights do (applyLightPoses); the
// direction is normalised (the viewer's panel does the same) and must not be zero.
Expected<void> setLightPose(Scene& scene, const LightPose& pose);
// Puts the scene's camera at the pose (its animation cleared), as a camera path's keys do.
Expected<void> placeCamera(Scene& scene, const CameraPose& pose);

}  // namespace bounce
