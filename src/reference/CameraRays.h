#pragma once
// Primary rays that see exactly what the rasteriser sees: each ray is the inverse image, under
// Camera::clipFromView * Camera::viewFromWorld, of a pixel position, running from the near plane
// to the far plane. Pixel (x, y) covers [x, x+1) x [y, y+1) with y = 0 the top row of the output
// Image; aspect = width / height.
#include "scene/Scene.h"

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

}  // namespace bounce
