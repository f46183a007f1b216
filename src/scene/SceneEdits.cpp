#include "scene/SceneEdits.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace bounce {
namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string vecText(glm::vec3 v) { return fmt::format("({}, {}, {})", v.x, v.y, v.z); }

}  // namespace

std::vector<size_t> movableObjects(const Scene& scene) {
    std::vector<size_t> out;
    for (size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].isDynamic()) out.push_back(i);
    return out;
}

Expected<void> moveLight(Scene& scene, size_t light, glm::vec3 delta) {
    if (light >= scene.lights.size())
        return makeError("light {} is not in scene '{}' ({} lights)", light, scene.name, scene.lights.size());
    if (!finite(delta)) return makeError("light move {}: not a finite vector", vecText(delta));
    scene.lights[light].position += delta;
    return {};
}

Expected<void> moveObject(Scene& scene, size_t object, glm::vec3 delta) {
    if (object >= scene.objects.size())
        return makeError("object {} is not in scene '{}' ({} objects)", object, scene.name, scene.objects.size());
    if (!scene.objects[object].isDynamic())
        return makeError("object {} ('{}') of scene '{}' is static (its geometry is uploaded once); only animated objects move",
                         object, scene.objects[object].name, scene.name);
    if (!finite(delta)) return makeError("object move {}: not a finite vector", vecText(delta));
    Object& o = scene.objects[object];
    o.transform = glm::translate(glm::mat4(1.0f), delta) * o.transform;
    return {};
}

Expected<void> setLightPose(Scene& scene, const LightPose& pose) {
    if (!finite(pose.position)) return makeError("light '{}': position {} is not finite", pose.name, vecText(pose.position));
    const float length = glm::length(pose.direction);
    if (!finite(pose.direction) || !(length > 0.0f))
        return makeError("light '{}': direction {} is not a non-zero finite vector", pose.name, vecText(pose.direction));
    LightPose p = pose;
    p.direction /= length;
    return applyLightPoses(scene, {p});
}

Expected<void> placeCamera(Scene& scene, const CameraPose& pose) {
    if (!finite(pose.position) || !finite(pose.target) || !finite(pose.up))
        return makeError("camera: position, target and up must be finite");
    if (glm::length(pose.target - pose.position) <= 0.0f) return makeError("camera: position and target are the same point");
    const glm::vec3 view = glm::normalize(pose.target - pose.position);
    if (!(glm::length(glm::cross(view, pose.up)) > 1e-6f)) return makeError("camera: up is parallel to the view direction");
    if (!(pose.verticalFov > 0.0f && pose.verticalFov < 3.14159265f))
        return makeError("camera: vertical field of view {} rad is not in (0, pi)", pose.verticalFov);
    scene.camera = pose.applyTo(scene.camera);
    return {};
}

}  // namespace bounce
