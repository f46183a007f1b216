#include "reference/CameraRays.h"

#include <glm/geometric.hpp>
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

CameraRay CameraRays::generate(float px, float py) const noexcept {
    const float ndcX = 2.0f * px * m_invWidth - 1.0f;
    const float ndcY = 1.0f - 2.0f * py * m_invHeight;
    const glm::vec4 nearH = m_worldFromClip * glm::vec4(ndcX, ndcY, -1.0f, 1.0f);
    const glm::vec4 farH = m_worldFromClip * glm::vec4(ndcX, ndcY, 1.0f, 1.0f);
    const glm::vec3 nearP = glm::vec3(nearH) / nearH.w;
    const glm::vec3 farP = glm::vec3(farH) / farH.w;
    const glm::vec3 span = farP - nearP;
    const float length = glm::length(span);
    return {nearP, span / length, length};
}

}  // namespace bounce
