#pragma once
// Primary rays that see exactly what the rasteriser sees: each ray is the inverse image, under
// Camera::clipFromView * Camera::viewFromWorld, of a pixel position, running from the near plane
// to the far plane. Pixel (x, y) covers [x, x+1) x [y, y+1) with y = 0 the top row of the output
// Image; aspect = width / height.
#include "scene/Scene.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

namespace bounce {

struct CameraRay {
    glm::vec3 origin;     // on the near plane
    glm::vec3 direction;  // unit
    float tMax;           // distance to the far plane along direction
};

class CameraRays {
public:
    // `camera` is already placed at the render time (Camera::at).
    CameraRays(const Camera& camera, int width, int height);

    // (px, py) in pixels from the top-left corner of the image.
    CameraRay generate(float px, float py) const noexcept;

private:
    glm::mat4 m_worldFromClip;
    float m_invWidth;
    float m_invHeight;
};

inline CameraRay CameraRays::generate(float px, float py) const noexcept {
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
