#include "reference/CameraRays.h"

#include <glm/matrix.hpp>

namespace bounce {

CameraRays::CameraRays(const Camera& camera, int width, int height)
    : m_invWidth(1.0f / static_cast<float>(width)), m_invHeight(1.0f / static_cast<float>(height)) {
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    // Invert in double: a near plane of 1 cm and a far plane of 100 m make the projection badly
    // conditioned in float.
    const glm::dmat4 clipFromWorld = glm::dmat4(camera.clipFromView(aspect)) * glm::dmat4(camera.viewFromWorld());
    m_worldFromClip = glm::mat4(glm::inverse(clipFromWorld));
}

}  // namespace bounce
